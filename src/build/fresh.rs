//! The no-op fast path: an output folder that still holds exactly what the cache says the
//! artifact stages produced needs no stage, no object read and no write.
//!
//! After every build the driver records, per output folder, each artifact's size, mtime and
//! SHA-256 (`<cache>/fresh/<hash of the folder path>.json`). A later build with the same
//! stage keys compares that record with the cache entries (hashes) and with `stat` of each
//! file (size, mtime); when all agree, nothing is read. Like cargo's fingerprints this trusts
//! a file whose size and mtime are unchanged; the record lives in the cache folder and never
//! in a key or an artifact. Anything else falls back to the full build, which re-verifies.

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;
use std::time::UNIX_EPOCH;

use serde::{Deserialize, Serialize};

use super::atomic::write_atomic;
use super::cache::Cache;
use super::manifest::{Artifact, Manifest};
use crate::hash::sha256_hex;

/// What the last build left in one output folder.
#[derive(Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FreshRecord {
    /// Path (relative, `/`-separated, `manifest.json` included) → size, mtime, sha256.
    pub files: BTreeMap<String, FileStamp>,
}

#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct FileStamp {
    pub bytes: u64,
    pub mtime_ns: u128,
    pub sha256: String,
}

fn record_path(cache: &Cache, out_dir: &Path) -> std::path::PathBuf {
    let name = sha256_hex(out_dir.to_string_lossy().as_bytes());
    cache.root().join("fresh").join(format!("{name}.json"))
}

fn stamp(path: &Path) -> Option<(u64, u128)> {
    let meta = fs::metadata(path).ok()?;
    let mtime = meta
        .modified()
        .ok()?
        .duration_since(UNIX_EPOCH)
        .ok()?
        .as_nanos();
    Some((meta.len(), mtime))
}

/// The manifest of an up-to-date output folder, or `None` when anything may have changed.
pub fn check(
    cache: &Cache,
    out_dir: &Path,
    name: &str,
    stages: &[(&'static str, &str)],
) -> Option<Manifest> {
    let record: FreshRecord =
        serde_json::from_slice(&fs::read(record_path(cache, out_dir)).ok()?).ok()?;
    let mut artifacts = Vec::new();
    for (stage, key) in stages {
        let entry = cache.entry(key)?;
        for (path, object) in &entry.outputs {
            artifacts.push(Artifact {
                path: path.clone(),
                sha256: object.sha256.clone(),
                bytes: object.bytes,
                stage: (*stage).to_owned(),
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
        let (bytes, mtime_ns) = stamp(&out_dir.join(path))?;
        if recorded.sha256 != sha || recorded.bytes != bytes || recorded.mtime_ns != mtime_ns {
            return None;
        }
        count += 1;
    }
    (count == record.files.len()).then_some(manifest)
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
        let Some((bytes, mtime_ns)) = stamp(&out_dir.join(&path)) else {
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
    if let Ok(text) = serde_json::to_vec(&FreshRecord { files }) {
        let _ = write_atomic(&record_path(cache, out_dir), &text);
    }
}
