//! Stage cache keys: (stage name, code version, the spec part it reads, its input keys) → SHA-256.
//!
//! The key's inputs, as in cargo's fingerprints:
//!
//! | input | why |
//! |---|---|
//! | stage name | two stages reading the same things still differ |
//! | cityspec version, the stage's own `VERSION` and the driver's `codec::VERSION` | new code or new encodings, new results |
//! | the canonical JSON of the spec part the stage reads | a spec change reruns exactly its readers |
//! | the keys of the stages it consumes (or an input file's SHA-256) | changes propagate downstream |
//!
//! Never an absolute path, a timestamp, a host name or a thread count.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::hash::sha256_hex;

/// What a stage key is the hash of.
#[derive(Clone, Debug, Serialize)]
pub struct StageKey {
    stage: &'static str,
    cityspec: &'static str,
    stage_version: u32,
    codec_version: u32,
    spec: serde_json::Value,
    inputs: BTreeMap<&'static str, String>,
}

impl StageKey {
    pub fn new(stage: &'static str, stage_version: u32) -> StageKey {
        StageKey {
            stage,
            cityspec: env!("CARGO_PKG_VERSION"),
            stage_version,
            codec_version: super::codec::VERSION,
            spec: serde_json::Value::Object(Default::default()),
            inputs: BTreeMap::new(),
        }
    }

    /// Adds a part of the spec the stage reads, under `name`.
    pub fn spec(mut self, name: &str, part: &impl Serialize) -> StageKey {
        let value = serde_json::to_value(part).expect("spec parts serialize to JSON");
        if let serde_json::Value::Object(map) = &mut self.spec {
            map.insert(name.to_owned(), value);
        }
        self
    }

    /// Sets the whole spec part: a stage's inputs, serialized (a JSON object).
    pub fn spec_whole(mut self, part: serde_json::Value) -> StageKey {
        self.spec = part;
        self
    }

    /// Adds the key of a consumed stage, or the hash of an input file.
    pub fn input(mut self, name: &'static str, key: &str) -> StageKey {
        self.inputs.insert(name, key.to_owned());
        self
    }

    /// [`StageKey::finish`], keeping what the key is the hash of in `made` (by key), for
    /// `cityspec explain`.
    pub fn finish_into(self, made: &mut BTreeMap<String, StageKey>) -> String {
        let key = self.finish();
        made.insert(key.clone(), self);
        key
    }

    /// The stage's `VERSION`.
    pub fn stage_version(&self) -> u32 {
        self.stage_version
    }

    /// The names of the spec parts the key holds, in order.
    pub fn spec_parts(&self) -> Vec<String> {
        match &self.spec {
            serde_json::Value::Object(map) => map.keys().cloned().collect(),
            _ => Vec::new(),
        }
    }

    /// The consumed stages' keys and input files' hashes, by name.
    pub fn inputs(&self) -> &BTreeMap<&'static str, String> {
        &self.inputs
    }

    /// The key: SHA-256 of the canonical JSON of all of the above.
    pub fn finish(&self) -> String {
        let text = serde_json::to_vec(self).expect("keys serialize to JSON");
        sha256_hex(&text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn key_depends_on_every_input() {
        let base = || {
            StageKey::new("parse", 1)
                .spec("palette", &[1, 2, 3])
                .input("mirror", "abc")
        };
        let k = base().finish();
        assert_eq!(k, base().finish());
        assert_ne!(
            k,
            StageKey::new("lamps", 1)
                .spec("palette", &[1, 2, 3])
                .input("mirror", "abc")
                .finish()
        );
        assert_ne!(
            k,
            StageKey::new("parse", 2)
                .spec("palette", &[1, 2, 3])
                .input("mirror", "abc")
                .finish()
        );
        assert_ne!(
            k,
            StageKey::new("parse", 1)
                .spec("palette", &[1, 2, 4])
                .input("mirror", "abc")
                .finish()
        );
        assert_ne!(
            k,
            StageKey::new("parse", 1)
                .spec("palette", &[1, 2, 3])
                .input("mirror", "abd")
                .finish()
        );
        assert_eq!(k.len(), 64);
    }
}
