//! Scans of a small scene: a road plane and a car-sized box.

use super::*;

/// Triangles with their normals, albedos and labels.
type Parts = (Vec<Tri>, Vec<[f32; 3]>, Vec<f32>, Vec<u32>);

/// Two triangles of the quad `a b c d` (counter-clockwise about `n`), labelled `label`.
fn quad(out: &mut Parts, q: [[f32; 3]; 4], n: [f32; 3], label: u32) {
    for t in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
        out.0.push(t);
        out.1.push(n);
        out.2.push(0.5);
        out.3.push(label);
    }
}

/// A 200 m road plane at y = 0 (instance 1) and a box (a car, instance 5) from x 8 to 12,
/// z −1 to 1, 1.5 m high: the two parts apart.
fn parts() -> (Parts, Parts) {
    let mut road = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    quad(
        &mut road,
        [
            [-100., 0., -100.],
            [-100., 0., 100.],
            [100., 0., 100.],
            [100., 0., -100.],
        ],
        [0., 1., 0.],
        label(Some(ObjectKind::Road), 1),
    );
    let mut car = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let id = label(Some(ObjectKind::Car), 5);
    // The face towards the sensor (x = 8) and the roof.
    quad(
        &mut car,
        [[8., 0., -1.], [8., 0., 1.], [8., 1.5, 1.], [8., 1.5, -1.]],
        [-1., 0., 0.],
        id,
    );
    quad(
        &mut car,
        [
            [8., 1.5, -1.],
            [8., 1.5, 1.],
            [12., 1.5, 1.],
            [12., 1.5, -1.],
        ],
        [0., 1., 0.],
        id,
    );
    (road, car)
}

/// The road and the car in one target.
fn target() -> Target {
    let (mut t, car) = parts();
    t.0.extend(car.0);
    t.1.extend(car.1);
    t.2.extend(car.2);
    t.3.extend(car.3);
    Target::new(t.0, t.1, t.2, t.3)
}

fn pose() -> CameraPose {
    CameraPose {
        eye: [0.0, 1.7, 0.0],
        target: [10.0, 1.7, 0.0],
        up: [0.0, 1.0, 0.0],
        angles: None,
        time: None,
    }
}

fn small() -> Scanner {
    Scanner {
        azimuth_steps: 256,
        ..Scanner::default_64()
    }
}

#[test]
fn scans_are_the_same_bytes_on_one_thread_and_two() {
    let target = target();
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| velodyne_bytes(&scan(&target, None, &small(), &pose(), 3, "top", 2)))
    };
    let one = run(1);
    assert!(!one.is_empty());
    assert_eq!(one, run(2));
}

#[test]
fn the_car_is_labelled_car_with_its_instance_where_it_stands() {
    let points = scan(&target(), None, &small(), &pose(), 3, "top", 0);
    let car: Vec<&Point> = points.iter().filter(|p| p.label == 10 | 5 << 16).collect();
    assert!(car.len() > 20, "{} car points", car.len());
    for p in &car {
        // Sensor frame: x forward (east), y left (north = −z world), z up.
        assert!((7.9..12.1).contains(&p.xyz[0]), "{p:?}");
        assert!((-1.1..1.1).contains(&p.xyz[1]), "{p:?}");
        assert!((-1.8..-0.1).contains(&p.xyz[2]), "{p:?}");
    }
    let road = points.iter().filter(|p| p.label == 40).count();
    assert!(road > 1000, "{road} road points");
    assert!(
        points
            .iter()
            .all(|p| p.label == 40 || p.label == 10 | 5 << 16)
    );
}

#[test]
fn without_noise_road_points_lie_on_the_road() {
    let scanner = Scanner {
        noise: 0.0,
        ..small()
    };
    let points = scan(&target(), None, &scanner, &pose(), 3, "top", 0);
    for p in points.iter().filter(|p| p.label == 40) {
        assert!((p.xyz[2] + 1.7).abs() < 1e-3, "{p:?}");
    }
}

#[test]
fn noise_and_dropout_are_seeded() {
    let scanner = Scanner {
        noise: 0.05,
        dropout: 0.2,
        ..small()
    };
    let a = scan(&target(), None, &scanner, &pose(), 3, "top", 0);
    assert_eq!(a, scan(&target(), None, &scanner, &pose(), 3, "top", 0));
    assert_ne!(a, scan(&target(), None, &scanner, &pose(), 4, "top", 0));
    assert_ne!(a, scan(&target(), None, &scanner, &pose(), 3, "top", 1));
    let all = scan(
        &target(),
        None,
        &Scanner {
            dropout: 0.0,
            ..scanner.clone()
        },
        &pose(),
        3,
        "top",
        0,
    );
    let kept = a.len() as f64 / all.len() as f64;
    assert!((0.76..0.84).contains(&kept), "{kept}");
    // Range noise: ground points off the plane by about 5 cm times |sin| of the beam.
    let spread: Vec<f32> = a
        .iter()
        .filter(|p| p.label == 40)
        .map(|p| (p.xyz[2] + 1.7).abs())
        .collect();
    assert!(spread.iter().any(|d| *d > 1e-3));
    assert!(spread.iter().all(|d| *d < 0.2));
}

#[test]
fn fog_dims_and_drops_far_returns() {
    let clear = scan(&target(), None, &small(), &pose(), 3, "top", 0);
    let foggy = Scanner {
        extinction: 0.03,
        min_intensity: 0.05,
        ..small()
    };
    let fog = scan(&target(), None, &foggy, &pose(), 3, "top", 0);
    assert!(fog.len() < clear.len());
    let far = |ps: &[Point]| {
        ps.iter()
            .map(|p| libm::hypotf(p.xyz[0], p.xyz[1]))
            .fold(0.0f32, f32::max)
    };
    assert!(far(&fog) < far(&clear));
}

#[test]
fn encodings_are_little_endian_records() {
    let p = Point {
        xyz: [1.0, -2.0, 0.5],
        intensity: 0.25,
        label: 10 | 7 << 16,
    };
    let bin = velodyne_bytes(&[p]);
    assert_eq!(bin.len(), 16);
    assert_eq!(f32::from_le_bytes(bin[4..8].try_into().unwrap()), -2.0);
    assert_eq!(label_bytes(&[p]), (10u32 | 7 << 16).to_le_bytes().to_vec());
}

/// The road alone, and the car alone.
fn split() -> (Target, Target) {
    let (road, car) = parts();
    (
        Target::new(road.0, road.1, road.2, road.3),
        Target::new(car.0, car.1, car.2, car.3),
    )
}

#[test]
fn what_moves_scanned_apart_gives_the_scan_of_the_whole() {
    let (still, moving) = split();
    let whole = scan(&target(), None, &small(), &pose(), 3, "top", 0);
    let parts = scan(&still, Some(&moving), &small(), &pose(), 3, "top", 0);
    assert_eq!(whole, parts);
    assert!(whole.iter().any(|p| p.label >> 16 == 5));
    // Without the moving part the car is gone, and the road behind it shows.
    let road = scan(&still, None, &small(), &pose(), 3, "top", 0);
    assert!(road.iter().all(|p| p.label >> 16 != 5));
    assert_ne!(road, whole);
}
