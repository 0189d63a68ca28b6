//! The no-op fast path: an output folder that still holds exactly what the cache says the
//! artifact stages produced needs no stage, no object read and no write.
//!
//! After every build the driver records, per output folder, each artifact's size, mtime and
//! SHA-256 (`<cache>/fresh/<hash of the folder path>.json`). A later build with the same
//! stage keys compares that record with the cache entries (hashes) and with `stat` of each
//! file (size, mtime); when all agree, nothing is read. Like cargo's fingerprints this trusts
//! a file whose size and mtime are unchanged; the record lives in the cache folder and never
//! in a key or an artifact. Anything else falls back to the full build, which re-verifies.
//!
//! The record also holds the mtime of every folder of the output folder: a file added,
//! removed or renamed anywhere (a temporary or an orphan) changes its folder's mtime, so
//! the fast path never leaves a stray file in place; the full path removes it.

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::{Artifact, Manifest, folders_of, mtime_ns};
use crate::atomic_file::write_atomic;
use crate::cache::Cache;
use crate::diagnostic::{Diagnostic, extend_unique};
use crate::driver::{Stage, is_safe_relative};
use crate::hash::sha256_hex;
use crate::regular_file::{self, Follow};

/// What the last build left in one output folder.
#[derive(Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FreshRecord {
    /// Path (relative, `/`-separated, `manifest.json` included) → size, mtime, sha256.
    pub files: BTreeMap<String, FileStamp>,
    /// Folder (relative, `""` for the output folder itself) → mtime. A record without
    /// folders (from an older cityspec) never matches.
    #[serde(default)]
    pub dirs: BTreeMap<String, u128>,
}

#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct FileStamp {
    pub bytes: u64,
    pub mtime_ns: u128,
    pub sha256: String,
}

/// Where the record lives: local state, so only a local cache has one (a build with a
/// remote cache always takes the full path, which verifies every artifact).
fn record_path(cache: &Cache, out_dir: &Path) -> Option<std::path::PathBuf> {
    let name = sha256_hex(out_dir.to_string_lossy().as_bytes());
    Some(
        cache
            .local_root()?
            .join("fresh")
            .join(format!("{name}.json")),
    )
}

/// Size and mtime of a regular file, or of a folder (`dir`), never through a symbolic link
/// at `path` itself (its parents are vouched for by their own recorded stamps).
fn stamp(path: &Path, dir: bool) -> Option<(u64, u128)> {
    let meta = fs::symlink_metadata(path).ok()?;
    let kind_ok = if dir { meta.is_dir() } else { meta.is_file() };
    kind_ok.then(|| (meta.len(), mtime_ns(&meta)))
}

/// The record of the last build into `out_dir`, if any.
pub fn load(cache: &Cache, out_dir: &Path) -> Option<FreshRecord> {
    let text = regular_file::read(&record_path(cache, out_dir)?, Follow::No).ok()?;
    serde_json::from_slice(&text).ok()
}

/// The manifest of an up-to-date output folder and the diagnostics its stages' entries
/// record, or `None` when anything may have changed.
pub fn check(
    cache: &Cache,
    out_dir: &Path,
    name: &str,
    stages: &[(Stage, &str)],
) -> Option<(Manifest, Vec<Diagnostic>)> {
    let record = load(cache, out_dir)?;
    let mut artifacts = Vec::new();
    let mut diagnostics = Vec::new();
    for (stage, key) in stages {
        let entry = cache.entry(key)?;
        extend_unique(&mut diagnostics, &entry.diagnostics);
        for (path, object) in &entry.outputs {
            if !is_safe_relative(path) {
                return None;
            }
            artifacts.push(Artifact {
                path: path.clone(),
                sha256: object.sha256.clone(),
                bytes: object.bytes,
                stage: stage.name().to_owned(),
                key: (*key).to_owned(),
            });
        }
    }
    artifacts.sort_by(|a, b| a.path.cmp(&b.path));
    let manifest = Manifest {
        name: name.to_owned(),
        artifacts,
    };
    let manifest_sha = sha256_hex(&manifest.to_bytes());
    let expected = manifest
        .artifacts
        .iter()
        .map(|a| (a.path.as_str(), a.sha256.as_str()))
        .chain([("manifest.json", manifest_sha.as_str())]);
    let mut count = 0;
    for (path, sha) in expected {
        let recorded = record.files.get(path)?;
        let (bytes, mtime_ns) = stamp(&out_dir.join(path), false)?;
        if recorded.sha256 != sha || recorded.bytes != bytes || recorded.mtime_ns != mtime_ns {
            return None;
        }
        count += 1;
    }
    if count != record.files.len() {
        return None;
    }
    let dirs = folders_of(manifest.artifacts.iter().map(|a| a.path.as_str()));
    if dirs.len() != record.dirs.len() {
        return None;
    }
    for dir in &dirs {
        let recorded = record.dirs.get(dir)?;
        let (_, mtime_ns) = stamp(&out_dir.join(dir), true)?;
        if *recorded != mtime_ns {
            return None;
        }
    }
    Some((manifest, diagnostics))
}

/// Records what the output folder holds after a build (best effort: a failure only costs
/// the next no-op build its fast path).
pub fn record(cache: &Cache, out_dir: &Path, manifest: &Manifest, manifest_bytes: &[u8]) {
    let mut files = BTreeMap::new();
    let items = manifest
        .artifacts
        .iter()
        .map(|a| (a.path.clone(), a.sha256.clone()))
        .chain([("manifest.json".to_owned(), sha256_hex(manifest_bytes))]);
    for (path, sha256) in items {
        let Some((bytes, mtime_ns)) = stamp(&out_dir.join(&path), false) else {
            return;
        };
        files.insert(
            path,
            FileStamp {
                bytes,
                mtime_ns,
                sha256,
            },
        );
    }
    let mut dirs = BTreeMap::new();
    for dir in folders_of(manifest.artifacts.iter().map(|a| a.path.as_str())) {
        let Some((_, mtime_ns)) = stamp(&out_dir.join(&dir), true) else {
            return;
        };
        dirs.insert(dir, mtime_ns);
    }
    if let (Some(path), Ok(text)) = (
        record_path(cache, out_dir),
        serde_json::to_vec(&FreshRecord { files, dirs }),
    ) {
        let _ = write_atomic(&path, &text);
    }
}
