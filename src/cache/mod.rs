//! The content-addressed stage cache: stage key → named output bytes.
//!
//! Layout on disk (default `.cityspec-cache/`):
//!
//! | path | holds |
//! |---|---|
//! | `CACHEDIR.TAG` | the marker: this folder is a cityspec cache ([`MARKER`]) |
//! | `objects/ab/abcdef…` | one output's bytes, named by their SHA-256 |
//! | `entries/<key>.json` | [`Entry`]: the stage name, its outputs' hashes and sizes, and its diagnostics |
//!
//! An entry is written only after all its objects are whole, so an interrupted build never
//! leaves an entry that points at missing bytes. Every read re-hashes the object: a cached
//! object whose bytes no longer match its name counts as a miss and is rebuilt, never used.
//!
//! Damage is a miss, never a crash or a hang: an entry is parsed into a validated [`Entry`]
//! (every hash 64 hex digits, every size in range) before anything indexes into it, and
//! every file is opened without following a symlink or blocking on a FIFO and read only
//! when it is a regular file ([`crate::regular_file`]). What is found damaged is reported
//! and replaced by the next write (a rename over it).
//!
//! The cache knows its own files by their exact names ([`CacheName`]): `cache gc` removes
//! nothing else, and only in a folder (or prefix) that holds the marker, which the first
//! write creates.
//!
//! The same layout lives either in a local folder (atomic renames) or under a bucket's
//! prefix (`--cache s3://…`, [`RemoteStore`]: whole-object PUTs). Only storage differs:
//! what is verified, and when, is the same for both.

use std::collections::BTreeMap;
use std::fs;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use crate::atomic_file::write_atomic;
use remote::{RemoteLocation, RemoteStore};

pub mod remote;
mod verified_memo;

use crate::diagnostic::Diagnostic;
use crate::hash::sha256_hex;
use crate::regular_file::{self, Follow};
pub use remote::cache_location;

/// The marker file at the cache's root. Its text follows the Cache Directory Tagging
/// specification (so backup tools skip the folder) and names cityspec, which is what
/// `cache gc` checks before it removes anything.
pub const MARKER: &str = "CACHEDIR.TAG";

const MARKER_TEXT: &str = "Signature: 8a477f597d28d172789f06886806bc55\n\
# This file is a cityspec cache's marker, written by cityspec when it created the cache.\n\
# `cityspec cache gc` removes files only where it finds this file.\n";

/// The largest object an entry may name (1 TiB): a size past it is damage.
pub const MAX_OBJECT_BYTES: u64 = 1 << 40;

/// A stage's outputs: file name → bytes, in memory or already stored as cache objects.
pub type Outputs = BTreeMap<String, Blob>;

/// One output's bytes: made by a stage and not yet stored, or an object in the cache,
/// with its bytes in memory or not. A stage that streams its outputs, like a camera path's
/// frames, stores each as it is made and keeps only its reference; cached stages whose
/// values nobody decodes are looked up the same way.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Blob {
    Bytes(Arc<Vec<u8>>),
    Stored(ObjectRef, Option<Arc<Vec<u8>>>),
}

impl Blob {
    /// The bytes, when they are in memory.
    pub fn bytes(&self) -> Option<&Arc<Vec<u8>>> {
        match self {
            Blob::Bytes(bytes) | Blob::Stored(_, Some(bytes)) => Some(bytes),
            Blob::Stored(_, None) => None,
        }
    }

    /// The SHA-256 of the bytes (computed only when not yet stored).
    pub fn sha256(&self) -> String {
        match self {
            Blob::Bytes(bytes) => sha256_hex(bytes),
            Blob::Stored(object, _) => object.sha256.clone(),
        }
    }

    /// The number of bytes.
    pub fn size(&self) -> u64 {
        match self {
            Blob::Bytes(bytes) => bytes.len() as u64,
            Blob::Stored(object, _) => object.bytes,
        }
    }

    /// This output once [`Cache::put`] stored it as `object`, keeping its bytes if it had
    /// them in memory.
    pub fn stored(self, object: ObjectRef) -> Blob {
        let bytes = match self {
            Blob::Bytes(bytes) | Blob::Stored(_, Some(bytes)) => Some(bytes),
            Blob::Stored(_, None) => None,
        };
        Blob::Stored(object, bytes)
    }
}

impl From<Vec<u8>> for Blob {
    fn from(bytes: Vec<u8>) -> Blob {
        Blob::Bytes(Arc::new(bytes))
    }
}

/// The names a stage's cache entry may hold, as its caller knows them: an entry naming
/// another is corrupt. The cache itself knows no stage.
pub trait NameCheck {
    /// Why `names` are not the stage's, if they are not.
    fn check_names(&self, names: &[&str]) -> Result<(), String>;
}

/// A cache that could not be opened: its location, and why.
#[derive(Debug)]
pub struct OpenError {
    pub path: PathBuf,
    pub source: io::Error,
}

