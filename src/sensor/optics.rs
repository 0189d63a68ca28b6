//! Linear radiance + depth + camera → the radiance after the lens and the moving camera:
//! motion blur, lateral chromatic aberration and vignetting.

use rayon::prelude::*;

use super::rays::Rays;

/// Bilinear sample of channel `k` at continuous position (x, y) (pixel centres at +0.5),
/// clamped to the image.
#[inline]
fn sample(img: &[[f32; 3]], w: usize, h: usize, x: f32, y: f32, k: usize) -> f32 {
    let fx = (x - 0.5).clamp(0.0, (w - 1) as f32);
    let fy = (y - 0.5).clamp(0.0, (h - 1) as f32);
    let (x0, y0) = (fx as usize, fy as usize);
    let (x1, y1) = ((x0 + 1).min(w - 1), (y0 + 1).min(h - 1));
    let (tx, ty) = (fx - x0 as f32, fy - y0 as f32);
    let top = img[y0 * w + x0][k] * (1.0 - tx) + img[y0 * w + x1][k] * tx;
    let bottom = img[y1 * w + x0][k] * (1.0 - tx) + img[y1 * w + x1][k] * tx;
    top * (1.0 - ty) + bottom * ty
}

/// Most samples along one pixel's motion, and the longest blur in pixels.
const MAX_SAMPLES: usize = 12;
const MAX_BLUR: f32 = 40.0;

/// Motion blur of a camera that moves `travel` metres along the unit direction `motion`
/// while the shutter is open (centred on the frame's pose, no rotation): each pixel
/// averages the image along the path its scene point takes on screen. Sky pixels (at
/// infinity) do not move.
pub(crate) fn motion_blur(
    linear: &mut [[f32; 3]],
    depth: &[f32],
    width: u32,
    rays: &Rays,
    motion: [f32; 3],
    travel: f32,
) {
    if travel <= 0.0 {
        return;
    }
    blur_along(
        linear,
        depth,
        width,
        rays,
        motion.map(|m| m * travel),
        |_| [0.0; 3],
    );
}

/// Motion blur of a camera whose eye moves by `eye` (world metres) while the shutter is
/// open, among objects that move too: `moved[id]` is how far object `id` (the instance
/// image `instance`'s value) moves over the same time (absent or zero: it stands still).
/// Each pixel averages the image along the path its scene point, carried by its object,
/// takes on screen.
pub(crate) fn moving_blur(
    linear: &mut [[f32; 3]],
    depth: &[f32],
    width: u32,
    rays: &Rays,
    eye: [f32; 3],
    (instance, moved): (&[u32], &[[f32; 3]]),
) {
    let still = eye.iter().all(|v| *v == 0.0);
    if (still && moved.iter().all(|m| m.iter().all(|v| *v == 0.0))) || instance.len() != depth.len()
    {
        return;
    }
    blur_along(linear, depth, width, rays, eye, |i| {
        moved.get(instance[i] as usize).copied().unwrap_or([0.0; 3])
    });
}

