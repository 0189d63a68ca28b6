//! The sidewalk walk on a map: a pedestrian's poses along the map's sidewalks, the block
//! on the right, frames evenly spaced by arc length.
//!
//! Each paved segment, in map order, is walked on its right sidewalk (from `a` to `b`)
//! and then on its left one (from `b` to `a`), so the buildings are always on the walker's
//! right, as on a layout's walk. The walker keeps to the line [`WALK_SHARE`] of the
//! sidewalk's width from its outer edge (the block's side). A sidewalk narrower than
//! [`MIN_SIDEWALK`] is not walked. Where the line crosses a carriageway (a junction, a
//! road ending on this one) the walk stops: a point is walked only when it is at least
//! [`CARRIAGEWAY_CLEARANCE`] from every paved segment's carriageway, inside the box, and
//! [`EDGE_TRIM`] from where the box cuts a road (beyond is the empty ground).
//! Stretches shorter than [`MIN_STRETCH`] are left out; between stretches the walker
//! jumps.

use super::CameraPose;
use super::aim::{Aim, aimed_pose};
use super::leg::{EDGE_TRIM, Leg, on_box_edge, stations};
use crate::model::geometry::WALK_SHARE;
use crate::model::geometry::polygon::{direction, distance, nearest};
use crate::model::{OsmMap, PavedSegment};
use crate::rng;
use crate::spec::FrameRule;

/// The narrowest sidewalk walked, metres.
pub const MIN_SIDEWALK: f64 = 1.5;
/// How far the walker keeps from a carriageway's edge, metres.
pub const CARRIAGEWAY_CLEARANCE: f64 = 0.5;
/// The shortest stretch of sidewalk walked, metres.
pub const MIN_STRETCH: f64 = 3.0;
/// How finely the walked line is tested, metres.
const STEP: f64 = 0.5;
/// Metres from the eye to the look-at point (only the direction matters).
const LOOK: f64 = 10.0;
/// Side of the grid cells the paved segments are bucketed in, metres.
const CELL: f64 = 25.0;

/// Up to `draws` (at least one) poses per frame of the walk along `map`'s sidewalks (see
/// the module's note), `frames` over its whole length (a [`FrameRule::Spacing`] divides
/// the walk's length); each frame draws its aim from
/// `rng::stream(seed, "cameras/aim", frame)`, as on a layout's walk. The build keeps one
/// per frame (`views::clear`). No poses when `aim` is invalid or nothing is walkable.
pub fn map_sidewalk_path_draws(
    map: &OsmMap,
    frames: FrameRule,
    aim: Aim,
    seed: u64,
    draws: usize,
) -> Vec<Vec<CameraPose>> {
    if !aim.is_valid() {
        return Vec::new();
    }
    let legs = walk_legs(map);
    let total: f64 = legs.iter().map(|l| l.length).sum();
    stations(&legs, frames.frames(total))
        .into_iter()
        .zip(0u64..)
        .map(|((ground, dir), i)| {
            let mut stream = rng::stream(seed, "cameras/aim", i);
            (0..draws.max(1))
                .map(|_| aimed_pose(ground, dir, (1.0, 0.0), aim.draw(&mut stream), LOOK))
                .collect()
        })
        .collect()
}

/// [`map_sidewalk_path_draws`]' first draws.
pub fn map_sidewalk_path(map: &OsmMap, frames: FrameRule, aim: Aim, seed: u64) -> Vec<CameraPose> {
    map_sidewalk_path_draws(map, frames, aim, seed, 1)
        .into_iter()
        .filter_map(|draws| draws.into_iter().next())
        .collect()
}

