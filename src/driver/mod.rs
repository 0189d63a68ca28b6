//! Build driver: spec files → output folders of content-hashed artifacts, through the cache.
//!
//! The only code that knows the stage order, reads and writes files and keeps the cache.
//! For each spec it reads the TOML, validates it ([`crate::spec::load`]), computes every
//! stage key, pulls the artifacts through the cache (`pipeline`) and puts them into
//! `<out>/<name>/` (`out_dir`): the folder is replaced whole or not at all, under a lock
//! that makes builds of one folder take turns. Files that already hold the right bytes are
//! kept, so a rebuild with nothing changed writes nothing.

mod build_world;
mod cache_gc;
mod chunks;
mod codec;
mod decode_error;
mod error;
mod explain;
mod frame_labels;
mod frames;
mod input_problem;
mod inputs;
#[cfg(test)]
mod kitti_tests;
mod model_files;
mod osm_map;
mod output_names;
mod pack;
mod pipeline;
mod render_input;
mod report;
mod shard;
mod source_frame;
mod spec_build;
mod stage_key;
mod stages;
mod verify;
mod webdataset;

use std::collections::BTreeMap;
use std::io;
use std::path::{Path, PathBuf};

pub use crate::atomic_file::{sweep_temporaries, write_atomic, write_atomic_with};
pub use crate::cache::cache_location;
pub use crate::cache::{Blob, Cache, CacheName, EntryState, Load, MARKER, Miss};
pub use crate::out_dir::{Artifact, Manifest};
/// Kept here for the tests and benches that place buildings by hand.
pub use crate::place::widths_px;
pub use build_world::BuildWorld;
pub use cache_gc::{GcOptions, GcReport, gc, parse_size};
/// The driver's encodings' version (PNG settings, JSON layout), in every stage key.
pub use codec::VERSION as CODEC_VERSION;
pub use decode_error::DecodeError;
pub use error::BuildError;
pub use explain::{Explained, StageLine, explain};
pub use osm_map::{MAX_EXTRACT_BYTES, OsmOutputs, read_osm};
pub use output_names::{OutputNames, is_safe_relative};
pub use pack::{Packed, SPEC_ENTRY, pack};
pub use pipeline::ArtifactOut;
pub use render_input::{PathRenderInput, path_render_input};
pub use report::{BuildReport, StageRun, StageStatus};
pub use shard::{Shard, ShardArg, ShardReport, ShardStats, build_shards};
pub use source_frame::{SourceFrame, framed_report};
pub use spec_build::build_spec;
pub use stages::{Declaration, Produces, Stage, key_table};
pub use verify::{Verdict, VerifyOptions, VerifyReport, verify, verify_all};

use crate::out_dir::lock;
use crate::spec::{self, Spec, SpecSource, SpecWorld};

/// Told of rendered frames: (spec name, camera name, frames done, frames in the path).
pub type Progress = std::sync::Arc<dyn Fn(&str, &str, usize, usize) + Send + Sync>;

/// Told that another build holds the output folder (its path) and this one waits its turn.
pub type Waiting = std::sync::Arc<dyn Fn(&Path) + Send + Sync>;

/// Where a build writes.
#[derive(Clone)]
pub struct BuildOptions {
    /// Each spec writes to `<out_root>/<name>/`.
    pub out_root: PathBuf,
    /// The stage cache.
    pub cache_dir: PathBuf,
    /// Called as frames are rendered (the CLI draws a progress bar).
    pub progress: Option<Progress>,
    /// Called when this build must wait for another build of the same output folder.
    pub waiting: Option<Waiting>,
    /// Warnings (objects placed fewer times than asked, facade problems) fail the build
    /// with [`BuildError::Strict`] before the output folder is touched.
    pub strict: bool,
    /// `--locked`: artifacts that differ from the spec's lock file (or a missing lock)
    /// fail the build with [`BuildError::Locked`] before the output folder is touched.
    pub locked: bool,
    /// `--set key.path=value` overrides, applied to every spec after its `extends`.
    pub sets: Vec<String>,
}

impl Default for BuildOptions {
    fn default() -> Self {
        BuildOptions {
            out_root: PathBuf::from("out"),
            cache_dir: PathBuf::from(".cityspec-cache"),
            progress: None,
            waiting: None,
            strict: false,
            locked: false,
            sets: Vec::new(),
        }
    }
}

/// Reads and validates one spec file (and the bases it extends).
pub fn load_spec(path: &Path) -> Result<Spec, BuildError> {
    load_spec_with(path, &[])
}

/// [`load_spec`], with `--set` overrides (`key.path=value`) applied after `extends`.
pub fn load_spec_with(path: &Path, sets: &[String]) -> Result<Spec, BuildError> {
    load_spec_in(path, sets, &BuildWorld)
}

