//! A layout's roads → `marking_NNNN` objects: where each road's marks go, painted by the
//! one painter maps use too ([`paint`](super::paint)). White dashes along each road's
//! centre line and between its driving lanes, a solid line along each parking lane (the
//! road's [`StreetProfile`]), and a zebra crossing on each approach to a crossing (any
//! stretch where another road's surface meets the centre line). Where the zebras lie, and
//! what is left of a road for its lines, is shared with the objects stage:
//! [`zebras`](crate::model::geometry::zebras). All markings stay out of every crossing and
//! a metre either side of it.
//!
//! - A zebra crossing starts a metre from the crossing: bars 3 m long, centred from curb
//!   to curb (less [`CURB_CLEARANCE`]), as pedestrians cross it from one block's corner to
//!   the other's. A stretch too short for its zebras, their clearances and one dash keeps
//!   its lines only.
//! - Before each zebra, where the traffic coming towards the crossing meets it first, a
//!   stop line [`STOP_LINE`] wide runs across that traffic's driving lanes, from the centre
//!   line to the parking lane (or [`CURB_CLEARANCE`] short of the curb), ending
//!   [`STOP_LINE_END`] from the crossing; cars standing in a lane wait behind it. Traffic
//!   keeps right: along a horizontal road it runs east on the south side, along a vertical
//!   one north on the east side.
//! - The lines stop [`LINE_CLEARANCE`] before a zebra.

use super::object;
use super::paint::{CURB_CLEARANCE, Line, Path, RoadMarks, STOP_LINE, StopMark, ZebraMark, paint};
use crate::model::geometry::zebras::{LINE_CLEARANCE, LINE_WIDTH, Stretches, road_stretches};
use crate::model::geometry::{MeshBuilder, STOP_LINE_END, StreetProfile, ZEBRA_END};
use crate::model::{Axis, ObjectKind, ParsedLayout, Road, SceneObject};

// The stop line lies between the zebra and the lines.
const _: () = assert!(STOP_LINE_END - STOP_LINE > ZEBRA_END);
const _: () = assert!(STOP_LINE_END < ZEBRA_END + LINE_CLEARANCE);

/// The markings of every road of `layout` (`mpp` metres per pixel), in road order; roads
/// without any are left out. Pure and deterministic.
pub fn marking_objects(layout: &ParsedLayout, mpp: f64, material: u32) -> Vec<SceneObject> {
    layout
        .roads
        .iter()
        .zip(road_stretches(layout, mpp))
        .filter_map(|(road, stretches)| {
            let mut mesh = MeshBuilder::new(material);
            paint(
                &mut mesh,
                &path(road, mpp),
                &road_marks(road, mpp, stretches),
            );
            (!mesh.is_empty()).then(|| {
                object(
                    ObjectKind::Marking,
                    format!("marking_{:04}", road.id),
                    vec![mesh],
                )
            })
        })
        .collect()
}

/// The painted centre line of `road` as a [`Path`] from the world's axis (x = 0 for a
/// horizontal road, z = 0 for a vertical one), so that arc length along it is the
/// along-axis coordinate in metres: a horizontal road runs east (its right is south), a
/// vertical one south (its right is west).
fn path(road: &Road, mpp: f64) -> Path {
    let line = road.line * mpp;
    let end = road.start.max(road.end) * mpp;
    Path::new(match road.axis {
        Axis::Horizontal => vec![[0.0, line], [end, line]],
        Axis::Vertical => vec![[line, 0.0], [line, end]],
    })
}

/// What is painted on `road`, whose zebras and line stretches are `stretches`: its
/// [`lines`], a zebra kerb to kerb at each of its zebras, and the stop line behind it.
fn road_marks(road: &Road, mpp: f64, stretches: Stretches) -> RoadMarks {
    let Stretches {
        zebras,
        lines: free,
    } = stretches;
    let across = zebra_across(road, mpp);
    RoadMarks {
        lines: vec![lines(road, mpp)],
        stretches: free,
        zebras: zebras
            .iter()
            .map(|&(along, _)| ZebraMark {
                segment: 0,
                along,
                across,
            })
            .collect(),
        stops: zebras
            .iter()
            .map(|&(along, at_start)| stop_line(road, mpp, along, at_start))
            .collect(),
    }
}

