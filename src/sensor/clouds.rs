//! Sky pixels + the frame's sun and sky light + drawn cover → clouds: a layer of cumulus
//! [`ALTITUDE`] metres up, its pattern a fixed tiling field of fractal value noise
//! ([`FIELD`]² cells over [`CLOUD_TILE`] metres), shifted per path by
//! `Conditions::cloud_offset`.
//!
//! A sky pixel's ray meets the layer at a point; the field there, against the threshold
//! that leaves `cover` of the field's cells above it (so `cover` is the share of the layer
//! under cloud), gives the cloud's opacity, soft over a band of the field's values. A
//! cloud is lit as a white surface facing down and out: the sun's light (brighter towards
//! the sun, none at night) and the sky's, its thick cores darker. Clouds thin towards the
//! horizon (haze) and vanish just above it, where the layer's pattern would shrink below a
//! pixel and flicker.
//!
//! Everything is `f32` arithmetic per pixel on a table built once with integer hashing:
//! the same bits on every machine and thread count. Only sky pixels (depth 0) change.

use std::sync::OnceLock;

use rayon::prelude::*;

use super::conditions::CLOUD_TILE;
use super::noise::splitmix;
use super::rays::Rays;

/// Height of the cloud layer above the ground, metres.
pub const ALTITUDE: f32 = 1200.0;
/// Cells per side of the noise field.
pub const FIELD: usize = 512;
/// Octaves of the field: its coarsest lattice cell is `FIELD / 8` cells (1 km), its finest 2
/// (32 m), each octave half the last's amplitude.
const OCTAVES: u32 = 6;
/// The field's band over which a cloud's edge goes from clear to opaque.
const SOFTNESS: f32 = 0.09;

/// The sun and sky light on the clouds, linear.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CloudLight {
    /// Unit direction towards the sun.
    pub sun_direction: [f32; 3],
    pub sun_colour: [f32; 3],
    /// The sky's light on an upward surface.
    pub sky: [f32; 3],
}

/// The noise field (values 0–1, row-major, tiling) and its values sorted (for the cover
/// thresholds).
struct Field {
    values: Vec<f32>,
    sorted: Vec<f32>,
}

fn field() -> &'static Field {
    static FIELD_CELLS: OnceLock<Field> = OnceLock::new();
    if let Some(field) = FIELD_CELLS.get() {
        return field;
    }
    // Built outside the lock: a rayon worker waiting inside `get_or_init`'s closure for
    // this parallel work steals other jobs, and one that calls `field()` (another build's
    // warm-up, in the same process) would wait on the lock it holds, forever. Two threads
    // may build the field at once; the first stored is kept (both are the same values).
    let built = build_field();
    FIELD_CELLS.get_or_init(|| built)
}

/// The noise field, on every core.
fn build_field() -> Field {
    let n = FIELD;
    // Value noise: a hashed lattice per octave, smoothly interpolated, tiling (each
    // octave's lattice divides the field).
    let lattice = |octave: u32, x: usize, y: usize| -> f32 {
        let h = splitmix((u64::from(octave) << 48) ^ ((x as u64) << 24) ^ (y as u64) ^ 0xC10D);
        (h >> 40) as f32 / (1u64 << 24) as f32
    };
    let mut values = vec![0f32; n * n];
    values.par_chunks_mut(n).enumerate().for_each(|(y, row)| {
        for (x, v) in row.iter_mut().enumerate() {
            let (mut sum, mut weight, mut amplitude) = (0f32, 0f32, 1f32);
            for octave in 0..OCTAVES {
                let cell = n >> (3 + octave);
                let cells = n / cell;
                let (fx, fy) = (x as f32 / cell as f32, y as f32 / cell as f32);
                let (x0, y0) = (x / cell, y / cell);
                let (tx, ty) = (smooth(fx - x0 as f32), smooth(fy - y0 as f32));
                let (x1, y1) = ((x0 + 1) % cells, (y0 + 1) % cells);
                let at = |a: usize, b: usize| lattice(octave, a, b);
                let top = at(x0, y0) + (at(x1, y0) - at(x0, y0)) * tx;
                let bottom = at(x0, y1) + (at(x1, y1) - at(x0, y1)) * tx;
                sum += (top + (bottom - top) * ty) * amplitude;
                weight += amplitude;
                amplitude *= 0.5;
            }
            *v = sum / weight;
        }
    });
    // `total_cmp` orders every bit pattern, so the parallel sort's order is the one
    // order there is.
    let mut sorted = values.clone();
    sorted.par_sort_unstable_by(f32::total_cmp);
    Field { values, sorted }
}