/// Blurs each pixel along the screen path of its scene point while the eye moves by
/// `eye` and the point by `point(pixel index)` (zero: it stands still, and `p ∓ 0` is
/// `p` exactly), both centred on the frame's instant.
fn blur_along(
    linear: &mut [[f32; 3]],
    depth: &[f32],
    width: u32,
    rays: &Rays,
    eye: [f32; 3],
    point: impl Fn(usize) -> [f32; 3] + Sync,
) {
    let w = width.max(1) as usize;
    let h = linear.len() / w;
    let source = linear.to_vec();
    let half = eye.map(|m| m * 0.5);
    let before = [0, 1, 2].map(|k| rays.eye[k] - half[k]);
    let after = [0, 1, 2].map(|k| rays.eye[k] + half[k]);
    linear.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, out) in row.iter_mut().enumerate() {
            let d = depth[y * w + x];
            if d <= 0.0 {
                continue;
            }
            let v = rays.dir(x, y);
            let p = [0, 1, 2].map(|k| rays.eye[k] + d * v[k]);
            let m = point(y * w + x);
            let from = [0, 1, 2].map(|k| p[k] - 0.5 * m[k]);
            let to = [0, 1, 2].map(|k| p[k] + 0.5 * m[k]);
            let (Some(a), Some(b)) = (
                rays.project_from(before, from),
                rays.project_from(after, to),
            ) else {
                continue;
            };
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let len = (dx * dx + dy * dy).sqrt();
            if len.is_nan() || len < 1.0 {
                continue;
            }
            let scale = if len > MAX_BLUR { MAX_BLUR / len } else { 1.0 };
            let (dx, dy) = (dx * scale, dy * scale);
            let n = (len.min(MAX_BLUR).ceil() as usize).clamp(2, MAX_SAMPLES);
            let (cx, cy) = (x as f32 + 0.5, y as f32 + 0.5);
            let mut sum = [0.0f32; 3];
            for i in 0..n {
                let t = i as f32 / (n - 1) as f32 - 0.5;
                for (k, s) in sum.iter_mut().enumerate() {
                    *s += sample(&source, w, h, cx + dx * t, cy + dy * t, k);
                }
            }
            *out = sum.map(|s| s / n as f32);
        }
    });
}

/// Lateral chromatic aberration: red is magnified and blue shrunk about the image centre
/// so that they sit `pixels` apart at the corners.
pub(crate) fn chromatic_aberration(linear: &mut [[f32; 3]], width: u32, pixels: f32) {
    if pixels <= 0.0 {
        return;
    }
    let w = width.max(1) as usize;
    let h = linear.len() / w;
    let (cx, cy) = (w as f32 / 2.0, h as f32 / 2.0);
    let k = 0.5 * pixels / (cx * cx + cy * cy).sqrt();
    let source = linear.to_vec();
    linear.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, out) in row.iter_mut().enumerate() {
            let (px, py) = (x as f32 + 0.5 - cx, y as f32 + 0.5 - cy);
            out[0] = sample(&source, w, h, cx + px * (1.0 - k), cy + py * (1.0 - k), 0);
            out[2] = sample(&source, w, h, cx + px * (1.0 + k), cy + py * (1.0 + k), 2);
        }
    });
}

