//! A road: a straight stretch of road pixels around a yellow centre line.

use serde::{Deserialize, Serialize};

use super::PavedSegment;

/// Which way a road runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Axis {
    /// Along x (image rows).
    Horizontal,
    /// Along y (image columns).
    Vertical,
}

/// A road in layout pixels (continuous coordinates, see [`crate::model`]).
///
/// "Along" is x for a horizontal road and y for a vertical one; "across" the other axis.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Road {
    /// Index in [`crate::model::ParsedLayout::roads`]: horizontal roads first, each group
    /// ordered by (across, start).
    pub id: u32,
    pub axis: Axis,
    /// Along-axis start of the centre line (the first yellow pixel's edge).
    pub start: f64,
    /// Along-axis end of the centre line (the last yellow pixel's far edge).
    pub end: f64,
    /// Across-axis position of the centre line (pixel centre, e.g. row + 0.5).
    pub line: f64,
    /// Across-axis edges of the road surface `[low, high)`: the run of road pixels through
    /// the centre line (median over the road's length, so crossings do not count).
    pub edges: [f64; 2],
}

impl Road {
    pub fn length(&self) -> f64 {
        self.end - self.start
    }

    pub fn width(&self) -> f64 {
        self.edges[1] - self.edges[0]
    }

    /// The road as a [`PavedSegment`] in layout pixels, as a map's roads are in metres:
    /// from `start` to `end` (so a horizontal road's left is above it, a vertical one's
    /// right of it), midway between its kerbs (the pixel edges of its surface; the painted
    /// line may sit half a pixel off), as wide as they are apart, with `sidewalks` left and
    /// right. Its `road` is the road's id.
    pub fn paved(&self, sidewalks: [f64; 2]) -> PavedSegment {
        let kerbs = [self.edges[0].ceil(), self.edges[1].floor()];
        let middle = (kerbs[0] + kerbs[1]) / 2.0;
        let (a, b) = match self.axis {
            Axis::Horizontal => ([self.start, middle], [self.end, middle]),
            Axis::Vertical => ([middle, self.start], [middle, self.end]),
        };
        PavedSegment {
            road: self.id as usize,
            a,
            b,
            width: kerbs[1] - kerbs[0],
            sidewalks,
        }
    }

    /// Centre of the centre line, as image `(x, y)`.
    pub fn centre(&self) -> [f64; 2] {
        let along = (self.start + self.end) / 2.0;
        match self.axis {
            Axis::Horizontal => [along, self.line],
            Axis::Vertical => [self.line, along],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A horizontal road runs east between its kerbs, left above; a vertical one south,
    /// left to the east: the same sides a map's segment has heading that way.
    #[test]
    fn a_road_is_a_paved_segment_between_its_kerbs() {
        let road = Road {
            id: 7,
            axis: Axis::Horizontal,
            start: 10.0,
            end: 90.0,
            line: 100.5,
            edges: [84.2, 116.0],
        };
        let s = road.paved([8.0, 6.0]);
        assert_eq!((s.road, s.a, s.b), (7, [10.0, 100.5], [90.0, 100.5]));
        assert_eq!((s.width, s.sidewalks), (31.0, [8.0, 6.0]));
        let left = crate::model::geometry::polygon::left_normal(s.a, s.b);
        assert_eq!(left, Some([0.0, -1.0]));
        let s = Road {
            axis: Axis::Vertical,
            edges: [84.0, 116.0],
            ..road
        }
        .paved([0.0, 0.0]);
        assert_eq!((s.a, s.b, s.width), ([100.0, 10.0], [100.0, 90.0], 32.0));
        let left = crate::model::geometry::polygon::left_normal(s.a, s.b).unwrap();
        assert_eq!(left[0], 1.0);
    }
}
