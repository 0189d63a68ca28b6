//! One spec's stage graph: every key computed up front from the spec alone, then the
//! artifacts pulled through the cache, running a stage only when its key misses.
//!
//! Evaluation is demand-driven: a stage's inputs are fetched (from the cache or by running
//! their stages) only when the stage itself must run. So a no-op rebuild touches only the
//! artifact stages' cache entries, and changing `[lamps]` reruns `lamps`, `plan` and
//! `preview` while `place` and `parse` stay cached.
//!
//! This file holds the [`Pipeline`], the order artifacts are pulled in and the key table
//! ([`keys`]); `graph` says what each stage gathers and runs, `evaluate` how a stage is
//! looked up or run and stored, `scene_values` the uncached scene, `frames_stage` one
//! camera path, `dataset_stage` the files over all paths. Every choice of what an output looks like lives in its stage's folder,
//! under that stage's `VERSION`, which is in the key of every stage that reads it.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, OnceLock};

use image::RgbImage;

mod dataset_stage;
mod evaluate;
#[cfg(test)]
mod facade_shares;
mod frames_stage;
mod graph;
pub(crate) use graph::render_shot;
mod scene_values;

use evaluate::evaluated;

use super::BuildError;
use super::inputs::{FacadeInput, SpecInputs};
use super::report::StageRun;
use super::stage_key::StageKey;
use super::stages::{Inputs, Keys, Stage};
use crate::cache::{Blob, Cache, Outputs};
use crate::diagnostic::Diagnostic;
use crate::model::{Building, FacadeSet, Lamp, MapBuilding, OsmMap, ParsedLayout, Scene, Streets};

/// A city's streets, held: a parsed layout or a map.
#[derive(Clone)]
pub(super) enum CityStreets {
    Layout(Arc<ParsedLayout>),
    Map(Arc<OsmMap>),
}

impl CityStreets {
    pub(super) fn get(&self) -> Streets<'_> {
        match self {
            CityStreets::Layout(parsed) => Streets::Layout(parsed),
            CityStreets::Map(map) => Streets::Map(map),
        }
    }
}
use crate::spec::Spec;
use crate::{objects, render};

/// An artifact a build writes: name in the output folder, bytes (in memory or a cache
/// object), producing stage and key.
pub struct ArtifactOut {
    pub path: String,
    pub blob: Blob,
    pub stage: Stage,
    pub key: String,
}

/// A stage's outputs, its typed value once computed or decoded, and its diagnostics (its
/// own and those of every stage it read, as its cache entry records them).
struct Slot<T> {
    outputs: Outputs,
    value: Option<Arc<T>>,
    diagnostics: Vec<Diagnostic>,
}

pub struct Pipeline<'a> {
    /// Every stage's inputs: all the pipeline knows of the spec (see `stages`).
    inputs: Inputs,
    spec_path: PathBuf,
    facade_input: FacadeInput,
    meshes: BTreeMap<String, objects::MeshFiles>,
    /// Per scene object: what annotations need (inserted objects' text and quads).
    object_info: Vec<Option<objects::ObjectInfo>>,
    /// Traffic signs' faces, by scene object index.
    sign_faces: BTreeMap<usize, objects::SignFace>,
    cache: &'a Cache,
    keys: Keys,
    pub runs: Vec<StageRun>,
    /// The diagnostics of every stage evaluated so far, run or cached, each once.
    pub diagnostics: Vec<Diagnostic>,
    /// While a stage gathers its inputs: the diagnostics of the stages it reads, innermost
    /// stage last (see `evaluate`).
    reading: Vec<Vec<Diagnostic>>,
    /// What a running stage reports (its run closure sees `&self`).
    reported: Mutex<Vec<Diagnostic>>,
    /// The scene's own diagnostics (objects short of their count): the scene is not
    /// cached, so every stage that reads it inherits them.
    scene_diagnostics: Vec<Diagnostic>,
    /// `--strict`: the first stage with a warning, run or cached, fails the build (its
    /// entry, written first, keeps the warning for the next build).
    pub strict: bool,
    /// Triangles in the scene, when the scene was built.
    pub triangles: Option<usize>,
    scene: Option<Arc<Scene>>,
    facades: Option<Slot<FacadeSet>>,
    export: Option<Slot<()>>,
    overview: Option<Slot<()>>,
    frames: Vec<Option<Slot<()>>>,
    dataset: Option<Slot<()>>,
    /// Set once: made beside the export when it runs (see `need_export`), else on demand.
    prepared: OnceLock<Arc<render::PreparedScene>>,
    /// Mip chains of the city's own textures, made beside the objects' insertion when the
    /// scene is built.
    mips: render::TextureMips,
    /// Reports frames rendered: (camera name, frames done, frames in the path).
    progress: &'a (dyn Fn(&str, usize, usize) + Sync),
    layout: Option<Slot<RgbImage>>,
    /// A map layout's layout stage (`map.json`).
    map: Option<Slot<OsmMap>>,
    mirror: Option<Slot<RgbImage>>,
    parse: Option<Slot<ParsedLayout>>,
    lamps: Option<Slot<Vec<Lamp>>>,
    place: Option<Slot<Vec<Building>>>,
    /// A map layout's place stage: buildings on its blocks without any.
    map_place: Option<Slot<Vec<MapBuilding>>>,
    /// The map with those buildings added (the map itself without the stage).
    city_map: Option<Arc<OsmMap>>,
    plan: Option<Slot<()>>,
    preview: Option<Slot<()>>,
    /// Keys of stages `cityspec verify` reruns despite their cache entry.
    recheck: Option<String>,
    /// Set while a rechecked stage runs: it stores nothing in the cache.
    rechecking: bool,
    verdict: Option<Option<String>>,
}

