//! Scene textures → the texture files the export writes: one per distinct PNG that some
//! material uses, named by content hash, shared by the OBJ/MTL and the glTF writers.

use std::collections::BTreeMap;

use rayon::prelude::*;

use crate::model::Scene;

/// The distinct texture files of a scene, in order of first use by its materials.
///
/// Two scene textures with the same PNG bytes become one file (and one glTF image); a
/// texture no material uses is not exported at all.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TextureFiles {
    /// Per scene texture: the index of its file in `files`, if some material uses it.
    file_of_texture: Vec<Option<usize>>,
    files: Vec<TextureFile>,
}

/// One exported texture file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TextureFile {
    /// `textures/<first 16 hex digits of the PNG's SHA-256>.png`.
    pub path: String,
    /// The first scene texture with these bytes (index into [`Scene::textures`]).
    pub texture: usize,
}

impl TextureFiles {
    /// Hashes each texture that a material uses, once (on every core), and deduplicates
    /// by content.
    pub fn collect(scene: &Scene) -> TextureFiles {
        let mut file_of_texture = vec![None; scene.textures.len()];
        let mut used = vec![false; scene.textures.len()];
        let mut first_use = Vec::new();
        for material in &scene.materials {
            let Some(t) = material.texture.map(|t| t as usize) else {
                continue;
            };
            if t < scene.textures.len() && !used[t] {
                used[t] = true;
                first_use.push(t);
            }
        }
        let hashes: Vec<String> = first_use
            .par_iter()
            .map(|&t| crate::hash::sha256_hex(&scene.textures[t].png))
            .collect();
        let mut files = Vec::new();
        let mut by_hash: BTreeMap<String, usize> = BTreeMap::new();
        for (t, hash) in first_use.into_iter().zip(hashes) {
            let next = files.len();
            let file = *by_hash.entry(hash[..16].to_owned()).or_insert(next);
            if file == next {
                files.push(TextureFile {
                    path: format!("textures/{}.png", &hash[..16]),
                    texture: t,
                });
            }
            file_of_texture[t] = Some(file);
        }
        TextureFiles {
            file_of_texture,
            files,
        }
    }

    /// The file index (= glTF image index) of a material's texture, if it has a valid one.
    pub fn file_index(&self, texture: Option<u32>) -> Option<usize> {
        texture.and_then(|t| self.file_of_texture.get(t as usize).copied().flatten())
    }

    /// The file of a material's texture, if it has a valid one.
    pub fn file(&self, texture: Option<u32>) -> Option<&TextureFile> {
        self.file_index(texture).map(|i| &self.files[i])
    }

    /// Every distinct file, in order of first use.
    pub fn files(&self) -> &[TextureFile] {
        &self.files
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::sample_scene::sample_scene;

    #[test]
    fn shared_bytes_make_one_file_and_unused_textures_none() {
        let scene = sample_scene();
        let files = TextureFiles::collect(&scene);
        // brick and brick_copy hold the same pixels; unused is used by no material.
        assert_eq!(files.files().len(), 2);
        let brick = files.file_index(Some(0));
        assert!(brick.is_some());
        assert_eq!(files.file_index(Some(1)), brick);
        assert_ne!(files.file_index(Some(2)), brick);
        assert_eq!(files.file_index(Some(3)), None, "unused texture");
        assert_eq!(files.file_index(Some(99)), None, "out of range");
        assert_eq!(files.file_index(None), None);
        for file in files.files() {
            let hash = crate::hash::sha256_hex(&scene.textures[file.texture].png);
            assert_eq!(file.path, format!("textures/{}.png", &hash[..16]));
        }
    }
}
