//! Shadows against a case computed by hand, and the pinned digest of a shadowed frame.

use super::tests::{UNIT_UV, cuboid, flat, material, object, pose, quad};
use super::view::View;
use super::*;
use crate::model::Scene;

/// A 20 m white plane with a 2 × 3 × 2 m box on it (box x −1…1, y 0…3, z −1…1).
fn box_on_plane() -> Scene {
    let plane = quad(
        0,
        [
            [-10.0, 0.0, -10.0],
            [10.0, 0.0, -10.0],
            [10.0, 0.0, 10.0],
            [-10.0, 0.0, 10.0],
        ],
        UNIT_UV,
        [0.0, 1.0, 0.0],
    );
    Scene {
        textures: Vec::new(),
        materials: vec![material([1.0; 3], None, [0.0; 3])],
        objects: vec![
            object("plane", vec![plane]),
            object("box", cuboid(0, [-1.0, 0.0, -1.0], [1.0, 3.0, 1.0])),
        ],
    }
}

/// Convex hull (counter-clockwise in x–z) of points, by the monotone chain.
fn hull(mut p: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    p.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut h: Vec<[f64; 2]> = Vec::new();
    for pass in 0..2 {
        let start = h.len();
        let points: Vec<[f64; 2]> = if pass == 0 {
            p.clone()
        } else {
            p.iter().rev().copied().collect()
        };
        for q in points {
            while h.len() >= start + 2 && cross(h[h.len() - 2], h[h.len() - 1], q) <= 0.0 {
                h.pop();
            }
            h.push(q);
        }
        h.pop();
    }
    h
}

/// Signed distance from `q` to the convex polygon's boundary: positive inside.
fn signed_distance(poly: &[[f64; 2]], q: [f64; 2]) -> f64 {
    let mut d = f64::INFINITY;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let e = [b[0] - a[0], b[1] - a[1]];
        let len = (e[0] * e[0] + e[1] * e[1]).sqrt();
        // Inward normal of a counter-clockwise polygon (x right, z "up" in the plane).
        let inside = (e[0] * (q[1] - a[1]) - e[1] * (q[0] - a[0])) / len;
        d = d.min(inside);
    }
    d
}

#[test]
fn a_box_casts_the_shadow_polygon_computed_by_hand() {
    let prepared = prepare(&box_on_plane()).unwrap();
    let sun = Sun {
        elevation: 40.0,
        azimuth: 120.0,
        hour: None,
    };
    let s = sun.direction();
    let mut lighting = flat();
    lighting.ambient = [0.2; 3];
    lighting.ground_ambient = [0.2; 3];
    lighting.sun_colour = [1.0; 3];
    lighting.sun_direction = s.map(|v| v as f32);
    lighting.shadows = true;
    // By hand: the top corners fall along −sun onto y = 0, 3 / tan(40°) m away.
    let (dx, dz) = (-s[0] / s[1] * 3.0, -s[2] / s[1] * 3.0);
    let mut corners = Vec::new();
    for (x, z) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        corners.push([x, z]);
        corners.push([x + dx, z + dz]);
    }
    let shadow = hull(corners);
    assert_eq!(shadow.len(), 6, "{shadow:?}");

    // Straight down from 30 m over the shadow's middle, 0.1 m per pixel.
    let (w, h) = (128, 128);
    let k = Intrinsics::from_fov(w, h, 6.4 / 30.0);
    let centre = [dx / 2.0, dz / 2.0];
    let eye = pose([centre[0], 30.0, centre[1]], [centre[0], 0.0, centre[1]]);
    let frame = render(&prepared, &eye, &k, &lighting, 1);
    let view = View::new(&eye, &k, 1).unwrap();
    let metres_per_pixel = 30.0 / k.fx;
    let lit = 0.2 + s[1] as f32;
    let (mut dark_checked, mut lit_checked) = (0, 0);
    for y in 0..h {
        for x in 0..w {
            if frame.instance.get_pixel(x, y).0[0] != 1 {
                continue;
            }
            let p = view.unproject(f64::from(x) + 0.5, f64::from(y) + 0.5, 30.0);
            assert!(p[1].abs() < 1e-9);
            let d = signed_distance(&shadow, [p[0], p[2]]) / metres_per_pixel;
            let v = frame.linear[(y * w + x) as usize][0];
            if d > 1.0 {
                assert!((v - 0.2).abs() < 1e-4, "({x}, {y}) {d:.2} px inside: {v}");
                dark_checked += 1;
            } else if d < -1.0 {
                assert!((v - lit).abs() < 1e-4, "({x}, {y}) {d:.2} px outside: {v}");
                lit_checked += 1;
            }
        }
    }
    assert!(
        dark_checked > 600 && lit_checked > 5000,
        "{dark_checked} {lit_checked}"
    );
}

#[test]
fn shadows_do_not_change_with_the_camera() {
    // The same ground point seen from two places gets the same shadow.
    let prepared = prepare(&box_on_plane()).unwrap();
    let lighting = Lighting::day();
    let k = Intrinsics::from_fov(64, 64, 0.4);
    let a = render(
        &prepared,
        &pose([0.0, 30.0, 0.0], [0.0; 3]),
        &k,
        &lighting,
        1,
    );
    let b = render(
        &prepared,
        &pose([0.0, 30.0, 0.0], [0.0; 3]),
        &k,
        &lighting,
        1,
    );
    assert_eq!(a, b);
    let map = prepared.shadow_map(lighting.sun_direction).unwrap();
    let again = prepared.shadow_map(lighting.sun_direction).unwrap();
    assert!(std::sync::Arc::ptr_eq(&map, &again), "one map per sun");
}

/// A small shadowed street-like frame under the day preset (sky, sun, shadows, tone
/// curve), pinned by digest. When this fails because lighting output changed on purpose,
/// bump `render::VERSION` (src/render/mod.rs) and put the new digest here.
#[test]
fn a_shadowed_frame_is_pinned() {
    let prepared = prepare(&box_on_plane()).unwrap();
    let k = Intrinsics::from_fov(64, 48, 0.6);
    let eye = pose([-6.0, 2.0, 7.0], [0.0, 1.0, 0.0]);
    let frame = render(&prepared, &eye, &k, &Lighting::day(), 2);
    let digest = crate::hash::sha256_hex(frame.rgb.as_raw());
    assert_eq!(
        (VERSION, digest.as_str()),
        (
            3,
            "795cfcf3fbb1d5e7ac56ed0b27eaeeb8494e166f596a0b667127871804b9615b"
        ),
        "lighting output changed: bump render::VERSION and update this digest"
    );
}
