//! Image pixels, one at a time → [`PixelBox`]: their tight inclusive box, and COCO's
//! `[x, y, w, h]` of it.

/// The tight box of some pixels, inclusive: columns `x_min..=x_max`, rows `y_min..=y_max`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelBox {
    pub x_min: u32,
    pub y_min: u32,
    pub x_max: u32,
    pub y_max: u32,
}

impl PixelBox {
    /// The box of the one pixel `(x, y)`.
    pub fn at(x: u32, y: u32) -> PixelBox {
        PixelBox {
            x_min: x,
            y_min: y,
            x_max: x,
            y_max: y,
        }
    }

    /// Grows the box to hold pixel `(x, y)`.
    pub fn include(&mut self, x: u32, y: u32) {
        self.x_min = self.x_min.min(x);
        self.y_min = self.y_min.min(y);
        self.x_max = self.x_max.max(x);
        self.y_max = self.y_max.max(y);
    }

    /// COCO `[x, y, w, h]` (pixel edges, so `w = x_max − x_min + 1`).
    pub fn bbox(&self) -> [u32; 4] {
        [
            self.x_min,
            self.y_min,
            self.x_max - self.x_min + 1,
            self.y_max - self.y_min + 1,
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
                x_min: 3,
                y_min: 1,
                x_max: 7,
                y_max: 4
            }
        );
        assert_eq!(b.bbox(), [3, 1, 5, 4]);
    }
}
