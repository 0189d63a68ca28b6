//! Roads → `marking_NNNN` objects: white dashes along each road's centre line and between
//! its driving lanes, a solid line along each parking lane (the road's
//! [`StreetProfile`]), and a zebra crossing on each approach to a crossing (any stretch
//! where another road's surface meets the centre line). Where the zebras lie, and what is
//! left of a road for its lines, is shared with the objects stage:
//! [`zebras`](crate::model::geometry::zebras). All markings stay out of every crossing and
//! a metre either side of it.
//!
//! - A zebra crossing starts a metre from the crossing: bars [`BAR`] wide and 3 m long,
//!   parallel to the road, [`BAR_GAP`] apart and centred from curb to curb (less
//!   [`CURB_CLEARANCE`]), as pedestrians cross it from one block's corner to the other's.
//!   A stretch too short for its zebras, their clearances and one dash keeps its lines
//!   only.
//! - Before each zebra, where the traffic coming towards the crossing meets it first, a
//!   stop line [`STOP_LINE`] wide runs across that traffic's driving lanes, from the centre line to
//!   the parking lane (or [`CURB_CLEARANCE`] short of the curb), ending [`STOP_LINE_END`]
//!   from the crossing; cars standing in a lane wait behind it. Traffic keeps right:
//!   along a horizontal road it runs east on the south side, along a vertical one north on
//!   the east side.
//! - The lines stop [`LINE_CLEARANCE`] before a zebra. Within each stretch left to them
//!   the dashes ([`DASH`] long, [`GAP`] apart) are centred, so a stretch between two
//!   crossings looks the same from both ends.

use super::object;
use crate::model::ObjectKind;
use crate::model::geometry::zebras::{DASH, LINE_CLEARANCE, LINE_WIDTH};
use crate::model::geometry::zebras::{Stretches, road_stretches};
use crate::model::geometry::{MARKING_Y, MeshBuilder, STOP_LINE_END, StreetProfile, ZEBRA_END};
use crate::model::{Axis, ParsedLayout, Road, SceneObject};

/// Gap between dashes, in metres (their length and the lines' width: [`DASH`],
/// [`LINE_WIDTH`]).
pub const GAP: f64 = 6.0;
/// A zebra crossing's bars' width and the gap between them, and the road kept clear at
/// each curb, in metres (its length: [`ZEBRA_DEPTH`](crate::model::geometry::zebras::ZEBRA_DEPTH)).
pub const BAR: f64 = 0.5;
pub const BAR_GAP: f64 = 0.6;
pub const CURB_CLEARANCE: f64 = 0.3;
/// Width of a stop line along the road, in metres.
pub const STOP_LINE: f64 = 0.4;
// The stop line lies between the zebra and the lines.
const _: () = assert!(STOP_LINE_END - STOP_LINE > ZEBRA_END);
const _: () = assert!(STOP_LINE_END < ZEBRA_END + LINE_CLEARANCE);

