//! Build driver: spec files → output folders of content-hashed artifacts, through the cache.
//!
//! The only code that knows the stage order, reads and writes files and keeps the cache.
//! For each spec it reads the TOML, validates it ([`crate::spec::load`]), computes every
//! stage key, pulls the artifacts through the cache ([`pipeline`]) and writes them into
//! `<out>/<name>/` atomically, `manifest.json` last. Files that already hold the right bytes
//! are left alone, so a rebuild with nothing changed writes nothing.

mod atomic;
mod cache;
mod codec;
mod error;
mod frames;
mod fresh;
mod inputs;
mod manifest;
mod pipeline;
mod report;
mod stage_key;

use std::collections::BTreeMap;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};
use std::time::Instant;

pub use atomic::{sweep_temporaries, write_atomic, write_atomic_with};
pub use cache::{Blob, Cache, Load, Miss};
pub use error::BuildError;
pub use manifest::{Artifact, Manifest};
pub use pipeline::widths_px;
pub use report::{BuildReport, StageRun, StageStatus};

use crate::spec::{self, FsWorld, Spec, SpecSource};
use pipeline::Pipeline;

/// Told of rendered frames: (spec name, camera name, frames done, frames in the path).
pub type Progress = std::sync::Arc<dyn Fn(&str, &str, usize, usize) + Send + Sync>;

/// Where a build writes.
#[derive(Clone)]
pub struct BuildOptions {
    /// Each spec writes to `<out_root>/<name>/`.
    pub out_root: PathBuf,
    /// The stage cache.
    pub cache_dir: PathBuf,
    /// Called as frames are rendered (the CLI draws a progress bar).
    pub progress: Option<Progress>,
}

impl Default for BuildOptions {
    fn default() -> Self {
        BuildOptions {
            out_root: PathBuf::from("out"),
            cache_dir: PathBuf::from(".cityspec-cache"),
            progress: None,
        }
    }
}

/// Reads and validates one spec file.
pub fn load_spec(path: &Path) -> Result<Spec, BuildError> {
    // Capped, and refused unless a regular file: a spec that is `/dev/zero` fails at once.
    let text =
        spec::read_text_capped(path, spec::MAX_SPEC_BYTES).map_err(|why| BuildError::ReadSpec {
            path: path.to_path_buf(),
            source: io::Error::other(format!("expected a spec file, found {why}")),
        })?;
    let source = SpecSource {
        path: path.to_path_buf(),
        text,
    };
    spec::load(&source, &FsWorld).map_err(BuildError::Spec)
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
        match load_spec(path) {
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
    let spec = load_spec(path)?;
    build_spec(path, &spec, options)
}

/// Builds an already validated spec read from `path`.
pub fn build_spec(
    path: &Path,
    spec: &Spec,
    options: &BuildOptions,
) -> Result<BuildReport, BuildError> {
    let start = Instant::now();
    let source = inputs::layout_source(path, spec)?;
    let facade_input = inputs::facade_input(path, spec)?;
    let meshes = inputs::mesh_files(path, spec)?;
    let cache = Cache::new(&options.cache_dir);
    let progress = |camera: &str, done: usize, total: usize| {
        if let Some(report) = &options.progress {
            report(&spec.name, camera, done, total);
        }
    };
    let mut pipeline = Pipeline::new(
        spec,
        path.to_path_buf(),
        source,
        facade_input,
        meshes,
        &cache,
        &progress,
    );
    let out_dir = options.out_root.join(&spec.name);
    let stages = pipeline.artifact_stages();
    if let Some(manifest) = fresh::check(&cache, &out_dir, &spec.name, &stages) {
        let lookup = start.elapsed();
        let mut unchanged: Vec<String> =
            manifest.artifacts.iter().map(|a| a.path.clone()).collect();
        unchanged.push("manifest.json".to_owned());
        let stages = stages
            .iter()
            .map(|(stage, key)| StageRun {
                stage,
                key: (*key).to_owned(),
                status: StageStatus::Cached,
                time: lookup / stages.len().max(1) as u32,
                repaired: None,
            })
            .collect();
        return Ok(BuildReport {
            name: spec.name.clone(),
            out_dir,
            stages,
            written: Vec::new(),
            unchanged,
            removed: Vec::new(),
            warnings: Vec::new(),
            triangles: None,
            elapsed: start.elapsed(),
        });
    }
    let artifacts = pipeline.artifacts()?;
    let output = |source: io::Error, file: &Path| BuildError::Output {
        path: file.to_path_buf(),
        source,
    };
    let mut folders: Vec<PathBuf> = artifacts
        .iter()
        .filter_map(|a| out_dir.join(&a.path).parent().map(Path::to_path_buf))
        .collect();
    folders.push(out_dir.clone());
    folders.sort();
    folders.dedup();
    for folder in &folders {
        sweep_temporaries(folder).map_err(|e| output(e, folder))?;
    }

    let old = fs::read(out_dir.join("manifest.json"))
        .ok()
        .and_then(|b| Manifest::from_bytes(&b));
    let mut written = Vec::new();
    let mut unchanged = Vec::new();
    let mut manifest = Manifest {
        name: spec.name.clone(),
        artifacts: Vec::new(),
    };
    for artifact in &artifacts {
        let file = out_dir.join(&artifact.path);
        let sha256 = artifact.blob.sha256();
        let size = artifact.blob.size();
        // One file at a time: a stored object is read only when the folder lacks it.
        let same = fs::metadata(&file).is_ok_and(|m| m.len() == size)
            && fs::read(&file).is_ok_and(|old| crate::hash::sha256_hex(&old) == sha256);
        if same {
            unchanged.push(artifact.path.clone());
        } else {
            match &artifact.blob {
                Blob::Bytes(bytes) | Blob::Stored(_, Some(bytes)) => write_atomic(&file, bytes),
                Blob::Stored(object, None) => match cache.read_object(object) {
                    Ok(bytes) => write_atomic(&file, &bytes),
                    Err(why) => Err(io::Error::other(format!("cache object {why}"))),
                },
            }
            .map_err(|e| output(e, &file))?;
            written.push(artifact.path.clone());
        }
        manifest.artifacts.push(Artifact {
            path: artifact.path.clone(),
            sha256,
            bytes: size,
            stage: artifact.stage.to_owned(),
            key: artifact.key.clone(),
        });
    }
    manifest.artifacts.sort_by(|a, b| a.path.cmp(&b.path));

    // Files an earlier build wrote that this one no longer produces would be stale.
    let mut removed = Vec::new();
    for stale in old.iter().flat_map(|m| &m.artifacts) {
        let still = manifest.artifacts.iter().any(|a| a.path == stale.path);
        let file = out_dir.join(&stale.path);
        if !still && !stale.path.contains("..") && file.is_file() {
            fs::remove_file(&file).map_err(|e| output(e, &file))?;
            removed.push(stale.path.clone());
        }
    }

    let manifest_file = out_dir.join("manifest.json");
    let bytes = manifest.to_bytes();
    if fs::read(&manifest_file).is_ok_and(|old| old == bytes) {
        unchanged.push("manifest.json".to_owned());
    } else {
        write_atomic(&manifest_file, &bytes).map_err(|e| output(e, &manifest_file))?;
        written.push("manifest.json".to_owned());
    }

    fresh::record(&cache, &out_dir, &manifest, &bytes);
    Ok(BuildReport {
        name: spec.name.clone(),
        out_dir,
        stages: pipeline.runs,
        written,
        unchanged,
        removed,
        warnings: pipeline.warnings,
        triangles: pipeline.triangles,
        elapsed: start.elapsed(),
    })
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
