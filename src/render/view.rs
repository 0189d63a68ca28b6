//! Pose + intrinsics + supersampling → the per-frame view: world → camera → pixel.
//!
//! All of it works at the internal (supersampled) resolution: `s` samples per pixel side
//! scale the focal lengths and the principal point by `s`.

use super::{CameraPose, Intrinsics};
use crate::model::CameraBasis;
use crate::model::geometry::{dot, sub};

/// Pixels beyond each image edge that projected vertices may reach before triangles are
/// clipped (keeps fixed-point edge functions far from overflow).
pub(crate) const GUARD: f64 = 4096.0;

/// One frame's camera at the internal resolution.
pub(crate) struct View {
    pub eye: [f64; 3],
    pub basis: CameraBasis,
    pub fx: f64,
    pub fy: f64,
    pub cx: f64,
    pub cy: f64,
    pub width: u32,
    pub height: u32,
    pub near: f64,
    pub far: f64,
    /// Clip planes `[a, b, c]` on camera coordinates: inside when `a·x + b·y + c·w ≥ 0`.
    pub guard_planes: [[f64; 3]; 4],
    pub viewport_planes: [[f64; 3]; 4],
}

impl View {
    pub(crate) fn new(pose: &CameraPose, k: &Intrinsics, samples: u32) -> Option<View> {
        if !k.is_usable() {
            return None;
        }
        let basis = pose.basis()?;
        let s = f64::from(samples);
        let (fx, fy, cx, cy) = (k.fx * s, k.fy * s, k.cx * s, k.cy * s);
        let (width, height) = (k.width * samples, k.height * samples);
        let planes = |g: f64| {
            let (w, h) = (f64::from(width), f64::from(height));
            [
                [fx, 0.0, cx + g],      // x ≥ −g
                [-fx, 0.0, w + g - cx], // x ≤ width + g
                [0.0, -fy, cy + g],     // y ≥ −g
                [0.0, fy, h + g - cy],  // y ≤ height + g
            ]
        };
        Some(View {
            eye: pose.eye,
            basis,
            fx,
            fy,
            cx,
            cy,
            width,
            height,
            near: k.near,
            far: k.far,
            guard_planes: planes(GUARD),
            viewport_planes: planes(0.0),
        })
    }

    /// Camera coordinates `[right·d, up·d, forward·d]` of world point `p`, `d = p − eye`.
    #[inline]
    pub(crate) fn to_camera(&self, p: [f64; 3]) -> [f64; 3] {
        let d = sub(p, self.eye);
        [
            dot(self.basis.right, d),
            dot(self.basis.up, d),
            dot(self.basis.forward, d),
        ]
    }

    /// Pixel coordinates of a camera-space point in front of the camera.
    #[inline]
    pub(crate) fn project(&self, c: [f64; 3]) -> [f64; 2] {
        [
            self.cx + self.fx * c[0] / c[2],
            self.cy - self.fy * c[1] / c[2],
        ]
    }

    /// World point seen at internal pixel position `(x, y)` at depth `depth`.
    #[inline]
    pub(crate) fn unproject(&self, x: f64, y: f64, depth: f64) -> [f64; 3] {
        let a = (x - self.cx) / self.fx;
        let b = (y - self.cy) / self.fy;
        let (r, u, f) = (self.basis.right, self.basis.up, self.basis.forward);
        [
            self.eye[0] + depth * (f[0] + a * r[0] - b * u[0]),
            self.eye[1] + depth * (f[1] + a * r[1] - b * u[1]),
            self.eye[2] + depth * (f[2] + a * r[2] - b * u[2]),
        ]
    }

    /// Camera coordinates of the eight corners of the axis-aligned world box `min`–`max`.
    pub(crate) fn box_corners(&self, min: [f64; 3], max: [f64; 3]) -> [[f64; 3]; 8] {
        std::array::from_fn(|i| {
            self.to_camera([
                if i & 1 == 0 { min[0] } else { max[0] },
                if i & 2 == 0 { min[1] } else { max[1] },
                if i & 4 == 0 { min[2] } else { max[2] },
            ])
        })
    }

