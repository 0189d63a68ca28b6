//! Scene + texture files → `city.glb`: glTF 2.0 binary with the geometry and the PNGs in
//! one embedded buffer; one node and one mesh per scene object, one primitive per mesh.
//!
//! The buffer (the GLB's BIN chunk) holds four geometry sections, each one bufferView
//! shared by the accessors of every primitive: all positions (VEC3 f32), all normals
//! (VEC3 f32), all texture coordinates (VEC2 f32, v down as in the scene: glTF's
//! convention too) and all indices (u32). Then each texture file's PNG bytes in its own
//! bufferView, referenced by an `image`. Every bufferView starts on a 4-byte boundary.
//! Fewer bufferViews than one per attribute keeps the JSON small for a city of thousands
//! of objects; `byteStride` is set as the spec requires for shared vertex bufferViews.
//!
//! Meshes without a triangle are left out (glTF accessors need `count ≥ 1`); an object
//! with no mesh left becomes a node without a mesh. Normals not of unit length are
//! normalised (the validator rejects them); uvs or normals not matching the positions in
//! number are left out of that primitive.

use std::collections::BTreeMap;
use std::ops::Range;

use super::gltf_document::*;
use super::texture_files::TextureFiles;
use crate::model::{Mesh, Scene};

const MAGIC: &[u8; 4] = b"glTF";
const CHUNK_JSON: &[u8; 4] = b"JSON";
const CHUNK_BIN: &[u8; 4] = b"BIN\0";
/// Non-metallic, mostly rough: stone, asphalt, paint.
const ROUGHNESS: f32 = 0.9;

/// The GLB bytes of `scene`, embedding the PNG of every file in `textures`.
///
/// The JSON is made first, from where every part of the BIN chunk will go; then the file
/// is allocated once, zeroed, and the BIN chunk's sections are filled in place, each on
/// its own task (a city's are tens of megabytes: no second buffer, no copy).
pub fn write_glb(scene: &Scene, textures: &TextureFiles) -> Vec<u8> {
    let plan = plan(scene, textures);
    let mut json = serde_json::to_vec(&plan.doc).expect("the glTF document serializes");
    json.resize(align4(json.len()), b' ');
    let bin_len = align4(plan.end);
    let bin_chunk = if bin_len == 0 { 0 } else { 8 + bin_len };
    let total = 12 + 8 + json.len() + bin_chunk;
    // Zeroed: the BIN's padding, and the uvs of a mesh without its own, stay zero.
    let mut out = vec![0u8; total];
    out[0..4].copy_from_slice(MAGIC);
    out[4..8].copy_from_slice(&2u32.to_le_bytes());
    out[8..12].copy_from_slice(&(total as u32).to_le_bytes());
    out[12..16].copy_from_slice(&(json.len() as u32).to_le_bytes());
    out[16..20].copy_from_slice(CHUNK_JSON);
    out[20..20 + json.len()].copy_from_slice(&json);
    if bin_len > 0 {
        let at = 20 + json.len();
        out[at..at + 4].copy_from_slice(&(bin_len as u32).to_le_bytes());
        out[at + 4..at + 8].copy_from_slice(CHUNK_BIN);
        fill(&mut out[at + 8..], &plan);
    }
    out
}

fn align4(n: usize) -> usize {
    n.div_ceil(4) * 4
}

/// What of a mesh becomes a primitive: vertex count, whether it gets normals and uvs,
/// index count (whole triangles).
struct PrimitiveParts {
    vertices: usize,
    normals: bool,
    uvs: bool,
    indices: usize,
}

impl PrimitiveParts {
    /// `None` for a mesh without a triangle. A mesh without uvs of a textured material
    /// gets zero uvs: glTF requires TEXCOORD_0 wherever a texture is bound.
    fn of(mesh: &Mesh, scene: &Scene, textures: &TextureFiles) -> Option<PrimitiveParts> {
        let vertices = mesh.positions.len();
        let indices = mesh.indices.len() / 3 * 3;
        let textured = scene
            .materials
            .get(mesh.material as usize)
            .is_some_and(|m| textures.file_index(m.texture).is_some());
        (vertices > 0 && indices > 0).then_some(PrimitiveParts {
            vertices,
            normals: mesh.normals.len() == vertices,
            uvs: mesh.uvs.len() == vertices || textured,
            indices,
        })
    }
}

