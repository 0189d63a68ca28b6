//! Scene tests on the default 768 × 768 city (layout → parse → lamps → place) with a small
//! hand-made facade set: the city and mesh helpers they share, one file per subject.

use image::{Rgb, RgbImage};

use super::{SceneInput, build};
use crate::model::{
    Building, Facade, FacadeSet, Lamp, Mesh, ParsedLayout, Roof, Scene, SceneObject, Texture,
};
use crate::test_support::{TestCity, test_city};

mod buildings;
mod map_city;
mod map_markings;
mod streets;
mod whole_scene;

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
        colour: tint,
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
