//! `manifest.json`: every artifact of a build with its hash, size, stage and stage key.

use serde::{Deserialize, Serialize};

/// The manifest of one spec's output folder.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Manifest {
    /// The spec's `name`.
    pub name: String,
    /// Artifacts sorted by path.
    pub artifacts: Vec<Artifact>,
}

/// One artifact in the output folder.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Artifact {
    /// Path relative to the output folder, `/`-separated.
    pub path: String,
    pub sha256: String,
    pub bytes: u64,
    /// The stage that produced it.
    pub stage: String,
    /// That stage's cache key.
    pub key: String,
}

impl Manifest {
    /// Pretty JSON with a trailing newline: the bytes written to `manifest.json`.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut text = serde_json::to_vec_pretty(self).expect("manifests serialize to JSON");
        text.push(b'\n');
        text
    }

    pub fn from_bytes(bytes: &[u8]) -> Option<Manifest> {
        serde_json::from_slice(bytes).ok()
    }
}
