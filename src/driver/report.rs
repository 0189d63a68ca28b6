//! What a build did: which stages ran or came from the cache, what it wrote.

use std::path::PathBuf;
use std::time::Duration;

/// Whether a stage's outputs were computed or taken from the cache.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum StageStatus {
    Ran,
    Cached,
}

/// One stage of one build.
#[derive(Clone, Debug)]
pub struct StageRun {
    pub stage: &'static str,
    /// The camera of a `frames` stage (one per `[[cameras]]` entry), else `None`.
    pub camera: Option<String>,
    pub key: String,
    pub status: StageStatus,
    /// Time spent on the stage (lookup and verification when cached).
    pub time: Duration,
    /// Set when a cache entry existed but was damaged and the stage was rebuilt.
    pub repaired: Option<String>,
}

/// The result of building one spec.
#[derive(Clone, Debug)]
pub struct BuildReport {
    pub name: String,
    /// The spec file built (the CLI places diagnostics in it).
    pub spec: PathBuf,
    pub out_dir: PathBuf,
    /// Stages in the order they finished. Stages whose outputs were not needed (because
    /// everything downstream came from the cache) do not appear.
    pub stages: Vec<StageRun>,
    /// Artifacts (and `manifest.json`) written because they were new or changed.
    pub written: Vec<String>,
    /// Artifacts already present with the right bytes.
    pub unchanged: Vec<String>,
    /// Files of an earlier build that this build no longer produces, now removed.
    pub removed: Vec<String>,
    /// The diagnostics of every stage the build used, run or cached (facades skipped for
    /// bad data, objects short of their count, …), sorted.
    pub warnings: Vec<crate::diagnostic::Diagnostic>,
    /// Triangles in the 3D scene, when this build made the scene.
    pub triangles: Option<usize>,
    pub elapsed: Duration,
}

impl BuildReport {
    pub fn ran(&self) -> impl Iterator<Item = &StageRun> {
        self.stages.iter().filter(|s| s.status == StageStatus::Ran)
    }

    /// Nothing ran and nothing was written.
    pub fn up_to_date(&self) -> bool {
        self.ran().next().is_none() && self.written.is_empty() && self.removed.is_empty()
    }
}