/// [`load_spec_with`] through `world` (`cityspec pack` notes the specs it reads).
pub(crate) fn load_spec_in(
    path: &Path,
    sets: &[String],
    world: &dyn SpecWorld,
) -> Result<Spec, BuildError> {
    // Capped, and refused unless a regular file: a spec that is `/dev/zero` fails at once.
    let text = spec::read_text_capped(path, spec::MAX_SPEC_BYTES).map_err(|source| {
        BuildError::SpecFile {
            path: path.to_path_buf(),
            source,
        }
    })?;
    let source = SpecSource {
        path: path.to_path_buf(),
        text,
    };
    spec::load_with(&source, sets, world).map_err(BuildError::Spec)
}

/// Loads and validates every spec first, reporting all their errors together; then runs
/// `each` on each spec in order, stopping at the first failure.
pub(crate) fn each_valid_spec<R>(
    paths: &[PathBuf],
    sets: &[String],
    mut each: impl FnMut(&Path, &Spec) -> Result<R, BuildError>,
) -> Result<Vec<R>, Vec<BuildError>> {
    let mut specs = Vec::new();
    let mut errors = Vec::new();
    for path in paths {
        match load_spec_with(path, sets) {
            Ok(spec) => specs.push((path, spec)),
            Err(e) => errors.push(e),
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    specs
        .iter()
        .map(|(path, spec)| each(path, spec).map_err(|e| vec![e]))
        .collect()
}

/// Validates every spec first (so all their errors show at once), then builds each in turn.
/// Stops at the first spec whose build fails.
pub fn build_all(
    paths: &[PathBuf],
    options: &BuildOptions,
) -> Result<Vec<BuildReport>, Vec<BuildError>> {
    let mut specs = Vec::new();
    let mut errors = Vec::new();
    let mut names: BTreeMap<String, PathBuf> = BTreeMap::new();
    for path in paths {
        match load_spec_with(path, &options.sets) {
            Ok(spec) => {
                if let Some(first) = names.insert(spec.name.clone(), path.clone()) {
                    errors.push(BuildError::DuplicateName {
                        name: spec.name.clone(),
                        first,
                        second: path.clone(),
                    });
                }
                specs.push((path, spec));
            }
            Err(e) => errors.push(e),
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    specs
        .iter()
        .map(|(path, spec)| build_spec(path, spec, options).map_err(|e| vec![e]))
        .collect()
}

/// Builds one spec file.
pub fn build(path: &Path, options: &BuildOptions) -> Result<BuildReport, BuildError> {
    let spec = load_spec_with(path, &options.sets)?;
    build_spec(path, &spec, options)
}

/// Checks a spec as `build` would before running any stage: the spec itself, every input
/// file it names (read, hashed and parsed as the build reads them), and a facade folder's
/// photos, boxes and floors, processed as the facades stage does. Returns the spec and the
/// facade warnings a build would print. `sets`: `--set` overrides, as [`load_spec_with`].
pub fn validate(
    path: &Path,
    sets: &[String],
) -> Result<(Spec, Vec<crate::diagnostic::Diagnostic>), BuildError> {
    let spec = load_spec_with(path, sets)?;
    let inputs = inputs::SpecInputs::read(path, &spec)?;
    let warnings = match &inputs.facades {
        inputs::FacadeInput::Builtin => Vec::new(),
        inputs::FacadeInput::Folder { source, .. } => {
            let f = &spec.facades;
            let (_, warnings) = crate::facades::process(source, f.floor_height, f.on_error)
                .map_err(|source| BuildError::Facades {
                    spec: path.to_path_buf(),
                    source,
                })?;
            warnings
        }
    };
    Ok((spec, warnings))
}

/// `cityspec lock`: builds every spec, then writes each one's lock file beside it from the
/// manifest the build wrote; returns the lock files' paths.
pub fn lock_all(
    paths: &[PathBuf],
    options: &BuildOptions,
) -> Result<Vec<PathBuf>, Vec<BuildError>> {
    let options = BuildOptions {
        locked: false,
        ..options.clone()
    };
    let reports = build_all(paths, &options)?;
    paths
        .iter()
        .zip(&reports)
        .map(|(spec, report)| {
            let path = report.out_dir.join("manifest.json");
            let manifest = std::fs::read(&path)
                .ok()
                .and_then(|bytes| Manifest::from_bytes(&bytes))
                .ok_or_else(|| {
                    vec![BuildError::Output {
                        path: path.clone(),
                        source: io::Error::other("the manifest just written does not read back"),
                    }]
                })?;
            let lock = lock::lock_path(spec);
            write_atomic(&lock, lock::render(&manifest).as_bytes()).map_err(|source| {
                vec![BuildError::Output {
                    path: lock.clone(),
                    source,
                }]
            })?;
            Ok(lock)
        })
        .collect()
}

/// Writes cityspec's built-in facade set to `dir` in the CMP layout; returns how many facades.
pub fn export_builtin_facades(dir: &Path) -> Result<usize, BuildError> {
    let source = crate::facades::builtin();
    for (name, bytes) in source.to_files() {
        let path = dir.join(name);
        write_atomic(&path, &bytes).map_err(|source| BuildError::Output { path, source })?;
    }
    Ok(source.files.len())
}
