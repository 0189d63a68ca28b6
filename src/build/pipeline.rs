//! One spec's stage graph: every key computed up front from the spec alone, then the
//! artifacts pulled through the cache, running a stage only when its key misses.
//!
//! Evaluation is demand-driven: a stage's inputs are fetched (from the cache or by running
//! their stages) only when the stage itself must run. So a no-op rebuild touches only the
//! artifact stages' cache entries, and changing `[lamps]` reruns `lamps`, `plan` and
//! `preview` while `place` and `parse` stay cached.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use image::RgbImage;

use super::BuildError;
use super::cache::{Blob, Cache, Load, Miss, ObjectRef, Outputs};
use super::codec;
use super::frame_labels;
use super::frames;
use super::inputs::{FacadeInput, LayoutSource};
use super::object_views;
use super::output_names::OutputNames;
use super::report::{StageRun, StageStatus};
use super::stage_key::StageKey;
use crate::model::{Building, FacadeSet, Lamp, ParsedLayout, Scene};
use crate::spec::{CameraPath, Spec, Vary};
use crate::{
    annotate, cameras, export, facades, lamps, layout, mirror, objects, parse, place, plan,
    preview, render, rng, scene, sensor,
};
use rand::Rng;

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
}

/// A stage's outputs, and its typed value once computed or decoded.
struct Slot<T> {
    outputs: Outputs,
    value: Option<Arc<T>>,
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
    /// Warnings of stages that ran (skipped facades, …).
    pub warnings: Vec<String>,
    /// `--strict`: objects placed short of `count` fail the scene, before any stage that
    /// reads it writes a cache entry (so a later plain build still warns).
    pub strict: bool,
    /// Triangles in the scene, when the scene was built.
    pub triangles: Option<usize>,
    scene: Option<Arc<Scene>>,
    facades: Option<Slot<FacadeSet>>,
    export: Option<Slot<()>>,
    overview: Option<Slot<()>>,
    frames: Vec<Option<Slot<()>>>,
    prepared: Option<Arc<render::PreparedScene>>,
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
        source: LayoutSource,
        facade_input: FacadeInput,
        meshes: (BTreeMap<String, objects::MeshFiles>, String),
        cache: &'a Cache,
        progress: &'a (dyn Fn(&str, usize, usize) + Sync),
    ) -> Self {
        let keys = keys(spec, &source, &facade_input, &meshes.1);
        Pipeline {
            spec,
            spec_path,
            source,
            facade_input,
            meshes: meshes.0,
            object_info: Vec::new(),
            sign_faces: BTreeMap::new(),
            cache,
            keys,
            runs: Vec::new(),
            warnings: Vec::new(),
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
            prepared: None,
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

    fn need_layout(&mut self) -> Result<(), BuildError> {
        let key = self.keys.layout.clone();
        self.stage(
            "layout",
            key,
            Load::Bytes,
            |p| &mut p.layout,
            |_| Ok(()),
            |p, ()| {
                let image = match &p.source {
                    LayoutSource::Generate => {
                        let generate = p.spec.layout.generate.clone().unwrap_or_default();
                        let mut stream = rng::stream(p.spec.seed, "layout", 0);
                        layout::generate(&generate, &p.spec.layout.palette, &mut stream).image
                    }
                    LayoutSource::Image { path, bytes } => {
                        layout::decode(bytes).map_err(|e| BuildError::Input {
                            spec: p.spec_path.clone(),
                            key: "layout.image",
                            file: path.clone(),
                            message: e.to_string(),
                        })?
                    }
                };
                let png = codec::encode_png(&image);
                Ok((image, one("layout.png", png)))
            },
        )
    }

    fn layout_image(&mut self) -> Result<Arc<RgbImage>, BuildError> {
        self.need_layout()?;
        value(&mut self.layout, "layout", |o| {
            codec::decode_png(codec::output(o, "layout.png")?)
        })
    }

    fn need_mirror(&mut self) -> Result<(), BuildError> {
        let key = self.keys.mirror.clone();
        self.stage(
            "mirror",
            key,
            Load::Bytes,
            |p| &mut p.mirror,
            |p| p.layout_image(),
            |p, layout| {
                let image = mirror::mirror(&layout, &p.spec.layout.mirror);
                let png = codec::encode_png(&image);
                Ok((image, one("layout.png", png)))
            },
        )
    }

    fn mirrored_image(&mut self) -> Result<Arc<RgbImage>, BuildError> {
        self.need_mirror()?;
        value(&mut self.mirror, "mirror", |o| {
            codec::decode_png(codec::output(o, "layout.png")?)
        })
    }

    fn need_parse(&mut self) -> Result<(), BuildError> {
        let key = self.keys.parse.clone();
        self.stage(
            "parse",
            key,
            Load::Bytes,
            |p| &mut p.parse,
            |p| p.mirrored_image(),
            |p, image| {
                let parsed = parse::parse(&image, &p.spec.layout.palette);
                let json = codec::to_json(&parsed);
                Ok((parsed, one("parsed.json", json)))
            },
        )
    }

    fn parsed(&mut self) -> Result<Arc<ParsedLayout>, BuildError> {
        self.need_parse()?;
        value(&mut self.parse, "parse", |o| {
            codec::from_json(codec::output(o, "parsed.json")?)
        })
    }

    fn need_lamps(&mut self) -> Result<(), BuildError> {
        let key = self.keys.lamps.clone();
        let gather = |p: &mut Self| Ok((p.mirrored_image()?, p.parsed()?));
        self.stage(
            "lamps",
            key,
            Load::Bytes,
            |p| &mut p.lamps,
            gather,
            |p, (image, parsed)| {
                let mpp = p.spec.layout.metres_per_pixel;
                let lamps = &p.spec.lamps;
                let sites = lamps::site_lamps(
                    &image,
                    &parsed,
                    &p.spec.layout.palette,
                    lamps.spacing / mpp,
                    lamps.min_distance / mpp,
                );
                let json = codec::to_json(&sites);
                Ok((sites, one("lamps.json", json)))
            },
        )
    }

    fn lamp_sites(&mut self) -> Result<Arc<Vec<Lamp>>, BuildError> {
        self.need_lamps()?;
        value(&mut self.lamps, "lamps", |o| {
            codec::from_json(codec::output(o, "lamps.json")?)
        })
    }

    fn need_place(&mut self) -> Result<(), BuildError> {
        let key = self.keys.place.clone();
        let gather = |p: &mut Self| {
            let facades = match p.spec.buildings.widths {
                Some(_) => None,
                None => Some(p.facade_set()?),
            };
            Ok((p.parsed()?, facades))
        };
        self.stage(
            "place",
            key,
            Load::Bytes,
            |p| &mut p.place,
            gather,
            |p, (parsed, facades)| {
                let mpp = p.spec.layout.metres_per_pixel;
                // Paper 3.2: without explicit widths, every facade is one building size.
                let widths_m: Vec<f64> = match (&p.spec.buildings.widths, &facades) {
                    (Some(widths), _) => widths.clone(),
                    (None, Some(set)) => set.facades.iter().map(|f| f.width).collect(),
                    (None, None) => Vec::new(),
                };
                let widths = widths_px(&widths_m, mpp);
                let gap = (p.spec.buildings.gap / mpp).round() as u32;
                let buildings = place::place(&parsed.blocks, &widths, gap, p.spec.seed);
                let json = codec::to_json(&buildings);
                Ok((buildings, one("buildings.json", json)))
            },
        )
    }

    fn buildings(&mut self) -> Result<Arc<Vec<Building>>, BuildError> {
        self.need_place()?;
        value(&mut self.place, "place", |o| {
            codec::from_json(codec::output(o, "buildings.json")?)
        })
    }

    fn need_plan(&mut self) -> Result<(), BuildError> {
        let key = self.keys.plan.clone();
        let gather = |p: &mut Self| Ok((p.parsed()?, p.lamp_sites()?, p.buildings()?));
        self.stage(
            "plan",
            key,
            Load::References,
            |p| &mut p.plan,
            gather,
            |p, (parsed, lamps, buildings)| {
                let mpp = p.spec.layout.metres_per_pixel;
                let city = plan::assemble(&parsed, &lamps, &buildings, mpp);
                Ok(((), one("plan.json", codec::to_pretty_json(&city))))
            },
        )
    }

    fn need_preview(&mut self) -> Result<(), BuildError> {
        let key = self.keys.preview.clone();
        let gather = |p: &mut Self| {
            Ok((
                p.mirrored_image()?,
                p.parsed()?,
                p.lamp_sites()?,
                p.buildings()?,
            ))
        };
        self.stage(
            "preview",
            key,
            Load::References,
            |p| &mut p.preview,
            gather,
            |_, (image, parsed, lamps, buildings)| {
                let picture = preview::draw(&image, &parsed, &lamps, &buildings);
                Ok(((), one("plan.png", codec::encode_png(&picture))))
            },
        )
    }

    fn need_facades(&mut self) -> Result<(), BuildError> {
        let key = self.keys.facades.clone();
        let before = self.runs.len();
        self.stage(
            "facades",
            key,
            Load::Bytes,
            |p| &mut p.facades,
            |_| Ok(()),
            |p, ()| {
                let generated;
                let source = match &p.facade_input {
                    FacadeInput::Builtin => {
                        generated = facades::builtin();
                        &generated
                    }
                    FacadeInput::Folder { source, .. } => source,
                };
                let f = &p.spec.facades;
                let (set, warnings) = facades::process(source, f.floor_height, f.on_error)
                    .map_err(|e| BuildError::Facades {
                        spec: p.spec_path.clone(),
                        message: e.to_string(),
                    })?;
                let warnings: Vec<String> = warnings.iter().map(|w| w.to_string()).collect();
                let mut outputs = codec::facade_set_outputs(&set);
                outputs.insert(
                    "warnings.json".to_owned(),
                    Blob::from(codec::to_json(&warnings)),
                );
                Ok((set, outputs))
            },
        )?;
        // Warnings are told when the facades are processed, not on every cached build.
        if self.runs.len() > before && self.runs[before].status == StageStatus::Ran {
            let outputs = &evaluated(&self.facades).outputs;
            let warnings: Vec<String> = codec::output(outputs, "warnings.json")
                .and_then(|bytes| codec::from_json(bytes))
                .unwrap_or_default();
            self.warnings.extend(warnings);
        }
        Ok(())
    }

    fn facade_set(&mut self) -> Result<Arc<FacadeSet>, BuildError> {
        self.need_facades()?;
        value(&mut self.facades, "facades", codec::facade_set_from_outputs)
    }

    /// The 3D scene. Not cached: it is a fast function of cached values, and only the
    /// export (and later the renderer) reads it.
    fn scene(&mut self) -> Result<Arc<Scene>, BuildError> {
        if let Some(scene) = &self.scene {
            return Ok(Arc::clone(scene));
        }
        let parsed = self.parsed()?;
        let lamps = self.lamp_sites()?;
        let buildings = self.buildings()?;
        let facades = self.facade_set()?;
        let start = Instant::now();
        let built = scene::build(&scene::SceneInput {
            layout: &parsed,
            lamps: &lamps,
            buildings: &buildings,
            facades: &facades,
            widths: self.spec.buildings.widths.as_deref(),
            metres_per_pixel: self.spec.layout.metres_per_pixel,
            seed: self.spec.seed,
        });
        let mut built = built;
        let inserted = objects::insert(&objects::ObjectsInput {
            specs: &self.spec.objects,
            layout: &parsed,
            lamps: &lamps,
            buildings: &buildings,
            facades: &facades,
            widths: self.spec.buildings.widths.as_deref(),
            meshes: &self.meshes,
            metres_per_pixel: self.spec.layout.metres_per_pixel,
            seed: self.spec.seed,
        })
        .map_err(|e| BuildError::Objects {
            spec: self.spec_path.clone(),
            message: e.to_string(),
        })?;
        // `count` is an upper bound; falling short is told, with the numbers.
        let shortfalls = inserted.shortfalls(&self.spec.objects);
        if self.strict && !shortfalls.is_empty() {
            return Err(BuildError::Strict {
                spec: self.spec_path.clone(),
                warnings: shortfalls,
            });
        }
        self.warnings.extend(shortfalls);
        let first = objects::merge(&mut built, &inserted);
        self.sign_faces = inserted
            .sign_faces
            .iter()
            .map(|(i, f)| (first + i, *f))
            .collect();
        self.object_info = vec![None; first];
        self.object_info.extend(inserted.info.into_iter().map(Some));
        self.triangles = Some(built.triangle_count());
        self.runs.push(StageRun {
            stage: "scene",
            key: String::new(),
            status: StageStatus::Ran,
            time: start.elapsed(),
            repaired: None,
        });
        let built = Arc::new(built);
        self.scene = Some(Arc::clone(&built));
        Ok(built)
    }

    fn need_export(&mut self) -> Result<(), BuildError> {
        let key = self.keys.export.clone();
        self.stage(
            "export",
            key,
            Load::References,
            |p| &mut p.export,
            |p| p.scene(),
            |_, scene| {
                let files = export::export(&scene);
                let outputs = files
                    .into_iter()
                    .map(|(path, bytes)| (path, Blob::from(bytes)))
                    .collect();
                Ok(((), outputs))
            },
        )
    }

    /// `overview.png`: the textured city from the air, rendered by cityspec's renderer.
    fn need_overview(&mut self) -> Result<(), BuildError> {
        let key = self.keys.overview.clone();
        let gather = |p: &mut Self| {
            Ok((
                p.prepared_scene()?,
                p.scene()?,
                p.parsed()?,
                p.lamp_sites()?,
                p.facade_set()?,
            ))
        };
        self.stage(
            "overview",
            key,
            Load::References,
            |p| &mut p.overview,
            gather,
            |p, (prepared, scene, parsed, lamps, facades)| {
                // The spec's light; a drawn sun is drawn for the overview on its own.
                let sun = render::Sun::draw(&p.spec.lighting, p.spec.seed, u32::MAX, 0);
                // Without ambient occlusion: its metre-wide creases are a pixel or two
                // from the air, and it would cost the cold build a tenth of a second.
                let lighting = render::Lighting {
                    ambient_occlusion: 0.0,
                    ..lighting(p.spec, &sun, &scene, &lamps, &facades)
                };
                let (w, h) = (f64::from(parsed.width), f64::from(parsed.height));
                let span = (w * w + h * h).sqrt() * p.spec.layout.metres_per_pixel;
                // The north-east corner of an orbit, 0.6 of the city's diagonal up: the whole
                // city in one oblique view.
                let poses =
                    cameras::orbit_path(&parsed, p.spec.layout.metres_per_pixel, 8, span * 0.6);
                let frame = match poses.get(1) {
                    Some(pose) => {
                        let mut intrinsics = render::Intrinsics::from_fov(1280, 960, 0.5);
                        intrinsics.far = span * 4.0;
                        render::render(&prepared, pose, &intrinsics, &lighting, 2).rgb
                    }
                    None => image::RgbImage::new(1280, 960),
                };
                Ok(((), one("overview.png", codec::encode_png(&frame))))
            },
        )
    }

    fn prepared_scene(&mut self) -> Result<Arc<render::PreparedScene>, BuildError> {
        if let Some(prepared) = &self.prepared {
            return Ok(Arc::clone(prepared));
        }
        let scene = self.scene()?;
        let prepared = render::prepare(&scene).map_err(|e| BuildError::Render {
            spec: self.spec_path.clone(),
            message: e.to_string(),
        })?;
        let prepared = Arc::new(prepared);
        self.prepared = Some(Arc::clone(&prepared));
        Ok(prepared)
    }

    /// Frames and annotations of `[[cameras]]` entry `index`.
    fn need_frames(&mut self, index: usize) -> Result<(), BuildError> {
        let key = self.keys.frames[index].clone();
        let gather = |p: &mut Self| {
            Ok((
                p.prepared_scene()?,
                p.scene()?,
                p.parsed()?,
                p.lamp_sites()?,
                p.facade_set()?,
            ))
        };
        self.stage(
            "frames",
            key,
            Load::References,
            move |p| &mut p.frames[index],
            gather,
            |p, (prepared, scene, parsed, lamps, facades)| {
                let spec = p.spec;
                let camera = &spec.cameras[index];
                let mpp = spec.layout.metres_per_pixel;
                // Seeded by the camera's name, not its place in the list: adding or
                // reordering cameras leaves every other camera's poses as they were.
                let camera_seed =
                    rng::stream(spec.seed, &format!("camera/{}", camera.name), 0).next_u64();
                let aim = cameras::Aim::of(camera);
                let poses = match camera.path {
                    CameraPath::Roads => cameras::road_path(
                        &parsed,
                        mpp,
                        &cameras::RoadPath {
                            frames: camera.frame_rule(),
                            aim,
                            look_ahead: camera.look_ahead,
                            jitter: camera.jitter,
                            lane_offset: camera.lane_offset,
                        },
                        camera_seed,
                    ),
                    CameraPath::Sidewalks => cameras::sidewalk_path(
                        &parsed,
                        mpp,
                        &cameras::SidewalkPath {
                            frames: camera.frame_rule(),
                            aim,
                            sidewalk: f64::from(scene::strip_width_px(&parsed)) * mpp,
                        },
                        camera_seed,
                    ),
                    CameraPath::Objects => object_views::aimed_poses(
                        &prepared,
                        &scene,
                        &parsed,
                        mpp,
                        camera,
                        camera_seed,
                    ),
                    CameraPath::Orbit => {
                        let length = cameras::orbit_length(&parsed, mpp);
                        let frames = camera.frame_rule().frames(length);
                        // A range of heights: the orbit flies at its middle.
                        cameras::orbit_path(&parsed, mpp, frames, camera.height.at(0.5))
                    }
                };
                let sun = render::Sun::draw(&spec.lighting, spec.seed, index as u32, 0);
                let lighting = lighting(spec, &sun, &scene, &lamps, &facades);
                let relight = (spec.lighting.vary == Vary::Frame).then_some({
                    |i: usize| {
                        let sun =
                            render::Sun::draw(&spec.lighting, spec.seed, index as u32, i as u32);
                        (self::lighting(spec, &sun, &scene, &lamps, &facades), sun)
                    }
                });
                let path_labels =
                    frame_labels::labels(spec, camera, &scene, &p.object_info, &p.sign_faces);
                let thresholds = annotate::Thresholds {
                    min_pixels: spec.annotations.min_pixels,
                    min_fraction: spec.annotations.min_fraction,
                };
                // Per text object: its words' world corners.
                let corners: BTreeMap<u32, Vec<[[f64; 3]; 4]>> = p
                    .object_info
                    .iter()
                    .enumerate()
                    .filter_map(|(i, info)| Some((i as u32 + 1, info.as_ref()?.corners.clone())))
                    .filter(|(_, words)| !words.is_empty())
                    .collect();
                let input = frames::PathInput {
                    corners: &corners,
                    camera,
                    scene: &prepared,
                    lighting: &lighting,
                    sun,
                    relight: relight.as_ref().map(|f| f as _),
                    categories: &path_labels.categories,
                    labels: &path_labels.labels,
                    thresholds: &thresholds,
                    yolo: path_labels.yolo.as_ref(),
                    weather: &spec.weather,
                    conditions_seed: rng::stream(spec.seed, "conditions", index as u64).next_u64(),
                };
                let total = poses.len();
                // Each file goes into the cache as it is made; only its reference stays.
                let mut outputs = Outputs::new();
                frames::render_path(
                    &input,
                    &poses,
                    |name, bytes| {
                        let object = if p.rechecking {
                            ObjectRef {
                                sha256: crate::hash::sha256_hex(&bytes),
                                bytes: bytes.len() as u64,
                            }
                        } else {
                            p.cache.put_object(&bytes)?
                        };
                        outputs.insert(name, Blob::Stored(object, None));
                        Ok(())
                    },
                    |done| (p.progress)(&camera.name, done, total),
                )
                .map_err(|source| BuildError::Cache {
                    path: p.cache.root().to_path_buf(),
                    source,
                })?;
                Ok(((), outputs))
            },
        )
    }

    /// Fills `slot` from the cache, or gathers the inputs and runs the stage.
    fn stage<I, T>(
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
            self.verdict = Some(super::verify::compare(&cached, &outputs));
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
        self.runs.push(StageRun {
            stage: name,
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
    fn output_names(&self, stage: &str, key: &str) -> OutputNames {
        let camera = self.keys.frames.iter().position(|k| k == key);
        OutputNames::of(stage, camera.map(|i| self.spec.cameras[i].name.as_str()))
    }
}

/// The slot's typed value, decoding its cached outputs on first use.
fn value<T>(
    slot: &mut Option<Slot<T>>,
    stage: &'static str,
    decode: impl FnOnce(&Outputs) -> Result<T, String>,
) -> Result<Arc<T>, BuildError> {
    let slot = slot.as_mut().expect("stage was evaluated");
    if slot.value.is_none() {
        let value =
            decode(&slot.outputs).map_err(|message| BuildError::Decode { stage, message })?;
        slot.value = Some(Arc::new(value));
    }
    Ok(Arc::clone(slot.value.as_ref().expect("just set")))
}

fn evaluated<T>(slot: &Option<Slot<T>>) -> &Slot<T> {
    slot.as_ref().expect("stage was evaluated")
}

fn one(name: &str, bytes: Vec<u8>) -> Outputs {
    Outputs::from([(name.to_owned(), Blob::from(bytes))])
}

/// Building widths in layout pixels (at least one pixel each).
pub fn widths_px(widths_m: &[f64], metres_per_pixel: f64) -> Vec<u32> {
    widths_m
        .iter()
        .map(|w| (w / metres_per_pixel).round().max(1.0) as u32)
        .collect()
}

/// Every stage's key, from the spec and the input files' hashes alone.
fn keys(spec: &Spec, source: &LayoutSource, facade_input: &FacadeInput, meshes: &str) -> Keys {
    let l = &spec.layout;
    let layout = match source {
        LayoutSource::Generate => StageKey::new("layout", layout::VERSION)
            .spec("generate", &l.generate.clone().unwrap_or_default())
            .spec("palette", &l.palette)
            .spec("seed", &spec.seed),
        LayoutSource::Image { bytes, .. } => {
            StageKey::new("layout", layout::VERSION).input("image", &crate::hash::sha256_hex(bytes))
        }
    }
    .finish();
    let mirror = StageKey::new("mirror", mirror::VERSION)
        .spec("mirror", &l.mirror)
        .input("layout", &layout)
        .finish();
    let parse = StageKey::new("parse", parse::VERSION)
        .spec("palette", &l.palette)
        .input("mirror", &mirror)
        .finish();
    let lamps = StageKey::new("lamps", lamps::VERSION)
        .spec("lamps", &spec.lamps)
        .spec("palette", &l.palette)
        .spec("metres_per_pixel", &l.metres_per_pixel)
        .input("mirror", &mirror)
        .input("parse", &parse)
        .finish();
    let facades = StageKey::new("facades", facades::VERSION)
        .spec("floor_height", &spec.facades.floor_height)
        .spec("on_error", &spec.facades.on_error);
    let facades = match facade_input {
        FacadeInput::Builtin => facades.input("builtin", &facades::BUILTIN_VERSION.to_string()),
        FacadeInput::Folder { digest, .. } => facades.input("folder", digest),
    }
    .finish();
    let mut place = StageKey::new("place", place::VERSION)
        .spec("buildings", &spec.buildings)
        .spec("metres_per_pixel", &l.metres_per_pixel)
        .spec("seed", &spec.seed)
        .input("parse", &parse);
    if spec.buildings.widths.is_none() {
        place = place.input("facades", &facades);
    }
    let place = place.finish();
    let plan = StageKey::new("plan", plan::VERSION)
        .spec("metres_per_pixel", &l.metres_per_pixel)
        .input("parse", &parse)
        .input("lamps", &lamps)
        .input("place", &place)
        .finish();
    let preview = StageKey::new("preview", preview::VERSION)
        .input("mirror", &mirror)
        .input("parse", &parse)
        .input("lamps", &lamps)
        .input("place", &place)
        .finish();
    // The scene is not cached: the export key holds everything the scene reads.
    let export = StageKey::new("export", export::VERSION)
        .spec("scene_version", &scene::VERSION)
        .spec("objects_version", &objects::VERSION)
        .spec("objects", &spec.objects)
        .input("meshes", meshes)
        .spec("widths", &spec.buildings.widths)
        .spec("metres_per_pixel", &l.metres_per_pixel)
        .spec("seed", &spec.seed)
        .input("parse", &parse)
        .input("lamps", &lamps)
        .input("place", &place)
        .input("facades", &facades)
        .finish();
    let overview = StageKey::new("overview", render::VERSION)
        .spec("cameras_version", &cameras::VERSION)
        .spec("lighting", &spec.lighting)
        .spec("seed", &spec.seed)
        .input("export", &export)
        .finish();
    let frames = spec
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
                .finish()
        })
        .collect();
    Keys {
        frames,
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

/// The spec's lighting under `sun`, with a light at every lamp head.
fn lighting(
    spec: &Spec,
    sun: &render::Sun,
    scene: &Scene,
    lamps: &[Lamp],
    facades: &FacadeSet,
) -> render::Lighting {
    let mpp = spec.layout.metres_per_pixel;
    let heads: Vec<[f64; 3]> = lamps
        .iter()
        .map(|lamp| scene::light_position(lamp, mpp))
        .collect();
    render::lighting_for(&spec.lighting, sun, scene, facades, &heads, spec.seed)
}
