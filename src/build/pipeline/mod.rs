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
//! camera path. Every choice of what an output looks like lives in its stage's folder,
//! under that stage's `VERSION`, which is in the key of every stage that reads it.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, OnceLock};

use image::RgbImage;

mod evaluate;
mod frames_stage;
mod graph;
mod scene_values;

use evaluate::evaluated;

use super::BuildError;
use super::cache::{Blob, Cache, Outputs};
use super::inputs::{FacadeInput, LayoutSource, SpecInputs};
use super::report::StageRun;
use super::stage_key::StageKey;
use crate::diagnostic::Diagnostic;
use crate::model::{Building, FacadeSet, Lamp, ParsedLayout, Scene};
use crate::spec::{OutputLayout, Spec};
use crate::{
    annotate, cameras, export, facades, lamps, layout, mirror, objects, parse, place, plan,
    preview, render, scene, sensor,
};

/// The sun stream of the overview (camera paths use their index): with `[lighting] sun`
/// drawn, the overview's sun is a draw of its own.
const OVERVIEW_SUN: u32 = u32::MAX;

/// An artifact a build writes: name in the output folder, bytes (in memory or a cache
/// object), producing stage and key.
pub struct ArtifactOut {
    pub path: String,
    pub blob: Blob,
    pub stage: &'static str,
    pub key: String,
}

struct Keys {
    layout: String,
    mirror: String,
    parse: String,
    lamps: String,
    place: String,
    plan: String,
    preview: String,
    facades: String,
    export: String,
    overview: String,
    /// One per `[[cameras]]` entry.
    frames: Vec<String>,
    /// Per camera, the key of its frames' content, whatever `[output]` says: its plan
    /// and chunks are keyed by it, so a change of layout renders nothing again.
    paths: Vec<String>,
    /// What each key above is the hash of, by key (for `cityspec explain`).
    made: BTreeMap<String, StageKey>,
}

/// A stage's outputs, its typed value once computed or decoded, and its diagnostics (its
/// own and those of every stage it read, as its cache entry records them).
struct Slot<T> {
    outputs: Outputs,
    value: Option<Arc<T>>,
    diagnostics: Vec<Diagnostic>,
}