pub fn marking_objects(layout: &ParsedLayout, mpp: f64, material: u32) -> Vec<SceneObject> {
    layout
        .roads
        .iter()
        .zip(road_stretches(layout, mpp))
        .filter_map(|(road, stretches)| {
            let mut mesh = MeshBuilder::new(material);
            let Stretches {
                zebras,
                lines: free,
            } = stretches;
            for (offset, solid) in lines(road, mpp) {
                for &stretch in &free {
                    let pieces = if solid {
                        vec![stretch]
                    } else {
                        centred_dashes(stretch)
                    };
                    for [a, b] in pieces {
                        stripe(&mut mesh, road, mpp, offset, [a, b]);
                    }
                }
            }
            let bars = bars(road, mpp);
            for (along, at_start) in zebras {
                for &across in &bars {
                    rect(&mut mesh, road, across, along);
                }
                let (across, along) = stop_line(road, mpp, along, at_start);
                rect(&mut mesh, road, across, along);
            }
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

/// The lines of `road` as (offset from the centre line in metres, solid): the dashed
/// centre line, dashed lines between the driving lanes of each side, and a solid line
/// along each parking lane ([`StreetProfile`]).
fn lines(road: &Road, mpp: f64) -> Vec<(f64, bool)> {
    let profile = StreetProfile::of((road.edges[1] - road.edges[0]) * mpp);
    let mut lines = vec![(0.0, false)];
    for side in [-1.0, 1.0] {
        for k in 0..profile.lanes - 1 {
            lines.push((side * profile.lane_edge(k), false));
        }
        if profile.parking > 0.0 {
            lines.push((side * profile.lane_edge(profile.lanes - 1), true));
        }
    }
    lines
}

/// The across-axis ranges (metres) of a zebra crossing's bars on `road`: as many as fit
/// between its curbs less [`CURB_CLEARANCE`], centred.
fn bars(road: &Road, mpp: f64) -> Vec<[f64; 2]> {
    let lo = road.edges[0].min(road.edges[1]) * mpp + CURB_CLEARANCE;
    let hi = road.edges[0].max(road.edges[1]) * mpp - CURB_CLEARANCE;
    centred_pieces([lo, hi], BAR, BAR_GAP)
}

/// The stop line of the zebra crossing `zebra` (along-axis metres; `at_start`: the
/// crossing lies before it) of `road`, as (across, along) ranges in metres: across the
/// driving lanes of the traffic coming towards the crossing, on the zebra's side away from
/// the crossing, so that traffic meets the line first.
fn stop_line(road: &Road, mpp: f64, zebra: [f64; 2], at_start: bool) -> ([f64; 2], [f64; 2]) {
    let profile = StreetProfile::of((road.edges[1] - road.edges[0]) * mpp);
    // Where the lanes end: the parking lane, or short of the curb.
    let reach = if profile.parking > 0.0 {
        profile.lane_edge(profile.lanes - 1) - LINE_WIDTH / 2.0
    } else {
        profile.half - CURB_CLEARANCE
    };
    let start = LINE_WIDTH / 2.0;
    // The traffic running towards +along keeps to the high side of a horizontal road
    // (east on the south side) and to the low side of a vertical one (north, towards
    // −along, on the east side).
    let towards_plus = !at_start;
    let high = towards_plus == (road.axis == Axis::Horizontal);
    let line = road.line * mpp;
    let across = if high {
        [line + start, line + reach]
    } else {
        [line - reach, line - start]
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
    (across, along)
}

/// One [`LINE_WIDTH`] quad along `road`, `offset` metres from its centre line, over
/// `along` (metres along its axis).
fn stripe(mesh: &mut MeshBuilder, road: &Road, mpp: f64, offset: f64, along: [f64; 2]) {
    let half = LINE_WIDTH / 2.0;
    let line = road.line * mpp + offset;
    rect(mesh, road, [line - half, line + half], along);
}

/// One marking quad on `road`: `across` and `along` its axis, in metres.
fn rect(mesh: &mut MeshBuilder, road: &Road, across: [f64; 2], along: [f64; 2]) {
    let (x, z) = match road.axis {
        Axis::Horizontal => (along, across),
        Axis::Vertical => (across, along),
    };
    // uv: the whole stripe is one white quad; 0..1 over it.
    let corners = [
        [x[0], MARKING_Y, z[0]],
        [x[1], MARKING_Y, z[0]],
        [x[1], MARKING_Y, z[1]],
        [x[0], MARKING_Y, z[1]],
    ];
    let uvs = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    mesh.quad(corners, crate::model::geometry::UP, uvs);
}

/// As many whole dashes as fit in `stretch`, centred in it.
pub(super) fn centred_dashes(stretch: [f64; 2]) -> Vec<[f64; 2]> {
    centred_pieces(stretch, DASH, GAP)
}

/// As many pieces `length` long and `gap` apart as fit in `range`, centred in it.
pub(super) fn centred_pieces(range: [f64; 2], length: f64, gap: f64) -> Vec<[f64; 2]> {
    let room = range[1] - range[0];
    let period = length + gap;
    // n pieces take n·length + (n − 1)·gap.
    let n = ((room + gap) / period).floor();
    // A non-finite range or fewer than one piece: nothing.
    if !n.is_finite() || n < 1.0 {
        return Vec::new();
    }
    let first = range[0] + (room - (n * period - gap)) / 2.0;
    (0..n as u64)
        .map(|k| {
            let a = first + k as f64 * period;
            [a, a + length]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dashes_are_centred_and_stay_inside() {
        assert_eq!(centred_dashes([0.0, 2.9]), Vec::<[f64; 2]>::new());
        assert_eq!(centred_dashes([10.0, 14.0]), vec![[10.5, 13.5]]);
        // 20 m: two dashes (3 + 6 + 3 = 12) with 4 m either side.
        assert_eq!(centred_dashes([0.0, 20.0]), vec![[4.0, 7.0], [13.0, 16.0]]);
        assert_eq!(centred_dashes([0.0, 21.0]).len(), 3);
        let many = centred_dashes([3.0, 700.0]);
        assert_eq!(many.len(), 78);
        assert!(many[0][0] >= 3.0 && many[77][1] <= 700.0);
    }

    #[test]
    fn zebra_bars_are_centred_between_the_curbs() {
        let road = |edges: [f64; 2]| Road {
            id: 0,
            axis: Axis::Horizontal,
            start: 0.0,
            end: 100.0,
            line: (edges[0] + edges[1]) / 2.0,
            edges,
        };
        // 17.05 m between the curbs, 16.45 m inside the clearances: 15 bars take 15 × 0.5 +
        // 14 × 0.6 = 15.9 m, 0.275 m either side.
        let bars = bars(&road([10.0, 41.0]), 0.55);
        assert_eq!(bars.len(), 15);
        let (lo, hi) = (10.0 * 0.55 + CURB_CLEARANCE, 41.0 * 0.55 - CURB_CLEARANCE);
        assert!((bars[0][0] - lo - 0.275).abs() < 1e-9, "{bars:?}");
        assert!((hi - bars[14][1] - 0.275).abs() < 1e-9, "{bars:?}");
        for pair in bars.windows(2) {
            assert!((pair[1][0] - pair[0][1] - BAR_GAP).abs() < 1e-9);
            assert!((pair[0][1] - pair[0][0] - BAR).abs() < 1e-12);
        }
        // Too narrow for one bar: none.
        assert!(bars_of_width(0.9).is_empty());
        assert_eq!(bars_of_width(1.2).len(), 1);
    }

    #[test]
    fn stop_lines_cross_the_oncoming_lanes_behind_each_zebra() {
        // 17.6 m wide (2 + 2 lanes of 3.1 m, parking 2.6 m), centre line at 20 m; crossed
        // over [40, 50] (zebras [36, 39] and [51, 54] as above).
        let road = |axis| Road {
            id: 0,
            axis,
            start: 0.0,
            end: 100.0,
            line: 20.0,
            edges: [11.2, 28.8],
        };
        let reach = 6.2 - LINE_WIDTH / 2.0;
        let start = LINE_WIDTH / 2.0;
        let close =
            |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9;
        // Horizontal: traffic towards +x (east) keeps to the high (south) side and meets
        // the crossing past the first zebra; its stop line ends 4.5 m before it.
        let (across, along) = stop_line(&road(Axis::Horizontal), 1.0, [36.0, 39.0], false);
        assert!(close(across, [20.0 + start, 20.0 + reach]), "{across:?}");
        assert!(close(along, [35.5, 35.9]), "{along:?}");
        // Traffic towards −x keeps to the low (north) side; its line lies past the second
        // zebra, 4.5 m from the crossing's far edge (50).
        let (across, along) = stop_line(&road(Axis::Horizontal), 1.0, [51.0, 54.0], true);
        assert!(close(across, [20.0 - reach, 20.0 - start]), "{across:?}");
        assert!(close(along, [54.1, 54.5]), "{along:?}");
        // Vertical: traffic towards +z (south) keeps to the low (west) side.
        let (across, _) = stop_line(&road(Axis::Vertical), 1.0, [36.0, 39.0], false);
        assert!(close(across, [20.0 - reach, 20.0 - start]), "{across:?}");
        let (across, _) = stop_line(&road(Axis::Vertical), 1.0, [51.0, 54.0], true);
        assert!(close(across, [20.0 + start, 20.0 + reach]), "{across:?}");
        // Between the zebra and the lines, which start 1.5 m past it.
        assert!(along[0] > 54.0 && along[1] < 54.0 + LINE_CLEARANCE);
    }

    /// The bars of a road `width` metres wide (1 m per pixel).
    fn bars_of_width(width: f64) -> Vec<[f64; 2]> {
        bars(
            &Road {
                id: 0,
                axis: Axis::Vertical,
                start: 0.0,
                end: 10.0,
                line: width / 2.0,
                edges: [0.0, width],
            },
            1.0,
        )
    }
}
