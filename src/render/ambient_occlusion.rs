//! Rasterized tiles + view → ambient visibility per output pixel (1 = open sky, lower in
//! creases and under things): screen-space ambient occlusion from the depth buffer.
//!
//! # Why screen space, and not baked
//!
//! The city is made of large flat quads: a wall is two triangles, a road a handful. Baking
//! per vertex would need every surface subdivided to show a crease along a wall's foot,
//! and baking per texel needs a lightmap atlas over hundreds of thousands of triangles,
//! built in the cold build (which has half a second for everything). From the depth
//! buffer the cost follows the pixels, not the scene, one pass after visibility, and
//! every object (walls, benches, signs, cars, trees, lamps) darkens its surroundings
//! without any change to the meshes or the cache. It is what a frame shows only; it
//! changes no id, depth or label.
//!
//! # Method
//!
//! At each pixel's centre sample ([`CentreSamples`]): its camera-space point `P` (from the
//! depth) and the face normal `n` of its triangle (exact, from the triangle id; no
//! reconstruction). Along 8 fixed screen directions, 2 steps out to the projection of
//! [`RADIUS`] metres, each step reads the point `S` of that pixel and scores `max(0,
//! n·(S − P)/|S − P| − BIAS) · (1 − |S − P|²/R²)`: how far above `P`'s tangent plane a
//! nearby surface rises, fading to nothing at `R` (so a foreground object far in front of
//! `P` casts no halo). A direction's occlusion is its largest score, the pixel's [`GAIN`]
//! times their mean (at most 1).
//!
//! It is measured at every [`GRID`]-th pixel of every `GRID`-th row, the steps starting at
//! an offset per grid cell from a fixed 4 × 4 pattern (ordered dither), so the two rings
//! blend into a smooth falloff instead of bands. A grid sample measures every other
//! direction, the straight four or the diagonal four in a checkerboard, so the four a
//! pixel blends cover all eight at half the taps (day street frames: 94 → 90 CPU ms; the
//! RGB image moves by more than 4 of 255 on 0.07 % of pixels). Every pixel then blends
//! the four grid samples around it by their bilinear weights, keeping those on its own
//! surface (its own triangle, or a point in its plane with a normal within ~25°), and is
//! measured itself, in all eight directions, only where none is: at silhouettes and on
//! surfaces thinner than the grid. A thirty-second of the taps, no blur across
//! silhouettes, and a smooth gradient where a crease is wider than the grid. The taps are
//! what costs: they read scattered pixels of the depth buffer, so a measured pixel costs
//! as much as its cache misses.
//!
//! Each pixel reads only the frame's buffers and writes only itself, in `f32` with
//! + − × ÷ and sqrt: the bytes do not depend on threads.

use rayon::prelude::*;

use super::centre_samples::CentreSamples;
use super::tile::{NOTHING, RasterContext};

/// Reach of the occlusion, metres: the crease along a wall's foot, a car's or a bench's
/// shadowless contact darkening.
pub(crate) const RADIUS: f32 = 1.2;
/// Ignores surfaces rising less than this (sine of the angle) above the tangent plane:
/// flat ground does not occlude itself.
const BIAS: f32 = 0.1;
/// Screen directions (a grid sample measures half of them, a pixel measured alone all).
const DIRECTIONS: usize = 8;
/// Steps per direction.
const STEPS: usize = 2;
/// Step offsets of the 4 × 4 ordered dither, in sixteenths of a step.
const DITHER: [u8; 16] = [0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5];
/// Occlusion per unit of the mean score: a ground point beside a wall scores in about a
/// third of its directions.
const GAIN: f32 = 2.0;
/// Spacing of the pixels measured, output pixels (see [`visibility`]).
const GRID: usize = 4;
/// Largest reach on screen, output pixels (very near surfaces).
const MAX_PIXELS: f32 = 48.0;

/// The screen directions, `k · 45°` for `k` in `0..8`: cos and sin exactly.
const DIRS: [[f32; 2]; DIRECTIONS] = {
    let c = std::f32::consts::FRAC_1_SQRT_2;
    [
        [1.0, 0.0],
        [c, c],
        [0.0, 1.0],
        [-c, c],
        [-1.0, 0.0],
        [-c, -c],
        [0.0, -1.0],
        [c, -c],
    ]
};

/// Ambient visibility per output pixel, row-major: `1 − strength · occlusion`.
pub(crate) fn visibility(ctx: &RasterContext, centres: &CentreSamples, strength: f32) -> Vec<f32> {
    let field = Field::new(ctx, centres, strength);
    // Measured on the grid, then blended per pixel (see the module's docs).
    let grid = field.measure_grid();
    field.blend(&grid)
}

