//! Screen triangles of one object → its [`Footprint`]: the pixels it would cover with
//! nothing in front of it and no image edge to stop it, their count and box.
//!
//! The annotator divides an object's visible pixels (from the instance image) by its
//! footprint's pixels to get the visible fraction, so occlusion and truncation by the image
//! edge both lower it. Inside the image the footprint is measured exactly as the instance
//! image is made: the same screen triangles, the same fill rule, the same near/far
//! acceptance of 1/w and, with supersampling, the same sample per pixel (the one nearest
//! the centre); so every visible pixel of an object lies in its footprint. Outside the
//! image the same object is rasterized again in a view widened by [`PAD`] image sizes on
//! every side (same focal length, same sample grid), counting only pixels off the image.

use rayon::prelude::*;

use super::prepared_scene::PreparedScene;
use super::screen_triangle::{self, ScreenTri};
use super::view::View;
use super::{CameraPose, Intrinsics};

/// How far beyond each image edge a footprint is measured, in image widths (left and
/// right) and heights (above and below). Parts of an object further out are not counted.
pub const PAD: u32 = 1;

/// Where one object would show with nothing in front of it, on an image without edges.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Footprint {
    /// Instance id (object index + 1).
    pub id: u32,
    /// Tight box of the covered pixels, inclusive `[x0, y0, x1, y1]`, in image pixel
    /// coordinates: it reaches past the image (below 0, beyond the size) where the object
    /// does, up to [`PAD`] image sizes.
    pub bounds: [i64; 4],
    /// Covered pixels, in the image and beyond it.
    pub pixels: u64,
    /// Covered pixels inside the image.
    pub inside: u64,
}

impl Footprint {
    /// COCO-style `[x, y, w, h]` of the box (pixel edges, so `w = x1 − x0 + 1`).
    pub fn bbox(&self) -> [i64; 4] {
        let [x0, y0, x1, y1] = self.bounds;
        [x0, y0, x1 - x0 + 1, y1 - y0 + 1]
    }
}

/// The footprints of the objects `ids` (instance ids) that cover a pixel of the image, in
/// the order of `ids`. `view` is the frame's view and `per_object` every object's screen
/// triangles in it (set up for `samples` per pixel side); `q_range` is the accepted 1/w.
///
/// An object whose bounding box projects wholly inside the image cannot reach past it and
/// is measured once; the others are rasterized again in the widened view, over the four
/// bands around the image only.
#[allow(clippy::too_many_arguments)] // the frame's context, passed as the renderer holds it
pub(crate) fn measure(
    scene: &PreparedScene,
    pose: &CameraPose,
    k: &Intrinsics,
    view: &View,
    samples: u32,
    per_object: &[&[ScreenTri]],
    ids: &[u32],
    q_range: (f64, f64),
) -> Vec<Footprint> {
    let (w, h) = (k.width, k.height);
    let s = samples.max(1);
    // The same camera on an image PAD sizes larger on every side, its pixel grid aligned
    // with the image's.
    let wide = Intrinsics {
        width: w * (1 + 2 * PAD),
        height: h * (1 + 2 * PAD),
        cx: k.cx + f64::from(w * PAD),
        cy: k.cy + f64::from(h * PAD),
        ..*k
    };
    let wide_view = View::new(pose, &wide, samples);
    // The widened view's internal pixels around the image: above, below, left, right.
    let (x0, y0) = (w * PAD * s, h * PAD * s);
    let (x1, y1) = (x0 + w * s, y0 + h * s);
    let (ww, wh) = (wide.width * s, wide.height * s);
    let bands = [
        [0, 0, ww, y0],
        [0, y1, ww, wh],
        [0, y0, x0, y1],
        [x1, y0, ww, y1],
    ];
    let shift = [i64::from(w * PAD), i64::from(h * PAD)];
    ids.par_iter()
        .filter_map(|&id| {
            let index = (id as usize).checked_sub(1)?;
            let tris = per_object.get(index)?;
            let inside = cover(tris, samples, q_range, [0, 0, u32::MAX, u32::MAX], [0, 0]);
            inside.bounds?;
            let object = scene.objects.get(index)?;
            let outside = match &wide_view {
                Some(wide_view) if !view.holds_box(object.min, object.max) => {
                    let mut tris = Vec::new();
                    for i in object.first..object.end {
                        screen_triangle::setup(&scene.triangles[i], i as u32, wide_view, &mut tris);
                    }
                    bands
                        .iter()
                        .map(|band| cover(&tris, samples, q_range, *band, shift))
                        .fold(Coverage::default(), Coverage::join)
                }
                _ => Coverage::default(),
            };
            inside.footprint(id, outside)
        })
        .collect()
}