/// Whether a looked-up stage's outputs are read into memory or only verified.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Load {
    /// Read every object (the stage's value is decoded from them).
    Bytes,
    /// Verify every object, one at a time, and keep only references (artifact-only stages:
    /// the driver copies them to the output folder one file at a time).
    References,
}

/// What `entries/<key>.json` records. Parsed only through [`Entry::parse`], so every
/// [`ObjectRef`] in it is valid.
#[derive(Debug, Serialize, Deserialize)]
pub struct Entry {
    pub stage: String,
    pub key: String,
    pub outputs: BTreeMap<String, ObjectRef>,
    /// The stage's diagnostics and those of every stage it read (see
    /// [`crate::diagnostic`]): replayed whenever the entry is used.
    pub diagnostics: Vec<Diagnostic>,
}

/// Why an entry's text is not an [`Entry`].
#[derive(Debug, PartialEq, Eq)]
pub enum BadEntry {
    /// Written by a cityspec before entries held diagnostics: used by none, rebuilt quietly.
    Older,
    /// Not an entry: what is wrong with it.
    Damaged(String),
}

impl Entry {
    /// The entry in `text`, validated (see [`ObjectRef`]).
    pub fn parse(text: &[u8]) -> Result<Entry, BadEntry> {
        /// The same fields, diagnostics optional, to tell an older entry from a damaged one.
        #[derive(Deserialize)]
        struct Record {
            stage: String,
            key: String,
            outputs: BTreeMap<String, ObjectRef>,
            diagnostics: Option<Vec<Diagnostic>>,
        }
        let record: Record =
            serde_json::from_slice(text).map_err(|e| BadEntry::Damaged(e.to_string()))?;
        let diagnostics = record.diagnostics.ok_or(BadEntry::Older)?;
        if record.stage.is_empty() {
            return Err(BadEntry::Damaged("it names no stage".to_owned()));
        }
        Ok(Entry {
            stage: record.stage,
            key: record.key,
            outputs: record.outputs,
            diagnostics,
        })
    }
}

/// One output: its hash and size. Deserialized only when the hash is 64 lowercase hex
/// digits and the size at most [`MAX_OBJECT_BYTES`], so code that names the object's file
/// (`objects/ab/…`) never meets a hash it cannot slice.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(try_from = "ObjectRecord")]
pub struct ObjectRef {
    pub sha256: String,
    pub bytes: u64,
}

/// An [`ObjectRef`] as read, before it is checked.
#[derive(Deserialize)]
struct ObjectRecord {
    sha256: String,
    bytes: u64,
}

impl TryFrom<ObjectRecord> for ObjectRef {
    type Error = String;

    fn try_from(record: ObjectRecord) -> Result<ObjectRef, String> {
        if !is_sha256(&record.sha256) {
            return Err(format!(
                "expected a SHA-256 of 64 lowercase hex digits, found {:?}",
                record.sha256
            ));
        }
        if record.bytes > MAX_OBJECT_BYTES {
            return Err(format!(
                "expected a size of at most {MAX_OBJECT_BYTES} bytes, found {}",
                record.bytes
            ));
        }
        Ok(ObjectRef {
            sha256: record.sha256,
            bytes: record.bytes,
        })
    }
}

/// Whether `text` is a SHA-256 as the cache writes it: 64 lowercase hex digits.
pub fn is_sha256(text: &str) -> bool {
    text.len() == 64 && text.bytes().all(|b| matches!(b, b'0'..=b'9' | b'a'..=b'f'))
}

/// What the cache holds under a key ([`Cache::entry_state`]).
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(tag = "state", rename_all = "lowercase")]
pub enum EntryState {
    /// No entry: the stage runs at the next build.
    Missing,
    /// An entry naming `outputs` objects of `bytes` in all, with `diagnostics` warnings.
    Cached {
        outputs: usize,
        bytes: u64,
        diagnostics: usize,
    },
    /// An entry an older cityspec wrote: the stage runs again, quietly.
    Older,
    /// An entry that cannot be used (unreadable, not an entry): rebuilt, with a warning.
    Damaged(String),
}

/// A stage's cached result: its outputs and its diagnostics.
#[derive(Debug)]
pub struct Hit {
    pub outputs: Outputs,
    pub diagnostics: Vec<Diagnostic>,
}

/// Why a lookup did not hit.
#[derive(Debug, PartialEq, Eq)]
pub enum Miss {
    /// No entry for the key.
    Absent,
    /// An entry exists but an object is missing, or its bytes do not match its hash.
    Corrupt(String),
}

/// The cache rooted at one folder, or at a bucket's prefix.
#[derive(Debug, Clone)]
pub struct Cache {
    /// The folder, or the URL (only named in messages then).
    root: PathBuf,
    /// Set for `s3://`, `gs://` and `az://` caches.
    remote: Option<Arc<RemoteStore>>,
    /// Set once this process has seen or written the marker.
    marked: Arc<OnceLock<()>>,
}

impl Cache {
    /// The cache in a local folder.
    pub fn new(root: impl Into<PathBuf>) -> Cache {
        Cache {
            root: root.into(),
            remote: None,
            marked: Arc::default(),
        }
    }

