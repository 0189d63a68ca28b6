//! Objects tests on the default 768 × 768 city (layout → parse → lamps → place, builtin
//! facade sizes) with text, sign and mesh entries: the city and entry helpers they share,
//! one file per kind of object.

use std::collections::{BTreeMap, BTreeSet};

use image::RgbImage;

use super::*;
use crate::model::{Facade, Lamp, Roof};
use crate::spec::{EntryKind, Ground, TextCase};
use crate::test_support::{TestCity, test_city};

mod entries;
mod models;
mod people;
mod signs;
mod text;
mod vehicles;

const SEED: u64 = 42;

/// The box around every vertex of `meshes`: (min, max) corners.
fn mesh_bounds(meshes: &[Mesh]) -> ([f64; 3], [f64; 3]) {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in meshes.iter().flat_map(|m| &m.positions) {
        for k in 0..3 {
            lo[k] = lo[k].min(f64::from(p[k]));
            hi[k] = hi[k].max(f64::from(p[k]));
        }
    }
    (lo, hi)
}
const BENCH: &str = "models/bench.obj";

struct City {
    image: RgbImage,
    layout: ParsedLayout,
    lamps: Vec<Lamp>,
    buildings: Vec<Building>,
    facades: FacadeSet,
    meshes: BTreeMap<String, MeshFiles>,
}

/// Three facades 12, 15 and 21 m high (10, 14, 18 m wide).
fn facade_set() -> FacadeSet {
    let texture = Texture::from_rgb("t", RgbImage::new(4, 4));
    let facade = |name: &str, floors: u32, width: f64| Facade {
        name: name.to_owned(),
        floors,
        height: f64::from(floors) * 3.0,
        width,
        molding: [0, 0, 0],
        colour: [128, 128, 128],
        roof: 0,
        windows: Vec::new(),
        texture: texture.clone(),
    };
    FacadeSet {
        facades: vec![
            facade("a", 4, 10.0),
            facade("b", 5, 14.0),
            facade("c", 7, 18.0),
        ],
        roofs: vec![Roof {
            name: "r".to_owned(),
            colour: [0, 0, 0],
            tile: 3.0,
            texture,
        }],
    }
}

fn city() -> City {
    let facades = facade_set();
    let metric: Vec<f64> = facades.facades.iter().map(|f| f.width).collect();
    let TestCity {
        image,
        layout,
        lamps,
        buildings,
    } = test_city(SEED, &metric);
    let bench = MeshFiles {
        obj: include_bytes!("../../../assets/models/bench.obj").to_vec(),
        mtl: Some(include_bytes!("../../../assets/models/bench.mtl").to_vec()),
        textures: BTreeMap::new(),
    };
    City {
        image,
        layout,
        lamps,
        buildings,
        facades,
        meshes: BTreeMap::from([(BENCH.to_owned(), bench)]),
    }
}

fn spec(kind: EntryKind, label: &str, count: u32) -> ObjectSpec {
    toml::from_str(&format!(
        "kind = {:?}\nlabel = {label:?}\ncount = {count}\n",
        kind.name()
    ))
    .unwrap()
}

fn bench(count: u32, on: Ground) -> ObjectSpec {
    ObjectSpec {
        model: Some(BENCH.to_owned()),
        scale: [0.8, 1.2],
        on,
        ..spec(EntryKind::Mesh, "bench", count)
    }
}

fn run(city: &City, specs: &[ObjectSpec]) -> Result<Inserted, ObjectsError> {
    insert(&input(city, specs))
}

fn input<'a>(city: &'a City, specs: &'a [ObjectSpec]) -> ObjectsInput<'a> {
    ObjectsInput {
        specs,
        layout: &city.layout,
        lamps: &city.lamps,
        buildings: &city.buildings,
        facades: &city.facades,
        widths: None,
        meshes: &city.meshes,
        metres_per_pixel: 1.0,
        seed: SEED,
    }
}

fn all_kinds() -> Vec<ObjectSpec> {
    vec![
        ObjectSpec {
            case: TextCase::Mixed,
            words: [1, 3],
            ..spec(EntryKind::Text, "text", 40)
        },
        spec(EntryKind::Sign, "traffic_sign", 25),
        bench(10, Ground::Sidewalk),
        ObjectSpec {
            label: "car".to_owned(),
            ..bench(6, Ground::Lane)
        },
    ]
}

#[test]
fn trees_cars_and_people_name_the_variant_they_were_drawn_as() {
    let city = city();
    let specs = [
        spec(EntryKind::Tree, "tree", 12),
        spec(EntryKind::Car, "car", 12),
        spec(EntryKind::Person, "person", 12),
    ];
    let inserted = run(&city, &specs).unwrap();
    let mut seen = BTreeMap::new();
    for info in &inserted.info {
        let key = match info.label.as_str() {
            "tree" => "species",
            "car" => "body",
            "person" => "appearance",
            _ => continue,
        };
        let value = info.attributes.get(key);
        assert!(value.is_some_and(|v| !v.is_empty()), "{info:?}");
        seen.entry(key)
            .or_insert_with(BTreeSet::new)
            .insert(value.unwrap().clone());
    }
    assert_eq!(seen.len(), 3, "{seen:?}");
    // Drawn at random: twelve of each show more than one variant.
    assert!(seen.values().all(|v| v.len() > 1), "{seen:?}");
}

#[test]
fn the_default_tree_mix_spreads_over_every_species() {
    let city = city();
    let trees = ObjectSpec {
        plazas: 0.0,
        ..spec(EntryKind::Tree, "tree", 140)
    };
    let inserted = run(&city, &[trees]).unwrap();
    let mut counts: BTreeMap<String, usize> = BTreeMap::new();
    for info in &inserted.info {
        *counts
            .entry(info.attributes["species"].clone())
            .or_default() += 1;
    }
    let placed: usize = counts.values().sum();
    assert!(placed >= 100, "{counts:?}");
    // All seven, none taking over.
    assert_eq!(
        counts.len(),
        crate::spec::TreeSpecies::ALL.len(),
        "{counts:?}"
    );
    assert!(counts.values().all(|&n| n * 4 <= placed), "{counts:?}");
}
