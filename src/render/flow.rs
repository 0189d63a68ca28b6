//! A frame's depth, its pose and the next frame's pose → forward optical flow: where each
//! pixel's surface point lands in the next frame, the camera moving and, with moving
//! traffic ([`Motion`]), the point moving with its object.
//!
//! Pixel `(x, y)`'s point is its centre `(x + ½, y + ½)` unprojected at the frame's depth
//! there (the depth of the surface the centre sample saw), then projected by the next
//! pose. The flow is valid where that point lies in front of the next camera, inside its
//! image, and is what the next frame sees there: the next pose's depth (a depth-only
//! render, [`super::visibility`]) agrees with the point's own depth within 1 % + 5 cm,
//! interpolated at the landing point or at one of the four pixels round it. The sky (no depth) has no flow; nor has a
//! point the next frame hides behind something nearer or sees past.

use image::{ImageBuffer, Luma, Rgb};
use rayon::prelude::*;

use super::view::View;
use super::{CameraPose, Intrinsics, PreparedScene};
use crate::model::Movement;
use crate::model::image_file::{PngEffort, encode_png};

/// Forward flow of one frame, row-major: per pixel `(u, v)` in pixels and whether it is
/// valid (`(0, 0)` where it is not).
#[derive(Clone, Debug, PartialEq)]
pub struct Flow {
    pub width: u32,
    pub height: u32,
    pub uv: Vec<[f32; 2]>,
    pub valid: Vec<bool>,
}

/// How far (relative, and metres) the next frame's depth may differ from a point's own
/// for the point to count as seen there.
const AGREE_RELATIVE: f64 = 0.01;
const AGREE_METRES: f64 = 0.05;

/// How the scene's objects move between the two frames: each pixel's point moves with the
/// object its instance id names (`next`'s offset less `now`'s).
pub struct Motion<'a> {
    /// The frame's instance ids.
    pub instance: &'a ImageBuffer<Luma<u32>, Vec<u32>>,
    pub now: &'a Movement,
    pub next: &'a Movement,
}

/// The flow from the frame seen from `pose` with `depth` (metres along the view axis, 0 for
/// the sky) to the frame `next` sees of `scene` (posed as the next frame has it), both with
/// intrinsics `k`; with `motion`, each point moves with its object.
pub fn flow(
    scene: &PreparedScene,
    depth: &ImageBuffer<Luma<f32>, Vec<f32>>,
    motion: Option<&Motion>,
    pose: &CameraPose,
    next: &CameraPose,
    k: &Intrinsics,
) -> Flow {
    let (width, height) = depth.dimensions();
    let n = width as usize * height as usize;
    let none = Flow {
        width,
        height,
        uv: vec![[0.0; 2]; n],
        valid: vec![false; n],
    };
    let (Some(view), Some(next_view)) = (View::new(pose, k, 1), View::new(next, k, 1)) else {
        return none;
    };
    if (width, height) != (k.width, k.height) || n == 0 {
        return none;
    }
    let (seen, _) = super::visibility(scene, next, k, &[]);
    let w = width as usize;
    // Per moving instance, how far it moves to the next frame.
    let moves: Vec<(u32, [f64; 3])> = motion.map_or_else(Vec::new, |m| {
        m.now
            .moves
            .iter()
            .map(|&(id, o)| {
                let n = m.next.offset(id);
                (id, [n[0] - o[0], n[1] - o[1], n[2] - o[2]])
            })
            .filter(|(_, d)| *d != [0.0; 3])
            .collect()
    });
    let moved = |x: usize, y: usize, p: [f64; 3]| {
        let Some(m) = motion.filter(|_| !moves.is_empty()) else {
            return p;
        };
        let id = m.instance.as_raw()[y * w + x];
        match moves.binary_search_by_key(&id, |(i, _)| *i) {
            Ok(k) => std::array::from_fn(|j| p[j] + moves[k].1[j]),
            Err(_) => p,
        }
    };
    let rows: Vec<(Vec<[f32; 2]>, Vec<bool>)> = (0..height as usize)
        .into_par_iter()
        .map(|y| {
            (0..w)
                .map(|x| {
                    let d = f64::from(depth.as_raw()[y * w + x]);
                    let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
                    let landing = (d > 0.0)
                        .then(|| next_view.to_camera(moved(x, y, view.unproject(px, py, d))))
                        .filter(|c| c[2] > next_view.near)
                        .map(|c| (next_view.project(c), c[2]))
                        .filter(|(p, z)| seen_at(&seen.depth, *p, *z));
                    match landing {
                        Some((p, _)) => ([(p[0] - px) as f32, (p[1] - py) as f32], true),
                        None => ([0.0; 2], false),
                    }
                })
                .unzip()
        })
        .collect();
    let (mut uv, mut valid) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for (u, v) in rows {
        uv.extend(u);
        valid.extend(v);
    }
    Flow {
        width,
        height,
        uv,
        valid,
    }
}

