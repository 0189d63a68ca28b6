//! A road → the rectangle of its surface in layout pixels, and rectangle differences (so
//! crossing roads do not overlap).

use crate::model::{Axis, Road};

/// An axis-aligned rectangle `[x0, x1] × [y0, y1]` in continuous layout pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoadRect {
    pub x: [f64; 2],
    pub y: [f64; 2],
}

impl RoadRect {
    /// The road's surface: `start..end` along, its edges across.
    pub fn of(road: &Road) -> RoadRect {
        let along = [road.start.min(road.end), road.start.max(road.end)];
        let across = [
            road.edges[0].min(road.edges[1]),
            road.edges[0].max(road.edges[1]),
        ];
        match road.axis {
            Axis::Horizontal => RoadRect {
                x: along,
                y: across,
            },
            Axis::Vertical => RoadRect {
                x: across,
                y: along,
            },
        }
    }

    /// Whether the two share interior area (touching edges do not count).
    pub fn overlaps(&self, other: &RoadRect) -> bool {
        self.x[0] < other.x[1]
            && other.x[0] < self.x[1]
            && self.y[0] < other.y[1]
            && other.y[0] < self.y[1]
    }

    fn is_empty(&self) -> bool {
        !(self.x[0] < self.x[1] && self.y[0] < self.y[1])
    }

    /// `self` minus `cut`, as at most four disjoint rectangles: the full-width strips above
    /// and below `cut`, then the pieces left and right of it.
    pub fn minus(&self, cut: &RoadRect) -> Vec<RoadRect> {
        if !self.overlaps(cut) {
            return vec![*self];
        }
        let mid = [self.y[0].max(cut.y[0]), self.y[1].min(cut.y[1])];
        let pieces = [
            RoadRect {
                x: self.x,
                y: [self.y[0], cut.y[0]],
            },
            RoadRect {
                x: self.x,
                y: [cut.y[1], self.y[1]],
            },
            RoadRect {
                x: [self.x[0], cut.x[0]],
                y: mid,
            },
            RoadRect {
                x: [cut.x[1], self.x[1]],
                y: mid,
            },
        ];
        pieces.into_iter().filter(|p| !p.is_empty()).collect()
    }

    /// The parts of `self` that none of `cuts` covers.
    pub fn minus_all(&self, cuts: &[RoadRect]) -> Vec<RoadRect> {
        let mut pieces = vec![*self];
        for cut in cuts {
            pieces = pieces.iter().flat_map(|p| p.minus(cut)).collect();
        }
        pieces
    }

    #[cfg(test)]
    pub fn area(&self) -> f64 {
        if self.is_empty() {
            0.0
        } else {
            (self.x[1] - self.x[0]) * (self.y[1] - self.y[0])
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x0: f64, x1: f64, y0: f64, y1: f64) -> RoadRect {
        RoadRect {
            x: [x0, x1],
            y: [y0, y1],
        }
    }

    #[test]
    fn minus_keeps_exactly_the_uncovered_area() {
        let base = rect(0.0, 10.0, 0.0, 100.0);
        let cases = [
            // A crossing road right through: two pieces.
            (rect(-5.0, 20.0, 40.0, 50.0), 2, 900.0),
            // A T-junction from one side: top, bottom and the piece beside it.
            (rect(4.0, 20.0, 40.0, 50.0), 3, 940.0),
            // Disjoint and merely touching cuts change nothing.
            (rect(10.0, 20.0, 0.0, 100.0), 1, 1000.0),
            (rect(30.0, 40.0, 0.0, 100.0), 1, 1000.0),
            // A hole in the middle: four pieces.
            (rect(2.0, 8.0, 40.0, 50.0), 4, 940.0),
            // Fully covered: nothing left.
            (rect(-1.0, 11.0, -1.0, 101.0), 0, 0.0),
        ];
        for (cut, count, area) in cases {
            let pieces = base.minus(&cut);
            assert_eq!(pieces.len(), count, "{cut:?}");
            let total: f64 = pieces.iter().map(RoadRect::area).sum();
            assert_eq!(total, area, "{cut:?}");
            for (i, p) in pieces.iter().enumerate() {
                assert!(!p.overlaps(&cut), "{cut:?}");
                for q in &pieces[i + 1..] {
                    assert!(!p.overlaps(q), "{cut:?}");
                }
            }
        }
    }
}
