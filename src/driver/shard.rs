//! `cityspec build --shard I/N` and `--stage city`: one machine's share of a build, written
//! only to the cache. A plain `cityspec build` afterwards (the merge) finds every chunk
//! there and writes the output folder without rendering a frame.
//!
//! Shards need nothing from each other: each builds (or finds) the city's stages and the
//! paths' plans, then renders the chunks [`super::chunks::owner`] gives it. Racing shards
//! stay correct because objects are immutable and named by their hash, and entries are
//! renamed into place whole; at worst two shards build the same city stage twice, which
//! `--stage city` before the array avoids.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use super::inputs::SpecInputs;
use super::pipeline::Pipeline;
use super::{BuildError, BuildOptions, each_valid_spec, spec_build};
use crate::cache::Cache;

/// Shard `index` of `count` (0-based).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub index: u32,
    pub count: u32,
}

/// What `--shard` asks for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ShardArg {
    /// `I/N`.
    Given(Shard),
    /// `auto`: from the array job's environment.
    Auto,
}

impl ShardArg {
    /// Parses `I/N` (0 ≤ I < N) or `auto`.
    pub fn parse(text: &str) -> Result<ShardArg, String> {
        if text == "auto" {
            return Ok(ShardArg::Auto);
        }
        let (i, n) = text
            .split_once('/')
            .ok_or_else(|| format!("expected I/N or auto, found {text:?}"))?;
        let number = |s: &str| {
            s.trim()
                .parse::<u32>()
                .map_err(|_| format!("expected I/N with whole numbers, found {text:?}"))
        };
        Shard::new(number(i)?, number(n)?).map(ShardArg::Given)
    }

    /// The shard, reading the environment for `auto` through `env`: Slurm's
    /// `SLURM_ARRAY_TASK_ID` (less `SLURM_ARRAY_TASK_MIN`) of `SLURM_ARRAY_TASK_COUNT`,
    /// else Kubernetes' `JOB_COMPLETION_INDEX` of `count` (`--shard-count`) or
    /// `CITYSPEC_SHARD_COUNT`. `count` also overrides Slurm's count when given.
    pub fn resolve(
        &self,
        count: Option<u32>,
        env: impl Fn(&str) -> Option<String>,
    ) -> Result<Shard, String> {
        let given = match self {
            ShardArg::Given(shard) => {
                return match count {
                    Some(n) if n != shard.count => Err(format!(
                        "--shard says {} shards, --shard-count {n}",
                        shard.count
                    )),
                    _ => Ok(*shard),
                };
            }
            ShardArg::Auto => count,
        };
        let number = |name: &str| -> Result<Option<u32>, String> {
            env(name)
                .map(|v| {
                    v.trim()
                        .parse::<u32>()
                        .map_err(|_| format!("{name}={v:?} is not a whole number"))
                })
                .transpose()
        };
        if let Some(id) = number("SLURM_ARRAY_TASK_ID")? {
            let min = number("SLURM_ARRAY_TASK_MIN")?.unwrap_or(0);
            let n = given.or(number("SLURM_ARRAY_TASK_COUNT")?).ok_or(
                "SLURM_ARRAY_TASK_ID is set but not SLURM_ARRAY_TASK_COUNT (give --shard-count)",
            )?;
            let index = id
                .checked_sub(min)
                .ok_or("SLURM_ARRAY_TASK_ID is below SLURM_ARRAY_TASK_MIN")?;
            return Shard::new(index, n);
        }
        if let Some(index) = number("JOB_COMPLETION_INDEX")? {
            let n = given.or(number("CITYSPEC_SHARD_COUNT")?).ok_or(
                "JOB_COMPLETION_INDEX is set: give the number of shards with --shard-count or CITYSPEC_SHARD_COUNT",
            )?;
            return Shard::new(index, n);
        }
        Err("--shard auto: neither SLURM_ARRAY_TASK_ID nor JOB_COMPLETION_INDEX is set".into())
    }
}

