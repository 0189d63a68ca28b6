//! Camera pose (eye, target) → an orthonormal look-at basis (right, up, forward): what the
//! renderer projects with and the annotator projects text corners with, so it lives with
//! the pose in `model`, not in either stage.

use super::CameraPose;
use super::geometry::{cross, normalize, sub};

/// The camera's axes in world coordinates, right-handed: `right = forward × up`,
/// `up = right × forward`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraBasis {
    pub right: [f64; 3],
    pub up: [f64; 3],
    pub forward: [f64; 3],
}

impl CameraPose {
    /// The look-at basis with the pose's `up` (world +y for a level camera; a rolled
    /// camera's is turned about the view direction). A camera looking along its up, e.g.
    /// a level camera straight up or down, uses −z (north) as its up instead, so the top
    /// of the image is north. `None` when eye and target coincide or are not finite.
    pub fn basis(&self) -> Option<CameraBasis> {
        let forward = normalize(sub(self.target, self.eye))?;
        let right = normalize(cross(forward, self.up))
            .or_else(|| normalize(cross(forward, [0.0, 0.0, -1.0])))?;
        let up = cross(right, forward);
        Some(CameraBasis { right, up, forward })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn looking_north_has_east_on_the_right() {
        let pose = CameraPose::level([0.0, 2.0, 0.0], [0.0, 2.0, -5.0]);
        let b = pose.basis().unwrap();
        assert_eq!(b.forward, [0.0, 0.0, -1.0]);
        assert_eq!(b.right, [1.0, 0.0, 0.0]);
        assert_eq!(b.up, [0.0, 1.0, 0.0]);
    }

    #[test]
    fn looking_down_uses_north_as_up_and_degenerate_poses_have_no_basis() {
        let down = CameraPose::level([0.0, 100.0, 0.0], [0.0, 0.0, 0.0]);
        let b = down.basis().unwrap();
        assert_eq!(b.forward, [0.0, -1.0, 0.0]);
        assert_eq!(b.up, [0.0, 0.0, -1.0]);
        assert_eq!(b.right, [1.0, 0.0, 0.0]);
        let nowhere = CameraPose::level([1.0, 1.0, 1.0], [1.0, 1.0, 1.0]);
        assert!(nowhere.basis().is_none());
        let nan = CameraPose::level([f64::NAN, 0.0, 0.0], [0.0; 3]);
        assert!(nan.basis().is_none());
    }

    #[test]
    fn a_rolled_up_turns_the_basis_about_the_view_direction() {
        // Looking north, up tilted towards east: the camera is rolled clockwise by 90°.
        let pose = CameraPose {
            up: [1.0, 0.0, 0.0],
            ..CameraPose::level([0.0, 2.0, 0.0], [0.0, 2.0, -5.0])
        };
        let b = pose.basis().unwrap();
        assert_eq!(b.forward, [0.0, 0.0, -1.0]);
        assert_eq!(b.up, [1.0, 0.0, 0.0]);
        assert_eq!(b.right, [0.0, -1.0, 0.0]);
    }
}
