//! Mirror stage: layout image + `spec.layout.mirror` → the mirrored (larger) layout image
//! (paper 3.3).
//!
//! Each op appends a flipped copy of the image so far: 1 flips vertically and puts the
//! upside-down copy below, 2 flips horizontally and puts the mirrored copy to the right, 3 is
//! 2 then 1. Ops apply in order, so `[2, 1]` turns one layout into a 2×2 city whose roads run
//! on across the seams.

/// Bump when this stage's output bytes change: it is part of the stage's cache key.
pub const VERSION: u32 = 1;

use image::RgbImage;

/// Applies the mirror `ops` in order; each one doubles the height (1), the width (2) or both
/// (3). Other op values are ignored: the spec stage only lets 1–3 through.
pub fn mirror(image: &RgbImage, ops: &[u8]) -> RgbImage {
    let mut out = image.clone();
    for &op in ops {
        out = match op {
            1 => append_below(&out),
            2 => append_right(&out),
            3 => append_below(&append_right(&out)),
            _ => out,
        };
    }
    out
}

/// `image` with its upside-down copy below.
fn append_below(image: &RgbImage) -> RgbImage {
    let (width, height) = image.dimensions();
    let stride = width as usize * 3;
    let top = &image.as_raw()[..stride * height as usize];
    let mut raw = Vec::with_capacity(top.len() * 2);
    raw.extend_from_slice(top);
    for row in top.chunks_exact(stride.max(1)).rev() {
        raw.extend_from_slice(row);
    }
    RgbImage::from_raw(width, height * 2, raw).expect("buffer sized for the doubled image")
}

/// `image` with its left-right mirrored copy to the right.
fn append_right(image: &RgbImage) -> RgbImage {
    let (width, height) = image.dimensions();
    let stride = width as usize * 3;
    let mut raw = Vec::with_capacity(stride * 2 * height as usize);
    for row in image.as_raw()[..stride * height as usize].chunks_exact(stride.max(1)) {
        raw.extend_from_slice(row);
        for px in row.chunks_exact(3).rev() {
            raw.extend_from_slice(px);
        }
    }
    RgbImage::from_raw(width * 2, height, raw).expect("buffer sized for the doubled image")
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::{Rgb, imageops};

    /// A small image whose every pixel differs, so any misplaced pixel shows.
    fn sample(width: u32, height: u32) -> RgbImage {
        RgbImage::from_fn(width, height, |x, y| {
            Rgb([x as u8, y as u8, (x * 7 + y) as u8])
        })
    }

    /// The quadrant of `image` at column `qx`, row `qy` of `w`×`h` tiles.
    fn tile(image: &RgbImage, qx: u32, qy: u32, w: u32, h: u32) -> RgbImage {
        imageops::crop_imm(image, qx * w, qy * h, w, h).to_image()
    }

    #[test]
    fn two_then_one_makes_a_two_by_two_city_of_flips() {
        let image = sample(5, 3);
        let out = mirror(&image, &[2, 1]);
        assert_eq!(out.dimensions(), (10, 6));
        assert_eq!(tile(&out, 0, 0, 5, 3), image);
        assert_eq!(tile(&out, 1, 0, 5, 3), imageops::flip_horizontal(&image));
        assert_eq!(tile(&out, 0, 1, 5, 3), imageops::flip_vertical(&image));
        assert_eq!(tile(&out, 1, 1, 5, 3), imageops::rotate180(&image));
    }

    #[test]
    fn ops_match_their_definitions() {
        let image = sample(4, 3);
        let cases: &[(&[u8], (u32, u32))] = &[
            (&[], (4, 3)),
            (&[1], (4, 6)),
            (&[2], (8, 3)),
            (&[3], (8, 6)),
            (&[1, 1], (4, 12)),
            (&[2, 1, 2, 1], (16, 12)),
            (&[0, 9], (4, 3)),
        ];
        for (ops, size) in cases {
            assert_eq!(mirror(&image, ops).dimensions(), *size, "{ops:?}");
        }
        assert_eq!(mirror(&image, &[3]), mirror(&image, &[2, 1]));
        let below = mirror(&image, &[1]);
        assert_eq!(tile(&below, 0, 1, 4, 3), imageops::flip_vertical(&image));
        let right = mirror(&image, &[2]);
        assert_eq!(tile(&right, 1, 0, 4, 3), imageops::flip_horizontal(&image));
    }
}
