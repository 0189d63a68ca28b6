//! Roads → `marking_NNNN` objects: white dashes along each road's centre line and between
//! its driving lanes, a solid line along each parking lane (the road's
//! [`StreetProfile`]), and a zebra crossing on each approach to a crossing (any stretch
//! where another road's surface meets the centre line). All of them stay out of every
//! crossing and [`CROSSING_MARGIN`] either side of it.
//!
//! - A zebra crossing starts [`CROSSING_MARGIN`] from the crossing: bars [`BAR`] wide and
//!   [`ZEBRA_DEPTH`] long, parallel to the road, [`BAR_GAP`] apart and centred from curb
//!   to curb (less [`CURB_CLEARANCE`]), as pedestrians cross it from one block's corner to
//!   the other's. A stretch too short for its zebras, their clearances and one dash keeps
//!   its lines only.
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
use crate::model::geometry::{
    MARKING_Y, MeshBuilder, RoadRect, STOP_LINE_END, StreetProfile, ZEBRA_END,
};
use crate::model::{Axis, ParsedLayout, Road, SceneObject};

/// Dash length, gap between dashes and line width, in metres.
pub const DASH: f64 = 3.0;
pub const GAP: f64 = 6.0;
pub const LINE_WIDTH: f64 = 0.15;
/// Clear road kept before and after a crossing, in metres.
pub const CROSSING_MARGIN: f64 = 1.0;
/// A zebra crossing: its length along the road, its bars' width and the gap between them,
/// and the road kept clear at each curb, in metres.
pub const ZEBRA_DEPTH: f64 = 3.0;
pub const BAR: f64 = 0.5;
pub const BAR_GAP: f64 = 0.6;
pub const CURB_CLEARANCE: f64 = 0.3;
/// Road kept clear between a zebra crossing and the lines, in metres.
pub const LINE_CLEARANCE: f64 = 1.5;
/// Width of a stop line along the road, in metres.
pub const STOP_LINE: f64 = 0.4;
// The objects stage keeps lane cars behind the zebras by the shared figure.
const _: () = assert!(CROSSING_MARGIN + ZEBRA_DEPTH == ZEBRA_END);
// The stop line lies between the zebra and the lines.
const _: () = assert!(STOP_LINE_END - STOP_LINE > ZEBRA_END);
const _: () = assert!(STOP_LINE_END < ZEBRA_END + LINE_CLEARANCE);

