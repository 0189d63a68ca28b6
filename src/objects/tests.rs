//! Objects tests on the default 768 × 768 city (layout → parse → lamps → place, builtin
//! facade sizes) with text, sign and mesh entries.

use std::collections::{BTreeMap, BTreeSet};

use image::RgbImage;

use super::ground_spots::travel;
use super::wall_text::{MIN_HEIGHT, TOP_CLEARANCE, WALL_OFFSET, Walls};
use super::*;
use crate::model::geometry::{KERB_Y, ROAD_Y, RoadRect, cross, dot, sub};
use crate::model::{Axis, Facade, Lamp, Roof};
use crate::spec::{Ground, ObjectKind, Palette, SignKind, TextCase};
use crate::test_support::{TestCity, test_city};

const SEED: u64 = 42;
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
        obj: include_bytes!("../../assets/models/bench.obj").to_vec(),
        mtl: Some(include_bytes!("../../assets/models/bench.mtl").to_vec()),
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

fn spec(kind: ObjectKind, label: &str, count: u32) -> ObjectSpec {
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
        ..spec(ObjectKind::Mesh, "bench", count)
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
            ..spec(ObjectKind::Text, "text", 40)
        },
        spec(ObjectKind::Sign, "traffic_sign", 25),
        bench(10, Ground::Sidewalk),
        ObjectSpec {
            label: "car".to_owned(),
            ..bench(6, Ground::Lane)
        },
    ]
}

#[test]
fn counts_names_and_labels() {
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
    let specs = [spec(ObjectKind::Text, "text", 5000)];
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
    let specs = [spec(ObjectKind::Sign, "traffic_sign", 3)];
    let inserted = run(&city, &specs).unwrap();
    assert_eq!(inserted.placed, vec![3]);
    assert!(inserted.shortfalls(&specs).is_empty());
}

#[test]
fn text_quads_lie_on_their_walls_without_overlapping() {
    let city = city();
    let specs = [ObjectSpec {
        letter_height: [0.5, 1.5],
        ..spec(ObjectKind::Text, "text", 150)
    }];
    let inserted = run(&city, &specs).unwrap();
    assert!(inserted.objects.len() > 100, "{}", inserted.objects.len());
    let walls = Walls::new(&input(&city, &specs));
    let heights: BTreeMap<u32, f64> = city
        .buildings
        .iter()
        .map(|b| {
            let f = &city.facades.facades[b.kind as usize];
            (b.id, f.height)
        })
        .collect();
    // Per wall: the plates found on it, as [u0, y0, u1, y1].
    let mut on_wall: BTreeMap<usize, Vec<[f64; 4]>> = BTreeMap::new();
    for (object, info) in inserted.objects.iter().zip(&inserted.info) {
        let mesh = &object.meshes[0];
        let points: Vec<[f64; 3]> = mesh.positions.iter().map(|p| p.map(f64::from)).collect();
        let (w, wall) = walls
            .walls()
            .iter()
            .enumerate()
            .find(|(_, wall)| {
                points.iter().all(|p| {
                    let out = (p[0] - wall.origin[0]) * wall.normal[0]
                        + (p[2] - wall.origin[1]) * wall.normal[1];
                    (out - WALL_OFFSET).abs() < 1e-4 && {
                        let u = (p[0] - wall.origin[0]) * wall.right[0]
                            + (p[2] - wall.origin[1]) * wall.right[1];
                        (-1e-4..=wall.length + 1e-4).contains(&u)
                    }
                })
            })
            .unwrap_or_else(|| panic!("{} is on no wall", object.name));
        let u: Vec<f64> = points
            .iter()
            .map(|p| {
                (p[0] - wall.origin[0]) * wall.right[0] + (p[2] - wall.origin[1]) * wall.right[1]
            })
            .collect();
        let y: Vec<f64> = points.iter().map(|p| p[1]).collect();
        let rect = [
            u.iter().copied().fold(f64::INFINITY, f64::min),
            y.iter().copied().fold(f64::INFINITY, f64::min),
            u.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            y.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        ];
        let top = KERB_Y + heights[&wall.building];
        assert!(rect[1] >= KERB_Y + MIN_HEIGHT - 1e-4, "{rect:?}");
        assert!(rect[3] <= top - TOP_CLEARANCE + 1e-4, "{rect:?}");
        // Faces outward: every triangle's winding and stored normal.
        for t in mesh.indices.chunks(3) {
            let p = |k: usize| points[t[k] as usize];
            let n = cross(sub(p(1), p(0)), sub(p(2), p(0)));
            let outward = [wall.normal[0], 0.0, wall.normal[1]];
            assert!(dot(n, outward) > 0.0);
            assert_eq!(mesh.normals[t[0] as usize].map(f64::from), outward);
        }
        // One box per word, each inside the plate, on the same plane, left to right.
        let text = info.text.as_deref().unwrap();
        assert_eq!(info.corners.len(), text.split(' ').count(), "{text}");
        for corners in &info.corners {
            for c in corners {
                let cu = (c[0] - wall.origin[0]) * wall.right[0]
                    + (c[2] - wall.origin[1]) * wall.right[1];
                assert!(rect[0] - 1e-4 <= cu && cu <= rect[2] + 1e-4);
                assert!(rect[1] - 1e-4 <= c[1] && c[1] <= rect[3] + 1e-4);
            }
            assert!(corners[0][1] > corners[3][1], "top above bottom");
        }
        let along = |c: [f64; 3]| {
            (c[0] - wall.origin[0]) * wall.right[0] + (c[2] - wall.origin[1]) * wall.right[1]
        };
        for pair in info.corners.windows(2) {
            assert!(
                along(pair[0][1]) <= along(pair[1][0]) + 1e-6,
                "{text}: words in order"
            );
        }
        on_wall.entry(w).or_default().push(rect);
    }
    assert!(
        on_wall.values().any(|r| r.len() > 1),
        "no wall holds two plates"
    );
    for rects in on_wall.values() {
        for (i, a) in rects.iter().enumerate() {
            for b in &rects[i + 1..] {
                let apart = a[2] <= b[0] || b[2] <= a[0] || a[3] <= b[1] || b[3] <= a[1];
                assert!(apart, "{a:?} overlaps {b:?}");
            }
        }
    }
}

