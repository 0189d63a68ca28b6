//! FakeWorld: a [`SpecWorld`] of fixed images and no folders or other files.

use std::path::Path;

use crate::spec::SpecWorld;

/// A world that knows only the images it is given (path as the spec stage resolves it,
/// and size); every folder and other file is missing.
#[derive(Clone, Debug, Default)]
pub struct FakeWorld {
    images: Vec<(&'static str, (u32, u32))>,
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
        }
    }
}

impl SpecWorld for FakeWorld {
    fn folder(&self, path: &Path) -> Result<(), String> {
        Err(format!("no folder {} in this fake world", path.display()))
    }

    fn file(&self, path: &Path) -> Result<(), String> {
        Err(format!("no file {} in this fake world", path.display()))
    }

    fn image_dimensions(&self, path: &Path) -> Result<(u32, u32), String> {
        self.images
            .iter()
            .find(|(p, _)| Path::new(p) == path)
            .map(|(_, size)| *size)
            .ok_or_else(|| "no such file".to_string())
    }
}
