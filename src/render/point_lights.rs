//! A frame's point lights (lamps, car lights, light spilling from lit windows): where on
//! screen each may reach, which of them a tile shades with, and what they add to the light
//! falling on a surface point.
//!
//! A light adds `colour · (1 − (d/range)²)² · near² / (near² + d²) · beam · max(0, n·l)`
//! at distance `d`: inverse-square beyond `near` (so a lamp lights a pool under itself and
//! little between lamps), finite at the light, and exactly zero from `range` on. `beam` is
//! 1 for a light that shines all round; for a beam (a street lamp's shielded head, a
//! headlight, a window) it is `(c − edge) / (1 − edge)` clamped to 0–1, with `c` the cosine
//! between the beam's axis and the direction to the point. A headlight's dipped beam is
//! also cut off above the horizontal: times `(cutoff − s) / CUTOFF_BAND` clamped to 0–1,
//! `s` the sine of the point's elevation seen from the light.

use super::tile::{NOTHING, TileRaster};
use super::view::View;
use super::{CUTOFF_BAND, Light};

/// At most this many lights shade one tile: those that may light its surfaces the most.
/// Keeps a frame's cost bounded however many windows glow and cars shine.
pub(crate) const MAX_TILE_LIGHTS: usize = 24;

/// A point light of this frame, with its conservative footprint in internal pixels.
pub(crate) struct FrameLight {
    pub position: [f64; 3],
    pub colour: [f32; 3],
    pub range2: f64,
    pub near2: f64,
    /// Unit beam axis, or zero all round.
    pub aim: [f64; 3],
    pub edge: f64,
    /// [`Light::cutoff`], infinite for none.
    pub cutoff: f64,
    /// Luminance of `colour` (which lights a full tile keeps).
    pub luminance: f64,
    /// Position in camera coordinates (right, up, forward).
    pub camera: [f64; 3],
    /// `[x0, y0, x1, y1)` internal pixels the light may reach.
    pub rect: [u32; 4],
}

/// The frame's point lights with the internal-pixel rectangles they may light; lights
/// wholly off screen, behind the camera, or black are dropped.
pub(crate) fn frame_lights(lights: &[Light], view: &View) -> Vec<FrameLight> {
    let (w, h) = (view.width, view.height);
    lights
        .iter()
        .filter_map(|l| {
            let r = f64::from(l.range);
            let position = l.position.map(f64::from);
            if !r.is_finite()
                || r <= 0.0
                || !position.iter().all(|v| v.is_finite())
                || l.colour.iter().all(|&c| c <= 0.0)
            {
                return None;
            }
            let c = view.to_camera(position);
            if c[2] + r < view.near {
                return None;
            }
            let rect = if c[2] - r <= view.near {
                [0, 0, w, h]
            } else {
                // The sphere lies in the box c ± r, with depth > 0: its projection lies
                // between the extreme projections of the box's corners.
                let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
                for dx in [-r, r] {
                    for dy in [-r, r] {
                        for dz in [-r, r] {
                            let [x, y] = view.project([c[0] + dx, c[1] + dy, c[2] + dz]);
                            (x0, x1) = (x0.min(x), x1.max(x));
                            (y0, y1) = (y0.min(y), y1.max(y));
                        }
                    }
                }
                let clamp = |v: f64, max: u32| v.clamp(0.0, f64::from(max)) as u32;
                [
                    clamp(x0.floor(), w),
                    clamp(y0.floor(), h),
                    clamp(x1.ceil() + 1.0, w),
                    clamp(y1.ceil() + 1.0, h),
                ]
            };
            let aim = l.aim.map(f64::from);
            let len = (aim[0] * aim[0] + aim[1] * aim[1] + aim[2] * aim[2]).sqrt();
            let aim = if len.is_finite() && len > 1e-6 {
                aim.map(|v| v / len)
            } else {
                [0.0; 3]
            };
            let near = f64::from(l.near);
            let near2 = if near.is_finite() && near > 0.0 {
                near * near
            } else {
                f64::MAX
            };
            (rect[0] < rect[2] && rect[1] < rect[3]).then_some(FrameLight {
                position,
                colour: l.colour,
                range2: r * r,
                near2,
                aim,
                edge: f64::from(l.edge).clamp(-1.0, 0.999),
                cutoff: l
                    .cutoff
                    .filter(|c| c.is_finite())
                    .map_or(f64::INFINITY, f64::from),
                luminance: f64::from(
                    0.2126 * l.colour[0] + 0.7152 * l.colour[1] + 0.0722 * l.colour[2],
                ),
                camera: c,
                rect,
            })
        })
        .collect()
}

