//! Whole-frame tests on small hand-built scenes.

use std::collections::BTreeMap;
use std::sync::Arc;

use image::{Rgb, RgbImage};

use super::prepared_scene::Triangle;
use super::screen_triangle::{self, ScreenTri};
use super::view::View;
use super::*;
use crate::model::geometry::{cross, dot, sub};
use crate::model::{Material, Mesh, PixelBox, Scene, SceneObject, Texture};

pub(super) fn material(colour: [f32; 3], texture: Option<u32>, emissive: [f32; 3]) -> Material {
    Material {
        name: format!("m{}", texture.map_or(-1, i64::from)),
        colour,
        texture,
        emissive,
    }
}

/// A quad through corners `c` (in order around it), wound counter-clockwise around
/// `normal`, with vertex normals `normal`.
pub(super) fn quad(material: u32, c: [[f32; 3]; 4], uv: [[f32; 2]; 4], normal: [f32; 3]) -> Mesh {
    let g = cross(sub(c[1], c[0]), sub(c[2], c[0]));
    let indices = if dot(g, normal) >= 0.0 {
        vec![0, 1, 2, 0, 2, 3]
    } else {
        vec![0, 2, 1, 0, 3, 2]
    };
    Mesh {
        material,
        positions: c.to_vec(),
        normals: vec![normal; 4],
        uvs: uv.to_vec(),
        indices,
    }
}

/// A flat ground quad (material 0) reaching `half` metres from the origin each way, up.
fn ground_quad(half: f32) -> Mesh {
    let c = [
        [-half, 0.0, -half],
        [half, 0.0, -half],
        [half, 0.0, half],
        [-half, 0.0, half],
    ];
    quad(0, c, UNIT_UV, [0.0, 1.0, 0.0])
}

pub(super) const UNIT_UV: [[f32; 2]; 4] = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];

/// A closed box, every face wound counter-clockwise seen from outside.
pub(super) fn cuboid(material: u32, lo: [f32; 3], hi: [f32; 3]) -> Vec<Mesh> {
    let [x0, y0, z0] = lo;
    let [x1, y1, z1] = hi;
    let faces = [
        (
            [[x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [x1, y0, z1]],
            [1.0, 0.0, 0.0],
        ),
        (
            [[x0, y0, z0], [x0, y1, z0], [x0, y1, z1], [x0, y0, z1]],
            [-1.0, 0.0, 0.0],
        ),
        (
            [[x0, y1, z0], [x1, y1, z0], [x1, y1, z1], [x0, y1, z1]],
            [0.0, 1.0, 0.0],
        ),
        (
            [[x0, y0, z0], [x1, y0, z0], [x1, y0, z1], [x0, y0, z1]],
            [0.0, -1.0, 0.0],
        ),
        (
            [[x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]],
            [0.0, 0.0, 1.0],
        ),
        (
            [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0]],
            [0.0, 0.0, -1.0],
        ),
    ];
    faces
        .into_iter()
        .map(|(c, n)| quad(material, c, UNIT_UV, n))
        .collect()
}

pub(super) fn object(name: &str, meshes: Vec<Mesh>) -> SceneObject {
    SceneObject {
        name: name.into(),
        class: "test".into(),
        meshes,
    }
}

fn checker_texture(size: u32, cell: u32) -> Texture {
    let image = RgbImage::from_fn(size, size, |x, y| {
        if (x / cell + y / cell).is_multiple_of(2) {
            Rgb([255, 255, 255])
        } else {
            Rgb([0, 0, 0])
        }
    });
    Texture::from_rgb(format!("checker_{size}_{cell}"), image)
}

pub(super) fn pose(eye: [f64; 3], target: [f64; 3]) -> CameraPose {
    CameraPose::level(eye, target)
}

/// Colour = albedo: black sky, white ambient, no sun, no emission.
pub(super) fn flat() -> Lighting {
    Lighting {
        sky: Sky::flat([0.0; 3]),
        ambient: [1.0; 3],
        ground_ambient: [1.0; 3],
        sun_direction: [0.0, 1.0, 0.0],
        sun_colour: [0.0; 3],
        shadows: false,
        shadow_map_side: MAX_SHADOW_MAP_SIDE,
        shadow_strength: 1.0,
        ambient_occlusion: 0.0,
        lights: Vec::new(),
        emission: 0.0,
        windows: None,
        exposure: 1.0,
    }
}

/// Pixel `(x, y)` of the frame's linear colour written as sRGB with a plain clip (no tone
/// curve): the albedo, under [`flat`] lighting.
fn clipped(frame: &Frame, x: u32, y: u32) -> [u8; 3] {
    let table = crate::model::srgb::srgb();
    frame.linear[(y * frame.rgb().width() + x) as usize].map(|c| table.to_srgb8(c))
}

fn count(frame: &Frame, id: u32) -> usize {
    frame.instance.pixels().filter(|p| p.0[0] == id).count()
}

// ---- coverage and the fill rule -------------------------------------------------------

