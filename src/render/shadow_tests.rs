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
            // Pixels beside the box mix with it (edge antialiasing): not the shadow's test.
            let beside_box = [(-1, 0), (1, 0), (0, -1), (0, 1)].iter().any(|&(dx, dy)| {
                let (nx, ny) = (x as i64 + dx, y as i64 + dy);
                (0..i64::from(w)).contains(&nx)
                    && (0..i64::from(h)).contains(&ny)
                    && frame.instance.get_pixel(nx as u32, ny as u32).0[0] != 1
            });
            if beside_box {
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
    let map = prepared
        .shadow_map(lighting.sun_direction, lighting.shadow_map_side)
        .unwrap();
    let again = prepared
        .shadow_map(lighting.sun_direction, lighting.shadow_map_side)
        .unwrap();
    assert!(std::sync::Arc::ptr_eq(&map, &again), "one map per sun");
    // A map of another side is another map, with texels as much coarser, and the one of
    // the first side is built again when asked for after it.
    let half = prepared
        .shadow_map(lighting.sun_direction, lighting.shadow_map_side / 2)
        .unwrap();
    assert!(
        (half.texel / map.texel - 2.0).abs() < 1e-9,
        "{} {}",
        half.texel,
        map.texel
    );
    let full = prepared
        .shadow_map(lighting.sun_direction, lighting.shadow_map_side)
        .unwrap();
    assert_eq!(full.texel, map.texel);
}

/// The ground and the hills stay out of the shadow map: a ring of hills kilometres away and
/// a wider ground leave the map's texel (and so every shadow) as the box alone makes it.
#[test]
fn the_ground_and_far_hills_leave_the_shadow_map_as_it_was() {
    let lighting = Lighting::day();
    let map_of = |scene: &Scene| {
        prepare(scene)
            .unwrap()
            .shadow_map(lighting.sun_direction, lighting.shadow_map_side)
            .unwrap()
            .texel
    };
    let mut scene = box_on_plane();
    scene.objects[0].kind = crate::model::ObjectKind::Ground;
    let alone = map_of(&scene);
    let mut hills = object(
        "hills",
        cuboid(0, [1500.0, 0.0, 0.0], [1600.0, 80.0, 2000.0]),
    );
    hills.kind = crate::model::ObjectKind::Hills;
    scene.objects.push(hills);
    scene.objects[0].meshes = vec![quad(
        0,
        [
            [-3000.0, 0.0, -3000.0],
            [3000.0, 0.0, -3000.0],
            [3000.0, 0.0, 3000.0],
            [-3000.0, 0.0, 3000.0],
        ],
        UNIT_UV,
        [0.0, 1.0, 0.0],
    )];
    assert_eq!(map_of(&scene), alone);
    // As a mesh, the same far box widens the map's texels fiftyfold.
    scene.objects[2].kind = crate::model::ObjectKind::Mesh;
    assert!(
        map_of(&scene) > 50.0 * alone,
        "{} vs {alone}",
        map_of(&scene)
    );
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
    let digest = crate::hash::sha256_hex(frame.rgb().as_raw());
    assert_eq!(
        (VERSION, digest.as_str()),
        (
            18,
            "4f688945913751bbc5324db443080fc3ca0d0dea380991d57a5073c29c8915c9"
        ),
        "lighting output changed: bump render::VERSION and update this digest"
    );
}

/// Flat ambient light only, with ambient occlusion at `strength`.
fn ambient_only(strength: f32) -> Lighting {
    let mut lighting = flat();
    lighting.ambient_occlusion = strength;
    lighting
}

