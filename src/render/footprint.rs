//! Screen triangles of one object → its [`Footprint`]: the pixels it would cover with
//! nothing in front of it, their count and box.
//!
//! The annotator divides an object's visible pixels (from the instance image) by its
//! footprint's pixels to get the visible fraction, so the footprint is measured exactly as
//! the instance image is made: the same screen triangles, the same fill rule, the same
//! near/far acceptance of 1/w, and, with supersampling, the same sample per pixel (the one
//! nearest the centre). Every visible pixel of an object is therefore in its footprint.

use super::screen_triangle::ScreenTri;
use crate::model::PixelBox;

/// Where one object would show if nothing were in front of it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Footprint {
    /// Instance id (object index + 1).
    pub id: u16,
    /// Tight box of the covered pixels.
    pub bounds: PixelBox,
    /// Covered pixels inside the image.
    pub pixels: u64,
}

/// The footprint of the object with instance `id` whose screen triangles are `tris`, or
/// `None` when it covers no pixel. `samples` is the supersampling factor the triangles were
/// set up for; `q_range` the accepted `(1/far, 1.0001/near]` of 1/w, as the tiles use.
pub(crate) fn measure(
    id: u16,
    tris: &[ScreenTri],
    samples: u32,
    q_range: (f64, f64),
) -> Option<Footprint> {
    let s = samples.max(1);
    let mid = (s - 1) / 2;
    let mut bounds = [u32::MAX, u32::MAX, 0, 0];
    for t in tris {
        bounds = [
            bounds[0].min(t.bounds[0]),
            bounds[1].min(t.bounds[1]),
            bounds[2].max(t.bounds[2]),
            bounds[3].max(t.bounds[3]),
        ];
    }
    if bounds[0] >= bounds[2] || bounds[1] >= bounds[3] {
        return None;
    }
    // Output pixels whose centre sample lies inside the internal bounds.
    let ox0 = bounds[0].saturating_sub(mid).div_ceil(s);
    let oy0 = bounds[1].saturating_sub(mid).div_ceil(s);
    let ox1 = (bounds[2] + s - 1 - mid) / s;
    let oy1 = (bounds[3] + s - 1 - mid) / s;
    if ox0 >= ox1 || oy0 >= oy1 {
        return None;
    }
    let bw = (ox1 - ox0) as usize;
    let mut covered = vec![false; bw * (oy1 - oy0) as usize];
    let (q_min, q_max) = q_range;
    for t in tris {
        t.rasterize(bounds, |x, y, q| {
            if x % s == mid && y % s == mid && q > q_min && q <= q_max {
                covered[(y / s - oy0) as usize * bw + (x / s - ox0) as usize] = true;
            }
        });
    }
    let mut found: Option<Footprint> = None;
    for (i, _) in covered.iter().enumerate().filter(|(_, c)| **c) {
        let (x, y) = (ox0 + (i % bw) as u32, oy0 + (i / bw) as u32);
        let f = found.get_or_insert(Footprint {
            id,
            bounds: PixelBox::at(x, y),
            pixels: 0,
        });
        f.bounds.include(x, y);
        f.pixels += 1;
    }
    found
}
