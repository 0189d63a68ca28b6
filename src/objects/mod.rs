//! Objects stage: `spec.objects` + plan (roads, lamps, buildings, facades) + model bytes →
//! [`Inserted`]: text planes on walls, traffic signs beside roads and user meshes, ready to
//! [`merge`] into the scene.
//!
//! | kind | object name | where | geometry |
//! |---|---|---|---|
//! | text | `text_0003` | free wall (no window, no other plate) facing a road, 2.5 m up to 1 m below the roof; shop signs low | a plate quad 2.5 cm in front of the wall (shop sign, banner, or painted on the wall's own pixels), one of eight fonts, its image on an atlas page shared by its entry (`<label>_atlas_N`) |
//! | sign | `sign_0012` | by its type's rule (`sign_rules`): stop, yield, priority road at the crossings' mouths, warnings 30–50 m before a zebra, speed limits past a crossing, else mid-strip 40 m from its type; ≥ 2 m from lamps, never in a crossing | pole + plate shaped like the sign (33 StVO types), facing the traffic it signs |
//! | mesh | `<label>_0004` | mid-strip (`sidewalk`) or mid right-hand lane (`lane`) | the user's OBJ, scaled and turned about y |
//! | car | `car_0007` + two `text_0150`… | parked in a curb's parking lane, or standing in a driving lane with the traffic | a low-poly sedan, hatchback, estate, coupe, SUV, minivan, pickup, van, bus or truck (`car` module) with an EU number plate at front and rear (`number_plate`): text objects of class `text` when an entry makes that class, else part of the car |
//! | tree | `tree_0011` | mid-strip beside a road, or on a block's open paving clear of buildings | trunk + a low-poly crown of one of seven species (`tree` module) |
//! | street_name | `street_pole_0002` (class `pole`) + four `text_0140`… | at a street corner, half a strip from both curbs | a pole and two stacked double-sided plates naming the two streets (`street_names` module) |
//! | traffic_light | `signal_pole_0001` (class `pole`) + two `traffic_light_0002`… | at a street corner, half a strip from both curbs | a pole and two signal heads looking along the two roads, one lamp lit (`traffic_lights` module) |
//!
//! Every object's class is its spec entry's `label`. Entry `i` draws from
//! `crate::rng::stream(seed, "objects", i)`; entries are placed as if in order (text and
//! the ground's kinds side by side, replayed in order: `entry_groups`) and later entries
//! avoid earlier ones, so changing entry 1 never moves entry 0's objects. An object that
//! finds no free spot in [`ATTEMPTS`] tries is drawn again (text: new words, size, style;
//! cars: a new body; trees: a new size and spot, the species kept) a few times, then left out: `count` is
//! met until the walls, curbs or strips are nearly full, and is an upper bound.
//!
//! No `sin`/`cos` from std: angles go through `trig` (`libm`, pure Rust), so the output is
//! the same bit for bit everywhere. The stage is pure: the driver reads the model files.

/// Bump when this stage's output bytes change: it is part of the stage's cache key.
pub const VERSION: u32 = 25;

mod atlas_layout;
mod bicycle;
mod car;
mod entry_groups;
mod footprint_grid;
mod ground_spots;
mod map_corners;
mod map_objects;
mod map_spots;
mod map_walls;
mod number_plate;
pub mod obj_lines;
mod objects_error;
mod open_ground;
mod person;
mod person_pose;
mod plate_light;
mod plate_style;
mod sign_codes;
mod sign_face;
mod sign_rules;
mod street_names;
#[cfg(test)]
mod tests;
mod text_colours;
mod text_font;
mod text_plate;
mod traffic_lights;
mod traffic_signs;
mod tree;
mod user_mesh;
mod vehicle_parts;
mod wall_text;
mod word_list;

use std::collections::{BTreeMap, BTreeSet};

use rand::RngExt;
use rand_pcg::Pcg64;

use crate::model::geometry::{FacadeChoice, MaterialBook, trig};
use crate::model::{
    Building, FacadeSet, Lamp, Material, Mesh, ParsedLayout, Scene, SceneObject, Texture,
};
use crate::spec::{EntryKind, ObjectSpec};

pub use map_objects::{MapObjectsInput, insert_map};
pub use objects_error::ObjectsError;
pub use traffic_lights::{Signal, lamp_material};
pub use traffic_signs::SignFace;
pub use word_list::{WORDS, parse_words};

