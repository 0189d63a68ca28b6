//! Scene → [`PreparedScene`]: decoded mip-mapped textures, flattened triangles with their
//! instance ids and face normals, and per-object bounding boxes for frustum culling.

use std::sync::{Arc, Mutex};

use rayon::prelude::*;

use super::RenderError;
use super::mip_texture::MipTexture;
use super::occlusion;
use super::shadow_map::ShadowMap;
use crate::model::geometry::{cross, dot, normalize};
use crate::model::{Mesh, Movement, ObjectKind, Scene, SceneObject, Texture};

/// The most objects a scene may hold: instance ids are 24-bit (the ids PNG packs them into
/// RGB, `id = R + 256·G + 256²·B`), and 0 is the sky.
pub const MAX_OBJECTS: u32 = (1 << 24) - 1;

/// A scene ready to render many frames: decoded textures with mip chains, flattened
/// triangles, per-object instance ids (object index + 1; 0 = sky) and bounding boxes.
pub struct PreparedScene {
    pub(crate) textures: Vec<Arc<MipTexture>>,
    pub(crate) materials: Vec<ShadeMaterial>,
    pub(crate) objects: Vec<ObjectBounds>,
    pub(crate) triangles: Vec<Triangle>,
    /// The last shadow map built, with the sun direction it was built for: a camera path
    /// under one sun builds it once.
    shadows: Mutex<Option<LastShadowMap>>,
    /// The last shadow map built without the objects that move ([`PreparedScene::posed`]),
    /// which each posed frame copies and adds its moved objects to.
    still_shadows: Mutex<Option<LastShadowMap>>,
}

/// A sun direction's bits, the map's side and the map (`None`: the sun is down).
type LastShadowMap = ([u32; 3], u32, Option<Arc<ShadowMap>>);

/// What shading needs of a material.
#[derive(Clone)]
pub(crate) struct ShadeMaterial {
    pub colour: [f32; 3],
    pub texture: Option<u32>,
    pub emissive: [f32; 3],
    /// Emission times the texture (a backlit face).
    pub emissive_textured: bool,
}

/// An object's box and its run of triangles.
#[derive(Clone)]
pub(crate) struct ObjectBounds {
    pub min: [f64; 3],
    pub max: [f64; 3],
    pub first: usize,
    pub end: usize,
    /// Whether its triangles are big enough to hide others ([`super::occlusion`]).
    pub occluder: bool,
    /// Whether the shadow map holds it: not the ground and fields (the floor shades
    /// nothing) nor the hills (they stand beyond everything they could shade, and would
    /// spread the map's texels over the countryside).
    pub casts_shadow: bool,
}

/// One triangle, wound counter-clockwise around `normal` (its front).
#[derive(Clone)]
pub(crate) struct Triangle {
    pub p: [[f32; 3]; 3],
    pub uv: [[f32; 2]; 3],
    /// Unit face normal, pointing to the front.
    pub normal: [f32; 3],
    pub material: u32,
    pub instance: u32,
}

impl PreparedScene {
    /// Number of objects (instance ids run 1..=this).
    pub fn object_count(&self) -> usize {
        self.objects.len()
    }

    /// The shadow map for the sun in direction `sun`, at most `side` texels a side (built
    /// now, or the last one if it was built for the same direction and side). `None` when
    /// the sun is at or below the horizon.
    ///
    /// The lock is never held while a map is built: the build runs rayon jobs, and a
    /// worker waiting for one of them may take up another frame that asks for a map here
    /// (frames render side by side); holding the lock then deadlocks. Frames that start
    /// together may each build the map; the builds are the same bytes and the first one
    /// stored is kept. A camera path builds it once ahead of its frames
    /// ([`super::warm_shadow_map`]).
    pub(crate) fn shadow_map(&self, sun: [f32; 3], side: u32) -> Option<Arc<ShadowMap>> {
        kept_map(&self.shadows, sun, side, || {
            ShadowMap::build(self, sun.map(f64::from), side, &[])
        })
    }

