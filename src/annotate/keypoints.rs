//! A person's 17 world keypoints + the frame's pose, intrinsics and depth image → COCO
//! `keypoints` (`[x, y, v]` × 17) with a visibility flag each from the depth test.
//!
//! `x, y` are continuous pixel coordinates, the same as `bbox` and the segmentation:
//! pixel `(i, j)` covers `[i, i + 1) × [j, j + 1)`, its centre at `(i + 0.5, j + 0.5)`.
//! (COCO's own keypoints were clicked on pixel indices, centres at integers: subtract 0.5
//! to match that.) `v` is
//!
//! - 0 when the keypoint lies outside the image or nearer than [`NEAR`] (behind the
//!   camera included): written `[0, 0, 0]`, as COCO writes unlabelled keypoints;
//! - 2 (visible) when the depth image at its pixel is no nearer than the keypoint's own
//!   depth less its [`SURFACE_DEPTH`] (a joint lies inside its limb, up to that deep under
//!   the surface the renderer draws), or shows the sky;
//! - 1 (labelled, not visible) otherwise: something, the figure itself included, is in
//!   front of it.

use image::{ImageBuffer, Luma};

use crate::model::CameraPose;

/// COCO's keypoint names, in COCO's order (the `person` category's `keypoints`).
pub const KEYPOINT_NAMES: [&str; 17] = [
    "nose",
    "left_eye",
    "right_eye",
    "left_ear",
    "right_ear",
    "left_shoulder",
    "right_shoulder",
    "left_elbow",
    "right_elbow",
    "left_wrist",
    "right_wrist",
    "left_hip",
    "right_hip",
    "left_knee",
    "right_knee",
    "left_ankle",
    "right_ankle",
];

/// COCO's 19 limbs, pairs of 1-based keypoint numbers (the category's `skeleton`).
pub const SKELETON: [[u8; 2]; 19] = [
    [16, 14],
    [14, 12],
    [17, 15],
    [15, 13],
    [12, 13],
    [6, 12],
    [7, 13],
    [6, 7],
    [6, 8],
    [7, 9],
    [8, 10],
    [9, 11],
    [2, 3],
    [1, 2],
    [1, 3],
    [2, 4],
    [3, 5],
    [4, 6],
    [5, 7],
];

/// Per keypoint, how far behind the surface the renderer drew at its pixel it may lie and
/// still count as visible, metres. A body joint: 0.15, about a body's half depth (a
/// torso is 0.2 m deep, a limb 0.13 m), so a joint inside a limb seen is visible, and one
/// behind the body (the far shoulder or hip seen from the side) is not. The nose and eyes
/// lie just under the face, 0.08: seen from behind they are hidden by the head (0.14 m
/// and more), the nose in profile is not (0.07 m under the head's side). The ears lie on
/// the head's sides, 0.1: seen from the front or back they show, from the side the far
/// one does not (0.12 m and more behind the near side).
pub const SURFACE_DEPTH: [f64; 17] = [
    0.08, 0.08, 0.08, 0.1, 0.1, 0.15, 0.15, 0.15, 0.15, 0.15, 0.15, 0.15, 0.15, 0.15, 0.15, 0.15,
    0.15,
];

/// Nearest a keypoint may lie along the view axis and be in the image, metres: the
/// renderer's near plane.
pub const NEAR: f64 = 0.1;

/// One projected keypoint: `[x, y, v]` (`v` 0, 1 or 2; `[0, 0, 0]` when `v` is 0).
pub type Keypoint = [f64; 3];

/// The 17 `world` keypoints seen from `pose` with `intrinsics` `[fx, fy, cx, cy]` in an
/// image whose depth (metres along the view axis, 0 the sky) is `depth`.
pub fn project_keypoints(
    world: &[[f64; 3]; 17],
    pose: &CameraPose,
    intrinsics: [f64; 4],
    depth: &ImageBuffer<Luma<f32>, Vec<f32>>,
) -> [Keypoint; 17] {
    let Some(basis) = pose.basis() else {
        return [[0.0; 3]; 17];
    };
    let [fx, fy, cx, cy] = intrinsics;
    let (width, height) = depth.dimensions();
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    std::array::from_fn(|i| {
        let p = world[i];
        let d = [p[0] - pose.eye[0], p[1] - pose.eye[1], p[2] - pose.eye[2]];
        let z = dot(basis.forward, d);
        if z.is_nan() || z < NEAR {
            return [0.0; 3];
        }
        let x = cx + fx * dot(basis.right, d) / z;
        let y = cy - fy * dot(basis.up, d) / z;
        let inside = (0.0..f64::from(width)).contains(&x) && (0.0..f64::from(height)).contains(&y);
        if !inside {
            return [0.0; 3];
        }
        let seen = f64::from(depth.get_pixel(x as u32, y as u32).0[0]);
        let visible = seen <= 0.0 || seen >= z - SURFACE_DEPTH[i];
        [x, y, if visible { 2.0 } else { 1.0 }]
    })
}