/// How many random spots an object tries before it is left out.
pub const ATTEMPTS: u32 = 40;

/// Text, car and tree entries stop after this many objects in a row found no room even
/// with their redraws: the walls, curbs or strips are full, and trying the rest of a huge
/// `count` would only burn time (the shortfall is reported as ever).
pub const GIVE_UP: u32 = 16;

/// A file set an object entry names, as the build driver read it: a user model's OBJ, MTL
/// and textures, or a text entry's word file (its bytes in `obj`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MeshFiles {
    pub obj: Vec<u8>,
    pub mtl: Option<Vec<u8>>,
    /// Texture file name (as the MTL names it) → its bytes (PNG or JPEG).
    pub textures: BTreeMap<String, Vec<u8>>,
}

/// Everything the objects stage reads.
pub struct ObjectsInput<'a> {
    pub specs: &'a [ObjectSpec],
    pub layout: &'a ParsedLayout,
    pub lamps: &'a [Lamp],
    pub buildings: &'a [Building],
    /// As the scene stage gets them: they set the buildings' heights.
    pub facades: &'a FacadeSet,
    pub widths: Option<&'a [f64]>,
    /// Keyed by the spec's `model` string.
    pub meshes: &'a BTreeMap<String, MeshFiles>,
    pub metres_per_pixel: f64,
    pub seed: u64,
}

impl ObjectsInput<'_> {
    /// How the scene stage picks each building's facade, and so its height: text goes on
    /// the same walls.
    pub fn facade_choice(&self) -> FacadeChoice<'_> {
        FacadeChoice {
            facades: self.facades,
            widths: self.widths,
            metres_per_pixel: self.metres_per_pixel,
            seed: self.seed,
        }
    }
}

/// What gets inserted: objects (named `text_0003`, `sign_0012`, `<label>_0004`…, class =
/// the spec's label), their materials and textures (indices local to this value), and per
/// object its category label and, for text, the transcription, the 4 corners of every
/// word's quad in world coordinates (for ICDAR quads) and its style attributes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Inserted {
    pub textures: Vec<Texture>,
    pub materials: Vec<Material>,
    pub objects: Vec<SceneObject>,
    /// One per object, same order.
    pub info: Vec<ObjectInfo>,
    /// The faces of the traffic signs, by index in `objects`.
    pub sign_faces: BTreeMap<usize, SignFace>,
    /// Per spec entry, how many objects it placed (at most its `count`); poles for a
    /// street-name entry.
    pub placed: Vec<u32>,
}

impl Inserted {
    /// One warning per spec entry that placed fewer objects than its `count` asks, with
    /// the numbers: `count` is an upper bound, so falling short is a warning, not an error.
    pub fn shortfalls(&self, specs: &[ObjectSpec]) -> Vec<crate::diagnostic::Diagnostic> {
        specs
            .iter()
            .zip(&self.placed)
            .enumerate()
            .filter(|(_, (spec, placed))| **placed < spec.count)
            .map(|(i, (spec, placed))| {
                let kind = spec.kind.name();
                let message = format!(
                    "objects[{i}] ({kind}, label {:?}): placed {} of {} (no free spot left \
                     after {ATTEMPTS} tries each)",
                    spec.label,
                    thousands(*placed),
                    thousands(spec.count)
                );
                crate::diagnostic::Diagnostic::warning("objects-short", message)
                    .at(format!("objects[{i}].count"))
            })
            .collect()
    }
}

/// `n` with a comma every three digits: `100,000`.
fn thousands(n: u32) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// Annotation data of one inserted object.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjectInfo {
    pub label: String,
    /// Text objects: the words as drawn (with their case).
    pub text: Option<String>,
    /// Text objects: per word of `text` (split at spaces, in order), its ink box's corners
    /// in world metres, clockwise from the top-left as seen from the front (top-left,
    /// top-right, bottom-right, bottom-left). Empty for other objects.
    pub corners: Vec<[[f64; 3]; 4]>,
    /// Extra annotation attributes (text objects: `text_style`, `text_font`).
    pub attributes: BTreeMap<String, String>,
    /// People and riders: the 17 COCO keypoints in COCO's order, world metres, from the
    /// rig their mesh is built on (each inside its body part). None for other objects.
    pub keypoints: Option<[[f64; 3]; 17]>,
    /// What it is to moving traffic: a lane vehicle, carried by one, a signal head, or a
    /// walking person.
    pub traffic: Option<crate::model::TrafficRole>,
}

