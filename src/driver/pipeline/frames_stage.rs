//! The frames stage of each camera path, through its plan and chunks (`driver::chunks`):
//! a plain build renders the chunks nobody rendered yet and assembles the path; a shard
//! ([`Pipeline::shard_work`]) renders only its own chunks and assembles nothing.

use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::Instant;

use rand::Rng;
use rayon::prelude::*;

use super::super::BuildError;
use super::super::codec;
use super::super::frame_labels;
use super::super::frames;
use super::super::output_names::OutputNames;
use super::super::report::{StageRun, StageStatus};
use super::super::stages::{FramesInputs, PathInputs, Stage};
use super::Pipeline;
use super::evaluate::one;
use crate::cache::{Load, Miss, Outputs};
use crate::driver::chunks::{self, PathPlan};
use crate::driver::shard::{Shard, ShardStats};
use crate::model::{CameraPose, FacadeSet, Lamp, ObjectKind, Scene};
use crate::spec::{LightingSpec, OutputLayout, Vary};
use crate::{annotate, lidar, render, rng, scene, traffic, views};

/// What rendering a path needs besides the spec: the prepared and the plain scene, the
/// streets (a parsed layout or a map), the lamps and the facades.
type Gathered = (
    Arc<render::PreparedScene>,
    Arc<Scene>,
    super::CityStreets,
    Arc<Vec<Lamp>>,
    Arc<FacadeSet>,
);

/// One chunk before the path runs.
enum Chunk {
    /// Its entry is in the cache, every object verified.
    Cached(Outputs),
    /// To be rendered here.
    Render,
    /// Another shard's.
    Skip,
}

/// A path's plan and chunks, and the scene when a chunk must be rendered.
pub(super) struct PathState {
    plan: PathPlan,
    chunks: Vec<Chunk>,
    gathered: Option<Gathered>,
}