/// A 64 × 64 view looking at −z from the origin, 16 px per metre at depth 1.
fn coverage_view() -> View {
    let k = Intrinsics {
        width: 64,
        height: 64,
        fx: 16.0,
        fy: 16.0,
        cx: 32.0,
        cy: 32.0,
        near: 0.1,
        far: 100.0,
    };
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

// ---- depth, occlusion, back faces ------------------------------------------------------

fn wall(z: f32, half: f32) -> Mesh {
    quad(
        0,
        [
            [-half, -half, z],
            [half, -half, z],
            [half, half, z],
            [-half, half, z],
        ],
        UNIT_UV,
        [0.0, 0.0, 1.0],
    )
}

#[test]
fn depth_of_a_wall_is_its_distance_in_millimetres() {
    let scene = Scene {
        textures: Vec::new(),
        materials: vec![material([0.5; 3], None, [0.0; 3])],
        objects: vec![object("wall", vec![wall(-10.0, 100.0)])],
    };
    let prepared = prepare(&scene).unwrap();
    let k = Intrinsics::from_fov(64, 48, 1.0);
    let frame = render(&prepared, &pose([0.0; 3], [0.0, 0.0, -1.0]), &k, &flat(), 1);
    // A wall square to the view axis: the same depth in every pixel, corners included.
    assert!(frame.depth_mm().pixels().all(|p| p.0[0] == 10_000));
    assert!(frame.instance.pixels().all(|p| p.0[0] == 1));
    // Seen from 2.5 m further back and off to the side, still forward·d.
    let frame = render(
        &prepared,
        &pose([3.0, 1.0, 2.5], [3.0, 1.0, 0.0]),
        &k,
        &flat(),
        1,
    );
    assert!(frame.depth_mm().pixels().all(|p| p.0[0] == 12_500));
}

#[test]
fn the_nearer_box_owns_the_pixels_where_boxes_overlap() {
    let near_box = cuboid(0, [-1.0, -1.0, -6.0], [1.0, 1.0, -5.0]);
    let far_box = cuboid(0, [0.0, -2.0, -12.0], [3.0, 2.0, -10.0]);
    let k = Intrinsics::from_fov(64, 48, 0.5);
    let eye = pose([0.0; 3], [0.0, 0.0, -1.0]);
    let alone = |meshes: Vec<Mesh>| {
        let scene = Scene {
            textures: Vec::new(),
            materials: vec![material([0.5; 3], None, [0.0; 3])],
            objects: vec![object("box", meshes)],
        };
        render(&prepare(&scene).unwrap(), &eye, &k, &flat(), 1)
    };
    let near_alone = alone(near_box.clone());
    let far_alone = alone(far_box.clone());
    for near_first in [true, false] {
        let objects = if near_first {
            vec![
                object("near", near_box.clone()),
                object("far", far_box.clone()),
            ]
        } else {
            vec![
                object("far", far_box.clone()),
                object("near", near_box.clone()),
            ]
        };
        let (near_id, far_id) = if near_first { (1, 2) } else { (2, 1) };
        let scene = Scene {
            textures: Vec::new(),
            materials: vec![material([0.5; 3], None, [0.0; 3])],
            objects,
        };
        let frame = render(&prepare(&scene).unwrap(), &eye, &k, &flat(), 1);
        let mut overlap = 0;
        for (x, y, p) in frame.instance.enumerate_pixels() {
            let n = near_alone.instance.get_pixel(x, y).0[0] != 0;
            let f = far_alone.instance.get_pixel(x, y).0[0] != 0;
            let expected = if n {
                near_id
            } else if f {
                far_id
            } else {
                0
            };
            assert_eq!(p.0[0], expected, "({x}, {y}), near first: {near_first}");
            if n {
                assert_eq!(frame.depth_mm().get_pixel(x, y).0[0], 5000);
            }
            overlap += usize::from(n && f);
        }
        assert!(overlap > 20, "the boxes overlap in {overlap} pixels");
    }
}

/// The tight box and pixel count of `id` in an instance image.
fn visible_box(frame: &Frame, id: u32) -> Option<(PixelBox, u64)> {
    let mut found: Option<(PixelBox, u64)> = None;
    for (x, y, p) in frame.instance.enumerate_pixels() {
        if p.0[0] == id {
            let (b, n) = found.get_or_insert((PixelBox::at(x, y), 0));
            b.include(x, y);
            *n += 1;
        }
    }
    found
}

fn corners(b: PixelBox) -> [i64; 4] {
    [b.x_min, b.y_min, b.x_max, b.y_max].map(i64::from)
}

fn inside(a: PixelBox, b: [i64; 4]) -> bool {
    let a = corners(a);
    a[0] >= b[0] && a[1] >= b[1] && a[2] <= b[2] && a[3] <= b[3]
}

#[test]
fn footprints_are_what_an_object_shows_with_nothing_in_front() {
    let near_box = cuboid(0, [-1.0, -1.0, -6.0], [1.0, 1.0, -5.0]);
    let far_box = cuboid(0, [0.0, -2.0, -12.0], [3.0, 2.0, -10.0]);
    let k = Intrinsics::from_fov(64, 48, 0.5);
    let eye = pose([0.0; 3], [0.0, 0.0, -1.0]);
    let scene = |objects| Scene {
        textures: Vec::new(),
        materials: vec![material([0.5; 3], None, [0.0; 3])],
        objects,
    };
    // Off-screen, behind the camera, or wholly hidden behind the near box: not measured.
    let behind = cuboid(0, [-1.0, -1.0, 5.0], [1.0, 1.0, 6.0]);
    let hidden = cuboid(0, [-0.3, -0.3, -9.0], [0.3, 0.3, -8.5]);
    let both = prepare(&scene(vec![
        object("near", near_box.clone()),
        object("far", far_box.clone()),
        object("behind", behind),
        object("hidden", hidden),
    ]))
    .unwrap();
    let far_alone = prepare(&scene(vec![object("far", far_box)])).unwrap();
    for samples in [1, 2, 3] {
        let (frame, footprints) =
            render_measuring(&both, &eye, &k, &flat(), samples, &[1, 2, 3, 4]);
        assert_eq!(frame, render(&both, &eye, &k, &flat(), samples));
        let ids: Vec<u32> = footprints.iter().map(|f| f.id).collect();
        assert_eq!(ids, [1, 2], "samples {samples}");
        // The far box's footprint is exactly what it shows when alone.
        let alone = render(&far_alone, &eye, &k, &flat(), samples);
        let (b, n) = visible_box(&alone, 1).unwrap();
        let far = footprints[1];
        assert_eq!((far.bounds, far.pixels), (corners(b), n));
        assert_eq!(far.inside, far.pixels);
        // Behind the near box it shows fewer pixels, all inside the footprint.
        let (vb, vn) = visible_box(&frame, 2).unwrap();
        assert!(vn > 0 && vn < far.pixels, "{vn} of {}", far.pixels);
        assert!(inside(vb, far.bounds));
        // The unoccluded near box: its footprint is what it shows.
        let near = footprints[0];
        let (nb, nn) = visible_box(&frame, 1).unwrap();
        assert_eq!((corners(nb), nn), (near.bounds, near.pixels));
    }
    assert!(
        render_measuring(&both, &eye, &k, &flat(), 1, &[])
            .1
            .is_empty()
    );
}

#[test]
fn empty_images_render_without_panicking() {
    let prepared = prepare(&street_scene()).unwrap();
    let eye = pose([1.0, 1.7, 5.0], [0.0, 3.0, -20.0]);
    for (w, h) in [(0, 0), (0, 40), (40, 0), (1, 1)] {
        let k = Intrinsics::from_fov(w, h, 0.6);
        for samples in [0, 1, 2] {
            let (frame, footprints) =
                render_measuring(&prepared, &eye, &k, &Lighting::day(), samples, &[1, 2]);
            assert_eq!(frame.instance.dimensions(), (w, h));
            assert_eq!(frame.linear.len(), (w * h) as usize);
            assert!(footprints.len() <= (w * h) as usize);
        }
        let (shown, _) = crate::render::visibility(&prepared, &eye, &k, &[1]);
        assert_eq!(shown.depth.dimensions(), (w, h));
    }
}

#[test]
fn footprints_reach_past_the_image_edge() {
    // A 4 m square 5 m ahead, shifted so its left part is out of a 64 × 48 image.
    let scene = Scene {
        textures: Vec::new(),
        materials: vec![material([0.5; 3], None, [0.0; 3])],
        objects: vec![object("square", vec![wall(-5.0, 2.0)])],
    };
    let prepared = prepare(&scene).unwrap();
    let eye = pose([3.5, 0.0, 0.0], [3.5, 0.0, -1.0]);
    let k = Intrinsics::from_fov(64, 48, 0.5);
    for samples in [1, 2] {
        let (frame, footprints) = render_measuring(&prepared, &eye, &k, &flat(), samples, &[1]);
        let [f] = footprints[..] else {
            panic!("{footprints:?}")
        };
        let (shown, n) = visible_box(&frame, 1).unwrap();
        assert_eq!(shown.x_min, 0);
        assert_eq!(f.inside, n);
        assert!(f.bounds[0] < 0 && f.pixels > 2 * n, "{f:?}, {n} shown");
        // The same camera on an image three times as wide, its grid aligned: the square
        // shows whole, as large as the footprint says.
        let wide = Intrinsics {
            width: 3 * 64,
            cx: k.cx + 64.0,
            ..k
        };
        let whole = render(&prepared, &eye, &wide, &flat(), samples);
        let (b, all) = visible_box(&whole, 1).unwrap();
        assert_eq!(corners(b)[0] - 64, f.bounds[0]);
        assert!(all.abs_diff(f.pixels) <= 4, "{all} vs {}", f.pixels);
    }
}

#[test]
fn visibility_gives_a_frames_ids_depth_and_footprints_without_its_colours() {
    let prepared = prepare(&street_scene()).unwrap();
    // A size that is not a multiple of the tile: the last tiles are partial.
    let k = Intrinsics::from_fov(100, 70, 0.6);
    let ids: Vec<u32> = (1..=prepared.object_count() as u32).collect();
    for eye in [
        pose([1.0, 1.7, 5.0], [0.0, 3.0, -20.0]),
        pose([-20.0, 1.5, -5.0], [10.0, 2.0, -18.0]),
    ] {
        let (frame, footprints) = render_measuring(&prepared, &eye, &k, &Lighting::day(), 1, &ids);
        let (shown, measured) = crate::render::visibility(&prepared, &eye, &k, &ids);
        assert_eq!(shown.instance, frame.instance);
        assert_eq!(shown.depth, frame.depth);
        assert_eq!(measured, footprints);
        // Something of the street and of the sky is in view: the check compares content.
        assert!(shown.instance.pixels().any(|p| p.0[0] > 1));
        assert!(shown.depth.pixels().any(|p| p.0[0] == 0.0));
    }
}

#[test]
fn every_visible_pixel_of_a_street_lies_in_its_objects_footprint() {
    let prepared = prepare(&street_scene()).unwrap();
    let k = Intrinsics::from_fov(96, 64, 0.6);
    let eye = pose([1.0, 1.7, 5.0], [0.0, 3.0, -20.0]);
    let ids: Vec<u32> = (1..=prepared.object_count() as u32).collect();
    for samples in [1, 2] {
        let (frame, footprints) =
            render_measuring(&prepared, &eye, &k, &Lighting::day(), samples, &ids);
        for id in ids.iter().copied() {
            let shown = visible_box(&frame, id);
            let footprint = footprints.iter().find(|f| f.id == id);
            match (shown, footprint) {
                (Some((b, n)), Some(f)) => {
                    assert!(n <= f.pixels, "id {id}: {n} > {}", f.pixels);
                    assert!(inside(b, f.bounds));
                }
                (Some(_), None) => panic!("id {id} shows but has no footprint"),
                (None, _) => {}
            }
        }
    }
}

#[test]
fn closed_boxes_show_from_every_side_and_single_walls_only_from_the_front() {
    let scene = Scene {
        textures: Vec::new(),
        materials: vec![material([0.5; 3], None, [0.0; 3])],
        objects: vec![object("box", cuboid(0, [-1.0; 3], [1.0; 3]))],
    };
    let prepared = prepare(&scene).unwrap();
    let k = Intrinsics::from_fov(32, 32, 1.0);
    for eye in [
        [5.0, 0.0, 0.0],
        [-5.0, 0.0, 0.0],
        [0.0, 5.0, 0.0],
        [0.0, -5.0, 0.0],
        [0.0, 0.0, 5.0],
        [0.0, 0.0, -5.0],
        [3.0, 4.0, -2.0],
    ] {
        let frame = render(&prepared, &pose(eye, [0.0; 3]), &k, &flat(), 1);
        assert_eq!(frame.instance.get_pixel(16, 16).0[0], 1, "from {eye:?}");
        assert!(count(&frame, 1) > 50, "from {eye:?}");
    }

    // One wall facing +z; then the same wall wound the wrong way round but with outward
    // normals: the normals decide, so it still shows from the front.
    let mut reversed = wall(0.0, 1.0);
    reversed.indices = vec![0, 2, 1, 0, 3, 2];
    for (name, mesh) in [("wound right", wall(0.0, 1.0)), ("wound wrong", reversed)] {
        let scene = Scene {
            textures: Vec::new(),
            materials: vec![material([0.5; 3], None, [0.0; 3])],
            objects: vec![object("wall", vec![mesh])],
        };
        let prepared = prepare(&scene).unwrap();
        let front = render(&prepared, &pose([0.0, 0.0, 5.0], [0.0; 3]), &k, &flat(), 1);
        let back = render(&prepared, &pose([0.0, 0.0, -5.0], [0.0; 3]), &k, &flat(), 1);
        // ±3.2 px around the centre.
        assert!(count(&front, 1) >= 36, "{name}: front");
        assert_eq!(count(&back, 1), 0, "{name}: back");
    }
}

// ---- near-plane clipping and perspective ----------------------------------------------

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

// ---- determinism and supersampling ------------------------------------------------------

fn street_scene() -> Scene {
    let ground = quad(
        0,
        [
            [-200.0, 0.0, -200.0],
            [200.0, 0.0, -200.0],
            [200.0, 0.0, 200.0],
            [-200.0, 0.0, 200.0],
        ],
        [[-50.0, -50.0], [50.0, -50.0], [50.0, 50.0], [-50.0, 50.0]],
        [0.0, 1.0, 0.0],
    );
    let mut objects = vec![object("ground", vec![ground])];
    for i in 0..10 {
        let x = -30.0 + 7.0 * i as f32;
        let z = -15.0 - 3.0 * (i % 3) as f32;
        objects.push(object(
            &format!("building_{i}"),
            cuboid(1 + (i % 2), [x, 0.0, z - 5.0], [x + 5.0, 6.0 + i as f32, z]),
        ));
    }
    objects.push(object(
        "lamp",
        cuboid(3, [2.0, 4.0, -8.0], [2.4, 4.3, -7.6]),
    ));
    Scene {
        textures: vec![checker_texture(16, 2), checker_texture(64, 8)],
        materials: vec![
            material([0.4, 0.4, 0.45], Some(0), [0.0; 3]),
            material([0.9, 0.8, 0.7], Some(1), [0.0; 3]),
            material([0.6, 0.7, 0.9], Some(0), [0.0; 3]),
            material([0.1; 3], None, [4.0, 3.5, 2.5]),
        ],
        objects,
    }
}

fn street_night() -> Lighting {
    Lighting::night(
        vec![Light::point([2.2, 3.9, -7.8], [3.0, 2.6, 2.0], 15.0)],
        Some(LitWindows {
            boxes: BTreeMap::from([(1, vec![[0.1, 0.1, 0.4, 0.4]])]),
            share: 0.5,
            seed: 3,
            colour: [1.0, 0.8, 0.4],
        }),
    )
}

#[test]
fn output_bytes_do_not_depend_on_the_thread_count() {
    let prepared = prepare(&street_scene()).unwrap();
    let k = Intrinsics::from_fov(96, 64, 0.6);
    let eye = pose([1.0, 1.7, 5.0], [0.0, 3.0, -20.0]);
    for lighting in [Lighting::day(), street_night()] {
        for samples in [1, 2] {
            let run = |threads: usize| {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap()
                    .install(|| render(&prepared, &eye, &k, &lighting, samples))
            };
            let one = run(1);
            let four = run(4);
            assert_eq!(
                one.encode(&one.rgb(), DepthFormat::Mm16),
                four.encode(&four.rgb(), DepthFormat::Mm16),
                "samples {samples}"
            );
            assert_eq!(one, four);
            // Several objects are in view, and every id is a real object's.
            let ids: std::collections::BTreeSet<u32> =
                one.instance.pixels().map(|p| p.0[0]).collect();
            assert!(ids.len() > 5, "{ids:?}");
            assert!(ids.iter().all(|&id| id as usize <= prepared.object_count()));
        }
    }
}

#[test]
fn supersampling_smooths_colour_but_keeps_ids_exact() {
    let prepared = prepare(&street_scene()).unwrap();
    let k = Intrinsics::from_fov(96, 64, 0.6);
    let eye = pose([1.0, 1.7, 5.0], [0.0, 3.0, -20.0]);
    let plain = render(&prepared, &eye, &k, &Lighting::day(), 1);
    let smooth = render(&prepared, &eye, &k, &Lighting::day(), 2);
    assert_eq!(smooth.rgb().dimensions(), (96, 64));
    assert_ne!(plain.rgb(), smooth.rgb());
    // Ids of the supersampled frame come from single samples: each is an object's id,
    // and they mostly agree with the plain frame.
    let same = plain
        .instance
        .pixels()
        .zip(smooth.instance.pixels())
        .filter(|(a, b)| a == b)
        .count();
    assert!(same * 10 > 96 * 64 * 9, "{same}");
    let plain_ids: std::collections::BTreeSet<u32> =
        plain.instance.pixels().map(|p| p.0[0]).collect();
    assert!(
        smooth
            .instance
            .pixels()
            .all(|p| plain_ids.contains(&p.0[0]))
    );

    // A white square on black, with edges off the pixel grid: supersampled edges are grey.
    let scene = Scene {
        textures: Vec::new(),
        materials: vec![material([1.0; 3], None, [0.0; 3])],
        objects: vec![object("square", vec![wall(-3.0, 0.77)])],
    };
    let prepared = prepare(&scene).unwrap();
    let k = Intrinsics::from_fov(32, 32, 0.5);
    let eye = pose([0.1, 0.0, 0.0], [0.1, 0.0, -1.0]);
    let grey = |f: &Frame| f.linear.iter().filter(|p| p[0] > 0.0 && p[0] < 1.0).count();
    assert_eq!(grey(&render(&prepared, &eye, &k, &flat(), 0)), 0);
    assert!(grey(&render(&prepared, &eye, &k, &flat(), 2)) > 10);
}

#[test]
fn edge_antialiasing_greys_edges_and_keeps_ids_and_depth_exact() {
    // A white square on black, edges off the pixel grid.
    let scene = Scene {
        textures: Vec::new(),
        materials: vec![material([1.0; 3], None, [0.0; 3])],
        objects: vec![object("square", vec![wall(-3.0, 0.77)])],
    };
    let prepared = prepare(&scene).unwrap();
    let k = Intrinsics::from_fov(32, 32, 0.5);
    let eye = pose([0.1, 0.0, 0.0], [0.1, 0.0, -1.0]);
    let hard = render(&prepared, &eye, &k, &flat(), 0);
    let soft = render(&prepared, &eye, &k, &flat(), 1);
    assert_eq!(hard.instance, soft.instance);
    assert_eq!(hard.depth, soft.depth);
    // Only pixels along the square's outline change, each towards its neighbour across it.
    let mut changed = 0;
    for (i, (a, b)) in hard.linear.iter().zip(&soft.linear).enumerate() {
        if a == b {
            continue;
        }
        changed += 1;
        assert!(b[0] > 0.0 && b[0] < 1.0, "{i}: {b:?}");
        let (x, y) = ((i % 32) as u32, (i / 32) as u32);
        let id = hard.instance.get_pixel(x, y).0[0];
        let differs = |nx: i64, ny: i64| {
            (0..32).contains(&nx)
                && (0..32).contains(&ny)
                && hard.instance.get_pixel(nx as u32, ny as u32).0[0] != id
        };
        let (x, y) = (i64::from(x), i64::from(y));
        assert!(
            differs(x - 1, y) || differs(x + 1, y) || differs(x, y - 1) || differs(x, y + 1),
            "({x}, {y}) is not on an edge"
        );
    }
    assert!(changed > 10, "{changed}");
    // The same for the street: ids and depth are the rasterizer's.
    let prepared = prepare(&street_scene()).unwrap();
    let k = Intrinsics::from_fov(96, 64, 0.6);
    let eye = pose([1.0, 1.7, 5.0], [0.0, 3.0, -20.0]);
    let hard = render(&prepared, &eye, &k, &Lighting::day(), 0);
    let soft = render(&prepared, &eye, &k, &Lighting::day(), 1);
    assert_eq!((&hard.instance, &hard.depth), (&soft.instance, &soft.depth));
    assert_ne!(hard.rgb(), soft.rgb());
}

// ---- night ------------------------------------------------------------------------------

#[test]
fn a_point_light_brightens_near_pixels_only() {
    let scene = Scene {
        textures: Vec::new(),
        materials: vec![material([0.5; 3], None, [0.0; 3])],
        objects: vec![object("wall", vec![wall(-10.0, 50.0)])],
    };
    let prepared = prepare(&scene).unwrap();
    let k = Intrinsics::from_fov(64, 48, 1.0);
    let eye = pose([0.0; 3], [0.0, 0.0, -1.0]);
    let dark = render(&prepared, &eye, &k, &Lighting::night(Vec::new(), None), 1);
    let lamp = Light::point([-5.0, 0.0, -9.0], [2.0, 2.0, 2.0], 4.0);
    let lit = render(&prepared, &eye, &k, &Lighting::night(vec![lamp], None), 1);
    // The light is 1 m in front of the wall at x = −5: pixel x = 32 − 24 · 0.5 = 20.
    let near = |f: &Frame| f.rgb().get_pixel(20, 24).0[0];
    assert!(
        near(&lit) > near(&dark) + 50,
        "{} vs {}",
        near(&lit),
        near(&dark)
    );
    // Beyond the range (x ≥ −1 on the wall): unchanged, to the byte.
    for x in 32..64 {
        for y in 0..48 {
            assert_eq!(
                lit.rgb().get_pixel(x, y),
                dark.rgb().get_pixel(x, y),
                "({x}, {y})"
            );
        }
    }
}

#[test]
fn emissive_surfaces_glow_without_any_light() {
    let scene = Scene {
        textures: Vec::new(),
        materials: vec![material([0.0; 3], None, [1.0, 0.5, 0.0])],
        objects: vec![object("lamp_head", cuboid(0, [-1.0; 3], [1.0; 3]))],
    };
    let prepared = prepare(&scene).unwrap();
    let k = Intrinsics::from_fov(16, 16, 1.0);
    let eye = pose([0.0, 0.0, 5.0], [0.0; 3]);
    let mut none = flat();
    none.ambient = [0.0; 3];
    let off = render(&prepared, &eye, &k, &none, 1);
    none.emission = 1.0;
    let on = render(&prepared, &eye, &k, &none, 1);
    assert_eq!(clipped(&off, 8, 8), [0, 0, 0]);
    assert_eq!(clipped(&on, 8, 8), [255, 188, 0]);
}

#[test]
fn lit_windows_glow_inside_their_boxes_only() {
    let facade = Texture::from_rgb("facade_a", RgbImage::from_pixel(8, 8, Rgb([60, 60, 60])));
    let scene = Scene {
        textures: vec![facade],
        materials: vec![material([1.0; 3], Some(0), [0.0; 3])],
        objects: vec![object("building", vec![wall(-5.0, 2.0)])],
    };
    let prepared = prepare(&scene).unwrap();
    let k = Intrinsics::from_fov(32, 32, 0.5);
    let eye = pose([0.0; 3], [0.0, 0.0, -1.0]);
    let windows = |share| LitWindows {
        boxes: BTreeMap::from([(0, vec![[0.25, 0.25, 0.75, 0.75]])]),
        share,
        seed: 1,
        colour: [1.0, 0.8, 0.4],
    };
    let off = render(
        &prepared,
        &eye,
        &k,
        &Lighting::night(Vec::new(), Some(windows(0.0))),
        1,
    );
    let on = render(
        &prepared,
        &eye,
        &k,
        &Lighting::night(Vec::new(), Some(windows(1.0))),
        1,
    );
    // The wall spans pixels 4–27; its middle half (the window) is pixels 10–21.
    assert!(on.rgb().get_pixel(16, 16).0[0] > off.rgb().get_pixel(16, 16).0[0] + 100);
    assert_eq!(on.rgb().get_pixel(6, 16), off.rgb().get_pixel(6, 16));
    assert_eq!(on.rgb().get_pixel(16, 25), off.rgb().get_pixel(16, 25));
}

// ---- preparing -------------------------------------------------------------------------

#[test]
fn bad_scenes_are_errors_not_panics() {
    let good = || Scene {
        textures: vec![checker_texture(4, 1)],
        materials: vec![material([1.0; 3], Some(0), [0.0; 3])],
        objects: vec![object("wall", vec![wall(0.0, 1.0)])],
    };
    let mut broken_png = good();
    broken_png.textures[0].png = Arc::new(vec![1, 2, 3]);
    let mut missing_texture = good();
    missing_texture.materials[0].texture = Some(5);
    let mut missing_material = good();
    missing_material.objects[0].meshes[0].material = 2;
    let mut bad_index = good();
    bad_index.objects[0].meshes[0].indices[4] = 9;
    type Check = fn(&RenderError) -> bool;
    let cases: Vec<(Scene, Check)> = vec![
        (broken_png, |e| matches!(e, RenderError::Texture { .. })),
        (missing_texture, |e| {
            matches!(e, RenderError::MissingTexture { texture: 5, .. })
        }),
        (missing_material, |e| {
            matches!(e, RenderError::MissingMaterial { material: 2, .. })
        }),
        (bad_index, |e| {
            matches!(e, RenderError::BadIndex { index: 9, .. })
        }),
    ];
    for (scene, expected) in cases {
        let err = prepare(&scene).err().expect("an error");
        assert!(expected(&err), "{err}");
    }
    let ok = prepare(&good()).unwrap();
    assert_eq!((ok.object_count(), ok.triangle_count()), (1, 2));
    // Past the old 16-bit limit is fine: ids are 24-bit. (A scene of 2^24 objects, which
    // `prepare` refuses, takes gigabytes to build; the bound is MAX_OBJECTS.)
    assert_eq!(MAX_OBJECTS, 16_777_215);
    let mut many = good();
    many.objects = (0..65_537)
        .map(|i| object(&format!("o{i}"), Vec::new()))
        .collect();
    assert_eq!(prepare(&many).unwrap().object_count(), 65_537);
}

/// Chains made ahead are taken for the very PNGs they were made from and for no other:
/// the frame is the one `prepare` gives, and a texture whose bytes were swapped since is
/// decoded afresh.
#[test]
fn mip_chains_made_ahead_serve_only_their_own_textures() {
    let scene = street_scene();
    assert!(scene.textures.len() >= 2, "a textured street");
    let mips = TextureMips::of(&scene.textures);
    assert_eq!(mips.len(), scene.textures.len());
    let k = Intrinsics::from_fov(96, 64, 1.0);
    let eye = pose([0.0, 1.7, 6.0], [0.0, 1.5, -10.0]);
    let frame = |prepared: &PreparedScene| render(prepared, &eye, &k, &flat(), 1).rgb();
    let fresh = frame(&prepare(&scene).unwrap());
    assert_eq!(frame(&prepare_with(&scene, &mips).unwrap()), fresh);

    let mut swapped = scene.clone();
    for t in &mut swapped.textures {
        *t = checker_texture(8, 1).renamed(t.name.clone());
    }
    let expected = frame(&prepare(&swapped).unwrap());
    assert_ne!(expected, fresh, "the swap shows");
    assert_eq!(frame(&prepare_with(&swapped, &mips).unwrap()), expected);
}

#[test]
fn unusable_cameras_render_sky() {
    let prepared = prepare(&street_scene()).unwrap();
    let k = Intrinsics::from_fov(8, 6, 1.0);
    let same = pose([1.0; 3], [1.0; 3]);
    let frame = render(&prepared, &same, &k, &Lighting::day(), 1);
    assert!(frame.instance.pixels().all(|p| p.0[0] == 0));
    let bad = Intrinsics { fx: -1.0, ..k };
    let frame = render(
        &prepared,
        &pose([0.0; 3], [0.0, 0.0, -1.0]),
        &bad,
        &Lighting::day(),
        0,
    );
    assert_eq!(frame.rgb().dimensions(), (8, 6));
    assert!(frame.depth_mm().pixels().all(|p| p.0[0] == 0));
}

/// A grey ground plane and a wall facing the eye 30 m ahead, under `lights` at night.
fn night_street(lights: Vec<Light>, windows: Option<LitWindows>) -> Frame {
    let ground = ground_quad(40.0);
    let scene = Scene {
        textures: Vec::new(),
        materials: vec![material([0.5; 3], None, [0.0; 3])],
        objects: vec![
            object("ground", vec![ground]),
            object("wall", vec![wall(-30.0, 20.0)]),
        ],
    };
    let prepared = prepare(&scene).unwrap();
    let k = Intrinsics::from_fov(64, 48, 1.2);
    let eye = pose([0.0, 1.5, 0.0], [0.0, 1.5, -10.0]);
    render(&prepared, &eye, &k, &Lighting::night(lights, windows), 1)
}

/// The frame's luminance at output pixel `(x, y)`, linear.
fn lum_at(f: &Frame, x: u32, y: u32) -> f32 {
    develop::luminance(f.linear[(y * f.rgb().width() + x) as usize])
}

#[test]
fn a_street_lamp_lights_a_pool_below_it_and_nothing_above() {
    let dark = night_street(Vec::new(), None);
    let lamp = Light::street_lamp([0.0, 5.7, -8.0], LAMP_COLOUR, 25.0);
    let lit = night_street(vec![lamp], None);
    // Rows of column 32 by what they show: the ground at about `z` metres from the eye.
    let row = |z: f32| {
        (24..48)
            .min_by(|&a, &b| {
                let d = |y| (lit.depth.get_pixel(32, y).0[0] - z).abs();
                d(a).total_cmp(&d(b))
            })
            .unwrap()
    };
    let gain = |y| lum_at(&lit, 32, y) - lum_at(&dark, 32, y);
    // About the noon sun's strength (× albedo 0.5) under the head, a pool falling off
    // around it: a twentieth 12 m away, a quarter 7 m away.
    let under = gain(row(8.0));
    assert!((0.3..0.8).contains(&under), "{under}");
    assert!(gain(row(20.0)) > 0.0 && gain(row(20.0)) < under / 10.0);
    assert!(gain(row(1.3)) < under / 2.0);
    // The wall 22 m behind the lamp, far above the head: unlit (the head is shielded).
    let high = (0..24)
        .find(|&y| lit.depth.get_pixel(32, y).0[0] > 0.0)
        .unwrap();
    assert_eq!(lum_at(&lit, 32, high), lum_at(&dark, 32, high));
}

#[test]
fn a_lit_window_spills_light_onto_the_ground_in_front_of_it() {
    let ground = ground_quad(40.0);
    let facade = Texture::from_rgb("facade_a", RgbImage::from_pixel(8, 8, Rgb([60, 60, 60])));
    let scene = Scene {
        textures: vec![facade],
        materials: vec![
            material([0.5; 3], None, [0.0; 3]),
            material([1.0; 3], Some(0), [0.0; 3]),
        ],
        objects: vec![
            object("ground", vec![ground]),
            object("building", vec![quad_material(wall(-10.0, 4.0), 1)]),
        ],
    };
    // One window, its centre 1.6 m above the ground (the wall spans y −4 to 4, v down).
    let windows = LitWindows {
        boxes: BTreeMap::from([(0, vec![[0.3, 0.2, 0.7, 0.4]])]),
        share: 1.0,
        seed: 1,
        colour: WINDOW_COLOUR,
    };
    let spill = windows.spill_lights(&scene);
    assert_eq!(spill.len(), 1);
    let prepared = prepare(&scene).unwrap();
    let k = Intrinsics::from_fov(64, 48, 1.2);
    let eye = pose([0.0, 1.5, 0.0], [0.0, 1.5, -10.0]);
    let off = render(
        &prepared,
        &eye,
        &k,
        &Lighting::night(Vec::new(), Some(windows.clone())),
        1,
    );
    let on = render(
        &prepared,
        &eye,
        &k,
        &Lighting::night(spill, Some(windows)),
        1,
    );
    let row = |z: f32| {
        (24..48)
            .min_by(|&a, &b| {
                let d = |y| (on.depth.get_pixel(32, y).0[0] - z).abs();
                d(a).total_cmp(&d(b))
            })
            .unwrap()
    };
    let gain = |y| lum_at(&on, 32, y) - lum_at(&off, 32, y);
    // 2 m in front of the wall: a warm pool; 8 m in front: next to nothing.
    let near = gain(row(8.0));
    assert!(near > 0.1, "{near}");
    assert!(gain(row(2.0)) < near / 20.0, "{near} {}", gain(row(2.0)));
    let p = on.linear[(row(8.0) * 64 + 32) as usize];
    assert!(p[0] > p[2], "warm: {p:?}");
}

fn quad_material(mut mesh: Mesh, material: u32) -> Mesh {
    mesh.material = material;
    mesh
}
