//! Preparing scenes, and input a frame cannot be made of: bad scenes, unusable cameras,
//! empty images.

use std::sync::Arc;

use super::*;

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