/// State shared by the entries of one group (see [`entry_groups`]) while they are placed
/// in order. It records every name and material asked for, so that the groups' results
/// can be replayed into one as if every entry had been placed in turn.
pub(crate) struct Placing<'a> {
    pub input: &'a ObjectsInput<'a>,
    book: MaterialBook,
    /// Per material of `book`, how it was asked for.
    requests: Vec<MaterialRequest>,
    /// Material of a name already registered (sign faces, poles), so it is made once.
    cached: BTreeMap<String, u32>,
    pub out: Inserted,
    /// Next number per object-name prefix.
    counters: BTreeMap<String, u32>,
    /// The prefix of every name handed out, in order.
    name_calls: Vec<String>,
}

/// How a material came to be registered: the name asked for (before the book makes it
/// unique) and, for one registered once per name, that name as its key.
#[derive(Clone, Debug)]
struct MaterialRequest {
    name: String,
    once: bool,
}

impl<'a> Placing<'a> {
    fn new(input: &'a ObjectsInput<'a>) -> Placing<'a> {
        Placing {
            input,
            book: MaterialBook::default(),
            requests: Vec::new(),
            cached: BTreeMap::new(),
            out: Inserted::default(),
            counters: BTreeMap::new(),
            name_calls: Vec::new(),
        }
    }

    /// The next unique name `<prefix>_NNNN`.
    pub fn name(&mut self, prefix: &str) -> String {
        self.name_calls.push(prefix.to_owned());
        next_name(&mut self.counters, prefix)
    }

    /// Registers a material (its name made unique by the book) and returns its index.
    pub fn add(
        &mut self,
        name: &str,
        colour: [f32; 3],
        texture: Option<&Texture>,
        emissive: [f32; 3],
    ) -> u32 {
        self.requests.push(MaterialRequest {
            name: name.to_owned(),
            once: false,
        });
        self.book.add(name, colour, texture, emissive)
    }

    /// Makes material `m`'s emission follow its texture (a backlit face).
    pub fn texture_emission(&mut self, m: u32) {
        self.book.texture_emission(m);
    }

    /// A material registered once under `name`, made by `make` the first time.
    pub fn material(
        &mut self,
        name: &str,
        make: impl FnOnce() -> ([f32; 3], Option<Texture>),
    ) -> u32 {
        if let Some(&m) = self.cached.get(name) {
            return m;
        }
        let (colour, texture) = make();
        let m = self.add(name, colour, texture.as_ref(), [0.0; 3]);
        self.registered_once(name, m)
    }

    /// A plain material of a colour drawn from `palette` (uniform, one draw of `rng`),
    /// registered once as `<prefix>_<index, two digits>`.
    pub fn palette_material(&mut self, rng: &mut Pcg64, prefix: &str, palette: &[[f32; 3]]) -> u32 {
        self.palette_pick(rng, prefix, palette).1
    }

    /// As [`Placing::palette_material`], with the palette index drawn.
    pub fn palette_pick(
        &mut self,
        rng: &mut Pcg64,
        prefix: &str,
        palette: &[[f32; 3]],
    ) -> (usize, u32) {
        let k = rng.random_range(0..palette.len());
        let colour = palette[k];
        (
            k,
            self.material(&format!("{prefix}_{k:02}"), || (colour, None)),
        )
    }

    /// A plain, emissive material registered once under `name`: it glows at night.
    pub fn glowing(&mut self, name: &str, colour: [f32; 3], emissive: [f32; 3]) -> u32 {
        if let Some(&m) = self.cached.get(name) {
            return m;
        }
        let m = self.add(name, colour, None, emissive);
        self.registered_once(name, m)
    }

    /// Marks material `m`, just added, as the one registered once under `name`.
    fn registered_once(&mut self, name: &str, m: u32) -> u32 {
        self.requests[m as usize].once = true;
        self.cached.insert(name.to_owned(), m);
        m
    }

    pub fn push(&mut self, object: SceneObject, info: ObjectInfo) {
        self.out.objects.push(object);
        self.out.info.push(info);
    }

    /// Sets what the object pushed last is to moving traffic.
    pub fn set_traffic(&mut self, role: crate::model::TrafficRole) {
        if let Some(info) = self.out.info.last_mut() {
            info.traffic = Some(role);
        }
    }

    /// Pushes an object of `kind` and class `label` that carries no text.
    pub fn push_plain(
        &mut self,
        kind: crate::model::ObjectKind,
        name: String,
        label: &str,
        meshes: Vec<Mesh>,
    ) {
        self.push_variant(kind, name, label, meshes, None);
    }

    /// Pushes an object of `kind` and class `label` that carries no text, with the COCO
    /// attribute `(key, value)` naming the variant it was drawn as, if any.
    pub fn push_variant(
        &mut self,
        kind: crate::model::ObjectKind,
        name: String,
        label: &str,
        meshes: Vec<Mesh>,
        variant: Option<(&str, String)>,
    ) {
        let attributes = variant
            .map(|(k, v)| BTreeMap::from([(k.to_owned(), v)]))
            .unwrap_or_default();
        self.push_figure(kind, name, label, meshes, attributes, None);
    }

    /// Pushes an object of `kind` and class `label` that carries no text, with the COCO
    /// `attributes` naming what it was drawn as (a person's `appearance` and `pose`) and,
    /// for a figure with a rig (a person or a rider), its 17 COCO `keypoints` in world
    /// metres.
    pub fn push_figure(
        &mut self,
        kind: crate::model::ObjectKind,
        name: String,
        label: &str,
        meshes: Vec<Mesh>,
        attributes: BTreeMap<String, String>,
        keypoints: Option<[[f64; 3]; 17]>,
    ) {
        let object = SceneObject {
            name,
            kind,
            class: label.to_owned(),
            meshes,
        };
        let info = ObjectInfo {
            traffic: None,
            label: label.to_owned(),
            text: None,
            corners: Vec::new(),
            attributes,
            keypoints,
        };
        self.push(object, info);
    }
}

