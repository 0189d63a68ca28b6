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

/// Ambient visibility per output pixel, row-major: `1 − strength · occlusion`.
pub(crate) fn visibility(ctx: &RasterContext, centres: &CentreSamples, strength: f32) -> Vec<f32> {
    let (w, h) = (centres.width, centres.height);
    let view = ctx.view;
    let scale = ctx.samples as f32;
    // Output-pixel intrinsics.
    let (fx, fy) = (view.fx as f32 / scale, view.fy as f32 / scale);
    let (cx, cy) = (view.cx as f32 / scale, view.cy as f32 / scale);
    let basis = &view.basis;
    // A pixel's camera-space point is `[across[x] · z, down[y] · z, z]`.
    let across: Vec<f32> = (0..w).map(|x| (x as f32 + 0.5 - cx) / fx).collect();
    let down: Vec<f32> = (0..h).map(|y| -(y as f32 + 0.5 - cy) / fy).collect();
    let (tri, z) = (&centres.tri, &centres.z);
    let point = |x: usize, y: usize| {
        let z = z[y * w + x];
        [across[x] * z, down[y] * z, z]
    };
    // Camera-space face normals of the triangles the pixels show, by screen triangle.
    let mut shown = vec![false; ctx.tris.len()];
    for &t in tri {
        if t != NOTHING {
            shown[t as usize] = true;
        }
    }
    let normals: Vec<[f32; 3]> = ctx
        .tris
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
        .collect();

    let dirs: [[f32; 2]; DIRECTIONS] = std::array::from_fn(|k| {
        // cos and sin of k · 45°, exactly.
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
        ][k]
    });
    let r2 = RADIUS * RADIUS;
    // Which of the directions a pixel measures: every other one from `first`.
    let occlusion = |x: usize, y: usize, first: usize, every: usize| -> f32 {
        let p = point(x, y);
        if p[2] <= 0.0 {
            return 1.0;
        }
        let n = normals[tri[y * w + x] as usize];
        let reach = (RADIUS * fx / p[2]).min(MAX_PIXELS);
        if reach < 2.0 {
            // Creases under two pixels wide: too small to show, and far away.
            return 1.0;
        }
        let jitter = f32::from(DITHER[(y / GRID % 4) * 4 + x / GRID % 4]) / 16.0;
        let mut sum = 0.0;
        for d in dirs.iter().skip(first).step_by(every) {
            let mut best = 0f32;
            for step in 0..STEPS {
                let t = reach * (step as f32 + 0.25 + 0.75 * jitter) / STEPS as f32;
                let sx = x as f32 + 0.5 + d[0] * t;
                let sy = y as f32 + 0.5 + d[1] * t;
                if sx < 0.0 || sy < 0.0 || sx >= w as f32 || sy >= h as f32 {
                    break;
                }
                let q = point(sx as usize, sy as usize);
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
            sum += best;
        }
        1.0 - strength * (GAIN * sum / (DIRECTIONS / every) as f32).min(1.0)
    };
    // Measured on the grid, then blended per pixel (see the module's docs).
    let (wc, hc) = ((w - 1) / GRID + 1, (h - 1) / GRID + 1);
    let mut coarse = vec![1f32; wc * hc];
    coarse.par_chunks_mut(wc).enumerate().for_each(|(j, row)| {
        for (i, slot) in row.iter_mut().enumerate() {
            *slot = occlusion(GRID * i, GRID * j, (i + j) % 2, 2);
        }
    });
    let mut out = vec![1f32; w * h];
    out.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        let (j0, fy) = (y / GRID, y % GRID);
        // Grid sample (i, j): its pixel, triangle and value; none outside the grid.
        let sample = |i: usize, j: usize| {
            (i < wc && j < hc).then(|| {
                let (gx, gy) = (GRID * i, GRID * j);
                (gx, gy, tri[gy * w + gx], coarse[j * wc + i])
            })
        };
        for (i0, cell) in row.chunks_mut(GRID).enumerate() {
            // The cell's four grid samples, read once for its GRID pixels of this row,
            // with their weight factors along y.
            let corners = [
                (sample(i0, j0), false, GRID - fy),
                (sample(i0 + 1, j0), true, GRID - fy),
                (sample(i0, j0 + 1), false, fy),
                (sample(i0 + 1, j0 + 1), true, fy),
            ];
            // Open all round (every grid sample 1, as on open ground, mid-wall or far
            // away): any blend of them is exactly 1, the value already in place, so a
            // pixel with a sample on its own triangle is done.
            let open = corners.iter().all(|(c, _, _)| c.is_none_or(|c| c.3 == 1.0));
            for (fx, slot) in cell.iter_mut().enumerate() {
                let x = i0 * GRID + fx;
                let t = tri[y * w + x];
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
                // This pixel's point and normal, worked out at the first sample on another
                // triangle (most pixels have none around them).
                let mut own = None;
                let (mut sum, mut weight) = (0f32, 0usize);
                for &(corner, right, ky) in &corners {
                    let k = if right { fx } else { GRID - fx } * ky;
                    let Some((gx, gy, u, value)) = corner.filter(|_| k > 0) else {
                        continue;
                    };
                    // A sample on this pixel's own triangle is on its surface; another
                    // triangle's is when it lies in this pixel's plane and faces its way.
                    let same = u == t
                        || u != NOTHING && {
                            let (p, n) =
                                *own.get_or_insert_with(|| (point(x, y), normals[t as usize]));
                            let (r, m) = (point(gx, gy), normals[u as usize]);
                            let v = [r[0] - p[0], r[1] - p[1], r[2] - p[2]];
                            (n[0] * v[0] + n[1] * v[1] + n[2] * v[2]).abs() <= 0.01 * p[2]
                                && n[0] * m[0] + n[1] * m[1] + n[2] * m[2] >= 0.9
                        };
                    if same {
                        sum += k as f32 * value;
                        weight += k;
                    }
                }
                *slot = if weight > 0 {
                    sum / weight as f32
                } else {
                    occlusion(x, y, 0, 1)
                };
            }
        }
    });
    out
}
