//! Surface normals: the face of the triangle at each pixel's centre, in camera axes,
//! facing the camera; and asking for them changes nothing else.

use super::*;

/// World vector `n` in OpenCV camera axes (x right, y down, z forward) of `pose`.
fn to_camera(pose: &CameraPose, n: [f64; 3]) -> [f64; 3] {
    let b = pose.basis().unwrap();
    [dot(b.right, n), -dot(b.up, n), dot(b.forward, n)]
}

/// The camera-space point seen at pixel `(x, y)`'s centre at `depth` (OpenCV axes).
fn point(k: &Intrinsics, x: u32, y: u32, depth: f32) -> [f64; 3] {
    let d = f64::from(depth);
    [
        (f64::from(x) + 0.5 - k.cx) / k.fx * d,
        (f64::from(y) + 0.5 - k.cy) / k.fy * d,
        d,
    ]
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let len = dot(v, v).sqrt();
    v.map(|c| c / len)
}

#[test]
fn normals_are_the_camera_facing_faces_the_depth_shows() {
    let prepared = prepare(&street_scene()).unwrap();
    let k = Intrinsics::from_fov(96, 72, 0.7);
    // Rolled and looking down a little, so no face normal lies along a camera axis.
    let mut eye = pose([-4.0, 3.0, 9.0], [6.0, 1.0, -16.0]);
    eye.up = unit([0.15, 1.0, 0.05]);
    let axes: Vec<[f64; 3]> = (0..6)
        .map(|i| {
            let mut n = [0.0; 3];
            n[i / 2] = if i % 2 == 0 { 1.0 } else { -1.0 };
            to_camera(&eye, n)
        })
        .collect();
    for (supersample, occlusion) in [(1, 0.0), (2, 0.0), (2, 0.5), (1, 0.5)] {
        let mut lighting = flat();
        lighting.ambient_occlusion = occlusion;
        let (frame, _) = render_with(&prepared, &eye, &k, &lighting, supersample, &[], true);
        let normals = frame.normals.as_ref().unwrap();
        let (w, h) = (k.width, k.height);
        let at = |x: u32, y: u32| normals[(y * w + x) as usize].map(f64::from);
        let mut flat_checked = 0;
        let mut seen = [false; 6];
        for y in 0..h {
            for x in 0..w {
                let id = frame.instance.get_pixel(x, y).0[0];
                let depth = frame.depth.get_pixel(x, y).0[0];
                let n = at(x, y);
                if id == 0 {
                    assert_eq!(n, [0.0; 3], "sky at ({x}, {y})");
                    continue;
                }
                // A face of the scene's boxes and ground, exactly, turned to the camera.
                let face = axes
                    .iter()
                    .position(|a| (0..3).all(|c| (a[c] - n[c]).abs() < 1e-6));
                let face = face.unwrap_or_else(|| panic!("({x}, {y}): {n:?} is no face"));
                seen[face] = true;
                assert!(
                    dot(n, point(&k, x, y, depth)) < 0.0,
                    "({x}, {y}) faces away"
                );
                // Where the pixel's neighbours show the same face, the plane their depths
                // span is the normal's.
                if x == 0 || y == 0 || x + 1 == w || y + 1 == h {
                    continue;
                }
                let near = [(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)];
                if near
                    .iter()
                    .any(|&(a, b)| frame.instance.get_pixel(a, b).0[0] != id || at(a, b) != n)
                {
                    continue;
                }
                let p = near.map(|(a, b)| point(&k, a, b, frame.depth.get_pixel(a, b).0[0]));
                let spanned = unit(cross(sub(p[1], p[0]), sub(p[3], p[2])));
                assert!(
                    dot(spanned, n).abs() > 0.995,
                    "({x}, {y}): {n:?} against the depth's {spanned:?}"
                );
                flat_checked += 1;
            }
        }
        assert!(flat_checked > 1000, "{flat_checked} pixels checked");
        // The ground, the boxes' fronts and their sides.
        assert!(seen.iter().filter(|s| **s).count() >= 3, "{seen:?}");
    }
}

#[test]
fn asking_for_normals_changes_nothing_else() {
    let prepared = prepare(&street_scene()).unwrap();
    let k = Intrinsics::from_fov(80, 60, 0.7);
    let eye = pose([-4.0, 3.0, 9.0], [6.0, 1.0, -16.0]);
    for supersample in [1, 2] {
        let (plain, plain_boxes) =
            render_measuring(&prepared, &eye, &k, &flat(), supersample, &[2, 3]);
        let (mut with, boxes) =
            render_with(&prepared, &eye, &k, &flat(), supersample, &[2, 3], true);
        assert!(plain.normals.is_none());
        assert!(with.normals.take().is_some());
        assert_eq!(with, plain);
        assert_eq!(boxes, plain_boxes);
    }
    // No usable view: all sky, normals too.
    let blind = pose([0.0; 3], [0.0; 3]);
    let (frame, _) = render_with(&prepared, &blind, &k, &flat(), 1, &[], true);
    assert!(frame.normals.unwrap().iter().all(|n| *n == [0.0; 3]));
}

#[test]
fn normals_png_decodes_to_the_normals_within_a_step() {
    let prepared = prepare(&street_scene()).unwrap();
    let k = Intrinsics::from_fov(64, 48, 0.7);
    let eye = pose([-4.0, 3.0, 9.0], [6.0, 1.0, -16.0]);
    let (frame, _) = render_with(&prepared, &eye, &k, &flat(), 1, &[], true);
    let png = frame
        .encode(&frame.rgb(), DepthFormat::Cm16)
        .normals
        .unwrap();
    let back = image::load_from_memory(&png).unwrap();
    assert!(matches!(back, image::DynamicImage::ImageRgb16(_)));
    let back = back.into_rgb16();
    let normals = frame.normals.as_ref().unwrap();
    let mut sky = 0;
    for (p, n) in back.pixels().zip(normals) {
        if p.0 == [0; 3] {
            assert_eq!(*n, [0.0; 3]);
            sky += 1;
            continue;
        }
        for c in 0..3 {
            let decoded = f64::from(p.0[c]) / 65535.0 * 2.0 - 1.0;
            assert!(
                (decoded - f64::from(n[c])).abs() <= 1.0 / 65535.0,
                "{p:?} {n:?}"
            );
        }
    }
    assert!(sky > 0 && sky < normals.len());
    // Without normals, no file.
    assert!(
        render(&prepared, &eye, &k, &flat(), 1)
            .encode(&frame.rgb(), DepthFormat::Cm16)
            .normals
            .is_none()
    );
}
