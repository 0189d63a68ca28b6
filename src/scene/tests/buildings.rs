//! Buildings: footprints, heights, walls and how their facades tile.

use std::collections::BTreeSet;

use super::*;
use crate::model::geometry::{KERB_Y, cross, dot, sub};

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
        assert_eq!(
            f64::from(fp.width()),
            city.facades.facades[building.kind as usize].width,
            "paper: footprint = its kind's facade width"
        );
        let walls = &scene.materials[object.meshes[0].material as usize];
        let facade = &city.facades.facades[facade_of(&walls.name, &city)];
        assert!((lo[1] - KERB_Y).abs() < 1e-6);
        assert!(
            (hi[1] - lo[1] - facade.height).abs() < 1e-4,
            "{}",
            object.name
        );
        let roof = &scene.materials[object.meshes[1].material as usize];
        let roof_name = &city.facades.roofs[facade.roof as usize].name;
        assert_eq!(untinted(&roof.name), format!("roof_{roof_name}"));
    }
    // One texture per facade and per roof, shared by their tinted materials.
    for (prefix, want) in [("facade_", 3), ("roof_", 2)] {
        let textures: BTreeSet<u32> = scene
            .materials
            .iter()
            .filter(|m| m.name.starts_with(prefix))
            .filter_map(|m| m.texture)
            .collect();
        assert_eq!(textures.len(), want, "{prefix}");
    }
}

/// A material name without its `_tint<k>` suffix.
fn untinted(name: &str) -> &str {
    name.rsplit_once("_tint").map_or(name, |(base, _)| base)
}

/// The facade index a wall material `name` clads with.
fn facade_of(name: &str, city: &City) -> usize {
    city.facades
        .facades
        .iter()
        .position(|f| format!("facade_{}", f.name) == untinted(name))
        .unwrap()
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
            let facade = facade_of(&scene.materials[walls.material as usize].name, city);
            (lo, hi, f64::from(building.footprint.width()), facade)
        })
        .collect()
}

#[test]
fn wall_u_spans_one_facade_or_tiles_it_by_width() {
    // Without widths: a whole number of copies, each stretched by at most ±20 %.
    let city_a = city(None);
    for (lo, hi, width, facade) in wall_u(&scene_of(&city_a, None), &city_a) {
        assert_eq!(lo, 0.0);
        assert!(hi >= 1.0 && hi.fract() == 0.0, "{hi}");
        let stretch = width / (f64::from(hi) * city_a.facades.facades[facade].width);
        assert!((0.8 - 1e-6..=1.2 + 1e-6).contains(&stretch), "{stretch}");
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
    // The balanced choice uses every facade across a thousand buildings.
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
