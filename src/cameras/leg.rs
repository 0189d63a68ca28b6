//! Legs of the road tour: parsed roads + lane offset + look-ahead → the stretches a camera
//! drives, each ending `look_ahead` metres before its road does.
//!
//! Where a road "ends" depends on what is there (the parse stage ends every road where its
//! centre line ends):
//!
//! - at the layout border the road surface stops with the line; beyond it is open ground,
//!   so the look-at point must stop at the line's end;
//! - at a T-junction or a corner the side road's line ends inside the crossing road (on
//!   its centre line); the surface goes on to the crossing road's far edge, where a block
//!   and its facades begin, so the look-at point may go that far;
//! - at a dead end the surface stops with the line, as at the border.
//!
//! The camera starts at the road's start (0 m in): it looks forward, into the road.

use crate::model::geometry::polygon::{distance, left_normal};
use crate::model::{
    Axis, MAP_CAMERA_LANE, OsmMap, ParsedLayout, PavedSegment, Road, driven_back, map_camera_lane,
};

/// How much farther from its end a map's road run is driven when the box cut its road
/// there, metres.
pub(super) const EDGE_TRIM: f64 = 50.0;

/// How far inside its kerb a map camera's lane stays, metres.
pub(super) const KERB_CLEARANCE: f64 = 1.0;

/// One road as driven: lane start `[x, z]` in metres, unit direction, and the length in
/// metres the eye travels.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Leg {
    pub origin: [f64; 2],
    pub dir: [f64; 2],
    pub length: f64,
}

/// The roads of `layout` in id order as legs on their right-hand lanes, each trimmed so
/// the point `look_ahead` metres ahead of the eye stays on the road surface: a leg is the
/// road's length up to its [`reach`] minus `look_ahead`, and a road whose reach is not
/// longer than `look_ahead` is left out. When that leaves no leg, every road is driven
/// whole instead (its look-at point passing its end), so a small city still gets a tour.
/// Roads with non-finite coordinates or no length are always left out.
pub(super) fn legs(layout: &ParsedLayout, m: f64, lane_offset: f64, look_ahead: f64) -> Vec<Leg> {
    let mut roads: Vec<&Road> = layout.roads.iter().filter(|r| sound(r)).collect();
    roads.sort_by_key(|r| r.id);
    let trimmed: Vec<Leg> = roads
        .iter()
        .filter_map(|road| {
            let length = (reach(road, &roads) - road.start) * m - look_ahead;
            (length > 0.0).then(|| lane(road, m, lane_offset, length))
        })
        .collect();
    if !trimmed.is_empty() {
        return trimmed;
    }
    roads
        .iter()
        .map(|road| lane(road, m, lane_offset, road.length() * m))
        .collect()
}

/// The roads of `map` with a surface, in map order, as legs: each paved segment in the
/// way's direction, on the right-hand lane: `lane_offset` right of the centreline, at most
/// [`MAP_CAMERA_LANE`] and [`KERB_CLEARANCE`] inside the kerb; on a one-way road in the
/// lane [`map_camera_lane`] gives (left of the centreline when the lanes are even). Each
/// run of consecutive paved segments of a road (a junction continues the run; an unpaved
/// segment ends it) is driven to `look_ahead` metres before its end, so the look-at point
/// stays on the road, and [`EDGE_TRIM`] more when it ends on the box's edge; a run no
/// longer than that is left out. Then the run is driven back the same way, from its end
/// to `look_ahead` (and the trim) before its start, on the segments that are
/// [`driven_back`] (two-way and wide enough that the vehicles standing at the far kerb
/// keep clear of that lane), skipping the others. When that leaves no leg, every run is
/// driven whole.
pub(super) fn map_legs(map: &OsmMap, lane_offset: f64, look_ahead: f64) -> Vec<Leg> {
    let runs = map.paved_runs();
    let lane = |s: &PavedSegment, length: f64| {
        let n = left_normal(s.a, s.b)?;
        let across = if map.roads[s.road].oneway {
            map_camera_lane(s.width)
        } else {
            lane_offset
                .min(MAP_CAMERA_LANE)
                .min(s.width / 2.0 - KERB_CLEARANCE)
                .max(0.0)
        };
        let len = distance(s.a, s.b);
        Some(Leg {
            origin: [s.a[0] - n[0] * across, s.a[1] - n[1] * across],
            dir: [(s.b[0] - s.a[0]) / len, (s.b[1] - s.a[1]) / len],
            length,
        })
    };
    // A run that ends where the box cuts its road stops short of the cut as well, so the
    // camera does not look out of the city into the empty ground beyond the box.
    let at_edge = |p: [f64; 2]| on_box_edge(map, p);
    // The legs of `run` driven to `trim` (and the edge's) before its end, of the segments
    // `drive` takes.
    let legs_of = |run: &[PavedSegment], trim: f64, drive: &dyn Fn(&PavedSegment) -> bool| {
        let total: f64 = run.iter().map(|s| distance(s.a, s.b)).sum();
        let end = run.last().is_some_and(|s| at_edge(s.b));
        let edge = if end && trim > 0.0 { EDGE_TRIM } else { 0.0 };
        let mut left = total - trim - edge;
        let mut legs = Vec::new();
        for s in run {
            if left <= 0.0 {
                break;
            }
            let length = distance(s.a, s.b).min(left);
            left -= length;
            if drive(s) {
                legs.extend(lane(s, length));
            }
        }
        legs
    };
    let back = |s: &PavedSegment| driven_back(s.width, map.roads[s.road].oneway);
    let tour = |trim: f64| -> Vec<Leg> {
        let mut legs = Vec::new();
        for run in &runs {
            legs.extend(legs_of(run, trim, &|_| true));
            if run.iter().any(back) {
                let turned: Vec<PavedSegment> = run.iter().rev().map(|s| s.turned()).collect();
                legs.extend(legs_of(&turned, trim, &back));
            }
        }
        legs
    };
    let trimmed = tour(look_ahead);
    if trimmed.is_empty() {
        tour(0.0)
    } else {
        trimmed
    }
}

