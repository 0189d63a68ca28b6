//! Evaluating one stage: its cache entry, or its inputs gathered and the stage run; and
//! reading a stage's typed value back from its outputs.

use std::sync::Arc;
use std::time::Instant;

use super::super::BuildError;
use super::super::cache::{Blob, Load, Miss, Outputs};
use super::super::decode_error::DecodeError;
use super::super::output_names::OutputNames;
use super::super::report::{StageRun, StageStatus};
use super::{Pipeline, Slot};

impl Pipeline<'_> {
    /// Fills `slot` from the cache, or gathers the inputs and runs the stage.
    pub(super) fn stage<I, T>(
        &mut self,
        name: &'static str,
        key: String,
        load: Load,
        slot: impl for<'x> Fn(&'x mut Self) -> &'x mut Option<Slot<T>>,
        gather: impl FnOnce(&mut Self) -> Result<I, BuildError>,
        run: impl FnOnce(&Self, I) -> Result<(T, Outputs), BuildError>,
    ) -> Result<(), BuildError> {
        let names = self.output_names(name, &key);
        if self.recheck.as_deref() == Some(key.as_str()) {
            // `cityspec verify`: run the stage whatever the cache holds, and compare.
            let cached = self.cache.get_stage(name, &key, Load::References, &names);
            let inputs = gather(self)?;
            self.rechecking = true;
            let ran = run(self, inputs);
            self.rechecking = false;
            let (value, outputs) = ran?;
            self.verdict = Some(super::super::verify::compare(&cached, &outputs));
            *slot(self) = Some(Slot {
                outputs,
                value: Some(Arc::new(value)),
            });
            return Ok(());
        }
        if slot(self).is_some() {
            return Ok(());
        }
        let lookup = Instant::now();
        let (filled, status, repaired, time) =
            match self.cache.get_stage(name, &key, load, &names) {
                Ok(outputs) => (
                    Slot {
                        outputs,
                        value: None,
                    },
                    StageStatus::Cached,
                    None,
                    lookup.elapsed(),
                ),
                Err(miss) => {
                    let repaired = match miss {
                        Miss::Absent => None,
                        Miss::Corrupt(why) => Some(why),
                    };
                    let inputs = gather(self)?;
                    let start = Instant::now();
                    let (value, mut outputs) = run(self, inputs)?;
                    let refs = self.cache.put(name, &key, &outputs).map_err(|source| {
                        BuildError::Cache {
                            path: self.cache.root().to_path_buf(),
                            source,
                        }
                    })?;
                    // Each output now knows its object, so its hash is not computed again;
                    // bytes the stage made stay in memory for the driver to write (a
                    // streamed stage's never were).
                    for (name, object) in refs {
                        if let Some(blob) = outputs.remove(&name) {
                            outputs.insert(name, blob.stored(object));
                        }
                    }
                    let slot = Slot {
                        outputs,
                        value: Some(Arc::new(value)),
                    };
                    (slot, StageStatus::Ran, repaired, start.elapsed())
                }
            };
        let camera = self.camera_of(&key).map(str::to_owned);
        self.runs.push(StageRun {
            stage: name,
            camera,
            key,
            status,
            time,
            repaired,
        });
        *slot(self) = Some(filled);
        Ok(())
    }
}

impl Pipeline<'_> {
    /// The names stage `stage` (of key `key`, which tells camera paths apart) writes.
    pub(super) fn output_names(&self, stage: &str, key: &str) -> OutputNames {
        OutputNames::of(stage, self.camera_of(key))
    }

    /// The camera whose `frames` stage has key `key`, if any.
    pub fn camera_of(&self, key: &str) -> Option<&str> {
        let camera = self.keys.frames.iter().position(|k| k == key)?;
        Some(self.spec.cameras[camera].name.as_str())
    }
}

/// The slot's typed value, decoding its cached outputs on first use.
pub(super) fn value<T>(
    slot: &mut Option<Slot<T>>,
    stage: &'static str,
    decode: impl FnOnce(&Outputs) -> Result<T, DecodeError>,
) -> Result<Arc<T>, BuildError> {
    let slot = slot.as_mut().expect("stage was evaluated");
    if slot.value.is_none() {
        let value = decode(&slot.outputs).map_err(|source| BuildError::Decode { stage, source })?;
        slot.value = Some(Arc::new(value));
    }
    Ok(Arc::clone(slot.value.as_ref().expect("just set")))
}

pub(super) fn evaluated<T>(slot: &Option<Slot<T>>) -> &Slot<T> {
    slot.as_ref().expect("stage was evaluated")
}

pub(super) fn one(name: &str, bytes: Vec<u8>) -> Outputs {
    Outputs::from([(name.to_owned(), Blob::from(bytes))])
}
