//! Why a build failed, and whether the user's input or the build is to blame.

use std::io;
use std::path::PathBuf;

use super::decode_error::DecodeError;
use super::input_problem::InputProblem;
use crate::diagnostic::Diagnostic;
use crate::facades::FacadeError;
use crate::layout::LayoutError;
use crate::objects::ObjectsError;
use crate::render::RenderError;
use crate::spec::{InputFileError, SpecErrors};

/// A failed build. Each stage's error is kept whole as the [`source`](std::error::Error::source),
/// so the CLI can tell bad input (exit code 2) from failures of the build itself (exit
/// code 1) by the cause, not by the message.
#[derive(Debug, thiserror::Error)]
pub enum BuildError {
    /// The spec file could not be read (missing, a folder or device, too large, not
    /// UTF-8).
    #[error("cannot read spec {}: expected a spec file, found {source}", path.display())]
    SpecFile {
        path: PathBuf,
        #[source]
        source: InputFileError,
    },
    /// A file given in place of a spec (a lock file) could not be read.
    #[error("cannot read spec {}: {source}", path.display())]
    ReadSpec { path: PathBuf, source: io::Error },
    /// The spec is invalid; every error is inside.
    #[error("{0}")]
    Spec(SpecErrors),
    /// An input file the spec names cannot be read or used (missing, too large, not a
    /// regular file, not UTF-8, a model that does not parse): `entry` names the spec entry
    /// when the key is a list's (`objects[2].model`).
    #[error("{}: {key} = {}: {source}{}", spec.display(), file.display(), entry.as_deref().map(|e| format!(" ({e})")).unwrap_or_default())]
    Input {
        spec: PathBuf,
        key: &'static str,
        file: PathBuf,
        entry: Option<String>,
        #[source]
        source: Box<InputProblem>,
    },
    /// The layout image the spec names does not decode.
    #[error("{}: layout.image = {}: {source}", spec.display(), file.display())]
    Layout {
        spec: PathBuf,
        file: PathBuf,
        #[source]
        source: LayoutError,
    },
    /// The facade set is unusable (the source names the file).
    #[error("{}: facades: {source}", spec.display())]
    Facades {
        spec: PathBuf,
        #[source]
        source: FacadeError,
    },
    /// An inserted object is unusable (a model file that does not load).
    #[error("{}: objects: {source}", spec.display())]
    Objects {
        spec: PathBuf,
        #[source]
        source: ObjectsError,
    },
    /// `[annotations] cityscapes = true` with more classes than Cityscapes' instance
    /// images can number.
    #[error("{}: annotations.cityscapes: {source}", spec.display())]
    Classes {
        spec: PathBuf,
        #[source]
        source: crate::annotate::TooManyClasses,
    },
    /// `--strict`: the build would have succeeded with these warnings.
    #[error("{}: --strict: {}", spec.display(), joined(warnings))]
    Strict {
        spec: PathBuf,
        warnings: Vec<Diagnostic>,
    },
    /// The renderer refused the scene: too many objects for the instance ids (the spec
    /// asks for too much), or a cityspec bug (a mesh naming a missing material).
    #[error("{}: render: {source}", spec.display())]
    Render {
        spec: PathBuf,
        #[source]
        source: RenderError,
    },
    /// Two specs of one build share a name and so an output folder.
    #[error("{} and {} are both named {name:?}: they would write the same output folder", first.display(), second.display())]
    DuplicateName {
        name: String,
        first: PathBuf,
        second: PathBuf,
    },
    /// `cityspec osm`: the extract cannot be read (missing, not a regular file, too large).
    #[error("cannot read the extract {}: {source}", file.display())]
    OsmFile {
        file: PathBuf,
        #[source]
        source: crate::spec::InputFileError,
    },
    /// `cityspec osm`: the extract is not OpenStreetMap data, or broken, or the box is wrong.
    #[error("{}: {source}", file.display())]
    Osm {
        file: PathBuf,
        #[source]
        source: crate::osm::OsmError,
    },
    /// `cityspec pack` could not read a file it packs, or write the archive.
    #[error("cannot pack {}: {source}", path.display())]
    Pack { path: PathBuf, source: io::Error },
    /// Writing the output folder failed.
    #[error("cannot write {}: {source}", path.display())]
    Output { path: PathBuf, source: io::Error },
    /// `cache gc` was pointed at a folder (or prefix) that is not a cityspec cache.
    #[error("{}: not a cityspec cache: {why}", path.display())]
    NotACache { path: PathBuf, why: String },
    /// `--out` names something that is not a folder (a usage error).
    #[error("{}: --out names a file, not a folder: give the folder the spec's output folder goes in (default `out`)", path.display())]
    OutNotAFolder { path: PathBuf },
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
    #[error("cached output of stage {stage} did not decode: {source}")]
    Decode {
        stage: &'static str,
        #[source]
        source: DecodeError,
    },
}

/// Diagnostics on one line, `; `-separated.
fn joined(diagnostics: &[Diagnostic]) -> String {
    let lines: Vec<String> = diagnostics.iter().map(ToString::to_string).collect();
    lines.join("; ")
}

impl From<crate::cache::OpenError> for BuildError {
    fn from(e: crate::cache::OpenError) -> BuildError {
        BuildError::Cache {
            path: e.path,
            source: e.source,
        }
    }
}