/// The lights that may reach the surfaces of `raster`'s tile, in frame order: those
/// whose sphere meets the box in camera space that holds them (the tile's pixels between
/// its nearest and farthest depth), at most [`MAX_TILE_LIGHTS`], the ones that could give
/// its surfaces the most light (then by order). A tile of sky gets none.
pub(crate) fn tile_lights<'a>(
    lights: &'a [FrameLight],
    view: &View,
    raster: &TileRaster,
) -> Vec<&'a FrameLight> {
    let inner = raster.inner;
    let (mut q0, mut q1) = (f64::MAX, f64::MIN);
    for (&q, &id) in raster.depth.iter().zip(&raster.id) {
        if id != NOTHING {
            (q0, q1) = (q0.min(q), q1.max(q));
        }
    }
    if !(q0 > 0.0 && q0 <= q1) {
        return Vec::new();
    }
    let (z0, z1) = (1.0 / q1, 1.0 / q0);
    // x = a · z and y = b · z over the tile's pixel edges and depths.
    let span = |a0: f64, a1: f64| {
        let (lo, hi) = (a0.min(a1), a0.max(a1));
        [(lo * z0).min(lo * z1), (hi * z0).max(hi * z1)]
    };
    let x = span(
        (f64::from(inner[0]) - view.cx) / view.fx,
        (f64::from(inner[2]) - view.cx) / view.fx,
    );
    let y = span(
        (view.cy - f64::from(inner[3])) / view.fy,
        (view.cy - f64::from(inner[1])) / view.fy,
    );
    let gap = |v: f64, [lo, hi]: [f64; 2]| {
        if v < lo {
            lo - v
        } else if v > hi {
            v - hi
        } else {
            0.0
        }
    };
    let mut hit: Vec<(usize, f64)> = lights
        .iter()
        .enumerate()
        .filter_map(|(i, l)| {
            let r = l.rect;
            if !(r[0] < inner[2] && inner[0] < r[2] && r[1] < inner[3] && inner[1] < r[3]) {
                return None;
            }
            let c = l.camera;
            let d = [gap(c[0], x), gap(c[1], y), gap(c[2], [z0, z1])];
            let d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if d2.is_nan() || d2 >= l.range2 {
                return None;
            }
            // The most the light can give any point of the box.
            let t = 1.0 - d2 / l.range2;
            Some((i, l.luminance * t * t * (l.near2 / (l.near2 + d2))))
        })
        .collect();
    if hit.len() > MAX_TILE_LIGHTS {
        hit.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
        hit.truncate(MAX_TILE_LIGHTS);
        hit.sort_unstable_by_key(|h| h.0);
    }
    hit.into_iter().map(|(i, _)| &lights[i]).collect()
}

