//! Pinhole intrinsics: focal lengths and principal point in pixels, image size, clip range.

use serde::{Deserialize, Serialize};

/// Pixel intrinsics (COCO image entries carry them): focal lengths and principal point
/// in pixels, image size, clip distances in metres.
///
/// Pixel `(i, j)` covers `[i, i + 1) × [j, j + 1)`; its centre is at `(i + 0.5, j + 0.5)`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Intrinsics {
    pub width: u32,
    pub height: u32,
    pub fx: f64,
    pub fy: f64,
    pub cx: f64,
    pub cy: f64,
    pub near: f64,
    pub far: f64,
}

/// Near clip distance of [`Intrinsics::from_fov`], metres.
pub const DEFAULT_NEAR: f64 = 0.1;
/// Far clip distance of [`Intrinsics::from_fov`], metres (a 4 × 4 mirrored city's diagonal
/// is about 4.3 km).
pub const DEFAULT_FAR: f64 = 5000.0;

impl Intrinsics {
    /// Square pixels, principal point at the image centre, vertical field of view given by
    /// the tangent of its half angle (the caller supplies the tangent, so no trigonometry
    /// happens here), near 0.1 m, far 5 km.
    pub fn from_fov(width: u32, height: u32, tan_half_fov_y: f64) -> Self {
        let fy = f64::from(height) / 2.0 / tan_half_fov_y;
        Intrinsics {
            width,
            height,
            fx: fy,
            fy,
            cx: f64::from(width) / 2.0,
            cy: f64::from(height) / 2.0,
            near: DEFAULT_NEAR,
            far: DEFAULT_FAR,
        }
    }

    /// Whether these intrinsics can render anything.
    pub(crate) fn is_usable(&self) -> bool {
        let finite = [self.fx, self.fy, self.cx, self.cy, self.near, self.far]
            .iter()
            .all(|v| v.is_finite());
        finite && self.fx > 0.0 && self.fy > 0.0 && self.near > 0.0 && self.far > self.near
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_fov_centres_the_principal_point() {
        // tan(45°) = 1: a 90° vertical field of view.
        let k = Intrinsics::from_fov(640, 480, 1.0);
        assert_eq!((k.fx, k.fy, k.cx, k.cy), (240.0, 240.0, 320.0, 240.0));
        assert!(k.is_usable());
        assert!(!Intrinsics::from_fov(640, 480, 0.0).is_usable());
        assert!(!Intrinsics { near: 0.0, ..k }.is_usable());
    }
}