/// Places every spec entry's objects, as if in entry order. Pure and deterministic.
///
/// Errors for mesh entries: a model missing from `meshes`, an OBJ/MTL tobj cannot read, a
/// texture the MTL names that is missing or not an image; for text entries: a word file
/// missing from `meshes` or without words. Each error names the file. With several, the
/// first entry's.
pub fn insert(input: &ObjectsInput) -> Result<Inserted, ObjectsError> {
    entry_groups::insert(input)
}

/// Entries placed into one [`Placing`], and per entry of the spec (`None` for the others)
/// what of it that entry made.
struct PlacedEntries<'a> {
    placing: Placing<'a>,
    shares: Vec<Option<EntryShare>>,
}

/// Places the entries of `input.specs` for which `chosen` holds, in order, each with its
/// own stream, into one [`Placing`]. An error comes with its entry's index.
fn place_entries<'a>(
    input: &'a ObjectsInput<'a>,
    chosen: impl Fn(&ObjectSpec) -> bool,
) -> Result<PlacedEntries<'a>, (usize, ObjectsError)> {
    let mut placing = Placing::new(input);
    let mut shares = vec![None; input.specs.len()];
    // The walls facing roads are found only by a group that places text (finding them
    // looks at every building); the ground's spots cost little and are simply made.
    let mut spots = ground_spots::GroundSpots::new(input);
    let mut walls = None;
    for (i, spec) in input.specs.iter().enumerate() {
        if !chosen(spec) {
            continue;
        }
        let mut rng = crate::rng::stream(input.seed, "objects", i as u64);
        let before = EntryShare::start(&placing);
        let mut counted = None;
        let placed = match spec.kind {
            EntryKind::Text => walls
                .get_or_insert_with(|| wall_text::Walls::new(input))
                .place(spec, &mut rng, &mut placing),
            EntryKind::Sign => {
                counted = Some(traffic_signs::place(
                    spec,
                    &mut rng,
                    &mut spots,
                    &mut placing,
                ));
                Ok(())
            }
            EntryKind::Mesh => {
                user_mesh::place(spec, &mut rng, &mut spots, &mut placing).map(|_| ())
            }
            EntryKind::Car => {
                counted = Some(car::place(spec, &mut rng, &mut spots, &mut placing));
                Ok(())
            }
            EntryKind::Tree => {
                tree::place(spec, &mut rng, &mut spots, &mut placing);
                Ok(())
            }
            EntryKind::Person => {
                person::place(spec, &mut rng, &mut spots, &mut placing);
                Ok(())
            }
            EntryKind::Bicycle => {
                counted = Some(bicycle::place(spec, &mut rng, &mut spots, &mut placing));
                Ok(())
            }
            EntryKind::StreetName => street_names::place(spec, &mut rng, &mut spots, &mut placing)
                .map(|n| counted = Some(n)),
            EntryKind::TrafficLight => {
                counted = Some(traffic_lights::place(
                    spec,
                    &mut rng,
                    &mut spots,
                    &mut placing,
                ));
                Ok(())
            }
        };
        placed.map_err(|e| (i, e))?;
        // Street-name and traffic-light entries count poles (each carries four text faces
        // or two signal heads), sign entries signs (a plate on a pole), bicycle entries
        // bicycles (a ridden one has a rider), car entries cars (with their number
        // plates); the others count objects.
        shares[i] = Some(before.end(&placing, counted));
    }
    person::walk_on(&spots, &mut placing);
    Ok(PlacedEntries { placing, shares })
}