/// The lines of `road`: the dashed centre line, dashed lines between the driving lanes of
/// each side, and a solid line along each parking lane ([`StreetProfile`]).
fn lines(road: &Road, mpp: f64) -> Vec<Line> {
    let profile = StreetProfile::of((road.edges[1] - road.edges[0]) * mpp);
    let line = |offset, solid| Line { offset, solid };
    let mut lines = vec![line(0.0, false)];
    for side in [-1.0, 1.0] {
        for k in 0..profile.lanes - 1 {
            lines.push(line(side * profile.lane_edge(k), false));
        }
        if profile.parking > 0.0 {
            lines.push(line(side * profile.lane_edge(profile.lanes - 1), true));
        }
    }
    lines
}

/// The range a zebra's bars on `road` are centred in, metres right of its [`path`]: its
/// kerbs less [`CURB_CLEARANCE`] (the painted line may sit off their middle).
fn zebra_across(road: &Road, mpp: f64) -> [f64; 2] {
    let line = road.line * mpp;
    let lo = road.edges[0].min(road.edges[1]) * mpp + CURB_CLEARANCE;
    let hi = road.edges[0].max(road.edges[1]) * mpp - CURB_CLEARANCE;
    match road.axis {
        // Right of a road running east is south (+z), of one running south west (−x).
        Axis::Horizontal => [lo - line, hi - line],
        Axis::Vertical => [line - hi, line - lo],
    }
}

/// The stop line of the zebra crossing over `zebra` (along-axis metres; `at_start`: the
/// crossing lies before it) of `road`: across the driving lanes of the traffic coming
/// towards the crossing, which keeps right, on the zebra's side away from the crossing,
/// so that traffic meets the line first.
fn stop_line(road: &Road, mpp: f64, zebra: [f64; 2], at_start: bool) -> StopMark {
    let profile = StreetProfile::of((road.edges[1] - road.edges[0]) * mpp);
    // Where the lanes end: the parking lane, or short of the curb.
    let reach = if profile.parking > 0.0 {
        profile.lane_edge(profile.lanes - 1) - LINE_WIDTH / 2.0
    } else {
        profile.half - CURB_CLEARANCE
    };
    let start = LINE_WIDTH / 2.0;
    // The traffic running along the path keeps to its right (positive offsets).
    let across = if at_start {
        [-reach, -start]
    } else {
        [start, reach]
    };
    // On the zebra's side away from the crossing, ending `STOP_LINE_END` from the
    // crossing, which lies `ZEBRA_END` from the zebra's far end.
    let along = if at_start {
        let crossing = zebra[1] - ZEBRA_END;
        [
            crossing + STOP_LINE_END - STOP_LINE,
            crossing + STOP_LINE_END,
        ]
    } else {
        let crossing = zebra[0] + ZEBRA_END;
        [
            crossing - STOP_LINE_END,
            crossing - STOP_LINE_END + STOP_LINE,
        ]
    };
    StopMark {
        segment: 0,
        along,
        across,
        give_way: None,
    }
}

#[cfg(test)]
mod tests {
    use super::super::paint::{BAR, BAR_GAP, centred_pieces};
    use super::*;

    fn road(axis: Axis, edges: [f64; 2]) -> Road {
        Road {
            id: 0,
            axis,
            start: 0.0,
            end: 100.0,
            line: (edges[0] + edges[1]) / 2.0,
            edges,
        }
    }

    /// Offsets right of `road`'s path (`mpp` 1) as world across-axis coordinates.
    fn world(road: &Road, across: [f64; 2]) -> [f64; 2] {
        match road.axis {
            Axis::Horizontal => across.map(|c| road.line + c),
            Axis::Vertical => [road.line - across[1], road.line - across[0]],
        }
    }