/// Whether `p` lies on the edge of `map`'s box (within a centimetre): where the box cut
/// the road that ends there.
pub(super) fn on_box_edge(map: &OsmMap, p: [f64; 2]) -> bool {
    let [x0, z0, x1, z1] = map.extent;
    let near = |a: f64, b: f64| (a - b).abs() < 0.01;
    near(p[0], x0) || near(p[0], x1) || near(p[1], z0) || near(p[1], z1)
}

/// Points `n` evenly spaced by arc length along `legs` taken one after another (the jumps
/// between legs do not count): point `i` at `(i + ½)·L/n` of the total length `L`, with
/// its leg's direction. Empty when `n` is 0 or `L` is not positive and finite.
pub(super) fn stations(legs: &[Leg], n: u32) -> Vec<([f64; 2], [f64; 2])> {
    let total: f64 = legs.iter().map(|l| l.length).sum();
    if !(total > 0.0 && total.is_finite()) || n == 0 {
        return Vec::new();
    }
    let arcs: Vec<f64> = (0..n)
        .map(|i| (f64::from(i) + 0.5) * total / f64::from(n))
        .collect();
    stations_at(legs, &arcs)
}

/// The eye and driving direction at each arc length of `arcs` (ascending, metres along the
/// legs end to end; past the end, the last leg's end).
pub(super) fn stations_at(legs: &[Leg], arcs: &[f64]) -> Vec<([f64; 2], [f64; 2])> {
    if legs.is_empty() {
        return Vec::new();
    }
    let mut out = Vec::with_capacity(arcs.len());
    let (mut leg, mut leg_start) = (0, 0.0);
    for &s in arcs {
        while leg + 1 < legs.len() && s >= leg_start + legs[leg].length {
            leg_start += legs[leg].length;
            leg += 1;
        }
        let l = &legs[leg];
        let along = (s - leg_start).clamp(0.0, l.length);
        out.push((
            [
                l.origin[0] + l.dir[0] * along,
                l.origin[1] + l.dir[1] * along,
            ],
            l.dir,
        ));
    }
    out
}

/// Whether `road` has finite coordinates and a positive length.
fn sound(road: &Road) -> bool {
    let coords = [
        road.start,
        road.end,
        road.line,
        road.edges[0],
        road.edges[1],
    ];
    coords.iter().all(|v| v.is_finite()) && road.end > road.start
}

/// How far along its axis `road`'s surface goes past its start, in pixels: the far edge of
/// a crossing road whose surface holds the end of `road`'s centre line (a T-junction or a
/// corner; a pixel of slack lets a line that stops at the crossing road's near edge count),
/// else the end of the line (the layout border or a dead end).
fn reach(road: &Road, roads: &[&Road]) -> f64 {
    roads
        .iter()
        .filter(|c| c.axis != road.axis)
        .filter(|c| c.start <= road.line && road.line <= c.end)
        .filter_map(|c| {
            let (low, high) = (c.edges[0].min(c.edges[1]), c.edges[0].max(c.edges[1]));
            (low - 1.0 <= road.end && road.end <= high).then_some(high)
        })
        .fold(road.end, f64::max)
}