/// Pixels covered by some triangles: their count and inclusive box.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Coverage {
    pub pixels: u64,
    pub bounds: Option<[i64; 4]>,
}

impl Coverage {
    /// Both coverages together (they must not share a pixel).
    pub(crate) fn join(self, other: Coverage) -> Coverage {
        let bounds = match (self.bounds, other.bounds) {
            (Some(a), Some(b)) => Some([
                a[0].min(b[0]),
                a[1].min(b[1]),
                a[2].max(b[2]),
                a[3].max(b[3]),
            ]),
            (a, b) => a.or(b),
        };
        Coverage {
            pixels: self.pixels + other.pixels,
            bounds,
        }
    }

    /// The footprint of object `id` whose pixels in the image are `self` and beyond it
    /// `outside`, or `None` when it covers no pixel of the image.
    pub(crate) fn footprint(self, id: u32, outside: Coverage) -> Option<Footprint> {
        self.bounds?;
        let all = self.join(outside);
        Some(Footprint {
            id,
            bounds: all.bounds?,
            pixels: all.pixels,
            inside: self.pixels,
        })
    }
}

/// The output pixels `tris` cover inside `clip` (internal pixels `[x0, y0, x1, y1)`), the
/// triangles being set up for `samples` per pixel side and `q_range` the accepted
/// `(1/far, 1.0001/near]` of 1/w, as the tiles use; positions moved by `-shift`.
pub(crate) fn cover(
    tris: &[ScreenTri],
    samples: u32,
    q_range: (f64, f64),
    clip: [u32; 4],
    shift: [i64; 2],
) -> Coverage {
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
    let bounds = [
        bounds[0].max(clip[0]),
        bounds[1].max(clip[1]),
        bounds[2].min(clip[2]),
        bounds[3].min(clip[3]),
    ];
    if bounds[0] >= bounds[2] || bounds[1] >= bounds[3] {
        return Coverage::default();
    }
    // Output pixels whose centre sample lies inside the internal bounds.
    let ox0 = bounds[0].saturating_sub(mid).div_ceil(s);
    let oy0 = bounds[1].saturating_sub(mid).div_ceil(s);
    let ox1 = (bounds[2] + s - 1 - mid) / s;
    let oy1 = (bounds[3] + s - 1 - mid) / s;
    if ox0 >= ox1 || oy0 >= oy1 {
        return Coverage::default();
    }
    let bw = (ox1 - ox0) as usize;
    let mut covered = vec![false; bw * (oy1 - oy0) as usize];
    let (q_min, q_max) = q_range;
    let accepted = |q: f64| q > q_min && q <= q_max;
    if s == 1 {
        // Every sample is its pixel's centre (no modulo per sample).
        let (ox0, oy0) = (ox0 as usize, oy0 as usize);
        for t in tris {
            t.rasterize(bounds, |x, y, q| {
                if accepted(q) {
                    covered[(y as usize - oy0) * bw + x as usize - ox0] = true;
                }
            });
        }
    } else {
        for t in tris {
            t.rasterize(bounds, |x, y, q| {
                if x % s == mid && y % s == mid && accepted(q) {
                    covered[(y / s - oy0) as usize * bw + (x / s - ox0) as usize] = true;
                }
            });
        }
    }
    // Count and box, a row at a time.
    let mut pixels = 0u64;
    let mut bounds: Option<[i64; 4]> = None;
    for (row, line) in covered.chunks_exact(bw).enumerate() {
        let Some(first) = line.iter().position(|&c| c) else {
            continue;
        };
        let last = line.iter().rposition(|&c| c).expect("a covered pixel");
        pixels += line[first..=last].iter().filter(|&&c| c).count() as u64;
        let y = i64::from(oy0) + row as i64 - shift[1];
        let (x0, x1) = (
            i64::from(ox0) + first as i64 - shift[0],
            i64::from(ox0) + last as i64 - shift[0],
        );
        bounds = Some(match bounds {
            None => [x0, y, x1, y],
            Some(b) => [b[0].min(x0), b[1], b[2].max(x1), y],
        });
    }
    Coverage { pixels, bounds }
}