impl Pipeline<'_> {
    /// Frames and annotations of `[[cameras]]` entry `index`.
    pub(super) fn need_frames(&mut self, index: usize) -> Result<(), BuildError> {
        let recheck = self.recheck.as_deref() == Some(self.keys.frames[index].as_str());
        self.stage(
            Stage::Frames,
            Some(index),
            move |p| &mut p.frames[index],
            move |p| p.path_state(index, recheck, None),
            move |p, mut state| {
                let FramesInputs { path, output } = &p.inputs.frames[index];
                let camera = &path.camera;
                if state.plan.poses.is_empty() {
                    let message = format!(
                        "camera path {:?} yields 0 frames: no pose along it fits (roads and \
                         sidewalks: none to drive or walk; objects: no target of its classes \
                         seen within its distance and height; orbit: an empty layout)",
                        camera.name
                    );
                    p.report(
                        crate::diagnostic::Diagnostic::warning("camera-no-frames", message)
                            .at(format!("cameras[{index}]")),
                    );
                }
                let chunks = p.render_chunks(index, &mut state)?;
                let store = !p.rechecking;
                let outputs =
                    chunks::assemble(p.cache, camera, &state.plan, &chunks, store, output)
                        .map_err(|source| p.cache_error(source))?;
                Ok(((), outputs))
            },
        )
    }

    /// A shard's share of the spec (`shard`), or with `None` (`--stage city`) the stages
    /// every shard shares: the city's artifact stages and every path's plan. Writes only
    /// the cache.
    pub fn shard_work(&mut self, shard: Option<Shard>) -> Result<ShardStats, BuildError> {
        if self.inputs.runs(Stage::Mirror) {
            self.need_mirror()?;
        }
        if self.inputs.runs(Stage::Plan) {
            self.need_plan()?;
        }
        self.need_preview()?;
        self.need_export()?;
        self.need_overview()?;
        let mut stats = ShardStats::default();
        for index in 0..self.cameras() {
            // A path already assembled needs nothing more from any shard.
            if self.cache.entry(&self.keys.frames[index]).is_some() {
                continue;
            }
            let Some(shard) = shard else {
                self.path_plan(index, false)?;
                continue;
            };
            let mut state = self.path_state(index, false, Some(shard))?;
            let ranges = chunks::ranges(state.plan.poses.len());
            let mut render = 0;
            for (chunk, range) in state.chunks.iter().zip(ranges) {
                match chunk {
                    Chunk::Cached(_) => stats.cached_chunks += 1,
                    Chunk::Skip => stats.other_chunks += 1,
                    Chunk::Render => {
                        render += 1;
                        stats.frames += range.len();
                    }
                }
            }
            stats.rendered_chunks += render;
            let start = Instant::now();
            self.render_chunks(index, &mut state)?;
            if render > 0 {
                self.runs.push(StageRun {
                    stage: "frames-chunk",
                    camera: Some(self.camera_name(index).to_owned()),
                    key: self.keys.frames[index].clone(),
                    status: StageStatus::Ran,
                    time: start.elapsed(),
                    repaired: None,
                });
            }
        }
        Ok(stats)
    }

    /// Every cache key this spec's build reads or writes: its stages', and each camera
    /// path's plan and (when the plan is cached, which says how many frames) chunks.
    pub fn cache_keys(&self) -> Vec<String> {
        let mut keys: Vec<String> = self.all_stages().into_iter().map(|(_, k)| k).collect();
        let names = OutputNames::path_plan();
        for path in &self.keys.paths {
            let plan_key = chunks::plan_key(path);
            let plan = self
                .cache
                .get_stage("frames-plan", &plan_key, Load::Bytes, &names)
                .ok()
                .and_then(|o| {
                    codec::from_json::<PathPlan>(codec::output(&o, chunks::PLAN).ok()?).ok()
                });
            if let Some(plan) = plan {
                keys.extend(
                    chunks::ranges(plan.poses.len())
                        .iter()
                        .map(|range| chunks::chunk_key(path, range)),
                );
            }
            keys.push(plan_key);
        }
        keys
    }

    fn cache_error(&self, source: std::io::Error) -> BuildError {
        BuildError::Cache {
            path: self.cache.root().to_path_buf(),
            source,
        }
    }

    fn gather_path(&mut self) -> Result<Gathered, BuildError> {
        Ok((
            self.prepared_scene()?,
            self.scene()?,
            self.streets()?,
            self.lamp_sites()?,
            self.facade_set()?,
        ))
    }

    /// The plan of path `index`: from the cache, or computed (and stored unless
    /// `recheck`), with the scene it was computed from.
    fn path_plan(
        &mut self,
        index: usize,
        recheck: bool,
    ) -> Result<(PathPlan, Option<Gathered>), BuildError> {
        let key = chunks::plan_key(&self.keys.paths[index]);
        let names = OutputNames::path_plan();
        // Why a cached plan was not used, when it was there.
        let mut repaired = None;
        if !recheck {
            let cached = self
                .cache
                .get_stage("frames-plan", &key, Load::Bytes, &names);
            match cached {
                Ok(outputs) => {
                    let bytes = codec::output(&outputs, chunks::PLAN);
                    match bytes.and_then(|b| codec::from_json::<PathPlan>(b)) {
                        Ok(plan) => return Ok((plan, None)),
                        Err(why) => repaired = Some(why.to_string()),
                    }
                }
                Err(Miss::Corrupt(why)) => repaired = Some(why),
                Err(Miss::Absent) => {}
            }
        }
        let gathered = self.gather_path()?;
        let start = Instant::now();
        let plan = self.compute_plan(index, &gathered)?;
        let bytes = codec::to_json(&plan);
        if !recheck {
            self.cache
                .put("frames-plan", &key, &one(chunks::PLAN, bytes.clone()), &[])
                .map_err(|source| self.cache_error(source))?;
            self.runs.push(StageRun {
                stage: "frames-plan",
                camera: Some(self.camera_name(index).to_owned()),
                key,
                status: StageStatus::Ran,
                time: start.elapsed(),
                repaired,
            });
        }
        // Rendered from the plan as stored, exactly as a shard that finds it in the cache.
        let plan = codec::from_json(&bytes).map_err(|source| BuildError::Decode {
            stage: "frames-plan",
            source,
        })?;
        Ok((plan, Some(gathered)))
    }

    /// The plan, the chunks (those of other shards skipped) and, when a chunk must be
    /// rendered, the scene. With `recheck` every chunk is rendered again.
    fn path_state(
        &mut self,
        index: usize,
        recheck: bool,
        shard: Option<Shard>,
    ) -> Result<PathState, BuildError> {
        let (plan, mut gathered) = self.path_plan(index, recheck)?;
        let frames_key = &self.keys.paths[index];
        let names = OutputNames::chunk(self.camera_name(index));
        let chunks: Vec<Chunk> = chunks::ranges(plan.poses.len())
            .iter()
            .enumerate()
            .map(|(k, range)| {
                if shard.is_some_and(|s| chunks::owner(index, k, s.count) != s.index) {
                    return Chunk::Skip;
                }
                if recheck {
                    return Chunk::Render;
                }
                let key = chunks::chunk_key(frames_key, range);
                match self
                    .cache
                    .get_stage("frames-chunk", &key, Load::References, &names)
                {
                    Ok(outputs) => Chunk::Cached(outputs),
                    Err(_) => Chunk::Render,
                }
            })
            .collect();
        if gathered.is_none() && chunks.iter().any(|c| matches!(c, Chunk::Render)) {
            gathered = Some(self.gather_path()?);
        }
        Ok(PathState {
            plan,
            chunks,
            gathered,
        })
    }

    /// Renders the chunks marked so (storing each unless rechecking) and returns every
    /// chunk's outputs but the skipped ones', in frame order.
    fn render_chunks(
        &self,
        index: usize,
        state: &mut PathState,
    ) -> Result<Vec<Outputs>, BuildError> {
        let camera = &self.inputs.frames[index].path.camera;
        let frames_key = &self.keys.paths[index];
        let ranges = chunks::ranges(state.plan.poses.len());
        let total: usize = ranges
            .iter()
            .zip(&state.chunks)
            .filter(|(_, c)| !matches!(c, Chunk::Skip))
            .map(|(r, _)| r.len())
            .sum();
        let store = !self.rechecking;
        let poses = &state.plan.poses;
        let semantic = state.plan.semantic.as_ref();
        let done = std::sync::atomic::AtomicUsize::new(0);
        let chunk_list = std::mem::take(&mut state.chunks);
        let (lidar_target, traffic) = self.path_extras(index, &chunk_list, state, poses);
        let extras = (lidar_target.as_ref(), traffic.as_ref());
        let render = |range: std::ops::Range<usize>,
                      gathered: &Gathered|
         -> Result<Outputs, BuildError> {
            let key = chunks::chunk_key(frames_key, &range);
            let outputs = self.with_path_input(index, gathered, (semantic, extras), |input| {
                let path = frames::PathFrames::new(input, poses);
                let keep_all = self.inputs.frames[index].output.layout == OutputLayout::Webdataset;
                let modes = (store, keep_all);
                chunks::render_chunk(self.cache, &path, poses.len(), range, modes, || {
                    let n = 1 + done.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    (self.progress)(&camera.name, n, total);
                })
            });
            let outputs = outputs.map_err(|source| self.cache_error(source))?;
            if store {
                self.cache
                    .put("frames-chunk", &key, &outputs, &[])
                    .map_err(|source| self.cache_error(source))?;
            }
            Ok(outputs)
        };
        // What every frame reads (the shadow map, the cloud field) once, with every core,
        // before chunks start side by side and each asks for it (`render_chunk` does not:
        // two chunks starting together would each build the same map).
        let first = chunk_list
            .iter()
            .zip(&ranges)
            .find(|(c, r)| matches!(c, Chunk::Render) && !r.is_empty());
        if let (Some((_, range)), Some(gathered)) = (first, state.gathered.as_ref()) {
            self.with_path_input(index, gathered, (semantic, extras), |input| {
                frames::PathFrames::new(input, poses).warm(range.start);
            });
        }
        // Chunks render side by side, each one's frames side by side: a chunk's serial
        // ends (its input, its last frame's tail, its summary and cache entry) overlap
        // another chunk's frames. Outputs come back in chunk order.
        let rendered: Vec<Option<Result<Outputs, BuildError>>> = chunk_list
            .into_par_iter()
            .zip(ranges)
            .map(|(chunk, range)| match chunk {
                Chunk::Skip => None,
                Chunk::Cached(outputs) => {
                    done.fetch_add(range.len(), std::sync::atomic::Ordering::Relaxed);
                    Some(Ok(outputs))
                }
                Chunk::Render => {
                    let gathered = state
                        .gathered
                        .as_ref()
                        .expect("path_state gathers the scene for chunks to render");
                    Some(render(range, gathered))
                }
            })
            .collect();
        // The first error in chunk order, whichever chunk failed first.
        rendered.into_iter().flatten().collect()
    }

    /// What path `index`'s frames read besides the scene, made once for all its chunks:
    /// the LiDAR's target and the traffic.
    fn path_extras(
        &self,
        index: usize,
        chunks: &[Chunk],
        state: &PathState,
        poses: &[CameraPose],
    ) -> (Option<lidar::Target>, Option<traffic::Traffic>) {
        let camera = &self.inputs.frames[index].path.camera;
        let gathered = state.gathered.as_ref();
        let traffic = self.path_traffic(index, gathered, poses);
        let target = lidar_target(camera, chunks, gathered, traffic.as_ref());
        (target, traffic)
    }

    /// Path `index`'s traffic, with `[traffic]` when a chunk renders (`gathered`): its lane
    /// vehicles and signal heads, a timed drive's junctions green as its camera crosses
    /// them. `None` without, or when nothing in the scene moves.
    fn path_traffic(
        &self,
        index: usize,
        gathered: Option<&Gathered>,
        poses: &[CameraPose],
    ) -> Option<traffic::Traffic> {
        let path = &self.inputs.frames[index].path;
        let ((_, spec), (_, scene, streets, ..)) = (path.traffic.as_ref()?, gathered?);
        // Traffic moves on a layout's roads only (the spec refuses it with a map).
        let super::CityStreets::Layout(parsed) = streets else {
            return None;
        };
        let roles: Vec<_> = self
            .object_info
            .iter()
            .map(|info| info.as_ref().and_then(|i| i.traffic.clone()))
            .collect();
        let material = |name: String| {
            scene
                .materials
                .iter()
                .position(|m| m.name == name)
                .map(|m| m as u32)
        };
        let lamp = |s: crate::objects::Signal| {
            Some([
                material(crate::objects::lamp_material(s, true))?,
                material(crate::objects::lamp_material(s, false))?,
            ])
        };
        let [red, amber, green] = crate::objects::Signal::ALL.map(lamp);
        let lamps = red.zip(amber).zip(green).map(|((r, a), g)| [r, a, g]);
        let ego: Vec<(f64, [f64; 2])> = poses
            .iter()
            .filter_map(|p| Some((p.time?, [p.eye[0], p.eye[2]])))
            .collect();
        let traffic = traffic::plan(&traffic::TrafficInput {
            spec,
            layout: parsed,
            metres_per_pixel: path.export.metres_per_pixel,
            roles: &roles,
            lamps,
            seed: path.seed,
            ego: &ego,
        });
        (!traffic.is_empty()).then_some(traffic)
    }

    /// Path `index`'s prepared scene, poses and first frame's lighting, for
    /// [`crate::driver::path_render_input`]: the city stages run or load as in a build.
    pub fn path_render_input(
        &mut self,
        index: usize,
    ) -> Result<
        (
            Arc<render::PreparedScene>,
            Vec<CameraPose>,
            render::Lighting,
        ),
        BuildError,
    > {
        let g = self.gather_path()?;
        let poses = self.poses(index, &g.0, &g.1, &g.2);
        let (lighting, _) = self.first_lighting(index, &g);
        Ok((g.0, poses, lighting))
    }

    /// The lighting of path `index`'s first frame (of every frame unless `vary = "frame"`)
    /// and the sun it was drawn with.
    fn first_lighting(&self, index: usize, g: &Gathered) -> (render::Lighting, render::Sun) {
        let (_, scene, _, lamps, facades) = g;
        let path = &self.inputs.frames[index].path;
        let sun = render::Sun::draw(&path.lighting, path.seed, index as u32, 0);
        (path_lighting(path, &sun, scene, lamps, facades), sun)
    }

    /// Poses, categories and YOLO classes of path `index`.
    fn compute_plan(&self, index: usize, g: &Gathered) -> Result<PathPlan, BuildError> {
        let (prepared, scene, streets, _, _) = g;
        let poses = self.poses(index, prepared, scene, streets);
        let path = &self.inputs.frames[index].path;
        let labels = frame_labels::labels(path, scene, &self.object_info, &self.sign_faces);
        let objects: Vec<(ObjectKind, &str)> = scene
            .objects
            .iter()
            .map(|o| (o.kind, o.class.as_str()))
            .collect();
        let semantic = path
            .annotations
            .cityscapes
            .then(|| annotate::SemanticClasses::of(&objects))
            .transpose()
            .map_err(|source| BuildError::Classes {
                spec: self.spec_path.clone(),
                source,
            })?;
        Ok(PathPlan {
            poses,
            instances: annotate::instances(&objects, &labels),
            categories: labels.categories,
            yolo: labels.yolo.map(|classes| classes.names_file()),
            semantic,
        })
    }

    fn poses(
        &self,
        index: usize,
        prepared: &render::PreparedScene,
        scene: &Scene,
        streets: &super::CityStreets,
    ) -> Vec<CameraPose> {
        let path = &self.inputs.frames[index].path;
        views::poses(&views::ViewsInput {
            camera: &path.camera,
            streets: streets.get(),
            scene,
            prepared,
            metres_per_pixel: path.export.metres_per_pixel,
            seed: path.seed,
        })
    }

    /// Calls `f` with path `index`'s rendering input.
    fn with_path_input<R>(
        &self,
        index: usize,
        g: &Gathered,
        (semantic, (lidar, traffic)): (Option<&annotate::SemanticClasses>, PathExtras),
        f: impl FnOnce(&frames::PathInput) -> R,
    ) -> R {
        let (prepared, scene, _, lamps, facades) = g;
        let path = &self.inputs.frames[index].path;
        let camera = &path.camera;
        let (lighting, sun) = self.first_lighting(index, g);
        let relight = (path.lighting.vary == Vary::Frame).then_some({
            |i: usize| {
                let sun = render::Sun::draw(&path.lighting, path.seed, index as u32, i as u32);
                (path_lighting(path, &sun, scene, lamps, facades), sun)
            }
        });
        let path_labels = frame_labels::labels(path, scene, &self.object_info, &self.sign_faces);
        let thresholds = annotate::Thresholds {
            min_pixels: path.annotations.min_pixels,
            min_fraction: path.annotations.min_fraction,
        };
        // Per text object: its words' world corners.
        let corners: BTreeMap<u32, Vec<[[f64; 3]; 4]>> = self
            .object_info
            .iter()
            .enumerate()
            .filter_map(|(i, info)| Some((i as u32 + 1, info.as_ref()?.corners.clone())))
            .filter(|(_, words)| !words.is_empty())
            .collect();
        let input = frames::PathInput {
            corners: &corners,
            camera,
            scene: prepared,
            lighting: &lighting,
            sun,
            relight: relight.as_ref().map(|f| f as _),
            categories: &path_labels.categories,
            labels: &path_labels.labels,
            thresholds: &thresholds,
            yolo: path_labels.yolo.as_ref(),
            weather: &path.weather,
            conditions_seed: rng::stream(path.seed, "conditions", index as u64).next_u64(),
            semantic,
            lidar,
            traffic,
            kinds: &scene.objects.iter().map(|o| o.kind).collect::<Vec<_>>(),
        };
        f(&input)
    }
}