    /// This scene with `movement` applied: its moving objects shifted by their offsets
    /// (their bounds with them) and the signal lamps' materials swapped. With `shadows`
    /// (the sun's direction and the map's side) the posed scene's shadow map is made at
    /// once: the map of everything that stands still (built once per sun and kept here),
    /// copied, with the moved objects added. The map's extent stays this scene's, so
    /// shadows do not crawl from frame to frame; at time 0 (nothing moved) the map is
    /// the very one the scene as built renders with.
    pub fn posed(&self, movement: &Movement, shadows: Option<([f32; 3], u32)>) -> PreparedScene {
        let mut triangles = self.triangles.clone();
        let mut objects = self.objects.clone();
        for &(id, offset) in &movement.moves {
            let Some(object) = objects.get_mut((id as usize).wrapping_sub(1)) else {
                continue;
            };
            if offset == [0.0; 3] {
                continue;
            }
            let d = offset.map(|v| v as f32);
            let run = &mut triangles[object.first..object.end];
            for t in run.iter_mut() {
                for p in &mut t.p {
                    for k in 0..3 {
                        p[k] += d[k];
                    }
                }
            }
            (object.min, object.max) = box_of(run);
        }
        for r in &movement.recolour {
            let Some(object) = objects.get((r.instance as usize).wrapping_sub(1)) else {
                continue;
            };
            for t in &mut triangles[object.first..object.end] {
                if t.material == r.from {
                    t.material = r.to;
                }
            }
        }
        let posed = PreparedScene {
            textures: self.textures.clone(),
            materials: self.materials.clone(),
            objects,
            triangles,
            shadows: Mutex::new(None),
            still_shadows: Mutex::new(None),
        };
        if let Some((sun, side)) = shadows {
            let movers: Vec<u32> = movement.moves.iter().map(|(id, _)| *id).collect();
            let map = self.still_shadow_map(sun, side, &movers).map(|still| {
                let mut map = (*still).clone();
                map.add(&posed, &movers);
                Arc::new(map)
            });
            *posed.shadows.lock().unwrap_or_else(|e| e.into_inner()) =
                Some((sun.map(f32::to_bits), side, map));
        }
        posed
    }

    /// The shadow map of everything but `movers` (instance ids, ascending), over this
    /// scene's whole extent: built now, or the last one if it was for the same sun and
    /// side.
    fn still_shadow_map(&self, sun: [f32; 3], side: u32, movers: &[u32]) -> Option<Arc<ShadowMap>> {
        kept_map(&self.still_shadows, sun, side, || {
            ShadowMap::build(self, sun.map(f64::from), side, movers)
        })
    }

    /// Number of drawable triangles (degenerate and non-finite ones are dropped).
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }
}

/// Mip chains made ahead of [`prepare_with`] (beside other work), each with the PNG
/// allocation it was decoded from: a scene texture that still holds that very allocation
/// takes the chain instead of decoding and halving its pixels again.
#[derive(Default)]
pub struct TextureMips(Vec<(Arc<Vec<u8>>, Arc<MipTexture>)>);

impl TextureMips {
    /// The mip chains of `textures`, made in parallel. A texture that does not decode is
    /// left out: [`prepare_with`] reports it.
    pub fn of(textures: &[Texture]) -> TextureMips {
        TextureMips(
            textures
                .par_iter()
                .filter_map(|t| {
                    let image = t.decode().ok()?;
                    Some((Arc::clone(&t.png), Arc::new(MipTexture::new(image))))
                })
                .collect(),
        )
    }

    /// The chain made from this very PNG allocation, if any.
    fn find(&self, png: &Arc<Vec<u8>>) -> Option<Arc<MipTexture>> {
        self.0
            .iter()
            .find(|(made_from, _)| Arc::ptr_eq(made_from, png))
            .map(|(_, mips)| Arc::clone(mips))
    }

