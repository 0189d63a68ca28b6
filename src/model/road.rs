//! A road: a straight stretch of road pixels around a yellow centre line.

use serde::{Deserialize, Serialize};

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

    /// Centre of the centre line, as image `(x, y)`.
    pub fn centre(&self) -> [f64; 2] {
        let along = (self.start + self.end) / 2.0;
        match self.axis {
            Axis::Horizontal => [along, self.line],
            Axis::Vertical => [self.line, along],
        }
    }
}