pub fn marking_objects(layout: &ParsedLayout, mpp: f64, material: u32) -> Vec<SceneObject> {
    let rects: Vec<RoadRect> = layout
        .roads
        .iter()
        .map(|r| metres(RoadRect::of(r), mpp))
        .collect();
    layout
        .roads
        .iter()
        .enumerate()
        .filter_map(|(i, road)| {
            let mut mesh = MeshBuilder::new(material);
            let own = [
                road.start.min(road.end) * mpp,
                road.start.max(road.end) * mpp,
            ];
            let (zebras, free) = zebras_and_lines(own, &free_along(road, own, i, &rects, mpp));
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
            (!mesh.is_empty())
                .then(|| object(format!("marking_{:04}", road.id), "marking", vec![mesh]))
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

/// A zebra crossing: its along-axis range (metres), and whether it lies at the start of
/// its stretch (the crossing before it, at lower along-axis values).
type Zebra = ([f64; 2], bool);

/// Of the stretches of a road clear of crossings (`free`, along-axis metres, in order; the
/// road runs over `own`): its zebra crossings, one at each end of a stretch that meets a
/// crossing (the along-axis range, and whether it is at the stretch's start, the crossing
/// lying before it), and what is left of each stretch for the lines.
fn zebras_and_lines(own: [f64; 2], free: &[[f64; 2]]) -> (Vec<Zebra>, Vec<[f64; 2]>) {
    let mut zebras = Vec::new();
    let mut lines = Vec::new();
    // A stretch ending short of the road's own end meets a crossing there.
    let eps = 1e-9;
    for &[a, b] in free {
        let ends = [a > own[0] + eps, b < own[1] - eps];
        let need = ends.iter().filter(|&&e| e).count() as f64 * (ZEBRA_DEPTH + LINE_CLEARANCE);
        if b - a < need + DASH {
            // Too short for its zebras and a dash between: lines only, as before.
            lines.push([a, b]);
            continue;
        }
        let mut left = [a, b];
        if ends[0] {
            zebras.push(([a, a + ZEBRA_DEPTH], true));
            left[0] += ZEBRA_DEPTH + LINE_CLEARANCE;
        }
        if ends[1] {
            zebras.push(([b - ZEBRA_DEPTH, b], false));
            left[1] -= ZEBRA_DEPTH + LINE_CLEARANCE;
        }
        lines.push(left);
    }
    (zebras, lines)
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

fn metres(r: RoadRect, mpp: f64) -> RoadRect {
    RoadRect {
        x: r.x.map(|v| v * mpp),
        y: r.y.map(|v| v * mpp),
    }
}

/// Along-axis `[from, to]` (metres) of the stretches of road `i` clear of crossings.
fn free_along(road: &Road, own: [f64; 2], i: usize, rects: &[RoadRect], mpp: f64) -> Vec<[f64; 2]> {
    let half = LINE_WIDTH / 2.0;
    let line = road.line * mpp;
    let strip = match road.axis {
        Axis::Horizontal => RoadRect {
            x: own,
            y: [line - half, line + half],
        },
        Axis::Vertical => RoadRect {
            x: [line - half, line + half],
            y: own,
        },
    };
    let blocked: Vec<[f64; 2]> = rects
        .iter()
        .enumerate()
        .filter(|&(j, other)| j != i && other.overlaps(&strip))
        .map(|(_, other)| {
            let along = match road.axis {
                Axis::Horizontal => other.x,
                Axis::Vertical => other.y,
            };
            [along[0] - CROSSING_MARGIN, along[1] + CROSSING_MARGIN]
        })
        .collect();
    free_stretches(own, blocked)
}

/// `range` minus the union of `blocked`, in order.
fn free_stretches(range: [f64; 2], mut blocked: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    blocked.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let mut free = Vec::new();
    let mut from = range[0];
    for [b0, b1] in blocked {
        if b0 > from {
            free.push([from, b0.min(range[1])]);
        }
        from = from.max(b1);
        if from >= range[1] {
            break;
        }
    }
    if from < range[1] {
        free.push([from, range[1]]);
    }
    free.retain(|s| s[0] < s[1]);
    free
}

/// As many whole dashes as fit in `stretch`, centred in it.
fn centred_dashes(stretch: [f64; 2]) -> Vec<[f64; 2]> {
    centred_pieces(stretch, DASH, GAP)
}

/// As many pieces `length` long and `gap` apart as fit in `range`, centred in it.
fn centred_pieces(range: [f64; 2], length: f64, gap: f64) -> Vec<[f64; 2]> {
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
    fn free_stretches_cases() {
        type Spans = Vec<[f64; 2]>;
        let cases: [(Spans, Spans); 5] = [
            (vec![], vec![[0.0, 100.0]]),
            (vec![[40.0, 50.0]], vec![[0.0, 40.0], [50.0, 100.0]]),
            (
                vec![[60.0, 70.0], [-5.0, 10.0]],
                vec![[10.0, 60.0], [70.0, 100.0]],
            ),
            (
                vec![[20.0, 40.0], [30.0, 50.0]],
                vec![[0.0, 20.0], [50.0, 100.0]],
            ),
            (vec![[90.0, 120.0], [-1.0, 101.0]], vec![]),
        ];
        for (blocked, want) in cases {
            assert_eq!(
                free_stretches([0.0, 100.0], blocked.clone()),
                want,
                "{blocked:?}"
            );
        }
    }

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
    fn zebras_sit_where_a_stretch_meets_a_crossing_and_lines_keep_clear_of_them() {
        // A road over [0, 100] crossed over [40, 50] (with the margins): the first stretch
        // meets it at its end, the second at its start; the road's own ends have none.
        let (zebras, lines) = zebras_and_lines([0.0, 100.0], &[[0.0, 39.0], [51.0, 100.0]]);
        assert_eq!(zebras, vec![([36.0, 39.0], false), ([51.0, 54.0], true)]);
        assert_eq!(lines, vec![[0.0, 34.5], [55.5, 100.0]]);
        // A 12 m stretch between two crossings just holds both zebras, their clearances and
        // one dash (2 × 4.5 m + 3 m); an 11 m one keeps its lines only.
        let (zebras, lines) = zebras_and_lines([0.0, 100.0], &[[30.0, 42.0]]);
        assert_eq!(zebras, vec![([30.0, 33.0], true), ([39.0, 42.0], false)]);
        assert_eq!(lines, vec![[34.5, 37.5]]);
        let (zebras, lines) = zebras_and_lines([0.0, 100.0], &[[30.0, 41.0]]);
        assert!(zebras.is_empty());
        assert_eq!(lines, vec![[30.0, 41.0]]);
        // A road crossed nowhere: lines only.
        let (zebras, lines) = zebras_and_lines([5.0, 60.0], &[[5.0, 60.0]]);
        assert!(zebras.is_empty());
        assert_eq!(lines, vec![[5.0, 60.0]]);
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