    /// The cache `--cache` names: a folder, or an `s3://`, `gs://` or `az://` URL, which is
    /// connected to (credentials from the environment) and listed once, so a store that
    /// cannot be reached fails here.
    pub fn open(location: &Path) -> Result<Cache, OpenError> {
        let text = location.to_string_lossy();
        let failed = |message: String| OpenError {
            path: location.to_path_buf(),
            source: io::Error::other(message),
        };
        match RemoteLocation::parse(&text).map_err(failed)? {
            None => Ok(Cache::new(location)),
            Some(remote) => Ok(Cache {
                root: location.to_path_buf(),
                remote: Some(Arc::new(RemoteStore::open(&remote).map_err(failed)?)),
                marked: Arc::default(),
            }),
        }
    }

    /// The folder, or the remote cache's URL.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// The folder of a local cache; `None` for a remote one.
    pub fn local_root(&self) -> Option<&Path> {
        self.remote.is_none().then_some(self.root.as_path())
    }

    /// The remote store, for a remote cache.
    pub fn remote(&self) -> Option<&RemoteStore> {
        self.remote.as_deref()
    }

    /// Whether the cache holds the marker `CACHEDIR.TAG` ([`MARKER`]) written by cityspec (`cache gc`
    /// removes nothing where it does not).
    pub fn is_marked(&self) -> io::Result<bool> {
        let text = match &self.remote {
            Some(remote) => remote.get(MARKER)?,
            None => match regular_file::read(&self.root.join(MARKER), Follow::No) {
                Ok(text) => Some(text),
                Err(e) if e.kind() == io::ErrorKind::NotFound => None,
                Err(e) if regular_file::is_not_regular(&e) => None,
                Err(e) => return Err(e),
            },
        };
        Ok(text.is_some_and(|t| t == MARKER_TEXT.as_bytes()))
    }

    /// Writes the marker unless this process saw it already: before the first object of
    /// every build (and at the start of every build, so a cache an older cityspec made is
    /// marked by its next build even when that build writes nothing), so a folder that
    /// holds cache files holds the marker too.
    pub fn mark(&self) -> io::Result<()> {
        if self.marked.get().is_some() {
            return Ok(());
        }
        match &self.remote {
            Some(remote) => {
                if remote.get(MARKER)?.is_none() {
                    remote.put(MARKER, MARKER_TEXT.as_bytes())?;
                }
            }
            None => {
                fs::create_dir_all(&self.root)?;
                // Never through a symlink or over a file someone else put there.
                match fs::File::create_new(self.root.join(MARKER)) {
                    Ok(mut file) => file.write_all(MARKER_TEXT.as_bytes())?,
                    Err(e) if e.kind() == io::ErrorKind::AlreadyExists => {}
                    Err(e) => return Err(e),
                }
            }
        }
        let _ = self.marked.set(());
        Ok(())
    }

    /// The entry recorded under `key`, without reading or verifying its objects; `None`
    /// when there is none or it is damaged.
    pub fn entry(&self, key: &str) -> Option<Entry> {
        let entry = Entry::parse(&self.read_entry(key).ok()??).ok()?;
        (entry.key == key).then_some(entry)
    }

    /// What the cache holds under `key`, from the entry alone (its objects are verified
    /// when a build reads them): for `cityspec explain`.
    pub fn entry_state(&self, key: &str) -> EntryState {
        match self.read_entry(key) {
            Ok(None) => EntryState::Missing,
            Err(e) => EntryState::Damaged(e.to_string()),
            Ok(Some(text)) => match Entry::parse(&text) {
                Ok(entry) if entry.key == key => EntryState::Cached {
                    outputs: entry.outputs.len(),
                    bytes: entry.outputs.values().map(|o| o.bytes).sum(),
                    diagnostics: entry.diagnostics.len(),
                },
                Ok(_) => EntryState::Damaged("it records another key".to_owned()),
                Err(BadEntry::Older) => EntryState::Older,
                Err(BadEntry::Damaged(why)) => EntryState::Damaged(why),
            },
        }
    }

    /// Whether an entry is recorded under `key` (whatever it holds).
    pub fn has_entry(&self, key: &str) -> bool {
        self.read_entry(key).is_ok_and(|text| text.is_some())
    }

    /// The bytes of `key`'s entry; `None` when there is none. A FIFO, folder or symlink
    /// there is an error (damage), found without blocking.
    fn read_entry(&self, key: &str) -> io::Result<Option<Vec<u8>>> {
        match &self.remote {
            Some(remote) => remote.get(&entry_name(key)),
            None => match regular_file::read(&self.entry_path(key), Follow::No) {
                Ok(text) => Ok(Some(text)),
                Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(None),
                Err(e) => Err(e),
            },
        }
    }

    /// The outputs recorded under `key`, each verified against its hash, read into memory
    /// or kept as references (`load`).
    pub fn get(&self, key: &str, load: Load) -> Result<Outputs, Miss> {
        self.get_checked(key, load, |_| Ok(()))
            .map(|hit| hit.outputs)
    }

