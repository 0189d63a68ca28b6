//! Exposed linear radiance → display RGB: automatic exposure, a filmic tone curve and the
//! sRGB encoding (the tables shared with the renderer, [`crate::model::srgb`]).
//!
//! The tone curve is Narkowicz's fit of the ACES filmic curve, a rational function (only
//! plus, minus, times, divide): a toe that keeps shadows soft, mid grey 0.18 → 0.27, and a shoulder that
//! rolls highlights off towards white instead of clipping them. Logs and powers come from
//! the pure-Rust `libm`, so every machine gets the same bits.

use std::sync::OnceLock;

use image::{Rgb, RgbImage};

use crate::model::image_file::rgb8_by_channel;
use crate::model::srgb::{Srgb, srgb};

/// Mid grey: automatic exposure maps the frame's log-average luminance here, in frames at
/// least as bright as [`DIM`].
const KEY: f32 = 0.18;
/// Automatic exposure stays within these multipliers, as a camera's does within its
/// shortest and longest shutter and its ISO range: it may darken a bright frame by 4 stops
/// but brighten a dark one by 1 stop only, so night and heavy rain stay dark (a gain of
/// 20, which a night street's mean asks for, turns night into a grey day) and a black
/// frame is not amplified into noise.
const AUTO_RANGE: (f32, f32) = (1.0 / 16.0, 2.0);
/// Log-average luminance at which the full gain ([`AUTO_RANGE`]'s 2) is reached. In
/// dimmer frames the key itself falls, faster than the frame: the gain drops as the fourth
/// root of the frame's brightness (about 1.3 on a night street), so a night frame stays a
/// night frame (dark walls, bright lamp pools) instead of sitting at the 2 limit, however
/// dark, and dusk darkens continuously into night.
const DIM: f32 = KEY / AUTO_RANGE.1;

/// Rec. 709 luminance of linear RGB.
#[inline]
pub(crate) fn luminance(c: [f32; 3]) -> f32 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// The multiplier that maps the log-average luminance of `linear` to mid grey (to less in
/// frames dimmer than `DIM`), from every 4th pixel of every 4th row (summed in a fixed
/// order, in f64).
pub fn auto_exposure(linear: &[[f32; 3]], width: u32) -> f32 {
    let w = width.max(1) as usize;
    let rows = linear.len() / w;
    let (mut sum, mut n) = (0.0f64, 0u32);
    for y in (0..rows).step_by(4) {
        for x in (0..w).step_by(4) {
            let l = luminance(linear[y * w + x]).max(0.0);
            sum += f64::from(libm::logf(l + 1e-4));
            n += 1;
        }
    }
    if n == 0 {
        return 1.0;
    }
    let mean = libm::exp(sum / f64::from(n)) as f32;
    let gain = if mean >= DIM {
        KEY / mean
    } else {
        AUTO_RANGE.1 * libm::sqrtf(libm::sqrtf(mean / DIM))
    };
    gain.clamp(AUTO_RANGE.0, AUTO_RANGE.1)
}

/// The filmic curve: exposed linear → display linear in 0–1.
#[inline]
pub(crate) fn filmic(x: f32) -> f32 {
    let x = x.max(0.0);
    (x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14)).min(1.0)
}

/// Exposed linear RGB (row-major, `width` wide) → 8-bit sRGB through the filmic curve.
pub fn tone_map(exposed: &[[f32; 3]], width: u32, height: u32) -> RgbImage {
    let (encoding, buckets) = (srgb(), tone_buckets());
    rgb8_by_channel(exposed, width, height, |c| tone_byte(encoding, buckets, c))
}

/// The sRGB byte of `filmic(x)`, the byte an exposed value `x` develops to.
#[inline]
fn tone_byte(encoding: &Srgb, buckets: &[u16], x: f32) -> u8 {
    // Buckets cover [BUCKETS_FROM, BUCKETS_TO); NaN fails the test.
    if (BUCKETS_FROM..BUCKETS_TO).contains(&x) {
        let b = buckets
            [((x.to_bits() >> BUCKET_SHIFT) - (BUCKETS_FROM.to_bits() >> BUCKET_SHIFT)) as usize];
        if let Ok(byte) = u8::try_from(b) {
            return byte;
        }
    }
    encoding.to_srgb8(filmic(x))
}

/// Mantissa bits below a bucket of [`tone_buckets`]: buckets keep 10 of the 23, so each
/// spans 1/1024 of its octave (0.1 %).
const BUCKET_SHIFT: u32 = 13;
/// The exposed values the buckets cover, whole octaves: below 2^-16 every value develops
/// to 0, above 64 to 255 or nearly; both ends are computed.
const BUCKETS_FROM: f32 = 1.0 / 65536.0;
const BUCKETS_TO: f32 = 64.0;