/// The walked stretches, in map order (each segment's right sidewalk, then its left).
fn walk_legs(map: &OsmMap) -> Vec<Leg> {
    let segments: Vec<PavedSegment> = map.paved_segments().collect();
    let grid = Grid::of(&segments);
    let [x0, z0, x1, z1] = map.extent;
    let cuts: Vec<[f64; 2]> = segments
        .iter()
        .flat_map(|s| [s.a, s.b])
        .filter(|&p| on_box_edge(map, p))
        .collect();
    let walkable = |p: [f64; 2]| {
        let inside = p[0] > x0 && p[0] < x1 && p[1] > z0 && p[1] < z1;
        inside
            && cuts.iter().all(|&c| distance(p, c) >= EDGE_TRIM)
            && grid.near(p).all(|k| {
                let s = &segments[k];
                distance(p, nearest(s.a, s.b, p)) >= s.width / 2.0 + CARRIAGEWAY_CLEARANCE
            })
    };
    let mut legs = Vec::new();
    for s in &segments {
        for side in [1, 0] {
            let width = s.sidewalks[side];
            // Right sidewalk a → b, left b → a: the block on the walker's right.
            let (from, to) = if side == 1 { (s.a, s.b) } else { (s.b, s.a) };
            let Some(dir) = direction(from, to).filter(|_| width >= MIN_SIDEWALK) else {
                continue;
            };
            let len = distance(from, to);
            let right = [-dir[1], dir[0]];
            let out = s.width / 2.0 + width * (1.0 - WALK_SHARE);
            let origin = [from[0] + right[0] * out, from[1] + right[1] * out];
            let at = |t: f64| [origin[0] + dir[0] * t, origin[1] + dir[1] * t];
            legs.extend(
                clear_stretches(len, |t| walkable(at(t)))
                    .into_iter()
                    .map(|[a, b]| Leg {
                        origin: at(a),
                        dir,
                        length: b - a,
                    }),
            );
        }
    }
    legs
}

/// The stretches of `[0, len]` at least [`MIN_STRETCH`] long whose test points (every
/// [`STEP`] and both ends) all pass `clear`.
fn clear_stretches(len: f64, clear: impl Fn(f64) -> bool) -> Vec<[f64; 2]> {
    let steps = (len / STEP).ceil() as usize;
    let mut out = Vec::new();
    let mut open: Option<f64> = None;
    let mut last_clear = 0.0;
    for k in 0..=steps {
        let t = (k as f64 * STEP).min(len);
        if clear(t) {
            open.get_or_insert(t);
            last_clear = t;
        } else if let Some(start) = open.take() {
            out.push([start, last_clear]);
        }
    }
    if let Some(start) = open {
        out.push([start, last_clear]);
    }
    out.retain(|s| s[1] - s[0] >= MIN_STRETCH);
    out
}

/// The paved segments bucketed by [`CELL`]-metre cells of the plane, each in every cell
/// its carriageway (and the clearance) reaches into.
struct Grid {
    cells: std::collections::BTreeMap<(i64, i64), Vec<usize>>,
}

impl Grid {
    fn of(segments: &[PavedSegment]) -> Grid {
        let mut cells: std::collections::BTreeMap<(i64, i64), Vec<usize>> = Default::default();
        for (k, s) in segments.iter().enumerate() {
            let pad = s.width / 2.0 + CARRIAGEWAY_CLEARANCE;
            let lo = [s.a[0].min(s.b[0]) - pad, s.a[1].min(s.b[1]) - pad];
            let hi = [s.a[0].max(s.b[0]) + pad, s.a[1].max(s.b[1]) + pad];
            if !(lo.iter().chain(&hi).all(|v| v.is_finite())) {
                continue;
            }
            for i in cell(lo[0])..=cell(hi[0]) {
                for j in cell(lo[1])..=cell(hi[1]) {
                    cells.entry((i, j)).or_default().push(k);
                }
            }
        }
        Grid { cells }
    }

    /// The segments whose carriageway may come within the clearance of `p`.
    fn near(&self, p: [f64; 2]) -> impl Iterator<Item = usize> + '_ {
        self.cells
            .get(&(cell(p[0]), cell(p[1])))
            .into_iter()
            .flatten()
            .copied()
    }
}