/// One geometry section of the BIN chunk: its bufferView and the next free byte in it.
struct Section {
    view: u32,
    used: usize,
}

impl Section {
    /// Adds a bufferView of `length` bytes at `start`, if `length` is not zero (glTF wants
    /// no empty bufferView).
    fn new(
        doc: &mut GltfDocument,
        start: usize,
        length: usize,
        stride: Option<u32>,
        target: u32,
    ) -> Option<Section> {
        (length > 0).then(|| Section {
            view: push_view(doc, start, length, stride, Some(target)),
            used: 0,
        })
    }

    /// Claims `length` bytes: returns the range within the section and the offset in the
    /// view (the same number: a section is one view).
    fn claim(&mut self, length: usize) -> (Range<usize>, usize) {
        let offset = self.used;
        self.used += length;
        (offset..self.used, offset)
    }
}

/// The four geometry sections, in BIN order.
struct Sections {
    positions: Option<Section>,
    normals: Option<Section>,
    uvs: Option<Section>,
    indices: Option<Section>,
}

/// The JSON document, and where every byte of the BIN chunk comes from.
struct Plan<'s> {
    doc: GltfDocument,
    /// Byte lengths of the position, normal, uv and index sections, in BIN order.
    sections: [usize; 4],
    /// Per texture file, its PNG and where it starts in BIN.
    images: Vec<(usize, &'s [u8])>,
    primitives: Vec<PrimitiveSlots<'s>>,
    /// The end of the last byte used (BIN is this, padded to 4).
    end: usize,
}

/// Where one primitive's data goes: ranges within each section.
struct PrimitiveSlots<'s> {
    mesh: &'s Mesh,
    positions: Range<usize>,
    normals: Option<Range<usize>>,
    /// Where the mesh's own uvs go: `None` without them (a textured mesh's uv slot then
    /// keeps the zeros the file starts with).
    uvs: Option<Range<usize>>,
    indices: Range<usize>,
}

fn plan<'s>(scene: &'s Scene, textures: &TextureFiles) -> Plan<'s> {
    let mut doc = GltfDocument {
        asset: Asset {
            version: "2.0",
            generator: "cityspec",
        },
        ..GltfDocument::default()
    };
    // Sizes first, so every view is placed up front.
    let sizes = section_sizes(scene, textures);
    let [positions, normals, uvs, indices] = sizes;
    // Section sizes are multiples of 4, so every section and the first image are aligned.
    let mut sections = Sections {
        positions: Section::new(&mut doc, 0, positions, Some(12), ARRAY_BUFFER),
        normals: Section::new(&mut doc, positions, normals, Some(12), ARRAY_BUFFER),
        uvs: Section::new(&mut doc, positions + normals, uvs, Some(8), ARRAY_BUFFER),
        indices: Section::new(
            &mut doc,
            positions + normals + uvs,
            indices,
            None,
            ELEMENT_ARRAY_BUFFER,
        ),
    };
    let (images, end) = push_images(&mut doc, scene, textures, sizes.iter().sum());
    let slots = push_nodes(&mut doc, &mut sections, scene, textures);
    push_materials(&mut doc, scene, textures);
    doc.scenes.push(GltfScene {
        nodes: (0..doc.nodes.len() as u32).collect(),
    });
    if end > 0 {
        doc.buffers.push(Buffer {
            byte_length: end as u64,
        });
    }
    Plan {
        doc,
        sections: sizes,
        images,
        primitives: slots,
        end,
    }
}

/// Byte lengths of the position, normal, uv and index sections, in BIN order.
fn section_sizes(scene: &Scene, textures: &TextureFiles) -> [usize; 4] {
    let (mut positions, mut normals, mut uvs, mut indices) = (0, 0, 0, 0);
    let meshes = || scene.objects.iter().flat_map(|o| &o.meshes);
    for parts in meshes().filter_map(|mesh| PrimitiveParts::of(mesh, scene, textures)) {
        positions += parts.vertices * 12;
        normals += if parts.normals {
            parts.vertices * 12
        } else {
            0
        };
        uvs += if parts.uvs { parts.vertices * 8 } else { 0 };
        indices += parts.indices * 4;
    }
    [positions, normals, uvs, indices]
}

