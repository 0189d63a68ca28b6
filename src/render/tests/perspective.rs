//! Near-plane clipping and perspective-correct texturing.

use super::*;

#[test]
fn a_ground_plane_reaching_behind_the_camera_clips_cleanly() {
    let ground = ground_quad(100.0);
    let scene = Scene {
        textures: Vec::new(),
        materials: vec![material([0.5; 3], None, [0.0; 3])],
        objects: vec![object("ground", vec![ground])],
    };
    let prepared = prepare(&scene).unwrap();
    // fy = 24, cy = 24: the horizon is the line y = 24.
    let k = Intrinsics::from_fov(64, 48, 1.0);
    let frame = render(
        &prepared,
        &pose([0.0, 1.5, 0.0], [0.0, 1.5, -10.0]),
        &k,
        &flat(),
        1,
    );
    for (x, y, p) in frame.instance.enumerate_pixels() {
        // The far edge (100 m) is at y = 24.36: rows 0–23 are sky, rows 24–47 all ground.
        assert_eq!(p.0[0], u32::from(y >= 24), "({x}, {y})");
        if y >= 24 {
            let depth = 1.5 * 24.0 / (f64::from(y) + 0.5 - 24.0);
            let mm = f64::from(frame.depth_mm().get_pixel(x, y).0[0]);
            let expected = (depth * 1000.0).min(65535.0);
            assert!((mm - expected).abs() <= 1.0, "({x}, {y}): {mm} vs {depth}");
        }
    }
}

#[test]
fn a_checker_floor_is_textured_perspective_correctly() {
    // 4 m per texture repeat, 2 m per checker cell.
    let floor = quad(
        0,
        [
            [-60.0, 0.0, -100.0],
            [60.0, 0.0, -100.0],
            [60.0, 0.0, 20.0],
            [-60.0, 0.0, 20.0],
        ],
        [[-15.0, -25.0], [15.0, -25.0], [15.0, 5.0], [-15.0, 5.0]],
        [0.0, 1.0, 0.0],
    );
    let scene = Scene {
        textures: vec![checker_texture(64, 32)],
        materials: vec![material([1.0; 3], Some(0), [0.0; 3])],
        objects: vec![object("floor", vec![floor])],
    };
    let prepared = prepare(&scene).unwrap();
    let k = Intrinsics {
        width: 200,
        height: 150,
        fx: 100.0,
        fy: 100.0,
        cx: 100.0,
        cy: 75.0,
        near: 0.1,
        far: 1000.0,
    };
    let frame = render(
        &prepared,
        &pose([0.0, 2.0, 0.0], [0.0, 2.0, -1.0]),
        &k,
        &flat(),
        1,
    );
    let mut checked = 0;
    for py in 76..150u32 {
        let t = 2.0 * 100.0 / (f64::from(py) + 0.5 - 75.0);
        if t > 6.0 {
            continue;
        }
        for px in 0..200u32 {
            let x = t * (f64::from(px) + 0.5 - 100.0) / 100.0;
            let z = -t;
            let margin = |v: f64| {
                let f = v / 2.0 - (v / 2.0).floor();
                2.0 * f.min(1.0 - f)
            };
            if margin(x) < 0.6 || margin(z) < 0.6 {
                continue;
            }
            let white = ((x / 2.0).floor() + (z / 2.0).floor()).rem_euclid(2.0) == 0.0;
            let expected = if white { [255; 3] } else { [0; 3] };
            assert_eq!(
                clipped(&frame, px, py),
                expected,
                "({px}, {py}) at x {x:.2}, z {z:.2}"
            );
            checked += 1;
        }
    }
    assert!(checked > 1000, "only {checked} pixels checked");
}
