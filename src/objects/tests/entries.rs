//! What `insert` makes of a list of entries: counts and shortfalls, names and labels,
//! determinism, merging into the scene, groups placed side by side.

use std::collections::BTreeSet;

use super::*;
use crate::objects::wall_text::Walls;

#[test]
fn objects_carry_their_entrys_label_a_unique_name_and_in_range_indices() {
    let city = city();
    let inserted = run(&city, &all_kinds()).unwrap();
    let count = |label: &str| inserted.info.iter().filter(|i| i.label == label).count();
    // The default city has room for all of them.
    assert_eq!(count("text"), 40);
    assert_eq!(count("traffic_sign"), 25);
    assert_eq!(count("bench"), 10);
    assert_eq!(count("car"), 6);
    assert_eq!(inserted.objects.len(), inserted.info.len());
    let names: BTreeSet<&str> = inserted.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names.len(), inserted.objects.len());
    for (object, info) in inserted.objects.iter().zip(&inserted.info) {
        assert_eq!(object.class, info.label);
        let prefix = match info.label.as_str() {
            "text" => "text_",
            "traffic_sign" => "sign_",
            "pole" => "sign_pole_",
            "bench" => "bench_",
            _ => "car_",
        };
        assert!(object.name.starts_with(prefix), "{}", object.name);
        assert_eq!(info.text.is_some(), info.label == "text");
        assert!(!object.meshes.is_empty());
        for mesh in &object.meshes {
            assert!((mesh.material as usize) < inserted.materials.len());
            assert_eq!(mesh.positions.len(), mesh.normals.len());
            // Plain-coloured solids carry no uvs; textured meshes one per vertex.
            assert!(mesh.uvs.is_empty() || mesh.positions.len() == mesh.uvs.len());
            assert!(
                mesh.indices
                    .iter()
                    .all(|&i| (i as usize) < mesh.positions.len())
            );
        }
    }
    for m in &inserted.materials {
        assert!(
            m.texture
                .is_none_or(|t| (t as usize) < inserted.textures.len())
        );
    }
}

#[test]
fn count_is_an_upper_bound_when_the_city_is_full() {
    let mut city = city();
    // Only one building that faces a road is left.
    let first = Walls::new(&input(&city, &[])).walls()[0].building;
    city.buildings.retain(|b| b.id == first);
    let specs = [spec(EntryKind::Text, "text", 5000)];
    let inserted = run(&city, &specs).unwrap();
    assert!(!inserted.objects.is_empty());
    assert!(inserted.objects.len() < 5000);
    // The shortfall is told with the numbers.
    assert_eq!(inserted.placed, vec![inserted.objects.len() as u32]);
    let warnings = inserted.shortfalls(&specs);
    assert_eq!(warnings.len(), 1);
    let expected = format!("placed {} of 5,000", inserted.objects.len());
    assert_eq!(warnings[0].code, "objects-short");
    assert_eq!(warnings[0].key.as_deref(), Some("objects[0].count"));
    let message = &warnings[0].message;
    assert!(
        message.starts_with("objects[0] (text, label \"text\")"),
        "{message}"
    );
    assert!(message.contains(&expected), "{message}");
}

#[test]
fn an_entry_that_places_all_it_asks_for_has_no_shortfall() {
    let city = city();
    let specs = [spec(EntryKind::Sign, "traffic_sign", 3)];
    let inserted = run(&city, &specs).unwrap();
    assert_eq!(inserted.placed, vec![3]);
    assert!(inserted.shortfalls(&specs).is_empty());
}

#[test]
fn same_seed_same_objects_and_entries_are_independent() {
    let city = city();
    let specs = all_kinds();
    let a = run(&city, &specs).unwrap();
    let b = run(&city, &specs).unwrap();
    assert_eq!(a, b);
    for t in 0..a.textures.len() {
        assert_eq!(a.textures[t].png, b.textures[t].png);
    }
    // Entry 1 changed (and a new entry 2): entry 0's text objects do not move.
    let mut changed = specs.clone();
    changed[1].count = 3;
    changed[2].kind = EntryKind::Text;
    let c = run(&city, &changed).unwrap();
    let texts = |i: &Inserted| -> Vec<SceneObject> {
        i.objects
            .iter()
            .filter(|o| o.class == "text")
            .take(40)
            .cloned()
            .collect()
    };
    assert_eq!(texts(&a), texts(&c));
    // Nor do their atlas pages: same materials, same pixels.
    let pages = |i: &Inserted| -> Vec<(Material, Vec<u8>)> {
        let used: BTreeSet<u32> = texts(i).iter().map(|o| o.meshes[0].material).collect();
        used.into_iter()
            .map(|m| {
                let material = i.materials[m as usize].clone();
                let png = i.textures[material.texture.unwrap() as usize].png.to_vec();
                (material, png)
            })
            .collect()
    };
    assert!(!pages(&a).is_empty());
    assert_eq!(pages(&a), pages(&c));
    // And another seed moves them.
    let other = insert(&ObjectsInput {
        seed: SEED + 1,
        ..input(&city, &specs)
    })
    .unwrap();
    assert_ne!(texts(&a), texts(&other));
}