/// What the measurement reads of a frame: each pixel's camera-space point (from its depth)
/// and the face normal of its triangle.
struct Field<'a> {
    w: usize,
    h: usize,
    /// Output-pixel focal length along x.
    fx: f32,
    /// A pixel's camera-space point is `[across[x] · z, down[y] · z, z]`.
    across: Vec<f32>,
    down: Vec<f32>,
    tri: &'a [u32],
    z: &'a [f32],
    /// Camera-space face normals of the triangles the pixels show, by screen triangle.
    normals: Vec<[f32; 3]>,
    strength: f32,
}

/// A grid sample: its pixel, triangle and value.
type GridSample = (usize, usize, u32, f32);

/// One of a cell's four grid samples (none outside the grid), whether it lies right of
/// the cell's pixels, and its weight factor along y.
type Corner = (Option<GridSample>, bool, usize);

/// The grid's values, row-major, `wc` a row.
struct Grid {
    values: Vec<f32>,
    wc: usize,
    hc: usize,
}

impl<'a> Field<'a> {
    fn new(ctx: &RasterContext, centres: &'a CentreSamples, strength: f32) -> Field<'a> {
        let (w, h) = (centres.width, centres.height);
        let view = ctx.view;
        let scale = ctx.samples as f32;
        // Output-pixel intrinsics.
        let (fx, fy) = (view.fx as f32 / scale, view.fy as f32 / scale);
        let (cx, cy) = (view.cx as f32 / scale, view.cy as f32 / scale);
        Field {
            w,
            h,
            fx,
            across: (0..w).map(|x| (x as f32 + 0.5 - cx) / fx).collect(),
            down: (0..h).map(|y| -(y as f32 + 0.5 - cy) / fy).collect(),
            tri: &centres.tri,
            z: &centres.z,
            normals: face_normals(ctx, &centres.tri),
            strength,
        }
    }

    fn point(&self, x: usize, y: usize) -> [f32; 3] {
        let z = self.z[y * self.w + x];
        [self.across[x] * z, self.down[y] * z, z]
    }

    /// The grid samples' values: every [`GRID`]-th pixel of every `GRID`-th row, each
    /// measuring every other direction, alternating in a checkerboard.
    fn measure_grid(&self) -> Grid {
        let (wc, hc) = ((self.w - 1) / GRID + 1, (self.h - 1) / GRID + 1);
        let mut values = vec![1f32; wc * hc];
        values.par_chunks_mut(wc).enumerate().for_each(|(j, row)| {
            for (i, slot) in row.iter_mut().enumerate() {
                *slot = self.occlusion(GRID * i, GRID * j, (i + j) % 2, 2);
            }
        });
        Grid { values, wc, hc }
    }

    /// The visibility at pixel `(x, y)` from the directions `first`, `first + every`, ….
    fn occlusion(&self, x: usize, y: usize, first: usize, every: usize) -> f32 {
        let p = self.point(x, y);
        if p[2] <= 0.0 {
            return 1.0;
        }
        let n = self.normals[self.tri[y * self.w + x] as usize];
        let reach = (RADIUS * self.fx / p[2]).min(MAX_PIXELS);
        if reach < 2.0 {
            // Creases under two pixels wide: too small to show, and far away.
            return 1.0;
        }
        let jitter = f32::from(DITHER[(y / GRID % 4) * 4 + x / GRID % 4]) / 16.0;
        let mut sum = 0.0;
        let centre = [x as f32 + 0.5, y as f32 + 0.5];
        for d in DIRS.iter().skip(first).step_by(every) {
            sum += self.rise_along(centre, p, n, *d, reach, jitter);
        }
        1.0 - self.strength * (GAIN * sum / (DIRECTIONS / every) as f32).min(1.0)
    }

    /// One direction's score at the pixel whose centre is `centre` (point `p`, normal `n`):
    /// the largest of its [`STEPS`] taps out to `reach` pixels.
    fn rise_along(
        &self,
        centre: [f32; 2],
        p: [f32; 3],
        n: [f32; 3],
        d: [f32; 2],
        reach: f32,
        jitter: f32,
    ) -> f32 {
        let r2 = RADIUS * RADIUS;
        let (w, h) = (self.w, self.h);
        let mut best = 0f32;
        for step in 0..STEPS {
            let t = reach * (step as f32 + 0.25 + 0.75 * jitter) / STEPS as f32;
            let sx = centre[0] + d[0] * t;
            let sy = centre[1] + d[1] * t;
            if sx < 0.0 || sy < 0.0 || sx >= w as f32 || sy >= h as f32 {
                break;
            }
            let q = self.point(sx as usize, sy as usize);
            if q[2] <= 0.0 {
                continue;
            }
            let v = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
            let l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            if l2 >= r2 || l2 <= 1e-8 {
                continue;
            }
            let above = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
            // Scores nothing unless `above / |v| > BIAS`: most taps (flat ground, open
            // walls) are settled here, without the square root and the division.
            if above <= 0.0 || above * above <= BIAS * BIAS * l2 {
                continue;
            }
            let rise = above / l2.sqrt() - BIAS;
            best = best.max(rise * (1.0 - l2 / r2));
        }
        best
    }

    /// Every pixel's visibility from the grid samples around it (see the module's docs).
    fn blend(&self, grid: &Grid) -> Vec<f32> {
        let w = self.w;
        let mut out = vec![1f32; w * self.h];
        out.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
            let (j0, fy) = (y / GRID, y % GRID);
            // Grid sample (i, j): its pixel, triangle and value; none outside the grid.
            let sample = |i: usize, j: usize| {
                (i < grid.wc && j < grid.hc).then(|| {
                    let (gx, gy) = (GRID * i, GRID * j);
                    (gx, gy, self.tri[gy * w + gx], grid.values[j * grid.wc + i])
                })
            };
            for (i0, cell) in row.chunks_mut(GRID).enumerate() {
                // The cell's four grid samples, read once for its GRID pixels of this row,
                // with their weight factors along y.
                let corners: [Corner; 4] = [
                    (sample(i0, j0), false, GRID - fy),
                    (sample(i0 + 1, j0), true, GRID - fy),
                    (sample(i0, j0 + 1), false, fy),
                    (sample(i0 + 1, j0 + 1), true, fy),
                ];
                self.blend_cell(y, i0, cell, &corners);
            }
        });
        out
    }

    /// The pixels of row `y` in grid cell `i0` (`cell`), from the cell's corners.
    fn blend_cell(&self, y: usize, i0: usize, cell: &mut [f32], corners: &[Corner; 4]) {
        // Open all round (every grid sample 1, as on open ground, mid-wall or far away):
        // any blend of them is exactly 1, the value already in place, so a pixel with a
        // sample on its own triangle is done.
        let open = corners.iter().all(|(c, _, _)| c.is_none_or(|c| c.3 == 1.0));
        for (fx, slot) in cell.iter_mut().enumerate() {
            let x = i0 * GRID + fx;
            let t = self.tri[y * self.w + x];
            if t == NOTHING {
                continue;
            }
            if open
                && corners.iter().any(|&(c, right, ky)| {
                    let k = if right { fx } else { GRID - fx } * ky;
                    k > 0 && c.is_some_and(|c| c.2 == t)
                })
            {
                continue;
            }
            *slot = self.blend_pixel(x, y, t, fx, corners);
        }
    }

    /// Pixel `(x, y)` on screen triangle `t`, `fx` pixels into its cell: the weighted mean
    /// of the corners on its own surface, or its own measurement where none is.
    fn blend_pixel(&self, x: usize, y: usize, t: u32, fx: usize, corners: &[Corner; 4]) -> f32 {
        // This pixel's point and normal, worked out at the first sample on another
        // triangle (most pixels have none around them).
        let mut own = None;
        let (mut sum, mut weight) = (0f32, 0usize);
        for &(corner, right, ky) in corners {
            let k = if right { fx } else { GRID - fx } * ky;
            let Some((gx, gy, u, value)) = corner.filter(|_| k > 0) else {
                continue;
            };
            // A sample on this pixel's own triangle is on its surface; another
            // triangle's is when it lies in this pixel's plane and faces its way.
            let same = u == t
                || u != NOTHING && {
                    let (p, n) =
                        *own.get_or_insert_with(|| (self.point(x, y), self.normals[t as usize]));
                    let (r, m) = (self.point(gx, gy), self.normals[u as usize]);
                    let v = [r[0] - p[0], r[1] - p[1], r[2] - p[2]];
                    (n[0] * v[0] + n[1] * v[1] + n[2] * v[2]).abs() <= 0.01 * p[2]
                        && n[0] * m[0] + n[1] * m[1] + n[2] * m[2] >= 0.9
                };
            if same {
                sum += k as f32 * value;
                weight += k;
            }
        }
        if weight > 0 {
            sum / weight as f32
        } else {
            self.occlusion(x, y, 0, 1)
        }
    }
}

/// Camera-space face normals of the triangles `tri` shows, by screen triangle (zero for
/// the others).
fn face_normals(ctx: &RasterContext, tri: &[u32]) -> Vec<[f32; 3]> {
    let basis = &ctx.view.basis;
    let mut shown = vec![false; ctx.tris.len()];
    for &t in tri {
        if t != NOTHING {
            shown[t as usize] = true;
        }
    }
    ctx.tris
        .par_iter()
        .zip(shown)
        .map(|(t, shown)| {
            if !shown {
                return [0.0; 3];
            }
            let m = ctx.scene.triangles[t.source as usize].normal.map(f64::from);
            let d = |a: [f64; 3]| (a[0] * m[0] + a[1] * m[1] + a[2] * m[2]) as f32;
            [d(basis.right), d(basis.up), d(basis.forward)]
        })
        .collect()
}
