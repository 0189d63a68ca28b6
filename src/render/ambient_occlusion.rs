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
//! At each pixel's centre sample: its camera-space point `P` (from the depth) and the face
//! normal `n` of its triangle (exact, from the triangle id; no reconstruction). Along 8
//! fixed screen directions, 2 steps out to the projection of [`RADIUS`] metres, each step
//! reads the point `S` of that pixel and scores `max(0, n·(S − P)/|S − P| − BIAS) ·
//! (1 − |S − P|²/R²)`: how far above `P`'s tangent plane a nearby surface rises, fading to
//! nothing at `R` (so a foreground object far in front of `P` casts no halo). A
//! direction's occlusion is its largest score, the pixel's [`GAIN`] times their mean (at most
//! 1).
//! The steps start at a per-2 × 2-block offset from a fixed 4 × 4 pattern (ordered
//! dither), so the two rings blend into a smooth falloff instead of bands. It is
//! measured at one pixel of each 2 × 2 block; the others share that value where they lie on
//! the same surface, and are measured themselves at edges: a quarter of the work, and no
//! blur across silhouettes.
//!
//! Each pixel reads only the frame's buffers and writes only itself, in `f32` with
//! + − × ÷ and sqrt: the bytes do not depend on threads.

use rayon::prelude::*;

use super::tile::{FrameContext, NOTHING, TILE, TileRaster};

/// Reach of the occlusion, metres: the crease along a wall's foot, a car's or a bench's
/// shadowless contact darkening.
pub(crate) const RADIUS: f32 = 1.2;
/// Ignores surfaces rising less than this (sine of the angle) above the tangent plane:
/// flat ground does not occlude itself.
const BIAS: f32 = 0.1;
/// Screen directions.
const DIRECTIONS: usize = 8;
/// Steps per direction.
const STEPS: usize = 2;
/// Step offsets of the 4 × 4 ordered dither, in sixteenths of a step.
const DITHER: [u8; 16] = [0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5];
/// Occlusion per unit of the mean score: a ground point beside a wall scores in about a
/// third of its directions.
const GAIN: f32 = 2.0;
/// Largest reach on screen, output pixels (very near surfaces).
const MAX_PIXELS: f32 = 48.0;

/// Ambient visibility per output pixel, row-major: `1 − strength · occlusion`.
pub(crate) fn visibility(ctx: &FrameContext, rasters: &[TileRaster], strength: f32) -> Vec<f32> {
    let (w, h) = (ctx.width as usize, ctx.height as usize);
    let s = ctx.samples as usize;
    let view = ctx.view;
    let scale = ctx.samples as f32;
    // Output-pixel intrinsics.
    let (fx, fy) = (view.fx as f32 / scale, view.fy as f32 / scale);
    let (cx, cy) = (view.cx as f32 / scale, view.cy as f32 / scale);
    let basis = &view.basis;
    // Camera-space point (z = 0: sky) and normal of every pixel's centre sample.
    let mut points = vec![[0f32; 3]; w * h];
    let mut normals = vec![[0f32; 3]; w * h];
    points
        .par_chunks_mut(w)
        .zip(normals.par_chunks_mut(w))
        .enumerate()
        .for_each(|(y, (prow, nrow))| {
            let ty = y / TILE as usize;
            // Neighbouring pixels mostly show the same triangle: its normal is kept.
            let mut last = (NOTHING, [0f32; 3]);
            for (x, (p, n)) in prow.iter_mut().zip(nrow.iter_mut()).enumerate() {
                let raster = &rasters[ty * ctx.tiles_x as usize + x / TILE as usize];
                let i = raster.centre(x - raster.rect[0] as usize, y - raster.rect[1] as usize, s);
                let t = raster.id[i];
                if t == NOTHING {
                    continue;
                }
                let z = (1.0 / raster.depth[i]) as f32;
                let (px, py) = (x as f32 + 0.5, y as f32 + 0.5);
                *p = [(px - cx) / fx * z, -(py - cy) / fy * z, z];
                if last.0 != t {
                    let source = &ctx.scene.triangles[ctx.tris[t as usize].source as usize];
                    let m = source.normal.map(f64::from);
                    let d = |a: [f64; 3]| (a[0] * m[0] + a[1] * m[1] + a[2] * m[2]) as f32;
                    last = (t, [d(basis.right), d(basis.up), d(basis.forward)]);
                }
                *n = last.1;
            }
        });

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
    let occlusion = |x: usize, y: usize| -> f32 {
        let p = points[y * w + x];
        if p[2] <= 0.0 {
            return 1.0;
        }
        let n = normals[y * w + x];
        let reach = (RADIUS * fx / p[2]).min(MAX_PIXELS);
        if reach < 2.0 {
            // Creases under two pixels wide: too small to show, and far away.
            return 1.0;
        }
        let jitter = f32::from(DITHER[(y / 2 % 4) * 4 + x / 2 % 4]) / 16.0;
        let mut sum = 0.0;
        for d in &dirs {
            let mut best = 0f32;
            for step in 0..STEPS {
                let t = reach * (step as f32 + 0.25 + 0.75 * jitter) / STEPS as f32;
                let sx = x as f32 + 0.5 + d[0] * t;
                let sy = y as f32 + 0.5 + d[1] * t;
                if sx < 0.0 || sy < 0.0 || sx >= w as f32 || sy >= h as f32 {
                    break;
                }
                let q = points[sy as usize * w + sx as usize];
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
        1.0 - strength * (GAIN * sum / DIRECTIONS as f32).min(1.0)
    };
    // Measured at the even pixels of even rows; the others take their 2 × 2 block's
    // value where they lie on the same surface (the block's point within 1 % of the depth
    // of this pixel's plane, normals within ~25°), and are measured themselves at edges
    // and creases.
    let (w2, h2) = (w.div_ceil(2), h.div_ceil(2));
    let mut coarse = vec![1f32; w2 * h2];
    coarse.par_chunks_mut(w2).enumerate().for_each(|(j, row)| {
        for (i, slot) in row.iter_mut().enumerate() {
            *slot = occlusion(2 * i, 2 * j);
        }
    });
    let mut out = vec![1f32; w * h];
    out.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, slot) in row.iter_mut().enumerate() {
            let (rx, ry) = (x & !1, y & !1);
            let (p, r) = (points[y * w + x], points[ry * w + rx]);
            let (n, m) = (normals[y * w + x], normals[ry * w + rx]);
            let v = [r[0] - p[0], r[1] - p[1], r[2] - p[2]];
            let same = r[2] > 0.0
                && (n[0] * v[0] + n[1] * v[1] + n[2] * v[2]).abs() <= 0.01 * p[2]
                && n[0] * m[0] + n[1] * m[1] + n[2] * m[2] >= 0.9;
            *slot = if same {
                coarse[(y / 2) * w2 + x / 2]
            } else {
                occlusion(x, y)
            };
        }
    });
    out
}