/// `road`'s right-hand lane as a leg of `length` metres, starting at the road's start.
fn lane(road: &Road, m: f64, lane_offset: f64, length: f64) -> Leg {
    let lo = road.edges[0].min(road.edges[1]).min(road.line);
    let hi = road.edges[0].max(road.edges[1]).max(road.line);
    // Right of the driving direction: +y (south) when driving east, −x (west) when driving
    // south.
    let (origin, dir) = match road.axis {
        Axis::Horizontal => {
            let across = (road.line + lane_offset / m).clamp(lo, hi);
            ([road.start * m, across * m], [1.0, 0.0])
        }
        Axis::Vertical => {
            let across = (road.line - lane_offset / m).clamp(lo, hi);
            ([across * m, road.start * m], [0.0, 1.0])
        }
    };
    Leg {
        origin,
        dir,
        length,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn road(id: u32, axis: Axis, start: f64, end: f64, line: f64) -> Road {
        Road {
            id,
            axis,
            start,
            end,
            line,
            edges: [line - 15.5, line + 16.5],
        }
    }

    fn layout(roads: Vec<Road>) -> ParsedLayout {
        ParsedLayout {
            width: 400,
            height: 300,
            blocks: Vec::new(),
            roads,
        }
    }

    /// (origin, length) of each leg.
    type Summary = Vec<([f64; 2], f64)>;

    /// (origin, length) of each leg, at 1 m per pixel with no lane offset.
    fn summary(roads: Vec<Road>, look_ahead: f64) -> Summary {
        legs(&layout(roads), 1.0, 0.0, look_ahead)
            .into_iter()
            .map(|l| (l.origin, l.length))
            .collect()
    }

    #[test]
    fn legs_stop_look_ahead_before_the_road_surface_ends() {
        use Axis::{Horizontal as H, Vertical as V};
        // Main road: horizontal, line at y 100.5 (surface 85–117), border to border.
        let main = || road(0, H, 0.0, 400.0, 100.5);
        let cases: Vec<(&str, Vec<Road>, Summary)> = vec![
            (
                "border to border: the end is the border",
                vec![main()],
                vec![([0.0, 100.5], 375.0)],
            ),
            (
                "a side road down from the main road to the border: starts on the main \
                 road's line, ends at the border",
                vec![main(), road(1, V, 100.0, 300.0, 200.5)],
                vec![([0.0, 100.5], 375.0), ([200.5, 100.0], 175.0)],
            ),
            (
                "a side road from the border up into a T: its surface goes on to the main \
                 road's far edge",
                vec![main(), road(1, V, 0.0, 101.0, 200.5)],
                vec![([0.0, 100.5], 375.0), ([200.5, 0.0], 117.0 - 25.0)],
            ),
            (
                "a line that stops a pixel short of the crossing road still reaches into it",
                vec![main(), road(1, V, 0.0, 84.0, 200.5)],
                vec![([0.0, 100.5], 375.0), ([200.5, 0.0], 92.0)],
            ),
            (
                "a dead end short of any road: the end is the line's end",
                vec![main(), road(1, V, 150.0, 260.0, 200.5)],
                vec![([0.0, 100.5], 375.0), ([200.5, 150.0], 85.0)],
            ),
            (
                "a road that ends at the main road's line but beyond its end is a dead end",
                vec![road(0, H, 0.0, 150.0, 100.5), road(1, V, 0.0, 101.0, 200.5)],
                vec![([0.0, 100.5], 125.0), ([200.5, 0.0], 76.0)],
            ),
            (
                "a road no longer than the look-ahead is dropped",
                vec![main(), road(1, V, 150.0, 175.0, 200.5)],
                vec![([0.0, 100.5], 375.0)],
            ),
        ];
        for (name, roads, expected) in cases {
            assert_eq!(summary(roads, 25.0), expected, "{name}");
        }
    }

    #[test]
    fn when_every_road_is_too_short_all_are_driven_whole() {
        let roads = vec![
            road(1, Axis::Vertical, 10.0, 22.0, 200.5),
            road(0, Axis::Horizontal, 0.0, 20.0, 100.5),
        ];
        assert_eq!(
            summary(roads.clone(), 25.0),
            vec![([0.0, 100.5], 20.0), ([200.5, 10.0], 12.0)]
        );
        // With a look-ahead that fits one of them, only that one is driven, trimmed.
        assert_eq!(summary(roads, 15.0), vec![([0.0, 100.5], 5.0)]);
    }

    #[test]
    fn unsound_roads_are_never_driven() {
        let mut nan = road(1, Axis::Vertical, 0.0, 300.0, 200.5);
        nan.edges[1] = f64::NAN;
        let backwards = road(2, Axis::Vertical, 300.0, 0.0, 50.5);
        let roads = vec![road(0, Axis::Horizontal, 0.0, 20.0, 100.5), nan, backwards];
        assert_eq!(summary(roads, 25.0), vec![([0.0, 100.5], 20.0)]);
    }

    #[test]
    fn a_map_is_driven_on_the_right_lane_along_its_paved_roads() {
        let map = crate::test_support::street_map();
        let legs = map_legs(&map, 3.0, 20.0);
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
        let expected = [
            // The two-way road: east, then north-east after its bend, 1.5 m (the most a
            // map camera keeps from a two-way road's centreline) right of it, the run
            // trimmed by the look-ahead at its end.
            // Both runs end on the box's edge, so they stop EDGE_TRIM shorter still.
            ([-150.0, 1.5], [1.0, 0.0], 150.0),
            (
                [1.5 * h, 1.5 * h],
                [h, -h],
                100.0 * 2f64.sqrt() - 20.0 - EDGE_TRIM,
            ),
            // Then back (it is 12 m wide: its far half keeps the standing vehicles clear
            // of that lane), from its end on the box's edge to as far before its start,
            // 1.5 m right of the way back.
            (
                [100.0 - 1.5 * h, -100.0 - 1.5 * h],
                [-h, h],
                100.0 * 2f64.sqrt(),
            ),
            ([0.0, -1.5], [-1.0, 0.0], 150.0 - 20.0 - EDGE_TRIM),
            // The one-way road (south, 8 m: two lanes of 4 m) in the middle of its left
            // lane, 2 m east of its centreline. The footway has no surface.
            ([-48.0, 0.0], [0.0, 1.0], 100.0 - 20.0 - EDGE_TRIM),
        ];
        assert_eq!(legs.len(), expected.len());
        for (leg, (origin, dir, length)) in legs.iter().zip(expected) {
            assert!(
                close(leg.origin[0], origin[0]) && close(leg.origin[1], origin[1]),
                "{leg:?}"
            );
            assert!(
                close(leg.dir[0], dir[0]) && close(leg.dir[1], dir[1]),
                "{leg:?}"
            );
            assert!(close(leg.length, length), "{leg:?}");
        }
        // Three lanes (9 m): the middle one, on the centreline.
        let mut three = map.clone();
        three.roads[1].fitted[0][0] = 9.0;
        assert_eq!(map_legs(&three, 3.0, 20.0)[4].origin, [-50.0, 0.0]);
        // A run ending inside the box stops the look-ahead short of its end only.
        let mut inside = map.clone();
        inside.roads[1].centreline[1] = [-50.0, 90.0];
        assert!(close(map_legs(&inside, 3.0, 20.0)[4].length, 70.0));
        // Narrowed to 9 m, the two-way road is driven east only.
        let mut narrow = map.clone();
        for f in &mut narrow.roads[0].fitted {
            f[0] = 9.0;
        }
        let legs = map_legs(&narrow, 3.0, 20.0);
        assert_eq!(legs.len(), 3);
        assert!(legs.iter().all(|l| l.dir[0] >= 0.0), "{legs:?}");
        // A narrow lane offset is kept; a look-ahead longer than every run drives all whole.
        let whole = map_legs(&map, 0.5, 500.0);
        assert_eq!(whole[0].origin, [-150.0, 0.5]);
        let total: f64 = whole.iter().map(|l| l.length).sum();
        assert!(close(total, 2.0 * (150.0 + 100.0 * 2f64.sqrt()) + 100.0));
    }

    #[test]
    fn lengths_scale_with_metres_per_pixel() {
        let roads = vec![road(0, Axis::Horizontal, 0.0, 400.0, 100.5)];
        let leg = &legs(&layout(roads), 0.5, 3.0, 25.0)[0];
        assert_eq!(leg.origin, [0.0, 100.5 * 0.5 + 3.0]);
        assert_eq!((leg.dir, leg.length), ([1.0, 0.0], 200.0 - 25.0));
    }
}