    /// Whether an axis-aligned world box may be visible (false only when it is surely not).
    pub(crate) fn may_see_box(&self, min: [f64; 3], max: [f64; 3]) -> bool {
        if min[0].is_nan() || min[0] > max[0] {
            return false;
        }
        let corners = self.box_corners(min, max);
        if corners.iter().all(|c| c[2] < self.near) || corners.iter().all(|c| c[2] > self.far) {
            return false;
        }
        !self
            .viewport_planes
            .iter()
            .any(|p| corners.iter().all(|c| plane(p, c) < 0.0))
    }
}

impl View {
    /// Whether an axis-aligned world box lies wholly in front of the near plane and
    /// projects inside the image (false when unsure).
    pub(crate) fn holds_box(&self, min: [f64; 3], max: [f64; 3]) -> bool {
        if !(min.iter().chain(&max).all(|v| v.is_finite()) && min[0] <= max[0]) {
            return false;
        }
        self.box_corners(min, max).iter().all(|c| {
            if c[2] < self.near {
                return false;
            }
            let [x, y] = self.project(*c);
            // A pixel of margin: the fill rule and snapping act within a pixel.
            x >= 1.0
                && y >= 1.0
                && x <= f64::from(self.width) - 1.0
                && y <= f64::from(self.height) - 1.0
        })
    }
}

/// Signed distance-like value of camera point `c` to a clip plane.
#[inline]
pub(crate) fn plane(p: &[f64; 3], c: &[f64; 3]) -> f64 {
    p[0] * c[0] + p[1] * c[1] + p[2] * c[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn view() -> View {
        let pose = CameraPose::level([0.0, 0.0, 0.0], [0.0, 0.0, -1.0]);
        View::new(&pose, &Intrinsics::from_fov(64, 48, 1.0), 1).unwrap()
    }

    #[test]
    fn project_and_unproject_are_inverse() {
        let v = view();
        let c = v.to_camera([1.0, 2.0, -4.0]);
        assert_eq!(c, [1.0, 2.0, 4.0]);
        let [x, y] = v.project(c);
        assert_eq!([x, y], [32.0 + 6.0, 24.0 - 12.0]);
        assert_eq!(v.unproject(x, y, 4.0), [1.0, 2.0, -4.0]);
    }

    #[test]
    fn only_boxes_projecting_wholly_inside_are_held() {
        let v = view();
        let cases = [
            ([-1.0, -1.0, -5.0], [1.0, 1.0, -4.0], true),
            // Reaches past the right edge: x = 32 + 24 · 9 / 4 = 86 > 64 at depth 4.
            ([-1.0, -1.0, -5.0], [9.0, 1.0, -4.0], false),
            // Behind the camera, or straddling the near plane.
            ([-1.0, -1.0, 4.0], [1.0, 1.0, 5.0], false),
            ([-1.0, -1.0, -5.0], [1.0, 1.0, 0.0], false),
            ([1.0, 1.0, 1.0], [-1.0, -1.0, -1.0], false),
            ([f64::NAN, 0.0, -5.0], [1.0, 1.0, -4.0], false),
        ];
        for (min, max, held) in cases {
            assert_eq!(v.holds_box(min, max), held, "{min:?} {max:?}");
        }
    }

    #[test]
    fn boxes_behind_or_beside_are_culled() {
        let v = view();
        let cases = [
            ([-1.0, -1.0, -5.0], [1.0, 1.0, -4.0], true),
            ([-1.0, -1.0, 4.0], [1.0, 1.0, 5.0], false),
            ([100.0, -1.0, -5.0], [101.0, 1.0, -4.0], false),
            ([-100.0, -1.0, -100.0], [100.0, 1.0, 100.0], true),
            ([1.0, 1.0, 1.0], [-1.0, -1.0, -1.0], false),
        ];
        for (min, max, visible) in cases {
            assert_eq!(v.may_see_box(min, max), visible, "{min:?} {max:?}");
        }
    }
}
