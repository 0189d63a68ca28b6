//! FakeWorld: a [`SpecWorld`] of fixed images and no folders or other files.

use std::path::{Path, PathBuf};

use crate::spec::{Spec, SpecSource, SpecWorld, load};

/// A world that knows only the images it is given (path as the spec stage resolves it,
/// and size); every folder and other file is missing.
#[derive(Clone, Debug, Default)]
pub struct FakeWorld {
    images: Vec<(&'static str, (u32, u32))>,
    specs: Vec<(&'static str, String)>,
}

impl FakeWorld {
    /// A world with no files at all.
    pub fn empty() -> FakeWorld {
        FakeWorld::default()
    }

    /// A world with these images (`"specs/a.png"`, `(640, 480)`).
    pub fn with_images(images: &[(&'static str, (u32, u32))]) -> FakeWorld {
        FakeWorld {
            images: images.to_vec(),
            specs: Vec::new(),
        }
    }

    /// This world with one more spec file a spec may extend (path as resolved).
    pub fn with_spec(mut self, path: &'static str, text: &str) -> FakeWorld {
        self.specs.push((path, text.to_string()));
        self
    }

    /// Loads spec `text` as if read from `path` in this world: the spec, or its problems
    /// as `key: message`.
    pub fn load(&self, path: &str, text: String) -> Result<Spec, Vec<String>> {
        let source = SpecSource {
            path: PathBuf::from(path),
            text,
        };
        load(&source, self).map_err(|e| {
            e.diagnostics
                .iter()
                .map(|d| format!("{}: {}", d.key, d.message))
                .collect()
        })
    }
}

impl SpecWorld for FakeWorld {
    fn folder(&self, path: &Path) -> Result<(), String> {
        Err(format!("no folder {} in this fake world", path.display()))
    }

    fn file(&self, path: &Path) -> Result<(), String> {
        Err(format!("no file {} in this fake world", path.display()))
    }

    fn spec_text(&self, path: &Path) -> Result<String, String> {
        self.specs
            .iter()
            .find(|(p, _)| Path::new(p) == path)
            .map(|(_, text)| text.clone())
            .ok_or_else(|| "no such file".to_string())
    }

    fn image_dimensions(&self, path: &Path) -> Result<(u32, u32), String> {
        self.images
            .iter()
            .find(|(p, _)| Path::new(p) == path)
            .map(|(_, size)| *size)
            .ok_or_else(|| "no such file".to_string())
    }
}