/// What a path's frames read besides the scene, made once per path: the LiDAR's target
/// and the traffic.
type PathExtras<'a> = (Option<&'a lidar::Target>, Option<&'a traffic::Traffic>);

/// The LiDAR's BVH over the scene (with moving traffic, over what stands still), when the
/// camera has a LiDAR and a chunk renders: built once for every chunk of the path.
fn lidar_target(
    camera: &crate::spec::CameraSpec,
    chunks: &[Chunk],
    gathered: Option<&Gathered>,
    traffic: Option<&traffic::Traffic>,
) -> Option<lidar::Target> {
    let (prepared, scene, ..) = camera
        .lidar
        .as_ref()
        .filter(|_| chunks.iter().any(|c| matches!(c, Chunk::Render)))
        .and(gathered)?;
    let kinds: Vec<ObjectKind> = scene.objects.iter().map(|o| o.kind).collect();
    let moving = traffic.map(|t| t.at(0.0));
    Some(lidar::Target::of_objects(prepared, &kinds, |id| {
        !moving.as_ref().is_some_and(|m| m.moves(id))
    }))
}

/// A camera path's lighting under `sun`.
fn path_lighting(
    path: &PathInputs,
    sun: &render::Sun,
    scene: &Scene,
    lamps: &[Lamp],
    facades: &FacadeSet,
) -> render::Lighting {
    let mpp = path.export.metres_per_pixel;
    lighting(&path.lighting, path.seed, mpp, sun, scene, lamps, facades)
}

/// `[lighting]` under `sun`, with a light at every lamp head.
pub(super) fn lighting(
    spec: &LightingSpec,
    seed: u64,
    metres_per_pixel: f64,
    sun: &render::Sun,
    scene: &Scene,
    lamps: &[Lamp],
    facades: &FacadeSet,
) -> render::Lighting {
    let heads: Vec<[f64; 3]> = lamps
        .iter()
        .map(|lamp| scene::light_position(lamp, metres_per_pixel))
        .collect();
    render::lighting_for(spec, sun, scene, facades, &heads, seed)
}