#[test]
fn text_plates_share_atlas_pages_and_each_maps_to_its_own_plate() {
    let city = city();
    let specs = [
        ObjectSpec {
            letter_height: [0.3, 1.5],
            words: [1, 3],
            ..spec(ObjectKind::Text, "text", 150)
        },
        spec(ObjectKind::Text, "shop_sign", 30),
    ];
    let inserted = run(&city, &specs).unwrap();
    assert!(inserted.objects.len() > 150, "{}", inserted.objects.len());
    let pages: BTreeSet<u32> = inserted
        .objects
        .iter()
        .map(|o| o.meshes[0].material)
        .collect();
    // Shop frames and banner hems pad plates more than bare text did: still a few pages.
    assert!(pages.len() <= 6, "{} pages for 180 plates", pages.len());
    let decoded: BTreeMap<u32, RgbImage> = pages
        .iter()
        .map(|&m| {
            let t = inserted.materials[m as usize].texture.unwrap();
            (m, inserted.textures[t as usize].decode().unwrap())
        })
        .collect();
    // Per page: the pixel rectangles the plates' uvs cover, [x0, y0, x1, y1).
    let mut on_page: BTreeMap<u32, Vec<[u32; 4]>> = BTreeMap::new();
    for (object, info) in inserted.objects.iter().zip(&inserted.info) {
        let mesh = &object.meshes[0];
        let page = &decoded[&mesh.material];
        let (w, h) = (f64::from(page.width()), f64::from(page.height()));
        let px = |v: f32, size: f64| {
            let p = f64::from(v) * size;
            assert!(
                (p - p.round()).abs() < 1e-3,
                "{}: uv off the pixel grid",
                object.name
            );
            p.round() as u32
        };
        let xs: Vec<u32> = mesh.uvs.iter().map(|uv| px(uv[0], w)).collect();
        let ys: Vec<u32> = mesh.uvs.iter().map(|uv| px(uv[1], h)).collect();
        let rect = [
            *xs.iter().min().unwrap(),
            *ys.iter().min().unwrap(),
            *xs.iter().max().unwrap(),
            *ys.iter().max().unwrap(),
        ];
        // Pixels per metre agree along both sides: the rectangle is this plate's own.
        let quad = |k: usize| mesh.positions[k].map(f64::from);
        let (dx, dz) = (quad(1)[0] - quad(0)[0], quad(1)[2] - quad(0)[2]);
        let across = (dx * dx + dz * dz).sqrt();
        let up = (quad(2)[1] - quad(1)[1]).abs();
        let ratio = f64::from(rect[2] - rect[0]) / across / (f64::from(rect[3] - rect[1]) / up);
        assert!((ratio - 1.0).abs() < 0.02, "{}: {ratio}", object.name);
        // The padding around it repeats its edge pixels; inside, the text stands out from
        // the plate (or the painted wall).
        let pad = super::atlas_layout::PADDING;
        for y in rect[1] - pad..rect[3] + pad {
            for x in rect[0] - pad..rect[2] + pad {
                let edge = [x.clamp(rect[0], rect[2] - 1), y.clamp(rect[1], rect[3] - 1)];
                if edge != [x, y] {
                    assert_eq!(
                        page.get_pixel(x, y),
                        page.get_pixel(edge[0], edge[1]),
                        "{} at {x},{y}",
                        object.name
                    );
                }
            }
        }
        let colours: BTreeSet<[u8; 3]> = (rect[1]..rect[3])
            .flat_map(|y| (rect[0]..rect[2]).map(move |x| (x, y)))
            .map(|(x, y)| page.get_pixel(x, y).0)
            .collect();
        assert!(
            colours.len() > 2,
            "{}: {} colours",
            object.name,
            colours.len()
        );
        assert!(info.text.is_some());
        on_page.entry(mesh.material).or_default().push(rect);
    }
    for rects in on_page.values() {
        for (i, a) in rects.iter().enumerate() {
            for b in &rects[i + 1..] {
                let apart = a[2] <= b[0] || b[2] <= a[0] || a[3] <= b[1] || b[3] <= a[1];
                assert!(apart, "{a:?} overlaps {b:?}");
            }
        }
    }
    // Each entry has pages of its own.
    let labels_per_page: BTreeSet<(u32, &str)> = inserted
        .objects
        .iter()
        .map(|o| (o.meshes[0].material, o.class.as_str()))
        .collect();
    assert_eq!(labels_per_page.len(), pages.len());
}

#[test]
fn every_text_wall_faces_a_nearby_road() {
    let city = city();
    let walls = Walls::new(&input(&city, &[]));
    assert!(walls.walls().len() > 20);
    let rects: Vec<RoadRect> = city.layout.roads.iter().map(RoadRect::of).collect();
    for wall in walls.walls() {
        // Step out of the wall's middle: a road lies within 2 strips + 1 px (8 px strip).
        let mid = [
            wall.origin[0] + wall.right[0] * wall.length / 2.0,
            wall.origin[1] + wall.right[1] * wall.length / 2.0,
        ];
        let hit = (1..=17).any(|d| {
            let p = [
                mid[0] + wall.normal[0] * f64::from(d),
                mid[1] + wall.normal[1] * f64::from(d),
            ];
            rects
                .iter()
                .any(|r| r.x[0] <= p[0] && p[0] <= r.x[1] && r.y[0] <= p[1] && p[1] <= r.y[1])
        });
        assert!(hit, "{wall:?}");
    }
}

