//! Coverage and the fill rule: which pixels a triangle owns.

use super::*;
use crate::render::prepared_scene::Triangle;
use crate::render::screen_triangle::{self, ScreenTri};
use crate::render::view::View;

/// A 64 × 64 view looking at −z from the origin, 16 px per metre at depth 1.
fn coverage_view() -> View {
    let k = coverage_view_intrinsics();
    View::new(&pose([0.0; 3], [0.0, 0.0, -1.0]), &k, 1).unwrap()
}

/// Coverage count per pixel of triangles given in pixel coordinates on the plane z = −1.
fn coverage(tris: &[[[f64; 2]; 3]]) -> Vec<u8> {
    let view = coverage_view();
    let mut screen: Vec<ScreenTri> = Vec::new();
    for t in tris {
        let mut p = t.map(|[x, y]| [((x - 32.0) / 16.0) as f32, ((32.0 - y) / 16.0) as f32, -1.0]);
        if cross(sub(p[1], p[0]), sub(p[2], p[0]))[2] < 0.0 {
            p.swap(1, 2);
        }
        let tri = Triangle {
            p,
            uv: [[0.0; 2]; 3],
            normal: [0.0, 0.0, 1.0],
            material: 0,
            instance: 1,
        };
        screen_triangle::setup(&tri, 0, &view, &mut screen);
    }
    let mut counts = vec![0u8; 64 * 64];
    for s in &screen {
        s.rasterize([0, 0, 64, 64], |x, y, _| counts[(y * 64 + x) as usize] += 1);
    }
    counts
}

fn fan(centre: [f64; 2], ring: &[[f64; 2]]) -> Vec<[[f64; 2]; 3]> {
    (0..ring.len())
        .map(|i| [centre, ring[i], ring[(i + 1) % ring.len()]])
        .collect()
}

#[test]
fn shared_edges_cover_every_pixel_exactly_once() {
    // Square with edges through pixel centres (16.5 and 48.5): the top-left rule takes
    // columns and rows 16–47.
    let (a, b, c, d) = ([16.5, 16.5], [48.5, 16.5], [48.5, 48.5], [16.5, 48.5]);
    let octagon = [
        [20.0, 10.5],
        [40.5, 10.5],
        [55.5, 25.0],
        [55.5, 40.0],
        [40.0, 55.5],
        [20.25, 55.5],
        [8.5, 40.0],
        [8.5, 25.5],
    ];
    type Tris = Vec<[[f64; 2]; 3]>;
    let cases: Vec<(&str, Tris, Tris)> = vec![
        (
            "square, both diagonals",
            vec![[a, b, c], [a, c, d]],
            vec![[a, b, d], [b, c, d]],
        ),
        (
            "square, fan from its centre on a pixel centre",
            fan([32.5, 32.5], &[a, b, c, d]),
            vec![[a, b, c], [a, c, d]],
        ),
        (
            "octagon, fans from two centres",
            fan([32.5, 32.5], &octagon),
            fan([30.3, 36.7], &octagon),
        ),
    ];
    for (name, first, second) in cases {
        let one = coverage(&first);
        let two = coverage(&second);
        assert!(one.iter().all(|&c| c <= 1), "{name}: a pixel covered twice");
        assert!(
            two.iter().all(|&c| c <= 1),
            "{name}: a pixel covered twice (2nd)"
        );
        assert_eq!(one, two, "{name}: triangulations disagree (a gap)");
        assert!(one.iter().filter(|&&c| c == 1).count() > 500, "{name}");
    }
    let square = coverage(&[[a, b, c], [a, c, d]]);
    for y in 0..64 {
        for x in 0..64 {
            let inside = (16..48).contains(&x) && (16..48).contains(&y);
            assert_eq!(square[y * 64 + x], u8::from(inside), "({x}, {y})");
        }
    }
}

#[test]
fn a_quad_in_front_of_the_camera_covers_the_expected_pixels() {
    // Two triangles as two objects; together exactly the 32 × 32 pixels of the square.
    let (a, b, c, d) = (
        [-31.0 / 32.0, 31.0 / 32.0, -1.0],
        [33.0 / 32.0, 31.0 / 32.0, -1.0],
        [33.0 / 32.0, -33.0 / 32.0, -1.0],
        [-31.0 / 32.0, -33.0 / 32.0, -1.0],
    );
    let tri = |p: [[f32; 3]; 3]| Mesh {
        material: 0,
        positions: p.to_vec(),
        normals: vec![[0.0, 0.0, 1.0]; 3],
        uvs: Vec::new(),
        indices: vec![0, 1, 2],
    };
    let scene = Scene {
        textures: Vec::new(),
        materials: vec![material([1.0; 3], None, [0.0; 3])],
        objects: vec![
            object("upper", vec![tri([a, d, b])]),
            object("lower", vec![tri([b, d, c])]),
        ],
    };
    let prepared = prepare(&scene).unwrap();
    let k = coverage_view_intrinsics();
    // Without antialiasing (0): the rasterizer's own coverage, pixel by pixel.
    let frame = render(&prepared, &pose([0.0; 3], [0.0, 0.0, -1.0]), &k, &flat(), 0);
    for (x, y, p) in frame.instance.enumerate_pixels() {
        let inside = (16..48).contains(&x) && (16..48).contains(&y);
        assert_eq!(p.0[0] != 0, inside, "({x}, {y})");
        if inside {
            // The diagonal runs through the centres of pixels with x + y = 64; they go to
            // the triangle for which it is a top-left edge: the lower one.
            let upper = x + y < 64;
            assert_eq!(p.0[0], if upper { 1 } else { 2 }, "({x}, {y})");
            assert_eq!(frame.depth_mm().get_pixel(x, y).0[0], 1000);
            assert_eq!(clipped(&frame, x, y), [255; 3]);
        } else {
            assert_eq!(clipped(&frame, x, y), [0; 3]);
        }
    }
    assert_eq!(count(&frame, 1) + count(&frame, 2), 32 * 32);
}

/// [`coverage_view`]'s intrinsics.
fn coverage_view_intrinsics() -> Intrinsics {
    Intrinsics {
        width: 64,
        height: 64,
        fx: 16.0,
        fy: 16.0,
        cx: 32.0,
        cy: 32.0,
        near: 0.1,
        far: 100.0,
    }
}