/// Per bucket of exposed values (all floats sharing their top bits, [`BUCKET_SHIFT`]),
/// the byte every value in it develops to, or 256 where its values develop to more than
/// one byte (a bucket straddling a step: about one in twenty, computed per value). The
/// curve and the encoding both rise with their input, so the bucket's two ends decide.
/// The same bytes as the sRGB encoding of `filmic(x)`, for a division less a value.
fn tone_buckets() -> &'static [u16] {
    static TABLE: OnceLock<Vec<u16>> = OnceLock::new();
    TABLE.get_or_init(|| {
        let encoding = srgb();
        let (first, end) = (
            BUCKETS_FROM.to_bits() >> BUCKET_SHIFT,
            BUCKETS_TO.to_bits() >> BUCKET_SHIFT,
        );
        (first..end)
            .map(|b| {
                let lo = f32::from_bits(b << BUCKET_SHIFT);
                let hi = f32::from_bits(((b + 1) << BUCKET_SHIFT) - 1);
                let (a, z) = (encoding.to_srgb8(filmic(lo)), encoding.to_srgb8(filmic(hi)));
                if a == z { u16::from(a) } else { 256 }
            })
            .collect()
    })
}

/// An sRGB image's pixels in linear light, row-major, through the shared table (for
/// callers holding 8-bit pictures, such as the sensor benchmark's synthetic street).
pub fn decode_srgb(rgb: &RgbImage) -> Vec<[f32; 3]> {
    let table = srgb();
    rgb.pixels()
        .map(|Rgb(p)| p.map(|c| table.to_linear(c)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn filmic_is_monotonic_with_a_soft_shoulder() {
        let mut last = -1.0;
        for i in 0..2000 {
            let y = filmic(i as f32 * 0.01);
            assert!(y >= last, "{i}");
            last = y;
        }
        assert_eq!(filmic(0.0), 0.0);
        assert!((filmic(0.18) - 0.267).abs() < 0.01);
        // Not a hard clip: 1 and 2 stay apart, and only very bright light reaches white.
        assert!(filmic(1.0) < 0.85 && filmic(2.0) > filmic(1.0) + 0.05);
    }

    #[test]
    fn the_buckets_develop_every_value_as_the_curve_does() {
        // Every 61st float from below the buckets to above them (a prime stride, so every
        // bucket is visited at many offsets), and the ends of every bucket.
        let (encoding, buckets) = (srgb(), tone_buckets());
        let exact = |x: f32| encoding.to_srgb8(filmic(x));
        let (from, to) = ((BUCKETS_FROM / 4.0).to_bits(), (BUCKETS_TO * 4.0).to_bits());
        for bits in (from..to).step_by(61) {
            let x = f32::from_bits(bits);
            assert_eq!(tone_byte(encoding, buckets, x), exact(x), "{x}");
        }
        for b in BUCKETS_FROM.to_bits() >> BUCKET_SHIFT..BUCKETS_TO.to_bits() >> BUCKET_SHIFT {
            for x in [b << BUCKET_SHIFT, ((b + 1) << BUCKET_SHIFT) - 1].map(f32::from_bits) {
                assert_eq!(tone_byte(encoding, buckets, x), exact(x), "{x}");
            }
        }
        for x in [f32::NAN, -1.0, 0.0, f32::INFINITY, 1e30] {
            assert_eq!(tone_byte(encoding, buckets, x), exact(x), "{x}");
        }
        // Most buckets hold one byte.
        let split = buckets.iter().filter(|&&b| b > 255).count();
        assert!(split * 8 < buckets.len(), "{split} of {}", buckets.len());
    }

    #[test]
    fn auto_exposure_brings_the_frame_to_mid_grey() {
        let frame = vec![[0.12f32; 3]; 64 * 48];
        let e = auto_exposure(&frame, 64);
        assert!((e * 0.12 - KEY).abs() < 0.001, "{e}");
        // Full gain at the dim limit; a night street (mean 0.009) gets less, not more,
        // and a black frame less still; a glare is darkened.
        let dim = auto_exposure(&vec![[DIM; 3]; 64], 8);
        assert!((dim - AUTO_RANGE.1).abs() < 0.01, "{dim}");
        let night = auto_exposure(&vec![[0.009; 3]; 64], 8);
        assert!((1.0..1.4).contains(&night), "{night}");
        let black = auto_exposure(&vec![[0.0; 3]; 64], 8);
        assert!(black < night && black >= AUTO_RANGE.0, "{black}");
        assert!(auto_exposure(&vec![[0.05; 3]; 64], 8) > night);
        let e = auto_exposure(&vec![[1.44f32; 3]; 64], 8);
        assert!((e - 0.125).abs() < 0.001, "{e}");
    }
}