    /// [`Cache::get`] for stage `stage`, whose output names must pass `names` (see
    /// `output_names`): an entry of another stage, or one naming a file its stage
    /// never writes, is corrupt before any of its objects is read.
    pub fn get_stage(
        &self,
        stage: &str,
        key: &str,
        load: Load,
        names: &dyn NameCheck,
    ) -> Result<Outputs, Miss> {
        self.lookup(stage, key, load, names).map(|hit| hit.outputs)
    }

    /// [`Cache::get_stage`] with the entry's diagnostics.
    pub fn lookup(
        &self,
        stage: &str,
        key: &str,
        load: Load,
        names: &dyn NameCheck,
    ) -> Result<Hit, Miss> {
        self.get_checked(key, load, |entry| {
            if entry.stage != stage {
                return Err(format!("it records stage {:?}, not {stage:?}", entry.stage));
            }
            let names_of: Vec<&str> = entry.outputs.keys().map(String::as_str).collect();
            names.check_names(&names_of)
        })
    }

    fn get_checked(
        &self,
        key: &str,
        load: Load,
        accept: impl FnOnce(&Entry) -> Result<(), String>,
    ) -> Result<Hit, Miss> {
        let entry_path = self.entry_path(key);
        let text = match self.read_entry(key) {
            Ok(Some(text)) => text,
            Ok(None) => return Err(Miss::Absent),
            // Unreadable (a FIFO, a symlink, a folder, no permission, a store that fails
            // to answer): damage, reported, and replaced when the stage's entry is written.
            Err(e) => {
                return Err(Miss::Corrupt(format!(
                    "{} cannot be read: {e}",
                    entry_path.display()
                )));
            }
        };
        let entry = match Entry::parse(&text) {
            Ok(entry) => entry,
            Err(BadEntry::Older) => return Err(Miss::Absent),
            Err(BadEntry::Damaged(why)) => {
                return Err(Miss::Corrupt(format!(
                    "{} is not a cache entry: {why}",
                    entry_path.display()
                )));
            }
        };
        if entry.key != key {
            return Err(Miss::Corrupt(format!(
                "{} records another key",
                entry_path.display()
            )));
        }
        accept(&entry).map_err(|why| Miss::Corrupt(format!("{}: {why}", entry_path.display())))?;
        let mut outputs = Outputs::new();
        for (name, object) in entry.outputs {
            let bytes = self
                .read_object(&object)
                .map_err(|why| Miss::Corrupt(format!("{why} ({name})")))?;
            let blob = match load {
                Load::Bytes => Blob::Stored(object, Some(Arc::new(bytes))),
                Load::References => {
                    // Downloaded once: the folder write takes these bytes (see
                    // `verified_memo`).
                    if let Some(remote) = &self.remote {
                        remote.verified.keep(&object.sha256, bytes);
                    }
                    Blob::Stored(object, None)
                }
            };
            outputs.insert(name, blob);
        }
        Ok(Hit {
            outputs,
            diagnostics: entry.diagnostics,
        })
    }

    /// The bytes of a stored object, verified against its size and hash (in this process:
    /// a remote object checked with its entry moments ago is not downloaded again).
    pub fn read_object(&self, object: &ObjectRef) -> Result<Vec<u8>, String> {
        let path = self.object_path(&object.sha256);
        let bytes = match &self.remote {
            Some(remote) => match remote.verified.take(&object.sha256) {
                // Hashed when kept: the memo holds only bytes that matched their name.
                Some(bytes) => return Ok(bytes),
                None => match remote.get(&object_name(&object.sha256)) {
                    Ok(Some(bytes)) => bytes,
                    Ok(None) => return Err(format!("{} is missing", path.display())),
                    Err(e) => return Err(format!("{} cannot be read: {e}", path.display())),
                },
            },
            None => match regular_file::read(&path, Follow::No) {
                Ok(bytes) => bytes,
                Err(e) if e.kind() == io::ErrorKind::NotFound => {
                    return Err(format!("{} is missing", path.display()));
                }
                Err(e) => return Err(format!("{} cannot be read: {e}", path.display())),
            },
        };
        if bytes.len() as u64 != object.bytes || sha256_hex(&bytes) != object.sha256 {
            return Err(format!("{} no longer matches its hash", path.display()));
        }
        Ok(bytes)
    }

    /// Stores one object (unless an intact copy is there already) and returns its reference.
    pub fn put_object(&self, bytes: &[u8]) -> io::Result<ObjectRef> {
        self.mark()?;
        let object = ObjectRef {
            sha256: sha256_hex(bytes),
            bytes: bytes.len() as u64,
        };
        if let Some(remote) = &self.remote {
            // Always uploaded, without reading what is there first: one request instead
            // of two, a damaged copy is replaced unseen, and the new Last-Modified keeps
            // `cache gc` off it (what `touch` does locally).
            remote.put(&object_name(&object.sha256), bytes)?;
            return Ok(object);
        }
        let path = self.object_path(&object.sha256);
        // The copy there is intact when it holds these very bytes: comparing costs less
        // than hashing again, and the export's textures are often there already (they
        // are the facade stage's objects).
        let intact = regular_file::read(&path, Follow::No).is_ok_and(|old| old == bytes);
        if intact {
            touch(&path);
        } else {
            write_atomic(&path, bytes)?;
        }
        Ok(object)
    }

