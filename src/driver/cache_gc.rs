//! `cityspec cache gc`: keep what the given specs (and lock files) need, remove the rest.
//!
//! Needed: every stage entry of each spec (its city stages, each camera path's entry, plan
//! and chunks) and every object those entries name, plus every object a given lock file
//! lists. Every other file of the cache may go: all of it without limits; with
//! `--max-age`, what is older than that; with `--max-size`, the oldest first until the
//! cache fits. Temporaries that killed builds left (`.…cityspec-tmp-…`) always go.
//!
//! Only the cache's own files ever go. gc refuses a folder (or prefix) without the marker
//! a cache's first write leaves ([`MARKER`]), so `--cache` pointed at a git repository or a
//! home folder removes nothing. Inside a marked cache it removes only names of the exact
//! shape the cache writes ([`CacheName`]: 64 hex digits under their two-digit shard, and so
//! on); everything else is left and reported as skipped. It never follows a symlink: a
//! symlinked `entries/`, `objects/` or shard folder is reported, not entered. A file with
//! one of the cache's names that is not a regular file (a FIFO, a symlink) is damage: it is
//! removed whatever its age (removing a symlink never touches what it points to).
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

use super::inputs::SpecInputs;
use super::pipeline::Pipeline;
use super::{BuildError, load_spec};
use crate::cache::{Cache, CacheName, MARKER};

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
    /// Files with the cache's names that were not regular files (FIFOs, symlinks): removed.
    pub removed_damaged: usize,
    pub removed_bytes: u64,
    /// Bytes in the cache afterwards.
    pub bytes: u64,
    /// What gc left alone because the cache does not write it: foreign names, folders
    /// where a file belongs, symlinked folders (relative paths, sorted).
    pub skipped: Vec<String>,
}

/// A file gc may remove.
struct Candidate {
    file: CacheFile,
    entry: bool,
}

/// A file of the cache: its path in a local folder, or under a remote cache's prefix.
struct CacheFile {
    path: PathBuf,
    name: CacheName,
    bytes: u64,
    modified: SystemTime,
    /// Not a regular file (local caches only): damage.
    damaged: bool,
}

/// The cache's files by kind, and what it skipped.
#[derive(Default)]
struct Listing {
    files: Vec<CacheFile>,
    skipped: Vec<String>,
}

/// Collects what `specs` (spec files, or lock files ending in `.lock`) need, then removes
/// the rest of the cache as [`GcOptions`] allow.
pub fn gc(specs: &[PathBuf], options: &GcOptions) -> Result<GcReport, Vec<BuildError>> {
    let cache = Cache::open(&options.cache_dir).map_err(|e| vec![e.into()])?;
    check_marked(&cache, options).map_err(|e| vec![e])?;
    let (entries, objects) = needed(specs, &cache)?;
    let now = SystemTime::now();
    let listing = cache_files(&cache, now).map_err(|source| {
        vec![BuildError::Cache {
            path: options.cache_dir.clone(),
            source,
        }]
    })?;
    Ok(sweep(&cache, listing, &entries, &objects, options, now))
}

/// Refuses a folder or prefix cityspec did not mark as its cache.
fn check_marked(cache: &Cache, options: &GcOptions) -> Result<(), BuildError> {
    let refuse = |why: String| BuildError::NotACache {
        path: options.cache_dir.clone(),
        why,
    };
    match cache.is_marked() {
        Ok(true) => Ok(()),
        Ok(false) => Err(refuse(format!(
            "it has no {MARKER} written by cityspec, so `cache gc` removes nothing from \
             it (a cache gets the marker with its first write; a cache made by an older \
             cityspec gets it at its next build)"
        ))),
        Err(e) => Err(refuse(format!("its {MARKER} cannot be read: {e}"))),
    }
}

