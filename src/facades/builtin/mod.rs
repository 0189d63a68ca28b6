//! Builtin facade set: fixed seeds → cityspec's own facades as CMP-layout files (painted
//! photo, XML boxes, label PNG), loaded by the same code as a user's CMP folder. The photo
//! stays pixels ([`Photo::Painted`]); `cityspec facades export` writes it as a JPEG.
//!
//! Facade `i` is designed from `crate::rng::stream(0, "builtin-facades", i)` (see
//! `design`) and painted with noise from `stream(0, "builtin-facades-paint", i)` (see
//! `painter`); it never depends on a spec's seed. Twelve styles cycle: brick grids,
//! plaster with shutters (some arched: Mediterranean), shopfronts with striped or plain
//! awnings or a signage band, balconies, townhouses with pilasters and a front door, plain
//! modern blocks over shops, glass curtain-wall offices, stone classical blocks with arched
//! windows over a rusticated ground floor (some an arcade), brick industrial lofts with
//! steel-grid windows over garage doors, half-timbered houses, painted clapboard houses
//! and tiled modernist blocks. Facades 0–11, 24–35 and 48–59 are narrow (2.7–3.1 floors
//! wide), so the narrowest footprint of paper Algorithm 1 fits many of them.

mod canvas;
mod design;
mod painter;
mod parts;
mod wall;

use rayon::prelude::*;

use super::cmp_box::write_cmp_xml;
use super::{FacadeFile, FacadeSource, Photo};
use crate::model::image_file::{PngEffort, encode_png};

pub use design::Design;

/// How many facades the builtin set has.
pub const COUNT: usize = 60;

/// cityspec's own facade set, as CMP-layout files. The same bytes on every call.
pub fn builtin() -> FacadeSource {
    FacadeSource {
        files: (0..COUNT).into_par_iter().map(facade_file).collect(),
        ..source_without_files()
    }
}

/// The builtin source's name and side files, without its photos (for messages).
pub(super) fn source_without_files() -> FacadeSource {
    FacadeSource {
        origin: "builtin".to_string(),
        files: Vec::new(),
        floors: None,
    }
}

/// The row where the loader crops every builtin facade (the top molding's bottom edge).
#[cfg(test)]
pub fn crop_top() -> u32 {
    painter::CROP_TOP
}

/// The name of builtin facade `i`.
pub fn name(i: usize) -> String {
    format!("builtin_{i:02}")
}

/// Designs, paints and encodes builtin facade `i`.
pub(super) fn facade_file(i: usize) -> FacadeFile {
    let design = Design::new(i);
    let mut rng = crate::rng::stream(0, "builtin-facades-paint", i as u64);
    let canvas = painter::paint(&design, &mut rng);
    let (w, h) = canvas.photo.dimensions();
    // Fast: the loader decodes these masks straight away (the same pixels at any level);
    // the best compression cost a cold build more time than the rest of the mask's life.
    let labels = encode_png(&canvas.mask, PngEffort::Fast);
    FacadeFile {
        name: name(i),
        photo: Photo::Painted(canvas.photo),
        xml: Some(write_cmp_xml(&canvas.boxes, w, h)),
        labels: Some(labels),
    }
}

#[cfg(test)]
mod distinct_tests {
    use super::*;

    /// The photo as a `8 × 12` grid of mean colours (any size, so facades of different
    /// sizes compare by their look, not their pixels).
    fn thumbnail(i: usize) -> Vec<f64> {
        let Photo::Painted(photo) = facade_file(i).photo else {
            panic!("builtin photos are painted");
        };
        let (w, h) = photo.dimensions();
        let (gw, gh) = (8u32, 12u32);
        let mut cells = vec![0.0; (gw * gh * 3) as usize];
        let mut counts = vec![0.0; (gw * gh) as usize];
        for (x, y, p) in photo.enumerate_pixels() {
            let cell = ((y * gh / h) * gw + x * gw / w) as usize;
            counts[cell] += 1.0;
            for c in 0..3 {
                cells[cell * 3 + c] += f64::from(p[c]);
            }
        }
        cells
            .iter()
            .enumerate()
            .map(|(k, v)| v / counts[k / 3])
            .collect()
    }

    #[test]
    fn every_builtin_facade_looks_different_from_every_other() {
        const { assert!(COUNT >= 60) };
        let thumbs: Vec<Vec<f64>> = (0..COUNT).into_par_iter().map(thumbnail).collect();
        let mut closest = (f64::INFINITY, 0, 0);
        for a in 0..COUNT {
            for b in a + 1..COUNT {
                let d = thumbs[a]
                    .iter()
                    .zip(&thumbs[b])
                    .map(|(x, y)| (x - y).abs())
                    .sum::<f64>()
                    / thumbs[a].len() as f64;
                if d < closest.0 {
                    closest = (d, a, b);
                }
            }
        }
        // Mean absolute difference of the grids' colours, in 0–255 levels.
        assert!(
            closest.0 > 8.0,
            "facades {} and {} differ by {:.1}",
            closest.1,
            closest.2,
            closest.0
        );
    }
}
