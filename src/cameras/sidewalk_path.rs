//! The sidewalk walk: blocks + sidewalk width → a pedestrian's poses, clockwise around each
//! block on its sidewalk, frames evenly spaced by arc length.

use serde::{Deserialize, Serialize};

use super::CameraPose;
use super::aim::{Aim, aimed_pose};
use super::leg::{Leg, stations};
use crate::model::ParsedLayout;
use crate::rng;
use crate::spec::FrameRule;

/// Where across the sidewalk the walker walks (shared with the objects stage, which keeps
/// people off that line).
pub use crate::model::geometry::WALK_SHARE;

/// Metres from the eye to the look-at point (only the direction matters).
const LOOK: f64 = 10.0;

/// How a pedestrian walks the sidewalks.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SidewalkPath {
    /// Frames over the whole walk: a count, or one every so many metres of it.
    pub frames: FrameRule,
    /// Heading (from the walking direction), pitch, roll and eye height, drawn per frame.
    pub aim: Aim,
    /// Width of the sidewalk (the lamp strip) around each block, metres.
    pub sidewalk: f64,
}

/// Walks around every block in id order, clockwise seen from above, so the block and its
/// shop fronts are on the walker's right (heading +90°) and the street on the left
/// (−90°): along the rectangle around the block's bounding box, [`WALK_SHARE`] of the
/// sidewalk's width out from it, cut to the layout. A side less than a sidewalk's width
/// from the layout's edge is left out: beyond it is the end of the world, not a street.
/// Frames are spaced evenly by arc length over the whole walk ([`walk_length`]); between
/// sides and blocks the walker jumps. Each frame draws its aim from
/// `rng::stream(seed, "cameras/aim", frame)`.
///
/// No poses when there are no frames, no block, or a parameter is out of range
/// (`metres_per_pixel` and `sidewalk` positive and finite, `aim` valid).
pub fn sidewalk_path(
    layout: &ParsedLayout,
    metres_per_pixel: f64,
    path: &SidewalkPath,
    seed: u64,
) -> Vec<CameraPose> {
    sidewalk_path_draws(layout, metres_per_pixel, path, seed, 1)
        .into_iter()
        .filter_map(|draws| draws.into_iter().next())
        .collect()
}

/// Up to `draws` (at least one) poses per frame of [`sidewalk_path`]: each frame's stream
/// drawn on, so the first draw is the pose `sidewalk_path` gives and the others are the
/// same walker at the same spot looking elsewhere. The build keeps one per frame (a view
/// not filled by something right in front of the eye, `views::clear`).
pub fn sidewalk_path_draws(
    layout: &ParsedLayout,
    metres_per_pixel: f64,
    path: &SidewalkPath,
    seed: u64,
    draws: usize,
) -> Vec<Vec<CameraPose>> {
    if !path.aim.is_valid() {
        return Vec::new();
    }
    let sides = sides(layout, metres_per_pixel, path.sidewalk);
    let total: f64 = sides.iter().map(|l| l.length).sum();
    stations(&sides, path.frames.frames(total))
        .into_iter()
        .zip(0u64..)
        .map(|((ground, dir), i)| {
            let mut aim = rng::stream(seed, "cameras/aim", i);
            (0..draws.max(1))
                .map(|_| aimed_pose(ground, dir, (1.0, 0.0), path.aim.draw(&mut aim), LOOK))
                .collect()
        })
        .collect()
}

/// Length in metres of the walk [`sidewalk_path`] takes: a [`FrameRule::Spacing`] takes
/// its frame count from it.
pub fn walk_length(layout: &ParsedLayout, metres_per_pixel: f64, sidewalk: f64) -> f64 {
    sides(layout, metres_per_pixel, sidewalk)
        .iter()
        .map(|l| l.length)
        .sum()
}

/// The axis-aligned side from `a` to `b`, cut to the layout `[0, size[0]] × [0, size[1]]`;
/// `None` when nothing of it is inside or it runs less than `margin` from the layout's
/// edge.
fn clipped(a: [f64; 2], b: [f64; 2], size: [f64; 2], margin: f64) -> Option<Leg> {
    // The axis the side runs along, and the one it stands still on.
    let (run, fixed) = if a[1] == b[1] { (0, 1) } else { (1, 0) };
    if !(margin..=size[fixed] - margin).contains(&a[fixed]) {
        return None;
    }
    let (from, to) = (a[run].clamp(0.0, size[run]), b[run].clamp(0.0, size[run]));
    let length = (to - from).abs();
    if length.is_nan() || length <= 0.0 {
        return None;
    }
    let mut origin = a;
    origin[run] = from;
    let mut dir = [0.0; 2];
    dir[run] = if to > from { 1.0 } else { -1.0 };
    Some(Leg {
        origin,
        dir,
        length,
    })
}