#[test]
fn signs_stand_on_the_strip_facing_oncoming_traffic() {
    let city = city();
    let inserted = run(&city, &[spec(ObjectKind::Sign, "traffic_sign", 40)]).unwrap();
    assert_eq!(inserted.objects.len(), 40);
    let strip = Palette::default().strip.0;
    let mut kinds = BTreeSet::new();
    for object in &inserted.objects {
        let [pole, face, back] = &object.meshes[..] else {
            panic!("{} has not 3 meshes", object.name)
        };
        kinds.insert(inserted.materials[face.material as usize].name.clone());
        assert!(inserted.materials[face.material as usize].texture.is_some());
        assert!(inserted.materials[back.material as usize].texture.is_none());
        // The pole's axis: the mean of its corners.
        let n = pole.positions.len() as f64;
        let foot = [
            pole.positions.iter().map(|p| f64::from(p[0])).sum::<f64>() / n,
            pole.positions.iter().map(|p| f64::from(p[2])).sum::<f64>() / n,
        ];
        let min_y = pole
            .positions
            .iter()
            .map(|p| f64::from(p[1]))
            .fold(f64::INFINITY, f64::min);
        assert!((min_y - KERB_Y).abs() < 1e-5);
        let pixel = city.image.get_pixel(foot[0] as u32, foot[1] as u32).0;
        assert_eq!(pixel, strip, "{} at {foot:?}", object.name);
        for lamp in &city.lamps {
            let (dx, dz) = (lamp.position[0] - foot[0], lamp.position[1] - foot[1]);
            let d = (dx * dx + dz * dz).sqrt();
            assert!(d >= 2.0, "{} {d} m from a lamp", object.name);
        }
        // The nearest road, the side the sign stands on, its lane's traffic.
        let (road, gap) = city
            .layout
            .roads
            .iter()
            .map(|r| {
                let rect = RoadRect::of(r);
                let dx = (rect.x[0] - foot[0]).max(foot[0] - rect.x[1]).max(0.0);
                let dy = (rect.y[0] - foot[1]).max(foot[1] - rect.y[1]).max(0.0);
                (r, dx.max(dy))
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap();
        assert!(gap <= 8.0);
        let high = match road.axis {
            Axis::Horizontal => foot[1] > road.line,
            Axis::Vertical => foot[0] > road.line,
        };
        let h = travel(road.axis, high);
        let normal = face.normals[0].map(f64::from);
        assert_eq!(
            [normal[0], normal[2]],
            [-h[0] + 0.0, -h[1] + 0.0],
            "{}",
            object.name
        );
        for t in face.indices.chunks(3) {
            let p = |k: usize| face.positions[t[k] as usize].map(f64::from);
            assert!(dot(cross(sub(p(1), p(0)), sub(p(2), p(0))), normal) > 0.0);
        }
    }
    assert!(kinds.len() >= 5, "{kinds:?}");
}

#[test]
fn signs_only_of_the_listed_kinds() {
    let city = city();
    let specs = [ObjectSpec {
        signs: vec![SignKind::Stop],
        ..spec(ObjectKind::Sign, "stop_sign", 5)
    }];
    let inserted = run(&city, &specs).unwrap();
    let faces: BTreeSet<&str> = inserted
        .objects
        .iter()
        .map(|o| {
            inserted.materials[o.meshes[1].material as usize]
                .name
                .as_str()
        })
        .collect();
    assert_eq!(faces, BTreeSet::from(["sign_stop"]));
    // One texture for all five stop signs.
    assert_eq!(inserted.textures.len(), 1);
}

#[test]
fn bench_asset_loads_with_its_materials_and_faces_out() {
    let city = city();
    let model = user_mesh::Model::load(BENCH, &city.meshes[BENCH]).unwrap();
    let names: Vec<&str> = model.materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["wood", "metal", "default"]);
    assert_eq!(model.materials[0].colour, [0.45, 0.28, 0.14]);
    assert_eq!(model.min_y, 0.0);
    let triangles: usize = model.parts.iter().map(|p| p.indices.len() / 3).sum();
    assert_eq!(triangles, 6 * 12);
    // Every triangle faces away from its box's centre: the file's faces wind CCW.
    for part in &model.parts {
        for t in part.indices.chunks(3) {
            let p = |k: usize| part.positions[t[k] as usize];
            let n = cross(sub(p(1), p(0)), sub(p(2), p(0)));
            let stored = part.normals[t[0] as usize];
            assert!(dot(n, stored) > 0.0);
        }
    }
}

#[test]
fn meshes_stand_on_sidewalks_and_in_lanes() {
    let city = city();
    let specs = [bench(12, Ground::Sidewalk), bench(8, Ground::Lane)];
    let inserted = run(&city, &specs).unwrap();
    assert_eq!(inserted.objects.len(), 20);
    let wood: Vec<&str> = inserted.materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(
        wood,
        [
            "bench_wood",
            "bench_metal",
            "bench_default",
            "bench_wood_2",
            "bench_metal_2",
            "bench_default_2"
        ]
    );
    let rects: Vec<RoadRect> = city.layout.roads.iter().map(RoadRect::of).collect();
    for (i, object) in inserted.objects.iter().enumerate() {
        let points: Vec<[f32; 3]> = object
            .meshes
            .iter()
            .flat_map(|m| m.positions.clone())
            .collect();
        let min_y = points
            .iter()
            .map(|p| f64::from(p[1]))
            .fold(f64::INFINITY, f64::min);
        let ground = if i < 12 { KERB_Y } else { ROAD_Y };
        assert!((min_y - ground).abs() < 1e-5, "{} {min_y}", object.name);
        let on_road = |p: &[f32; 3]| {
            let (x, z) = (f64::from(p[0]), f64::from(p[2]));
            rects
                .iter()
                .any(|r| r.x[0] <= x && x <= r.x[1] && r.y[0] <= z && z <= r.y[1])
        };
        if i < 12 {
            assert!(points.iter().all(|p| !on_road(p)), "{}", object.name);
        } else {
            assert!(points.iter().all(on_road), "{}", object.name);
        }
    }
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
    changed[2].kind = ObjectKind::Text;
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
fn merge_rebases_indices() {
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
            assert_eq!(scene.textures[t as usize].name, m.name);
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

/// A one-quad OBJ with vt, no normals, a textured MTL and a 2 × 2 PNG.
fn textured_quad() -> MeshFiles {
    let mut png = Vec::new();
    image::DynamicImage::ImageRgb8(RgbImage::from_pixel(2, 2, image::Rgb([9, 99, 199])))
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    MeshFiles {
        obj: b"mtllib q.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
               usemtl poster\nf 1/1 2/2 3/3 4/4\n"
            .to_vec(),
        mtl: Some(b"newmtl poster\nKd 1 1 1\nmap_Kd poster.png\n".to_vec()),
        textures: BTreeMap::from([("poster.png".to_owned(), png)]),
    }
}

#[test]
fn textured_models_keep_their_uvs_flipped_and_get_flat_normals() {
    let model = user_mesh::Model::load("q.obj", &textured_quad()).unwrap();
    let texture = model.materials[0].texture.as_ref().unwrap();
    assert_eq!((texture.width, texture.height), (2, 2));
    let part = &model.parts[0];
    assert_eq!(part.indices.len(), 6);
    for (p, uv) in part.positions.iter().zip(&part.uvs) {
        // vt (0, 0) is the image's bottom-left: v down is 1 there.
        assert_eq!([f64::from(uv[0]), f64::from(uv[1])], [p[0], 1.0 - p[1]]);
    }
    assert!(part.normals.iter().all(|n| *n == [0.0, 0.0, 1.0]));
}

#[test]
fn model_errors_name_the_model() {
    let city = city();
    let specs = [ObjectSpec {
        model: Some("cars/missing.obj".to_owned()),
        ..bench(1, Ground::Lane)
    }];
    let error = run(&city, &specs).unwrap_err();
    assert!(
        matches!(&error, ObjectsError::MissingModel { model } if model == "cars/missing.obj"),
        "{error:?}"
    );
    let mut no_texture = textured_quad();
    no_texture.textures.clear();
    let mut no_mtl = textured_quad();
    no_mtl.mtl = None;
    let mut bad_png = textured_quad();
    bad_png
        .textures
        .insert("poster.png".to_owned(), b"not a png".to_vec());
    let empty = MeshFiles {
        obj: b"# nothing\n".to_vec(),
        ..MeshFiles::default()
    };
    let cases = [
        (
            no_texture,
            "model q.obj: texture poster.png named by its MTL is missing",
        ),
        (
            no_mtl,
            "model q.obj: cannot read its MTL: the OBJ names an MTL file the build did not read",
        ),
        (
            bad_png,
            "model q.obj: texture poster.png is not a PNG or JPEG image",
        ),
        (empty, "model q.obj: has no triangles"),
    ];
    for (files, want) in cases {
        let error = user_mesh::Model::load("q.obj", &files).unwrap_err();
        assert!(error.to_string().starts_with(want), "{error}");
    }
}

/// The plate's rectangle `[u0, y0, u1, y1]` on `wall`, if its quad lies on that wall.
fn plate_rect(object: &SceneObject, wall: &wall_text::Wall) -> Option<[f64; 4]> {
    let points: Vec<[f64; 3]> = object.meshes[0]
        .positions
        .iter()
        .map(|p| p.map(f64::from))
        .collect();
    let along = |p: &[f64; 3]| {
        (p[0] - wall.origin[0]) * wall.right[0] + (p[2] - wall.origin[1]) * wall.right[1]
    };
    let on = points.iter().all(|p| {
        let out =
            (p[0] - wall.origin[0]) * wall.normal[0] + (p[2] - wall.origin[1]) * wall.normal[1];
        (out - WALL_OFFSET).abs() < 1e-4 && (-1e-4..=wall.length + 1e-4).contains(&along(p))
    });
    on.then(|| {
        let u: Vec<f64> = points.iter().map(along).collect();
        let y: Vec<f64> = points.iter().map(|p| p[1]).collect();
        let lo = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = |v: &[f64]| v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        [lo(&u), lo(&y), hi(&u), hi(&y)]
    })
}

#[test]
fn plates_keep_clear_of_windows_and_record_style_and_font() {
    let mut city = city();
    // Two window columns per floor.
    for f in &mut city.facades.facades {
        let n = f.floors as f32;
        f.windows = (0..f.floors)
            .flat_map(|row| {
                let (v0, v1) = ((row as f32 + 0.3) / n, (row as f32 + 0.8) / n);
                [[0.1, v0, 0.3, v1], [0.6, v0, 0.8, v1]]
            })
            .collect();
    }
    let specs = [ObjectSpec {
        letter_height: [0.3, 0.8],
        ..spec(ObjectKind::Text, "text", 300)
    }];
    let inserted = run(&city, &specs).unwrap();
    assert!(inserted.objects.len() > 100, "{}", inserted.objects.len());
    let walls = Walls::new(&input(&city, &specs));
    assert!(walls.walls().iter().all(|w| !w.windows.is_empty()));
    let mut styles = BTreeSet::new();
    let mut fonts = BTreeSet::new();
    for (object, info) in inserted.objects.iter().zip(&inserted.info) {
        let (wall, rect) = walls
            .walls()
            .iter()
            .find_map(|w| Some((w, plate_rect(object, w)?)))
            .unwrap_or_else(|| panic!("{} is on no wall", object.name));
        for win in &wall.windows {
            let apart =
                rect[2] <= win[0] || win[2] <= rect[0] || rect[3] <= win[1] || win[3] <= rect[1];
            assert!(apart, "{} {rect:?} covers window {win:?}", object.name);
        }
        let style = &info.attributes["text_style"];
        if style == "shop" {
            assert!(rect[1] <= KERB_Y + MIN_HEIGHT + plate_style::SHOP_BAND + 1e-9);
        }
        styles.insert(style.clone());
        fonts.insert(info.attributes["text_font"].clone());
    }
    assert_eq!(styles.len(), 3, "{styles:?}");
    assert!(fonts.len() >= 6, "{fonts:?}");
}

#[test]
fn a_wall_behind_another_building_does_not_face_the_road() {
    let city = city();
    let walls = Walls::new(&input(&city, &[]));
    for wall in walls.walls() {
        let mid = [
            wall.origin[0] + wall.right[0] * wall.length / 2.0,
            wall.origin[1] + wall.right[1] * wall.length / 2.0,
        ];
        // Straight out of the wall's middle, no other building before the road.
        let rects: Vec<RoadRect> = city.layout.roads.iter().map(RoadRect::of).collect();
        for d in 1..=17 {
            let p = [
                mid[0] + wall.normal[0] * f64::from(d),
                mid[1] + wall.normal[1] * f64::from(d),
            ];
            let in_road = rects
                .iter()
                .any(|r| r.x[0] <= p[0] && p[0] <= r.x[1] && r.y[0] <= p[1] && p[1] <= r.y[1]);
            if in_road {
                break;
            }
            let in_building = city.buildings.iter().any(|b| {
                let f = b.footprint;
                b.id != wall.building
                    && f64::from(f.x0) < p[0]
                    && p[0] < f64::from(f.x1)
                    && f64::from(f.y0) < p[1]
                    && p[1] < f64::from(f.y1)
            });
            assert!(!in_building, "{wall:?} looks into a building at {p:?}");
        }
    }
}

#[test]
fn a_word_file_replaces_the_built_in_words() {
    let mut city = city();
    city.meshes.insert(
        "words.txt".to_owned(),
        MeshFiles {
            obj: "# names\nÉcole Bäckerei\nPIZZA\n".as_bytes().to_vec(),
            ..MeshFiles::default()
        },
    );
    let specs = [ObjectSpec {
        words_file: Some("words.txt".to_owned()),
        case: TextCase::Upper,
        ..spec(ObjectKind::Text, "text", 40)
    }];
    let inserted = run(&city, &specs).unwrap();
    assert!(!inserted.info.is_empty());
    for info in &inserted.info {
        for word in info.text.as_deref().unwrap().split(' ') {
            assert!(["ÉCOLE", "BÄCKEREI", "PIZZA"].contains(&word), "{word}");
        }
    }
    let missing = [ObjectSpec {
        words_file: Some("nowhere.txt".to_owned()),
        ..spec(ObjectKind::Text, "text", 4)
    }];
    let result = run(&city, &missing);
    assert!(
        matches!(&result, Err(ObjectsError::MissingWords { file }) if file == "nowhere.txt"),
        "{:?}",
        result.err()
    );
}

#[test]
fn cars_and_trees_never_overlap_anything_standing() {
    let city = city();
    let specs = [
        spec(ObjectKind::Sign, "traffic_sign", 60),
        spec(ObjectKind::Tree, "tree", 200),
        spec(ObjectKind::Car, "car", 400),
    ];
    // At the example specs' scale: 4.4 m strips, so big crowns stand at the curb.
    let mpp = 0.55;
    let inserted = insert(&ObjectsInput {
        metres_per_pixel: mpp,
        ..input(&city, &specs)
    })
    .unwrap();
    // Ground boxes (x0, x1, z0, z1) and heights (y0, y1) of meshes, from their vertices.
    let bounds = |meshes: &[crate::model::Mesh]| {
        let mut b = [f64::MAX, f64::MIN, f64::MAX, f64::MIN];
        let mut y = [f64::MAX, f64::MIN];
        for p in meshes.iter().flat_map(|m| &m.positions) {
            let p = p.map(f64::from);
            b = [
                b[0].min(p[0]),
                b[1].max(p[0]),
                b[2].min(p[2]),
                b[3].max(p[2]),
            ];
            y = [y[0].min(p[1]), y[1].max(p[1])];
        }
        (b, y)
    };
    // A tree stands on its trunk (its first mesh): a curbside crown reaches over the
    // parking lane, above the cars (checked below).
    let boxes: Vec<(&str, [f64; 4])> = inserted
        .objects
        .iter()
        .map(|o| {
            let standing = if o.class == "tree" {
                &o.meshes[..1]
            } else {
                &o.meshes[..]
            };
            (o.class.as_str(), bounds(standing).0)
        })
        .collect();
    let car_tops: Vec<([f64; 4], f64)> = inserted
        .objects
        .iter()
        .filter(|o| o.class == "car")
        .map(|o| {
            let (b, y) = bounds(&o.meshes);
            (b, y[1])
        })
        .collect();
    let mut over_cars = 0;
    for crown in inserted.objects.iter().filter(|o| o.class == "tree") {
        let (c, y) = bounds(&crown.meshes[1..]);
        for (b, top) in &car_tops {
            if c[0] < b[1] && b[0] < c[1] && c[2] < b[3] && b[2] < c[3] {
                over_cars += 1;
                assert!(
                    y[0] >= top + 0.5,
                    "crown from {} over a car {top} tall",
                    y[0]
                );
            }
        }
    }
    assert!(over_cars > 0, "no crown reaches over a parked car");
    let cars: Vec<[f64; 4]> = boxes.iter().filter(|b| b.0 == "car").map(|b| b.1).collect();
    let trees = boxes.iter().filter(|b| b.0 == "tree").count();
    assert!(
        cars.len() > 200 && trees > 100,
        "{} cars, {trees} trees",
        cars.len()
    );
    for (i, a) in boxes.iter().enumerate() {
        for b in &boxes[i + 1..] {
            if a.0 == "traffic_sign" && b.0 == "traffic_sign" {
                continue;
            }
            let (p, q) = (a.1, b.1);
            // Lights and wheels stand out of a car's footprint by at most 3 cm.
            let overlap = p[0] + 0.03 < q[1] - 0.03
                && q[0] + 0.03 < p[1] - 0.03
                && p[2] + 0.03 < q[3] - 0.03
                && q[2] + 0.03 < p[3] - 0.03;
            let is_tree_pair = a.0 == "tree" || b.0 == "tree";
            // Crowns take circles, so a tree's box may overlap another tree's or a sign's
            // box at a corner; a car's box never overlaps any other object's.
            assert!(
                !overlap || is_tree_pair && a.0 != "car" && b.0 != "car",
                "{a:?} {b:?}"
            );
        }
    }
    // Every car stands wholly on a road.
    for c in &cars {
        let on_road = city.layout.roads.iter().any(|r| {
            let px = RoadRect::of(r);
            let rect = RoadRect {
                x: px.x.map(|v| v * mpp),
                y: px.y.map(|v| v * mpp),
            };
            rect.x[0] <= c[0] + 0.05
                && c[1] - 0.05 <= rect.x[1]
                && rect.y[0] <= c[2] + 0.05
                && c[3] - 0.05 <= rect.y[1]
        });
        assert!(on_road, "{c:?}");
    }
}

#[test]
fn people_stand_in_the_strips_apart_from_each_other_and_from_trunks() {
    let city = city();
    let specs = [
        spec(ObjectKind::Sign, "traffic_sign", 60),
        spec(ObjectKind::Tree, "tree", 200),
        spec(ObjectKind::Car, "car", 300),
        spec(ObjectKind::Person, "person", 300),
    ];
    let mpp = 0.55;
    let inserted = insert(&ObjectsInput {
        metres_per_pixel: mpp,
        ..input(&city, &specs)
    })
    .unwrap();
    // Where an object stands: the mean of its vertices on its lowest level (a person's
    // soles, a tree trunk's foot), and that level.
    let foot = |meshes: &[crate::model::Mesh]| -> ([f64; 2], f64) {
        let points: Vec<[f64; 3]> = meshes
            .iter()
            .flat_map(|m| &m.positions)
            .map(|p| p.map(f64::from))
            .collect();
        let low = points.iter().map(|p| p[1]).fold(f64::MAX, f64::min);
        let soles: Vec<&[f64; 3]> = points.iter().filter(|p| p[1] < low + 1e-4).collect();
        let n = soles.len() as f64;
        let mean = soles
            .iter()
            .fold([0.0, 0.0], |a, p| [a[0] + p[0] / n, a[1] + p[2] / n]);
        (mean, low)
    };
    let people: Vec<[f64; 2]> = inserted
        .objects
        .iter()
        .filter(|o| o.class == "person")
        .map(|o| {
            let (at, low) = foot(&o.meshes);
            assert!((low - KERB_Y).abs() < 1e-4, "{} stands at {low}", o.name);
            assert!(o.name.starts_with("person_"));
            at
        })
        .collect();
    assert_eq!(inserted.placed[3] as usize, people.len());
    assert!(people.len() >= 250, "{} people", people.len());
    let trunks: Vec<[f64; 2]> = inserted
        .objects
        .iter()
        .filter(|o| o.class == "tree")
        .map(|o| foot(&o.meshes[..1]).0)
        .collect();
    let apart = |a: [f64; 2], b: [f64; 2]| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
    // Soles centre 2 cm ahead of the spot a person took: 5 cm of slack.
    for (i, &p) in people.iter().enumerate() {
        for &q in &people[i + 1..] {
            assert!(apart(p, q) >= 2.0 * person::ROOM - 0.05, "{p:?} {q:?}");
        }
        for &t in &trunks {
            assert!(
                apart(p, t) >= person::ROOM + tree::TRUNK_ROOM - 0.05,
                "{p:?} {t:?}"
            );
        }
        // Off the roads: in a strip, at least CURB_ROOM from the curb.
        for r in &city.layout.roads {
            let px = RoadRect::of(r);
            let inside = (px.x[0] * mpp - person::CURB_ROOM + 0.05
                ..=px.x[1] * mpp + person::CURB_ROOM - 0.05)
                .contains(&p[0])
                && (px.y[0] * mpp - person::CURB_ROOM + 0.05
                    ..=px.y[1] * mpp + person::CURB_ROOM - 0.05)
                    .contains(&p[1]);
            assert!(!inside, "{p:?} on or by road {r:?}");
        }
    }
}

#[test]
fn street_name_signs_stand_at_corners_and_name_each_street_alike() {
    let city = city();
    let specs = [ObjectSpec {
        letter_height: [0.18, 0.24],
        ..spec(ObjectKind::StreetName, "text", 12)
    }];
    let inserted = run(&city, &specs).unwrap();
    assert_eq!(inserted.placed, [12]);
    let poles = inserted
        .objects
        .iter()
        .filter(|o| o.class == "pole")
        .count();
    let texts: Vec<usize> = (0..inserted.objects.len())
        .filter(|&i| inserted.objects[i].class == "text")
        .collect();
    assert_eq!((poles, texts.len()), (12, 48));
    // Each plate face: a name and a suffix, two word quads, above the pole's top, the
    // street style; the two faces of a plate look opposite ways.
    let mut names = BTreeSet::new();
    for &i in &texts {
        let info = &inserted.info[i];
        let text = info.text.as_deref().unwrap();
        let (word, suffix) = text.split_once(' ').unwrap();
        assert!(super::street_names::SUFFIXES.contains(&suffix), "{text}");
        assert!(!word.is_empty());
        names.insert(text.to_owned());
        assert_eq!(info.corners.len(), 2, "{text}");
        assert_eq!(info.attributes["text_style"], "street");
        for quad in &info.corners {
            for p in quad {
                assert!(p[1] > KERB_Y + super::street_names::POLE_HEIGHT, "{p:?}");
            }
        }
    }
    // One name per road: at most as many names as roads.
    assert!(names.len() <= city.layout.roads.len(), "{names:?}");
    assert!(names.len() >= 2);
    // Placing is deterministic; a larger count than corners falls short, never panics.
    assert_eq!(run(&city, &specs).unwrap(), inserted);
    let many = [spec(ObjectKind::StreetName, "text", 10_000)];
    let all = run(&city, &many).unwrap();
    assert!(all.placed[0] > 12 && all.placed[0] < 10_000);
}

#[test]
fn traffic_lights_stand_at_corners_with_one_head_along_each_road() {
    use super::traffic_lights::{HEAD_OFFSET, HEAD_SIZE, POLE_HEIGHT};
    let city = city();
    let specs = [spec(ObjectKind::TrafficLight, "traffic_light", 10)];
    let inserted = run(&city, &specs).unwrap();
    assert_eq!(inserted.placed, [10]);
    let objects = &inserted.objects;
    assert_eq!(objects.len(), 30);
    // Bounding box of an object's meshes, and of one mesh.
    let bounds = |meshes: &[Mesh]| {
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for p in meshes.iter().flat_map(|m| &m.positions) {
            for k in 0..3 {
                lo[k] = lo[k].min(f64::from(p[k]));
                hi[k] = hi[k].max(f64::from(p[k]));
            }
        }
        (lo, hi)
    };
    let centre = |(lo, hi): ([f64; 3], [f64; 3])| [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0);
    let mut states = BTreeSet::new();
    for pole_and_heads in objects.chunks(3) {
        let [pole, heads @ ..] = pole_and_heads else {
            unreachable!()
        };
        assert!(pole.name.starts_with("signal_pole_") && pole.class == "pole");
        let (lo, hi) = bounds(&pole.meshes);
        assert!((hi[1] - lo[1] - POLE_HEIGHT).abs() < 1e-4);
        let foot = centre((lo, hi));
        let mut offsets = Vec::new();
        let mut signals = Vec::new();
        for head in heads {
            assert!(head.name.starts_with("traffic_light_"), "{}", head.name);
            assert_eq!(head.class, "traffic_light");
            let i = objects.iter().position(|o| o.name == head.name).unwrap();
            let state = inserted.info[i].attributes["state"].clone();
            // The body: a head's height, HEAD_OFFSET out from the pole along x or z.
            let body = centre(bounds(&head.meshes[..1]));
            let d = [body[0] - foot[0], body[2] - foot[2]];
            assert!(
                (d[0].abs() - HEAD_OFFSET).abs() < 1e-3 && d[1].abs() < 1e-3
                    || (d[1].abs() - HEAD_OFFSET).abs() < 1e-3 && d[0].abs() < 1e-3,
                "{d:?}"
            );
            let (blo, bhi) = bounds(&head.meshes[..1]);
            assert!((bhi[1] - blo[1] - HEAD_SIZE[0]).abs() < 1e-4);
            // Three lenses in front of the body, red over amber over green; only the one
            // the state names glows.
            let lenses = &head.meshes[2..];
            assert_eq!(lenses.len(), 3);
            let mut lit = Vec::new();
            let mut last_y = f64::INFINITY;
            for (lens, colour) in lenses.iter().zip(["red", "amber", "green"]) {
                let material = &inserted.materials[lens.material as usize];
                assert!(material.name.starts_with(&format!("signal_{colour}_")));
                let c = centre(bounds(std::slice::from_ref(lens)));
                assert!(c[1] < last_y);
                last_y = c[1];
                let out = [c[0] - foot[0], c[2] - foot[2]];
                assert!(out[0] * d[0] + out[1] * d[1] > HEAD_OFFSET * HEAD_OFFSET);
                if material.emissive.iter().any(|&e| e > 0.0) {
                    lit.push(colour);
                }
            }
            assert_eq!(lit, [state.as_str()]);
            offsets.push(d);
            signals.push(state.clone());
            states.insert(state);
        }
        // One head along each road, away from each other; one road has red.
        assert!(offsets[0][0] * offsets[1][0] + offsets[0][1] * offsets[1][1] == 0.0);
        signals.sort();
        assert!(
            signals == ["green", "red"] || signals == ["amber", "red"],
            "{signals:?}"
        );
    }
    assert!(
        states.contains("red") && states.contains("green"),
        "{states:?}"
    );
    // Deterministic; a larger count than corners falls short, never panics.
    assert_eq!(run(&city, &specs).unwrap(), inserted);
    let many = [spec(ObjectKind::TrafficLight, "traffic_light", 10_000)];
    let all = run(&city, &many).unwrap();
    assert!(all.placed[0] >= 10 && all.placed[0] < 10_000);
}

#[test]
fn only_cars_in_the_driving_lanes_have_their_lights_on() {
    let city = city();
    for (parked, on) in [(1.0, false), (0.0, true)] {
        let specs = [ObjectSpec {
            parked,
            ..spec(ObjectKind::Car, "car", 30)
        }];
        let inserted = run(&city, &specs).unwrap();
        assert!(inserted.objects.len() > 5, "{}", inserted.objects.len());
        let material = |name: &str| inserted.materials.iter().find(|m| m.name == name);
        for lens in ["car_headlight", "car_taillight"] {
            let lit = material(lens);
            let off = material(&format!("{lens}_off"));
            assert_eq!(
                (lit.is_some(), off.is_some()),
                (on, !on),
                "{lens}, parked {parked}"
            );
            if let Some(lit) = lit {
                assert!(lit.emissive.iter().any(|&e| e > 0.0));
            }
            if let Some(off) = off {
                assert_eq!(off.emissive, [0.0; 3]);
            }
        }
    }
}

#[test]
fn bicycles_are_parked_on_the_strips_or_ridden_in_the_lanes_with_a_rider_each() {
    use super::bicycle::RIDDEN_HALF;
    use crate::spec::RIDER_CLASS;
    let city = city();
    let specs = [
        spec(ObjectKind::Car, "car", 200),
        ObjectSpec {
            parked: 0.4,
            ..spec(ObjectKind::Bicycle, "bicycle", 80)
        },
    ];
    let mpp = 0.55;
    let inserted = insert(&ObjectsInput {
        metres_per_pixel: mpp,
        ..input(&city, &specs)
    })
    .unwrap();
    let bounds = |meshes: &[Mesh]| {
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for p in meshes.iter().flat_map(|m| &m.positions) {
            for k in 0..3 {
                lo[k] = lo[k].min(f64::from(p[k]));
                hi[k] = hi[k].max(f64::from(p[k]));
            }
        }
        (lo, hi)
    };
    let cars: Vec<([f64; 3], [f64; 3])> = inserted
        .objects
        .iter()
        .filter(|o| o.class == "car")
        .map(|o| bounds(&o.meshes))
        .collect();
    let first = inserted
        .objects
        .iter()
        .position(|o| o.class != "car")
        .unwrap();
    let rest = &inserted.objects[first..];
    let (mut parked, mut ridden) = (0, 0);
    let mut k = 0;
    let mut footprints: Vec<([f64; 3], [f64; 3])> = Vec::new();
    while k < rest.len() {
        let bike = &rest[k];
        assert!(bike.name.starts_with("bicycle_"), "{}", bike.name);
        assert_eq!(bike.class, "bicycle");
        let (lo, hi) = bounds(&bike.meshes);
        let rider = rest.get(k + 1).filter(|o| o.class == RIDER_CLASS);
        if let Some(rider) = rider {
            // Ridden: on the road, along it (the long side along x or z), the rider over it.
            assert!((lo[1] - ROAD_Y).abs() < 1e-4, "{} at {}", bike.name, lo[1]);
            assert!(rider.name.starts_with("rider_"));
            let (rlo, rhi) = bounds(&rider.meshes);
            assert!(rlo[1] > lo[1] && rhi[1] > hi[1] + 0.5, "{rlo:?} {rhi:?}");
            let both = (
                [0, 1, 2].map(|i| lo[i].min(rlo[i])),
                [0, 1, 2].map(|i| hi[i].max(rhi[i])),
            );
            let size = [both.1[0] - both.0[0], both.1[2] - both.0[2]];
            let (long, short) = (size[0].max(size[1]), size[0].min(size[1]));
            assert!(
                long <= 2.0 * RIDDEN_HALF[0] + 1e-6 && long > 1.6,
                "{size:?}"
            );
            assert!(short <= 2.0 * RIDDEN_HALF[1] + 1e-6, "{size:?}");
            footprints.push(both);
            ridden += 1;
            k += 2;
        } else {
            // Parked: on the sidewalk.
            assert!((lo[1] - KERB_Y).abs() < 1e-4, "{} at {}", bike.name, lo[1]);
            footprints.push((lo, hi));
            parked += 1;
            k += 1;
        }
    }
    assert_eq!(inserted.placed[1] as usize, parked + ridden);
    assert!(
        parked >= 15 && ridden >= 30,
        "{parked} parked, {ridden} ridden"
    );
    // No bicycle overlaps a car or another bicycle (their boxes on the ground).
    let overlap = |a: &([f64; 3], [f64; 3]), b: &([f64; 3], [f64; 3])| {
        a.0[0] < b.1[0] && b.0[0] < a.1[0] && a.0[2] < b.1[2] && b.0[2] < a.1[2]
    };
    for (i, a) in footprints.iter().enumerate() {
        assert!(!cars.iter().any(|c| overlap(a, c)), "{a:?}");
        assert!(!footprints[i + 1..].iter().any(|b| overlap(a, b)), "{a:?}");
    }
    // Deterministic; a huge count falls short without panicking.
    assert_eq!(
        insert(&ObjectsInput {
            metres_per_pixel: mpp,
            ..input(&city, &specs)
        })
        .unwrap(),
        inserted
    );
    let many = [spec(ObjectKind::Bicycle, "bicycle", 100_000)];
    let all = run(&city, &many).unwrap();
    assert!(all.placed[0] > 80 && all.placed[0] < 100_000);
}

/// Every zebra crossing of `city` at `mpp` metres a pixel: its road's index and its
/// along-road range, metres.
fn zebras_of(city: &City, mpp: f64) -> Vec<(usize, [f64; 2])> {
    crate::model::geometry::zebras::road_stretches(&city.layout, mpp)
        .into_iter()
        .enumerate()
        .flat_map(|(i, s)| s.zebras.into_iter().map(move |(z, _)| (i, z)))
        .collect()
}

/// An object's middle seen from above (the mean of its vertices' x and z) and its lowest
/// point's height.
fn plan_middle_and_low(object: &SceneObject) -> ([f64; 2], f64) {
    let points: Vec<[f64; 3]> = object
        .meshes
        .iter()
        .flat_map(|m| &m.positions)
        .map(|p| p.map(f64::from))
        .collect();
    let low = points.iter().map(|p| p[1]).fold(f64::MAX, f64::min);
    let n = points.len() as f64;
    let mid = points
        .iter()
        .fold([0.0, 0.0], |a, p| [a[0] + p[0] / n, a[1] + p[2] / n]);
    (mid, low)
}

#[test]
fn crossers_walk_across_the_zebras_near_the_centre_line() {
    use super::person::ZEBRA_REACH;
    use crate::model::geometry::MARKING_Y;
    let city = city();
    let mpp = 0.55;
    let specs = [
        spec(ObjectKind::Car, "car", 200),
        ObjectSpec {
            crossing: 1.0,
            ..spec(ObjectKind::Person, "person", 40)
        },
    ];
    let inserted = insert(&ObjectsInput {
        metres_per_pixel: mpp,
        ..input(&city, &specs)
    })
    .unwrap();
    let zebras = zebras_of(&city, mpp);
    assert!(!zebras.is_empty());
    let people: Vec<&SceneObject> = inserted
        .objects
        .iter()
        .filter(|o| o.class == "person")
        .collect();
    assert_eq!(people.len(), 40);
    assert_eq!(inserted.placed[1], 40);
    for person in people {
        let (mid, low) = plan_middle_and_low(person);
        assert!((low - MARKING_Y).abs() < 1e-4, "{} at {low}", person.name);
        // Its middle lies on a zebra, within reach of the centre line.
        let on_zebra = zebras.iter().any(|&(i, [a, b])| {
            let road = &city.layout.roads[i];
            let (along, across) = match road.axis {
                Axis::Horizontal => (mid[0], mid[1]),
                Axis::Vertical => (mid[1], mid[0]),
            };
            a - 0.1 <= along
                && along <= b + 0.1
                && (across - road.line * mpp).abs() <= ZEBRA_REACH + 0.1
        });
        assert!(on_zebra, "{} at {mid:?}", person.name);
    }
    // Without crossers an entry places no one on the road.
    let specs = [spec(ObjectKind::Person, "person", 40)];
    let strips = run(&city, &specs).unwrap();
    for person in &strips.objects {
        let low = person
            .meshes
            .iter()
            .flat_map(|m| &m.positions)
            .map(|p| f64::from(p[1]))
            .fold(f64::MAX, f64::min);
        assert!((low - KERB_Y).abs() < 1e-4);
    }
}

#[test]
fn people_waiting_stand_at_the_zebras_ends_facing_the_road() {
    use super::person::{CURB_ROOM, ROOM, WAITING_DEPTH};
    let city = city();
    let mpp = 0.55;
    let zebras = zebras_of(&city, mpp);
    // Where a point in metres lies against zebra `i`'s road: along it, and how far past
    // its nearer curb (negative on the road).
    let beside = |i: usize, p: [f64; 2]| {
        let road = &city.layout.roads[i];
        let (along, across) = match road.axis {
            Axis::Horizontal => (p[0], p[1]),
            Axis::Vertical => (p[1], p[0]),
        };
        let (low, high) = (road.edges[0] * mpp, road.edges[1] * mpp);
        (along, (low - across).max(across - high))
    };
    let at_an_end = |p: [f64; 2], slack: f64| {
        zebras.iter().any(|&(i, [a, b])| {
            let (along, past) = beside(i, p);
            a - slack <= along
                && along <= b + slack
                && CURB_ROOM - slack <= past
                && past <= CURB_ROOM + WAITING_DEPTH + slack
        })
    };
    // The spots: at a zebra's end in the strip, apart, their travel straight at the road.
    let specs: [ObjectSpec; 0] = [];
    let objects_input = ObjectsInput {
        metres_per_pixel: mpp,
        ..input(&city, &specs)
    };
    let mut spots = super::ground_spots::GroundSpots::new(&objects_input);
    let mut rng = crate::rng::stream(7, "test", 0);
    let mut found = 0;
    for k in 0..20 {
        let from_curb = CURB_ROOM + WAITING_DEPTH * f64::from(k % 3) / 2.0;
        let Some(spot) = spots.zebra_kerb(&mut rng, ROOM, from_curb, 40) else {
            continue;
        };
        found += 1;
        assert!(at_an_end(spot.position, 1e-6), "{:?}", spot.position);
        let road = city
            .layout
            .roads
            .iter()
            .find(|r| r.id == spot.road)
            .unwrap();
        let step = spot.position.map(|v| v / mpp);
        let ahead = [step[0] + spot.travel[0], step[1] + spot.travel[1]];
        let centre = |q: [f64; 2]| match road.axis {
            Axis::Horizontal => (q[1] - road.line).abs(),
            Axis::Vertical => (q[0] - road.line).abs(),
        };
        assert!(
            (centre(step) - centre(ahead) - 1.0).abs() < 1e-9,
            "{:?} from {:?}",
            spot.travel,
            spot.position
        );
    }
    assert!(found >= 15, "{found}");
    // An entry that waits: all placed, on the kerb, and those at the ends are as many
    // as the ends hold (the others stand in the strips).
    let specs = [ObjectSpec {
        waiting: 1.0,
        ..spec(ObjectKind::Person, "person", 30)
    }];
    let inserted = insert(&ObjectsInput {
        metres_per_pixel: mpp,
        ..input(&city, &specs)
    })
    .unwrap();
    assert_eq!(inserted.placed[0], 30);
    let mut waiting = 0;
    for person in &inserted.objects {
        let (mid, low) = plan_middle_and_low(person);
        assert!((low - KERB_Y).abs() < 1e-4, "{} at {low}", person.name);
        if at_an_end(mid, ROOM) {
            waiting += 1;
        }
    }
    assert!(waiting >= 15, "{waiting} of 30 at the zebras' ends");
    // Without `waiting`, the same entry's people stand along the strips: few by chance
    // at a zebra's end.
    let specs = [spec(ObjectKind::Person, "person", 30)];
    let strips = insert(&ObjectsInput {
        metres_per_pixel: mpp,
        ..input(&city, &specs)
    })
    .unwrap();
    let by_chance = strips
        .objects
        .iter()
        .filter(|person| at_an_end(plan_middle_and_low(person).0, ROOM))
        .count();
    assert!(by_chance < waiting / 2, "{by_chance} vs {waiting}");
}

#[test]
fn zebra_spots_travel_across_their_road_and_never_overlap() {
    let city = city();
    let specs: [ObjectSpec; 0] = [];
    let input = input(&city, &specs);
    let mut spots = super::ground_spots::GroundSpots::new(&input);
    let mut rng = crate::rng::stream(7, "test", 0);
    let mut taken: Vec<[f64; 2]> = Vec::new();
    for _ in 0..30 {
        let Some(spot) = spots.zebra(&mut rng, 0.6, 2.4, 40) else {
            continue;
        };
        let road = city
            .layout
            .roads
            .iter()
            .find(|r| r.id == spot.road)
            .unwrap();
        let across = match road.axis {
            Axis::Horizontal => [0.0, 1.0],
            Axis::Vertical => [1.0, 0.0],
        };
        let d = spot.travel[0] * across[0] + spot.travel[1] * across[1];
        assert!((d.abs() - 1.0).abs() < 1e-12, "{:?}", spot.travel);
        for p in &taken {
            let gap =
                ((p[0] - spot.position[0]).powi(2) + (p[1] - spot.position[1]).powi(2)).sqrt();
            assert!(gap >= 1.2 - 1e-9, "{gap}");
        }
        taken.push(spot.position);
    }
    assert!(taken.len() >= 20, "{}", taken.len());
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
        ..spec(ObjectKind::Text, label, count)
    };
    // Interleaved kinds, with what the two groups could get wrong when replayed: street
    // names make `text_` objects as wall text does, a bench labelled `text` too; the
    // second text entry's atlas pages are named as the street names' pages (`text_street_
    // atlas_0`); two sign entries share their once-registered pole and faces.
    let specs = vec![
        ObjectSpec {
            letter_height: [0.18, 0.24],
            ..spec(ObjectKind::StreetName, "text", 4)
        },
        text("text", 20),
        ObjectSpec {
            label: "text".to_owned(),
            ..bench(5, Ground::Sidewalk)
        },
        spec(ObjectKind::Sign, "traffic_sign", 8),
        text("text_street", 12),
        spec(ObjectKind::Car, "car", 6),
        spec(ObjectKind::Sign, "traffic_sign", 4),
        spec(ObjectKind::Tree, "tree", 6),
        spec(ObjectKind::TrafficLight, "traffic_light", 2),
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
        materials.contains(&"text_street_atlas_0_2"),
        "{materials:?}"
    );
    assert_eq!(got, expected);
}