#[test]
fn merging_into_a_scene_rebases_indices_and_renames_clashing_materials() {
    let city = city();
    let inserted = run(&city, &all_kinds()).unwrap();
    let mut scene = crate::test_support::scene(
        &city.layout,
        &city.lamps,
        &city.buildings,
        &city.facades,
        SEED,
    );
    let before = scene.clone();
    let first = merge(&mut scene, inserted.clone());
    assert_eq!(first, before.objects.len());
    assert_eq!(scene.objects.len(), first + inserted.objects.len());
    assert_eq!(scene.objects[..first], before.objects[..]);
    for (merged, original) in scene.objects[first..].iter().zip(&inserted.objects) {
        assert_eq!(merged.name, original.name);
        for (m, o) in merged.meshes.iter().zip(&original.meshes) {
            let material = &scene.materials[m.material as usize];
            let source = &inserted.materials[o.material as usize];
            assert_eq!(material.colour, source.colour);
            assert_eq!(
                material
                    .texture
                    .map(|t| scene.textures[t as usize].png.clone()),
                source
                    .texture
                    .map(|t| inserted.textures[t as usize].png.clone())
            );
            assert_eq!(m.positions, o.positions);
        }
    }
    let names: BTreeSet<&str> = scene.materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names.len(), scene.materials.len());
    for m in &scene.materials {
        if let Some(t) = m.texture {
            // A tinted building material shares its untinted one's texture.
            let base = m
                .name
                .rsplit_once("_tint")
                .map_or(m.name.as_str(), |(b, _)| b);
            assert_eq!(scene.textures[t as usize].name, base);
        }
    }

    // A clash with a scene name is renamed, texture and all.
    let mut clash = inserted.clone();
    clash.materials[0].name = "asphalt".to_owned();
    let mut scene = before.clone();
    merge(&mut scene, clash);
    let renamed = &scene.materials[before.materials.len()];
    assert_eq!(renamed.name, "asphalt_2");
}

/// Every entry placed in turn in one [`Placing`]: what [`insert`] must give.
fn in_turn(city: &City, specs: &[ObjectSpec]) -> Inserted {
    let input = input(city, specs);
    let PlacedEntries { placing, shares } =
        place_entries(&input, |_| true).map_err(|(_, e)| e).unwrap();
    let mut out = placing.out;
    (out.textures, out.materials) = placing.book.finish();
    out.placed = shares.into_iter().map(|s| s.unwrap().placed).collect();
    out
}

#[test]
fn groups_placed_side_by_side_give_what_placing_in_turn_gives() {
    let city = city();
    let text = |label: &str, count| ObjectSpec {
        letter_height: [0.3, 0.8],
        ..spec(EntryKind::Text, label, count)
    };
    // Interleaved kinds, with what the two groups could get wrong when replayed: street
    // names make `text_` objects as wall text does, a bench labelled `text` too; the
    // second text entry's atlas pages are named as the street names' pages (`text_street_
    // atlas_0`); two sign entries share their once-registered pole and faces.
    let specs = vec![
        ObjectSpec {
            letter_height: [0.18, 0.24],
            ..spec(EntryKind::StreetName, "text", 4)
        },
        text("text", 20),
        ObjectSpec {
            label: "text".to_owned(),
            ..bench(5, Ground::Sidewalk)
        },
        spec(EntryKind::Sign, "traffic_sign", 8),
        text("text_street", 12),
        spec(EntryKind::Car, "car", 6),
        spec(EntryKind::Sign, "traffic_sign", 4),
        spec(EntryKind::Tree, "tree", 6),
        spec(EntryKind::TrafficLight, "traffic_light", 2),
    ];
    let expected = in_turn(&city, &specs);
    let got = run(&city, &specs).unwrap();
    // The cases above happen: the same names and material names asked for by both groups.
    let named = |prefix: &str| {
        expected
            .objects
            .iter()
            .filter(|o| o.name.starts_with(prefix))
            .count()
    };
    assert!(named("text_") > 36, "street-name faces, plates and benches");
    let materials: Vec<&str> = expected.materials.iter().map(|m| &m.name[..]).collect();
    assert!(
        materials
            .iter()
            .any(|m| m.starts_with("text_street_atlas") && m.ends_with("_2")),
        "{materials:?}"
    );
    assert_eq!(got, expected);
}