/// The grid cell a coordinate falls in.
fn cell(v: f64) -> i64 {
    (v / CELL).floor() as i64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::ValueRange;
    use crate::test_support::street_map;

    /// Looking straight along the walk, at eye height 1.6 m.
    fn ahead() -> Aim {
        Aim {
            heading: ValueRange::Fixed(0.0),
            pitch: ValueRange::Fixed(0.0),
            roll: ValueRange::Fixed(0.0),
            height: ValueRange::Fixed(1.6),
        }
    }

    /// The paved segment nearest to `p` and the distance to its centreline.
    fn nearest_paved(map: &OsmMap, p: [f64; 2]) -> (PavedSegment, f64) {
        let (s, _, d) = map.nearest_paved(p).unwrap();
        (s, d)
    }

    #[test]
    fn the_walker_keeps_to_the_sidewalks_with_the_block_on_the_right() {
        let map = street_map();
        let poses = map_sidewalk_path(&map, FrameRule::Count(40), ahead(), 5);
        assert_eq!(poses.len(), 40);
        let cuts = [[-150.0, 0.0], [100.0, -100.0], [-50.0, 100.0]];
        for pose in &poses {
            let eye = [pose.eye[0], pose.eye[2]];
            assert!((pose.eye[1] - 1.6).abs() < 1e-9);
            // On its sidewalk's walking line: road 0 (12 m, 3 m sidewalks) 6 + 2.1 m out,
            // road 1 (8 m, 2 m sidewalks) 4 + 1.4 m (poses are rounded to the millimetre).
            let (s, d) = nearest_paved(&map, eye);
            let line = s.width / 2.0 + s.sidewalks[0] * (1.0 - WALK_SHARE);
            assert!((d - line).abs() < 2e-3, "{eye:?} {d} {line}");
            for other in map.paved_segments() {
                let gap = distance(eye, nearest(other.a, other.b, eye));
                assert!(
                    gap >= other.width / 2.0 + CARRIAGEWAY_CLEARANCE - 2e-3,
                    "{eye:?}"
                );
            }
            assert!(cuts.iter().all(|&c| distance(eye, c) >= EDGE_TRIM - 2e-3));
            // Looking along the road, its centreline on the left.
            let f = [pose.target[0] - pose.eye[0], pose.target[2] - pose.eye[2]];
            let right = [-f[1], f[0]];
            let q = nearest(s.a, s.b, eye);
            assert!((q[0] - eye[0]) * right[0] + (q[1] - eye[1]) * right[1] < 0.0);
            let along = (s.b[0] - s.a[0]) * f[0] + (s.b[1] - s.a[1]) * f[1];
            let len = distance(s.a, s.b) * (f[0] * f[0] + f[1] * f[1]).sqrt();
            assert!((along.abs() - len).abs() < 1e-3 * len, "{eye:?}");
        }
        // The same walk again; another seed draws other aims at the same stations.
        assert_eq!(
            poses,
            map_sidewalk_path(&map, FrameRule::Count(40), ahead(), 5)
        );
    }

    #[test]
    fn the_walk_stops_at_the_side_road_and_the_box_cuts() {
        let map = street_map();
        let legs = walk_legs(&map);
        // Road 0's first segment, south side (right of west → east): from 50 m past the
        // cut at x −150 to road 1's carriageway (x −54 … −46) and on from it to the bend.
        let south: Vec<&Leg> = legs
            .iter()
            .filter(|l| l.dir == [1.0, 0.0] && (l.origin[1] - 8.1).abs() < 1e-9)
            .collect();
        assert_eq!(south.len(), 2, "{legs:?}");
        let ends = |l: &Leg| [l.origin[0], l.origin[0] + l.length];
        // 50 m from (−150, 0) along z = 8.1: x = −150 + √(50² − 8.1²).
        let first = -150.0 + (50.0f64 * 50.0 - 8.1 * 8.1).sqrt();
        assert!(
            (ends(south[0])[0] - first).abs() <= STEP,
            "{:?}",
            ends(south[0])
        );
        assert!(
            (ends(south[0])[1] - (-54.5)).abs() <= STEP,
            "{:?}",
            ends(south[0])
        );
        assert!(
            (ends(south[1])[0] - (-45.5)).abs() <= STEP,
            "{:?}",
            ends(south[1])
        );
        // Road 1 (one-way south, 8 m): both sidewalks, from road 0's kerb + 0.5 m.
        let road1: Vec<&Leg> = legs.iter().filter(|l| l.dir[0] == 0.0).collect();
        assert_eq!(road1.len(), 2, "{road1:?}");
        for l in road1 {
            let z = [l.origin[1], l.origin[1] + l.dir[1] * l.length];
            assert!(
                z.iter().all(|z| (6.5 - 1e-9..=50.0 + 1e-9).contains(z)),
                "{l:?}"
            );
        }
        // No sidewalks, no walk.
        let mut bare = map.clone();
        for road in &mut bare.roads {
            for f in &mut road.fitted {
                f[1] = 1.0;
                f[2] = 1.0;
            }
        }
        assert!(map_sidewalk_path(&bare, FrameRule::Count(10), ahead(), 5).is_empty());
    }
}
