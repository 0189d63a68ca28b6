//! A frame's annotated objects with 3D boxes → its KITTI object files: the `label_2` lines
//! and the `calib` file, as the KITTI object devkit describes them.
//!
//! Coordinates are KITTI's rectified camera: the frame's [`LevelCamera`] (at the eye, y
//! down along gravity, z the view's level heading), so every box stands upright and turns
//! about y only, as KITTI's do, whatever the camera's pitch and roll. `R0_rect` turns the
//! real camera's axes into it, and `P2 = K · [R0_rectᵀ | 0]` projects it: `P2 = K` for a
//! level camera, and a point `X` of a label projects to `P2 · (X, 1)` in pixels of the
//! rendered image (pixel `(i, j)` covers `[i, i + 1) × [j, j + 1)`). `P0`, `P1`, `P3` are
//! `P2` (one camera). `Tr_velo_to_cam` maps a KITTI velodyne frame at the eye (x forward,
//! y left, z up, level) into the real camera; `Tr_imu_to_velo` is the identity.
//!
//! Per object: `type truncated occluded alpha left top right bottom h w l x y z
//! rotation_y`. The type is the COCO category's name (`car` → `Car`, `person` →
//! `Pedestrian`, `rider` → `Cyclist`, as KITTI names them). The 2D box is the visible
//! pixels' box (edges). `truncated` is the share of the full projected box (what the
//! object would cover unoccluded, past the image edge too) outside the image; `occluded`
//! is 0 where the object shows at least 90 % of its in-image part, 1 at least 50 %, 2
//! less, 3 unknown (the visible fraction divided by the in-image share of the full box).

use std::fmt::Write;

use super::box3d::LevelCamera;
use super::frame_annotations::FrameAnnotations;
use super::object_label::Category;

/// One frame's KITTI object files.
#[derive(Clone, Debug, PartialEq)]
pub struct KittiFiles {
    /// `label_2/NNNNNN.txt`.
    pub label: String,
    /// `calib/NNNNNN.txt`.
    pub calib: String,
}

/// The KITTI files of `frame`: a line per annotated (not ignored) object of `categories`
/// that has a 3D box.
pub fn kitti(frame: &FrameAnnotations, categories: &[Category]) -> KittiFiles {
    let Some(camera) = LevelCamera::of(&frame.pose) else {
        return KittiFiles {
            label: String::new(),
            calib: calib(frame.intrinsics, None),
        };
    };
    let mut label = String::new();
    for object in frame.objects.iter().filter(|o| o.passes()) {
        let (Some(category), Some(b)) = (object.category, object.label.box3d.as_ref()) else {
            continue;
        };
        let Some(name) = categories
            .iter()
            .find(|c| c.id == category)
            .map(|c| &c.name)
        else {
            continue;
        };
        let (at, rotation_y) = camera.kitti_pose(b);
        let alpha = wrap(rotation_y - libm::atan2(at[0], at[2]));
        let truncated = object
            .full_box
            .map_or(0.0, |f| outside(f, frame.width, frame.height));
        let occluded = match object.fraction {
            Some(f) if truncated < 1.0 => {
                let seen = f / (1.0 - truncated);
                if seen >= 0.9 {
                    0
                } else if seen >= 0.5 {
                    1
                } else {
                    2
                }
            }
            _ => 3,
        };
        let v = object.visible.bounds;
        let _ = write!(label, "{} {} {occluded}", kitti_type(name), two(truncated));
        let edges = [v.x_min, v.y_min, v.x_max + 1, v.y_max + 1].map(f64::from);
        let size = [b.size[2], b.size[1], b.size[0]];
        for value in [alpha].iter().chain(&edges).chain(&size).chain(&at) {
            let _ = write!(label, " {}", two(*value));
        }
        let _ = writeln!(label, " {}", two(rotation_y));
    }
    KittiFiles {
        label,
        calib: calib(frame.intrinsics, Some(&camera)),
    }
}

/// `v` with two decimals, as KITTI's labels are written (`-0.00` as `0.00`).
fn two(v: f64) -> String {
    format!("{:.2}", crate::model::geometry::round_to(v, 100.0))
}

