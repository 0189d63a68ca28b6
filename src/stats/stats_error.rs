//! Why an output folder cannot be measured.

use std::path::PathBuf;

use thiserror::Error;

/// A folder `cityspec stats` cannot read.
#[derive(Debug, Error)]
pub enum StatsError {
    #[error("cannot read {path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: {message}")]
    Bad { path: PathBuf, message: String },
    #[error(
        "{dir} holds no camera path (no frames/<name>/coco.json): build a spec with [[cameras]] first"
    )]
    NoPaths { dir: PathBuf },
}
