//! Forward optical flow: each valid pixel lands on what the next frame shows of its
//! surface point; the sky and what the next frame hides are not valid; the KITTI PNG
//! holds the values.

use super::*;

/// The next frame's instance at the pixel a flow vector from `(x, y)` lands in.
fn landed(next: &Frame, x: u32, y: u32, uv: [f32; 2]) -> Option<u32> {
    let (w, h) = next.instance.dimensions();
    let tx = (f64::from(x) + 0.5 + f64::from(uv[0])).floor();
    let ty = (f64::from(y) + 0.5 + f64::from(uv[1])).floor();
    (tx >= 0.0 && ty >= 0.0 && tx < f64::from(w) && ty < f64::from(h))
        .then(|| next.instance.get_pixel(tx as u32, ty as u32).0[0])
}

#[test]
fn valid_flow_lands_on_the_same_surface_in_the_next_frame() {
    let prepared = prepare(&street_scene()).unwrap();
    let k = Intrinsics::from_fov(96, 72, 0.7);
    // Driving forward and turning a little: every pixel moves, the buildings' sides
    // come into view and nearer ones hide parts of farther ones.
    let here = pose([-3.0, 1.6, 12.0], [2.0, 1.4, -20.0]);
    let next = pose([-2.2, 1.6, 10.5], [4.0, 1.4, -20.0]);
    let frame = render(&prepared, &here, &k, &flat(), 1);
    let after = render(&prepared, &next, &k, &flat(), 1);
    let flow = flow(&prepared, &frame.depth, None, &here, &next, &k);
    let (mut valid, mut same, mut moved) = (0, 0, 0);
    for y in 0..k.height {
        for x in 0..k.width {
            let i = (y * k.width + x) as usize;
            let id = frame.instance.get_pixel(x, y).0[0];
            if id == 0 {
                assert!(!flow.valid[i], "sky at ({x}, {y}) has flow");
                continue;
            }
            if !flow.valid[i] {
                assert_eq!(flow.uv[i], [0.0; 2]);
                continue;
            }
            valid += 1;
            same += usize::from(landed(&after, x, y, flow.uv[i]) == Some(id));
            moved += usize::from(flow.uv[i][0].abs() + flow.uv[i][1].abs() > 0.5);
        }
    }
    let seen = frame
        .instance
        .as_raw()
        .iter()
        .filter(|id| **id != 0)
        .count();
    // The near ground leaves the image at the bottom as the car drives on.
    assert!(valid * 2 > seen, "{valid} valid pixels of {seen}");
    // The rest land on an edge pixel that shows the neighbour.
    assert!(
        same * 100 >= valid * 97,
        "{same} of {valid} land on their surface"
    );
    assert!(moved * 2 > valid, "{moved} of {valid} moved");
}

#[test]
fn a_still_camera_has_zero_flow_everywhere_but_the_sky() {
    let prepared = prepare(&street_scene()).unwrap();
    let k = Intrinsics::from_fov(64, 48, 0.7);
    let here = pose([0.0, 1.6, 10.0], [1.0, 1.4, -20.0]);
    let frame = render(&prepared, &here, &k, &flat(), 1);
    let flow = flow(&prepared, &frame.depth, None, &here, &here, &k);
    for (i, (&uv, &valid)) in flow.uv.iter().zip(&flow.valid).enumerate() {
        let sky = frame.instance.as_raw()[i] == 0;
        assert_eq!(valid, !sky, "pixel {i}");
        assert!(
            uv[0].abs() < 1e-3 && uv[1].abs() < 1e-3,
            "pixel {i}: {uv:?}"
        );
    }
}

#[test]
fn what_the_next_frame_hides_has_no_flow() {
    // A wall, and a box in front of it that the camera's sideways step brings in front of
    // a strip of the wall.
    let scene = Scene {
        textures: Vec::new(),
        materials: vec![material([0.5; 3], None, [0.0; 3])],
        objects: vec![
            object("wall", vec![wall(-20.0, 30.0)]),
            object("box", cuboid(0, [-1.0, -1.0, -9.0], [1.0, 1.0, -7.0])),
        ],
    };
    let prepared = prepare(&scene).unwrap();
    let k = Intrinsics::from_fov(80, 60, 0.6);
    let here = pose([0.0, 0.0, 0.0], [0.0, 0.0, -20.0]);
    let next = pose([1.5, 0.0, 0.0], [1.5, 0.0, -20.0]);
    let frame = render(&prepared, &here, &k, &flat(), 1);
    let after = render(&prepared, &next, &k, &flat(), 1);
    let flow = flow(&prepared, &frame.depth, None, &here, &next, &k);
    let (mut hidden, mut hidden_valid) = (0, 0);
    for y in 0..k.height {
        for x in 0..k.width {
            let i = (y * k.width + x) as usize;
            if frame.instance.get_pixel(x, y).0[0] != 1 {
                continue;
            }
            // Where the wall's point lands if nothing hid it: the wall moves 1.5 m × f / 20.
            let shift = [(-1.5 * k.fx / 20.0) as f32, 0.0];
            if landed(&after, x, y, shift) == Some(2) {
                hidden += 1;
                hidden_valid += usize::from(flow.valid[i]);
            }
        }
    }
    assert!(hidden > 20, "only {hidden} wall pixels go behind the box");
    // A pixel landing beside the box's edge may be judged by its neighbour's depth (the
    // four pixels round the landing point): at most one column of them.
    assert!(
        hidden_valid * 10 <= hidden,
        "{hidden_valid} of {hidden} hidden pixels valid"
    );
}

#[test]
fn the_kitti_png_holds_the_flow_in_64ths_and_the_valid_flag() {
    let flow = Flow {
        width: 3,
        height: 1,
        uv: vec![[1.5, -2.25], [0.0; 2], [-600.0, 0.01]],
        valid: vec![true, false, true],
    };
    let png = image::load_from_memory(&flow.kitti_png())
        .unwrap()
        .into_rgb16();
    assert_eq!(png.get_pixel(0, 0).0, [32768 + 96, 32768 - 144, 1]);
    assert_eq!(png.get_pixel(1, 0).0, [0, 0, 0]);
    // Beyond ±512 px the code clamps; 0.01 px rounds to 1/64.
    assert_eq!(png.get_pixel(2, 0).0, [0, 32769, 1]);
}
