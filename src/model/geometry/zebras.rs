//! Roads → where their zebra crossings lie, and the stretches left for their lines: one
//! zebra crossing on each approach to a crossing (any stretch of a road where another
//! road's surface meets its centre line), [`CROSSING_MARGIN`] to [`ZEBRA_END`] from the
//! crossing, [`LINE_CLEARANCE`] before the lines. A stretch too short for its zebras, their
//! clearances and one [`DASH`] keeps its lines only.
//!
//! The scene paints the zebras and lines ([`crate::scene`]'s markings); the objects stage
//! stands pedestrians on the zebras. Both read them from here.

use super::{RoadRect, ZEBRA_END};
use crate::model::{Axis, ParsedLayout, Road};

/// Dash length, and the width of a line (the centre line a crossing meets), metres.
pub const DASH: f64 = 3.0;
pub const LINE_WIDTH: f64 = 0.15;
/// Clear road kept before and after a crossing, in metres.
pub const CROSSING_MARGIN: f64 = 1.0;
/// A zebra crossing's length along the road, metres.
pub const ZEBRA_DEPTH: f64 = 3.0;
/// Road kept clear between a zebra crossing and the lines, in metres.
pub const LINE_CLEARANCE: f64 = 1.5;
const _: () = assert!(CROSSING_MARGIN + ZEBRA_DEPTH == ZEBRA_END);

/// One road's zebra crossings and what is left of it for the lines, along-axis metres.
#[derive(Clone, Debug, PartialEq)]
pub struct Stretches {
    pub zebras: Vec<Zebra>,
    pub lines: Vec<[f64; 2]>,
}

/// Per road of `layout`, in order: its zebra crossings and line stretches, in metres
/// (`mpp` metres per layout pixel).
pub fn road_stretches(layout: &ParsedLayout, mpp: f64) -> Vec<Stretches> {
    let rects: Vec<RoadRect> = layout
        .roads
        .iter()
        .map(|r| metres(RoadRect::of(r), mpp))
        .collect();
    layout
        .roads
        .iter()
        .enumerate()
        .map(|(i, road)| {
            let own = [
                road.start.min(road.end) * mpp,
                road.start.max(road.end) * mpp,
            ];
            let (zebras, lines) = zebras_and_lines(own, &free_along(road, own, i, &rects, mpp));
            Stretches { zebras, lines }
        })
        .collect()
}

fn metres(r: RoadRect, mpp: f64) -> RoadRect {
    RoadRect {
        x: r.x.map(|v| v * mpp),
        y: r.y.map(|v| v * mpp),
    }
}

/// A zebra crossing: its along-axis range (metres), and whether it lies at the start of
/// its stretch (the crossing before it, at lower along-axis values).
pub type Zebra = ([f64; 2], bool);

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
pub fn free_stretches(range: [f64; 2], mut blocked: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_stretches_are_the_unblocked_gaps_of_the_range() {
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
}
