//! A camera path's `preview.png`: up to 12 of its frames, spread over the path, at half
//! size in a grid, each kept annotation's box and class drawn on top.
//!
//! Part of the annotate stage's output: a change here changes `preview.png`, so bump
//! [`super::VERSION`].

use std::collections::BTreeMap;

use ab_glyph::FontRef;
use image::{Rgb, RgbImage, imageops};
use imageproc::drawing::{draw_hollow_rect_mut, draw_text_mut};
use imageproc::rect::Rect;
use rayon::prelude::*;

use super::{Category, FrameAnnotations};
use crate::model::PixelBox;

/// Frames on a sheet, at most.
const SHEET_FRAMES: usize = 12;
/// Grid columns, at most.
const COLUMNS: u32 = 3;
/// Margin around and between frames, pixels.
const MARGIN: u32 = 4;
/// Background between frames.
const BACKGROUND: Rgb<u8> = Rgb([20, 20, 20]);
/// Box colours, by category id (cycling).
const COLOURS: [[u8; 3]; 6] = [
    [255, 220, 0],
    [0, 230, 255],
    [255, 80, 200],
    [120, 255, 80],
    [255, 140, 0],
    [200, 160, 255],
];

/// A box drawn on the sheet: category and visible box.
struct SheetBox {
    category: u32,
    bounds: PixelBox,
}

/// The sheet being gathered while a path renders: only the picked frames are kept.
pub struct ContactSheet {
    picks: Vec<usize>,
    frames: Vec<(RgbImage, Vec<SheetBox>)>,
}

impl ContactSheet {
    /// A sheet for a path of `frames` frames.
    pub fn new(frames: usize) -> ContactSheet {
        let picks = picks(frames);
        ContactSheet {
            frames: Vec::with_capacity(picks.len()),
            picks,
        }
    }

    /// Whether the sheet shows frame `index`.
    pub fn wants(&self, index: usize) -> bool {
        self.picks.contains(&index)
    }

    /// Adds the next shown frame: its developed image and its boxes
    /// (`[category, x_min, y_min, x_max, y_max]`, from [`ContactSheet::boxes`]).
    pub fn add(&mut self, rgb: RgbImage, boxes: Vec<[u32; 5]>) {
        let boxes = boxes
            .into_iter()
            .map(|[category, x_min, y_min, x_max, y_max]| SheetBox {
                category,
                bounds: PixelBox {
                    x_min,
                    y_min,
                    x_max,
                    y_max,
                },
            })
            .collect();
        self.frames.push((rgb, boxes));
    }

    /// The boxes a frame shows on the sheet: those of objects that pass the thresholds and
    /// have one of `categories`.
    pub fn boxes(summary: &FrameAnnotations, categories: &[Category]) -> Vec<(u32, PixelBox)> {
        let listed = |c: u32| categories.iter().any(|k| k.id == c);
        summary
            .objects
            .iter()
            .filter(|o| o.passes())
            .filter_map(|o| Some((o.category.filter(|&c| listed(c))?, o.visible.bounds)))
            .collect()
    }

