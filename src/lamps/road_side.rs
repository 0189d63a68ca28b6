//! Road + side + layout image → `RoadSide`: the strip pixels beside one side of a road.

use image::RgbImage;

use crate::model::PixelClass;
use crate::model::{Axis, Road};
use crate::spec::Palette;

/// Which side of a road: `Low` is above a horizontal road / left of a vertical one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Side {
    Low,
    High,
}

/// One side of one road, read off the layout image.
pub(crate) struct RoadSide<'a> {
    image: &'a RgbImage,
    palette: &'a Palette,
    road: &'a Road,
    side: Side,
}

impl<'a> RoadSide<'a> {
    pub(crate) fn new(
        image: &'a RgbImage,
        palette: &'a Palette,
        road: &'a Road,
        side: Side,
    ) -> Self {
        RoadSide {
            image,
            palette,
            road,
            side,
        }
    }

    /// The across-axis pixel boundary between road and strip on this side.
    pub(crate) fn boundary(&self) -> f64 {
        match self.side {
            Side::Low => self.road.edges[0].ceil(),
            Side::High => self.road.edges[1].floor(),
        }
    }

    /// The run of strip pixels at along-pixel `along`, counted outward from the road edge
    /// (0 if the first pixel past the edge is not strip, or lies off the image).
    pub(crate) fn run(&self, along: i64) -> u32 {
        let (step, mut across) = match self.side {
            Side::Low => (-1, self.boundary() as i64 - 1),
            Side::High => (1, self.boundary() as i64),
        };
        let mut run = 0;
        while self.class_at(along, across) == Some(PixelClass::Strip) {
            run += 1;
            across += step;
        }
        run
    }

    /// The strip's usual depth on this side: the lower median of the non-zero runs over
    /// every along-pixel of the road, or `None` if the side has no strip at all.
    ///
    /// Lamps use `min(run, typical depth)`: where a crossing road's strip meets this one
    /// (the ring's corner) the run follows the other strip for the whole block, and a lamp
    /// at half of that would stand far from its road.
    pub(crate) fn typical_depth(&self) -> Option<u32> {
        let first = self.road.start.floor().max(0.0) as i64;
        let last = self.road.end.ceil().min(self.along_extent() as f64) as i64;
        let mut runs: Vec<u32> = (first..last)
            .map(|a| self.run(a))
            .filter(|&r| r > 0)
            .collect();
        if runs.is_empty() {
            return None;
        }
        runs.sort_unstable();
        Some(runs[(runs.len() - 1) / 2])
    }

    fn along_extent(&self) -> u32 {
        match self.road.axis {
            Axis::Horizontal => self.image.width(),
            Axis::Vertical => self.image.height(),
        }
    }

    fn class_at(&self, along: i64, across: i64) -> Option<PixelClass> {
        let (x, y) = match self.road.axis {
            Axis::Horizontal => (along, across),
            Axis::Vertical => (across, along),
        };
        let x = u32::try_from(x).ok().filter(|&x| x < self.image.width())?;
        let y = u32::try_from(y).ok().filter(|&y| y < self.image.height())?;
        Some(self.palette.classify(self.image.get_pixel(x, y).0))
    }
}