/// The entries `specs` need (their stages' keys) and the objects they and `.lock` files
/// name.
fn needed(
    specs: &[PathBuf],
    cache: &Cache,
) -> Result<(BTreeSet<String>, BTreeSet<String>), Vec<BuildError>> {
    let mut entries = BTreeSet::new();
    let mut objects = BTreeSet::new();
    let mut errors = Vec::new();
    for path in specs {
        let needed = if path.extension().is_some_and(|e| e == "lock") {
            lock_objects(path).map(|hashes| objects.extend(hashes))
        } else {
            spec_keys(path, cache).map(|keys| entries.extend(keys))
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
    Ok((entries, objects))
}

/// Removes from `listing` the damaged files, old temporaries, and what no needed entry or
/// object names, as `options` allow: past the grace period, older than `max_age`, oldest
/// first until the cache fits `max_size`.
fn sweep(
    cache: &Cache,
    listing: Listing,
    entries: &BTreeSet<String>,
    objects: &BTreeSet<String>,
    options: &GcOptions,
    now: SystemTime,
) -> GcReport {
    let mut report = GcReport {
        skipped: listing.skipped,
        ..GcReport::default()
    };
    let mut candidates = Vec::new();
    let mut total = 0u64;
    let mut temporaries = Vec::new();
    for file in listing.files {
        total += file.bytes;
        if file.damaged {
            if remove(cache, &file) {
                report.removed_damaged += 1;
                total -= file.bytes;
            }
            continue;
        }
        let young = now.duration_since(file.modified).unwrap_or_default() < options.grace;
        let (needed, entry) = match &file.name {
            CacheName::Temporary => {
                if !young {
                    temporaries.push(file);
                }
                continue;
            }
            CacheName::Entry(key) => (entries.contains(key), true),
            CacheName::Object(sha256) => (objects.contains(sha256), false),
        };
        match (needed, entry) {
            (true, true) => report.kept_entries += 1,
            (true, false) => report.kept_objects += 1,
            (false, _) if young => {}
            (false, _) => candidates.push(Candidate { file, entry }),
        }
    }
    for file in temporaries {
        if remove(cache, &file) {
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
        if remove(cache, &c.file) {
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
    report
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
    let text = crate::regular_file::read_to_string(path, crate::regular_file::Follow::Yes)
        .map_err(|source| BuildError::ReadSpec {
            path: path.to_path_buf(),
            source,
        })?;
    crate::out_dir::lock::hashes(&text).map_err(|why| BuildError::ReadSpec {
        path: path.to_path_buf(),
        source: io::Error::other(why),
    })
}

/// Every file of the cache with one of its own names, local or remote, and what was
/// skipped.
fn cache_files(cache: &Cache, now: SystemTime) -> io::Result<Listing> {
    let Some(remote) = cache.remote() else {
        return local_files(cache.root(), now);
    };
    let mut listing = Listing::default();
    for folder in ["entries", "objects"] {
        for listed in remote.list(folder)? {
            match CacheName::of(&listed.name) {
                Some(name) => listing.files.push(CacheFile {
                    path: PathBuf::from(listed.name),
                    name,
                    bytes: listed.bytes,
                    modified: listed.modified,
                    damaged: false,
                }),
                None => listing.skipped.push(listed.name),
            }
        }
    }
    listing.skipped.sort();
    Ok(listing)
}

/// [`cache_files`] of a local cache: `entries/*` and `objects/*/*`, walked without
/// following a symlink.
fn local_files(root: &Path, now: SystemTime) -> io::Result<Listing> {
    let mut listing = Listing::default();
    for top in ["entries", "objects"] {
        let dir = root.join(top);
        match fs::symlink_metadata(&dir) {
            Err(e) if e.kind() == io::ErrorKind::NotFound => continue,
            Err(e) => return Err(e),
            Ok(meta) if meta.is_dir() => {}
            Ok(meta) => {
                listing.skipped.push(format!("{top} ({})", kind_of(&meta)));
                continue;
            }
        }
        for (name, meta) in children(&dir)? {
            let relative = format!("{top}/{name}");
            if top == "objects" && meta.is_dir() {
                // A shard folder (two hex digits): its files, one level down.
                let shard =
                    name.len() == 2 && name.bytes().all(|b| matches!(b, b'0'..=b'9' | b'a'..=b'f'));
                if !shard {
                    listing.skipped.push(format!("{relative} (a folder)"));
                    continue;
                }
                for (inner, meta) in children(&dir.join(&name))? {
                    let relative = format!("{relative}/{inner}");
                    listing.add(root, relative, &meta, now);
                }
            } else {
                listing.add(root, relative, &meta, now);
            }
        }
    }
    listing.skipped.sort();
    Ok(listing)
}

impl Listing {
    /// Files the cache names are listed (damaged when not regular files); folders there
    /// and foreign names are skipped.
    fn add(&mut self, root: &Path, relative: String, meta: &fs::Metadata, now: SystemTime) {
        match CacheName::of(&relative) {
            Some(name) if !meta.is_dir() => self.files.push(CacheFile {
                path: root.join(&relative),
                name,
                bytes: if meta.is_file() { meta.len() } else { 0 },
                modified: meta.modified().unwrap_or(now),
                damaged: !meta.is_file(),
            }),
            _ if meta.is_symlink() => self.skipped.push(format!("{relative} (a symlink)")),
            _ if meta.is_dir() => self.skipped.push(format!("{relative} (a folder)")),
            _ => self.skipped.push(relative),
        }
    }
}

/// What a non-folder is, for the skipped list.
fn kind_of(meta: &fs::Metadata) -> &'static str {
    if meta.is_symlink() {
        "a symlink: not followed"
    } else {
        "not a folder"
    }
}

/// The entries of a folder with their own metadata (a symlink is reported as one, never
/// followed).
fn children(dir: &Path) -> io::Result<Vec<(String, fs::Metadata)>> {
    let mut out = Vec::new();
    for entry in fs::read_dir(dir)? {
        let entry = entry?;
        let meta = fs::symlink_metadata(entry.path())?;
        out.push((entry.file_name().to_string_lossy().into_owned(), meta));
    }
    Ok(out)
}

/// Removes one file of the cache (a symlink itself, never its target); whether it went.
fn remove(cache: &Cache, file: &CacheFile) -> bool {
    match cache.remote() {
        Some(remote) => remote.delete(&file.path.to_string_lossy()).is_ok(),
        None => fs::remove_file(&file.path).is_ok(),
    }
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