/// The walked sides of every block, in block id order, each clockwise from the north-west
/// corner: north (east-bound), east (south-bound), south (west-bound), west (north-bound).
fn sides(layout: &ParsedLayout, m: f64, sidewalk: f64) -> Vec<Leg> {
    let valid = m.is_finite() && m > 0.0 && sidewalk.is_finite() && sidewalk > 0.0;
    if !valid {
        return Vec::new();
    }
    let (w, h) = (f64::from(layout.width) * m, f64::from(layout.height) * m);
    let out = WALK_SHARE * sidewalk;
    let mut blocks: Vec<_> = layout.blocks.iter().collect();
    blocks.sort_by_key(|b| b.id);
    let mut legs = Vec::new();
    for block in blocks {
        let b = block.bbox;
        let (x0, x1) = (f64::from(b.x0) * m - out, f64::from(b.x1) * m + out);
        let (z0, z1) = (f64::from(b.y0) * m - out, f64::from(b.y1) * m + out);
        // Corners clockwise from the north-west; each side runs from one to the next.
        let corners = [[x0, z0], [x1, z0], [x1, z1], [x0, z1]];
        for k in 0..4 {
            let (a, b) = (corners[k], corners[(k + 1) % 4]);
            if let Some(leg) = clipped(a, b, [w, h], sidewalk) {
                legs.push(leg);
            }
        }
    }
    legs
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Band, Block, PxRect};
    use crate::spec::ValueRange;

    /// A 100 × 80 px layout at 0.5 m per pixel holding two blocks: one inside, one touching
    /// the top border.
    fn layout() -> ParsedLayout {
        let block = |id: u32, x0: u32, y0: u32, x1: u32, y1: u32| Block {
            id,
            bbox: PxRect { x0, y0, x1, y1 },
            area: u64::from((x1 - x0) * (y1 - y0)),
            outline: Vec::new(),
            bands: vec![Band {
                y0,
                y1,
                spans: vec![[x0, x1]],
            }],
        };
        ParsedLayout {
            width: 100,
            height: 80,
            blocks: vec![block(1, 60, 0, 90, 30), block(0, 20, 40, 40, 60)],
            roads: Vec::new(),
        }
    }

    fn path(frames: u32, heading: ValueRange) -> SidewalkPath {
        SidewalkPath {
            frames: FrameRule::Count(frames),
            aim: Aim {
                heading,
                pitch: ValueRange::Fixed(0.0),
                roll: ValueRange::Fixed(0.0),
                height: ValueRange::Fixed(1.6),
            },
            sidewalk: 5.0,
        }
    }

    #[test]
    fn walks_clockwise_around_each_block_beside_it() {
        // Block 0 spans x 10–20 m, z 20–30 m; the walk is 1.5 m out: a 13 × 13 m ring.
        // Block 1 (x 30–45 m, z 0–15 m) touches the top border, and its east side runs
        // 3.5 m from the right border (50 m), less than a sidewalk: only its south side
        // (18 m) and west side (cut at the border: 16.5 m) are walked.
        assert_eq!(walk_length(&layout(), 0.5, 5.0), 4.0 * 13.0 + 34.5);
        let poses = sidewalk_path(&layout(), 0.5, &path(173, ValueRange::Fixed(90.0)), 3);
        assert_eq!(poses.len(), 173);
        assert!(poses.iter().all(|p| p.eye[0] != 46.5));
        for p in &poses {
            let (x, z) = (p.eye[0], p.eye[2]);
            let on_ring0 = ((x == 8.5 || x == 21.5) && (18.5..=31.5).contains(&z))
                || ((z == 18.5 || z == 31.5) && (8.5..=21.5).contains(&x));
            let on_ring1 = ((x == 28.5 || x == 46.5) && (0.0..=16.5).contains(&z))
                || (z == 16.5 && (28.5..=46.5).contains(&x));
            assert!(on_ring0 || on_ring1, "{p:?}");
            // Turned 90° right of the walk: looking at the block's middle side-on.
            let (cx, cz) = if on_ring0 { (15.0, 25.0) } else { (37.5, 7.5) };
            let to_block = [cx - x, cz - z];
            let view = [p.target[0] - x, p.target[2] - z];
            assert!(to_block[0] * view[0] + to_block[1] * view[1] > 0.0, "{p:?}");
        }
        // The first frame is half a step into block 0's north side, walking east.
        assert_eq!(poses[0].eye, [8.75, 1.6, 18.5]);
    }

    #[test]
    fn draws_repeat_per_seed_and_bad_input_gives_nothing() {
        let ranged = path(30, ValueRange::Between([-120.0, 120.0]));
        let a = sidewalk_path(&layout(), 0.5, &ranged, 5);
        assert_eq!(a, sidewalk_path(&layout(), 0.5, &ranged, 5));
        assert_ne!(a, sidewalk_path(&layout(), 0.5, &ranged, 6));
        assert!(sidewalk_path(&layout(), 0.0, &ranged, 5).is_empty());
        let no_walk = SidewalkPath {
            sidewalk: 0.0,
            ..ranged
        };
        assert!(sidewalk_path(&layout(), 0.5, &no_walk, 5).is_empty());
        let empty = ParsedLayout {
            blocks: Vec::new(),
            ..layout()
        };
        assert!(sidewalk_path(&empty, 0.5, &ranged, 5).is_empty());
    }

    #[test]
    fn the_first_draw_is_the_path_pose_and_the_rest_look_elsewhere_from_it() {
        let ranged = path(30, ValueRange::Between([-120.0, 120.0]));
        let poses = sidewalk_path(&layout(), 0.5, &ranged, 5);
        let draws = sidewalk_path_draws(&layout(), 0.5, &ranged, 5, 4);
        assert_eq!(draws.len(), poses.len());
        for (frame, pose) in draws.iter().zip(&poses) {
            assert_eq!(frame.len(), 4);
            assert_eq!(&frame[0], pose);
            assert!(frame.iter().all(|d| d.eye == pose.eye));
            assert!(frame[1..].iter().all(|d| d.target != pose.target));
        }
    }
}