impl Shard {
    pub fn new(index: u32, count: u32) -> Result<Shard, String> {
        if count == 0 || index >= count {
            return Err(format!(
                "shard {index}/{count}: expected 0 ≤ I < N (shards are numbered from 0)"
            ));
        }
        Ok(Shard { index, count })
    }
}

/// What one shard did for one spec.
#[derive(Clone, Debug, Default)]
pub struct ShardStats {
    /// Chunks this shard rendered, found already rendered, or left to other shards.
    pub rendered_chunks: usize,
    pub cached_chunks: usize,
    pub other_chunks: usize,
    /// Frames rendered.
    pub frames: usize,
}

/// One spec's shard run.
#[derive(Clone, Debug)]
pub struct ShardReport {
    pub name: String,
    /// `None` for `--stage city`.
    pub shard: Option<Shard>,
    pub stats: ShardStats,
    pub elapsed: Duration,
}

/// Validates every spec, then does `shard`'s share of each (or with `None` the shared
/// stages only), writing only the cache.
pub fn build_shards(
    paths: &[PathBuf],
    options: &BuildOptions,
    shard: Option<Shard>,
) -> Result<Vec<ShardReport>, Vec<BuildError>> {
    each_valid_spec(paths, &options.sets, |path, spec| {
        shard_spec(path, spec, options, shard)
    })
}

fn shard_spec(
    path: &Path,
    spec: &crate::spec::Spec,
    options: &BuildOptions,
    shard: Option<Shard>,
) -> Result<ShardReport, BuildError> {
    let start = Instant::now();
    let inputs = SpecInputs::read(path, spec)?;
    let cache = Cache::open(&options.cache_dir)?;
    // Best effort, as in a plain build.
    let _ = cache.mark();
    let progress = spec_build::progress_of(spec, options);
    let mut pipeline = Pipeline::new(spec, path.to_path_buf(), inputs, &cache, &progress);
    pipeline.strict = options.strict;
    let stats = pipeline.shard_work(shard)?;
    spec_build::strict_check(path, pipeline, options)?;
    Ok(ShardReport {
        name: spec.name.clone(),
        shard,
        stats,
        elapsed: start.elapsed(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env<'a>(pairs: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |name| {
            pairs
                .iter()
                .find(|(k, _)| *k == name)
                .map(|(_, v)| v.to_string())
        }
    }

    #[test]
    fn parses_i_of_n_and_refuses_the_rest() {
        assert_eq!(
            ShardArg::parse("2/7"),
            Ok(ShardArg::Given(Shard { index: 2, count: 7 }))
        );
        assert_eq!(ShardArg::parse("auto"), Ok(ShardArg::Auto));
        for bad in ["7/7", "1/0", "a/2", "3", "-1/2", ""] {
            assert!(ShardArg::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn auto_reads_slurm_then_kubernetes() {
        let slurm = env(&[
            ("SLURM_ARRAY_TASK_ID", "5"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_COUNT", "8"),
        ]);
        assert_eq!(
            ShardArg::Auto.resolve(None, &slurm),
            Ok(Shard { index: 4, count: 8 })
        );
        let k8s = env(&[("JOB_COMPLETION_INDEX", "3")]);
        assert!(ShardArg::Auto.resolve(None, &k8s).is_err());
        assert_eq!(
            ShardArg::Auto.resolve(Some(4), &k8s),
            Ok(Shard { index: 3, count: 4 })
        );
        let k8s_env = env(&[("JOB_COMPLETION_INDEX", "0"), ("CITYSPEC_SHARD_COUNT", "2")]);
        assert_eq!(
            ShardArg::Auto.resolve(None, &k8s_env),
            Ok(Shard { index: 0, count: 2 })
        );
        assert!(ShardArg::Auto.resolve(None, env(&[])).is_err());
        assert!(
            ShardArg::Auto
                .resolve(Some(2), env(&[("JOB_COMPLETION_INDEX", "2")]))
                .is_err()
        );
        let given = ShardArg::Given(Shard { index: 1, count: 3 });
        assert!(given.resolve(Some(4), env(&[])).is_err());
    }
}
