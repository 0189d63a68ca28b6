//! The entries placed as two groups side by side, then replayed into one result.
//!
//! Text entries place plates on walls and read nothing the other kinds place; those share
//! the ground (strips, curbs, corners). Each group is placed on its own core, in entry
//! order, in its own [`Placing`]; then every entry's share is replayed in entry order into
//! one: its materials registered again (a material registered once per name by an
//! earlier entry of the other group is that one), its names numbered again, its objects
//! moved over. The result is the one of placing every entry in turn, byte for byte: the
//! groups draw from the entries' own streams, and naming and registering depend only on
//! the order of the calls, which the replay keeps.

use std::collections::BTreeMap;

use super::{
    EntryShare, Inserted, ObjectsError, ObjectsInput, PlacedEntries, next_name, place_entries,
};
use crate::model::geometry::MaterialBook;
use crate::spec::{EntryKind, ObjectSpec};

/// See [`super::insert`].
pub(super) fn insert(input: &ObjectsInput) -> Result<Inserted, ObjectsError> {
    let on_walls = |spec: &ObjectSpec| spec.kind == EntryKind::Text;
    let (walls, ground) = rayon::join(
        || place_entries(input, on_walls),
        || place_entries(input, |spec| !on_walls(spec)),
    );
    let (walls, ground) = match (walls, ground) {
        (Ok(walls), Ok(ground)) => (walls, ground),
        // The first entry's error, as placing in turn would stop at it.
        (Err((i, e)), Err((j, f))) => return Err(if i < j { e } else { f }),
        (Err((_, e)), Ok(_)) | (Ok(_), Err((_, e))) => return Err(e),
    };
    let mut groups = [Group::new(walls), Group::new(ground)];
    let mut book = MaterialBook::default();
    let mut once: BTreeMap<String, u32> = BTreeMap::new();
    let mut counters = BTreeMap::new();
    let mut out = Inserted::default();
    for (i, spec) in input.specs.iter().enumerate() {
        let group = &mut groups[usize::from(!on_walls(spec))];
        let share = group.shares[i]
            .take()
            .expect("each entry is placed by its group");
        for m in share.materials.clone() {
            let request = &group.requests[m];
            let material = &group.materials[m];
            let known = request
                .once
                .then(|| once.get(&request.name).copied())
                .flatten();
            let index = known.unwrap_or_else(|| {
                let texture = material.texture.map(|t| &group.textures[t as usize]);
                let index = book.add(&request.name, material.colour, texture, material.emissive);
                if material.emissive_textured {
                    book.texture_emission(index);
                }
                if request.once {
                    once.insert(request.name.clone(), index);
                }
                index
            });
            group.material_index.push(index);
        }
        let mut renamed = BTreeMap::new();
        for prefix in &group.name_calls[share.names.clone()] {
            let old = next_name(&mut group.counters, prefix);
            renamed.insert(old, next_name(&mut counters, prefix));
        }
        // A group's entries come in order, and their objects with them.
        let objects = group.objects.by_ref().zip(group.info.by_ref());
        for (k, (mut object, info)) in share.objects.clone().zip(objects) {
            if let Some(name) = renamed.get(&object.name) {
                object.name.clone_from(name);
            }
            for mesh in &mut object.meshes {
                mesh.material = group.material_index[mesh.material as usize];
            }
            if let Some(face) = group.sign_faces.remove(&k) {
                out.sign_faces.insert(out.objects.len(), face);
            }
            out.objects.push(object);
            out.info.push(info);
        }
        out.placed.push(share.placed);
    }
    (out.textures, out.materials) = book.finish();
    Ok(out)
}

/// One group's result, taken apart for the replay.
struct Group {
    shares: Vec<Option<EntryShare>>,
    requests: Vec<super::MaterialRequest>,
    materials: Vec<crate::model::Material>,
    textures: Vec<crate::model::Texture>,
    name_calls: Vec<String>,
    objects: std::vec::IntoIter<crate::model::SceneObject>,
    info: std::vec::IntoIter<super::ObjectInfo>,
    sign_faces: BTreeMap<usize, super::SignFace>,
    /// The group's names as it numbered them, numbered again in replay order.
    counters: BTreeMap<String, u32>,
    /// Per material of the group, its index in the replayed book.
    material_index: Vec<u32>,
}

impl Group {
    fn new(PlacedEntries { placing, shares }: PlacedEntries) -> Group {
        let (textures, materials) = placing.book.finish();
        Group {
            shares,
            requests: placing.requests,
            materials,
            textures,
            name_calls: placing.name_calls,
            objects: placing.out.objects.into_iter(),
            info: placing.out.info.into_iter(),
            sign_faces: placing.out.sign_faces,
            counters: BTreeMap::new(),
            material_index: Vec::new(),
        }
    }
}