    /// The sheet; a 1 × 1 black image for a path without frames.
    pub fn draw(&self, categories: &[Category]) -> RgbImage {
        let Some((first, _)) = self.frames.first() else {
            return RgbImage::new(1, 1);
        };
        let (w, h) = (first.width() / 2, first.height() / 2);
        let columns = COLUMNS.min(self.frames.len() as u32);
        let rows = (self.frames.len() as u32).div_ceil(columns);
        let mut sheet = RgbImage::from_pixel(
            columns * w + (columns + 1) * MARGIN,
            rows * h + (rows + 1) * MARGIN,
            BACKGROUND,
        );
        let font =
            FontRef::try_from_slice(notosans::REGULAR_TTF).expect("the embedded font parses");
        let names: BTreeMap<u32, &str> =
            categories.iter().map(|c| (c.id, c.name.as_str())).collect();
        // Each frame shrunk and drawn on its own core, then placed in order.
        let smalls: Vec<RgbImage> = self
            .frames
            .par_iter()
            .map(|(rgb, boxes)| {
                let mut small = halve(rgb);
                for b in boxes {
                    let PixelBox {
                        x_min: x0,
                        y_min: y0,
                        x_max: x1,
                        y_max: y1,
                    } = b.bounds;
                    let (bx, by) = ((x0 / 2) as i32, (y0 / 2) as i32);
                    let (bw, bh) = (((x1 - x0) / 2).max(1), ((y1 - y0) / 2).max(1));
                    let colour = Rgb(COLOURS[b.category as usize % COLOURS.len()]);
                    draw_hollow_rect_mut(&mut small, Rect::at(bx, by).of_size(bw, bh), colour);
                    let name = names.get(&b.category).copied().unwrap_or("?");
                    draw_text_mut(&mut small, colour, bx, (by - 12).max(0), 11.0, &font, name);
                }
                small
            })
            .collect();
        for (slot, small) in smalls.iter().enumerate() {
            let (col, row) = (slot as u32 % columns, slot as u32 / columns);
            imageops::overlay(
                &mut sheet,
                small,
                i64::from(MARGIN + col * (w + MARGIN)),
                i64::from(MARGIN + row * (h + MARGIN)),
            );
        }
        sheet
    }
}

/// `rgb` at half its size (width and height halved, rounding down): each pixel the mean
/// of a 2 × 2 block, rounding half up. One pass over the bytes, where the triangle-filtered
/// resize took 20–32 ms of a 100-frame path's assembly, for a picture a sheet shows small.
fn halve(rgb: &RgbImage) -> RgbImage {
    let (w, h) = (rgb.width() / 2, rgb.height() / 2);
    let stride = rgb.width() as usize * 3;
    let raw = rgb.as_raw();
    let mut small = RgbImage::new(w, h);
    if w == 0 {
        return small;
    }
    for (y, row) in small.chunks_exact_mut(w as usize * 3).enumerate() {
        let top = &raw[2 * y * stride..][..stride];
        let bottom = &raw[(2 * y + 1) * stride..][..stride];
        for (x, px) in row.chunks_exact_mut(3).enumerate() {
            for (c, out) in px.iter_mut().enumerate() {
                let (a, b) = (6 * x + c, 6 * x + 3 + c);
                let sum = u16::from(top[a]) + u16::from(top[b]) + u16::from(bottom[a]);
                *out = ((sum + u16::from(bottom[b]) + 2) / 4) as u8;
            }
        }
    }
    small
}

/// The frames a path of `frames` frames shows on its sheet: up to `SHEET_FRAMES`,
/// spread over the path.
pub fn picks(frames: usize) -> Vec<usize> {
    let n = frames.min(SHEET_FRAMES);
    (0..n).map(|k| k * frames / n.max(1)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halving_averages_two_by_two_blocks_and_drops_an_odd_edge() {
        let rgb = RgbImage::from_fn(5, 3, |x, y| Rgb([(10 * x + y) as u8, 200, (x * y) as u8]));
        let small = halve(&rgb);
        assert_eq!(small.dimensions(), (2, 1));
        // Block (0..2, 0..2): red 0, 10, 1, 11 → 5.5 → 6; blue 0, 0, 0, 1 → 0.25 → 0.
        assert_eq!(small.get_pixel(0, 0).0, [6, 200, 0]);
        // Block (2..4, 0..2): red 20, 30, 21, 31 → 25.5 → 26; blue 0, 0, 2, 3 → 1.25 → 1.
        assert_eq!(small.get_pixel(1, 0).0, [26, 200, 1]);
        assert_eq!(halve(&RgbImage::new(1, 7)).dimensions(), (0, 3));
    }

    #[test]
    fn picks_spread_over_the_path() {
        assert_eq!(picks(3), [0, 1, 2]);
        assert_eq!(picks(24), [0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22]);
        assert!(picks(0).is_empty());
    }
}
