//! Depth, occlusion between objects, back faces.

use super::*;

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
