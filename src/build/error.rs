//! Why a build failed, and whether the user's input or the build is to blame.

use std::io;
use std::path::PathBuf;

use crate::spec::SpecErrors;

/// A failed build. [`BuildError::is_input_error`] separates bad input (exit code 2) from
/// failures of the build itself (exit code 1).
#[derive(Debug, thiserror::Error)]
pub enum BuildError {
    /// The spec file could not be read.
    #[error("cannot read spec {}: {source}", path.display())]
    ReadSpec { path: PathBuf, source: io::Error },
    /// The spec is invalid; every error is inside.
    #[error("{0}")]
    Spec(SpecErrors),
    /// An input file the spec names is unusable.
    #[error("{}: {key} = {}: {message}", spec.display(), file.display())]
    Input {
        spec: PathBuf,
        key: &'static str,
        file: PathBuf,
        message: String,
    },
    /// The facade set is unusable (the message names the file).
    #[error("{}: facades: {message}", spec.display())]
    Facades { spec: PathBuf, message: String },
    /// An inserted object is unusable (a model file that does not load).
    #[error("{}: objects: {message}", spec.display())]
    Objects { spec: PathBuf, message: String },
    /// `--strict`: the build would have succeeded with these warnings.
    #[error("{}: --strict: {}", spec.display(), warnings.join("; "))]
    Strict {
        spec: PathBuf,
        warnings: Vec<String>,
    },
    /// The renderer refused the scene (a cityspec bug or an unusable texture).
    #[error("{}: render: {message}", spec.display())]
    Render { spec: PathBuf, message: String },
    /// Two specs of one build share a name and so an output folder.
    #[error("{} and {} are both named {name:?}: they would write the same output folder", first.display(), second.display())]
    DuplicateName {
        name: String,
        first: PathBuf,
        second: PathBuf,
    },
    /// Writing the output folder failed.
    #[error("cannot write {}: {source}", path.display())]
    Output { path: PathBuf, source: io::Error },
    /// The output folder is one cityspec must not replace (a link, a folder of the
    /// user's), or a stage named a path outside it.
    #[error("{}: {message}", path.display())]
    OutputFolder { path: PathBuf, message: String },
    /// Writing the cache failed.
    #[error("cannot write the cache at {}: {source}", path.display())]
    Cache { path: PathBuf, source: io::Error },
    /// `--locked`: the build's artifacts differ from the spec's lock file, or there is none.
    #[error("{}: the build differs from the lock:\n  {}", lock.display(), differences.join("\n  "))]
    Locked {
        lock: PathBuf,
        differences: Vec<String>,
    },
    /// A cached value that verified by hash still did not decode: a cityspec bug.
    #[error("cached output of stage {stage} did not decode: {message}")]
    Decode {
        stage: &'static str,
        message: String,
    },
}

impl BuildError {
    /// Whether the user's spec or input is at fault (exit code 2) rather than the build.
    pub fn is_input_error(&self) -> bool {
        matches!(
            self,
            BuildError::ReadSpec { .. }
                | BuildError::Spec(_)
                | BuildError::Input { .. }
                | BuildError::Facades { .. }
                | BuildError::Objects { .. }
                | BuildError::Strict { .. }
                | BuildError::DuplicateName { .. }
        )
    }
}
