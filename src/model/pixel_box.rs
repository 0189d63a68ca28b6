//! Image pixels, one at a time → [`PixelBox`]: their tight inclusive box, and COCO's
//! `[x, y, w, h]` of it.

/// The tight box of some pixels, inclusive: columns `x0..=x1`, rows `y0..=y1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelBox {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

impl PixelBox {
    /// The box of the one pixel `(x, y)`.
    pub fn at(x: u32, y: u32) -> PixelBox {
        PixelBox {
            x0: x,
            y0: y,
            x1: x,
            y1: y,
        }
    }

    /// Grows the box to hold pixel `(x, y)`.
    pub fn include(&mut self, x: u32, y: u32) {
        self.x0 = self.x0.min(x);
        self.y0 = self.y0.min(y);
        self.x1 = self.x1.max(x);
        self.y1 = self.y1.max(y);
    }

    /// COCO `[x, y, w, h]` (pixel edges, so `w = x1 − x0 + 1`).
    pub fn bbox(&self) -> [u32; 4] {
        [
            self.x0,
            self.y0,
            self.x1 - self.x0 + 1,
            self.y1 - self.y0 + 1,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grows_to_hold_every_pixel() {
        let mut b = PixelBox::at(5, 2);
        assert_eq!(b.bbox(), [5, 2, 1, 1]);
        for (x, y) in [(3, 4), (7, 1), (6, 3)] {
            b.include(x, y);
        }
        assert_eq!(
            b,
            PixelBox {
                x0: 3,
                y0: 1,
                x1: 7,
                y1: 4
            }
        );
        assert_eq!(b.bbox(), [3, 1, 5, 4]);
    }
}
