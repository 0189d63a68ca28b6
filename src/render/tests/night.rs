//! Night: point lights, street lamps, emissive surfaces and lit windows.

use std::collections::BTreeMap;

use super::*;

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

/// Three signs side by side on a dark wall, facing the camera: a backlit one (material 1),
/// a lamp-lit one (material 2, [`crate::model::LAMP_LIT_SUFFIX`]) and an unlit one
/// (material 3), all printed with the same page: pale paper, a dark stripe of letters.
fn three_signs(lit: bool) -> Scene {
    let page = RgbImage::from_fn(16, 16, |_, y| {
        if (6..10).contains(&y) {
            Rgb([20, 20, 20])
        } else {
            Rgb([230, 225, 210])
        }
    });
    let page = Texture::from_rgb("page", page);
    // Unlit, the first two are plain pages too.
    let mut backlit = material([1.0; 3], Some(0), [0.0; 3]);
    let mut lamp_lit = material([1.0; 3], Some(0), [0.0; 3]);
    if lit {
        backlit.emissive = [0.6; 3];
        backlit.emissive_textured = true;
        lamp_lit.name = format!("page_0{}", crate::model::LAMP_LIT_SUFFIX);
    }
    let sign = |m: u32, x: f32| {
        let c = [
            [x - 1.0, -1.0, -9.9],
            [x + 1.0, -1.0, -9.9],
            [x + 1.0, 1.0, -9.9],
            [x - 1.0, 1.0, -9.9],
        ];
        object("sign", vec![quad(m, c, UNIT_UV, [0.0, 0.0, 1.0])])
    };
    Scene {
        textures: vec![page],
        materials: vec![
            material([0.3; 3], None, [0.0; 3]),
            backlit,
            lamp_lit,
            material([1.0; 3], Some(0), [0.0; 3]),
        ],
        objects: vec![
            object("wall", vec![wall(-10.0, 20.0)]),
            sign(1, -3.0),
            sign(2, 0.0),
            sign(3, 3.0),
        ],
    }
}

/// Mean luma of the pixels of instance `id` in rows `rows`.
fn mean_luma(frame: &Frame, id: u32, rows: std::ops::Range<u32>) -> f64 {
    let (mut sum, mut n) = (0.0, 0.0);
    for (x, y, p) in frame.rgb().enumerate_pixels() {
        if rows.contains(&y) && frame.instance.get_pixel(x, y).0[0] == id {
            let [r, g, b] = p.0.map(f64::from);
            sum += 0.2126 * r + 0.7152 * g + 0.0722 * b;
            n += 1.0;
        }
    }
    assert!(n > 0.0, "instance {id} shows in rows {rows:?}");
    sum / n
}

#[test]
fn lit_signs_show_their_letters_at_night_and_nothing_changes_by_day() {
    let scene = three_signs(true);
    let prepared = prepare(&scene).unwrap();
    let k = Intrinsics::from_fov(192, 128, 1.2);
    let eye = pose([0.0; 3], [0.0, 0.0, -1.0]);
    let night = Lighting::night(lamps_of(&scene), None);
    let frame = render(&prepared, &eye, &k, &night, 1);
    // Signs are instances 2, 3 and 4; the rows they cover.
    let rows: Vec<u32> = (0..128)
        .filter(|&y| (0..192).any(|x| frame.instance.get_pixel(x, y).0[0] == 2))
        .collect();
    let (top, bottom) = (rows[0], rows[rows.len() - 1] + 1);
    assert!(bottom - top >= 8, "{top}..{bottom}");
    let [backlit, lamp_lit, unlit] = [2, 3, 4].map(|id| mean_luma(&frame, id, top..bottom));
    assert!(backlit > unlit + 40.0, "backlit {backlit} vs unlit {unlit}");
    assert!(
        lamp_lit > unlit + 20.0,
        "lamp-lit {lamp_lit} vs unlit {unlit}"
    );
    // The paper glows, the letters (the middle quarter of the page) stay dark.
    let middle = (top + bottom) / 2;
    let paper = mean_luma(&frame, 2, top + 1..top + 3);
    let letters = mean_luma(&frame, 2, middle - 1..middle + 1);
    assert!(paper > letters + 60.0, "paper {paper} vs letters {letters}");
    // By day the backlit face and the sign lamp are off: the same bytes as plain pages.
    let day = |scene: &Scene| {
        let day = Lighting::from_sun(&crate::render::sun::DAY, 3.0, lamps_of(scene), None);
        render(&prepare(scene).unwrap(), &eye, &k, &day, 1)
    };
    assert_eq!(day(&scene).rgb(), day(&three_signs(false)).rgb());
}

/// The sign lamps of `scene`, without their objects.
fn lamps_of(scene: &crate::model::Scene) -> Vec<Light> {
    crate::render::scene_lighting::sign_lamps(scene)
        .into_iter()
        .map(|(l, _)| l)
        .collect()
}