impl<'a> Pipeline<'a> {
    pub fn new(
        spec: &Spec,
        spec_path: PathBuf,
        files: SpecInputs,
        cache: &'a Cache,
        progress: &'a (dyn Fn(&str, usize, usize) + Sync),
    ) -> Self {
        let inputs = Inputs::of(spec, &files.layout);
        let keys = Keys::of(&inputs, &files);
        let cameras = inputs.frames.len();
        Pipeline {
            inputs,
            spec_path,
            facade_input: files.facades,
            meshes: files.meshes,
            object_info: Vec::new(),
            sign_faces: BTreeMap::new(),
            cache,
            keys,
            runs: Vec::new(),
            diagnostics: Vec::new(),
            reading: Vec::new(),
            reported: Mutex::default(),
            scene_diagnostics: Vec::new(),
            strict: false,
            triangles: None,
            scene: None,
            facades: None,
            export: None,
            overview: None,
            frames: (0..cameras).map(|_| None).collect(),
            dataset: None,
            prepared: OnceLock::new(),
            mips: render::TextureMips::default(),
            progress,
            layout: None,
            map: None,
            mirror: None,
            parse: None,
            lamps: None,
            place: None,
            map_place: None,
            city_map: None,
            plan: None,
            preview: None,
            recheck: None,
            rechecking: false,
            verdict: None,
        }
    }

    /// Every cached stage's (stage, key), in evaluation order.
    pub fn all_stages(&self) -> Vec<(Stage, String)> {
        self.keys
            .all()
            .into_iter()
            .map(|(stage, _, key)| (stage, key.to_owned()))
            .collect()
    }

    /// Each cached stage in evaluation order, what its key is the hash of, and what the
    /// cache holds under it (`cityspec explain`).
    pub fn explain(&self) -> Vec<super::explain::StageLine> {
        self.keys
            .all()
            .into_iter()
            .map(|(stage, camera, key)| {
                let made = self.keys.made.get(key);
                super::explain::StageLine {
                    stage,
                    camera: camera.map(|c| self.camera_name(c).to_owned()),
                    version: made.map_or(0, StageKey::stage_version),
                    spec: made.map(StageKey::spec_parts).unwrap_or_default(),
                    inputs: made
                        .map(|m| {
                            m.inputs()
                                .iter()
                                .map(|(name, value)| ((*name).to_owned(), value.clone()))
                                .collect()
                        })
                        .unwrap_or_default(),
                    state: self.cache.entry_state(key),
                    key: key.to_owned(),
                }
            })
            .collect()
    }

