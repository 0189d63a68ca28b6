//! Words + letter size → a plate's measures and the text's box within it; + colours → the
//! plate image with the words drawn in Noto Sans.

use std::sync::LazyLock;

use ab_glyph::{FontRef, PxScale};
use image::{Rgb, RgbImage};
use imageproc::drawing::{draw_text_mut, text_size};

/// Texture pixels per metre of letter height: a 0.5 m letter is drawn 32 px tall.
pub const PX_PER_LETTER_METRE: f64 = 64.0;
/// Smallest and largest letter size drawn, in pixels.
const MIN_PX: f64 = 24.0;
const MAX_PX: f64 = 160.0;
/// Margin around the text, as a fraction of the letter size.
const PAD: f64 = 0.25;

/// The embedded font (Noto Sans Regular).
pub static FONT: LazyLock<FontRef<'static>> = LazyLock::new(|| {
    FontRef::try_from_slice(notosans::REGULAR_TTF).expect("the embedded Noto Sans parses")
});

/// A plate's measures: its size, the text's box `[x0, y0, x1, y1]` in its pixels and the
/// letter size. Measuring is cheap; [`TextPlate::draw`] makes the pixels, so a caller can
/// place plates first and draw them all at once, in parallel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextPlate {
    pub width: u32,
    pub height: u32,
    pub text_box: [u32; 4],
    /// The letter size in pixels (the height of the text box).
    pub letter_px: u32,
}

/// Letter size in pixels for a letter `height` metres tall.
pub fn letter_px(height: f64) -> u32 {
    (height * PX_PER_LETTER_METRE).clamp(MIN_PX, MAX_PX).round() as u32
}

impl TextPlate {
    /// The plate for `text` with letters `letter_px` tall.
    pub fn measure(text: &str, letter_px: u32) -> TextPlate {
        let (w, _) = text_size(PxScale::from(letter_px as f32), &*FONT, text);
        let pad = (f64::from(letter_px) * PAD).round() as u32;
        TextPlate {
            width: w.max(1) + 2 * pad,
            height: letter_px + 2 * pad,
            text_box: [pad, pad, pad + w.max(1), pad + letter_px],
            letter_px,
        }
    }

    /// `text` (the text it was measured for) in `ink` on a `paper` plate.
    pub fn draw(&self, text: &str, paper: [u8; 3], ink: [u8; 3]) -> RgbImage {
        let mut image = RgbImage::from_pixel(self.width, self.height, Rgb(paper));
        let [x0, y0, ..] = self.text_box;
        draw_text_mut(
            &mut image,
            Rgb(ink),
            x0 as i32,
            y0 as i32,
            PxScale::from(self.letter_px as f32),
            &*FONT,
            text,
        );
        image
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ink_stays_inside_the_text_box_and_width_follows_the_text() {
        let paper = [240, 240, 230];
        let ink = [20, 20, 40];
        let short = TextPlate::measure("Sun", 64);
        let long = TextPlate::measure("Sun Garden", 64);
        assert!(long.width > short.width * 2);
        for (plate, text) in [(&short, "Sun"), (&long, "Sun Garden")] {
            let image = plate.draw(text, paper, ink);
            assert_eq!((image.width(), image.height()), (plate.width, plate.height));
            let [x0, y0, x1, y1] = plate.text_box;
            let mut inked = 0;
            for (x, y, p) in image.enumerate_pixels() {
                if p.0 != paper {
                    inked += 1;
                    assert!(x0 <= x && x <= x1 && y0 <= y && y <= y1, "ink at {x},{y}");
                }
            }
            assert!(inked > 100);
        }
    }

    #[test]
    fn letter_size_is_clamped() {
        assert_eq!(letter_px(0.5), 32);
        assert_eq!(letter_px(0.1), 24);
        assert_eq!(letter_px(10.0), 160);
    }
}