    /// Stores one object whose bytes `fill` writes, without holding them in memory: they
    /// go to a temporary file in `objects/`, hashed as they pass, which is then renamed to
    /// its hash's name (or removed, when an intact copy is there already).
    pub fn put_object_with(
        &self,
        fill: impl FnOnce(&mut dyn Write) -> io::Result<()>,
    ) -> io::Result<ObjectRef> {
        self.mark()?;
        // A remote cache stages the bytes in a local temporary file, then uploads it.
        let dir = match &self.remote {
            Some(_) => std::env::temp_dir(),
            None => self.root.join("objects"),
        };
        fs::create_dir_all(&dir)?;
        // Removed when dropped, on every path but the rename into place.
        let mut temp = crate::atomic_file::temp_file(&dir, Path::new("stream"))?;
        let object = {
            let mut out = Hashing::new(io::BufWriter::new(temp.as_file_mut()));
            fill(&mut out)?;
            out.inner.flush()?;
            out.finish()
        };
        if let Some(remote) = &self.remote {
            return remote
                .put_file(&object_name(&object.sha256), temp.path())
                .map(|()| object);
        }
        let path = self.object_path(&object.sha256);
        let intact = regular_file::read(&path, Follow::No)
            .is_ok_and(|old| sha256_hex(&old) == object.sha256);
        if intact {
            touch(&path);
        } else {
            fs::create_dir_all(path.parent().expect("objects have a folder"))?;
            temp.persist(&path).map_err(|e| e.error)?;
        }
        Ok(object)
    }

    /// Records `outputs` and `diagnostics` under `key`: objects first (those in memory are
    /// stored now; stored ones were stored by [`Cache::put_object`]), then the entry.
    pub fn put(
        &self,
        stage: &str,
        key: &str,
        outputs: &Outputs,
        diagnostics: &[Diagnostic],
    ) -> io::Result<BTreeMap<String, ObjectRef>> {
        self.mark()?;
        let store = |(name, blob): (&String, &Blob)| {
            let object = match blob {
                Blob::Bytes(bytes) => self.put_object(bytes)?,
                Blob::Stored(object, _) => object.clone(),
            };
            Ok::<_, io::Error>((name.clone(), object))
        };
        // A local cache hashes and writes the objects in parallel (the export's OBJ and GLB
        // are 24 MB each); a remote one uploads them one by one from this thread.
        let refs: BTreeMap<String, ObjectRef> = match &self.remote {
            Some(_) => outputs.iter().map(store).collect::<io::Result<_>>()?,
            None => {
                // Largest first, one output a task, so the two biggest go to two threads.
                let mut largest_first: Vec<(&String, &Blob)> = outputs.iter().collect();
                largest_first.sort_by_key(|(_, blob)| std::cmp::Reverse(blob.size()));
                largest_first
                    .into_par_iter()
                    .with_max_len(1)
                    .map(store)
                    .collect::<io::Result<Vec<_>>>()?
                    .into_iter()
                    .collect()
            }
        };
        let entry = Entry {
            stage: stage.to_owned(),
            key: key.to_owned(),
            outputs: refs.clone(),
            diagnostics: diagnostics.to_vec(),
        };
        let mut text = serde_json::to_vec_pretty(&entry).map_err(io::Error::other)?;
        text.push(b'\n');
        match &self.remote {
            // One whole-object PUT: readers see the old entry or the new one.
            Some(remote) => remote.put(&entry_name(key), &text)?,
            None => write_atomic(&self.entry_path(key), &text)?,
        }
        Ok(refs)
    }

    /// Where the object with this hash lives (for a remote cache, its URL).
    pub fn object_path(&self, sha256: &str) -> PathBuf {
        self.root.join(object_name(sha256))
    }

    /// Where the entry of `key` lives (for a remote cache, its URL).
    pub fn entry_path(&self, key: &str) -> PathBuf {
        self.root.join(entry_name(key))
    }
}

/// An object's path in the cache: `objects/ab/abcdef…` (a hash too short to shard, which
/// no valid [`ObjectRef`] holds, names a file no cache writes, so it is only missing).
fn object_name(sha256: &str) -> String {
    format!("objects/{}/{sha256}", sha256.get(..2).unwrap_or("--"))
}

/// An entry's path in the cache: `entries/<key>.json`.
fn entry_name(key: &str) -> String {
    format!("entries/{key}.json")
}

