//! Scene tests on the default 768 × 768 city (layout → parse → lamps → place) with a small
//! hand-made facade set.

use std::collections::BTreeSet;

use image::{Rgb, RgbImage};

use super::{SceneInput, build};
use crate::model::geometry::{KERB_Y, RoadRect, cross, dot, sub};
use crate::model::{
    Building, Facade, FacadeSet, Lamp, Mesh, ParsedLayout, Roof, Scene, SceneObject, Texture,
};
use crate::test_support::{TestCity, test_city};

const SEED: u64 = 42;

fn image(w: u32, h: u32, tint: [u8; 3]) -> RgbImage {
    RgbImage::from_fn(w, h, |x, y| {
        let window = x % 8 >= 2 && x % 8 < 6 && y % 8 >= 2 && y % 8 < 6;
        if window { Rgb([40, 60, 90]) } else { Rgb(tint) }
    })
}

/// Three facades (10, 14, 18 m wide; 12, 15, 21 m high) and two roofs.
fn facade_set() -> FacadeSet {
    let facade = |name: &str, floors: u32, width: f64, roof: u32, tint| Facade {
        name: name.to_owned(),
        floors,
        height: f64::from(floors) * 3.0,
        width,
        molding: tint,
        roof,
        windows: Vec::new(),
        texture: Texture::from_rgb(format!("facade_{name}"), image(24, 32, tint)),
    };
    let roof = |name: &str, colour, tile| Roof {
        name: name.to_owned(),
        colour,
        tile,
        texture: Texture::from_rgb(format!("roof_{name}"), image(16, 16, colour)),
    };
    FacadeSet {
        facades: vec![
            facade("brick", 4, 10.0, 0, [150, 80, 60]),
            facade("stone", 5, 14.0, 1, [190, 185, 170]),
            facade("glass", 7, 18.0, 1, [120, 150, 170]),
        ],
        roofs: vec![
            roof("tar", [60, 60, 60], 3.0),
            roof("gravel", [150, 150, 140], 2.0),
        ],
    }
}

struct City {
    layout: ParsedLayout,
    lamps: Vec<Lamp>,
    buildings: Vec<Building>,
    facades: FacadeSet,
}

/// The default city, its buildings sized by the facades (`widths` None) or by `widths`.
fn city(widths: Option<&[f64]>) -> City {
    let facades = facade_set();
    let metric: Vec<f64> = match widths {
        Some(w) => w.to_vec(),
        None => facades.facades.iter().map(|f| f.width).collect(),
    };
    let TestCity {
        layout,
        lamps,
        buildings,
        ..
    } = test_city(SEED, &metric);
    City {
        layout,
        lamps,
        buildings,
        facades,
    }
}

fn scene_of(city: &City, widths: Option<&[f64]>) -> Scene {
    build(&SceneInput {
        layout: &city.layout,
        lamps: &city.lamps,
        buildings: &city.buildings,
        facades: &city.facades,
        widths,
        metres_per_pixel: 1.0,
        seed: SEED,
    })
}

fn of_class<'a>(scene: &'a Scene, class: &'a str) -> impl Iterator<Item = &'a SceneObject> {
    scene.objects.iter().filter(move |o| o.class == class)
}

fn position(mesh: &Mesh, i: u32) -> [f64; 3] {
    mesh.positions[i as usize].map(f64::from)
}

/// Each triangle of `mesh`: its three corners and the stored normal of its first corner.
fn triangles(mesh: &Mesh) -> impl Iterator<Item = ([[f64; 3]; 3], [f64; 3])> + '_ {
    mesh.indices.chunks(3).map(|t| {
        let corners = [
            position(mesh, t[0]),
            position(mesh, t[1]),
            position(mesh, t[2]),
        ];
        (corners, mesh.normals[t[0] as usize].map(f64::from))
    })
}

fn bounds(object: &SceneObject) -> ([f64; 3], [f64; 3]) {
    object.bounds().expect("the object has vertices")
}

