//! Canvas: the generator's drawing surface → a photo, its CMP label mask and XML boxes.
//!
//! Every labelled part is drawn through [`Canvas::part`], which records its box for the XML
//! and paints its class into the mask, so the annotations cannot drift from the pixels.

use image::{GrayImage, Luma, RgbImage};
use rand::RngExt;
use rand_pcg::Pcg64;

use crate::model::PxRect;
pub use crate::model::geometry::rounding::round;
use crate::model::geometry::rounding::round_i32;

use super::super::cmp_box::CmpBox;
use super::super::cmp_label::CmpLabel;

/// An sRGB colour.
pub type Colour = [u8; 3];

/// A photo being drawn, with its label mask and boxes.
pub struct Canvas {
    pub photo: RgbImage,
    pub mask: GrayImage,
    pub boxes: Vec<CmpBox>,
}

impl Canvas {
    /// A `width × height` canvas, all facade (mask value 2), black.
    pub fn new(width: u32, height: u32) -> Canvas {
        Canvas {
            photo: RgbImage::new(width, height),
            mask: GrayImage::from_pixel(width, height, Luma([CmpLabel::Facade.mask_value()])),
            boxes: Vec::new(),
        }
    }

    /// Records `rect` as a `label` box and paints it into the mask (no pixels drawn).
    pub fn part(&mut self, label: CmpLabel, rect: PxRect) {
        let rect = self.clip(rect);
        if rect.x0 >= rect.x1 || rect.y0 >= rect.y1 {
            return;
        }
        self.label_only(label, rect);
        self.boxes.push(CmpBox { label, rect });
    }

    /// Paints `label` into the mask over `rect` without recording a box (for classes CMP
    /// annotates as regions, such as background).
    pub fn label_only(&mut self, label: CmpLabel, rect: PxRect) {
        let rect = self.clip(rect);
        for y in rect.y0..rect.y1 {
            for x in rect.x0..rect.x1 {
                self.mask.put_pixel(x, y, Luma([label.mask_value()]));
            }
        }
    }

    /// Fills `rect` with `colour`.
    pub fn fill(&mut self, rect: PxRect, colour: Colour) {
        self.each(rect, |_, _, _| colour);
    }

    /// Fills `rect` with `colour` plus per-pixel grain of ±`grain`.
    pub fn fill_grain(&mut self, rect: PxRect, colour: Colour, grain: i32, rng: &mut Pcg64) {
        let mut noise = Grain::new(rng);
        self.each(rect, |_, _, _| {
            let g = noise.next(grain);
            colour.map(|c| add(c, g))
        });
    }

    /// Fills `rect` with a vertical gradient from `top` to `bottom`.
    pub fn gradient(&mut self, rect: PxRect, top: Colour, bottom: Colour) {
        let span = rect.height().max(2) - 1;
        // One colour a row, mixed once.
        let mut row = (u32::MAX, [0; 3]);
        self.each(rect, |_, y, _| {
            if row.0 != y {
                let t = f64::from(y - rect.y0) / f64::from(span);
                row = (y, mix(top, bottom, t));
            }
            row.1
        });
    }

    /// Multiplies the pixels of `rect` by `factor` (below 1 darkens, above 1 lightens).
    pub fn shade(&mut self, rect: PxRect, factor: f64) {
        // Each of the 256 channel values scaled once: the same numbers as per pixel.
        let table: [u8; 256] = std::array::from_fn(|c| scale_channel(c as u8, factor));
        self.each(rect, |_, _, p| p.map(|c| table[usize::from(c)]));
    }

    /// Calls `f(x, y, current)` for every pixel of `rect` (clipped) and stores its result.
    pub fn each(&mut self, rect: PxRect, mut f: impl FnMut(u32, u32, Colour) -> Colour) {
        let rect = self.clip(rect);
        if rect.x0 >= rect.x1 {
            return;
        }
        // Row slices, not `get_pixel`/`put_pixel`: a facade is painted over many times.
        let width = self.photo.width() as usize;
        let buffer: &mut [u8] = &mut self.photo;
        for y in rect.y0..rect.y1 {
            let start = (y as usize * width + rect.x0 as usize) * 3;
            let end = (y as usize * width + rect.x1 as usize) * 3;
            for (x, pixel) in (rect.x0..).zip(buffer[start..end].chunks_exact_mut(3)) {
                let out = f(x, y, [pixel[0], pixel[1], pixel[2]]);
                pixel.copy_from_slice(&out);
            }
        }
    }

