//! Scene stage: plan (blocks, roads, lamps, buildings) + facades → the 3D [`Scene`].
//!
//! World coordinates are metres: x east (= layout x), y up, z south (= layout y); a layout
//! pixel `(i, j)` covers `[i, i + 1) × [j, j + 1)` times `metres_per_pixel`. Objects come
//! in the order [`Scene::objects`] documents, each named `<class>_<id:04>` after the plan
//! item it stands for (`ground`, `fields` and `hills` have no number):
//!
//! | object | class | geometry | material |
//! |---|---|---|---|
//! | `ground` | ground | one quad under the layout, [`GROUND_MARGIN`] beyond it | `grass` |
//! | `fields` | ground | flat land from the ground's edge out past the hills (see `horizon`) | `grass` |
//! | `hills` | hills | a ring of wooded hills round the city, clear of the ground (see `horizon`) | `woods` |
//! | `block_0007` | block | one quad per band span of the block's pixels | `paving` |
//! | `road_0003` | road | the road's rectangle minus earlier roads' (crossings belong to the lower id) | `asphalt` |
//! | `marking_0003` | marking | centre and lane lines, parking-lane edges, a zebra crossing on each approach to a crossing, clear of other roads | `marking` |
//! | `sidewalk_0007` | sidewalk | the strip ring: a raised slab with curb faces | `concrete` |
//! | `building_0042` | building | walls with the facade, flat roof | `facade_*`, `roof_*` |
//! | `lamp_0017` | lamp | pole, arm, emissive head | `lamp_metal`, `lamp_head` |
//!
//! Every road has an object (possibly without triangles if earlier roads cover it all);
//! markings and sidewalks only exist where they have triangles. Surfaces never overlap in
//! plan at one height: roads are clipped against each other, sidewalks against blocks,
//! roads and each other, so nothing z-fights.
//!
//! Heights: ground 0, roads [`ROAD_Y`], markings [`MARKING_Y`], blocks and sidewalks
//! [`KERB_Y`]; buildings stand on the block surface. The heights, the mesh builder and the
//! road rectangles live in [`crate::model::geometry`], since the objects stage builds on them too.
//!
//! [`ROAD_Y`]: crate::model::geometry::ROAD_Y
//! [`MARKING_Y`]: crate::model::geometry::MARKING_Y
//! [`KERB_Y`]: crate::model::geometry::KERB_Y
//!
//! Only `+ − × ÷ sqrt` are used, in f64, rounded to f32 at the end: the scene is the same
//! bit for bit on every platform.

/// Bump when this stage's output bytes change: it is part of the stage's cache key.
pub const VERSION: u32 = 14;
/// Bump when a map's city ([`map_city`], its markings and roofs, and the objects and
/// camera paths placed on a map) changes for the same map: it is in the export's key for
/// a map layout only (and so in its frames'), so a layout's key stays as it was.
pub const MAP_VERSION: u32 = 6;

mod blocks;
mod buildings;
mod horizon;
mod map_city;
mod map_markings;
mod markings;
mod paint;
mod procedural;
mod roads;
mod row_region;
mod sidewalks;
mod street_lamps;
mod surfaces;
#[cfg(test)]
mod tests;

use crate::model::geometry::{FacadeChoice, MaterialBook, MeshBuilder};
use crate::model::{Building, FacadeSet, Lamp, ObjectKind, ParsedLayout, Scene, SceneObject};
use surfaces::Surfaces;

// The build driver measures the strip for its street cameras as the scene does.
pub use crate::model::geometry::strip_width_px;
pub use buildings::{TINTS, building_name};
pub use map_city::{MapSceneInput, map_city};
pub use street_lamps::light_position;

/// How far the ground reaches beyond the layout on every side, in metres.
pub const GROUND_MARGIN: f64 = 100.0;

/// The scene stage: plan + facades → the 3D city. Pure and deterministic.
pub struct SceneInput<'a> {
    pub layout: &'a ParsedLayout,
    pub lamps: &'a [Lamp],
    pub buildings: &'a [Building],
    pub facades: &'a FacadeSet,
    /// The spec's explicit building widths (metres), if any. None: `building.kind` is the
    /// index of the facade whose width the footprint has (paper); Some: kind indexes these
    /// widths. Either way the facade is chosen by [`FacadeChoice::all`].
    pub widths: Option<&'a [f64]>,
    pub metres_per_pixel: f64,
    pub seed: u64,
}

impl SceneInput<'_> {
    /// How this input picks each building's facade (and so its height).
    pub fn facade_choice(&self) -> FacadeChoice<'_> {
        FacadeChoice {
            facades: self.facades,
            widths: self.widths,
            metres_per_pixel: self.metres_per_pixel,
            seed: self.seed,
        }
    }
}

/// The 3D city of `input`.
///
/// Never panics: a building whose facade index is out of range takes facade `kind % n`; with
/// no facades at all, buildings get a plain material and a default height (see the
/// `buildings` module); a facade without a valid roof gets a plain roof.
pub fn build(input: &SceneInput) -> Scene {
    let mut book = MaterialBook::default();
    let surfaces = Surfaces::register(&mut book);
    let clad = buildings::Cladding::register(input, &mut book);
    let mpp = input.metres_per_pixel;
    let layout = input.layout;

    let mut objects: Vec<SceneObject> = Vec::new();
    objects.push(ground(layout, mpp, surfaces.grass));
    objects.extend(horizon::horizon_objects(
        layout,
        mpp,
        input.seed,
        surfaces.grass,
        surfaces.woods,
    ));
    objects.extend(blocks::block_objects(layout, mpp, surfaces.paving));
    objects.extend(roads::road_objects(layout, mpp, surfaces.asphalt));
    objects.extend(markings::marking_objects(layout, mpp, surfaces.marking));
    objects.extend(sidewalks::sidewalk_objects(layout, mpp, surfaces.concrete));
    objects.extend(buildings::building_objects(input, &clad));
    objects.extend(street_lamps::lamp_objects(input.lamps, mpp, &surfaces));

    let (textures, materials) = book.finish();
    Scene {
        textures,
        materials,
        objects,
    }
}

/// One quad under the whole layout and [`GROUND_MARGIN`] around it.
fn ground(layout: &ParsedLayout, mpp: f64, material: u32) -> SceneObject {
    let mut mesh = MeshBuilder::new(material);
    let x = [
        -GROUND_MARGIN,
        f64::from(layout.width) * mpp + GROUND_MARGIN,
    ];
    let z = [
        -GROUND_MARGIN,
        f64::from(layout.height) * mpp + GROUND_MARGIN,
    ];
    mesh.floor(x, z, 0.0, procedural::GRASS_TILE);
    object(ObjectKind::Ground, "ground".to_owned(), vec![mesh])
}

/// A named object of the non-empty meshes among `meshes`, of class `kind`'s name.
fn object(kind: ObjectKind, name: String, meshes: Vec<MeshBuilder>) -> SceneObject {
    SceneObject {
        name,
        kind,
        class: kind.name().to_owned(),
        meshes: meshes
            .into_iter()
            .filter(|m| !m.is_empty())
            .map(MeshBuilder::finish)
            .collect(),
    }
}