#[test]
fn ambient_occlusion_darkens_the_foot_of_a_box_and_changes_no_id_or_depth() {
    let prepared = prepare(&box_on_plane()).unwrap();
    let k = Intrinsics::from_fov(160, 120, 0.5);
    // Looking down at the box's +z face and the ground in front of it.
    let eye = pose([0.0, 4.0, 7.0], [0.0, 0.0, 0.0]);
    let off = render(&prepared, &eye, &k, &ambient_only(0.0), 1);
    let on = render(&prepared, &eye, &k, &ambient_only(1.0), 1);
    assert_eq!(off.instance, on.instance);
    assert_eq!(off.depth, on.depth);
    let view = View::new(&eye, &k, 1).unwrap();
    let (mut near, mut far) = (Vec::new(), Vec::new());
    for y in 0..120 {
        for x in 0..160 {
            if on.instance.get_pixel(x, y).0[0] != 1 {
                continue;
            }
            let d = f64::from(on.depth.get_pixel(x, y).0[0]);
            let p = view.unproject(f64::from(x) + 0.5, f64::from(y) + 0.5, d);
            let i = (y * 160 + x) as usize;
            let ratio = on.linear[i][0] / off.linear[i][0];
            // In front of the box's +z face (z = 1), within its width.
            if p[0].abs() < 0.8 && (1.05..1.25).contains(&p[2]) {
                near.push(ratio);
            } else if p[0].abs() > 4.0 || p[2] > 4.0 {
                far.push(ratio);
            }
        }
    }
    assert!(
        near.len() > 20 && far.len() > 1000,
        "{} {}",
        near.len(),
        far.len()
    );
    let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
    // Clearly darker at the foot, but not black; open ground untouched.
    assert!((0.4..0.9).contains(&mean(&near)), "{}", mean(&near));
    assert!(far.iter().all(|&r| r == 1.0), "{far:?}");
}

#[test]
fn weak_shadow_strength_lifts_shadows_part_way() {
    let prepared = prepare(&box_on_plane()).unwrap();
    let sun = Sun {
        elevation: 40.0,
        azimuth: 120.0,
        hour: None,
    };
    let mut lighting = flat();
    lighting.ambient = [0.2; 3];
    lighting.ground_ambient = [0.2; 3];
    lighting.sun_colour = [1.0; 3];
    lighting.sun_direction = sun.direction().map(|v| v as f32);
    lighting.shadows = true;
    let k = Intrinsics::from_fov(64, 64, 0.4);
    let eye = pose([0.0, 30.0, 0.0], [0.0; 3]);
    let full = render(&prepared, &eye, &k, &lighting, 1);
    lighting.shadow_strength = 0.25;
    let weak = render(&prepared, &eye, &k, &lighting, 1);
    let lit = 0.2 + sun.direction()[1] as f32;
    // The darkest ground pixel of the full shadow holds the ambient only; under a quarter
    // strength it keeps three quarters of the sun.
    let i = (0..64 * 64)
        .filter(|&i| full.instance.as_raw()[i] == 1)
        .min_by(|&a, &b| full.linear[a][0].total_cmp(&full.linear[b][0]))
        .unwrap();
    assert!(
        (full.linear[i][0] - 0.2).abs() < 1e-4,
        "{}",
        full.linear[i][0]
    );
    let expected = 0.2 + 0.75 * (lit - 0.2);
    assert!(
        (weak.linear[i][0] - expected).abs() < 1e-3,
        "{}",
        weak.linear[i][0]
    );
}

#[test]
fn frames_asking_for_shadow_maps_side_by_side_finish() {
    // Frames render side by side in rayon, each with parallel work of its own (its tiles),
    // and each asks for its sun's map, which is built with rayon jobs too: a worker
    // waiting for one of them may take up another frame, which asks for a map while the
    // first build is under way. Every frame has a sun of its own (no map is reused); 8
    // threads, under a watchdog. With the lock held over the build (before `cf7779b`) this
    // hung in 2 of 3 runs; it cannot prove the absence of a deadlock, only catch one.
    use rayon::prelude::*;
    use std::sync::{Arc, mpsc};
    use std::time::Duration;

    const FRAMES: u32 = 128;
    let scene = Arc::new(prepare(&box_on_plane()).unwrap());
    let (done, finished) = mpsc::channel();
    std::thread::spawn(move || {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(8)
            .build()
            .unwrap();
        let built: u32 = pool.install(|| {
            (0..FRAMES)
                .into_par_iter()
                .with_max_len(1)
                .map(|k| {
                    let tiles: u64 = (0..64u64).into_par_iter().map(|t| t * t).sum();
                    let sun = Sun {
                        elevation: 20.0 + f64::from(k) * 0.5,
                        azimuth: 5.0 * f64::from(k),
                        hour: None,
                    };
                    let map = scene.shadow_map(sun.direction().map(|c| c as f32), 2048);
                    u32::from(map.is_some() && tiles > 0)
                })
                .sum()
        });
        let _ = done.send(built);
    });
    let built = finished
        .recv_timeout(Duration::from_secs(60))
        .expect("the frames did not finish in 60 s: a deadlock");
    assert_eq!(built, FRAMES);
}
