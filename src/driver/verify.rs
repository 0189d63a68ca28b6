//! Cache verification: spec + cache → for a seeded sample of the cached stages (or all),
//! whether running the stage again gives the bytes its entry names.
//!
//! In the spirit of Nix's `--check`: the cache is trusted by key (see ARCHITECTURE.md,
//! "Trust model"), and an entry that names whole, valid objects which are not the stage's
//! output, whether poisoned or left by a cityspec that forgot to bump a `VERSION`, is only
//! found by rebuilding. A rechecked stage takes its inputs from the cache, so a wrong entry
//! is blamed on its own stage, not on the stages downstream of it. Nothing is written to
//! the output folder; the cache gains only entries of input stages that were missing.

use super::stages::Stage;
use std::path::{Path, PathBuf};

use rand::RngExt;

use super::each_valid_spec;
use super::error::BuildError;
use super::inputs::SpecInputs;
use super::pipeline::Pipeline;
use crate::cache::{Cache, Miss, Outputs};
use crate::spec::Spec;

/// Which cached stages to recheck.
#[derive(Clone, Debug)]
pub struct VerifyOptions {
    pub cache_dir: PathBuf,
    /// Every cached stage, not a sample.
    pub all: bool,
    /// How many stages a sample holds.
    pub sample: usize,
    /// Picks the sample.
    pub seed: u64,
}

/// One rechecked stage.
#[derive(Clone, Debug)]
pub struct Verdict {
    pub stage: &'static str,
    pub key: String,
    /// The entry's file.
    pub entry: PathBuf,
    /// `None` when the rebuilt bytes are the cached ones; else what differs.
    pub problem: Option<String>,
}

/// The checks of one spec.
#[derive(Clone, Debug)]
pub struct VerifyReport {
    pub name: String,
    /// Stages of the spec with a cache entry.
    pub cached: usize,
    pub verdicts: Vec<Verdict>,
}

impl VerifyReport {
    pub fn failed(&self) -> impl Iterator<Item = &Verdict> {
        self.verdicts.iter().filter(|v| v.problem.is_some())
    }
}

/// Validates every spec, then verifies each.
pub fn verify_all(
    paths: &[PathBuf],
    options: &VerifyOptions,
) -> Result<Vec<VerifyReport>, Vec<BuildError>> {
    each_valid_spec(paths, &[], |path, spec| verify(path, spec, options))
}

/// Reruns the chosen cached stages of `spec` and compares their outputs with the cache's.
pub fn verify(
    path: &Path,
    spec: &Spec,
    options: &VerifyOptions,
) -> Result<VerifyReport, BuildError> {
    let inputs = SpecInputs::read(path, spec)?;
    let cache = Cache::open(&options.cache_dir)?;
    let quiet = |_: &str, _: usize, _: usize| {};
    let mut pipeline = Pipeline::new(spec, path.to_path_buf(), inputs, &cache, &quiet);
    let cached: Vec<(Stage, String)> = pipeline
        .all_stages()
        .into_iter()
        .filter(|(_, key)| cache.has_entry(key))
        .collect();
    let mut chosen: Vec<usize> = (0..cached.len()).collect();
    if !options.all {
        // A partial Fisher–Yates shuffle: the first `sample` of a seeded permutation.
        let mut stream = crate::rng::stream(options.seed, "verify", 0);
        let take = options.sample.min(chosen.len());
        for i in 0..take {
            let j = stream.random_range(i..chosen.len());
            chosen.swap(i, j);
        }
        chosen.truncate(take);
        chosen.sort_unstable();
    }
    let mut verdicts = Vec::new();
    for i in chosen {
        let (stage, key) = &cached[i];
        let verdict = pipeline.recheck(*stage, key)?;
        verdicts.push(Verdict {
            stage: stage.name(),
            key: key.clone(),
            entry: cache.entry_path(key),
            problem: verdict,
        });
    }
    Ok(VerifyReport {
        name: spec.name.clone(),
        cached: cached.len(),
        verdicts,
    })
}

/// What differs between a stage's cached outputs and the ones it just made, if anything.
pub fn compare(cached: &Result<Outputs, Miss>, rebuilt: &Outputs) -> Option<String> {
    let cached = match cached {
        Ok(outputs) => outputs,
        Err(Miss::Absent) => return Some("the entry disappeared".to_owned()),
        Err(Miss::Corrupt(why)) => return Some(format!("damaged entry: {why}")),
    };
    let short = |sha: &str| sha.get(..12).unwrap_or(sha).to_owned() + "…";
    let mut problems = Vec::new();
    for (name, blob) in cached {
        match rebuilt.get(name) {
            None => problems.push(format!("{name} is cached but not made by the stage")),
            Some(fresh) if fresh.sha256() != blob.sha256() => problems.push(format!(
                "{name} is cached as {} but rebuilds as {}",
                short(&blob.sha256()),
                short(&fresh.sha256())
            )),
            Some(_) => {}
        }
    }
    for name in rebuilt.keys().filter(|n| !cached.contains_key(*n)) {
        problems.push(format!(
            "{name} is made by the stage but missing from the entry"
        ));
    }
    if problems.is_empty() {
        return None;
    }
    let more = problems.len().saturating_sub(3);
    problems.truncate(3);
    if more > 0 {
        problems.push(format!("and {more} more"));
    }
    Some(problems.join("; "))
}
