//! Linear scene radiance (HDR, one `[f32; 3]` per pixel) → an 8-bit sRGB image: exposure,
//! a filmic tone curve, sRGB encoding. Pure; the sensor stage calls it with its own
//! exposure.
//!
//! The tone curve is Narkowicz's fit of the ACES filmic curve,
//! `f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14)`, on `0.8 x` (so mid-grey stays
//! about mid-grey): a gentle toe, nearly linear mid-tones and a shoulder that rolls highlights (the sun disk, lamp pools) off to white
//! instead of clipping them. Only `+ − × ÷`: the same bytes on every machine.

use image::RgbImage;

use crate::model::image_file::rgb8_by_channel;

use crate::model::srgb::srgb;

/// The tone curve on one linear value (after exposure), within 0–1.
#[inline]
pub fn tone(x: f32) -> f32 {
    let x = 0.8 * x.max(0.0);
    if !x.is_finite() {
        return if x.is_nan() { 0.0 } else { 1.0 };
    }
    ((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0)
}

/// Develops `linear` (row-major, `width × height`) with `exposure` (a plain factor on the
/// radiance), the tone curve and sRGB encoding.
///
/// # Panics
/// If `linear` does not hold `width × height` pixels.
pub fn develop(linear: &[[f32; 3]], width: u32, height: u32, exposure: f32) -> RgbImage {
    assert_eq!(linear.len(), width as usize * height as usize);
    let table = srgb();
    rgb8_by_channel(linear, width, height, |c| {
        table.to_srgb8(tone(c * exposure))
    })
}

/// Luminance (Rec. 709 weights) of a linear colour.
#[inline]
pub fn luminance(c: [f32; 3]) -> f32 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// An exposure that brings the frame's typical brightness to mid-grey: `0.18` over the
/// mean luminance of the frame, where each pixel's luminance is first capped at 4 (so a
/// sun disk or a lamp does not darken the whole frame) and the mean skips nothing else.
/// Summed in a fixed order (row by row) in `f64`: the same bits at any thread count.
/// Within 1/16–16; an all-black frame gives 16.
pub fn auto_exposure(linear: &[[f32; 3]]) -> f32 {
    if linear.is_empty() {
        return 1.0;
    }
    let sum: f64 = linear
        .iter()
        .map(|&c| f64::from(luminance(c).clamp(0.0, 4.0)))
        .sum();
    let mean = sum / linear.len() as f64;
    if mean.is_nan() || mean <= 0.0 {
        return 16.0;
    }
    ((0.18 / mean) as f32).clamp(1.0 / 16.0, 16.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tone_curve_is_monotone_filmic_and_bounded() {
        assert_eq!(tone(0.0), 0.0);
        assert_eq!(tone(-1.0), 0.0);
        assert_eq!(tone(f32::NAN), 0.0);
        assert_eq!(tone(f32::INFINITY), 1.0);
        let mut last = 0.0;
        for i in 1..2000 {
            let v = tone(i as f32 * 0.01);
            assert!(v >= last, "monotone at {i}");
            last = v;
        }
        // Mid-grey stays mid-grey-ish; highlights roll off below white instead of clipping.
        assert!((tone(0.18) - 0.18).abs() < 0.03, "{}", tone(0.18));
        assert!(
            tone(1.0) < 0.8 && tone(4.0) > 0.93,
            "{} {}",
            tone(1.0),
            tone(4.0)
        );
    }

    #[test]
    fn develop_applies_exposure_and_auto_exposure_finds_mid_grey() {
        let linear = vec![[0.09, 0.09, 0.09]; 6];
        let e = auto_exposure(&linear);
        assert!((e - 2.0).abs() < 1e-4, "{e}");
        let dark = develop(&linear, 3, 2, 1.0);
        let bright = develop(&linear, 3, 2, e);
        assert!(bright.get_pixel(2, 1)[0] > dark.get_pixel(2, 1)[0]);
        assert_eq!(auto_exposure(&[[0.0; 3]; 4]), 16.0);
    }
}
