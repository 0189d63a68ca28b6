//! Whether an object shows in the frame's final RGB image: after lighting, weather, the
//! sensor and the tone curve, a black car on a black night road or a plate lost in fog
//! has pixels in the instance image but nothing a camera (or a person) could see.
//!
//! An object's contrast is the larger of two measures on the 8-bit sRGB luma
//! (`0.2126 R + 0.7152 G + 0.0722 B`):
//! - how far its pixels' mean lies from its surroundings' (the pixels of its box grown by a
//!   quarter of its larger side, at least 2 px, that are not the object);
//! - how much its own pixels vary (their standard deviation): the letters on a plate, a
//!   car's windows against its body.
//!
//! Below [`MIN_CONTRAST`] the object is an ignore region, not a positive.

use image::{ImageBuffer, Luma, RgbImage};

use crate::model::PixelBox;

/// The contrast an annotated object needs, in 8-bit luma steps: about 3 % of the range.
/// Under it, night text averaging 12/255 with a deviation under 4 (no letters to read) and
/// cars merged into a dark road stop being positives.
pub const MIN_CONTRAST: f64 = 8.0;

fn luma(rgb: &RgbImage, x: u32, y: u32) -> f64 {
    let [r, g, b] = rgb.get_pixel(x, y).0;
    0.2126 * f64::from(r) + 0.7152 * f64::from(g) + 0.0722 * f64::from(b)
}

/// Object `id`'s contrast in `rgb`, its visible pixels those of `instance` inside `bounds`.
pub fn contrast(
    rgb: &RgbImage,
    instance: &ImageBuffer<Luma<u32>, Vec<u32>>,
    id: u32,
    bounds: PixelBox,
) -> f64 {
    let (w, h) = instance.dimensions();
    if rgb.dimensions() != (w, h) || w == 0 || h == 0 {
        return 0.0;
    }
    let side = (bounds.x_max - bounds.x_min).max(bounds.y_max - bounds.y_min) + 1;
    let grow = (side / 4).max(2);
    let (x0, y0) = (
        bounds.x_min.saturating_sub(grow),
        bounds.y_min.saturating_sub(grow),
    );
    let (x1, y1) = (
        (bounds.x_max + grow).min(w - 1),
        (bounds.y_max + grow).min(h - 1),
    );
    // Sums over the object (count, Σ, Σ²) and over its surroundings (count, Σ).
    let (mut n, mut sum, mut squares) = (0.0f64, 0.0f64, 0.0f64);
    let (mut around, mut around_sum) = (0.0f64, 0.0f64);
    for y in y0..=y1 {
        for x in x0..=x1 {
            let l = luma(rgb, x, y);
            if instance.get_pixel(x, y)[0] == id {
                n += 1.0;
                sum += l;
                squares += l * l;
            } else {
                around += 1.0;
                around_sum += l;
            }
        }
    }
    if n == 0.0 {
        return 0.0;
    }
    let mean = sum / n;
    let spread = (squares / n - mean * mean).max(0.0).sqrt();
    let apart = if around > 0.0 {
        (mean - around_sum / around).abs()
    } else {
        0.0
    };
    spread.max(apart)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::annotate::test_image;

    fn grey(rows: &[&[u8]]) -> RgbImage {
        RgbImage::from_fn(rows[0].len() as u32, rows.len() as u32, |x, y| {
            let v = rows[y as usize][x as usize];
            image::Rgb([v, v, v])
        })
    }

    fn bounds(x_min: u32, y_min: u32, x_max: u32, y_max: u32) -> PixelBox {
        PixelBox {
            x_min,
            y_min,
            x_max,
            y_max,
        }
    }

    #[test]
    fn an_object_like_its_surroundings_has_no_contrast() {
        let ids = test_image(&[&[0, 0, 0, 0], &[0, 1, 1, 0], &[0, 0, 0, 0]]);
        let dark = grey(&[&[5, 5, 5, 5], &[5, 6, 6, 5], &[5, 5, 5, 5]]);
        assert!(contrast(&dark, &ids, 1, bounds(1, 1, 2, 1)) < 1.5);
        let bright = grey(&[&[5, 5, 5, 5], &[5, 90, 90, 5], &[5, 5, 5, 5]]);
        assert!((contrast(&bright, &ids, 1, bounds(1, 1, 2, 1)) - 85.0).abs() < 1e-9);
    }

    #[test]
    fn letters_on_a_plate_are_contrast_even_on_a_wall_of_its_mean() {
        let ids = test_image(&[&[0, 0, 0, 0], &[0, 1, 1, 0], &[0, 0, 0, 0]]);
        // A plate of 20 and 60 on a wall of 40: the means agree, the letters do not.
        let rgb = grey(&[&[40, 40, 40, 40], &[40, 20, 60, 40], &[40, 40, 40, 40]]);
        assert!((contrast(&rgb, &ids, 1, bounds(1, 1, 2, 1)) - 20.0).abs() < 1e-9);
    }

    #[test]
    fn an_object_filling_the_frame_is_measured_by_its_own_spread() {
        let ids = test_image(&[&[1, 1]]);
        assert_eq!(
            contrast(&grey(&[&[10, 30]]), &ids, 1, bounds(0, 0, 1, 0)),
            10.0
        );
    }
}
