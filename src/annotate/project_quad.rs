//! A word's four world corners + camera pose and intrinsics → its quad in the image, for
//! ICDAR lines.

use crate::model::CameraPose;

/// The image positions of four world points, if all are in front of the camera (at least
/// `near` metres along the view direction): `x = cx + fx·(right·d)/(forward·d)`,
/// `y = cy − fy·(up·d)/(forward·d)`. `intrinsics` is `[fx, fy, cx, cy]`.
pub fn project_quad(
    pose: &CameraPose,
    intrinsics: [f64; 4],
    near: f64,
    corners: &[[f64; 3]; 4],
) -> Option<[[f64; 2]; 4]> {
    let [fx, fy, cx, cy] = intrinsics;
    let basis = pose.basis()?;
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let mut out = [[0.0; 2]; 4];
    for (slot, c) in out.iter_mut().zip(corners) {
        let d = [c[0] - pose.eye[0], c[1] - pose.eye[1], c[2] - pose.eye[2]];
        let z = dot(basis.forward, d);
        if z < near {
            return None;
        }
        *slot = [
            cx + fx * dot(basis.right, d) / z,
            cy - fy * dot(basis.up, d) / z,
        ];
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quad_ahead_projects_and_one_behind_does_not() {
        let pose = CameraPose::level([0.0, 0.0, 0.0], [0.0, 0.0, -10.0]);
        let ahead = [
            [-1.0, 1.0, -10.0],
            [1.0, 1.0, -10.0],
            [1.0, -1.0, -10.0],
            [-1.0, -1.0, -10.0],
        ];
        let quad = project_quad(&pose, [100.0, 100.0, 50.0, 40.0], 0.1, &ahead).unwrap();
        assert_eq!(quad[0], [40.0, 30.0]);
        assert_eq!(quad[2], [60.0, 50.0]);
        let behind = ahead.map(|[x, y, z]| [x, y, -z]);
        assert_eq!(
            project_quad(&pose, [100.0, 100.0, 50.0, 40.0], 0.1, &behind),
            None
        );
    }
}