    fn clip(&self, r: PxRect) -> PxRect {
        let (w, h) = self.photo.dimensions();
        PxRect {
            x0: r.x0.min(w),
            y0: r.y0.min(h),
            x1: r.x1.min(w),
            y1: r.y1.min(h),
        }
    }
}

/// Per-pixel grain: SplitMix64 from one draw of the painter's generator. A pixel's grain
/// costs a few integer operations instead of a draw from the PCG stream with rejection
/// (the facades stage 211 → 198 ms); one call's pixels still get independent, uniform
/// values, and the stream moves on by one draw per call.
pub struct Grain(u64);

impl Grain {
    pub fn new(rng: &mut Pcg64) -> Grain {
        Grain(rng.random())
    }

    /// The next value, uniform in `−amplitude ..= amplitude` (0 for a negative amplitude).
    #[inline]
    pub fn next(&mut self, amplitude: i32) -> i32 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        // The top 32 bits scaled to the range: off uniform by at most 2⁻³² a value.
        let span = (2 * i64::from(amplitude.max(0)) + 1) as u64;
        (((z >> 32) * span) >> 32) as i32 - amplitude.max(0)
    }
}

/// `[x0, x1) × [y0, y1)`, with an empty rectangle when the ends cross.
pub fn rect(x0: u32, y0: u32, x1: u32, y1: u32) -> PxRect {
    PxRect {
        x0,
        y0,
        x1: x1.max(x0),
        y1: y1.max(y0),
    }
}

/// `colour` with `delta` added to each channel, clamped.
pub fn add(c: u8, delta: i32) -> u8 {
    (i32::from(c) + delta).clamp(0, 255) as u8
}

/// `colour` scaled by `factor`, clamped.
pub fn scale(colour: Colour, factor: f64) -> Colour {
    colour.map(|c| scale_channel(c, factor))
}

fn scale_channel(c: u8, factor: f64) -> u8 {
    // `round_i32` is `round` for every product a factor of a few could make (a NaN
    // factor gives 0 either way), without its branches: `shade` tabulates this for all
    // 256 values on every call.
    round_i32(f64::from(c) * factor).clamp(0, 255) as u8
}

/// Linear mix of two colours, `t` in 0–1.
pub fn mix(a: Colour, b: Colour, t: f64) -> Colour {
    let mut out = [0u8; 3];
    for c in 0..3 {
        out[c] = round(f64::from(a[c]) * (1.0 - t) + f64::from(b[c]) * t) as u8;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_are_clipped_recorded_and_painted_into_the_mask() {
        let mut canvas = Canvas::new(10, 8);
        canvas.part(CmpLabel::Window, rect(6, 2, 14, 5));
        canvas.part(CmpLabel::Door, rect(20, 2, 30, 5)); // wholly outside: not recorded
        assert_eq!(
            canvas.boxes,
            vec![CmpBox {
                label: CmpLabel::Window,
                rect: rect(6, 2, 10, 5)
            }]
        );
        assert_eq!(canvas.mask.get_pixel(7, 3).0, [3]);
        assert_eq!(canvas.mask.get_pixel(5, 3).0, [2]);
        canvas.fill(rect(0, 0, 2, 2), [10, 20, 30]);
        canvas.shade(rect(0, 0, 1, 1), 0.5);
        assert_eq!(canvas.photo.get_pixel(0, 0).0, [5, 10, 15]);
        assert_eq!(canvas.photo.get_pixel(1, 1).0, [10, 20, 30]);
    }

    #[test]
    fn grain_is_uniform_over_its_range_and_repeats_from_the_same_stream() {
        let draw = |n: usize| {
            let mut noise = Grain::new(&mut crate::rng::stream(0, "grain-test", 0));
            (0..n).map(|_| noise.next(6)).collect::<Vec<i32>>()
        };
        let values = draw(130_000);
        assert_eq!(values, draw(130_000));
        let mut counts = [0usize; 13];
        for v in &values {
            assert!((-6..=6).contains(v), "{v}");
            counts[(v + 6) as usize] += 1;
        }
        // 10,000 expected per value; a binomial spread is about ±96.
        for (v, &n) in counts.iter().enumerate() {
            assert!(
                (9_500..=10_500).contains(&n),
                "{} drawn {n} times",
                v as i32 - 6
            );
        }
        // Neighbouring pixels are not correlated: a value follows itself 1/13 of the time.
        let repeats = values.windows(2).filter(|w| w[0] == w[1]).count();
        assert!((9_400..=10_600).contains(&repeats), "{repeats}");
        let mut flat = Grain::new(&mut crate::rng::stream(0, "grain-test", 1));
        assert!((0..100).all(|_| flat.next(0) == 0));
    }
}
