//! Where the roads cross: the rectangles two crossing roads share, in metres.

use crate::model::geometry::RoadRect;
use crate::model::{Axis, ParsedLayout};

/// The area a horizontal and a vertical road share, world metres (x east, z south).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Junction {
    pub x: [f64; 2],
    pub z: [f64; 2],
    /// The horizontal road's id, then the vertical one's.
    pub roads: [u32; 2],
}

impl Junction {
    /// Its extent along a road along `axis`, and across it.
    pub fn along_across(&self, axis: Axis) -> ([f64; 2], [f64; 2]) {
        match axis {
            Axis::Horizontal => (self.x, self.z),
            Axis::Vertical => (self.z, self.x),
        }
    }

    /// Distance from `p` (x, z) to the rectangle; 0 inside.
    pub fn distance(&self, p: [f64; 2]) -> f64 {
        let gap = |r: [f64; 2], v: f64| (r[0] - v).max(v - r[1]).max(0.0);
        let (dx, dz) = (gap(self.x, p[0]), gap(self.z, p[1]));
        (dx * dx + dz * dz).sqrt()
    }
}

/// The index of the junction of `junctions` nearest to `p` (x, z); the first of equals.
pub(super) fn nearest(junctions: &[Junction], p: [f64; 2]) -> Option<usize> {
    junctions
        .iter()
        .enumerate()
        .map(|(j, junction)| (junction.distance(p), j))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, j)| j)
}

/// Every junction of the layout, horizontal roads first in id order, then by vertical
/// road id.
pub(super) fn junctions(layout: &ParsedLayout, metres_per_pixel: f64) -> Vec<Junction> {
    let of = |axis: Axis| layout.roads.iter().filter(move |r| r.axis == axis);
    let mut out = Vec::new();
    for h in of(Axis::Horizontal) {
        let a = RoadRect::of(h);
        for v in of(Axis::Vertical) {
            let b = RoadRect::of(v);
            if !a.overlaps(&b) {
                continue;
            }
            let x = [a.x[0].max(b.x[0]), a.x[1].min(b.x[1])];
            let z = [a.y[0].max(b.y[0]), a.y[1].min(b.y[1])];
            out.push(Junction {
                x: x.map(|v| v * metres_per_pixel),
                z: z.map(|v| v * metres_per_pixel),
                roads: [h.id, v.id],
            });
        }
    }
    out
}