/// Whether a point at depth `z` landing at pixel position `p` is what `depth` shows
/// there: inside the image, and either the depth interpolated there from the four pixels
/// round `p` (whose centres surround it) agrees with `z` (inverse depth, which is affine
/// over a plane's image, bilinearly, so a slanted road far ahead agrees), or one of those
/// four pixels does (at an object's edge, where they show different surfaces).
fn seen_at(depth: &ImageBuffer<Luma<f32>, Vec<f32>>, p: [f64; 2], z: f64) -> bool {
    let (w, h) = depth.dimensions();
    if !(p[0] >= 0.0 && p[1] >= 0.0 && p[0] < f64::from(w) && p[1] < f64::from(h)) {
        return false;
    }
    let (x0, y0) = ((p[0] - 0.5).floor(), (p[1] - 0.5).floor());
    let (fx, fy) = (p[0] - 0.5 - x0, p[1] - 0.5 - y0);
    let tolerance = AGREE_RELATIVE * z + AGREE_METRES;
    // The four pixels' depths, clamped to the image (0: the sky).
    let corner = |k: u32| {
        let x = (x0 + f64::from(k & 1)).clamp(0.0, f64::from(w - 1));
        let y = (y0 + f64::from(k >> 1)).clamp(0.0, f64::from(h - 1));
        f64::from(depth.get_pixel(x as u32, y as u32)[0])
    };
    let d = [corner(0), corner(1), corner(2), corner(3)];
    if d.iter().all(|d| *d > 0.0) {
        let inverse =
            (1.0 - fy) * ((1.0 - fx) / d[0] + fx / d[1]) + fy * ((1.0 - fx) / d[2] + fx / d[3]);
        if (1.0 / inverse - z).abs() <= tolerance {
            return true;
        }
    }
    d.iter().any(|d| *d > 0.0 && (d - z).abs() <= tolerance)
}

impl Flow {
    /// The KITTI flow PNG (the KITTI 2015 devkit's encoding): 16-bit RGB, `R = u · 64 +
    /// 2¹⁵`, `G = v · 64 + 2¹⁵` (rounded, clamped to 0–65535, so ±512 px), `B` = 1 where
    /// valid; `(0, 0, 0)` where not.
    pub fn kitti_png(&self) -> Vec<u8> {
        let code = |f: f32| (f64::from(f) * 64.0 + 32768.0).round().clamp(0.0, 65535.0) as u16;
        let image = ImageBuffer::<Rgb<u16>, Vec<u16>>::from_fn(self.width, self.height, |x, y| {
            let i = y as usize * self.width as usize + x as usize;
            if self.valid[i] {
                Rgb([code(self.uv[i][0]), code(self.uv[i][1]), 1])
            } else {
                Rgb([0, 0, 0])
            }
        });
        encode_png(&image, PngEffort::Fast)
    }
}
