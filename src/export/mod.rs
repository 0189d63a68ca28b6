//! Export stage: [`Scene`] → the city as files: `city.obj` + `city.mtl` + `textures/*.png`
//! and `city.glb` (glTF 2.0 binary with the textures embedded).
//!
//! Both formats hold the same scene: one OBJ object and one glTF node (with one mesh) per
//! scene object, named after it; one OBJ `usemtl` group and one glTF primitive per mesh;
//! one MTL material and one glTF material per scene material. Each distinct texture (by
//! content) that a material uses is written once, as `textures/<first 16 hex digits of
//! its SHA-256>.png`, referenced by `map_Kd` and embedded once in the GLB.
//!
//! Pure and deterministic: the same scene gives the same bytes on every platform (fixed
//! float formats for the text files, a fixed field order for the glTF JSON). The build
//! driver writes the files and lists them in the manifest.
//!
//! | file | module |
//! |---|---|
//! | `city.obj` | [`obj`] |
//! | `city.mtl` | [`mtl`] |
//! | `city.glb` | [`glb`] (JSON types in [`gltf_document`]) |
//! | `textures/*.png` | [`texture_files`] decides names and sharing |

pub mod fixed;
pub mod glb;
pub mod gltf_document;
pub mod mtl;
pub mod obj;
#[cfg(test)]
mod sample_scene;
pub mod texture_files;

use std::sync::Arc;

use crate::model::Scene;
pub use texture_files::{TextureFile, TextureFiles};

/// Bump when this stage's output bytes change: it is part of the stage's cache key.
pub const VERSION: u32 = 3;

/// The export stage: scene → files, as (path relative to the output folder, bytes), sorted
/// by path: `city.glb`, `city.mtl`, `city.obj`, `textures/<first 16 hex of sha256>.png`…
/// A texture file's bytes are the scene texture's own PNG, shared, not copied.
pub fn export(scene: &Scene) -> Vec<(String, Arc<Vec<u8>>)> {
    let textures = TextureFiles::collect(scene);
    // The GLB and the OBJ text are the two big writes: one on each core.
    let (glb, obj) = rayon::join(
        || glb::write_glb(scene, &textures),
        || obj::write_obj(scene, &textures),
    );
    let mut files = Vec::with_capacity(3 + textures.files().len());
    files.push(("city.glb".to_owned(), Arc::new(glb)));
    files.push((
        "city.mtl".to_owned(),
        Arc::new(mtl::write_mtl(scene, &textures)),
    ));
    files.push(("city.obj".to_owned(), Arc::new(obj)));
    for file in textures.files() {
        let png = &scene.textures[file.texture].png;
        files.push((file.path.clone(), Arc::clone(png)));
    }
    files.sort_by(|a, b| a.0.cmp(&b.0));
    files
}

/// Clamps a colour channel into 0–1, as both MTL readers and glTF expect (NaN becomes 0).
fn unit_interval(x: f32) -> f32 {
    if x > 0.0 { x.min(1.0) } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::sample_scene::sample_scene;
    use super::*;

    #[test]
    fn files_sorted_by_path_with_textures_named_by_content() {
        let scene = sample_scene();
        let files = export(&scene);
        let paths: Vec<&str> = files.iter().map(|(p, _)| &p[..]).collect();
        assert_eq!(paths[..3], ["city.glb", "city.mtl", "city.obj"]);
        assert_eq!(paths.len(), 5, "two distinct used textures: {paths:?}");
        assert!(paths.is_sorted());
        for (path, bytes) in &files[3..] {
            let hash = crate::hash::sha256_hex(bytes);
            assert_eq!(path, &format!("textures/{}.png", &hash[..16]));
            assert!(scene.textures.iter().any(|t| t.png[..] == bytes[..]));
        }
        // Every texture the MTL names is among the files.
        let mtl = std::str::from_utf8(&files[1].1).unwrap();
        for line in mtl.lines().filter_map(|l| l.strip_prefix("map_Kd ")) {
            assert!(paths.contains(&line), "{line}");
        }
    }

    #[test]
    fn same_scene_same_bytes() {
        let scene = sample_scene();
        let a = export(&scene);
        let b = export(&scene.clone());
        assert_eq!(a, b);
        let one_thread = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        assert_eq!(one_thread.install(|| export(&scene)), a);
    }

    #[test]
    fn textures_are_deduplicated_by_content_not_name() {
        let mut scene = sample_scene();
        let before = export(&scene);
        // Renaming a texture changes no file; changing its pixels changes its file name.
        scene.textures[0].name = "renamed".to_owned();
        let renamed = export(&scene);
        assert_eq!(
            before.iter().map(|f| &f.0).collect::<Vec<_>>(),
            renamed.iter().map(|f| &f.0).collect::<Vec<_>>()
        );
        let other = image::RgbImage::from_pixel(8, 8, image::Rgb([1, 2, 3]));
        scene.textures[1] = crate::model::Texture::from_rgb("brick_copy", other);
        let split = export(&scene);
        assert_eq!(
            split.len(),
            before.len() + 1,
            "facade_b's texture now differs"
        );
    }

    #[test]
    fn empty_scene_exports_valid_empty_files() {
        let scene = Scene {
            textures: vec![],
            materials: vec![],
            objects: vec![],
        };
        let files = export(&scene);
        assert_eq!(files.len(), 3);
        let obj = std::str::from_utf8(&files[2].1).unwrap();
        assert!(obj.ends_with("mtllib city.mtl\n"));
    }

    /// Writes the sample scene's export into `$CITYSPEC_EXPORT_SAMPLE_DIR`, for the
    /// external checks of `.ci/run` (glTF validator, trimesh). Run with `--ignored`.
    #[test]
    #[ignore = "writes files for .ci/run's external checks"]
    fn write_sample_export() {
        let dir = std::path::PathBuf::from(
            std::env::var_os("CITYSPEC_EXPORT_SAMPLE_DIR")
                .expect("set CITYSPEC_EXPORT_SAMPLE_DIR to the folder to write"),
        );
        for (path, bytes) in export(&sample_scene()) {
            let path = dir.join(path);
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(&path, &bytes[..]).unwrap();
        }
    }
}