/// The `calib` file: `P0`–`P3`, `R0_rect`, `Tr_velo_to_cam`, `Tr_imu_to_velo`, each value
/// as KITTI writes it (`%.12e`). Without a camera (an unusable pose), a level one.
fn calib([fx, fy, cx, cy]: [f64; 4], camera: Option<&LevelCamera>) -> String {
    let r0 = camera.map_or([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], |c| {
        c.rectification()
    });
    // Rect → real camera is R0ᵀ; then K.
    let k = [[fx, 0.0, cx], [0.0, fy, cy], [0.0, 0.0, 1.0]];
    let p: Vec<f64> = (0..3)
        .flat_map(|i| {
            let row: [f64; 3] = std::array::from_fn(|j| (0..3).map(|m| k[i][m] * r0[j][m]).sum());
            [row[0], row[1], row[2], 0.0]
        })
        .collect();
    // Velodyne (x forward, y left, z up) → rect (x right, y down, z forward) → real.
    let velo = [[0.0, -1.0, 0.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]];
    let tr: Vec<f64> = (0..3)
        .flat_map(|i| {
            let row: [f64; 3] =
                std::array::from_fn(|j| (0..3).map(|m| r0[m][i] * velo[m][j]).sum());
            [row[0], row[1], row[2], 0.0]
        })
        .collect();
    let identity = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    let mut out = String::new();
    for n in 0..4 {
        line(&mut out, &format!("P{n}"), &p);
    }
    line(&mut out, "R0_rect", r0.as_flattened());
    line(&mut out, "Tr_velo_to_cam", &tr);
    line(&mut out, "Tr_imu_to_velo", &identity);
    out
}

/// `name: v v v …` with each value as C's `%.12e`.
fn line(out: &mut String, name: &str, values: &[f64]) {
    out.push_str(name);
    out.push(':');
    for &v in values {
        out.push(' ');
        out.push_str(&exponent(v));
    }
    out.push('\n');
}

/// `v` as C's `%.12e` (`7.215377000000e+02`); `-0` as `0`.
fn exponent(v: f64) -> String {
    let v = if v == 0.0 { 0.0 } else { v };
    let text = format!("{v:.12e}");
    let (mantissa, exp) = text.split_once('e').expect("Rust's {:e} writes an e");
    let exp: i32 = exp.parse().expect("an integer exponent");
    let sign = if exp < 0 { '-' } else { '+' };
    format!("{mantissa}e{sign}{:02}", exp.abs())
}

/// KITTI's name of a category: its own for the classes KITTI has, else the category's
/// (spaces, which would split the line, as `_`).
fn kitti_type(name: &str) -> String {
    match name {
        "car" => "Car".into(),
        "person" => "Pedestrian".into(),
        "rider" => "Cyclist".into(),
        _ => name.replace(char::is_whitespace, "_"),
    }
}

/// The share of box `[x, y, w, h]` (pixels) outside a `width` × `height` image.
fn outside([x, y, w, h]: [f64; 4], width: u32, height: u32) -> f64 {
    let overlap = |lo: f64, len: f64, size: u32| (lo + len).min(f64::from(size)) - lo.max(0.0);
    let area = w * h;
    if area <= 0.0 {
        return 0.0;
    }
    let inside = overlap(x, w, width).max(0.0) * overlap(y, h, height).max(0.0);
    (1.0 - inside / area).clamp(0.0, 1.0)
}

/// `a` in `(−π, π]`.
fn wrap(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    if a > PI {
        a - TAU
    } else if a <= -PI {
        a + TAU
    } else {
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_written_as_c_does() {
        assert_eq!(exponent(721.5377), "7.215377000000e+02");
        assert_eq!(exponent(-0.0), "0.000000000000e+00");
        assert_eq!(exponent(0.00123), "1.230000000000e-03");
        assert_eq!(exponent(-1.0), "-1.000000000000e+00");
    }

    #[test]
    fn truncation_is_the_share_outside_the_image() {
        assert_eq!(outside([10.0, 10.0, 20.0, 20.0], 100, 100), 0.0);
        assert_eq!(outside([-10.0, 0.0, 20.0, 10.0], 100, 100), 0.5);
        assert_eq!(outside([200.0, 0.0, 20.0, 10.0], 100, 100), 1.0);
    }
}
