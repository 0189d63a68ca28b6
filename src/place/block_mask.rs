//! Block → `BlockMask`: the block's pixels in bbox-local coordinates, with a summed-area
//! table so "is this square all block pixels?" costs O(1).

use crate::model::Block;

/// A block's pixel mask over its bounding box, plus its summed-area table.
///
/// Coordinates are local: `(0, 0)` is the bbox's top-left pixel. Band spans that stick out
/// of the bbox are clipped, so a malformed block gives a smaller mask, never a panic.
#[derive(Clone, Debug)]
pub(crate) struct BlockMask {
    width: u64,
    height: u64,
    /// `sat[y * (width + 1) + x]` = number of block pixels in `[0, x) × [0, y)`.
    sat: Vec<u64>,
}

impl BlockMask {
    pub(crate) fn new(block: &Block) -> BlockMask {
        let b = block.bbox;
        let width = u64::from(b.x1.saturating_sub(b.x0));
        let height = u64::from(b.y1.saturating_sub(b.y0));
        let mut inside = vec![false; (width * height) as usize];
        for band in &block.bands {
            let y0 = band.y0.max(b.y0);
            let y1 = band.y1.min(b.y1);
            for y in y0..y1 {
                let row = u64::from(y - b.y0) * width;
                for span in &band.spans {
                    let x0 = span[0].max(b.x0);
                    let x1 = span[1].min(b.x1);
                    for x in x0..x1 {
                        inside[(row + u64::from(x - b.x0)) as usize] = true;
                    }
                }
            }
        }
        let stride = width + 1;
        let mut sat = vec![0u64; (stride * (height + 1)) as usize];
        for y in 0..height {
            let mut row_sum = 0;
            for x in 0..width {
                row_sum += u64::from(inside[(y * width + x) as usize]);
                sat[((y + 1) * stride + x + 1) as usize] =
                    sat[(y * stride + x + 1) as usize] + row_sum;
            }
        }
        BlockMask { width, height, sat }
    }

    pub(crate) fn width(&self) -> u64 {
        self.width
    }

    pub(crate) fn height(&self) -> u64 {
        self.height
    }

    /// Number of block pixels in the local rectangle `[x0, x1) × [y0, y1)` (clipped).
    pub(crate) fn count(&self, x0: u64, y0: u64, x1: u64, y1: u64) -> u64 {
        let (x1, y1) = (x1.min(self.width), y1.min(self.height));
        if x0 >= x1 || y0 >= y1 {
            return 0;
        }
        let s = self.width + 1;
        let at = |x: u64, y: u64| self.sat[(y * s + x) as usize];
        at(x1, y1) + at(x0, y0) - at(x0, y1) - at(x1, y0)
    }

    /// Whether the local square with top-left `(x, y)` and side `w` is all block pixels.
    pub(crate) fn holds_square(&self, x: u64, y: u64, w: u64) -> bool {
        w > 0
            && x + w <= self.width
            && y + w <= self.height
            && self.count(x, y, x + w, y + w) == w * w
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Band, PxRect};

    /// An L: a 10×4 bar on top of a 4×6 leg, at offset (5, 7).
    fn l_block() -> Block {
        Block {
            id: 0,
            bbox: PxRect {
                x0: 5,
                y0: 7,
                x1: 15,
                y1: 17,
            },
            area: 40 + 24,
            outline: vec![],
            bands: vec![
                Band {
                    y0: 7,
                    y1: 11,
                    spans: vec![[5, 15]],
                },
                Band {
                    y0: 11,
                    y1: 17,
                    spans: vec![[5, 9]],
                },
            ],
        }
    }

    #[test]
    fn counts_match_the_bands() {
        let block = l_block();
        let mask = BlockMask::new(&block);
        assert_eq!((mask.width(), mask.height()), (10, 10));
        assert_eq!(mask.count(0, 0, 10, 10), block.area);
        for y in 0..10u64 {
            for x in 0..10u64 {
                let want = block.contains_pixel(x as u32 + 5, y as u32 + 7);
                assert_eq!(
                    mask.count(x, y, x + 1, y + 1) == 1,
                    want,
                    "pixel ({x}, {y})"
                );
            }
        }
    }

    #[test]
    fn squares_on_and_off_the_block() {
        let mask = BlockMask::new(&l_block());
        let cases = [
            // (x, y, w, holds)
            (0, 0, 4, true),
            (6, 0, 4, true),
            (0, 6, 4, true),
            (0, 0, 5, false), // reaches into the notch
            (7, 0, 4, false), // leaves the bbox
            (4, 4, 1, false), // the notch itself
            (0, 0, 0, false), // empty squares never fit
        ];
        for (x, y, w, holds) in cases {
            assert_eq!(mask.holds_square(x, y, w), holds, "square ({x}, {y}, {w})");
        }
    }
}
