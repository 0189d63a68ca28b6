//! Evaluating one stage: its cache entry, or its inputs gathered and the stage run; and
//! reading a stage's typed value back from its outputs.
//!
//! Diagnostics travel with results. A stage that runs records, in its cache entry, what it
//! reported itself and what every stage it read carried (collected on `reading` while it
//! gathers its inputs); a stage found in the cache hands on what its entry records. So the
//! artifact stages' entries hold every diagnostic of the build, and a warm build says what
//! a cold one said, `--strict` included.

use std::sync::Arc;
use std::time::{Duration, Instant};

use super::super::BuildError;
use super::super::decode_error::DecodeError;
use super::super::output_names::OutputNames;
use super::super::report::{StageRun, StageStatus};
use super::super::stages::Stage;
use super::{Pipeline, Slot};
use crate::cache::{Blob, Load, Miss, Outputs};
use crate::diagnostic::{Diagnostic, extend_unique};

impl Pipeline<'_> {
    /// Fills `slot` from the cache, or gathers the inputs and runs the stage.
    pub(super) fn stage<I, T>(
        &mut self,
        stage: Stage,
        camera: Option<usize>,
        slot: impl for<'x> Fn(&'x mut Self) -> &'x mut Option<Slot<T>>,
        gather: impl FnOnce(&mut Self) -> Result<I, BuildError>,
        run: impl FnOnce(&Self, I) -> Result<(T, Outputs), BuildError>,
    ) -> Result<(), BuildError> {
        let (name, load) = (stage.name(), stage.declaration().load);
        let key = self.keys.of_stage(stage, camera).to_owned();
        let names = self.output_names(stage, camera);
        if self.recheck.as_deref() == Some(key.as_str()) {
            // `cityspec verify`: run the stage whatever the cache holds, and compare.
            let cached = self.cache.get_stage(name, &key, Load::References, &names);
            let (value, outputs, diagnostics, _) = self.gather_and_run(gather, run, true)?;
            self.verdict = Some(super::super::verify::compare(&cached, &outputs));
            *slot(self) = Some(Slot {
                outputs,
                value: Some(Arc::new(value)),
                diagnostics,
            });
            return Ok(());
        }
        if let Some(filled) = slot(self) {
            let diagnostics = filled.diagnostics.clone();
            return self.read_diagnostics(&diagnostics);
        }
        let lookup = Instant::now();
        let (filled, status, repaired, time) = match self.cache.lookup(name, &key, load, &names) {
            Ok(hit) => (
                Slot {
                    outputs: hit.outputs,
                    value: None,
                    diagnostics: hit.diagnostics,
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
                let (slot, time) = self.run_and_store(name, &key, gather, run)?;
                (slot, StageStatus::Ran, repaired, time)
            }
        };
        let camera = camera.map(|c| self.camera_name(c).to_owned());
        self.runs.push(StageRun {
            stage: name,
            camera,
            key,
            status,
            time,
            repaired,
        });
        let diagnostics = filled.diagnostics.clone();
        *slot(self) = Some(filled);
        self.read_diagnostics(&diagnostics)
    }

    /// Runs stage `name` (key `key`), its inputs gathered, and stores its outputs and
    /// diagnostics in the cache: the filled slot and how long the run took.
    fn run_and_store<I, T>(
        &mut self,
        name: &'static str,
        key: &str,
        gather: impl FnOnce(&mut Self) -> Result<I, BuildError>,
        run: impl FnOnce(&Self, I) -> Result<(T, Outputs), BuildError>,
    ) -> Result<(Slot<T>, Duration), BuildError> {
        let (value, mut outputs, diagnostics, time) = self.gather_and_run(gather, run, false)?;
        let refs = self
            .cache
            .put(name, key, &outputs, &diagnostics)
            .map_err(|source| BuildError::Cache {
                path: self.cache.root().to_path_buf(),
                source,
            })?;
        // Each output now knows its object, so its hash is not computed again; bytes the
        // stage made stay in memory for the driver to write (a streamed stage's never were).
        for (name, object) in refs {
            if let Some(blob) = outputs.remove(&name) {
                outputs.insert(name, blob.stored(object));
            }
        }
        let slot = Slot {
            outputs,
            value: Some(Arc::new(value)),
            diagnostics,
        };
        Ok((slot, time))
    }

    /// Gathers a stage's inputs, collecting what the stages it reads carry, then runs it
    /// (storing nothing while `rechecking`): its value and outputs, every diagnostic (read
    /// and its own) and how long the run took.
    fn gather_and_run<I, T>(
        &mut self,
        gather: impl FnOnce(&mut Self) -> Result<I, BuildError>,
        run: impl FnOnce(&Self, I) -> Result<(T, Outputs), BuildError>,
        rechecking: bool,
    ) -> Result<(T, Outputs, Vec<Diagnostic>, Duration), BuildError> {
        self.reading.push(Vec::new());
        let inputs = gather(self);
        let mut diagnostics = self.reading.pop().unwrap_or_default();
        let inputs = inputs?;
        let start = Instant::now();
        self.rechecking = rechecking;
        let ran = run(self, inputs);
        self.rechecking = false;
        let (value, outputs) = ran?;
        extend_unique(&mut diagnostics, &self.take_reported());
        Ok((value, outputs, diagnostics, start.elapsed()))
    }

    /// A stage (or the scene) was read with `diagnostics`: the stage gathering its inputs
    /// inherits them, and the build reports them. With `--strict`, a warning fails the
    /// build here, as soon as it is known, run or cached.
    pub(super) fn read_diagnostics(
        &mut self,
        diagnostics: &[Diagnostic],
    ) -> Result<(), BuildError> {
        if let Some(reader) = self.reading.last_mut() {
            extend_unique(reader, diagnostics);
        }
        extend_unique(&mut self.diagnostics, diagnostics);
        if self.strict && self.diagnostics.iter().any(Diagnostic::is_warning) {
            return Err(BuildError::Strict {
                spec: self.spec_path.clone(),
                warnings: self.diagnostics.clone(),
            });
        }
        Ok(())
    }

    /// Reports a diagnostic of the stage now running (from its run closure).
    pub(super) fn report(&self, diagnostic: Diagnostic) {
        if let Ok(mut reported) = self.reported.lock() {
            reported.push(diagnostic);
        }
    }

    fn take_reported(&self) -> Vec<Diagnostic> {
        self.reported
            .lock()
            .map(|mut reported| std::mem::take(&mut *reported))
            .unwrap_or_default()
    }
}

impl Pipeline<'_> {
    /// The names stage `stage` (`camera`'s, for `frames`) writes.
    pub(super) fn output_names(&self, stage: Stage, camera: Option<usize>) -> OutputNames {
        OutputNames::of(stage, camera.map(|c| self.camera_name(c)))
    }

    /// The camera whose `frames` stage has key `key`, if any.
    pub fn camera_of(&self, key: &str) -> Option<&str> {
        let camera = self.keys.frames.iter().position(|k| k == key)?;
        Some(self.camera_name(camera))
    }
}

/// The slot's typed value, decoding its cached outputs on first use.
pub(super) fn value<T>(
    slot: &mut Option<Slot<T>>,
    stage: Stage,
    decode: impl FnOnce(&Outputs) -> Result<T, DecodeError>,
) -> Result<Arc<T>, BuildError> {
    let slot = slot.as_mut().expect("stage was evaluated");
    if slot.value.is_none() {
        let value = decode(&slot.outputs).map_err(|source| BuildError::Decode {
            stage: stage.name(),
            source,
        })?;
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
