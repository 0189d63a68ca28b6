//! A user's OBJ (+ MTL + textures, as bytes) and a mesh spec → `<label>_NNNN` objects:
//! the model scaled, turned about y and stood on a sidewalk strip or in a right-hand lane
//! (a layout's or a map's, [`MeshSpots`]), or at a map's nodes ([`place_mapped`]).
//!
//! The model's origin (x, z) stands on the spot and its lowest point on the surface. Its
//! front is its −z side: on a lane, rotation 0 heads it with the traffic. Faces are
//! triangulated by tobj; OBJ `vt` is v-up, so v is flipped; a mesh without normals gets
//! flat ones (its triangles are unwelded for that).

use std::io::Cursor;

use rand::RngExt;
use rand_pcg::Pcg64;

use super::car::CURB_GAP;
use super::ground_spots::{GroundSpots, RoadSlot, RoadSpots, Spot, StripSpots};
use super::map_spots::MapSpots;
use super::trig::{add, cos_sin_deg};
use super::{ATTEMPTS, MeshFiles, ObjectsError, Placing};
use crate::model::geometry::{KERB_Y, ROAD_Y, cross, dot, sub};
use crate::model::{Mesh, Texture};
use crate::spec::{Ground, ObjectSpec};

/// Colour of model parts without a material (linear RGB).
const DEFAULT_COLOUR: [f32; 3] = [0.6, 0.6, 0.6];

/// A loaded model in its own units, ready to be instanced.
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    /// Its materials; the last one is the default for parts without a material.
    pub materials: Vec<ModelMaterial>,
    pub parts: Vec<Part>,
    /// Lowest y of any vertex.
    pub min_y: f64,
    /// Largest horizontal distance of a vertex from the model's y axis.
    pub radius: f64,
}

#[derive(Clone, Debug, PartialEq)]
pub struct ModelMaterial {
    pub name: String,
    pub colour: [f32; 3],
    pub texture: Option<Texture>,
}

/// Triangles of one material (index into [`Model::materials`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Part {
    pub material: usize,
    pub positions: Vec<[f64; 3]>,
    pub normals: Vec<[f64; 3]>,
    pub uvs: Vec<[f32; 2]>,
    pub indices: Vec<u32>,
}

impl Model {
    /// Reads `files` with tobj; `model` (the spec's string) names it in errors.
    pub fn load(model: &str, files: &MeshFiles) -> Result<Model, ObjectsError> {
        let options = tobj::LoadOptions {
            triangulate: true,
            single_index: true,
            ..Default::default()
        };
        let (models, materials) = tobj::load_obj_buf(
            &mut Cursor::new(&files.obj[..]),
            &options,
            |_| match &files.mtl {
                Some(mtl) => tobj::load_mtl_buf(&mut Cursor::new(&mtl[..])),
                None => Err(tobj::LoadError::OpenFileFailed),
            },
        )
        .map_err(|source| ObjectsError::BadObj {
            model: model.to_owned(),
            source,
        })?;
        let materials = match materials {
            Ok(m) => m,
            Err(source) => {
                let model = model.to_owned();
                return Err(match files.mtl {
                    None => ObjectsError::MtlNotRead { model },
                    Some(_) => ObjectsError::BadMtl { model, source },
                });
            }
        };
        let mut out_materials = Vec::new();
        for m in &materials {
            let texture = match &m.diffuse_texture {
                Some(name) => Some(load_texture(model, name, files)?),
                None => None,
            };
            out_materials.push(ModelMaterial {
                name: m.name.clone(),
                colour: m.diffuse.unwrap_or(DEFAULT_COLOUR),
                texture,
            });
        }
        let default = out_materials.len();
        out_materials.push(ModelMaterial {
            name: "default".to_owned(),
            colour: DEFAULT_COLOUR,
            texture: None,
        });
        let parts: Vec<Part> = models
            .iter()
            .map(|m| {
                part(
                    &m.mesh,
                    m.mesh
                        .material_id
                        .filter(|&i| i < default)
                        .unwrap_or(default),
                )
            })
            .filter(|p| !p.indices.is_empty())
            .collect();
        let all = parts.iter().flat_map(|p| &p.positions);
        let min_y = all.clone().map(|p| p[1]).fold(f64::INFINITY, f64::min);
        let radius = all
            .map(|p| (p[0] * p[0] + p[2] * p[2]).sqrt())
            .fold(0.0, f64::max);
        if parts.is_empty() || !min_y.is_finite() || !radius.is_finite() {
            return Err(ObjectsError::Empty {
                model: model.to_owned(),
            });
        }
        Ok(Model {
            materials: out_materials,
            parts,
            min_y,
            radius,
        })
    }
}

fn load_texture(model: &str, name: &str, files: &MeshFiles) -> Result<Texture, ObjectsError> {
    let bytes = files
        .textures
        .get(name)
        .ok_or_else(|| ObjectsError::MissingTexture {
            model: model.to_owned(),
            texture: name.to_owned(),
        })?;
    let image = image::load_from_memory(bytes).map_err(|source| ObjectsError::BadTexture {
        model: model.to_owned(),
        texture: name.to_owned(),
        source: Box::new(source),
    })?;
    Ok(Texture::from_rgb(name, image.to_rgb8()))
}