/// Adds each texture file's PNG as a bufferView and an image, after the geometry's `end`;
/// returns where each PNG starts in BIN, and the new end.
fn push_images<'s>(
    doc: &mut GltfDocument,
    scene: &'s Scene,
    textures: &TextureFiles,
    mut end: usize,
) -> (Vec<(usize, &'s [u8])>, usize) {
    let mut images = Vec::with_capacity(textures.files().len());
    for file in textures.files() {
        let texture = &scene.textures[file.texture];
        let start = align4(end);
        end = start + texture.png.len();
        images.push((start, &texture.png[..]));
        let buffer_view = push_view(doc, start, texture.png.len(), None, None);
        doc.images.push(Image {
            name: texture.name.clone(),
            buffer_view,
            mime_type: "image/png",
        });
    }
    (images, end)
}

/// Adds a node per scene object, and a mesh for each with a primitive; returns where
/// every primitive's data goes.
fn push_nodes<'s>(
    doc: &mut GltfDocument,
    sections: &mut Sections,
    scene: &'s Scene,
    textures: &TextureFiles,
) -> Vec<PrimitiveSlots<'s>> {
    let mut slots = Vec::new();
    for object in &scene.objects {
        let primitives: Vec<Primitive> = object
            .meshes
            .iter()
            .filter_map(|mesh| {
                let parts = PrimitiveParts::of(mesh, scene, textures)?;
                let (mut primitive, slot) = place_primitive(doc, sections, mesh, &parts);
                slots.push(slot);
                primitive.material =
                    ((mesh.material as usize) < scene.materials.len()).then_some(mesh.material);
                Some(primitive)
            })
            .collect();
        let mesh = (!primitives.is_empty()).then(|| {
            doc.meshes.push(GltfMesh {
                name: object.name.clone(),
                primitives,
            });
            doc.meshes.len() as u32 - 1
        });
        doc.nodes.push(Node {
            name: object.name.clone(),
            mesh,
            extras: NodeExtras {
                class: object.class.clone(),
            },
        });
    }
    slots
}

/// Adds one mesh's accessors, claiming its share of each section; returns the primitive
/// (without its material) referring to them, and where its data goes.
fn place_primitive<'s>(
    doc: &mut GltfDocument,
    sections: &mut Sections,
    mesh: &'s Mesh,
    parts: &PrimitiveParts,
) -> (Primitive, PrimitiveSlots<'s>) {
    // The sections were sized from the same parts, so each one needed here exists.
    let mut attributes = BTreeMap::new();
    let mut slots = PrimitiveSlots {
        mesh,
        positions: 0..0,
        normals: None,
        uvs: None,
        indices: 0..0,
    };
    if let Some(section) = sections.positions.as_mut() {
        let (range, offset) = section.claim(parts.vertices * 12);
        let bounds = bounds(&mesh.positions);
        let a = push_accessor(
            doc,
            section.view,
            offset,
            FLOAT,
            parts.vertices,
            "VEC3",
            Some(bounds),
        );
        attributes.insert("POSITION", a);
        slots.positions = range;
    }
    if let (true, Some(section)) = (parts.normals, sections.normals.as_mut()) {
        let (range, offset) = section.claim(parts.vertices * 12);
        let a = push_accessor(
            doc,
            section.view,
            offset,
            FLOAT,
            parts.vertices,
            "VEC3",
            None,
        );
        attributes.insert("NORMAL", a);
        slots.normals = Some(range);
    }
    if let (true, Some(section)) = (parts.uvs, sections.uvs.as_mut()) {
        let (range, offset) = section.claim(parts.vertices * 8);
        let a = push_accessor(
            doc,
            section.view,
            offset,
            FLOAT,
            parts.vertices,
            "VEC2",
            None,
        );
        attributes.insert("TEXCOORD_0", a);
        slots.uvs = (mesh.uvs.len() == parts.vertices).then_some(range);
    }
    let mut indices = 0;
    if let Some(section) = sections.indices.as_mut() {
        let (range, offset) = section.claim(parts.indices * 4);
        indices = push_accessor(
            doc,
            section.view,
            offset,
            UNSIGNED_INT,
            parts.indices,
            "SCALAR",
            None,
        );
        slots.indices = range;
    }
    let primitive = Primitive {
        attributes,
        indices,
        material: None,
    };
    (primitive, slots)
}