    #[test]
    fn zebra_bars_are_centred_between_the_curbs() {
        // 17.05 m between the curbs, 16.45 m inside the clearances: 15 bars take 15 × 0.5 +
        // 14 × 0.6 = 15.9 m, 0.275 m either side.
        for axis in [Axis::Horizontal, Axis::Vertical] {
            let mut r = road(axis, [10.0, 41.0]);
            r.line = 25.0;
            let scaled = Road {
                line: r.line * 0.55,
                edges: r.edges.map(|e| e * 0.55),
                ..r.clone()
            };
            let bars: Vec<[f64; 2]> = centred_pieces(zebra_across(&r, 0.55), BAR, BAR_GAP)
                .into_iter()
                .map(|b| world(&scaled, b))
                .collect();
            assert_eq!(bars.len(), 15);
            let (lo, hi) = (10.0 * 0.55 + CURB_CLEARANCE, 41.0 * 0.55 - CURB_CLEARANCE);
            let (first, last) = (
                bars.iter().map(|b| b[0]).fold(f64::INFINITY, f64::min),
                bars.iter().map(|b| b[1]).fold(f64::NEG_INFINITY, f64::max),
            );
            assert!((first - lo - 0.275).abs() < 1e-9, "{bars:?}");
            assert!((hi - last - 0.275).abs() < 1e-9, "{bars:?}");
            for bar in &bars {
                assert!((bar[1] - bar[0] - BAR).abs() < 1e-12);
            }
        }
        // Too narrow for one bar: none.
        let bars_of_width = |w: f64| {
            centred_pieces(
                zebra_across(&road(Axis::Vertical, [0.0, w]), 1.0),
                BAR,
                BAR_GAP,
            )
        };
        assert!(bars_of_width(0.9).is_empty());
        assert_eq!(bars_of_width(1.2).len(), 1);
    }

    #[test]
    fn stop_lines_cross_the_oncoming_lanes_behind_each_zebra() {
        // 17.6 m wide (2 + 2 lanes of 3.1 m, parking 2.6 m), centre line at 20 m; crossed
        // over [40, 50] (zebras [36, 39] and [51, 54] as above).
        let reach = 6.2 - LINE_WIDTH / 2.0;
        let start = LINE_WIDTH / 2.0;
        let close =
            |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9;
        let line = |axis, zebra, at_start| {
            let r = road(axis, [11.2, 28.8]);
            let stop = stop_line(&r, 1.0, zebra, at_start);
            (world(&r, stop.across), stop.along)
        };
        // Horizontal: traffic towards +x (east) keeps to the high (south) side and meets
        // the crossing past the first zebra; its stop line ends 4.5 m before it.
        let (across, along) = line(Axis::Horizontal, [36.0, 39.0], false);
        assert!(close(across, [20.0 + start, 20.0 + reach]), "{across:?}");
        assert!(close(along, [35.5, 35.9]), "{along:?}");
        // Traffic towards −x keeps to the low (north) side; its line lies past the second
        // zebra, 4.5 m from the crossing's far edge (50).
        let (across, along) = line(Axis::Horizontal, [51.0, 54.0], true);
        assert!(close(across, [20.0 - reach, 20.0 - start]), "{across:?}");
        assert!(close(along, [54.1, 54.5]), "{along:?}");
        // Vertical: traffic towards +z (south) keeps to the low (west) side.
        let (across, _) = line(Axis::Vertical, [36.0, 39.0], false);
        assert!(close(across, [20.0 - reach, 20.0 - start]), "{across:?}");
        let (across, _) = line(Axis::Vertical, [51.0, 54.0], true);
        assert!(close(across, [20.0 + start, 20.0 + reach]), "{across:?}");
        // Between the zebra and the lines, which start 1.5 m past it.
        assert!(along[0] > 54.0 && along[1] < 54.0 + LINE_CLEARANCE);
    }

    #[test]
    fn a_road_path_measures_along_from_the_axis_and_paints_where_the_road_is() {
        // A vertical road at x = 20, from 30 to 90: a dash at along [40, 43] lies at z 40..43.
        let mut r = road(Axis::Vertical, [11.2, 28.8]);
        (r.start, r.end) = (30.0, 90.0);
        let marks = RoadMarks {
            lines: vec![vec![Line {
                offset: 0.0,
                solid: true,
            }]],
            stretches: vec![[40.0, 43.0]],
            ..RoadMarks::default()
        };
        let mut mesh = MeshBuilder::new(0);
        paint(&mut mesh, &path(&r, 1.0), &marks);
        let mesh = mesh.finish();
        let near = |v: f32, of: &[f64]| of.iter().any(|&w| (f64::from(v) - w).abs() < 1e-5);
        let h = LINE_WIDTH / 2.0;
        assert_eq!(mesh.positions.len(), 4);
        for p in &mesh.positions {
            assert!(
                near(p[0], &[20.0 - h, 20.0 + h]) && near(p[2], &[40.0, 43.0]),
                "{p:?}"
            );
        }
    }
}
