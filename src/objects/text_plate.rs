//! Words + colours + letter size → a plate image with the words drawn in Noto Sans, and the
//! text's box within it.

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

/// A drawn plate: the image and the text's box `[x0, y0, x1, y1]` in its pixels.
pub struct TextPlate {
    pub image: RgbImage,
    pub text_box: [u32; 4],
    /// The letter size in pixels (the height of the text box).
    pub letter_px: u32,
}

/// Letter size in pixels for a letter `height` metres tall.
pub fn letter_px(height: f64) -> u32 {
    (height * PX_PER_LETTER_METRE).clamp(MIN_PX, MAX_PX).round() as u32
}

/// `text` in `ink` on a `paper` plate, letters `letter_px` tall.
pub fn draw(text: &str, letter_px: u32, paper: [u8; 3], ink: [u8; 3]) -> TextPlate {
    let scale = PxScale::from(letter_px as f32);
    let (w, _) = text_size(scale, &*FONT, text);
    let pad = (f64::from(letter_px) * PAD).round() as u32;
    let width = w.max(1) + 2 * pad;
    let height = letter_px + 2 * pad;
    let mut image = RgbImage::from_pixel(width, height, Rgb(paper));
    draw_text_mut(
        &mut image,
        Rgb(ink),
        pad as i32,
        pad as i32,
        scale,
        &*FONT,
        text,
    );
    TextPlate {
        image,
        text_box: [pad, pad, pad + w.max(1), pad + letter_px],
        letter_px,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ink_stays_inside_the_text_box_and_width_follows_the_text() {
        let paper = [240, 240, 230];
        let ink = [20, 20, 40];
        let short = draw("Sun", 64, paper, ink);
        let long = draw("Sun Garden", 64, paper, ink);
        assert!(long.image.width() > short.image.width() * 2);
        for plate in [&short, &long] {
            let [x0, y0, x1, y1] = plate.text_box;
            let mut inked = 0;
            for (x, y, p) in plate.image.enumerate_pixels() {
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
