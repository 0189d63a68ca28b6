//! Determinism across thread counts, supersampling and edge antialiasing.

use std::collections::BTreeMap;

use super::*;

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
    let (prepared, k, eye) = off_grid_square();
    let grey = |f: &Frame| f.linear.iter().filter(|p| p[0] > 0.0 && p[0] < 1.0).count();
    assert_eq!(grey(&render(&prepared, &eye, &k, &flat(), 0)), 0);
    assert!(grey(&render(&prepared, &eye, &k, &flat(), 2)) > 10);
}

#[test]
fn edge_antialiasing_greys_edges_and_keeps_ids_and_depth_exact() {
    let (prepared, k, eye) = off_grid_square();
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

/// A white square on black with its edges off the pixel grid: the prepared scene, a 32 ×
/// 32 camera and its pose.
fn off_grid_square() -> (crate::render::PreparedScene, Intrinsics, CameraPose) {
    let scene = Scene {
        textures: Vec::new(),
        materials: vec![material([1.0; 3], None, [0.0; 3])],
        objects: vec![object("square", vec![wall(-3.0, 0.77)])],
    };
    let prepared = prepare(&scene).unwrap();
    let k = Intrinsics::from_fov(32, 32, 0.5);
    let eye = pose([0.1, 0.0, 0.0], [0.1, 0.0, -1.0]);
    (prepared, k, eye)
}