/// Vignetting: light falls off as `1 − amount · r²`, `r` the distance from the centre
/// with the corners at 1.
pub(crate) fn vignette(linear: &mut [[f32; 3]], width: u32, amount: f32) {
    if amount <= 0.0 {
        return;
    }
    let w = width.max(1) as usize;
    let h = linear.len() / w;
    let (cx, cy) = (w as f32 / 2.0, h as f32 / 2.0);
    let inv = 1.0 / (cx * cx + cy * cy);
    linear.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        let py = y as f32 + 0.5 - cy;
        for (x, out) in row.iter_mut().enumerate() {
            let px = x as f32 + 0.5 - cx;
            let f = 1.0 - amount * (px * px + py * py) * inv;
            *out = out.map(|c| c * f.max(0.0));
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::CameraPose;

    #[test]
    fn vignetting_darkens_corners_only() {
        let mut img = vec![[1.0f32; 3]; 40 * 30];
        vignette(&mut img, 40, 0.5);
        assert!(img[15 * 40 + 20][0] > 0.99);
        assert!((img[0][0] - 0.5).abs() < 0.05);
    }

    #[test]
    fn aberration_splits_red_and_blue_at_the_edges() {
        // A white vertical line near the right edge.
        let (w, h) = (64usize, 16usize);
        let mut img = vec![[0.0f32; 3]; w * h];
        for y in 0..h {
            img[y * w + 60] = [1.0; 3];
        }
        chromatic_aberration(&mut img, w as u32, 6.0);
        let row = &img[8 * w..9 * w];
        let peak = |k: usize| {
            (0..w)
                .max_by(|&a, &b| row[a][k].total_cmp(&row[b][k]))
                .unwrap()
        };
        // Red is sampled nearer the centre (it appears farther out), blue farther.
        assert!(peak(0) > 60 && peak(2) < 60, "{} {}", peak(0), peak(2));
        assert_eq!(peak(1), 60);
    }

    /// A wall 5 m ahead, seen `w` pixels wide: its image striped every 2 pixels, its
    /// depth, and its ids (the middle third of the columns object 7, the rest object 3).
    struct Wall {
        w: usize,
        rays: Rays,
        img: Vec<[f32; 3]>,
        depth: Vec<f32>,
        ids: Vec<u32>,
    }

    fn striped_wall() -> Wall {
        let (w, h) = (60usize, 40usize);
        let pose = CameraPose::level([0.0, 1.5, 0.0], [0.0, 1.5, -10.0]);
        Wall {
            w,
            rays: Rays::new(&pose, [40.0, 40.0, 30.0, 20.0]).unwrap(),
            img: (0..w * h).map(|i| [(i % w / 2 % 2) as f32; 3]).collect(),
            depth: vec![5.0; w * h],
            ids: (0..w * h)
                .map(|i| if (20..40).contains(&(i % w)) { 7 } else { 3 })
                .collect(),
        }
    }

    impl Wall {
        /// The wall's image after [`moving_blur`] with the eye moving by `eye` and the
        /// objects by `moved`.
        fn blurred(&self, eye: [f32; 3], moved: &[[f32; 3]]) -> Vec<[f32; 3]> {
            let mut img = self.img.clone();
            let (w, ids) = (self.w as u32, &self.ids);
            moving_blur(&mut img, &self.depth, w, &self.rays, eye, (ids, moved));
            img
        }
    }

    #[test]
    fn a_moving_object_blurs_and_what_stands_still_does_not() {
        let wall = striped_wall();
        // Object 7 moves 0.5 m to the right (4 pixels at 5 m), the camera stands.
        let mut moved = vec![[0.0f32; 3]; 8];
        moved[7] = [0.5, 0.0, 0.0];
        let blurred = wall.blurred([0.0; 3], &moved);
        let w = wall.w;
        let changed = |x: usize| (blurred[20 * w + x][0] - wall.img[20 * w + x][0]).abs() > 0.05;
        assert!((24..36).all(changed), "the mover streaks");
        assert!(
            !(0..18).any(changed) && !(42..60).any(changed),
            "the rest stays"
        );
        // Nothing moving: nothing changes.
        assert_eq!(wall.blurred([0.0; 3], &[[0.0; 3]; 8]), wall.img);
    }

    #[test]
    fn the_eye_moving_alone_blurs_as_the_camera_blur_does() {
        let wall = striped_wall();
        let moving = wall.blurred([0.3, 0.0, 0.0], &[[0.0; 3]; 8]);
        let mut camera = wall.img.clone();
        let (w, rays) = (wall.w as u32, &wall.rays);
        motion_blur(&mut camera, &wall.depth, w, rays, [1.0, 0.0, 0.0], 0.3);
        assert_eq!(moving, camera);
        assert_ne!(moving, wall.img);
    }

    #[test]
    fn forward_motion_blurs_the_edges_not_the_centre() {
        let (w, h) = (64usize, 48usize);
        let pose = CameraPose::level([0.0, 1.5, 0.0], [0.0, 1.5, -10.0]);
        let rays = Rays::new(&pose, [40.0, 40.0, 32.0, 24.0]).unwrap();
        // A checkerboard wall 5 m ahead.
        let img: Vec<[f32; 3]> = (0..w * h)
            .map(|i| [((i % w / 2 + i / w / 2) % 2) as f32; 3])
            .collect();
        let depth = vec![5.0f32; w * h];
        let mut blurred = img.clone();
        motion_blur(&mut blurred, &depth, w as u32, &rays, [0.0, 0.0, -1.0], 1.0);
        let changed = |i: usize| (blurred[i][0] - img[i][0]).abs() > 0.05;
        assert!(!changed(24 * w + 32), "the centre does not move");
        assert!(changed(2 * w + 2), "a corner streaks");
    }
}