pub struct Pipeline<'a> {
    spec: &'a Spec,
    spec_path: PathBuf,
    source: LayoutSource,
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
    /// Set once: made beside the export when it runs (see `need_export`), else on demand.
    prepared: OnceLock<Arc<render::PreparedScene>>,
    /// Mip chains of the city's own textures, made beside the objects' insertion when the
    /// scene is built.
    mips: render::TextureMips,
    /// Reports frames rendered: (camera name, frames done, frames in the path).
    progress: &'a (dyn Fn(&str, usize, usize) + Sync),
    layout: Option<Slot<RgbImage>>,
    mirror: Option<Slot<RgbImage>>,
    parse: Option<Slot<ParsedLayout>>,
    lamps: Option<Slot<Vec<Lamp>>>,
    place: Option<Slot<Vec<Building>>>,
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
        spec: &'a Spec,
        spec_path: PathBuf,
        inputs: SpecInputs,
        cache: &'a Cache,
        progress: &'a (dyn Fn(&str, usize, usize) + Sync),
    ) -> Self {
        let keys = keys(spec, &inputs);
        Pipeline {
            spec,
            spec_path,
            source: inputs.layout,
            facade_input: inputs.facades,
            meshes: inputs.meshes,
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
            frames: vec![None; spec.cameras.len()]
                .into_iter()
                .map(|_: Option<()>| None)
                .collect(),
            prepared: OnceLock::new(),
            mips: render::TextureMips::default(),
            progress,
            layout: None,
            mirror: None,
            parse: None,
            lamps: None,
            place: None,
            plan: None,
            preview: None,
            recheck: None,
            rechecking: false,
            verdict: None,
        }
    }

    /// Every cached stage's (name, key), in evaluation order.
    pub fn all_stages(&self) -> Vec<(&'static str, String)> {
        let k = &self.keys;
        let mut stages: Vec<(&'static str, String)> = [
            ("layout", &k.layout),
            ("mirror", &k.mirror),
            ("parse", &k.parse),
            ("lamps", &k.lamps),
            ("facades", &k.facades),
            ("place", &k.place),
            ("plan", &k.plan),
            ("preview", &k.preview),
            ("export", &k.export),
            ("overview", &k.overview),
        ]
        .into_iter()
        .map(|(stage, key)| (stage, key.clone()))
        .collect();
        stages.extend(k.frames.iter().map(|key| ("frames", key.clone())));
        stages
    }

    /// Each cached stage in evaluation order, what its key is the hash of, and what the
    /// cache holds under it (`cityspec explain`).
    pub fn explain(&self) -> Vec<super::explain::StageLine> {
        self.all_stages()
            .into_iter()
            .map(|(stage, key)| {
                let made = self.keys.made.get(&key);
                super::explain::StageLine {
                    stage,
                    camera: self.camera_of(&key).map(str::to_owned),
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
                    state: self.cache.entry_state(&key),
                    key,
                }
            })
            .collect()
    }

    /// Runs stage `stage` (key `key`) again, its inputs from the cache, and compares its
    /// outputs with its cache entry: `None` when they match, else what differs.
    pub fn recheck(&mut self, stage: &str, key: &str) -> Result<Option<String>, BuildError> {
        self.recheck = Some(key.to_owned());
        self.verdict = None;
        match stage {
            "layout" => self.need_layout(),
            "mirror" => self.need_mirror(),
            "parse" => self.need_parse(),
            "lamps" => self.need_lamps(),
            "facades" => self.need_facades(),
            "place" => self.need_place(),
            "plan" => self.need_plan(),
            "preview" => self.need_preview(),
            "export" => self.need_export(),
            "overview" => self.need_overview(),
            _ => match self.keys.frames.iter().position(|k| k == key) {
                Some(camera) => self.need_frames(camera),
                None => Ok(()),
            },
        }?;
        self.recheck = None;
        Ok(self.verdict.take().unwrap_or_else(|| {
            Some("already evaluated from the cache before it could be rechecked".to_owned())
        }))
    }

    /// The artifact stages' (name, key), in the order [`Pipeline::artifacts`] evaluates them.
    pub fn artifact_stages(&self) -> Vec<(&'static str, &str)> {
        let k = &self.keys;
        let mut stages = vec![
            ("mirror", k.mirror.as_str()),
            ("plan", k.plan.as_str()),
            ("preview", k.preview.as_str()),
            ("export", k.export.as_str()),
            ("overview", k.overview.as_str()),
        ];
        stages.extend(k.frames.iter().map(|key| ("frames", key.as_str())));
        stages
    }

    /// Every artifact of the spec, from the cache where possible.
    pub fn artifacts(&mut self) -> Result<Vec<ArtifactOut>, BuildError> {
        self.need_mirror()?;
        self.need_plan()?;
        self.need_preview()?;
        self.need_export()?;
        self.need_overview()?;
        for camera in 0..self.spec.cameras.len() {
            self.need_frames(camera)?;
        }
        let stages: [(&Outputs, &'static str, &String); 5] = [
            (
                &evaluated(&self.mirror).outputs,
                "mirror",
                &self.keys.mirror,
            ),
            (&evaluated(&self.plan).outputs, "plan", &self.keys.plan),
            (
                &evaluated(&self.preview).outputs,
                "preview",
                &self.keys.preview,
            ),
            (
                &evaluated(&self.export).outputs,
                "export",
                &self.keys.export,
            ),
            (
                &evaluated(&self.overview).outputs,
                "overview",
                &self.keys.overview,
            ),
        ];
        let frames = self
            .frames
            .iter()
            .zip(&self.keys.frames)
            .map(|(slot, key)| (&evaluated(slot).outputs, "frames", key));
        let mut artifacts: Vec<ArtifactOut> = stages
            .into_iter()
            .chain(frames)
            .flat_map(|(outputs, stage, key)| {
                outputs.iter().map(move |(path, blob)| ArtifactOut {
                    path: path.clone(),
                    blob: blob.clone(),
                    stage,
                    key: key.clone(),
                })
            })
            .collect();
        artifacts.sort_by(|a, b| a.path.cmp(&b.path));
        Ok(artifacts)
    }
}

