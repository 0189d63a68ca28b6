//! One block + widths + gap + a random stream → `Filler`: paper Algorithm 1 on a pixel mask.
//!
//! The paper's recursion, made exact (all coordinates bbox-local):
//!
//! 1. A *row* fills a region `[x0, x1) × [y0, y1)` starting at its top-left `(x0, y0)`.
//! 2. At the current `x` the row picks uniformly among the widths that fit there: the
//!    square `[x, x + w) × [y0, y0 + w)` lies in the region, covers only block pixels, and
//!    contains no pixel within `gap` of a building placed before.
//! 3. It places that square, then fills the column below it, `[x, x + w) × [y0 + w + gap,
//!    y1)`, as a row of its own (recursively), then moves right to `x + w + gap`.
//! 4. It stops when nothing fits.
//!
//! Blocks need not be rectangles, so the driver ([`Filler::fill`]) starts rows wherever the
//! smallest width fits, scanning the block in raster order. The first such spot of a
//! rectangular block is its top-left, so the first row is the paper's algorithm exactly;
//! later spots only add buildings where it left room: notches of non-rectangular blocks,
//! and spots straddling the leftovers of neighbouring columns, which no single column's
//! region can reach.
//!
//! The recursion runs on an explicit stack (same order as the recursive call would take),
//! so a tall block with tiny buildings cannot overflow a rayon thread's stack.

use rand::RngExt;
use rand_pcg::Pcg64;

use super::block_mask::BlockMask;

/// A placed square in bbox-local pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct LocalSquare {
    pub(crate) x: u64,
    pub(crate) y: u64,
    pub(crate) width: u64,
    pub(crate) kind: u32,
}

/// A row in progress: its region and the `x` where the next building goes.
struct Row {
    x: u64,
    y0: u64,
    x1: u64,
    y1: u64,
}

/// The state of Algorithm 1 on one block.
pub(crate) struct Filler<'a> {
    mask: &'a BlockMask,
    widths: &'a [u32],
    gap: u64,
    rng: Pcg64,
    /// Pixels within `gap` of a placed building (or under one), row-major over the bbox.
    blocked: Vec<bool>,
    placed: Vec<LocalSquare>,
}

impl<'a> Filler<'a> {
    pub(crate) fn new(mask: &'a BlockMask, widths: &'a [u32], gap: u32, rng: Pcg64) -> Self {
        let cells = (mask.width() * mask.height()) as usize;
        Filler {
            mask,
            widths,
            gap: u64::from(gap),
            rng,
            blocked: vec![false; cells],
            placed: Vec::new(),
        }
    }

    /// Runs Algorithm 1 from every raster-order spot where the smallest width still fits
    /// and returns the squares in placement order.
    pub(crate) fn fill(mut self) -> Vec<LocalSquare> {
        let Some(smallest) = self.widths.iter().copied().filter(|&w| w > 0).min() else {
            return self.placed;
        };
        let smallest = u64::from(smallest);
        let (w, h) = (self.mask.width(), self.mask.height());
        for y in 0..h.saturating_sub(smallest - 1) {
            for x in 0..w.saturating_sub(smallest - 1) {
                if self.fits(x, y, smallest, w, h) {
                    self.fill_row(Row {
                        x,
                        y0: y,
                        x1: w,
                        y1: h,
                    });
                }
            }
        }
        self.placed
    }

    /// One row of Algorithm 1 with all its recursive sub-rows.
    fn fill_row(&mut self, first: Row) {
        let mut stack = vec![first];
        let mut fitting: Vec<u32> = Vec::with_capacity(self.widths.len());
        while let Some(row) = stack.last_mut() {
            let (x, y0, x1, y1) = (row.x, row.y0, row.x1, row.y1);
            fitting.clear();
            for (kind, &w) in self.widths.iter().enumerate() {
                if self.fits(x, y0, u64::from(w), x1, y1) {
                    fitting.push(kind as u32);
                }
            }
            if fitting.is_empty() {
                stack.pop();
                continue;
            }
            let kind = fitting[self.rng.random_range(0..fitting.len() as u32) as usize];
            let w = u64::from(self.widths[kind as usize]);
            self.put(LocalSquare {
                x,
                y: y0,
                width: w,
                kind,
            });
            row.x = x + w + self.gap;
            let below = y0 + w + self.gap;
            if below < y1 {
                stack.push(Row {
                    x,
                    y0: below,
                    x1: x + w,
                    y1,
                });
            }
        }
    }

    /// Whether a square of side `w` at `(x, y)` fits inside `[.., x1) × [.., y1)`, on block
    /// pixels, clear of every placed building by `gap`.
    fn fits(&self, x: u64, y: u64, w: u64, x1: u64, y1: u64) -> bool {
        if w == 0 || x + w > x1 || y + w > y1 || !self.mask.holds_square(x, y, w) {
            return false;
        }
        let stride = self.mask.width();
        (y..y + w).all(|yy| {
            let row = (yy * stride) as usize;
            !self.blocked[row + x as usize..row + (x + w) as usize].contains(&true)
        })
    }

    fn put(&mut self, square: LocalSquare) {
        let stride = self.mask.width();
        let x0 = square.x.saturating_sub(self.gap);
        let y0 = square.y.saturating_sub(self.gap);
        let x1 = (square.x + square.width + self.gap).min(stride);
        let y1 = (square.y + square.width + self.gap).min(self.mask.height());
        for yy in y0..y1 {
            let row = (yy * stride) as usize;
            self.blocked[row + x0 as usize..row + x1 as usize].fill(true);
        }
        self.placed.push(square);
    }
}
