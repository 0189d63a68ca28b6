//! Roads → `marking_NNNN` objects: white dashes along each road's centre line and between
//! its driving lanes, and a solid line along each parking lane (the road's
//! [`StreetProfile`]), all left out of every crossing (any stretch where another road's
//! surface meets the centre line) and [`CROSSING_MARGIN`] either side of it.
//!
//! Within each free stretch the dashes ([`DASH`] long, [`GAP`] apart) are centred, so a
//! stretch between two crossings looks the same from both ends.

use super::object;
use crate::model::geometry::{MARKING_Y, MeshBuilder, RoadRect, StreetProfile};
use crate::model::{Axis, ParsedLayout, Road, SceneObject};

/// Dash length, gap between dashes and line width, in metres.
pub const DASH: f64 = 3.0;
pub const GAP: f64 = 6.0;
pub const LINE_WIDTH: f64 = 0.15;
/// Clear road kept before and after a crossing, in metres.
pub const CROSSING_MARGIN: f64 = 1.0;

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
            let free = free_along(road, i, &rects, mpp);
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

/// One [`LINE_WIDTH`] quad along `road`, `offset` metres from its centre line, from `a` to
/// `b` metres along it.
fn stripe(mesh: &mut MeshBuilder, road: &Road, mpp: f64, offset: f64, [a, b]: [f64; 2]) {
    let half = LINE_WIDTH / 2.0;
    let line = road.line * mpp + offset;
    let (x, z) = match road.axis {
        Axis::Horizontal => ([a, b], [line - half, line + half]),
        Axis::Vertical => ([line - half, line + half], [a, b]),
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
fn free_along(road: &Road, i: usize, rects: &[RoadRect], mpp: f64) -> Vec<[f64; 2]> {
    let half = LINE_WIDTH / 2.0;
    let line = road.line * mpp;
    let own = [
        road.start.min(road.end) * mpp,
        road.start.max(road.end) * mpp,
    ];
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
    let length = stretch[1] - stretch[0];
    let period = DASH + GAP;
    // n dashes take n·DASH + (n − 1)·GAP.
    let n = ((length + GAP) / period).floor();
    // A non-finite stretch or fewer than one dash: nothing.
    if !n.is_finite() || n < 1.0 {
        return Vec::new();
    }
    let first = stretch[0] + (length - (n * period - GAP)) / 2.0;
    (0..n as u64)
        .map(|k| {
            let a = first + k as f64 * period;
            [a, a + DASH]
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
}