/// How many of `keypoints` are labelled (`v` > 0): COCO's `num_keypoints`.
pub fn labelled(keypoints: &[Keypoint; 17]) -> usize {
    keypoints.iter().filter(|k| k[2] > 0.0).count()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 100 × 80 image, `fx = fy = 100`, centre `(50, 40)`, looking down −z from the
    /// origin; depth `wall` everywhere but the sky (0) in its top-left quarter.
    fn scene(wall: f32) -> (CameraPose, [f64; 4], ImageBuffer<Luma<f32>, Vec<f32>>) {
        let pose = CameraPose::level([0.0, 0.0, 0.0], [0.0, 0.0, -10.0]);
        let depth = ImageBuffer::from_fn(100, 80, |x, y| {
            Luma([if x < 50 && y < 40 { 0.0 } else { wall }])
        });
        (pose, [100.0, 100.0, 50.0, 40.0], depth)
    }

    #[test]
    fn keypoints_project_with_pixel_centres_at_halves_and_flag_what_hides_them() {
        let (pose, k, depth) = scene(5.0);
        let mut world = [[0.0, 0.0, -5.05]; 17];
        // (0.2, 0.1) at 5 m: 4 px right, 2 px up of the centre.
        world[1] = [0.2, 0.1, -5.0];
        // Just inside the body's depth and just beyond it, for an eye, an ear and a hip:
        // the surface at 5 m is in front.
        world[2] = [0.5, -0.5, -5.0 - SURFACE_DEPTH[2] + 0.01];
        world[3] = [0.5, -0.5, -5.0 - SURFACE_DEPTH[3] - 0.01];
        world[11] = [0.5, -0.5, -5.0 - SURFACE_DEPTH[11] + 0.01];
        world[12] = [0.5, -0.5, -5.0 - SURFACE_DEPTH[11] - 0.01];
        // Behind the camera, beside the image, under it.
        world[4] = [0.0, 0.0, 1.0];
        world[5] = [-3.0, 0.0, -5.0];
        world[6] = [0.0, -2.5, -5.0];
        // Against the sky, far away: nothing in front.
        world[7] = [-10.0, 5.0, -50.0];
        // Right at the near plane's edge.
        world[8] = [0.0, 0.0, -(NEAR - 1e-6)];
        let out = project_keypoints(&world, &pose, k, &depth);
        assert_eq!(out[0], [50.0, 40.0, 2.0]);
        let [x, y, v] = out[1];
        assert!((x - 54.0).abs() < 1e-9 && (y - 38.0).abs() < 1e-9 && v == 2.0);
        assert_eq!(
            [out[2][2], out[3][2], out[11][2], out[12][2]],
            [2.0, 1.0, 2.0, 1.0]
        );
        for i in [4, 5, 6, 8] {
            assert_eq!(out[i], [0.0; 3], "{i}");
        }
        assert_eq!(out[7], [30.0, 30.0, 2.0]);
        assert_eq!(labelled(&out), 17 - 4);
    }

    #[test]
    fn an_occluder_well_in_front_hides_a_keypoint_and_the_image_edge_is_half_open() {
        let (pose, k, depth) = scene(2.0);
        let mut world = [[0.0, 0.0, -5.0]; 17];
        // x = 50 + 100 · 0.5 / 1 = 100: the right edge, outside; a hair left of it, inside.
        world[1] = [0.5, -0.1, -1.0];
        world[2] = [0.4999, -0.1, -1.0];
        let out = project_keypoints(&world, &pose, k, &depth);
        assert_eq!(out[0][2], 1.0, "the wall at 2 m hides a point at 5 m");
        assert_eq!(out[1], [0.0; 3]);
        assert_eq!(out[2][2], 2.0);
        assert!(out[2][0] < 100.0);
    }
}