    /// How many chains are held.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// Whether none is held.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

/// [`prepare_with`] with no chains made ahead.
pub fn prepare(scene: &Scene) -> Result<PreparedScene, RenderError> {
    prepare_with(scene, &TextureMips::default())
}

/// Decodes textures (in parallel; those with a chain in `mips` take it) and flattens the
/// meshes.
///
/// The winding decides the front face, except where a mesh's vertex normals disagree
/// with it: then the normals win and the triangle is turned round, so a wall wound the
/// wrong way still shows its outside. Degenerate triangles and those with non-finite
/// coordinates are dropped; missing uvs read as (0, 0).
pub fn prepare_with(scene: &Scene, mips: &TextureMips) -> Result<PreparedScene, RenderError> {
    if scene.objects.len() > MAX_OBJECTS as usize {
        return Err(RenderError::TooManyObjects {
            count: scene.objects.len(),
        });
    }
    let materials = shade_materials(scene)?;
    let textures = decode_textures(scene, mips)?;
    let mut objects = Vec::with_capacity(scene.objects.len());
    let mut triangles = Vec::with_capacity(scene.triangle_count());
    for (index, object) in scene.objects.iter().enumerate() {
        let instance = (index + 1) as u32;
        let first = triangles.len();
        for mesh in &object.meshes {
            if mesh.material as usize >= materials.len() {
                return Err(RenderError::MissingMaterial {
                    object: object.name.clone(),
                    material: mesh.material,
                    count: materials.len(),
                });
            }
            flatten_mesh(object, mesh, instance, &mut triangles)?;
        }
        let casts_shadow = !matches!(object.kind, ObjectKind::Ground | ObjectKind::Hills);
        objects.push(ObjectBounds::of(&triangles, first, casts_shadow));
    }
    Ok(PreparedScene {
        textures,
        materials,
        objects,
        triangles,
        shadows: Mutex::new(None),
        still_shadows: Mutex::new(None),
    })
}

/// The scene's materials as the shader reads them; an error for one naming a texture
/// the scene lacks.
fn shade_materials(scene: &Scene) -> Result<Vec<ShadeMaterial>, RenderError> {
    let mut materials = Vec::with_capacity(scene.materials.len());
    for m in &scene.materials {
        if let Some(t) = m.texture
            && t as usize >= scene.textures.len()
        {
            return Err(RenderError::MissingTexture {
                material: m.name.clone(),
                texture: t,
                count: scene.textures.len(),
            });
        }
        materials.push(ShadeMaterial {
            colour: m.colour,
            texture: m.texture,
            emissive: m.emissive,
            emissive_textured: m.emissive_textured,
        });
    }
    Ok(materials)
}

/// Every scene texture's mip chain, decoded in parallel unless `mips` has it.
fn decode_textures(scene: &Scene, mips: &TextureMips) -> Result<Vec<Arc<MipTexture>>, RenderError> {
    scene
        .textures
        .par_iter()
        .map(|t| {
            if let Some(made) = mips.find(&t.png) {
                return Ok(made);
            }
            t.decode()
                .map(|image| Arc::new(MipTexture::new(image)))
                .map_err(|source| RenderError::Texture {
                    name: t.name.clone(),
                    source,
                })
        })
        .collect()
}

/// Appends `mesh`'s triangles (of object `instance`) to `triangles`, turned round where
/// its vertex normals disagree with the winding; drops degenerate and non-finite ones.
fn flatten_mesh(
    object: &SceneObject,
    mesh: &Mesh,
    instance: u32,
    triangles: &mut Vec<Triangle>,
) -> Result<(), RenderError> {
    for tri in mesh.indices.chunks_exact(3) {
        let mut ids = [tri[0], tri[1], tri[2]];
        if let Some(&bad) = ids.iter().find(|&&i| i as usize >= mesh.positions.len()) {
            return Err(RenderError::BadIndex {
                object: object.name.clone(),
                index: bad,
                count: mesh.positions.len(),
            });
        }
        let pos = |i: u32| mesh.positions[i as usize].map(f64::from);
        if !ids.iter().all(|&i| pos(i).iter().all(|v| v.is_finite())) {
            continue;
        }
        let (a, b, c) = (pos(ids[0]), pos(ids[1]), pos(ids[2]));
        let face = cross(
            [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
            [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
        );
        let Some(mut normal) = normalize(face) else {
            continue;
        };
        if ids.iter().all(|&i| (i as usize) < mesh.normals.len()) {
            let n = ids.iter().fold([0.0; 3], |s, &i| {
                let n = mesh.normals[i as usize].map(f64::from);
                [s[0] + n[0], s[1] + n[1], s[2] + n[2]]
            });
            if dot(n, normal) < 0.0 {
                ids.swap(1, 2);
                normal = normal.map(|v| -v);
            }
        }
        let uv = |i: u32| mesh.uvs.get(i as usize).copied().unwrap_or([0.0, 0.0]);
        triangles.push(Triangle {
            p: ids.map(|i| mesh.positions[i as usize]),
            uv: ids.map(uv),
            normal: normal.map(|v| v as f32),
            material: mesh.material,
            instance,
        });
    }
    Ok(())
}

/// The map `slot` keeps if it was built for `sun` and `side`, else one `build` makes now
/// (and `slot` keeps, unless another frame stored one meanwhile: the same bytes). The lock
/// is not held while building ([`PreparedScene::shadow_map`] says why).
fn kept_map(
    slot: &Mutex<Option<LastShadowMap>>,
    sun: [f32; 3],
    side: u32,
    build: impl FnOnce() -> Option<ShadowMap>,
) -> Option<Arc<ShadowMap>> {
    let key = (sun.map(f32::to_bits), side);
    let last = |slot: &Option<LastShadowMap>| {
        slot.as_ref()
            .filter(|(bits, built_side, _)| (*bits, *built_side) == key)
            .map(|(_, _, map)| map.clone())
    };
    if let Some(map) = last(&slot.lock().unwrap_or_else(|e| e.into_inner())) {
        return map;
    }
    let map = build().map(Arc::new);
    let mut kept = slot.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(earlier) = last(&kept) {
        return earlier;
    }
    *kept = Some((key.0, key.1, map.clone()));
    map
}

/// The box around `triangles`' corners.
fn box_of(triangles: &[Triangle]) -> ([f64; 3], [f64; 3]) {
    let mut min = [f64::INFINITY; 3];
    let mut max = [f64::NEG_INFINITY; 3];
    for t in triangles {
        for p in t.p {
            for k in 0..3 {
                min[k] = min[k].min(f64::from(p[k]));
                max[k] = max[k].max(f64::from(p[k]));
            }
        }
    }
    (min, max)
}

impl ObjectBounds {
    /// The bounds of the object whose triangles are `triangles[first..]`.
    fn of(triangles: &[Triangle], first: usize, casts_shadow: bool) -> ObjectBounds {
        let (min, max) = box_of(&triangles[first..]);
        ObjectBounds {
            min,
            max,
            first,
            end: triangles.len(),
            occluder: occlusion::is_occluder(&triangles[first..]),
            casts_shadow,
        }
    }
}
