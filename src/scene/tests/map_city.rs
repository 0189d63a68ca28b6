//! The 3D city of an OpenStreetMap map: footprints, mapped heights, facades at their own
//! scale, the street surface.

use super::facade_set;
use crate::model::geometry::KERB_Y;
use crate::model::geometry::polygon::contains;
use crate::model::{
    LeftOut, MapBuilding, MapPolygon, ObjectKind, OsmElement, OsmMap, Scene, SceneObject,
};
use crate::scene::{MapSceneInput, map_city};

/// A map of two buildings beside a street: an L-shaped one 18 m tall with a courtyard
/// cut into its long arm, and a square one the map gives no height.
fn map() -> OsmMap {
    let square = |x: f64, z: f64, s: f64| vec![[x, z], [x + s, z], [x + s, z + s], [x, z + s]];
    let polygon =
        |outer: Vec<[f64; 2]>, holes: Vec<Vec<[f64; 2]>>, area| MapPolygon { outer, holes, area };
    let l_shape = vec![
        [0.0, 0.0],
        [30.0, 0.0],
        [30.0, 10.0],
        [10.0, 10.0],
        [10.0, 30.0],
        [0.0, 30.0],
    ];
    let courtyard: Vec<[f64; 2]> = square(14.0, 3.0, 4.0).into_iter().rev().collect();
    let building = |element, outer, holes: Vec<Vec<[f64; 2]>>, area, height| MapBuilding {
        area,
        height,
        height_from: "height".to_owned(),
        ..MapBuilding::new(element, 0, outer, holes)
    };
    OsmMap {
        bounds: crate::model::GeoBox {
            south: 60.0,
            west: 25.0,
            north: 60.001,
            east: 25.001,
        },
        origin: [60.0005, 25.0005],
        metres_per_degree: [55_800.0, 111_412.0],
        extent: [-10.0, -20.0, 60.0, 50.0],
        buildings: vec![
            building(
                OsmElement::Way(1),
                l_shape,
                vec![courtyard],
                500.0 - 16.0,
                Some(18.0),
            ),
            building(
                OsmElement::Way(2),
                square(40.0, 0.0, 12.0),
                Vec::new(),
                144.0,
                None,
            ),
        ],
        roads: Vec::new(),
        features: Vec::new(),
        carriageway: vec![polygon(
            vec![[-10.0, -20.0], [60.0, -20.0], [60.0, -10.0], [-10.0, -10.0]],
            Vec::new(),
            700.0,
        )],
        sidewalks: vec![polygon(
            vec![[-10.0, -10.0], [60.0, -10.0], [60.0, -8.0], [-10.0, -8.0]],
            Vec::new(),
            140.0,
        )],
        blocks: vec![polygon(
            vec![[-10.0, -8.0], [60.0, -8.0], [60.0, 50.0], [-10.0, 50.0]],
            Vec::new(),
            4060.0,
        )],
        green: Vec::new(),
        paths: Vec::new(),
        squares: Vec::new(),
        left_out: LeftOut::default(),
    }
}

fn city() -> Scene {
    map_city(&MapSceneInput {
        lamps: &[],
        map: &map(),
        facades: &facade_set(),
        seed: 7,
    })
}

/// `map`'s city, without lamps.
fn scene_of(map: &OsmMap) -> Scene {
    map_city(&MapSceneInput {
        lamps: &[],
        map,
        facades: &facade_set(),
        seed: 5,
    })
}

fn triangles(object: &SceneObject) -> impl Iterator<Item = [[f32; 3]; 3]> + '_ {
    object.meshes.iter().flat_map(|m| {
        m.indices
            .chunks_exact(3)
            .map(|t| [0, 1, 2].map(|k| m.positions[t[k] as usize]))
    })
}

fn area_from_above(t: [[f32; 3]; 3]) -> f64 {
    let [a, b, c] = t.map(|p| [f64::from(p[0]), f64::from(p[2])]);
    ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).abs() / 2.0
}