/// Builds the cloud layer's noise field now when a path may draw clouds (`most_cover`, its
/// largest cover, above 0). Built by its first frame instead, it took one core while the
/// frames beside it waited for it, idle: about 25 ms at the start of a street path.
pub fn warm(most_cover: f64) {
    if most_cover > 0.0 {
        field();
    }
}

/// `3t² − 2t³`.
fn smooth(t: f32) -> f32 {
    t * t * (3.0 - 2.0 * t)
}

fn smoothstep(a: f32, b: f32, x: f32) -> f32 {
    smooth(((x - a) / (b - a)).clamp(0.0, 1.0))
}

/// The field's value at `(u, v)` cells (any real; it tiles), bilinear.
fn sample(f: &Field, u: f32, v: f32) -> f32 {
    let n = FIELD as f32;
    // Wrapped into the tile by floor (one instruction; `rem_euclid` calls `fmodf`).
    let wrap = |t: f32| t - (t * (1.0 / n)).floor() * n;
    let (u, v) = (wrap(u), wrap(v));
    let (x0, y0) = ((u as usize).min(FIELD - 1), (v as usize).min(FIELD - 1));
    let (tx, ty) = (u - x0 as f32, v - y0 as f32);
    let (x1, y1) = ((x0 + 1) % FIELD, (y0 + 1) % FIELD);
    let at = |x: usize, y: usize| f.values[y * FIELD + x];
    let top = at(x0, y0) + (at(x1, y0) - at(x0, y0)) * tx;
    let bottom = at(x0, y1) + (at(x1, y1) - at(x0, y1)) * tx;
    top + (bottom - top) * ty
}

/// The field value above which `cover` of the layer lies (1 clears the sky).
fn threshold(f: &Field, cover: f32) -> f32 {
    if cover <= 0.0 {
        return f32::INFINITY;
    }
    let k = ((1.0 - cover.min(1.0)) * (f.sorted.len() - 1) as f32) as usize;
    f.sorted[k]
}

/// Opacity of the cloud layer along unit-length-agnostic ray `v` from `eye` (0 below the
/// horizon), and the field's value there.
fn opacity(f: &Field, eye: [f32; 3], v: [f32; 3], offset: [f32; 2], edge: f32) -> (f32, f32) {
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let vy = v[1] / len;
    if vy.is_nan() || vy <= 0.02 || !edge.is_finite() {
        return (0.0, 0.0);
    }
    let t = (ALTITUDE - eye[1]) / vy;
    let per_cell = FIELD as f32 / CLOUD_TILE as f32;
    let x = (eye[0] + v[0] / len * t + offset[0]) * per_cell;
    let z = (eye[2] + v[2] / len * t + offset[1]) * per_cell;
    let n = sample(f, x, z);
    let alpha = smoothstep(edge - SOFTNESS * 0.5, edge + SOFTNESS, n);
    // Far off, the layer is seen through haze and its pattern shrinks towards a pixel:
    // clouds thin towards the horizon and vanish at it.
    let haze = smoothstep(0.015, 0.06, vy) * (0.45 + 0.55 * smoothstep(0.03, 0.3, vy));
    (alpha * haze, n)
}

/// How much of the sun the cloud layer hides from the ground at `ground` (world metres):
/// the opacity the sky's clouds are drawn with at the pixel looking from there straight
/// at the sun (`sun_direction`), for the same `cover` and `offset`. So a frame is shaded
/// exactly when its sky would show a cloud over the sun; a low sun, towards the haze
/// where the clouds thin, is hardly shaded, and the sun below the horizon not at all.
pub fn sun_shade(cover: f32, offset: [f64; 2], ground: [f64; 3], sun_direction: [f32; 3]) -> f32 {
    if cover.is_nan() || cover <= 0.0 {
        return 0.0;
    }
    let f = field();
    let offset = offset.map(|o| o as f32);
    opacity(
        f,
        ground.map(|v| v as f32),
        sun_direction,
        offset,
        threshold(f, cover),
    )
    .0
}

