//! Footprints (what an object would show with nothing in front) and visibility passes.

use super::*;
use crate::model::PixelBox;

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
