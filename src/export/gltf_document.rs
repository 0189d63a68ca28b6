//! The glTF 2.0 JSON document as serde types: just the parts cityspec writes.
//!
//! Field order is declaration order and maps are `BTreeMap`s, so the JSON bytes are fixed.
//! Empty arrays and default values are left out, as the glTF schema wants (`minItems: 1`).

use std::collections::BTreeMap;

use serde::Serialize;

pub const ARRAY_BUFFER: u32 = 34962;
pub const ELEMENT_ARRAY_BUFFER: u32 = 34963;
pub const FLOAT: u32 = 5126;
pub const UNSIGNED_INT: u32 = 5125;
pub const LINEAR: u32 = 9729;
pub const LINEAR_MIPMAP_LINEAR: u32 = 9987;
pub const REPEAT: u32 = 10497;

/// The whole glTF JSON document.
#[derive(Debug, Default, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct GltfDocument {
    pub asset: Asset,
    pub scene: u32,
    pub scenes: Vec<GltfScene>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub nodes: Vec<Node>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub meshes: Vec<GltfMesh>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub materials: Vec<GltfMaterial>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub textures: Vec<GltfTexture>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub images: Vec<Image>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub samplers: Vec<Sampler>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub accessors: Vec<Accessor>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub buffer_views: Vec<BufferView>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub buffers: Vec<Buffer>,
}

#[derive(Debug, Default, Serialize)]
pub struct Asset {
    pub version: &'static str,
    pub generator: &'static str,
}

#[derive(Debug, Default, Serialize)]
pub struct GltfScene {
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub nodes: Vec<u32>,
}

#[derive(Debug, Serialize)]
pub struct Node {
    pub name: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mesh: Option<u32>,
    pub extras: NodeExtras,
}

#[derive(Debug, Serialize)]
pub struct NodeExtras {
    pub class: String,
}

#[derive(Debug, Serialize)]
pub struct GltfMesh {
    pub name: String,
    pub primitives: Vec<Primitive>,
}

#[derive(Debug, Serialize)]
pub struct Primitive {
    /// `POSITION`, `NORMAL`, `TEXCOORD_0` → accessor.
    pub attributes: BTreeMap<&'static str, u32>,
    pub indices: u32,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub material: Option<u32>,
}

#[derive(Debug, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct GltfMaterial {
    pub name: String,
    pub pbr_metallic_roughness: PbrMetallicRoughness,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub emissive_factor: Option<[f32; 3]>,
    /// The base colour's texture again, for a material whose emission follows it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub emissive_texture: Option<TextureInfo>,
}

#[derive(Debug, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct PbrMetallicRoughness {
    pub base_color_factor: [f32; 4],
    #[serde(skip_serializing_if = "Option::is_none")]
    pub base_color_texture: Option<TextureInfo>,
    pub metallic_factor: f32,
    pub roughness_factor: f32,
}

#[derive(Clone, Debug, Serialize)]
pub struct TextureInfo {
    pub index: u32,
}

#[derive(Debug, Serialize)]
pub struct GltfTexture {
    pub sampler: u32,
    pub source: u32,
}

#[derive(Debug, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Image {
    pub name: String,
    pub buffer_view: u32,
    pub mime_type: &'static str,
}

#[derive(Debug, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Sampler {
    pub mag_filter: u32,
    pub min_filter: u32,
    pub wrap_s: u32,
    pub wrap_t: u32,
}

#[derive(Debug, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Accessor {
    pub buffer_view: u32,
    #[serde(skip_serializing_if = "is_zero")]
    pub byte_offset: u64,
    pub component_type: u32,
    pub count: u64,
    #[serde(rename = "type")]
    pub kind: &'static str,
    /// `f64` holding `f32` values exactly, so the JSON numbers equal the binary data.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max: Option<[f64; 3]>,
}

#[derive(Debug, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct BufferView {
    pub buffer: u32,
    #[serde(skip_serializing_if = "is_zero")]
    pub byte_offset: u64,
    pub byte_length: u64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub byte_stride: Option<u32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target: Option<u32>,
}

#[derive(Debug, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Buffer {
    pub byte_length: u64,
}

fn is_zero(n: &u64) -> bool {
    *n == 0
}
