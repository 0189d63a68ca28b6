//! Words + letter size + font + style → a plate's measures, the text's box and each word's
//! ink box within it; + colours (or a wall patch) → the plate image.
//!
//! Glyphs are laid out here rather than by `imageproc::draw_text_mut` so that the ink box of
//! every word is known (ICDAR 2015 is word-level) and kerning is applied between the right
//! pair of glyphs. Coverage is blended in sRGB bytes, as imageproc does.

use std::sync::LazyLock;

use ab_glyph::{Font, FontRef, OutlinedGlyph, PxScale, ScaleFont, point};
use image::{Rgb, RgbImage};

use super::plate_style::PlateStyle;
use super::text_font::TextFont;

/// Texture pixels per metre of letter height: a 0.5 m letter is drawn 32 px tall.
pub const PX_PER_LETTER_METRE: f64 = 64.0;
/// Smallest and largest letter size drawn, in pixels.
const MIN_PX: f64 = 24.0;
const MAX_PX: f64 = 160.0;

/// Noto Sans Regular, for the traffic signs' lettering.
pub static FONT: LazyLock<FontRef<'static>> = LazyLock::new(|| {
    FontRef::try_from_slice(notosans::REGULAR_TTF).expect("the embedded Noto Sans parses")
});

/// A plate's measures: its size, the text's box `[x0, y0, x1, y1]` and every word's ink box
/// in its pixels, the letter size, font and style. Measuring is cheap; [`TextPlate::draw`]
/// makes the pixels, so a caller can place plates first and draw them all at once.
#[derive(Clone, Debug, PartialEq)]
pub struct TextPlate {
    pub width: u32,
    pub height: u32,
    pub text_box: [u32; 4],
    /// Per word (split at spaces): the box of its ink `[x0, y0, x1, y1]` in plate pixels.
    pub words: Vec<[f32; 4]>,
    /// The letter size in pixels (the font's ascent-to-descent height).
    pub letter_px: u32,
    pub font: TextFont,
    pub style: PlateStyle,
    /// Where the first glyph's pen starts: `(x, baseline − ascent)` in plate pixels.
    pub(crate) origin: [f32; 2],
}

/// Letter size in pixels for a letter `height` metres tall.
pub fn letter_px(height: f64) -> u32 {
    (height * PX_PER_LETTER_METRE).clamp(MIN_PX, MAX_PX).round() as u32
}

/// The glyphs of `text` at `scale`, pen starting at (0, 0) = the top of the ascent, each with
/// the index of the word it belongs to; and the advance width.
fn layout(font: TextFont, scale: PxScale, text: &str) -> (Vec<(OutlinedGlyph, usize)>, f32) {
    let face = font.face().as_scaled(scale);
    let mut caret = 0.0f32;
    let mut prev = None;
    let mut word = 0usize;
    let mut glyphs = Vec::new();
    for c in text.chars() {
        if c == ' ' {
            word += 1;
        }
        let id = face.glyph_id(c);
        if let Some(p) = prev {
            caret += face.kern(p, id);
        }
        let glyph = id.with_scale_and_position(scale, point(caret, face.ascent()));
        caret += face.h_advance(id);
        prev = Some(id);
        if let Some(outline) = font.face().outline_glyph(glyph) {
            glyphs.push((outline, word));
        }
    }
    (glyphs, caret)
}

impl TextPlate {
    /// The plate for `text` with letters `letter_px` tall in `font`, padded as `style` asks.
    pub fn measure(text: &str, letter_px: u32, font: TextFont, style: PlateStyle) -> TextPlate {
        let scale = PxScale::from(letter_px as f32);
        let (glyphs, advance) = layout(font, scale, text);
        let height = font.face().as_scaled(scale).height();
        // The text box holds the advance box and every glyph's ink (scripts swash past it).
        let mut b = [0.0f32, 0.0, advance.max(1.0), height];
        let n_words = text.split(' ').count();
        let mut words = vec![
            [
                f32::INFINITY,
                f32::INFINITY,
                f32::NEG_INFINITY,
                f32::NEG_INFINITY
            ];
            n_words
        ];
        for (g, w) in &glyphs {
            let r = g.px_bounds();
            b = [
                b[0].min(r.min.x),
                b[1].min(r.min.y),
                b[2].max(r.max.x),
                b[3].max(r.max.y),
            ];
            let k = &mut words[*w];
            *k = [
                k[0].min(r.min.x),
                k[1].min(r.min.y),
                k[2].max(r.max.x),
                k[3].max(r.max.y),
            ];
        }
        let [pad_x, pad_y] = style
            .padding()
            .map(|p| (f64::from(letter_px) * p).round() as f32);
        let shift = [pad_x - b[0].floor(), pad_y - b[1].floor()];
        let text_box = [
            pad_x as u32,
            pad_y as u32,
            (b[2] + shift[0]).ceil() as u32,
            (b[3] + shift[1]).ceil() as u32,
        ];
        let words = words
            .into_iter()
            .map(|k| {
                if k[0].is_finite() {
                    [
                        k[0] + shift[0],
                        k[1] + shift[1],
                        k[2] + shift[0],
                        k[3] + shift[1],
                    ]
                } else {
                    // A word without ink (cannot happen for letters): a sliver at the pen.
                    [shift[0], shift[1], shift[0], shift[1] + height]
                }
            })
            .collect();
        TextPlate {
            width: text_box[2] + pad_x as u32,
            height: text_box[3] + pad_y as u32,
            text_box,
            words,
            letter_px,
            font,
            style,
            origin: shift,
        }
    }

