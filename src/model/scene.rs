//! The 3D city: named, labelled objects made of triangle meshes, with materials and textures.
//!
//! World coordinates in metres: x east (= layout x), y up, z south (= layout y). Triangles
//! wind counter-clockwise seen from their front (outside) face; normals point out.

use serde::{Deserialize, Serialize};

use super::{ObjectKind, Texture};

/// Everything the exporter writes and the renderer draws.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Scene {
    pub textures: Vec<Texture>,
    pub materials: Vec<Material>,
    /// Objects in a stable order: ground, blocks, roads, markings, sidewalks, buildings,
    /// lamps (and, later, inserted objects).
    pub objects: Vec<SceneObject>,
}

/// A surface description both OBJ/MTL and glTF can express.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// Unique, file-name-safe (`facade_builtin_07`, `asphalt`, `lamp_head`).
    pub name: String,
    /// Base colour (linear RGB, 0–1), multiplied with the texture when there is one.
    pub colour: [f32; 3],
    /// Index into [`Scene::textures`].
    pub texture: Option<u32>,
    /// Emitted light (linear RGB, 0–1); zero for ordinary surfaces.
    pub emissive: [f32; 3],
    /// Whether the emission is multiplied by the texture, as glTF's `emissiveTexture` (and
    /// MTL's `map_Ke`) naming the base colour's texture: a backlit sign, whose printed face
    /// glows where light passes through it (pale paper bright, dark letters dark).
    #[serde(default)]
    pub emissive_textured: bool,
}

/// The end of the name of a material whose surface a small lamp lights after dusk (a
/// lamp-lit sign): the renderer puts a light over every mesh of such a material.
pub const LAMP_LIT_SUFFIX: &str = "_lamplit";

/// One named, labelled object.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SceneObject {
    /// Stable name: `building_0042`, `road_0003`, `lamp_0017`, …
    pub name: String,
    /// What it is, set by the stage that made it.
    pub kind: ObjectKind,
    /// Class label, kept for annotations: `building`, `road`, `lamp`, `ground`, …
    pub class: String,
    pub meshes: Vec<Mesh>,
}

/// Triangles of one material.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Mesh {
    /// Index into [`Scene::materials`].
    pub material: u32,
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    /// Texture coordinates, v down from the image's top edge (as OBJ `vt` with v flipped
    /// and as glTF `TEXCOORD_0` directly). May exceed 0–1: textures repeat.
    pub uvs: Vec<[f32; 2]>,
    /// Three per triangle, counter-clockwise from the front.
    pub indices: Vec<u32>,
}

impl Scene {
    /// Triangles in the whole scene.
    pub fn triangle_count(&self) -> usize {
        self.objects
            .iter()
            .flat_map(|o| &o.meshes)
            .map(|m| m.indices.len() / 3)
            .sum()
    }
}

impl SceneObject {
    /// The box around all its vertices, `(min, max)` in world metres; `None` when it has
    /// no vertex or a coordinate is not finite.
    pub fn bounds(&self) -> Option<([f64; 3], [f64; 3])> {
        let mut min = [f64::INFINITY; 3];
        let mut max = [f64::NEG_INFINITY; 3];
        for p in self.meshes.iter().flat_map(|m| &m.positions) {
            for (k, &c) in p.iter().enumerate() {
                min[k] = min[k].min(f64::from(c));
                max[k] = max[k].max(f64::from(c));
            }
        }
        min.iter()
            .chain(&max)
            .all(|v| v.is_finite())
            .then_some((min, max))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_span_every_vertex_and_an_empty_object_has_none() {
        let mesh = |positions| Mesh {
            positions,
            ..Mesh::default()
        };
        let object = SceneObject {
            name: "car_0007".to_owned(),
            kind: ObjectKind::Car,
            class: "car".to_owned(),
            meshes: vec![
                mesh(vec![[1.0, 0.0, -2.0], [3.0, 1.5, 0.0]]),
                mesh(vec![[-1.0, 0.5, 4.0]]),
            ],
        };
        assert_eq!(object.bounds(), Some(([-1.0, 0.0, -2.0], [3.0, 1.5, 4.0])));
        let empty = SceneObject {
            meshes: vec![mesh(Vec::new())],
            ..object
        };
        assert_eq!(empty.bounds(), None);
    }
}
