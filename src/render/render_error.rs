//! Why a scene cannot be prepared for rendering.

use thiserror::Error;

/// A scene the renderer cannot draw.
#[derive(Debug, Error)]
pub enum RenderError {
    /// A texture's PNG bytes do not decode.
    #[error("texture {name:?} does not decode: {source}")]
    Texture {
        name: String,
        #[source]
        source: image::ImageError,
    },
    /// Instance ids are 24-bit (RGB-packed in the ids PNG): 0 is the sky, objects are
    /// 1–16,777,215.
    #[error("the scene has {count} objects; instance ids allow at most 16777215")]
    TooManyObjects { count: usize },
    /// A mesh names a material the scene does not have.
    #[error("object {object:?}: a mesh uses material {material}, but the scene has {count}")]
    MissingMaterial {
        object: String,
        material: u32,
        count: usize,
    },
    /// A material names a texture the scene does not have.
    #[error("material {material:?} uses texture {texture}, but the scene has {count}")]
    MissingTexture {
        material: String,
        texture: u32,
        count: usize,
    },
    /// A mesh index points past the mesh's positions.
    #[error("object {object:?}: index {index} is past the mesh's {count} positions")]
    BadIndex {
        object: String,
        index: u32,
        count: usize,
    },
}