/// Fills the BIN chunk's data (`bin`, zeroed) as `plan` places it: the four sections and
/// the images side by side, each written in primitive order.
fn fill(bin: &mut [u8], plan: &Plan) {
    let [positions, normals, uvs, indices] = plan.sections;
    let (position_bytes, rest) = bin.split_at_mut(positions);
    let (normal_bytes, rest) = rest.split_at_mut(normals);
    let (uv_bytes, rest) = rest.split_at_mut(uvs);
    let (index_bytes, image_bytes) = rest.split_at_mut(indices);
    let images_start = positions + normals + uvs + indices;
    let slots = &plan.primitives;
    rayon::join(
        || {
            rayon::join(
                || {
                    for slot in slots {
                        put_positions(
                            &mut position_bytes[slot.positions.clone()],
                            &slot.mesh.positions,
                        );
                    }
                },
                || {
                    for slot in slots {
                        if let Some(range) = slot.normals.clone() {
                            put_normals(&mut normal_bytes[range], &slot.mesh.normals);
                        }
                    }
                },
            )
        },
        || {
            rayon::join(
                || {
                    for slot in slots {
                        if let Some(range) = slot.uvs.clone() {
                            let floats = slot.mesh.uvs.iter().flatten();
                            for (bytes, v) in uv_bytes[range].chunks_exact_mut(4).zip(floats) {
                                bytes.copy_from_slice(&v.to_le_bytes());
                            }
                        }
                    }
                    for &(start, png) in &plan.images {
                        let at = start - images_start;
                        image_bytes[at..at + png.len()].copy_from_slice(png);
                    }
                },
                || {
                    for slot in slots {
                        let range = slot.indices.clone();
                        for (bytes, i) in index_bytes[range]
                            .chunks_exact_mut(4)
                            .zip(&slot.mesh.indices)
                        {
                            bytes.copy_from_slice(&i.to_le_bytes());
                        }
                    }
                },
            )
        },
    );
}

/// One glTF material per scene material, in order; one texture per image, sharing one
/// sampler (repeat, trilinear).
fn push_materials(doc: &mut GltfDocument, scene: &Scene, textures: &TextureFiles) {
    for material in &scene.materials {
        let [r, g, b] = material.colour.map(super::unit_interval);
        let emissive = material.emissive.map(super::unit_interval);
        let texture = textures
            .file_index(material.texture)
            .map(|i| TextureInfo { index: i as u32 });
        let glows = emissive.iter().any(|&e| e > 0.0);
        doc.materials.push(GltfMaterial {
            name: material.name.clone(),
            pbr_metallic_roughness: PbrMetallicRoughness {
                base_color_factor: [r, g, b, 1.0],
                base_color_texture: texture.clone(),
                metallic_factor: 0.0,
                roughness_factor: ROUGHNESS,
            },
            emissive_factor: glows.then_some(emissive),
            emissive_texture: texture.filter(|_| glows && material.emissive_textured),
        });
    }
    if !doc.images.is_empty() {
        doc.samplers.push(Sampler {
            mag_filter: LINEAR,
            min_filter: LINEAR_MIPMAP_LINEAR,
            wrap_s: REPEAT,
            wrap_t: REPEAT,
        });
        doc.textures = (0..doc.images.len() as u32)
            .map(|source| GltfTexture { sampler: 0, source })
            .collect();
    }
}

fn push_view(
    doc: &mut GltfDocument,
    offset: usize,
    length: usize,
    stride: Option<u32>,
    target: Option<u32>,
) -> u32 {
    doc.buffer_views.push(BufferView {
        buffer: 0,
        byte_offset: offset as u64,
        byte_length: length as u64,
        byte_stride: stride,
        target,
    });
    doc.buffer_views.len() as u32 - 1
}

fn push_accessor(
    doc: &mut GltfDocument,
    buffer_view: u32,
    byte_offset: usize,
    component_type: u32,
    count: usize,
    kind: &'static str,
    bounds: Option<([f32; 3], [f32; 3])>,
) -> u32 {
    doc.accessors.push(Accessor {
        buffer_view,
        byte_offset: byte_offset as u64,
        component_type,
        count: count as u64,
        kind,
        min: bounds.map(|(min, _)| min.map(f64::from)),
        max: bounds.map(|(_, max)| max.map(f64::from)),
    });
    doc.accessors.len() as u32 - 1
}

