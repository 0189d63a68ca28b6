//! `cityspec cache gc`: keep what the given specs (and lock files) need, remove the rest.
//!
//! Needed: every stage entry of each spec (its city stages, each camera path's entry, plan
//! and chunks) and every object those entries name, plus every object a given lock file
//! lists. Everything else in `entries/` and `objects/` may go: all of it without limits;
//! with `--max-age`, what is older than that; with `--max-size`, the oldest first until the
//! cache fits. Temporaries that killed builds left (`.…cityspec-tmp-…`) always go.
//!
//! Safe while other builds run: nothing modified within the grace period (default one
//! hour) is removed. A build writes its objects before the entry that names them, and
//! [`Cache::put_object`] refreshes the mtime of an object it finds already there, so an
//! object a running build has just made or reused is always younger than the grace
//! period. Entries go before objects, so a kept entry never names a removed object. A
//! build that needs something gc removed finds it missing and builds it again: a miss,
//! never a wrong result.
//!
//! A remote cache (`s3://…`) is listed and pruned the same way, by each object's
//! Last-Modified: a build re-uploads an object it reuses (see [`Cache::put_object`]), so
//! the grace period protects it there too. It holds no temporaries (uploads are whole).
//!
//! No fsync anywhere in the cache, by choice: every read re-hashes the object and parses
//! the entry, so what a power loss leaves torn is a miss, rebuilt, never used.

use std::collections::BTreeSet;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

use super::cache::Cache;
use super::inputs::SpecInputs;
use super::pipeline::Pipeline;
use super::{BuildError, load_spec};

/// What `cache gc` may remove.
#[derive(Clone, Debug)]
pub struct GcOptions {
    pub cache_dir: PathBuf,
    /// Remove unneeded files only until the cache holds at most this many bytes.
    pub max_size: Option<u64>,
    /// Remove only unneeded files older than this.
    pub max_age: Option<Duration>,
    /// Never remove a file younger than this (a running build may have just written it).
    pub grace: Duration,
}

/// What `cache gc` did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct GcReport {
    pub kept_entries: usize,
    pub kept_objects: usize,
    pub removed_entries: usize,
    pub removed_objects: usize,
    pub removed_temporaries: usize,
    pub removed_bytes: u64,
    /// Bytes in the cache afterwards.
    pub bytes: u64,
}

/// A file gc may remove.
struct Candidate {
    file: CacheFile,
    entry: bool,
}

/// A file of the cache: its path in a local folder, or under a remote cache's prefix.
struct CacheFile {
    path: PathBuf,
    name: String,
    bytes: u64,
    modified: SystemTime,
}