#[test]
fn buildings_stand_on_their_footprints_at_their_heights() {
    let scene = city();
    let buildings: Vec<&SceneObject> = scene
        .objects
        .iter()
        .filter(|o| o.kind == ObjectKind::Building)
        .collect();
    assert_eq!(buildings.len(), 2);
    for (object, map_building) in buildings.iter().zip(&map().buildings) {
        let [walls, roof] = [&object.meshes[0], &object.meshes[1]];
        // The roof covers the footprint less its courtyard, flat at the top of the walls.
        let roof_area: f64 = roof
            .indices
            .chunks_exact(3)
            .map(|t| area_from_above([0, 1, 2].map(|k| roof.positions[t[k] as usize])))
            .sum();
        assert!(
            (roof_area - map_building.area).abs() < 1e-3,
            "{roof_area} {}",
            map_building.area
        );
        let top = roof.positions[0][1];
        assert!(roof.positions.iter().all(|p| p[1] == top));
        let wall_top = walls
            .positions
            .iter()
            .map(|p| p[1])
            .fold(f32::MIN, f32::max);
        assert_eq!(wall_top, top);
        match map_building.height {
            Some(h) => assert!((f64::from(top) - KERB_Y - h).abs() < 1e-4, "{top}"),
            // 3 to 7 floors of 3 m (the test facades' floor).
            None => {
                let floors = (f64::from(top) - KERB_Y) / 3.0;
                assert!(
                    (3.0..=7.0).contains(&floors) && (floors - floors.round()).abs() < 1e-4,
                    "{floors}"
                );
            }
        }
        // Every wall faces out of the footprint (into the courtyard on a hole's edges):
        // half a metre in front of each wall quad's middle is outside the building.
        for quad in walls.indices.chunks_exact(6) {
            let corners = [quad[0], quad[1], quad[2], quad[5]].map(|i| walls.positions[i as usize]);
            let n = walls.normals[quad[0] as usize];
            let mid = |k: usize| corners.iter().map(|c| f64::from(c[k])).sum::<f64>() / 4.0;
            let out = [
                mid(0) + f64::from(n[0]) * 0.5,
                mid(2) + f64::from(n[2]) * 0.5,
            ];
            let inside = contains(&map_building.outer, out)
                && !map_building.holes.iter().any(|h| contains(h, out));
            assert!(
                !inside,
                "a wall at {corners:?} faces {n:?}, into the building"
            );
        }
    }
}

#[test]
fn facades_keep_their_scale_on_every_wall() {
    // One unit of v is the facade's whole height, one of u its width: whatever the wall's
    // length and the building's height, windows keep their size.
    let scene = city();
    let facades = facade_set().facades;
    for object in scene
        .objects
        .iter()
        .filter(|o| o.kind == ObjectKind::Building)
    {
        let walls = &object.meshes[0];
        let material = &scene.materials[walls.material as usize];
        let facade = facades
            .iter()
            .find(|f| material.name == format!("facade_{}", f.name))
            .expect("a facade");
        for quad in walls.indices.chunks_exact(6) {
            let corners: Vec<usize> = quad.iter().map(|&i| i as usize).collect();
            let (p, uv) = (&walls.positions, &walls.uvs);
            let (lo, hi) = (
                corners
                    .iter()
                    .min_by(|a, b| p[**a][1].total_cmp(&p[**b][1]))
                    .copied()
                    .unwrap(),
                corners
                    .iter()
                    .max_by(|a, b| p[**a][1].total_cmp(&p[**b][1]))
                    .copied()
                    .unwrap(),
            );
            let metres = f64::from(p[hi][1] - p[lo][1]);
            let v = f64::from(uv[lo][1] - uv[hi][1]);
            assert!(
                (metres / v - facade.height).abs() < 1e-3,
                "{metres} m over v {v}"
            );
            assert!(
                uv.iter().all(|t| (0.0..=1.0 + 1e-6).contains(&t[1])),
                "v stays on the facade"
            );
        }
    }
}

