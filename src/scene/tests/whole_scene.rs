//! The scene as a whole: its objects and their order, well-formed meshes, determinism,
//! bad facade input, scale.

use std::collections::BTreeSet;

use super::*;
use crate::model::geometry::{cross, dot, sub};

#[test]
fn default_city_has_one_object_per_plan_item_in_the_documented_order() {
    let city = city(None);
    let scene = scene_of(&city, None);
    assert!(city.buildings.len() > 500, "{}", city.buildings.len());
    assert!(!city.lamps.is_empty());
    let mut want = vec!["ground".to_owned(), "fields".to_owned(), "hills".to_owned()];
    want.extend(
        city.layout
            .blocks
            .iter()
            .map(|b| format!("block_{:04}", b.id)),
    );
    want.extend(
        city.layout
            .roads
            .iter()
            .map(|r| format!("road_{:04}", r.id)),
    );
    want.extend(
        city.layout
            .roads
            .iter()
            .map(|r| format!("marking_{:04}", r.id)),
    );
    want.extend(
        city.layout
            .blocks
            .iter()
            .map(|b| format!("sidewalk_{:04}", b.id)),
    );
    want.extend(
        city.buildings
            .iter()
            .map(|b| format!("building_{:04}", b.id)),
    );
    want.extend(city.lamps.iter().map(|l| format!("lamp_{:04}", l.id)));
    let names: Vec<&str> = scene.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, want);
    assert_eq!(names.iter().collect::<BTreeSet<_>>().len(), names.len());
    for object in &scene.objects {
        let prefix = match object.name.split('_').next().unwrap() {
            "fields" => "ground",
            prefix => prefix,
        };
        assert_eq!(object.class, prefix, "{}", object.name);
        assert!(
            !object.meshes.is_empty(),
            "{} has no triangles",
            object.name
        );
    }
    let count = |class| of_class(&scene, class).count();
    assert_eq!(count("building"), city.buildings.len());
    assert_eq!(count("lamp"), city.lamps.len());
    assert_eq!(count("road"), city.layout.roads.len());
    assert_eq!(count("block"), city.layout.blocks.len());
}

#[test]
fn meshes_are_well_formed_and_wound_towards_their_normals() {
    let city = city(None);
    let scene = scene_of(&city, None);
    let names: BTreeSet<&str> = scene.materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names.len(), scene.materials.len(), "material names unique");
    let names: BTreeSet<&str> = scene.textures.iter().map(|t| t.name.as_str()).collect();
    assert_eq!(names.len(), scene.textures.len(), "texture names unique");
    for material in &scene.materials {
        if let Some(t) = material.texture {
            assert!((t as usize) < scene.textures.len(), "{}", material.name);
        }
    }
    for object in &scene.objects {
        for mesh in &object.meshes {
            let n = mesh.positions.len();
            assert!((mesh.material as usize) < scene.materials.len());
            assert_eq!(mesh.normals.len(), n, "{}", object.name);
            assert_eq!(mesh.uvs.len(), n, "{}", object.name);
            assert_eq!(mesh.indices.len() % 3, 0, "{}", object.name);
            assert!(
                mesh.indices.iter().all(|&i| (i as usize) < n),
                "{}",
                object.name
            );
            for normal in &mesh.normals {
                let len = normal.iter().map(|c| c * c).sum::<f32>().sqrt();
                assert!((len - 1.0).abs() < 1e-5, "{}: {normal:?}", object.name);
            }
            for (t, normal) in triangles(mesh) {
                let g = cross(sub(t[1], t[0]), sub(t[2], t[0]));
                let area = dot(g, g).sqrt() / 2.0;
                assert!(area > 1e-6, "{}: degenerate {t:?}", object.name);
                // The winding agrees with the stored normal (same direction, within f32).
                assert!(
                    dot(g, normal) / (2.0 * area) > 0.999,
                    "{}: {t:?}",
                    object.name
                );
            }
        }
    }
}

#[test]
fn same_input_gives_the_same_scene() {
    let a = city(None);
    let b = city(None);
    let first = scene_of(&a, None);
    let second = scene_of(&b, None);
    assert_eq!(first, second);
    let bytes = |s: &Scene| s.textures.iter().map(|t| t.png.clone()).collect::<Vec<_>>();
    assert_eq!(bytes(&first), bytes(&second));
    // A different seed changes the tiled facades' choice, not the geometry's object list.
    let widths = [12.0, 25.0];
    let c = city(Some(&widths));
    let mut input = SceneInput {
        layout: &c.layout,
        lamps: &c.lamps,
        buildings: &c.buildings,
        facades: &c.facades,
        widths: Some(&widths),
        metres_per_pixel: 1.0,
        seed: SEED,
    };
    let s1 = build(&input);
    input.seed = SEED + 1;
    let s2 = build(&input);
    assert_ne!(s1, s2);
    let names = |s: &Scene| s.objects.iter().map(|o| o.name.clone()).collect::<Vec<_>>();
    assert_eq!(names(&s1), names(&s2));
}

#[test]
fn bad_facade_input_falls_back_without_panicking() {
    let mut city = city(None);
    // Kinds beyond the facade list, a roof index beyond the roofs, a zero-height facade.
    city.buildings[0].kind = 7;
    city.facades.facades[1].roof = 9;
    city.facades.facades[2].height = 0.0;
    let scene = scene_of(&city, None);
    assert!(scene.materials.iter().any(|m| m.name == "roof_plain"));
    let none = FacadeSet {
        facades: Vec::new(),
        roofs: Vec::new(),
    };
    city.facades = none;
    let scene = scene_of(&city, None);
    let building = of_class(&scene, "building").next().unwrap();
    let (lo, hi) = bounds(building);
    assert!((hi[1] - lo[1] - crate::model::geometry::PLAIN_HEIGHT).abs() < 1e-4);
    assert_eq!(
        scene.materials[building.meshes[0].material as usize].name,
        "facade_plain"
    );
}

#[test]
fn metres_per_pixel_scales_the_plan() {
    let city = city(None);
    let scene = build(&SceneInput {
        layout: &city.layout,
        lamps: &city.lamps,
        buildings: &city.buildings,
        facades: &city.facades,
        widths: None,
        metres_per_pixel: 0.5,
        seed: SEED,
    });
    let building = of_class(&scene, "building").next().unwrap();
    let fp = city.buildings[0].footprint;
    let (lo, hi) = bounds(building);
    assert_eq!(
        [lo[0], lo[2]],
        [f64::from(fp.x0) / 2.0, f64::from(fp.y0) / 2.0]
    );
    assert_eq!(
        [hi[0], hi[2]],
        [f64::from(fp.x1) / 2.0, f64::from(fp.y1) / 2.0]
    );
    let (_, ground_hi) = bounds(&scene.objects[0]);
    assert_eq!(ground_hi[0], 384.0 + crate::scene::GROUND_MARGIN);
}