/// Collects what `specs` (spec files, or lock files ending in `.lock`) need, then removes
/// the rest of the cache as [`GcOptions`] allow.
pub fn gc(specs: &[PathBuf], options: &GcOptions) -> Result<GcReport, Vec<BuildError>> {
    let cache = Cache::open(&options.cache_dir).map_err(|e| vec![e])?;
    let mut entries = BTreeSet::new();
    let mut objects = BTreeSet::new();
    let mut errors = Vec::new();
    for path in specs {
        let needed = if path.extension().is_some_and(|e| e == "lock") {
            lock_objects(path).map(|hashes| objects.extend(hashes))
        } else {
            spec_keys(path, &cache).map(|keys| entries.extend(keys))
        };
        if let Err(e) = needed {
            errors.push(e);
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    for key in &entries {
        if let Some(entry) = cache.entry(key) {
            objects.extend(entry.outputs.into_values().map(|o| o.sha256));
        }
    }
    let io_error = |source| {
        vec![BuildError::Cache {
            path: options.cache_dir.clone(),
            source,
        }]
    };
    let now = SystemTime::now();
    let mut report = GcReport::default();
    let mut candidates = Vec::new();
    let mut total = 0u64;
    let mut temporaries = Vec::new();
    for (entry, file) in cache_files(&cache, now).map_err(io_error)? {
        let young = now.duration_since(file.modified).unwrap_or_default() < options.grace;
        total += file.bytes;
        if file.name.contains(".cityspec-tmp-") {
            if !young {
                temporaries.push(file);
            }
            continue;
        }
        let needed = if entry {
            file.name
                .strip_suffix(".json")
                .is_some_and(|k| entries.contains(k))
        } else {
            objects.contains(&file.name)
        };
        match (needed, entry) {
            (true, true) => report.kept_entries += 1,
            (true, false) => report.kept_objects += 1,
            (false, _) if young => {}
            (false, _) => candidates.push(Candidate { file, entry }),
        }
    }
    for file in temporaries {
        if remove(&cache, &file) {
            report.removed_temporaries += 1;
            report.removed_bytes += file.bytes;
            total -= file.bytes;
        }
    }
    if let Some(age) = options.max_age {
        candidates.retain(|c| now.duration_since(c.file.modified).unwrap_or_default() >= age);
    }
    // Oldest first, entries before objects of the same age.
    candidates.sort_by_key(|c| (c.file.modified, !c.entry));
    if let Some(limit) = options.max_size {
        let mut over = total.saturating_sub(limit);
        candidates.retain(|c| {
            let take = over > 0;
            over = over.saturating_sub(c.file.bytes);
            take
        });
    }
    // Entries first: a kept entry never names a removed object.
    candidates.sort_by_key(|c| !c.entry);
    for c in candidates {
        if remove(&cache, &c.file) {
            if c.entry {
                report.removed_entries += 1;
            } else {
                report.removed_objects += 1;
            }
            report.removed_bytes += c.file.bytes;
            total -= c.file.bytes;
        }
    }
    report.bytes = total;
    Ok(report)
}

/// Every key the spec's build reads or writes.
fn spec_keys(path: &Path, cache: &Cache) -> Result<Vec<String>, BuildError> {
    let spec = load_spec(path)?;
    let inputs = SpecInputs::read(path, &spec)?;
    let progress = |_: &str, _: usize, _: usize| {};
    let pipeline = Pipeline::new(&spec, path.to_path_buf(), inputs, cache, &progress);
    Ok(pipeline.cache_keys())
}

/// The objects a lock file lists.
fn lock_objects(path: &Path) -> Result<Vec<String>, BuildError> {
    let text = fs::read_to_string(path).map_err(|source| BuildError::ReadSpec {
        path: path.to_path_buf(),
        source,
    })?;
    super::lock::hashes(&text).map_err(|why| BuildError::ReadSpec {
        path: path.to_path_buf(),
        source: io::Error::other(why),
    })
}

/// Every entry (`true`) and object (`false`) file of the cache, local or remote.
fn cache_files(cache: &Cache, now: SystemTime) -> io::Result<Vec<(bool, CacheFile)>> {
    let Some(remote) = cache.remote() else {
        let root = cache.root();
        let entries = files_of(&root.join("entries"))?
            .into_iter()
            .map(|f| (true, f));
        let objects = files_of_nested(&root.join("objects"))?;
        let local = |(path, meta): (PathBuf, fs::Metadata)| CacheFile {
            name: path
                .file_name()
                .unwrap_or_default()
                .to_string_lossy()
                .into_owned(),
            bytes: meta.len(),
            modified: meta.modified().unwrap_or(now),
            path,
        };
        return Ok(entries
            .chain(objects.into_iter().map(|f| (false, f)))
            .map(|(entry, file)| (entry, local(file)))
            .collect());
    };
    let mut files = Vec::new();
    for (folder, entry) in [("entries", true), ("objects", false)] {
        for listed in remote.list(folder)? {
            let name = listed
                .name
                .rsplit('/')
                .next()
                .unwrap_or_default()
                .to_owned();
            files.push((
                entry,
                CacheFile {
                    path: PathBuf::from(listed.name),
                    name,
                    bytes: listed.bytes,
                    modified: listed.modified,
                },
            ));
        }
    }
    Ok(files)
}

/// Removes one file of the cache; whether it went.
fn remove(cache: &Cache, file: &CacheFile) -> bool {
    match cache.remote() {
        Some(remote) => remote.delete(&file.path.to_string_lossy()).is_ok(),
        None => fs::remove_file(&file.path).is_ok(),
    }
}

/// The files of a folder (none when it is missing).
fn files_of(dir: &Path) -> io::Result<Vec<(PathBuf, fs::Metadata)>> {
    let entries = match fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(e),
    };
    let mut out = Vec::new();
    for entry in entries {
        let entry = entry?;
        let meta = entry.metadata()?;
        if meta.is_file() {
            out.push((entry.path(), meta));
        }
    }
    Ok(out)
}

/// The files of a folder and of its subfolders one level down (`objects/ab/…`).
fn files_of_nested(dir: &Path) -> io::Result<Vec<(PathBuf, fs::Metadata)>> {
    let mut out = files_of(dir)?;
    if let Ok(entries) = fs::read_dir(dir) {
        for entry in entries {
            let entry = entry?;
            if entry.file_type()?.is_dir() {
                out.extend(files_of(&entry.path())?);
            }
        }
    }
    Ok(out)
}

/// Parses a size: a number of bytes with an optional `K`, `M`, `G` or `T` (powers of
/// 1024), optionally followed by `B` or `iB`: `500M`, `20GiB`, `1.5T`.
pub fn parse_size(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let t = t
        .strip_suffix("iB")
        .or_else(|| t.strip_suffix('B'))
        .unwrap_or(t);
    let (number, scale) = match t.char_indices().last() {
        Some((i, c)) if c.is_ascii_alphabetic() => {
            let power = match c.to_ascii_uppercase() {
                'K' => 1,
                'M' => 2,
                'G' => 3,
                'T' => 4,
                _ => return Err(format!("expected a size like 500M or 20G, found {text:?}")),
            };
            (&t[..i], 1024f64.powi(power))
        }
        _ => (t, 1.0),
    };
    let value: f64 = number
        .trim()
        .parse()
        .map_err(|_| format!("expected a size like 500M or 20G, found {text:?}"))?;
    if !(value.is_finite() && value >= 0.0) {
        return Err(format!("expected a size like 500M or 20G, found {text:?}"));
    }
    Ok((value * scale) as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse() {
        assert_eq!(parse_size("123"), Ok(123));
        assert_eq!(parse_size("2K"), Ok(2048));
        assert_eq!(parse_size("1.5M"), Ok(1_572_864));
        assert_eq!(parse_size("20GiB"), Ok(20 << 30));
        assert_eq!(parse_size("1GB"), Ok(1 << 30));
        assert!(parse_size("ten").is_err());
        assert!(parse_size("5X").is_err());
        assert!(parse_size("-1").is_err());
    }
}