/// A file the cache writes, known by its exact name (relative to the cache's root,
/// `/`-separated). `cache gc` removes these and nothing else.
#[derive(Debug, PartialEq, Eq)]
pub enum CacheName {
    /// `entries/<key>.json`, the key 64 hex digits.
    Entry(String),
    /// `objects/ab/<sha256>`, the shard the hash's first two digits.
    Object(String),
    /// What a killed write left: `.<one of those names>.cityspec-tmp-<random>` beside
    /// it, or `objects/.stream.cityspec-tmp-<random>` (`<random>` is tempfile's six
    /// letters and digits; older cityspec versions wrote `<pid>-<n>` there).
    Temporary,
}

impl CacheName {
    /// What `relative` is, when it is a name the cache writes.
    pub fn of(relative: &str) -> Option<CacheName> {
        let parts: Vec<&str> = relative.split('/').collect();
        match parts[..] {
            ["entries", name] => match name.strip_suffix(".json") {
                Some(key) if is_sha256(key) => Some(CacheName::Entry(key.to_owned())),
                _ => temporary_of(name, |base| {
                    base.strip_suffix(".json").is_some_and(is_sha256)
                }),
            },
            ["objects", shard, name] if shard.len() == 2 && is_lower_hex(shard) => {
                if is_sha256(name) && name.starts_with(shard) {
                    Some(CacheName::Object(name.to_owned()))
                } else {
                    temporary_of(name, |base| is_sha256(base) && base.starts_with(shard))
                }
            }
            ["objects", name] => temporary_of(name, |base| base == "stream"),
            _ => None,
        }
    }
}

/// [`CacheName::Temporary`] when `name` is a temporary of a file whose name passes `base`.
fn temporary_of(name: &str, base: impl Fn(&str) -> bool) -> Option<CacheName> {
    let (stem, tail) = name
        .strip_prefix('.')?
        .split_once(crate::atomic_file::TEMP_MARK)?;
    let random = tail.len() == crate::atomic_file::TEMP_RANDOM
        && tail.bytes().all(|b| b.is_ascii_alphanumeric());
    let digits = |t: &str| !t.is_empty() && t.bytes().all(|b| b.is_ascii_digit());
    let pid_and_count = tail
        .split_once('-')
        .is_some_and(|(pid, n)| digits(pid) && digits(n));
    (base(stem) && (random || pid_and_count)).then_some(CacheName::Temporary)
}

fn is_lower_hex(text: &str) -> bool {
    text.bytes().all(|b| matches!(b, b'0'..=b'9' | b'a'..=b'f'))
}

/// Sets an object's mtime to now: `cache gc` removes nothing younger than its grace
/// period, so an object a running build reuses (instead of writing it) is kept until
/// the build has written the entry that names it. Best effort: a read-only cache still
/// builds.
fn touch(path: &Path) {
    if let Ok(file) = fs::File::options().append(true).open(path) {
        let _ = file.set_modified(std::time::SystemTime::now());
    }
}

/// A writer that hashes and counts what passes through it; with `io::sink()` it only
/// hashes (the reference bytes would have, without storing them).
pub struct Hashing<W> {
    inner: W,
    hasher: Sha256,
    bytes: u64,
}

impl<W: Write> Hashing<W> {
    pub fn new(inner: W) -> Hashing<W> {
        Hashing {
            inner,
            hasher: Sha256::new(),
            bytes: 0,
        }
    }

    /// The reference of everything written.
    pub fn finish(self) -> ObjectRef {
        ObjectRef {
            sha256: crate::hash::hex(&self.hasher.finalize()),
            bytes: self.bytes,
        }
    }
}