/// One tobj mesh as a part: v flipped, flat normals where the file has none.
fn part(mesh: &tobj::Mesh, material: usize) -> Part {
    let vertex = |i: usize| -> [f64; 3] {
        let p = &mesh.positions;
        [p[3 * i], p[3 * i + 1], p[3 * i + 2]].map(f64::from)
    };
    let uv = |i: usize| -> [f32; 2] {
        let t = &mesh.texcoords;
        if t.len() >= 2 * i + 2 {
            [t[2 * i], 1.0 - t[2 * i + 1]]
        } else {
            [0.0, 0.0]
        }
    };
    let count = mesh.positions.len() / 3;
    let valid: Vec<[usize; 3]> = mesh
        .indices
        .chunks_exact(3)
        .map(|t| [t[0] as usize, t[1] as usize, t[2] as usize])
        .filter(|t| t.iter().all(|&i| i < count))
        .collect();
    let mut out = Part {
        material,
        positions: Vec::new(),
        normals: Vec::new(),
        uvs: Vec::new(),
        indices: Vec::new(),
    };
    if mesh.normals.len() == mesh.positions.len() {
        out.positions = (0..count).map(vertex).collect();
        out.uvs = (0..count).map(uv).collect();
        out.normals = (0..count)
            .map(|i| {
                [
                    mesh.normals[3 * i],
                    mesh.normals[3 * i + 1],
                    mesh.normals[3 * i + 2],
                ]
                .map(f64::from)
            })
            .collect();
        out.indices = valid.iter().flatten().map(|&i| i as u32).collect();
    } else {
        for t in &valid {
            let [a, b, c] = t.map(vertex);
            let n = cross(sub(b, a), sub(c, a));
            let len = dot(n, n).sqrt();
            let n = if len > 0.0 {
                n.map(|v| v / len)
            } else {
                [0.0, 1.0, 0.0]
            };
            for &i in t {
                out.indices.push(out.positions.len() as u32);
                out.positions.push(vertex(i));
                out.normals.push(n);
                out.uvs.push(uv(i));
            }
        }
    }
    out
}

/// Where a seeded model stands: a layout's ground ([`GroundSpots`]) or a map's
/// (`map_spots::MapSpots`). On a sidewalk it stands mid-sidewalk ([`StripSpots::strip_at`]
/// at half the width); in a lane where [`MeshSpots::lane`] says.
pub trait MeshSpots: StripSpots {
    /// A free spot for a model of `radius` metres in a right-hand lane, its `travel` the
    /// lane's; None after [`ATTEMPTS`].
    fn lane(&mut self, rng: &mut Pcg64, radius: f64) -> Option<Spot>;
}

impl MeshSpots for GroundSpots<'_> {
    /// The middle of a right-hand lane ([`GroundSpots::lane`]).
    fn lane(&mut self, rng: &mut Pcg64, radius: f64) -> Option<Spot> {
        GroundSpots::lane(self, rng, radius, ATTEMPTS)
    }
}

impl MeshSpots for MapSpots<'_> {
    /// At the kerb side of the right-hand lane, [`CURB_GAP`] from the kerb, as a map's
    /// parked cars: the middle of the lane is the roads cameras' (`OsmMap`'s
    /// `CAMERA_LANE`), and a model there would fill their view. A carriageway too narrow
    /// for that takes none.
    fn lane(&mut self, rng: &mut Pcg64, radius: f64) -> Option<Spot> {
        let slot = |width: f64| {
            let offset = width / 2.0 - CURB_GAP - radius;
            (offset > radius).then_some(RoadSlot {
                half: [radius, radius],
                offset,
                crossing_clearance: 0.0,
                gap: 0.0,
                parked: false,
            })
        };
        self.road(rng, ATTEMPTS, slot)
    }
}

/// Places `spec.count` copies of the spec's model (fewer if they do not fit); returns how
/// many.
pub fn place(
    spec: &ObjectSpec,
    rng: &mut Pcg64,
    spots: &mut impl MeshSpots,
    placing: &mut Placing,
) -> Result<u32, ObjectsError> {
    let model = spec_model(spec, placing)?;
    let mut copies = Copies::new(spec, &model);
    let mut placed = 0;
    for _ in 0..spec.count {
        let scale = uniform(rng, spec.scale);
        let turn = cos_sin_deg(uniform(rng, spec.rotation));
        let radius = model.radius * scale;
        let spot = match spec.on {
            // A layout's strips are one width: half of it is `GroundSpots::strip`'s
            // middle, exactly.
            Ground::Sidewalk => spots.strip_at(rng, radius, |width| width / 2.0, ATTEMPTS),
            Ground::Lane => spots.lane(rng, radius),
        };
        let Some(spot) = spot else {
            continue;
        };
        let (ground, turn) = match spec.on {
            Ground::Sidewalk => (KERB_Y, turn),
            // Rotation 0 maps the model's −z onto the travel direction h: sin = −h.x,
            // cos = −h.z.
            Ground::Lane => (ROAD_Y, add((-spot.travel[1], -spot.travel[0]), turn)),
        };
        copies.push(placing, &spot, scale, turn, ground);
        placed += 1;
    }
    Ok(placed)
}

