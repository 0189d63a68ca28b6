//! A labelled object's mesh vertices → its oriented 3D box ([`Box3d`]: centre, size,
//! yaw about the vertical), and that box seen from a frame's camera.
//!
//! The box stands upright (world +y up) and is the smallest-area rectangle around the
//! vertices' ground-plane hull (rotating calipers over the hull's edges), from the lowest
//! to the highest vertex: it holds every vertex, so its projection holds every pixel the
//! object covers. `size` is `[length, width, height]` with the length the longer side;
//! the mesh does not say which end is the front, so `yaw` is the length axis' direction
//! taken in `(−90°, 90°]`.

use serde::{Deserialize, Serialize};

use crate::model::CameraPose;
use crate::model::geometry::dot;

/// An upright oriented box in world metres.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Box3d {
    /// Centre (of the volume).
    pub centre: [f64; 3],
    /// `[length, width, height]`, length ≥ width.
    pub size: [f64; 3],
    /// The length axis is `(cos yaw, 0, −sin yaw)` (radians, anticlockwise seen from
    /// above about +y), `yaw` in `(−π/2, π/2]`.
    pub yaw: f64,
}

impl Box3d {
    /// The box around `points`, or `None` for none (or a non-finite one).
    pub fn around(points: impl IntoIterator<Item = [f64; 3]>) -> Option<Box3d> {
        let mut ground = Vec::new();
        let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in points {
            if !p.iter().all(|v| v.is_finite()) {
                return None;
            }
            (low, high) = (low.min(p[1]), high.max(p[1]));
            ground.push([p[0], p[2]]);
        }
        let hull = hull(ground);
        let first = *hull.first()?;
        // Each hull edge's direction, and the axis-aligned one (a single point or segment).
        let mut best: Option<(f64, [f64; 2], [f64; 4])> = None;
        let edges = hull.iter().zip(hull.iter().cycle().skip(1));
        let directions = edges
            .filter_map(|(a, b)| unit([b[0] - a[0], b[1] - a[1]]))
            .chain(std::iter::once([1.0, 0.0]));
        for u in directions {
            let v = [-u[1], u[0]];
            let mut r = [
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            ];
            for p in &hull {
                let (a, b) = (p[0] * u[0] + p[1] * u[1], p[0] * v[0] + p[1] * v[1]);
                r = [r[0].min(a), r[1].max(a), r[2].min(b), r[3].max(b)];
            }
            let area = (r[1] - r[0]) * (r[3] - r[2]);
            if best.is_none_or(|(a, _, _)| area < a) {
                best = Some((area, u, r));
            }
        }
        let (_, u, r) = best.unwrap_or((0.0, [1.0, 0.0], [first[0], first[0], first[1], first[1]]));
        let v = [-u[1], u[0]];
        let (mid_u, mid_v) = ((r[0] + r[1]) / 2.0, (r[2] + r[3]) / 2.0);
        let centre = [
            u[0] * mid_u + v[0] * mid_v,
            (low + high) / 2.0,
            u[1] * mid_u + v[1] * mid_v,
        ];
        let (along_u, along_v) = (r[1] - r[0], r[3] - r[2]);
        let (length, width, axis) = if along_u >= along_v {
            (along_u, along_v, u)
        } else {
            (along_v, along_u, v)
        };
        // Axis (x, z) = (cos yaw, −sin yaw); one of ±axis gives yaw in (−90°, 90°].
        let axis = if axis[0] < 0.0 || (axis[0] == 0.0 && axis[1] > 0.0) {
            [-axis[0], -axis[1]]
        } else {
            axis
        };
        Some(Box3d {
            centre,
            size: [length, width, high - low],
            yaw: libm::atan2(-axis[1], axis[0]),
        })
    }

    /// The eight corners in world metres: the four at the bottom, then the four at the top,
    /// each going round the box.
    pub fn corners(&self) -> [[f64; 3]; 8] {
        let [l, w, h] = self.size.map(|s| s / 2.0);
        let (c, s) = (libm::cos(self.yaw), libm::sin(self.yaw));
        let (along, across) = ([c, -s], [s, c]);
        std::array::from_fn(|i| {
            let a = if matches!(i % 4, 0 | 3) { l } else { -l };
            let b = if matches!(i % 4, 0 | 1) { w } else { -w };
            [
                self.centre[0] + a * along[0] + b * across[0],
                self.centre[1] + if i < 4 { -h } else { h },
                self.centre[2] + a * along[1] + b * across[1],
            ]
        })
    }
}

/// A frame's gravity-aligned camera (KITTI's rectified camera): at the eye, y down along
/// gravity, z the view direction's heading (level), x = y × z (right). With the real
/// camera (OpenCV axes of `pose`'s basis) it gives `R0_rect`.
#[derive(Clone, Copy, Debug)]
pub struct LevelCamera {
    pub eye: [f64; 3],
    /// World directions of its x, y, z axes.
    pub axes: [[f64; 3]; 3],
    /// World directions of the real camera's OpenCV x, y, z axes.
    pub real: [[f64; 3]; 3],
}

