//! Scene → `city.obj` text: one `o` per scene object, its vertices, and `usemtl` + faces
//! per mesh, referring to the materials of `city.mtl`.
//!
//! Positions print with 4 decimals (0.1 mm), texture coordinates and normals with 5, via
//! [`super::fixed`], so the bytes are the same on every platform. OBJ's `vt` has v up, the
//! scene's v is down from the image top: `vt u (1 - v)`. Indices are global and 1-based.
//! A mesh without triangles writes nothing; a mesh whose uvs or normals do not match its
//! positions in number writes faces without them (`a//c`, `a/b`, `a`).

use rayon::prelude::*;

use super::fixed::{push_fixed, push_u64};
use super::texture_files::TextureFiles;
use crate::model::{Mesh, Scene};

const POSITION_DECIMALS: usize = 4;
const UNIT_DECIMALS: usize = 5;

/// The OBJ text of `scene`; names its materials' library `city.mtl`. A mesh without uvs
/// whose material has a texture gets `vt 0 1` for each vertex (the texture's top-left
/// texel), so that every textured face has texture coordinates, as in the GLB.
pub fn write_obj(scene: &Scene, textures: &TextureFiles) -> Vec<u8> {
    let meshes = || scene.objects.iter().flat_map(|o| &o.meshes);
    let vertices: usize = meshes().map(|m| m.positions.len()).sum();
    let triangles = scene.triangle_count();
    let mut header = Vec::new();
    header.extend_from_slice(b"# city.obj written by cityspec (");
    header.extend_from_slice(env!("CARGO_PKG_NAME").as_bytes());
    header.push(b' ');
    header.extend_from_slice(env!("CARGO_PKG_VERSION").as_bytes());
    header.extend_from_slice(b")\n# objects ");
    push_u64(&mut header, scene.objects.len() as u64);
    header.extend_from_slice(b", vertices ");
    push_u64(&mut header, vertices as u64);
    header.extend_from_slice(b", triangles ");
    push_u64(&mut header, triangles as u64);
    header.extend_from_slice(b"\nmtllib city.mtl\n");

    let material = |mesh: &Mesh| scene.materials.get(mesh.material as usize);
    let textured = |mesh: &Mesh| material(mesh).is_some_and(|m| textures.file(m.texture).is_some());
    // Each object's first 1-based index of each vertex kind, then the objects written in
    // parallel runs (the text is most of a cold build's export), joined in order.
    let mut firsts = Vec::with_capacity(scene.objects.len());
    let mut next = Bases { v: 1, vt: 1, vn: 1 };
    for object in &scene.objects {
        firsts.push(next);
        for mesh in &object.meshes {
            next.advance(mesh, textured(mesh));
        }
    }
    let runs: Vec<Vec<u8>> = scene
        .objects
        .par_chunks(OBJECTS_PER_RUN)
        .zip(firsts.par_chunks(OBJECTS_PER_RUN))
        .map(|(objects, firsts)| {
            let mut run = Vec::new();
            for (object, &first) in objects.iter().zip(firsts) {
                run.extend_from_slice(b"o ");
                push_name(&mut run, &object.name);
                run.push(b'\n');
                let mut next = first;
                for mesh in &object.meshes {
                    let name = material(mesh).map(|m| &m.name[..]);
                    write_mesh(&mut run, mesh, name, textured(mesh), &mut next);
                }
            }
            run
        })
        .collect();
    // The header and the runs copied into the file side by side: it is allocated once,
    // zeroed by the allocator (so its pages are first touched by the copies that fill
    // them), and cut into their places.
    let mut out = vec![0u8; header.len() + runs.iter().map(Vec::len).sum::<usize>()];
    let (head, mut rest) = out.split_at_mut(header.len());
    head.copy_from_slice(&header);
    let mut places = Vec::with_capacity(runs.len());
    for run in &runs {
        let (place, after) = rest.split_at_mut(run.len());
        places.push(place);
        rest = after;
    }
    places
        .into_par_iter()
        .zip(&runs)
        .for_each(|(place, run)| place.copy_from_slice(run));
    out
}

/// Objects a parallel run of [`write_obj`] writes.
const OBJECTS_PER_RUN: usize = 256;

#[derive(Clone, Copy)]
struct Bases {
    v: u64,
    vt: u64,
    vn: u64,
}