#[test]
fn green_ground_and_squares_are_cut_out_of_their_paved_block() {
    let mut map = map();
    let lawn = MapPolygon {
        outer: vec![[35.0, 25.0], [55.0, 25.0], [55.0, 45.0], [35.0, 45.0]],
        holes: Vec::new(),
        area: 400.0,
    };
    map.green = vec![crate::model::MapArea {
        block: 0,
        shape: lawn,
    }];
    let plaza = MapPolygon {
        outer: vec![[35.0, 5.0], [55.0, 5.0], [55.0, 15.0], [35.0, 15.0]],
        holes: Vec::new(),
        area: 200.0,
    };
    map.squares = vec![crate::model::MapArea {
        block: 0,
        shape: plaza,
    }];
    let scene = scene_of(&map);
    let named = |name: &str| scene.objects.iter().find(|o| o.name == name).unwrap();
    let (block, green) = (named("block_0000"), named("green_0000"));
    let square = named("square_0000");
    assert_eq!(
        (block.kind, green.kind, square.kind),
        (ObjectKind::Block, ObjectKind::Ground, ObjectKind::Block)
    );
    let area = |o: &SceneObject| triangles(o).map(area_from_above).sum::<f64>();
    assert!((area(block) - 3460.0).abs() < 1e-3, "{}", area(block));
    assert!((area(square) - 200.0).abs() < 1e-3, "{}", area(square));
    assert!((area(green) - 400.0).abs() < 1e-3, "{}", area(green));
    let grass = scene
        .materials
        .iter()
        .position(|m| m.name == "grass")
        .unwrap() as u32;
    assert!(green.meshes.iter().all(|m| m.material == grass));
    assert!(block.meshes.iter().all(|m| m.material != grass));
    assert!(square.meshes.iter().all(|m| m.material != grass));
}

#[test]
fn paths_across_the_green_are_paved_and_cut_out_of_the_grass() {
    let mut map = map();
    let lawn = MapPolygon {
        outer: vec![[35.0, 25.0], [55.0, 25.0], [55.0, 45.0], [35.0, 45.0]],
        holes: Vec::new(),
        area: 400.0,
    };
    // A path 2 m wide across the lawn, west to east.
    let path = MapPolygon {
        outer: vec![[35.0, 34.0], [55.0, 34.0], [55.0, 36.0], [35.0, 36.0]],
        holes: Vec::new(),
        area: 40.0,
    };
    let on_block = |shape| crate::model::MapArea { block: 0, shape };
    map.green = vec![on_block(lawn)];
    map.paths = vec![on_block(path)];
    let scene = scene_of(&map);
    let named = |name: &str| scene.objects.iter().find(|o| o.name == name).unwrap();
    let (green, path) = (named("green_0000"), named("path_0000"));
    assert_eq!(
        (green.kind, path.kind),
        (ObjectKind::Ground, ObjectKind::Sidewalk)
    );
    let area = |o: &SceneObject| triangles(o).map(area_from_above).sum::<f64>();
    assert!((area(green) - 360.0).abs() < 1e-3, "{}", area(green));
    assert!((area(path) - 40.0).abs() < 1e-3, "{}", area(path));
    // No grass under the path: every grass triangle's centre is off it.
    for t in triangles(green) {
        let z = (t[0][2] + t[1][2] + t[2][2]) / 3.0;
        assert!(!(34.0..=36.0).contains(&z), "{t:?}");
    }
    assert!(triangles(path).all(|t| t.iter().all(|p| p[1] == KERB_Y as f32)));
}

#[test]
fn the_street_surface_and_the_blocks_are_paved() {
    let scene = city();
    let kinds: Vec<ObjectKind> = scene.objects.iter().map(|o| o.kind).collect();
    for kind in [ObjectKind::Ground, ObjectKind::Block, ObjectKind::Road] {
        assert_eq!(kinds.iter().filter(|k| **k == kind).count(), 1, "{kind:?}");
    }
    // The sidewalk and the carriageway's kerb.
    let sidewalks = scene
        .objects
        .iter()
        .filter(|o| o.kind == ObjectKind::Sidewalk);
    let names: Vec<&str> = sidewalks.map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["sidewalk_0000", "kerb_0000"]);
    let road = scene
        .objects
        .iter()
        .find(|o| o.kind == ObjectKind::Road)
        .unwrap();
    let area: f64 = triangles(road).map(area_from_above).sum();
    assert!((area - 700.0).abs() < 1e-3, "{area}");
    // Same input, same scene.
    assert_eq!(city(), scene);
}