/// The model an entry names, loaded from the files the build read.
fn spec_model(spec: &ObjectSpec, placing: &Placing) -> Result<Model, ObjectsError> {
    let name = spec.model.as_deref().unwrap_or_default();
    let files = placing
        .input
        .meshes
        .get(name)
        .ok_or_else(|| ObjectsError::MissingModel {
            model: name.to_owned(),
        })?;
    Model::load(name, files)
}

/// An entry's copies of its model: its materials, made with the first copy.
struct Copies<'m> {
    spec: &'m ObjectSpec,
    model: &'m Model,
    materials: Option<Vec<u32>>,
}

impl<'m> Copies<'m> {
    fn new(spec: &'m ObjectSpec, model: &'m Model) -> Copies<'m> {
        Copies {
            spec,
            model,
            materials: None,
        }
    }

    /// Pushes a copy standing on `spot` ([`instance`]), named `<label>_NNNN`.
    fn push(
        &mut self,
        placing: &mut Placing,
        spot: &Spot,
        scale: f64,
        turn: (f64, f64),
        ground: f64,
    ) {
        let (spec, model) = (self.spec, self.model);
        let ids = self.materials.get_or_insert_with(|| {
            model
                .materials
                .iter()
                .map(|m| {
                    let key = format!("{}_{}", spec.label, m.name);
                    placing.add(&key, m.colour, m.texture.as_ref(), [0.0; 3])
                })
                .collect()
        });
        let meshes = instance(model, ids, spot, scale, turn, ground);
        let name = placing.name(&spec.label);
        placing.push_plain(crate::model::ObjectKind::Mesh, name, &spec.label, meshes);
    }
}

/// Places the spec's model at the map's nodes `sites` (each a position and, when a paved
/// road is near, the way its front looks: towards the road), in node order, up to
/// `spec.count`: each scaled and turned by the spec's ranges (from facing the road where
/// it has one), where `clear` says a model of that radius fits and `claim` grants its
/// ground. Returns how many stand.
pub fn place_mapped(
    spec: &ObjectSpec,
    rng: &mut Pcg64,
    sites: &[([f64; 2], Option<[f64; 2]>)],
    clear: &dyn Fn([f64; 2], f64) -> bool,
    claim: &mut dyn FnMut(super::ground_spots::Footprint) -> bool,
    placing: &mut Placing,
) -> Result<u32, ObjectsError> {
    let model = spec_model(spec, placing)?;
    let mut copies = Copies::new(spec, &model);
    let mut placed = 0;
    for &(position, facing) in sites {
        if placed >= spec.count {
            break;
        }
        let scale = uniform(rng, spec.scale);
        let turn = cos_sin_deg(uniform(rng, spec.rotation));
        let radius = model.radius * scale;
        if !clear(position, radius)
            || !claim(super::ground_spots::Footprint::Circle(position, radius))
        {
            continue;
        }
        // Its −z onto `facing`, as a lane's heading: sin = −f.x, cos = −f.z.
        let turn = facing.map_or(turn, |f| add((-f[1], -f[0]), turn));
        let spot = Spot {
            position,
            travel: facing.unwrap_or([0.0, -1.0]),
            road: 0,
        };
        copies.push(placing, &spot, scale, turn, KERB_Y);
        placed += 1;
    }
    Ok(placed)
}

/// The model's parts scaled by `scale`, turned by `(cos, sin)` about y (counter-clockwise
/// seen from above), its origin on `spot` and its lowest point at height `ground`.
pub fn instance(
    model: &Model,
    materials: &[u32],
    spot: &Spot,
    scale: f64,
    (c, s): (f64, f64),
    ground: f64,
) -> Vec<Mesh> {
    let turn = |v: [f64; 3]| [c * v[0] + s * v[2], v[1], -s * v[0] + c * v[2]];
    let lift = ground - model.min_y * scale;
    model
        .parts
        .iter()
        .map(|part| Mesh {
            material: materials[part.material],
            positions: part
                .positions
                .iter()
                .map(|&p| {
                    let r = turn(p.map(|v| v * scale));
                    [
                        r[0] + spot.position[0],
                        r[1] + lift,
                        r[2] + spot.position[1],
                    ]
                    .map(|v| v as f32)
                })
                .collect(),
            normals: part
                .normals
                .iter()
                .map(|&n| turn(n).map(|v| v as f32))
                .collect(),
            uvs: part.uvs.clone(),
            indices: part.indices.clone(),
        })
        .collect()
}

fn uniform(rng: &mut Pcg64, range: [f64; 2]) -> f64 {
    range[0] + rng.random::<f64>() * (range[1] - range[0])
}
