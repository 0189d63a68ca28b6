//! `cityspec explain SPEC`: each cached stage of a spec, what its key is the hash of, and
//! what the cache holds under it, as cargo writes its fingerprints out.
//!
//! Nothing runs and nothing is written: the keys come from the spec and its input files
//! alone, and each entry is read, not its objects (a build verifies those when it reads
//! them).

use std::path::{Path, PathBuf};

use serde::Serialize;

use super::inputs::SpecInputs;
use super::pipeline::Pipeline;
use super::stages::Stage;
use super::{BuildError, load_spec_with};
use crate::cache::{Cache, EntryState};

/// One stage of a spec.
#[derive(Clone, Debug, Serialize)]
pub struct StageLine {
    pub stage: Stage,
    /// The camera path, for a `frames` stage.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub camera: Option<String>,
    pub key: String,
    /// The stage's `VERSION`.
    pub version: u32,
    /// The names of the spec parts its key holds.
    pub spec: Vec<String>,
    /// The keys of the stages it consumes and the hashes of the input files it reads.
    pub inputs: Vec<(String, String)>,
    /// What the cache holds under the key.
    pub state: EntryState,
}

/// A spec's stages.
#[derive(Clone, Debug, Serialize)]
pub struct Explained {
    pub name: String,
    pub spec: PathBuf,
    pub cache: PathBuf,
    pub stages: Vec<StageLine>,
}

/// Explains the spec at `path` (with `--set` overrides `sets`) against the cache at
/// `cache_dir` (which is not created).
pub fn explain(path: &Path, sets: &[String], cache_dir: &Path) -> Result<Explained, BuildError> {
    let spec = load_spec_with(path, sets)?;
    let inputs = SpecInputs::read(path, &spec)?;
    let cache = Cache::open(cache_dir)?;
    let progress = |_: &str, _: usize, _: usize| {};
    let pipeline = Pipeline::new(&spec, path.to_path_buf(), inputs, &cache, &progress);
    Ok(Explained {
        name: spec.name.clone(),
        spec: path.to_path_buf(),
        cache: cache_dir.to_path_buf(),
        stages: pipeline.explain(),
    })
}