    /// Runs stage `stage` (key `key`) again, its inputs from the cache, and compares its
    /// outputs with its cache entry: `None` when they match, else what differs.
    pub fn recheck(&mut self, stage: Stage, key: &str) -> Result<Option<String>, BuildError> {
        let Some((_, camera, _)) = self
            .keys
            .all()
            .into_iter()
            .find(|(s, _, k)| (*s, *k) == (stage, key))
        else {
            return Ok(Some(format!(
                "no {} stage of this spec has key {key}",
                stage.name()
            )));
        };
        self.recheck = Some(key.to_owned());
        self.verdict = None;
        self.need(stage, camera)?;
        self.recheck = None;
        Ok(self.verdict.take().unwrap_or_else(|| {
            Some("already evaluated from the cache before it could be rechecked".to_owned())
        }))
    }

    /// Evaluates `stage` (`camera`'s for `frames`): from the cache, or run.
    fn need(&mut self, stage: Stage, camera: Option<usize>) -> Result<(), BuildError> {
        match stage {
            Stage::Layout => self.need_layout(),
            Stage::Mirror => self.need_mirror(),
            Stage::Parse => self.need_parse(),
            Stage::Lamps => self.need_lamps(),
            Stage::Facades => self.need_facades(),
            Stage::Place => self.need_place(),
            Stage::Plan => self.need_plan(),
            Stage::Preview => self.need_preview(),
            Stage::Export => self.need_export(),
            Stage::Overview => self.need_overview(),
            Stage::Frames => self.need_frames(camera.unwrap_or_default()),
            Stage::Dataset => self.need_dataset(),
        }
    }

    /// The outputs of `stage` (`camera`'s for `frames`), once evaluated.
    fn outputs_of(&self, stage: Stage, camera: Option<usize>) -> &Outputs {
        match stage {
            Stage::Layout if self.inputs.layout.is_map() => &evaluated(&self.map).outputs,
            Stage::Layout => &evaluated(&self.layout).outputs,
            Stage::Mirror => &evaluated(&self.mirror).outputs,
            Stage::Parse => &evaluated(&self.parse).outputs,
            Stage::Lamps => &evaluated(&self.lamps).outputs,
            Stage::Facades => &evaluated(&self.facades).outputs,
            Stage::Place if self.inputs.layout.is_map() => &evaluated(&self.map_place).outputs,
            Stage::Place => &evaluated(&self.place).outputs,
            Stage::Plan => &evaluated(&self.plan).outputs,
            Stage::Preview => &evaluated(&self.preview).outputs,
            Stage::Export => &evaluated(&self.export).outputs,
            Stage::Overview => &evaluated(&self.overview).outputs,
            Stage::Frames => &evaluated(&self.frames[camera.unwrap_or_default()]).outputs,
            Stage::Dataset => &evaluated(&self.dataset).outputs,
        }
    }

    /// The artifact stages' (stage, key), in the order [`Pipeline::artifacts`] evaluates
    /// them.
    pub fn artifact_stages(&self) -> Vec<(Stage, &str)> {
        self.keys
            .all()
            .into_iter()
            .filter(|(stage, _, _)| stage.declaration().artifact)
            .map(|(stage, _, key)| (stage, key))
            .collect()
    }

    /// The number of camera paths.
    pub fn cameras(&self) -> usize {
        self.inputs.frames.len()
    }

    /// The name of camera path `camera`.
    pub fn camera_name(&self, camera: usize) -> &str {
        &self.inputs.frames[camera].path.camera.name
    }

    /// Every artifact of the spec, from the cache where possible.
    pub fn artifacts(&mut self) -> Result<Vec<ArtifactOut>, BuildError> {
        let stages: Vec<(Stage, Option<usize>, String)> = self
            .keys
            .all()
            .into_iter()
            .filter(|(stage, _, _)| stage.declaration().artifact)
            .map(|(stage, camera, key)| (stage, camera, key.to_owned()))
            .collect();
        for &(stage, camera, _) in &stages {
            self.need(stage, camera)?;
        }
        let mut artifacts: Vec<ArtifactOut> = stages
            .into_iter()
            .flat_map(|(stage, camera, key)| {
                self.outputs_of(stage, camera)
                    .iter()
                    .map(move |(path, blob)| ArtifactOut {
                        path: path.clone(),
                        blob: blob.clone(),
                        stage,
                        key: key.clone(),
                    })
                    .collect::<Vec<_>>()
            })
            .collect();
        artifacts.sort_by(|a, b| a.path.cmp(&b.path));
        Ok(artifacts)
    }
}