/// What one entry made in its [`Placing`]: ranges of its objects, materials and name
/// calls, and how many it placed by its `count`'s measure.
#[derive(Clone, Debug)]
struct EntryShare {
    objects: std::ops::Range<usize>,
    materials: std::ops::Range<usize>,
    names: std::ops::Range<usize>,
    placed: u32,
}

impl EntryShare {
    fn start(placing: &Placing) -> EntryShare {
        let (o, m, n) = (
            placing.out.objects.len(),
            placing.requests.len(),
            placing.name_calls.len(),
        );
        EntryShare {
            objects: o..o,
            materials: m..m,
            names: n..n,
            placed: 0,
        }
    }

    fn end(self, placing: &Placing, counted: Option<u32>) -> EntryShare {
        let objects = self.objects.start..placing.out.objects.len();
        EntryShare {
            placed: counted.unwrap_or(objects.len() as u32),
            objects,
            materials: self.materials.start..placing.requests.len(),
            names: self.names.start..placing.name_calls.len(),
        }
    }
}

/// The next name `<prefix>_NNNN` by `counters`.
fn next_name(counters: &mut BTreeMap<String, u32>, prefix: &str) -> String {
    let n = counters.entry(prefix.to_owned()).or_insert(0);
    let name = format!("{prefix}_{n:04}");
    *n += 1;
    name
}

/// Moves the objects, materials and textures of `inserted` into `scene`, re-basing
/// material and texture indices; returns the index of the first inserted object in
/// scene.objects. The rest of `inserted` (`info`, `sign_faces`, `placed`) is not read.
///
/// A material whose name the scene already uses is renamed `<name>_2`, `<name>_3`, … (and
/// its texture with it), so exported names stay unique.
pub fn merge(scene: &mut Scene, inserted: Inserted) -> usize {
    let texture_base = scene.textures.len() as u32;
    let material_base = scene.materials.len() as u32;
    let mut material_names: BTreeSet<String> =
        scene.materials.iter().map(|m| m.name.clone()).collect();
    let mut texture_names: BTreeSet<String> =
        scene.textures.iter().map(|t| t.name.clone()).collect();
    let mut textures = inserted.textures;
    for material in inserted.materials {
        let mut name = material.name.clone();
        let mut n = 2u32;
        while material_names.contains(&name)
            || (material.texture.is_some() && texture_names.contains(&name))
        {
            name = format!("{}_{n}", material.name);
            n += 1;
        }
        material_names.insert(name.clone());
        if let Some(t) = material.texture.and_then(|t| textures.get_mut(t as usize)) {
            t.name = name.clone();
            texture_names.insert(name.clone());
        }
        scene.materials.push(Material {
            name,
            texture: material.texture.map(|t| t + texture_base),
            ..material
        });
    }
    scene.textures.extend(textures);
    let first = scene.objects.len();
    scene
        .objects
        .extend(inserted.objects.into_iter().map(|mut object| {
            for mesh in &mut object.meshes {
                mesh.material += material_base;
            }
            object
        }));
    first
}