/// Every stage's key, from the spec and the input files' hashes alone.
fn keys(spec: &Spec, inputs: &SpecInputs) -> Keys {
    let mut made = BTreeMap::new();
    let l = &spec.layout;
    let layout = match &inputs.layout {
        LayoutSource::Generate => StageKey::new("layout", layout::VERSION)
            .spec("generate", &l.generate.clone().unwrap_or_default())
            .spec("palette", &l.palette)
            .spec("seed", &spec.seed),
        LayoutSource::Image { bytes, .. } => {
            StageKey::new("layout", layout::VERSION).input("image", &crate::hash::sha256_hex(bytes))
        }
    }
    .finish_into(&mut made);
    let mirror = StageKey::new("mirror", mirror::VERSION)
        .spec("mirror", &l.mirror)
        .input("layout", &layout)
        .finish_into(&mut made);
    let parse = StageKey::new("parse", parse::VERSION)
        .spec("palette", &l.palette)
        .input("mirror", &mirror)
        .finish_into(&mut made);
    let lamps = StageKey::new("lamps", lamps::VERSION)
        .spec("lamps", &spec.lamps)
        .spec("palette", &l.palette)
        .spec("metres_per_pixel", &l.metres_per_pixel)
        .input("mirror", &mirror)
        .input("parse", &parse)
        .finish_into(&mut made);
    let facades = StageKey::new("facades", facades::VERSION)
        .spec("floor_height", &spec.facades.floor_height)
        .spec("on_error", &spec.facades.on_error);
    let facades = match &inputs.facades {
        FacadeInput::Builtin => facades.input("builtin", &facades::BUILTIN_VERSION.to_string()),
        FacadeInput::Folder { digest, .. } => facades.input("folder", digest),
    }
    .finish_into(&mut made);
    let mut place = StageKey::new("place", place::VERSION)
        .spec("buildings", &spec.buildings)
        .spec("metres_per_pixel", &l.metres_per_pixel)
        .spec("seed", &spec.seed)
        .input("parse", &parse);
    if spec.buildings.widths.is_none() {
        place = place.input("facades", &facades);
    }
    let place = place.finish_into(&mut made);
    let plan = StageKey::new("plan", plan::VERSION)
        .spec("metres_per_pixel", &l.metres_per_pixel)
        .input("parse", &parse)
        .input("lamps", &lamps)
        .input("place", &place)
        .finish_into(&mut made);
    let preview = StageKey::new("preview", preview::VERSION)
        .input("mirror", &mirror)
        .input("parse", &parse)
        .input("lamps", &lamps)
        .input("place", &place)
        .finish_into(&mut made);
    // The scene is not cached: the export key holds everything the scene reads.
    let export = StageKey::new("export", export::VERSION)
        .spec("scene_version", &scene::VERSION)
        .spec("objects_version", &objects::VERSION)
        .spec("objects", &spec.objects)
        .input("meshes", &inputs.meshes_digest)
        .spec("widths", &spec.buildings.widths)
        .spec("metres_per_pixel", &l.metres_per_pixel)
        .spec("seed", &spec.seed)
        .input("parse", &parse)
        .input("lamps", &lamps)
        .input("place", &place)
        .input("facades", &facades)
        .finish_into(&mut made);
    let overview = StageKey::new("overview", render::VERSION)
        .spec("cameras_version", &cameras::VERSION)
        .spec("lighting", &spec.lighting)
        .spec("seed", &spec.seed)
        .input("export", &export)
        .finish_into(&mut made);
    let paths: Vec<String> = spec
        .cameras
        .iter()
        .map(|camera| {
            StageKey::new("frames", render::VERSION)
                .spec("versions", &[cameras::VERSION, annotate::VERSION])
                .spec("sensor_version", &sensor::VERSION)
                .spec("camera", camera)
                .spec("lighting", &spec.lighting)
                .spec("weather", &spec.weather)
                .spec("annotations", &spec.annotations)
                .spec("seed", &spec.seed)
                .input("export", &export)
                .finish_into(&mut made)
        })
        .collect();
    let frames = paths
        .iter()
        .map(|path| match spec.output.layout {
            OutputLayout::Files => path.clone(),
            OutputLayout::Webdataset => StageKey::new("frames", super::webdataset::VERSION)
                .spec("output", &spec.output)
                .input("path", path)
                .finish_into(&mut made),
        })
        .collect();
    Keys {
        made,
        frames,
        paths,
        overview,
        layout,
        mirror,
        parse,
        lamps,
        place,
        plan,
        preview,
        facades,
        export,
    }
}
