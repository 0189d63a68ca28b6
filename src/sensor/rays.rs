//! Camera pose + intrinsics → per-pixel view rays and projections, in f32 for the
//! image-space passes.

use crate::model::CameraPose;
use crate::model::geometry::dot;

/// A frame's camera: eye, axes and pinhole intrinsics.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Rays {
    pub eye: [f32; 3],
    pub right: [f32; 3],
    pub up: [f32; 3],
    pub forward: [f32; 3],
    pub fx: f32,
    pub fy: f32,
    pub cx: f32,
    pub cy: f32,
}

impl Rays {
    /// `None` for a pose without a view direction.
    pub fn new(pose: &CameraPose, intrinsics: [f64; 4]) -> Option<Rays> {
        let basis = pose.basis()?;
        let f = |v: [f64; 3]| v.map(|x| x as f32);
        Some(Rays {
            eye: f(pose.eye),
            right: f(basis.right),
            up: f(basis.up),
            forward: f(basis.forward),
            fx: intrinsics[0] as f32,
            fy: intrinsics[1] as f32,
            cx: intrinsics[2] as f32,
            cy: intrinsics[3] as f32,
        })
    }

    /// World direction through the centre of pixel (x, y), scaled so its component along
    /// the view axis is 1: the point at depth `d` is `eye + d · dir`.
    #[inline]
    pub fn dir(&self, x: usize, y: usize) -> [f32; 3] {
        let a = (x as f32 + 0.5 - self.cx) / self.fx;
        let b = -(y as f32 + 0.5 - self.cy) / self.fy;
        [0, 1, 2].map(|k| self.forward[k] + a * self.right[k] + b * self.up[k])
    }

    /// Image position of world point `p` seen from `eye`, if in front of the camera.
    #[inline]
    pub fn project_from(&self, eye: [f32; 3], p: [f32; 3]) -> Option<[f32; 2]> {
        let d = [p[0] - eye[0], p[1] - eye[1], p[2] - eye[2]];
        let z = dot(self.forward, d);
        if z <= 0.05 {
            return None;
        }
        Some([
            self.cx + self.fx * dot(self.right, d) / z,
            self.cy - self.fy * dot(self.up, d) / z,
        ])
    }
}

#[inline]
pub(crate) fn length(a: [f32; 3]) -> f32 {
    dot(a, a).sqrt()
}
