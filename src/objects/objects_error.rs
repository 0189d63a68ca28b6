//! Why inserting objects failed: a user model or word file that cannot be read (each names
//! its file as the spec wrote it).

use thiserror::Error;

/// An objects-stage error; every variant names the spec's `model` or `words_file` string.
#[derive(Debug, Error)]
pub enum ObjectsError {
    #[error("word file {file}: the build did not read it, or it holds no words")]
    MissingWords { file: String },
    #[error("model {model}: the build did not read its files")]
    MissingModel { model: String },
    #[error("model {model}: cannot read the OBJ: {source}")]
    BadObj {
        model: String,
        #[source]
        source: tobj::LoadError,
    },
    #[error("model {model}: cannot read its MTL: {source}")]
    BadMtl {
        model: String,
        #[source]
        source: tobj::LoadError,
    },
    #[error("model {model}: cannot read its MTL: the OBJ names an MTL file the build did not read")]
    MtlNotRead { model: String },
    #[error("model {model}: has no triangles")]
    Empty { model: String },
    #[error("model {model}: texture {texture} named by its MTL is missing")]
    MissingTexture { model: String, texture: String },
    #[error("model {model}: texture {texture} is not a PNG or JPEG image: {source}")]
    BadTexture {
        model: String,
        texture: String,
        #[source]
        source: Box<image::ImageError>,
    },
}