/// Adds to `light` what `lights` shine on the surface point `p` with unit normal `n`, in
/// order (the same sum at any thread count).
#[inline]
pub(crate) fn add_lights(light: &mut [f32; 3], lights: &[&FrameLight], p: [f64; 3], n: [f32; 3]) {
    let n = n.map(f64::from);
    for lamp in lights {
        let d = [
            lamp.position[0] - p[0],
            lamp.position[1] - p[1],
            lamp.position[2] - p[2],
        ];
        let d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if d2.is_nan() || d2 >= lamp.range2 || d2 <= 0.0 {
            continue;
        }
        let inv = 1.0 / d2.sqrt();
        let n_dot = (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) * inv;
        if n_dot <= 0.0 {
            continue;
        }
        let a = lamp.aim;
        let beam = if a == [0.0; 3] {
            1.0
        } else {
            // d points at the light: the beam's axis meets −d.
            let c = -(a[0] * d[0] + a[1] * d[1] + a[2] * d[2]) * inv;
            ((c - lamp.edge) / (1.0 - lamp.edge)).min(1.0)
        };
        // A cut-off: the sine of the elevation of p seen from the light, against the line.
        let beam = if lamp.cutoff.is_finite() {
            let rise = -d[1] * inv;
            beam * ((lamp.cutoff - rise) / f64::from(CUTOFF_BAND)).clamp(0.0, 1.0)
        } else {
            beam
        };
        if beam <= 0.0 {
            continue;
        }
        let t = 1.0 - d2 / lamp.range2;
        let k = (t * t * n_dot * beam * (lamp.near2 / (lamp.near2 + d2))) as f32;
        for (l, c) in light.iter_mut().zip(lamp.colour) {
            *l += c * k;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A headlight 0.7 m up at the origin, aimed along +x and dipped as a car's, with the
    /// cut-off `cutoff` (infinite for none).
    fn headlight(cutoff: f64) -> FrameLight {
        let aim = [1.0, -0.06, 0.0];
        let len = (1.0f64 + 0.06 * 0.06).sqrt();
        FrameLight {
            position: [0.0, 0.7, 0.0],
            colour: [1.0; 3],
            range2: 30.0 * 30.0,
            near2: 36.0,
            aim: aim.map(|v| v / len),
            edge: 0.8,
            cutoff,
            luminance: 1.0,
            camera: [0.0; 3],
            rect: [0, 0, 1, 1],
        }
    }

    fn received(light: &FrameLight, p: [f64; 3], n: [f32; 3]) -> f32 {
        let mut sum = [0f32; 3];
        add_lights(&mut sum, &[light], p, n);
        sum[0]
    }

    #[test]
    fn a_dipped_beam_lights_a_wall_ahead_up_to_the_lamps_height_and_the_road_far_ahead() {
        let (open, dipped) = (headlight(f64::INFINITY), headlight(0.005));
        // A wall 4 m ahead, facing the lamp. The beam's cone reaches 2 m up it; the cut-off
        // stops the light a few centimetres above the lamp's height (sine 0.005 − 0.015
        // is full light, 0.005 none), with a thin fade between.
        let wall = |light: &FrameLight, y: f64| received(light, [4.0, y, 0.0], [-1.0, 0.0, 0.0]);
        assert!(wall(&open, 2.0) > 0.1, "{}", wall(&open, 2.0));
        assert_eq!(wall(&dipped, 2.0), 0.0);
        assert_eq!(wall(&dipped, 0.73), 0.0);
        let fading = wall(&dipped, 0.69);
        assert!(fading > 0.0 && fading < wall(&open, 0.69), "{fading}");
        assert_eq!(wall(&dipped, 0.5), wall(&open, 0.5));
        assert!(wall(&dipped, 0.5) > 0.1);
        // The road is lit as before out to the beam's reach, and nothing outside the cone
        // (behind the lamp, or far to its side) is lit by either.
        let road =
            |light: &FrameLight, x: f64, z: f64| received(light, [x, 0.0, z], [0.0, 1.0, 0.0]);
        for x in [3.0, 10.0, 25.0] {
            assert!(road(&dipped, x, 0.0) > 0.0, "{x} m");
            assert_eq!(road(&dipped, x, 0.0), road(&open, x, 0.0), "{x} m");
        }
        for light in [&open, &dipped] {
            assert_eq!(road(light, -5.0, 0.0), 0.0);
            assert_eq!(road(light, 3.0, 8.0), 0.0);
            assert_eq!(received(light, [3.0, 6.0, 8.0], [0.0, -1.0, 0.0]), 0.0);
        }
    }
}