impl Bases {
    /// Past the vertices `mesh` writes (none for a mesh without triangles or positions).
    fn advance(&mut self, mesh: &Mesh, textured: bool) {
        if mesh.indices.len() / 3 == 0 || mesh.positions.is_empty() {
            return;
        }
        let has_uv = mesh.uvs.len() == mesh.positions.len() || textured;
        let has_normal = mesh.normals.len() == mesh.positions.len();
        let count = mesh.positions.len() as u64;
        self.v += count;
        self.vt += if has_uv { count } else { 0 };
        self.vn += if has_normal {
            normal_runs(&mesh.normals)
        } else {
            0
        };
    }
}

fn write_mesh(
    out: &mut Vec<u8>,
    mesh: &Mesh,
    material: Option<&str>,
    textured: bool,
    next: &mut Bases,
) {
    let triangles = mesh.indices.len() / 3;
    if triangles == 0 || mesh.positions.is_empty() {
        return;
    }
    let own_uvs = mesh.uvs.len() == mesh.positions.len();
    let has_uv = own_uvs || textured;
    let has_normal = mesh.normals.len() == mesh.positions.len();
    write_vertices(out, mesh, own_uvs, has_uv);
    let normal_of = if has_normal {
        write_normals(out, &mesh.normals)
    } else {
        Vec::new()
    };
    if let Some(name) = material {
        out.extend_from_slice(b"usemtl ");
        push_name(out, name);
        out.push(b'\n');
    }
    for tri in mesh.indices[..triangles * 3].chunks_exact(3) {
        out.push(b'f');
        for &i in tri {
            let i = u64::from(i);
            out.push(b' ');
            push_u64(out, next.v + i);
            if has_uv || has_normal {
                out.push(b'/');
            }
            if has_uv {
                push_u64(out, next.vt + i);
            }
            if has_normal {
                out.push(b'/');
                push_u64(out, next.vn + normal_of[i as usize]);
            }
        }
        out.push(b'\n');
    }
    next.advance(mesh, textured);
}

/// The `v` lines of `mesh`, then its `vt` lines: its own uvs (v flipped up), zeros when
/// it has none but needs them (`has_uv`), or none.
fn write_vertices(out: &mut Vec<u8>, mesh: &Mesh, own_uvs: bool, has_uv: bool) {
    for p in &mesh.positions {
        out.push(b'v');
        for &c in p {
            out.push(b' ');
            push_fixed(out, c, POSITION_DECIMALS);
        }
        out.push(b'\n');
    }
    if own_uvs {
        for &[u, v] in &mesh.uvs {
            out.extend_from_slice(b"vt ");
            push_fixed(out, u, UNIT_DECIMALS);
            out.push(b' ');
            push_fixed(out, 1.0 - v, UNIT_DECIMALS);
            out.push(b'\n');
        }
    } else if has_uv {
        for _ in &mesh.positions {
            out.extend_from_slice(b"vt 0.00000 1.00000\n");
        }
    }
}

/// One `vn` line per run of equal normals (a flat-shaded face's corners share one);
/// returns each vertex's normal index, counted from 0.
fn write_normals(out: &mut Vec<u8>, normals: &[[f32; 3]]) -> Vec<u64> {
    let mut normal_of = Vec::with_capacity(normals.len());
    let mut last: Option<[f32; 3]> = None;
    let mut count = 0u64;
    for &n in normals {
        if last.is_none_or(|l| l.map(f32::to_bits) != n.map(f32::to_bits)) {
            out.extend_from_slice(b"vn");
            for c in n {
                out.push(b' ');
                push_fixed(out, c, UNIT_DECIMALS);
            }
            out.push(b'\n');
            last = Some(n);
            count += 1;
        }
        normal_of.push(count - 1);
    }
    normal_of
}

/// How many `vn` lines `normals` take: one per run of equal normals.
fn normal_runs(normals: &[[f32; 3]]) -> u64 {
    let bits = |n: &[f32; 3]| n.map(f32::to_bits);
    let changes = normals
        .windows(2)
        .filter(|w| bits(&w[0]) != bits(&w[1]))
        .count();
    if normals.is_empty() {
        0
    } else {
        changes as u64 + 1
    }
}

