//! A building block: one connected region of block-coloured pixels.

use serde::{Deserialize, Serialize};

/// An axis-aligned pixel rectangle `[x0, x1) × [y0, y1)`: half-open, so `x1` is one past
/// the last column. [`crate::model::PixelBox`] is the inclusive box, with `x_min..=x_max`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct PxRect {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

impl PxRect {
    pub fn width(&self) -> u32 {
        self.x1 - self.x0
    }

    pub fn height(&self) -> u32 {
        self.y1 - self.y0
    }

    /// Whether the two rectangles share at least one pixel.
    pub fn intersects(&self, other: &PxRect) -> bool {
        self.x0 < other.x1 && other.x0 < self.x1 && self.y0 < other.y1 && other.y0 < self.y1
    }

    /// Whether `other` lies wholly inside `self`.
    pub fn contains(&self, other: &PxRect) -> bool {
        self.x0 <= other.x0 && other.x1 <= self.x1 && self.y0 <= other.y0 && other.y1 <= self.y1
    }
}

/// Rows `y0..y1` of a block, each covered by the same half-open x spans.
///
/// A rectangular block is one band; an L-shaped block two. Bands are sorted by `y0` and
/// spans by `x0`; spans never touch or overlap.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Band {
    pub y0: u32,
    pub y1: u32,
    pub spans: Vec<[u32; 2]>,
}

/// One building block.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Block {
    /// Index in [`crate::model::ParsedLayout::blocks`], ordered by (top row, left column) of
    /// the block's first pixel in raster order.
    pub id: u32,
    /// Tight bounding box of the block's pixels.
    pub bbox: PxRect,
    /// Number of block pixels.
    pub area: u64,
    /// Outer contour (as OpenCV's `findContours` gives it: centres of the border pixels),
    /// simplified to its corners.
    pub outline: Vec<[u32; 2]>,
    /// Exactly the block's pixels, as horizontal bands.
    pub bands: Vec<Band>,
}

impl Block {
    /// Whether pixel `(x, y)` belongs to the block.
    pub fn contains_pixel(&self, x: u32, y: u32) -> bool {
        self.bands
            .iter()
            .any(|b| b.y0 <= y && y < b.y1 && b.spans.iter().any(|s| s[0] <= x && x < s[1]))
    }
}