/// Draws the clouds covering `cover` of the layer onto the sky pixels (`depth` 0) of
/// `linear` (row-major, `width` wide), lit by `light`.
pub(crate) fn draw_clouds(
    linear: &mut [[f32; 3]],
    depth: &[f32],
    width: u32,
    rays: &Rays,
    light: &CloudLight,
    cover: f32,
    offset: [f64; 2],
) {
    if cover.is_nan() || cover <= 0.0 || depth.iter().all(|&d| d > 0.0) {
        return;
    }
    let f = field();
    let edge = threshold(f, cover);
    let offset = offset.map(|o| o as f32);
    let w = width.max(1) as usize;
    let s = light.sun_direction;
    linear
        .par_chunks_mut(w)
        .zip(depth.par_chunks(w))
        .enumerate()
        .for_each(|(y, (row, depths))| {
            for (x, (colour, &d)) in row.iter_mut().zip(depths).enumerate() {
                if d > 0.0 {
                    continue;
                }
                let v = rays.dir(x, y);
                let (alpha, n) = opacity(f, rays.eye, v, offset, edge);
                if alpha <= 0.0 {
                    continue;
                }
                let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                let towards = (v[0] * s[0] + v[1] * s[1] + v[2] * s[2]) / len;
                // Silver lining towards the sun, the sun's light on the cloud's side, and
                // the sky's; thick cores (field far above the edge) darker below.
                let sun = 0.55 + 0.45 * towards.max(0.0) * towards.max(0.0);
                let core = 1.0 - 0.4 * smoothstep(edge, edge + 0.25, n);
                let lit: [f32; 3] = std::array::from_fn(|k| {
                    (light.sun_colour[k] * sun * 0.85 + light.sky[k] * 1.1) * core
                });
                *colour = std::array::from_fn(|k| colour[k] + (lit[k] - colour[k]) * alpha);
            }
        });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::CameraPose;

    #[test]
    fn the_field_tiles_spans_zero_to_one_and_its_thresholds_give_the_cover() {
        let f = field();
        assert_eq!(f.values.len(), FIELD * FIELD);
        assert!(f.values.iter().all(|v| (0.0..=1.0).contains(v)));
        // Tiling: the bilinear sample one tile over is the same (up to the rounding of
        // the shifted coordinates), and continuous across the tile's edge.
        for (u, v) in [(3.3, 7.9), (500.5, 1.25), (511.9, 511.9)] {
            let (a, b) = (
                sample(f, u, v),
                sample(f, u + FIELD as f32, v - FIELD as f32),
            );
            assert!((a - b).abs() < 1e-4, "{a} {b}");
        }
        let n = FIELD as f32;
        assert!((sample(f, n - 1e-3, 5.0) - sample(f, 0.0, 5.0)).abs() < 0.01);
        for cover in [0.1f32, 0.3, 0.6, 0.9] {
            let edge = threshold(f, cover);
            let above = f.values.iter().filter(|&&v| v > edge).count() as f32;
            let share = above / f.values.len() as f32;
            assert!((share - cover).abs() < 0.01, "{cover}: {share}");
        }
        assert_eq!(threshold(f, 0.0), f32::INFINITY);
    }

    #[test]
    fn the_sun_is_shaded_on_about_the_covered_share_of_the_ground_as_drawn_in_the_sky() {
        let sun = LIGHT.sun_direction;
        // Ground points every 37 m over 8 km: the share under a cloud follows the cover.
        let share = |cover: f32| {
            let points: Vec<[f64; 3]> = (0..220 * 220)
                .map(|i| [f64::from(i % 220) * 37.0, 0.0, f64::from(i / 220) * 37.0])
                .collect();
            let shaded = points
                .iter()
                .filter(|&&g| sun_shade(cover, [0.0; 2], g, sun) > 0.5)
                .count();
            shaded as f32 / points.len() as f32
        };
        for cover in [0.2f32, 0.5, 0.8] {
            let s = share(cover);
            assert!((s - cover).abs() < 0.12, "cover {cover}: {s}");
        }
        assert_eq!(share(0.0), 0.0);
        // No shade with the sun down, or no cover.
        let night = [0.0, -0.2, -0.98];
        assert_eq!(sun_shade(0.9, [0.0; 2], [50.0, 0.0, 50.0], night), 0.0);
        // A sun 2° up is seen through the haze, where the drawn clouds thin out: it is
        // hardly ever hidden, whatever the cover.
        let low = [0.0, 0.035, -0.999];
        let hidden = (0..2000)
            .map(|i| [f64::from(i) * 29.0, 0.0, f64::from(i % 37) * 41.0])
            .filter(|&g| sun_shade(0.8, [0.0; 2], g, low) > 0.5)
            .count();
        assert_eq!(hidden, 0);
    }

    fn rays() -> Rays {
        let pose = CameraPose {
            eye: [100.0, 1.6, 200.0],
            target: [100.0, 40.0, 150.0],
            up: [0.0, 1.0, 0.0],
            angles: None,
            time: None,
        };
        Rays::new(&pose, [320.0, 320.0, 320.0, 240.0]).unwrap()
    }

    const LIGHT: CloudLight = CloudLight {
        sun_direction: [0.0, 0.8, -0.6],
        sun_colour: [1.0, 0.95, 0.9],
        sky: [0.3, 0.4, 0.6],
    };

    #[test]
    fn clouds_cover_about_their_share_of_the_sky_above_and_only_the_sky() {
        let (w, h) = (640u32, 480u32);
        let n = (w * h) as usize;
        let blue = [0.2f32, 0.35, 0.8];
        // The lower fifth is ground (depth 10 m).
        let depth: Vec<f32> = (0..n)
            .map(|i| if i / w as usize >= 384 { 10.0 } else { 0.0 })
            .collect();
        let mut covered = Vec::new();
        for cover in [0.0f32, 0.25, 0.75] {
            let mut linear = vec![blue; n];
            draw_clouds(
                &mut linear,
                &depth,
                w,
                &rays(),
                &LIGHT,
                cover,
                [300.0, 900.0],
            );
            for (c, d) in linear.iter().zip(&depth) {
                if *d > 0.0 {
                    assert_eq!(*c, blue);
                }
            }
            let changed = linear.iter().filter(|c| **c != blue).count();
            covered.push(changed as f32 / (n as f32 * 0.8));
            // Deterministic.
            let mut again = vec![blue; n];
            draw_clouds(
                &mut again,
                &depth,
                w,
                &rays(),
                &LIGHT,
                cover,
                [300.0, 900.0],
            );
            assert_eq!(again, linear);
        }
        assert_eq!(covered[0], 0.0);
        assert!(covered[1] > 0.05 && covered[1] < covered[2], "{covered:?}");
        assert!(covered[2] > 0.4, "{covered:?}");
    }

    #[test]
    fn clouds_are_lit_by_the_sun_and_dark_at_night() {
        let f = field();
        let edge = threshold(f, 0.9);
        let (alpha, _) = opacity(f, [0.0, 1.6, 0.0], [0.0, 1.0, 0.0], [0.0; 2], edge);
        assert!(alpha > 0.0);
        let (w, n) = (4u32, 16usize);
        let pose = CameraPose {
            eye: [0.0, 1.6, 0.0],
            target: [0.0, 100.0, -1.0],
            up: [0.0, 1.0, 0.0],
            angles: None,
            time: None,
        };
        let rays = Rays::new(&pose, [4.0, 4.0, 2.0, 2.0]).unwrap();
        let mut day = vec![[0.2f32, 0.35, 0.8]; n];
        draw_clouds(&mut day, &[0.0; 16], w, &rays, &LIGHT, 1.0, [0.0; 2]);
        let night_light = CloudLight {
            sun_colour: [0.0; 3],
            sky: [0.004, 0.005, 0.012],
            ..LIGHT
        };
        let mut night = vec![[0.005f32, 0.007, 0.02]; n];
        draw_clouds(
            &mut night,
            &[0.0; 16],
            w,
            &rays,
            &night_light,
            1.0,
            [0.0; 2],
        );
        let lum = |c: [f32; 3]| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        // Fully overcast overhead: the day's clouds brighter than its blue sky, white-ish;
        // the night's dark.
        for c in &day {
            assert!(lum(*c) > lum([0.2, 0.35, 0.8]), "{c:?}");
            assert!(c[2] / c[0] < 1.6, "{c:?}");
        }
        for c in &night {
            assert!(lum(*c) < 0.02, "{c:?}");
        }
    }
}