#[test]
fn default_city_has_one_object_per_plan_item_in_the_documented_order() {
    let city = city(None);
    let scene = scene_of(&city, None);
    assert!(city.buildings.len() > 500, "{}", city.buildings.len());
    assert!(!city.lamps.is_empty());
    let mut want = vec!["ground".to_owned()];
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
        let prefix = object.name.split('_').next().unwrap();
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
fn buildings_stand_on_their_footprints_as_tall_as_their_facades() {
    let city = city(None);
    let scene = scene_of(&city, None);
    let buildings: Vec<&SceneObject> = of_class(&scene, "building").collect();
    for (object, building) in buildings.iter().zip(&city.buildings) {
        let (lo, hi) = bounds(object);
        let fp = building.footprint;
        assert_eq!(
            [lo[0], lo[2]],
            [f64::from(fp.x0), f64::from(fp.y0)],
            "{}",
            object.name
        );
        assert_eq!(
            [hi[0], hi[2]],
            [f64::from(fp.x1), f64::from(fp.y1)],
            "{}",
            object.name
        );
        let facade = &city.facades.facades[building.kind as usize];
        assert_eq!(
            f64::from(fp.width()),
            facade.width,
            "paper: footprint = facade width"
        );
        assert!((lo[1] - KERB_Y).abs() < 1e-6);
        assert!(
            (hi[1] - lo[1] - facade.height).abs() < 1e-4,
            "{}",
            object.name
        );
        let walls = &scene.materials[object.meshes[0].material as usize];
        assert_eq!(walls.name, format!("facade_{}", facade.name));
        let roof = &scene.materials[object.meshes[1].material as usize];
        let roof_name = &city.facades.roofs[facade.roof as usize].name;
        assert_eq!(roof.name, format!("roof_{roof_name}"));
    }
    // One material per facade texture and per roof texture, shared by their buildings.
    let facade_materials = scene
        .materials
        .iter()
        .filter(|m| m.name.starts_with("facade_"));
    assert_eq!(facade_materials.count(), 3);
    let roof_materials = scene
        .materials
        .iter()
        .filter(|m| m.name.starts_with("roof_"));
    assert_eq!(roof_materials.count(), 2);
}

/// u range of the walls of each building (min, max), and the building's wall width.
fn wall_u(scene: &Scene, city: &City) -> Vec<(f32, f32, f64, usize)> {
    of_class(scene, "building")
        .zip(&city.buildings)
        .map(|(object, building)| {
            let walls = &object.meshes[0];
            let lo = walls
                .uvs
                .iter()
                .map(|uv| uv[0])
                .fold(f32::INFINITY, f32::min);
            let hi = walls
                .uvs
                .iter()
                .map(|uv| uv[0])
                .fold(f32::NEG_INFINITY, f32::max);
            let name = &scene.materials[walls.material as usize].name;
            let facade = city
                .facades
                .facades
                .iter()
                .position(|f| format!("facade_{}", f.name) == *name)
                .unwrap();
            (lo, hi, f64::from(building.footprint.width()), facade)
        })
        .collect()
}

#[test]
fn wall_u_spans_one_facade_or_tiles_it_by_width() {
    let city_a = city(None);
    for (lo, hi, _, _) in wall_u(&scene_of(&city_a, None), &city_a) {
        assert_eq!((lo, hi), (0.0, 1.0));
    }
    let widths = [12.0, 25.0];
    let city_b = city(Some(&widths));
    let scene = scene_of(&city_b, Some(&widths));
    let mut used = BTreeSet::new();
    for (lo, hi, width, facade) in wall_u(&scene, &city_b) {
        let want = (width / city_b.facades.facades[facade].width) as f32;
        assert_eq!((lo, hi), (0.0, want), "width {width}, facade {facade}");
        used.insert(facade);
    }
    // The seeded choice uses every facade across a thousand buildings.
    assert_eq!(used.len(), 3);
    for object in of_class(&scene, "building") {
        let v: BTreeSet<u32> = object.meshes[0]
            .uvs
            .iter()
            .map(|uv| uv[1].to_bits())
            .collect();
        assert_eq!(v, BTreeSet::from([0.0f32.to_bits(), 1.0f32.to_bits()]));
    }
}

#[test]
fn building_walls_face_outwards_with_the_facade_top_at_the_roof() {
    let city = city(None);
    let scene = scene_of(&city, None);
    for object in of_class(&scene, "building").take(50) {
        let (lo, hi) = bounds(object);
        let centre = [
            (lo[0] + hi[0]) / 2.0,
            (lo[1] + hi[1]) / 2.0,
            (lo[2] + hi[2]) / 2.0,
        ];
        let walls = &object.meshes[0];
        assert_eq!(walls.indices.len(), 4 * 6);
        for (t, normal) in triangles(walls) {
            let g = cross(sub(t[1], t[0]), sub(t[2], t[0]));
            let mid = [
                (t[0][0] + t[1][0] + t[2][0]) / 3.0,
                (t[0][1] + t[1][1] + t[2][1]) / 3.0,
                (t[0][2] + t[1][2] + t[2][2]) / 3.0,
            ];
            assert!(dot(g, sub(mid, centre)) > 0.0, "{}: {t:?}", object.name);
            assert!(dot(g, normal) > 0.0, "{}: {t:?}", object.name);
            assert_eq!(g[1], 0.0, "walls are vertical");
        }
        for (p, uv) in walls.positions.iter().zip(&walls.uvs) {
            let at_top = f64::from(p[1]) == hi[1];
            assert_eq!(uv[1], if at_top { 0.0 } else { 1.0 }, "{}", object.name);
        }
    }
}

#[test]
fn lamps_stand_at_their_sites_with_an_emissive_head_towards_the_road() {
    let city = city(None);
    let scene = scene_of(&city, None);
    let lamps: Vec<&SceneObject> = of_class(&scene, "lamp").collect();
    for (object, lamp) in lamps.iter().zip(&city.lamps) {
        let [metal, head] = &object.meshes[..] else {
            panic!("{}: pole and head", object.name)
        };
        let head_material = &scene.materials[head.material as usize];
        assert_eq!(head_material.name, "lamp_head");
        assert!(head_material.emissive.iter().all(|&e| e > 0.0));
        assert_eq!(scene.materials[metal.material as usize].emissive, [0.0; 3]);
        // The pole's lowest ring is centred on the site.
        let ring: Vec<[f64; 3]> = (0..metal.positions.len() as u32)
            .map(|i| position(metal, i))
            .filter(|p| p[1] == 0.0)
            .collect();
        assert!(!ring.is_empty());
        let cx = ring.iter().map(|p| p[0]).sum::<f64>() / ring.len() as f64;
        let cz = ring.iter().map(|p| p[2]).sum::<f64>() / ring.len() as f64;
        assert!((cx - lamp.position[0]).abs() < 1e-3 && (cz - lamp.position[1]).abs() < 1e-3);
        // The head hangs out along `facing`.
        let n = head.positions.len() as f64;
        let hx = head.positions.iter().map(|p| f64::from(p[0])).sum::<f64>() / n;
        let hz = head.positions.iter().map(|p| f64::from(p[2])).sum::<f64>() / n;
        let (dx, dz) = (hx - lamp.position[0], hz - lamp.position[1]);
        let along = dx * lamp.facing[0] + dz * lamp.facing[1];
        let across = dx * lamp.facing[1] - dz * lamp.facing[0];
        assert!(
            along > 1.0 && across.abs() < 1e-3,
            "{}: {along} {across}",
            object.name
        );
        // The night light shines from just under the head's middle (1 px = 1 m here).
        let light = super::light_position(lamp, 1.0);
        let bottom = head
            .positions
            .iter()
            .map(|p| f64::from(p[1]))
            .fold(f64::INFINITY, f64::min);
        assert!((light[0] - hx).abs() < 1e-3 && (light[2] - hz).abs() < 1e-3);
        assert!(
            light[1] < bottom && light[1] > bottom - 0.1,
            "{light:?} {bottom}"
        );
    }
}

#[test]
fn markings_stay_out_of_crossings_and_on_their_road() {
    let city = city(None);
    let scene = scene_of(&city, None);
    let rects: Vec<RoadRect> = city.layout.roads.iter().map(RoadRect::of).collect();
    let (mut dashes, mut bars) = (0, 0);
    for object in of_class(&scene, "marking") {
        // No two markings of a road overlap: lines stop short of the zebra crossings.
        let pieces: Vec<RoadRect> = object.meshes[0]
            .positions
            .chunks(4)
            .map(plan_rect)
            .collect();
        for (i, a) in pieces.iter().enumerate() {
            for b in &pieces[i + 1..] {
                assert!(!a.overlaps(b), "{}: {a:?} overlaps {b:?}", object.name);
            }
        }
        let id: usize = object.name["marking_".len()..].parse().unwrap();
        for dash in pieces {
            dashes += 1;
            if quad_is_zebra_bar(&dash) {
                bars += 1;
            }
            let own = &rects[id];
            let inside = own.x[0] <= dash.x[0]
                && dash.x[1] <= own.x[1]
                && own.y[0] <= dash.y[0]
                && dash.y[1] <= own.y[1];
            assert!(inside, "{}: {dash:?} off its road", object.name);
            for (j, other) in rects.iter().enumerate() {
                assert!(
                    j == id || !dash.overlaps(other),
                    "{}: {dash:?} in road {j}",
                    object.name
                );
            }
        }
    }
    assert!(dashes > 100, "{dashes}");
    // The test city's crossings have zebra crossings on their approaches.
    assert!(bars > 20, "{bars} zebra bars");
}

/// The plan rectangle (x and z extents) of a flat quad's corners.
fn plan_rect(quad: &[[f32; 3]]) -> RoadRect {
    let xs = quad.iter().map(|p| f64::from(p[0]));
    let zs = quad.iter().map(|p| f64::from(p[2]));
    RoadRect {
        x: [
            xs.clone().fold(f64::INFINITY, f64::min),
            xs.fold(f64::NEG_INFINITY, f64::max),
        ],
        y: [
            zs.clone().fold(f64::INFINITY, f64::min),
            zs.fold(f64::NEG_INFINITY, f64::max),
        ],
    }
}

/// Whether a marking quad (its plan rectangle, layout pixels) is a zebra crossing's bar: 3 m
/// along the road, 0.5 m across (the test city's scale is 1 m a pixel).
fn quad_is_zebra_bar(r: &RoadRect) -> bool {
    let (w, h) = (r.x[1] - r.x[0], r.y[1] - r.y[0]);
    let near = |a: f64, b: f64| (a - b).abs() < 1e-3;
    (near(w, 3.0) && near(h, 0.5)) || (near(w, 0.5) && near(h, 3.0))
}

#[test]
fn road_surfaces_do_not_overlap_and_cover_every_road() {
    let city = city(None);
    let scene = scene_of(&city, None);
    let mut pieces: Vec<RoadRect> = Vec::new();
    let mut area = 0.0;
    for object in of_class(&scene, "road") {
        for quad in object.meshes[0].positions.chunks(4) {
            let piece = plan_rect(quad);
            assert!(
                pieces.iter().all(|p| !p.overlaps(&piece)),
                "{}",
                object.name
            );
            area += piece.area();
            pieces.push(piece);
        }
    }
    // Full-span roads: the union is every road's area minus each crossing counted once.
    let rects: Vec<RoadRect> = city.layout.roads.iter().map(RoadRect::of).collect();
    let mut union = 0.0;
    for (i, r) in rects.iter().enumerate() {
        union += r
            .minus_all(&rects[..i])
            .iter()
            .map(RoadRect::area)
            .sum::<f64>();
    }
    let crossings: f64 = rects
        .iter()
        .enumerate()
        .flat_map(|(i, a)| rects[i + 1..].iter().map(move |b| (a, b)))
        .filter(|(a, b)| a.overlaps(b))
        .map(|(a, b)| {
            (a.x[1].min(b.x[1]) - a.x[0].max(b.x[0])) * (a.y[1].min(b.y[1]) - a.y[0].max(b.y[0]))
        })
        .sum();
    let total: f64 = rects.iter().map(RoadRect::area).sum();
    assert_eq!(area, union);
    assert_eq!(union, total - crossings);
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
    assert_eq!(ground_hi[0], 384.0 + super::GROUND_MARGIN);
}