impl LevelCamera {
    /// The level camera of `pose`, or `None` for a pose without a basis.
    pub fn of(pose: &CameraPose) -> Option<LevelCamera> {
        let b = pose.basis()?;
        // A camera looking straight down heads where its image's top looks.
        let heading = unit([b.forward[0], b.forward[2]])
            .filter(|_| b.forward[1].abs() < 0.999_999)
            .or_else(|| unit([b.up[0], b.up[2]]))?;
        let z = [heading[0], 0.0, heading[1]];
        let x = [-heading[1], 0.0, heading[0]];
        Some(LevelCamera {
            eye: pose.eye,
            axes: [x, [0.0, -1.0, 0.0], z],
            real: [b.right, b.up.map(|v| -v), b.forward],
        })
    }

    /// World point `p` in this camera's axes.
    pub fn point(&self, p: [f64; 3]) -> [f64; 3] {
        let d = [p[0] - self.eye[0], p[1] - self.eye[1], p[2] - self.eye[2]];
        self.axes.map(|a| dot(a, d))
    }

    /// `R0_rect`: real camera (OpenCV axes) → level camera, row-major.
    pub fn rectification(&self) -> [[f64; 3]; 3] {
        self.axes.map(|a| self.real.map(|r| dot(a, r)))
    }

    /// The box's KITTI pose in this camera: bottom centre `[x, y, z]` and `rotation_y`
    /// (radians in `(−π, π]`; the length axis is `(cos r, 0, −sin r)` in camera axes).
    pub fn kitti_pose(&self, b: &Box3d) -> ([f64; 3], f64) {
        let bottom = [b.centre[0], b.centre[1] - b.size[2] / 2.0, b.centre[2]];
        let axis = [libm::cos(b.yaw), 0.0, -libm::sin(b.yaw)];
        let (ax, az) = (dot(self.axes[0], axis), dot(self.axes[2], axis));
        (self.point(bottom), libm::atan2(-az, ax))
    }
}

/// `v` scaled to unit length, or `None` for a zero (or non-finite) vector.
fn unit(v: [f64; 2]) -> Option<[f64; 2]> {
    let len = (v[0] * v[0] + v[1] * v[1]).sqrt();
    (len > 1e-12 && len.is_finite()).then(|| [v[0] / len, v[1] / len])
}

/// The convex hull of `points` (Andrew's monotone chain), anticlockwise, without
/// collinear points; one point or two for degenerate input.
fn hull(mut points: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    points.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let turn = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut out: Vec<[f64; 2]> = Vec::with_capacity(points.len() * 2);
    for pass in [
        &points[..],
        &points.iter().rev().copied().collect::<Vec<_>>()[..],
    ] {
        let start = out.len();
        for &p in pass {
            while out.len() >= start + 2 && turn(out[out.len() - 2], out[out.len() - 1], p) <= 0.0 {
                out.pop();
            }
            out.push(p);
        }
        out.pop();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_turned_box_is_found_from_its_corners() {
        for yaw_deg in [0.0f64, 17.0, 60.0, 89.0, -45.0, -80.0] {
            let b = Box3d {
                centre: [3.0, 1.2, -7.0],
                size: [4.5, 1.8, 1.4],
                yaw: yaw_deg.to_radians(),
            };
            // The corners and points inside.
            let inner = b.corners().map(|c| c.map(|v| v * 0.999));
            let found = Box3d::around(b.corners().into_iter().chain(inner.map(|c| {
                [
                    c[0] + b.centre[0] * 0.001,
                    c[1] + b.centre[1] * 0.001,
                    c[2] + b.centre[2] * 0.001,
                ]
            })))
            .unwrap();
            for k in 0..3 {
                assert!(
                    (found.centre[k] - b.centre[k]).abs() < 1e-9,
                    "{yaw_deg}: {found:?}"
                );
                assert!(
                    (found.size[k] - b.size[k]).abs() < 1e-9,
                    "{yaw_deg}: {found:?}"
                );
            }
            assert!((found.yaw - b.yaw).abs() < 1e-9, "{yaw_deg}: {found:?}");
        }
        assert!(Box3d::around([]).is_none());
        let point = Box3d::around([[1.0, 2.0, 3.0]]).unwrap();
        assert_eq!((point.centre, point.size), ([1.0, 2.0, 3.0], [0.0; 3]));
    }

    #[test]
    fn the_kitti_pose_of_a_box_ahead() {
        let pose = CameraPose::level([0.0, 1.5, 0.0], [0.0, 1.5, -10.0]);
        let cam = LevelCamera::of(&pose).unwrap();
        // Level camera: R0_rect is the identity.
        let r = cam.rectification();
        for (i, row) in r.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                assert!((v - f64::from(u8::from(i == j))).abs() < 1e-12);
            }
        }
        // A car 10 m ahead, its length along world x (the camera's right).
        let b = Box3d {
            centre: [0.0, 0.7, -10.0],
            size: [4.0, 2.0, 1.4],
            yaw: 0.0,
        };
        let (at, ry) = cam.kitti_pose(&b);
        for (v, e) in at.iter().zip([0.0, 1.5, 10.0]) {
            assert!((v - e).abs() < 1e-12, "{at:?}");
        }
        assert!(ry.abs() < 1e-12);
        // Turned to run along the view (world −z): KITTI's rotation_y −90° or 90°.
        let along = Box3d {
            yaw: std::f64::consts::FRAC_PI_2,
            ..b
        };
        assert!((cam.kitti_pose(&along).1.abs() - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    }
}