/// The per-axis min and max of `positions` (glTF requires both).
fn bounds(positions: &[[f32; 3]]) -> ([f32; 3], [f32; 3]) {
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    for p in positions {
        for c in 0..3 {
            min[c] = min[c].min(p[c]);
            max[c] = max[c].max(p[c]);
        }
    }
    (min, max)
}

/// Writes positions (f32, little-endian).
fn put_positions(bin: &mut [u8], positions: &[[f32; 3]]) {
    for (bytes, p) in bin.chunks_exact_mut(12).zip(positions) {
        for c in 0..3 {
            bytes[c * 4..c * 4 + 4].copy_from_slice(&p[c].to_le_bytes());
        }
    }
}

/// Writes normals, normalising those not already of unit length; a zero normal (which
/// cannot be normalised) becomes +y.
fn put_normals(bin: &mut [u8], normals: &[[f32; 3]]) {
    for (slot, &n) in bin.chunks_exact_mut(12).zip(normals) {
        let len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        let n = if (len2 - 1.0).abs() <= 1e-5 {
            n
        } else if len2 > 0.0 && len2.is_finite() {
            let len = len2.sqrt();
            [n[0] / len, n[1] / len, n[2] / len]
        } else {
            [0.0, 1.0, 0.0]
        };
        for c in 0..3 {
            slot[c * 4..c * 4 + 4].copy_from_slice(&n[c].to_le_bytes());
        }
    }
}

#[cfg(test)]
mod tests {
    use serde_json::Value;

    use super::*;
    use crate::export::sample_scene::sample_scene;

    fn u32_at(bytes: &[u8], at: usize) -> usize {
        u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize
    }

    fn f32_at(bytes: &[u8], at: usize) -> f32 {
        f32::from_le_bytes(bytes[at..at + 4].try_into().unwrap())
    }

    fn n(v: &Value) -> usize {
        v.as_u64().unwrap() as usize
    }

    /// Checks the GLB container and returns the JSON and the BIN chunk's data.
    fn open(glb: &[u8]) -> (Value, &[u8]) {
        assert_eq!(&glb[0..4], b"glTF");
        assert_eq!(u32_at(glb, 4), 2, "version");
        assert_eq!(u32_at(glb, 8), glb.len(), "header length");
        let json_len = u32_at(glb, 12);
        assert_eq!(&glb[16..20], b"JSON");
        assert_eq!(json_len % 4, 0);
        let json = &glb[20..20 + json_len];
        assert!(json.ends_with(b"}") || json.ends_with(b" "));
        let doc: Value = serde_json::from_slice(json).expect("JSON chunk parses");
        let rest = &glb[20 + json_len..];
        if rest.is_empty() {
            return (doc, rest);
        }
        let bin_len = u32_at(rest, 0);
        assert_eq!(&rest[4..8], b"BIN\0");
        assert_eq!(bin_len % 4, 0);
        assert_eq!(rest.len(), 8 + bin_len, "nothing after the BIN chunk");
        (doc, &rest[8..])
    }

    /// Every bufferView and accessor in bounds and aligned; returns each accessor's
    /// (absolute byte offset in BIN, stride).
    fn check_bounds(doc: &Value, bin: &[u8]) -> Vec<(usize, usize)> {
        let buffer_len = n(&doc["buffers"][0]["byteLength"]);
        assert!(buffer_len <= bin.len() && bin.len() - buffer_len < 4);
        let views = doc["bufferViews"].as_array().unwrap();
        for v in views {
            let offset = v.get("byteOffset").map_or(0, n);
            assert_eq!(offset % 4, 0, "bufferView aligned");
            assert!(n(&v["byteLength"]) > 0);
            assert!(
                offset + n(&v["byteLength"]) <= buffer_len,
                "bufferView in bounds"
            );
        }
        let mut out = Vec::new();
        for a in doc["accessors"].as_array().unwrap() {
            let view = &views[n(&a["bufferView"])];
            let element = match a["type"].as_str().unwrap() {
                "SCALAR" => 4,
                "VEC2" => 8,
                "VEC3" => 12,
                other => panic!("type {other}"),
            };
            let stride = view.get("byteStride").map_or(element, n);
            let offset = a.get("byteOffset").map_or(0, n);
            let count = n(&a["count"]);
            assert!(count > 0);
            assert_eq!(offset % 4, 0);
            assert!(offset + stride * (count - 1) + element <= n(&view["byteLength"]));
            out.push((view.get("byteOffset").map_or(0, n) + offset, stride));
        }
        out
    }