    /// `text` (the text it was measured for) in `ink` on `background`: a plate colour, or
    /// the wall's own pixels for painted text (an image of the plate's size).
    pub fn draw(&self, text: &str, background: &Background, ink: [u8; 3]) -> RgbImage {
        let mut image = match background {
            Background::Paper(paper) => {
                let mut image = RgbImage::from_pixel(self.width, self.height, Rgb(*paper));
                self.style.decorate(&mut image, self.text_box, *paper, ink);
                image
            }
            Background::Wall(patch) => patch.clone(),
        };
        let scale = PxScale::from(self.letter_px as f32);
        let (glyphs, _) = layout(self.font, scale, text);
        let (w, h) = (self.width as i32, self.height as i32);
        for (g, _) in glyphs {
            let r = g.px_bounds();
            let x0 = (r.min.x + self.origin[0]).round() as i32;
            let y0 = (r.min.y + self.origin[1]).round() as i32;
            g.draw(|gx, gy, coverage| {
                let (x, y) = (x0 + gx as i32, y0 + gy as i32);
                if (0..w).contains(&x) && (0..h).contains(&y) {
                    let c = coverage.clamp(0.0, 1.0);
                    let p = image.get_pixel_mut(x as u32, y as u32);
                    for (channel, ink) in p.0.iter_mut().zip(ink) {
                        let v = f32::from(*channel) * (1.0 - c) + f32::from(ink) * c;
                        *channel = v.round().clamp(0.0, 255.0) as u8;
                    }
                }
            });
        }
        image
    }
}

/// What a plate's text is drawn on.
#[derive(Clone, Debug, PartialEq)]
pub enum Background {
    /// A plate of one colour (sRGB), decorated by its style.
    Paper([u8; 3]),
    /// The wall behind painted text, already cut to the plate's size.
    Wall(RgbImage),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ink_stays_inside_the_text_box_and_words_are_boxed_in_order() {
        let paper = [240, 240, 230];
        let ink = [20, 20, 40];
        for font in TextFont::ALL {
            let short = TextPlate::measure("Sun", 64, font, PlateStyle::Painted);
            let long = TextPlate::measure("Sun Garden", 64, font, PlateStyle::Painted);
            assert!(long.width > short.width * 2, "{}", font.name());
            assert_eq!((short.words.len(), long.words.len()), (1, 2));
            let [a, b] = [long.words[0], long.words[1]];
            assert!(a[2] < b[0], "{}: words apart {a:?} {b:?}", font.name());
            for (plate, text) in [(&short, "Sun"), (&long, "Sun Garden")] {
                let image = plate.draw(text, &Background::Paper(paper), ink);
                assert_eq!((image.width(), image.height()), (plate.width, plate.height));
                let [x0, y0, x1, y1] = plate.text_box;
                let mut inked = 0;
                for (x, y, p) in image.enumerate_pixels() {
                    if p.0 != paper {
                        inked += 1;
                        assert!(x0 <= x && x <= x1 && y0 <= y && y <= y1, "ink at {x},{y}");
                        let xf = x as f32 + 0.5;
                        let yf = y as f32 + 0.5;
                        let in_word = plate.words.iter().any(|w| {
                            w[0] - 1.0 <= xf
                                && xf <= w[2] + 1.0
                                && w[1] - 1.0 <= yf
                                && yf <= w[3] + 1.0
                        });
                        assert!(
                            in_word,
                            "{}: ink at {x},{y} outside every word",
                            font.name()
                        );
                    }
                }
                assert!(inked > 100);
            }
        }
    }

    #[test]
    fn letter_size_is_clamped() {
        assert_eq!(letter_px(0.5), 32);
        assert_eq!(letter_px(0.1), 24);
        assert_eq!(letter_px(10.0), 160);
    }
}
