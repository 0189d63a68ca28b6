//! The content-addressed stage cache: stage key → named output bytes.
//!
//! Layout on disk (default `.cityspec-cache/`):
//!
//! | path | holds |
//! |---|---|
//! | `objects/ab/abcdef…` | one output's bytes, named by their SHA-256 |
//! | `entries/<key>.json` | [`Entry`]: the stage name and its outputs' hashes and sizes |
//!
//! An entry is written only after all its objects are whole, so an interrupted build never
//! leaves an entry that points at missing bytes. Every read re-hashes the object: a cached
//! object whose bytes no longer match its name counts as a miss and is rebuilt, never used.

use std::collections::BTreeMap;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use serde::{Deserialize, Serialize};

use super::atomic::write_atomic;
use crate::hash::sha256_hex;

/// A stage's outputs: file name → bytes.
pub type Outputs = BTreeMap<String, Arc<Vec<u8>>>;

/// What `entries/<key>.json` records.
#[derive(Debug, Serialize, Deserialize)]
pub struct Entry {
    pub stage: String,
    pub key: String,
    pub outputs: BTreeMap<String, ObjectRef>,
}

/// One output: its hash and size.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ObjectRef {
    pub sha256: String,
    pub bytes: u64,
}

/// Why a lookup did not hit.
#[derive(Debug, PartialEq, Eq)]
pub enum Miss {
    /// No entry for the key.
    Absent,
    /// An entry exists but an object is missing, or its bytes do not match its hash.
    Corrupt(String),
}

/// The cache rooted at one folder.
#[derive(Debug, Clone)]
pub struct Cache {
    root: PathBuf,
}

impl Cache {
    pub fn new(root: impl Into<PathBuf>) -> Cache {
        Cache { root: root.into() }
    }

    pub fn root(&self) -> &Path {
        &self.root
    }

    /// The entry recorded under `key`, without reading or verifying its objects.
    pub fn entry(&self, key: &str) -> Option<Entry> {
        let entry: Entry = serde_json::from_slice(&fs::read(self.entry_path(key)).ok()?).ok()?;
        (entry.key == key).then_some(entry)
    }

    /// The outputs recorded under `key`, each verified against its hash.
    pub fn get(&self, key: &str) -> Result<Outputs, Miss> {
        let entry_path = self.entry_path(key);
        let text = match fs::read(&entry_path) {
            Ok(text) => text,
            Err(_) => return Err(Miss::Absent),
        };
        let entry: Entry = serde_json::from_slice(&text)
            .map_err(|_| Miss::Corrupt(format!("{} is not a cache entry", entry_path.display())))?;
        if entry.key != key {
            return Err(Miss::Corrupt(format!(
                "{} records another key",
                entry_path.display()
            )));
        }
        let mut outputs = Outputs::new();
        for (name, object) in &entry.outputs {
            let path = self.object_path(&object.sha256);
            let bytes = fs::read(&path)
                .map_err(|_| Miss::Corrupt(format!("{} is missing ({name})", path.display())))?;
            if bytes.len() as u64 != object.bytes || sha256_hex(&bytes) != object.sha256 {
                return Err(Miss::Corrupt(format!(
                    "{} no longer matches its hash ({name})",
                    path.display()
                )));
            }
            outputs.insert(name.clone(), Arc::new(bytes));
        }
        Ok(outputs)
    }

    /// Records `outputs` under `key`: objects first, then the entry.
    pub fn put(
        &self,
        stage: &str,
        key: &str,
        outputs: &Outputs,
    ) -> io::Result<BTreeMap<String, ObjectRef>> {
        let mut refs = BTreeMap::new();
        for (name, bytes) in outputs {
            let object = ObjectRef {
                sha256: sha256_hex(bytes),
                bytes: bytes.len() as u64,
            };
            let path = self.object_path(&object.sha256);
            let intact = fs::read(&path).is_ok_and(|old| sha256_hex(&old) == object.sha256);
            if !intact {
                write_atomic(&path, bytes)?;
            }
            refs.insert(name.clone(), object);
        }
        let entry = Entry {
            stage: stage.to_owned(),
            key: key.to_owned(),
            outputs: refs.clone(),
        };
        let mut text = serde_json::to_vec_pretty(&entry).map_err(io::Error::other)?;
        text.push(b'\n');
        write_atomic(&self.entry_path(key), &text)?;
        Ok(refs)
    }

    /// Where the object with this hash lives.
    pub fn object_path(&self, sha256: &str) -> PathBuf {
        self.root.join("objects").join(&sha256[..2]).join(sha256)
    }

    fn entry_path(&self, key: &str) -> PathBuf {
        self.root.join("entries").join(format!("{key}.json"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn outputs(pairs: &[(&str, &[u8])]) -> Outputs {
        pairs
            .iter()
            .map(|(n, b)| (n.to_string(), Arc::new(b.to_vec())))
            .collect()
    }

    #[test]
    fn put_then_get_round_trips() {
        let dir = tempfile::tempdir().unwrap();
        let cache = Cache::new(dir.path());
        assert_eq!(cache.get("k1"), Err(Miss::Absent));
        let out = outputs(&[("a.json", b"{}"), ("b.png", b"png bytes")]);
        cache.put("parse", "k1", &out).unwrap();
        assert_eq!(cache.get("k1").unwrap(), out);
    }

    #[test]
    fn corrupted_or_missing_object_is_a_miss() {
        let dir = tempfile::tempdir().unwrap();
        let cache = Cache::new(dir.path());
        let refs = cache
            .put("mirror", "k2", &outputs(&[("layout.png", b"pixels")]))
            .unwrap();
        let object = cache.object_path(&refs["layout.png"].sha256);
        fs::write(&object, b"pixelz").unwrap();
        assert!(
            matches!(cache.get("k2"), Err(Miss::Corrupt(m)) if m.contains("no longer matches"))
        );
        // Putting the same outputs again repairs the object.
        cache
            .put("mirror", "k2", &outputs(&[("layout.png", b"pixels")]))
            .unwrap();
        assert!(cache.get("k2").is_ok());
        fs::remove_file(&object).unwrap();
        assert!(matches!(cache.get("k2"), Err(Miss::Corrupt(m)) if m.contains("missing")));
    }

    #[test]
    fn garbled_entry_is_a_miss() {
        let dir = tempfile::tempdir().unwrap();
        let cache = Cache::new(dir.path());
        fs::create_dir_all(dir.path().join("entries")).unwrap();
        fs::write(dir.path().join("entries/k3.json"), b"{ half").unwrap();
        assert!(matches!(cache.get("k3"), Err(Miss::Corrupt(_))));
    }
}
