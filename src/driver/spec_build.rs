//! One validated spec → its output folder: read the inputs, lock the folder, try the no-op
//! fast path, pull the artifacts through the stage graph, write the folder, report.
//!
//! [`build_spec`] is that sequence of named steps; each step is a function here or in the
//! module that owns it, so a new step (sharding, another output format) goes in between
//! two lines of it.

use std::path::Path;
use std::time::Instant;

use super::inputs::SpecInputs;
use super::pipeline::{ArtifactOut, Pipeline};
use super::report::{BuildReport, StageRun, StageStatus};
use super::{BuildError, BuildOptions};
use crate::cache::Cache;
use crate::diagnostic::Diagnostic;
use crate::out_dir::OutDir;
use crate::out_dir::fresh;
use crate::out_dir::lock;
use crate::out_dir::{Artifact, Manifest};
use crate::spec::Spec;

/// Builds an already validated spec read from `path`.
pub fn build_spec(
    path: &Path,
    spec: &Spec,
    options: &BuildOptions,
) -> Result<BuildReport, BuildError> {
    let start = Instant::now();
    let inputs = SpecInputs::read(path, spec)?;
    let cache = Cache::open(&options.cache_dir)?;
    // Best effort: a read-only cache that holds every stage still builds.
    let _ = cache.mark();
    let progress = progress_of(spec, options);
    let mut pipeline = Pipeline::new(spec, path.to_path_buf(), inputs, &cache, &progress);
    pipeline.strict = options.strict;
    // Held until this build returns: builds of one output folder take turns.
    let out = lock_output_folder(spec, options)?;
    if let Some((manifest, report)) = up_to_date(path, spec, &pipeline, &cache, &out, start) {
        // A no-op build: its entries replayed the warnings.
        strict_failure(path, &report.warnings, options)?;
        check_lock(path, &manifest, options)?;
        return Ok(report);
    }
    let artifacts = pipeline.artifacts()?;
    let pipeline = strict_check(path, pipeline, options)?;
    let manifest = manifest_of(spec, &artifacts);
    check_lock(path, &manifest, options)?;
    let synced = write_output_folder(&out, &artifacts, &manifest, &cache)?;
    Ok(BuildReport {
        name: spec.name.clone(),
        spec: path.to_path_buf(),
        out_dir: out.path().to_path_buf(),
        stages: pipeline.runs,
        written: synced.written,
        unchanged: synced.unchanged,
        removed: synced.removed,
        warnings: sorted(pipeline.diagnostics),
        triangles: pipeline.triangles,
        elapsed: start.elapsed(),
    })
}

/// The pipeline's progress callback: `options.progress`, told the spec's name.
pub(super) fn progress_of<'a>(
    spec: &'a Spec,
    options: &'a BuildOptions,
) -> impl Fn(&str, usize, usize) + 'a {
    move |camera: &str, done: usize, total: usize| {
        if let Some(report) = &options.progress {
            report(&spec.name, camera, done, total);
        }
    }
}

/// `--strict`: the pipeline back when it warned of nothing, [`BuildError::Strict`] with
/// its warnings otherwise (before the output folder is touched).
pub(super) fn strict_check<'a>(
    path: &Path,
    pipeline: Pipeline<'a>,
    options: &BuildOptions,
) -> Result<Pipeline<'a>, BuildError> {
    strict_failure(path, &pipeline.diagnostics, options)?;
    Ok(pipeline)
}

/// `--strict` and a warning among `diagnostics`: [`BuildError::Strict`] with them, sorted.
fn strict_failure(
    path: &Path,
    diagnostics: &[Diagnostic],
    options: &BuildOptions,
) -> Result<(), BuildError> {
    if options.strict && diagnostics.iter().any(Diagnostic::is_warning) {
        return Err(BuildError::Strict {
            spec: path.to_path_buf(),
            warnings: sorted(diagnostics.to_vec()),
        });
    }
    Ok(())
}

/// Diagnostics in one order, whatever order the stages were evaluated or looked up in: a
/// warm build says what a cold one said, in the same words and order.
pub(super) fn sorted(mut diagnostics: Vec<Diagnostic>) -> Vec<Diagnostic> {
    diagnostics.sort();
    diagnostics.dedup();
    diagnostics
}

/// Locks `<out>/<name>/` (saying so when another build holds it) and removes what a
/// killed build left beside it.
fn lock_output_folder(spec: &Spec, options: &BuildOptions) -> Result<OutDir, BuildError> {
    let waiting = |dir: &Path| {
        if let Some(report) = &options.waiting {
            report(dir);
        }
    };
    OutDir::open(&options.out_root, &spec.name, &waiting)
}

/// The no-op fast path ([`fresh`]): when the output folder is exactly as the last build
/// left it and the artifact stages' entries name the same objects, the report of a build
/// that did nothing, with the manifest it found.
fn up_to_date(
    path: &Path,
    spec: &Spec,
    pipeline: &Pipeline,
    cache: &Cache,
    out: &OutDir,
    start: Instant,
) -> Option<(Manifest, BuildReport)> {
    let stages = pipeline.artifact_stages();
    let (manifest, diagnostics) = fresh::check(cache, out.path(), &spec.name, &stages)?;
    let lookup = start.elapsed();
    let mut unchanged: Vec<String> = manifest.artifacts.iter().map(|a| a.path.clone()).collect();
    unchanged.push("manifest.json".to_owned());
    let stages = stages
        .iter()
        .map(|(stage, key)| StageRun {
            stage: stage.name(),
            camera: pipeline.camera_of(key).map(str::to_owned),
            key: (*key).to_owned(),
            status: StageStatus::Cached,
            time: lookup / stages.len().max(1) as u32,
            repaired: None,
        })
        .collect();
    let report = BuildReport {
        name: spec.name.clone(),
        spec: path.to_path_buf(),
        out_dir: out.path().to_path_buf(),
        stages,
        written: Vec::new(),
        unchanged,
        removed: Vec::new(),
        warnings: sorted(diagnostics),
        triangles: None,
        elapsed: start.elapsed(),
    };
    Some((manifest, report))
}

/// `--locked`: the artifacts must match the spec's lock file, checked before the output
/// folder is touched.
fn check_lock(path: &Path, manifest: &Manifest, options: &BuildOptions) -> Result<(), BuildError> {
    if options.locked {
        lock::check(path, manifest)?;
    }
    Ok(())
}

/// `manifest.json`: every artifact's path, hash, size, stage and key, sorted by path.
fn manifest_of(spec: &Spec, artifacts: &[ArtifactOut]) -> Manifest {
    let mut manifest = Manifest {
        name: spec.name.clone(),
        artifacts: artifacts
            .iter()
            .map(|artifact| Artifact {
                path: artifact.path.clone(),
                sha256: artifact.blob.sha256(),
                bytes: artifact.blob.size(),
                stage: artifact.stage.name().to_owned(),
                key: artifact.key.clone(),
            })
            .collect(),
    };
    manifest.artifacts.sort_by(|a, b| a.path.cmp(&b.path));
    manifest
}

/// Makes the output folder hold exactly the artifacts and the manifest, then records it
/// for the next build's fast path.
fn write_output_folder(
    out: &OutDir,
    artifacts: &[ArtifactOut],
    manifest: &Manifest,
    cache: &Cache,
) -> Result<crate::out_dir::Synced, BuildError> {
    let bytes = manifest.to_bytes();
    let record = fresh::load(cache, out.path());
    let synced = out.sync(artifacts, &bytes, cache, record.as_ref())?;
    fresh::record(cache, out.path(), manifest, &bytes);
    Ok(synced)
}