impl<W: Write> Write for Hashing<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.hasher.update(&buf[..n]);
        self.bytes += n as u64;
        Ok(n)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every name is a stage's.
    struct AnyNames;

    impl NameCheck for AnyNames {
        fn check_names(&self, _: &[&str]) -> Result<(), String> {
            Ok(())
        }
    }

    fn outputs(pairs: &[(&str, &[u8])]) -> Outputs {
        pairs
            .iter()
            .map(|(n, b)| (n.to_string(), Blob::from(b.to_vec())))
            .collect()
    }

    #[test]
    fn put_then_get_round_trips() {
        let dir = tempfile::tempdir().unwrap();
        let cache = Cache::new(dir.path());
        assert_eq!(cache.get("k1", Load::Bytes), Err(Miss::Absent));
        let out = outputs(&[("a.json", b"{}"), ("b.png", b"png bytes")]);
        cache.put("parse", "k1", &out, &[]).unwrap();
        let back = cache.get("k1", Load::Bytes).unwrap();
        for (name, blob) in &back {
            assert_eq!(blob.bytes(), out[name].bytes());
            assert_eq!(blob.sha256(), out[name].sha256());
        }
        // By reference: the same hashes, no bytes.
        let refs = cache.get("k1", Load::References).unwrap();
        assert_eq!(refs.len(), 2);
        for (name, blob) in &refs {
            assert!(blob.bytes().is_none());
            assert_eq!(blob.sha256(), out[name].sha256());
            assert_eq!(blob.size(), out[name].size());
        }
    }

    #[test]
    fn corrupted_or_missing_object_is_a_miss() {
        let dir = tempfile::tempdir().unwrap();
        let cache = Cache::new(dir.path());
        let refs = cache
            .put("mirror", "k2", &outputs(&[("layout.png", b"pixels")]), &[])
            .unwrap();
        let object = cache.object_path(&refs["layout.png"].sha256);
        fs::write(&object, b"pixelz").unwrap();
        assert!(
            matches!(cache.get("k2", Load::References), Err(Miss::Corrupt(m)) if m.contains("no longer matches"))
        );
        // Putting the same outputs again repairs the object.
        cache
            .put("mirror", "k2", &outputs(&[("layout.png", b"pixels")]), &[])
            .unwrap();
        assert!(cache.get("k2", Load::References).is_ok());
        fs::remove_file(&object).unwrap();
        assert!(
            matches!(cache.get("k2", Load::References), Err(Miss::Corrupt(m)) if m.contains("missing"))
        );
    }

    #[test]
    fn streamed_objects_are_recorded_by_reference() {
        let dir = tempfile::tempdir().unwrap();
        let cache = Cache::new(dir.path());
        let frame = cache.put_object(b"frame 0").unwrap();
        assert_eq!(cache.read_object(&frame).unwrap(), b"frame 0");
        let out = Outputs::from([
            (
                "rgb/000000.png".to_owned(),
                Blob::Stored(frame.clone(), None),
            ),
            ("coco.json".to_owned(), Blob::from(b"{}".to_vec())),
        ]);
        cache.put("frames", "k4", &out, &[]).unwrap();
        let back = cache.get("k4", Load::Bytes).unwrap();
        assert_eq!(
            back["rgb/000000.png"].bytes().unwrap().as_slice(),
            b"frame 0"
        );
        assert_eq!(
            cache.get("k4", Load::References).unwrap()["rgb/000000.png"],
            Blob::Stored(frame, None)
        );
    }

    const SHA: &str = "3f2a0000000000000000000000000000000000000000000000000000000000e1";

    #[test]
    fn the_cache_knows_its_own_names_and_no_others() {
        let own = [
            (
                format!("entries/{SHA}.json"),
                CacheName::Entry(SHA.to_owned()),
            ),
            (
                format!("objects/3f/{SHA}"),
                CacheName::Object(SHA.to_owned()),
            ),
            (
                format!("entries/.{SHA}.json.cityspec-tmp-12-0"),
                CacheName::Temporary,
            ),
            (
                format!("objects/3f/.{SHA}.cityspec-tmp-7-31"),
                CacheName::Temporary,
            ),
            (
                "objects/.stream.cityspec-tmp-7-2".to_owned(),
                CacheName::Temporary,
            ),
            (
                format!("entries/.{SHA}.json.cityspec-tmp-aZ09xy"),
                CacheName::Temporary,
            ),
            (
                format!("objects/3f/.{SHA}.cityspec-tmp-Qr5tUv"),
                CacheName::Temporary,
            ),
            (
                "objects/.stream.cityspec-tmp-k3Jd8w".to_owned(),
                CacheName::Temporary,
            ),
        ];
        for (name, kind) in own {
            assert_eq!(CacheName::of(&name), Some(kind), "{name}");
        }
        let foreign = [
            "objects/README-keep.txt".to_owned(),
            // git's objects: 38 hex digits under a two-digit shard.
            "objects/3f/2a00000000000000000000000000000000000e".to_owned(),
            format!("objects/ab/{SHA}"),
            format!("objects/3F/{}", SHA.to_uppercase()),
            format!("objects/3f/{SHA}/x"),
            "entries/HEAD".to_owned(),
            "entries/k1.json".to_owned(),
            format!("entries/{SHA}.json.bak"),
            format!("entries/.{SHA}.json.cityspec-tmp-x-0"),
            "entries/.notes.cityspec-tmp-1-0".to_owned(),
            "objects/.stream.cityspec-tmp-k3Jd8".to_owned(),
            "objects/.stream.cityspec-tmp-k3Jd8w.bak".to_owned(),
            "objects/info/packs".to_owned(),
            format!("fresh/{SHA}.json"),
        ];
        for name in foreign {
            assert_eq!(CacheName::of(&name), None, "{name}");
        }
    }

    #[test]
    fn entries_with_bad_hashes_or_sizes_are_damage_not_panics() {
        let dir = tempfile::tempdir().unwrap();
        let cache = Cache::new(dir.path());
        fs::create_dir_all(dir.path().join("entries")).unwrap();
        let entry = |sha: &str, bytes: &str| {
            format!(
                r#"{{"stage":"mirror","key":"k5","outputs":{{"layout.png":{{"sha256":"{sha}","bytes":{bytes}}}}},"diagnostics":[]}}"#
            )
        };
        for (sha, bytes) in [
            ("", "1"),
            ("a", "1"),
            ("é", "1"),
            (&SHA.to_uppercase()[..], "1"),
            (SHA, "1099511627777"),
        ] {
            fs::write(dir.path().join("entries/k5.json"), entry(sha, bytes)).unwrap();
            assert!(
                matches!(cache.get("k5", Load::Bytes), Err(Miss::Corrupt(m)) if m.contains("not a cache entry")),
                "{sha:?} {bytes}"
            );
            assert!(cache.entry("k5").is_none());
        }
        // An entry of an older cityspec (no diagnostics) is no entry: rebuilt quietly.
        let older = r#"{"stage":"mirror","key":"k5","outputs":{}}"#;
        fs::write(dir.path().join("entries/k5.json"), older).unwrap();
        assert_eq!(cache.get("k5", Load::Bytes), Err(Miss::Absent));
        // A hash from nowhere names a file that is only missing.
        assert_eq!(
            cache.object_path("a"),
            dir.path().join("objects/--/a"),
            "no slice past the end"
        );
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn a_fifo_or_symlink_in_the_cache_is_damage_found_without_blocking_and_replaced() {
        let dir = tempfile::tempdir().unwrap();
        let cache = Cache::new(dir.path());
        let out = outputs(&[("layout.png", b"pixels")]);
        let refs = cache.put("mirror", "k6", &out, &[]).unwrap();
        let entry = cache.entry_path("k6");
        fs::remove_file(&entry).unwrap();
        rustix::fs::mkfifoat(rustix::fs::CWD, &entry, rustix::fs::Mode::RUSR).unwrap();
        // Opened blocking, this read would wait for a writer forever.
        let miss = cache.get("k6", Load::Bytes);
        assert!(
            matches!(&miss, Err(Miss::Corrupt(m)) if m.contains("a FIFO, not a regular file")),
            "{miss:?}"
        );
        cache.put("mirror", "k6", &out, &[]).unwrap();
        assert!(
            cache.get("k6", Load::Bytes).is_ok(),
            "the FIFO was replaced"
        );
        // An object replaced by a symlink to a file with the same bytes is not followed.
        let object = cache.object_path(&refs["layout.png"].sha256);
        let elsewhere = dir.path().join("elsewhere");
        fs::write(&elsewhere, b"pixels").unwrap();
        fs::remove_file(&object).unwrap();
        std::os::unix::fs::symlink(&elsewhere, &object).unwrap();
        let miss = cache.get("k6", Load::Bytes);
        assert!(
            matches!(&miss, Err(Miss::Corrupt(m)) if m.contains("a symlink")),
            "{miss:?}"
        );
        cache.put("mirror", "k6", &out, &[]).unwrap();
        assert!(!fs::symlink_metadata(&object).unwrap().is_symlink());
        assert!(cache.get("k6", Load::Bytes).is_ok());
    }

    #[test]
    fn diagnostics_are_kept_with_the_entry_and_the_first_write_marks_the_cache() {
        let dir = tempfile::tempdir().unwrap();
        let cache = Cache::new(dir.path().join("new"));
        assert!(!cache.is_marked().unwrap());
        let warned = [Diagnostic::warning("facade-skipped", "skipped a.jpg")];
        cache
            .put(
                "facades",
                "k7",
                &outputs(&[("facades.json", b"[]")]),
                &warned,
            )
            .unwrap();
        let hit = cache
            .lookup("facades", "k7", Load::Bytes, &AnyNames)
            .unwrap();
        assert_eq!(hit.diagnostics, warned);
        assert!(cache.is_marked().unwrap());
        // A marker someone else wrote is not cityspec's.
        let other = tempfile::tempdir().unwrap();
        fs::write(
            other.path().join(MARKER),
            "Signature: 8a477f597d28d172789f06886806bc55\n",
        )
        .unwrap();
        assert!(!Cache::new(other.path()).is_marked().unwrap());
    }

    #[test]
    fn garbled_entry_is_a_miss() {
        let dir = tempfile::tempdir().unwrap();
        let cache = Cache::new(dir.path());
        fs::create_dir_all(dir.path().join("entries")).unwrap();
        fs::write(dir.path().join("entries/k3.json"), b"{ half").unwrap();
        assert!(matches!(
            cache.get("k3", Load::Bytes),
            Err(Miss::Corrupt(_))
        ));
    }

    #[test]
    fn streamed_object_is_stored_under_its_hash() {
        let dir = tempfile::tempdir().unwrap();
        let cache = Cache::new(dir.path());
        let object = cache
            .put_object_with(|out| {
                out.write_all(b"coco ")?;
                out.write_all(b"text")
            })
            .unwrap();
        assert_eq!(object, cache.put_object(b"coco text").unwrap());
        assert_eq!(cache.read_object(&object).unwrap(), b"coco text");
        // Again, with the object in place: the same reference, no temporary left.
        let again = cache.put_object_with(|out| out.write_all(b"coco text"));
        assert_eq!(again.unwrap(), object);
        let left: Vec<_> = fs::read_dir(dir.path().join("objects"))
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(left.len(), 1, "{left:?}");
        // A failing writer leaves nothing.
        let failed = cache.put_object_with(|_| Err(io::Error::other("no")));
        assert!(failed.is_err());
        assert_eq!(fs::read_dir(dir.path().join("objects")).unwrap().count(), 1);
    }
}