#[test]
fn roofs_follow_roof_shape_with_a_mapped_height_at_the_top() {
    let mut map = map();
    // The L with its courtyard: gabled asked, flat built. The square without a height: a
    // pyramid over walls of its seeded floors. A 20 × 10 m house 12 m tall: gabled,
    // its ridge at 12 m.
    map.buildings[0].roof_shape = Some("gabled".to_owned());
    map.buildings[1].roof_shape = Some("pyramidal".to_owned());
    map.buildings[1].height_from = "none".to_owned();
    let mut house = map.buildings[1].clone();
    house.outer = vec![[0.0, 35.0], [20.0, 35.0], [20.0, 45.0], [0.0, 45.0]];
    (house.area, house.height) = (200.0, Some(12.0));
    house.roof_shape = Some("gabled".to_owned());
    house.height_from = "height".to_owned();
    map.buildings.push(house);
    let scene = map_city(&MapSceneInput {
        lamps: &[],
        map: &map,
        facades: &facade_set(),
        seed: 7,
    });
    let flat = city();
    let buildings: Vec<&SceneObject> = (scene.objects.iter())
        .filter(|o| o.kind == ObjectKind::Building)
        .collect();
    let highest =
        |mesh: &crate::model::Mesh| mesh.positions.iter().map(|p| p[1]).fold(f32::MIN, f32::max);
    // The L is as it was without a shape.
    let flat_l = flat
        .objects
        .iter()
        .find(|o| o.name == buildings[0].name)
        .unwrap();
    assert_eq!(buildings[0].meshes, flat_l.meshes);
    // The pyramid: its walls as tall as the flat roof was, its apex above them.
    let flat_square = flat
        .objects
        .iter()
        .find(|o| o.name == buildings[1].name)
        .unwrap();
    let eave = highest(&flat_square.meshes[1]);
    assert_eq!(highest(&buildings[1].meshes[0]), eave);
    let apex = highest(&buildings[1].meshes[1]);
    assert!(
        (f64::from(apex - eave) - 0.6 * 6.0).abs() < 1e-4,
        "{apex} {eave}"
    );
    // The house: the ridge at its mapped height, the walls below by the roof's rise (0.6
    // of its half-depth), gables rising to the ridge.
    let [walls, roof] = [&buildings[2].meshes[0], &buildings[2].meshes[1]];
    assert!((f64::from(highest(roof)) - KERB_Y - 12.0).abs() < 1e-4);
    assert!(
        (f64::from(highest(walls)) - KERB_Y - 12.0).abs() < 1e-4,
        "the gables"
    );
    let wall_quads =
        (walls.positions.iter()).filter(|p| (f64::from(p[1]) - KERB_Y - 9.0).abs() < 1e-4);
    assert!(wall_quads.count() >= 8, "the walls stop at 12 − 3 m");
    let covered: f64 = triangles(buildings[2])
        .skip(walls.indices.len() / 3)
        .map(area_from_above)
        .sum();
    assert!((covered - 200.0).abs() < 1e-3, "{covered}");
}

#[test]
fn kerb_faces_close_the_step_from_the_carriageway_up_to_kerb_height() {
    use crate::model::geometry::ROAD_Y;
    let faces = |map: &OsmMap| -> Vec<([f32; 3], [[f32; 3]; 3])> {
        let scene = scene_of(map);
        let kerb = scene.objects.iter().find(|o| o.name == "kerb_0000");
        let kerb = kerb.expect("a kerb per carriageway");
        assert_eq!(kerb.kind, ObjectKind::Sidewalk);
        (kerb.meshes.iter())
            .flat_map(|m| {
                m.indices.chunks_exact(3).map(|t| {
                    let corners = [0, 1, 2].map(|k| m.positions[t[k] as usize]);
                    (m.normals[t[0] as usize], corners)
                })
            })
            .collect()
    };
    // The street's only edge off the box is its south kerb (z = -10, x -10 … 60), where
    // the sidewalk meets it: two triangles facing north, into the street.
    let street = faces(&map());
    assert_eq!(street.len(), 2);
    let mut covered = 0.0;
    for (normal, corners) in &street {
        assert_eq!(*normal, [0.0, 0.0, -1.0]);
        for p in corners {
            assert_eq!(p[2], -10.0);
            assert!(p[1] == ROAD_Y as f32 || p[1] == KERB_Y as f32, "{p:?}");
        }
        let [a, b, c] = corners.map(|p| [f64::from(p[0]), f64::from(p[1])]);
        covered += ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).abs() / 2.0;
    }
    assert!(
        (covered - 70.0 * (KERB_Y - ROAD_Y)).abs() < 1e-4,
        "{covered}"
    );
    // An island in the street (a hole, turning either way): its four sides face out of
    // it, into the street around it, whichever way its ring turns.
    for turn in [false, true] {
        let mut map = map();
        let mut island = vec![[10.0, -17.0], [20.0, -17.0], [20.0, -13.0], [10.0, -13.0]];
        if turn {
            island.reverse();
        }
        map.carriageway[0].holes.push(island);
        let faces = faces(&map);
        assert_eq!(faces.len(), 2 + 8);
        for (normal, corners) in &faces[2..] {
            let (x, z) = (corners[0][0], corners[0][2]);
            let out = match normal {
                [0.0, 0.0, -1.0] => z == -17.0,
                [0.0, 0.0, 1.0] => z == -13.0,
                [-1.0, 0.0, 0.0] => x == 10.0,
                [1.0, 0.0, 0.0] => x == 20.0,
                _ => false,
            };
            assert!(out, "{normal:?} at {corners:?}");
        }
    }
}