    #[test]
    fn container_chunks_and_every_reference_in_bounds() {
        let scene = sample_scene();
        let textures = TextureFiles::collect(&scene);
        let glb = write_glb(&scene, &textures);
        let (doc, bin) = open(&glb);
        assert_eq!(
            doc["asset"],
            serde_json::json!({"version": "2.0", "generator": "cityspec"})
        );
        let at = check_bounds(&doc, bin);
        let accessors = doc["accessors"].as_array().unwrap();

        // Nodes: one per object, in order, named, classed, all in the scene.
        let nodes = doc["nodes"].as_array().unwrap();
        assert_eq!(nodes.len(), scene.objects.len());
        for (node, object) in nodes.iter().zip(&scene.objects) {
            assert_eq!(node["name"], object.name.as_str());
            assert_eq!(node["extras"]["class"], object.class.as_str());
            let mesh = &doc["meshes"][n(&node["mesh"])];
            assert_eq!(mesh["name"], object.name.as_str());
            let primitives = mesh["primitives"].as_array().unwrap();
            assert_eq!(primitives.len(), object.meshes.len());
            // The data read back through the accessors is the scene's.
            for (p, m) in primitives.iter().zip(&object.meshes) {
                assert_eq!(n(&p["material"]), m.material as usize);
                let pos = n(&p["attributes"]["POSITION"]);
                assert_eq!(n(&accessors[pos]["count"]), m.positions.len());
                let (start, stride) = at[pos];
                let mut min = [f32::INFINITY; 3];
                let mut max = [f32::NEG_INFINITY; 3];
                for (k, want) in m.positions.iter().enumerate() {
                    for c in 0..3 {
                        let got = f32_at(bin, start + k * stride + c * 4);
                        assert_eq!(got, want[c]);
                        min[c] = min[c].min(got);
                        max[c] = max[c].max(got);
                    }
                }
                let json_min: Vec<f64> =
                    serde_json::from_value(accessors[pos]["min"].clone()).unwrap();
                let json_max: Vec<f64> =
                    serde_json::from_value(accessors[pos]["max"].clone()).unwrap();
                assert_eq!(json_min, min.map(f64::from));
                assert_eq!(json_max, max.map(f64::from));
                let (start, stride) = at[n(&p["attributes"]["TEXCOORD_0"])];
                for (k, want) in m.uvs.iter().enumerate() {
                    assert_eq!(f32_at(bin, start + k * stride + 4), want[1], "v as is");
                }
                let (start, stride) = at[n(&p["attributes"]["NORMAL"])];
                assert_eq!(f32_at(bin, start + stride + 4), m.normals[1][1]);
                let idx = n(&p["indices"]);
                assert_eq!(accessors[idx]["componentType"], UNSIGNED_INT);
                let (start, _) = at[idx];
                let got: Vec<u32> = (0..n(&accessors[idx]["count"]))
                    .map(|k| u32_at(bin, start + k * 4) as u32)
                    .collect();
                assert_eq!(got, m.indices);
                assert!(got.iter().all(|&i| (i as usize) < m.positions.len()));
            }
        }
        assert_eq!(
            doc["scenes"][0]["nodes"].as_array().unwrap().len(),
            nodes.len()
        );
        assert_eq!(doc["scene"], 0);

        // Images: one per distinct texture, the PNG bytes as they are.
        let images = doc["images"].as_array().unwrap();
        assert_eq!(images.len(), textures.files().len());
        assert_eq!(images.len(), 2);
        for (image, file) in images.iter().zip(textures.files()) {
            assert_eq!(image["mimeType"], "image/png");
            let view = &doc["bufferViews"][n(&image["bufferView"])];
            let offset = view.get("byteOffset").map_or(0, n);
            let png = &bin[offset..offset + n(&view["byteLength"])];
            assert_eq!(png, &scene.textures[file.texture].png[..]);
        }
        assert_eq!(doc["textures"].as_array().unwrap().len(), images.len());
        assert_eq!(
            doc["samplers"][0],
            serde_json::json!({"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497})
        );
    }

    #[test]
    fn materials_carry_colour_texture_and_emission() {
        let scene = sample_scene();
        let (doc, _) = open(&write_glb(&scene, &TextureFiles::collect(&scene)));
        let materials = doc["materials"].as_array().unwrap();
        assert_eq!(materials.len(), scene.materials.len());
        let pbr = |i: usize| &materials[i]["pbrMetallicRoughness"];
        assert_eq!(pbr(0)["baseColorTexture"]["index"], 0);
        assert_eq!(
            pbr(1)["baseColorTexture"]["index"],
            0,
            "same bytes, same texture"
        );
        assert_eq!(pbr(4)["baseColorTexture"]["index"], 1);
        assert!(pbr(2).get("baseColorTexture").is_none());
        assert_eq!(pbr(2)["metallicFactor"], 0.0);
        let colour: Vec<f32> = serde_json::from_value(pbr(1)["baseColorFactor"].clone()).unwrap();
        assert_eq!(colour, [0.9, 0.8, 0.7, 1.0]);
        assert_eq!(materials[3]["name"], "lamp_head");
        let emissive: Vec<f32> =
            serde_json::from_value(materials[3]["emissiveFactor"].clone()).unwrap();
        assert_eq!(emissive, [1.0, 0.9, 0.6]);
        assert!(materials[0].get("emissiveFactor").is_none());
    }

    #[test]
    fn degenerate_scenes_stay_valid() {
        // Empty scene: no buffer, no BIN chunk, a scene without nodes.
        let empty = Scene {
            textures: vec![],
            materials: vec![],
            objects: vec![],
        };
        let glb = write_glb(&empty, &TextureFiles::collect(&empty));
        let (doc, bin) = open(&glb);
        assert!(bin.is_empty());
        assert!(doc.get("buffers").is_none() && doc.get("nodes").is_none());
        assert_eq!(doc["scenes"], serde_json::json!([{}]));

        // No normals or uvs anywhere, an empty mesh, a bad material index, a long normal.
        let mut scene = sample_scene();
        for mesh in scene.objects.iter_mut().flat_map(|o| &mut o.meshes) {
            mesh.uvs.clear();
            mesh.normals.clear();
        }
        scene.objects[0].meshes[0].normals = vec![[0.0, 3.0, 0.0]; 4];
        scene.objects[1].meshes[0].material = 99;
        scene.objects[2].meshes[1].indices.truncate(2);
        scene.objects[4].meshes.clear();
        let glb = write_glb(&scene, &TextureFiles::collect(&scene));
        let (doc, bin) = open(&glb);
        let at = check_bounds(&doc, bin);
        let ground = &doc["meshes"][0]["primitives"][0];
        let (start, stride) = at[n(&ground["attributes"]["NORMAL"])];
        assert_eq!(f32_at(bin, start + stride + 4), 1.0, "normalised");
        assert!(doc["meshes"][1]["primitives"][0].get("material").is_none());
        assert_eq!(doc["meshes"][2]["primitives"].as_array().unwrap().len(), 1);
        assert!(doc["nodes"][4].get("mesh").is_none());
        assert_eq!(doc["nodes"][4]["name"], "sign_0000");
        // Textured materials keep (zero) uvs: glTF needs TEXCOORD_0 where a texture is bound.
        for mesh in doc["meshes"].as_array().unwrap() {
            for p in mesh["primitives"].as_array().unwrap() {
                let textured = p.get("material").is_some_and(|m| {
                    doc["materials"][n(m)]["pbrMetallicRoughness"]
                        .get("baseColorTexture")
                        .is_some()
                });
                let uv = p["attributes"].get("TEXCOORD_0");
                assert_eq!(uv.is_some(), textured, "{p}");
                if let Some(uv) = uv {
                    let (start, stride) = at[n(uv)];
                    let count = n(&doc["accessors"][n(uv)]["count"]);
                    assert!((0..count * stride).all(|k| bin[start + k] == 0));
                }
            }
        }
    }
}