/// Appends a name as OBJ and MTL can hold it: one token, so whitespace and control
/// characters become `_` (scene names are file-name-safe already; this only guards).
pub fn push_name(out: &mut Vec<u8>, name: &str) {
    if name.is_empty() {
        out.push(b'_');
    } else if name.bytes().all(|b| b.is_ascii_graphic()) {
        out.extend_from_slice(name.as_bytes());
    } else {
        let mut buf = [0u8; 4];
        for c in name.chars() {
            let c = if c.is_whitespace() || c.is_control() {
                '_'
            } else {
                c
            };
            out.extend_from_slice(c.encode_utf8(&mut buf).as_bytes());
        }
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;
    use std::io::Cursor;

    use super::*;
    use crate::export::mtl::write_mtl;
    use crate::export::sample_scene::sample_scene;

    fn load(scene: &Scene) -> (Vec<tobj::Model>, Vec<tobj::Material>) {
        let obj = write_obj(scene, &TextureFiles::collect(scene));
        let mtl = write_mtl(scene, &TextureFiles::collect(scene));
        let options = tobj::LoadOptions {
            triangulate: false,
            single_index: false,
            ..Default::default()
        };
        let (models, materials) = tobj::load_obj_buf(&mut Cursor::new(obj), &options, |path| {
            assert_eq!(path, std::path::Path::new("city.mtl"));
            tobj::load_mtl_buf(&mut Cursor::new(&mtl[..]))
        })
        .expect("tobj reads the OBJ");
        (models, materials.expect("tobj reads the MTL"))
    }

    /// What tobj makes of the scene: per object, consecutive meshes of one material merged.
    fn groups(scene: &Scene) -> Vec<(String, Mesh)> {
        let mut out: Vec<(String, Mesh)> = Vec::new();
        for object in &scene.objects {
            for (k, mesh) in object.meshes.iter().enumerate() {
                match out.last_mut() {
                    Some((_, last)) if k > 0 && last.material == mesh.material => {
                        let base = last.positions.len() as u32;
                        last.positions.extend(&mesh.positions);
                        last.normals.extend(&mesh.normals);
                        last.uvs.extend(&mesh.uvs);
                        last.indices.extend(mesh.indices.iter().map(|i| i + base));
                    }
                    _ => out.push((object.name.clone(), mesh.clone())),
                }
            }
        }
        out
    }

    #[test]
    fn tobj_reads_back_objects_faces_and_materials() {
        let scene = sample_scene();
        let (models, materials) = load(&scene);

        // tobj starts a model per object and per change of material inside one.
        let names: BTreeSet<&str> = models.iter().map(|m| &m.name[..]).collect();
        let want: BTreeSet<&str> = scene.objects.iter().map(|o| &o.name[..]).collect();
        assert_eq!(names, want);
        assert_eq!(models.len(), groups(&scene).len());
        let faces: usize = models.iter().map(|m| m.mesh.indices.len() / 3).sum();
        assert_eq!(faces, scene.triangle_count());
        assert_eq!(materials.len(), scene.materials.len());

        let exported: BTreeSet<String> = TextureFiles::collect(&scene)
            .files()
            .iter()
            .map(|f| f.path.clone())
            .collect();
        for (want, got) in scene.materials.iter().zip(&materials) {
            assert_eq!(got.name, want.name);
            assert_eq!(got.diffuse, Some(want.colour));
            match (&want.texture, &got.diffuse_texture) {
                (Some(_), Some(path)) => assert!(exported.contains(path), "{path}"),
                (None, None) => {}
                other => panic!("{}: texture mismatch {other:?}", want.name),
            }
        }
        // Each model has its object's name and its meshes' material.
        let got: Vec<(&str, usize)> = models
            .iter()
            .map(|m| (&m.name[..], m.mesh.material_id.unwrap()))
            .collect();
        let groups = groups(&scene);
        let want: Vec<(&str, usize)> = groups
            .iter()
            .map(|(name, mesh)| (&name[..], mesh.material as usize))
            .collect();
        assert_eq!(got, want);
    }

    #[test]
    fn vertices_round_trip_with_v_flipped() {
        let scene = sample_scene();
        let (models, _) = load(&scene);
        let groups = groups(&scene);
        assert_eq!(models.len(), groups.len());
        for (model, (_, mesh)) in models.iter().zip(&groups) {
            let m = &model.mesh;
            assert_eq!(m.positions.len(), mesh.positions.len() * 3);
            for (k, &i) in m.indices.iter().enumerate() {
                // tobj's indices are per model; the scene's are per mesh: same order here.
                let src = mesh.indices[k] as usize;
                for c in 0..3 {
                    let p = m.positions[i as usize * 3 + c];
                    assert!((p - mesh.positions[src][c]).abs() <= 5e-5);
                }
                let t = m.texcoord_indices[k] as usize;
                assert!((m.texcoords[t * 2] - mesh.uvs[src][0]).abs() <= 5e-6);
                assert!((m.texcoords[t * 2 + 1] - (1.0 - mesh.uvs[src][1])).abs() <= 5e-6);
                let n = m.normal_indices[k] as usize;
                assert_eq!(m.normals[n * 3 + 1], mesh.normals[src][1]);
            }
        }
    }

    #[test]
    fn fixed_text_without_negative_zero() {
        let obj = String::from_utf8(write_obj(
            &sample_scene(),
            &TextureFiles::collect(&sample_scene()),
        ))
        .unwrap();
        assert!(obj.starts_with("# city.obj written by cityspec"));
        assert!(obj.contains("\nmtllib city.mtl\no ground\nv -50.0000 0.0000 50.0000\n"));
        assert!(
            obj.contains("\nvn 0.00000 1.00000 0.00000\n"),
            "ground normal"
        );
        assert!(!obj.contains("-0.0000"), "negative zero");
        // The ground's four corners share normal 1; the first wall's, normal 2.
        assert!(obj.contains("\nusemtl facade_a\nf 5/5/2 6/6/2 7/7/2\nf 5/5/2 7/7/2 8/8/2\n"));
        assert!(obj.ends_with('\n'));
    }

    #[test]
    fn missing_uvs_or_normals_and_odd_meshes() {
        let mesh = |material: u32, uvs: usize, normals: usize, indices: &[u32]| Mesh {
            material,
            positions: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]],
            normals: vec![[0.0, 1.0, 0.0]; normals],
            uvs: vec![[0.25, 0.5]; uvs],
            indices: indices.to_vec(),
        };
        // (material, uvs, normals, indices, face lines, vt lines); material 0 (facade_a)
        // is textured, 2 (roof) is not.
        type Case<'a> = (u32, usize, usize, &'a [u32], &'a str, &'a str);
        let cases: &[Case] = &[
            (
                2,
                3,
                3,
                &[0, 1, 2],
                "f 1/1/1 2/2/1 3/3/1\n",
                "vt 0.25000 0.50000\n",
            ),
            (2, 0, 3, &[0, 1, 2], "f 1//1 2//1 3//1\n", ""),
            (
                2,
                3,
                0,
                &[0, 1, 2],
                "f 1/1 2/2 3/3\n",
                "vt 0.25000 0.50000\n",
            ),
            (2, 0, 0, &[0, 1, 2], "f 1 2 3\n", ""),
            (2, 2, 1, &[0, 1, 2, 0], "f 1 2 3\n", ""),
            (
                0,
                0,
                3,
                &[0, 1, 2],
                "f 1/1/1 2/2/1 3/3/1\n",
                "vt 0.00000 1.00000\n",
            ),
            (
                0,
                2,
                0,
                &[0, 1, 2],
                "f 1/1 2/2 3/3\n",
                "vt 0.00000 1.00000\n",
            ),
            (2, 3, 3, &[0, 1], "", ""),
        ];
        for &(material, uvs, normals, indices, faces, vt) in cases {
            let mut scene = sample_scene();
            scene.objects.truncate(1);
            scene.objects[0].meshes = vec![mesh(material, uvs, normals, indices)];
            let obj = write_obj(&scene, &TextureFiles::collect(&scene));
            let obj = String::from_utf8(obj).unwrap();
            let tail = obj.split_once("o ground\n").unwrap().1;
            let case = format!("material {material}, {uvs} uvs, {normals} normals:\n{tail}");
            if faces.is_empty() {
                assert_eq!(tail, "", "a mesh without a triangle writes nothing");
                continue;
            }
            let name = &scene.materials[material as usize].name;
            assert!(tail.ends_with(&format!("usemtl {name}\n{faces}")), "{case}");
            // The three corners share one normal: one `vn`.
            let vns = tail.lines().filter(|l| l.starts_with("vn ")).count();
            assert_eq!(vns, usize::from(normals == 3), "{case}");
            let vts: Vec<&str> = tail.lines().filter(|l| l.starts_with("vt ")).collect();
            if vt.is_empty() {
                assert!(vts.is_empty(), "{case}");
            } else {
                assert_eq!(vts, [vt.trim_end(); 3], "{case}");
            }
        }
    }

    #[test]
    fn names_stay_one_token() {
        let mut out = Vec::new();
        for name in ["building_0001", "two words", "tab\there", "", "façade 2"] {
            push_name(&mut out, name);
            out.push(b'|');
        }
        assert_eq!(
            out,
            "building_0001|two_words|tab_here|_|façade_2|".as_bytes()
        );
    }
}