#[test]
fn a_part_lifted_off_the_ground_carries_on_the_facade_from_the_floors_below() {
    // The square building gets a part over its west half from 7.5 m up to 21 m.
    let mut map = map();
    let mut part = map.buildings[1].clone();
    part.element = OsmElement::Way(3);
    part.outer = vec![[40.0, 0.0], [46.0, 0.0], [46.0, 12.0], [40.0, 12.0]];
    part.area = 72.0;
    (part.height, part.height_from) = (Some(21.0), "levels".to_owned());
    part.min_height = Some(7.5);
    map.buildings[1].parts.push(part);
    let scene = scene_of(&map);
    let object = (scene.objects.iter())
        .find(|o| o.name == "building_0001")
        .unwrap();
    let [walls, roof] = [&object.meshes[0], &object.meshes[1]];
    // The building's whole footprint stands under the part (nothing of it is on the
    // ground), and both have a flat roof: 144 + 72 m² from above.
    let roof_area: f64 = (roof.indices.chunks_exact(3))
        .map(|t| area_from_above([0, 1, 2].map(|k| roof.positions[t[k] as usize])))
        .sum();
    assert!((roof_area - 216.0).abs() < 1e-3, "{roof_area}");
    let material = &scene.materials[walls.material as usize];
    let facade = (facade_set().facades.into_iter())
        .find(|f| material.name == format!("facade_{}", f.name))
        .unwrap();
    // The facade's v at `y` metres above the kerb, counted from the ground: its ground
    // floor (3 m), then its upper floors repeated.
    let floors = f64::from(facade.floors);
    let (ground_v, upper) = (1.0 - 1.0 / floors, facade.height - 3.0);
    let v_at = |y: f64, top: bool| {
        if y <= 3.0 {
            return 1.0 - y / 3.0 * (1.0 - ground_v);
        }
        let into = (y - 3.0) % upper;
        // The top of a repeat is v 0, not the next repeat's ground_v.
        let into = if top && into < 1e-9 { upper } else { into };
        ground_v * (1.0 - into / upper)
    };
    let mut lifted = 0;
    for quad in walls.indices.chunks_exact(6) {
        let corners: Vec<usize> = quad.iter().map(|&i| i as usize).collect();
        let (p, uv) = (&walls.positions, &walls.uvs);
        let ys: Vec<f64> = corners
            .iter()
            .map(|&c| f64::from(p[c][1]) - KERB_Y)
            .collect();
        let (lo, hi) = (
            ys.iter().copied().fold(f64::MAX, f64::min),
            ys.iter().copied().fold(f64::MIN, f64::max),
        );
        lifted += usize::from((lo - 7.5).abs() < 1e-4);
        for (k, &c) in corners.iter().enumerate() {
            let want = v_at(ys[k], (ys[k] - hi).abs() < 1e-6 && ys[k] > lo);
            assert!(
                (f64::from(uv[c][1]) - want).abs() < 1e-4,
                "v {} at {} m, not {want}",
                uv[c][1],
                ys[k]
            );
        }
    }
    // The part's four walls start at 7.5 m.
    assert_eq!(lifted, 4);
}
