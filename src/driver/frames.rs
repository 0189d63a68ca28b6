//! One camera path's dataset: scene + poses + lighting → frames (RGB, RGB-packed instance
//! ids, depth in the camera's format, optional surface normals), COCO, optional YOLO (with `yolo/classes.txt`), ICDAR
//! for text, poses, and a `preview.png` contact sheet.
//!
//! Glue between the cameras, render and annotate stages. Frames are rendered one at a time
//! ([`PathFrames::render`]): each frame's files go to the caller's `emit` as soon as they
//! are encoded, and the frame is then dropped; what the path's own files need of it comes
//! back as a small [`FrameRecord`]. The path's files (`poses.json`, `preview.png`; COCO
//! through [`annotate::write_coco`]) are assembled from those records, so the frames can be
//! rendered on different machines ([`super::chunks`]). Pure: the driver decides where
//! emitted files go. File names are relative to the output folder.

use std::collections::BTreeMap;

use image::RgbImage;
use serde::{Deserialize, Serialize};
use serde_json::{Value, json};

use super::codec;
use crate::annotate::{
    self, Category, CocoLines, ContactSheet, DepthFile, FrameInput, ObjectLabel, Segment,
    SemanticClasses, Thresholds, YoloClasses,
};
use crate::cameras::tan_half_degrees;
use crate::lidar;
use crate::model::{CameraPose, Movement, ObjectKind};
use crate::render::{self, Intrinsics, Light, Lighting, PreparedScene, Sun};
use crate::sensor::{self, CloudLight, SensorFrame};
use crate::spec::{CameraPath, CameraSpec, WeatherSpec};
use crate::traffic::Traffic;

/// How far the eye (world metres) and each object (by instance id) move while a frame's
/// shutter is open ([`PathFrames::shutter_motion`]).
type ShutterShift = ([f32; 3], Vec<[f32; 3]>);

/// Everything one camera path needs besides its poses.
pub struct PathInput<'a> {
    /// Per text object by instance id: its words' world corners, for ICDAR quads.
    pub corners: &'a BTreeMap<u32, Vec<[[f64; 3]; 4]>>,
    pub camera: &'a CameraSpec,
    pub scene: &'a PreparedScene,
    pub lighting: &'a Lighting,
    /// The sun `lighting` was made for, recorded in each frame's `conditions`.
    pub sun: Sun,
    /// With `[lighting] vary = "frame"`: the lighting and sun of frame `i` (instead of
    /// `lighting` and `sun`).
    pub relight: Option<&'a (dyn Fn(usize) -> (Lighting, Sun) + Sync)>,
    pub categories: &'a [Category],
    pub labels: &'a [ObjectLabel],
    pub thresholds: &'a Thresholds,
    /// YOLO's classes, when YOLO files are written.
    pub yolo: Option<&'a YoloClasses>,
    pub weather: &'a WeatherSpec,
    /// Seed of this camera's per-frame conditions (`sensor::draw`).
    pub conditions_seed: u64,
    /// The scene's Cityscapes labels, when the path writes Cityscapes-format files.
    pub semantic: Option<&'a SemanticClasses>,
    /// What the camera's LiDAR scans (the scene's triangles and their BVH; with moving
    /// traffic, what stands still), when it has one and frames are rendered.
    pub lidar: Option<&'a lidar::Target>,
    /// The traffic, with `[traffic]`: each frame poses the scene at its time.
    pub traffic: Option<&'a Traffic>,
    /// The scene's objects' kinds, by instance id − 1 (the LiDAR's labels of what moves).
    pub kinds: &'a [ObjectKind],
}

/// Frame `i`'s scene: as built, or with the traffic where it stands at the frame's time.
struct FrameScene<'s> {
    movement: Option<Movement>,
    posed: Option<PreparedScene>,
    built: &'s PreparedScene,
}

impl FrameScene<'_> {
    fn scene(&self) -> &PreparedScene {
        self.posed.as_ref().unwrap_or(self.built)
    }
}

/// A camera path ready to render its frames one at a time, in any order and on any
/// machine ([`super::chunks`] groups them): each frame's files go to `emit`, and what the
/// path's own files need of the frame comes back as a [`FrameRecord`].
pub struct PathFrames<'a> {
    input: &'a PathInput<'a>,
    poses: &'a [CameraPose],
    intrinsics: Intrinsics,
    /// Objects whose visible fraction matters: those that may be annotated (a sign by its
    /// front or its back).
    measured: Vec<u32>,
    has_text: bool,
    dir: String,
    /// The path's median step between poses, for each frame's direction of travel.
    median_step: Option<f64>,
}

/// What one rendered frame leaves for its path's `coco.json`, `poses.json` and
/// `preview.png`: a few hundred bytes per annotation, kept in the cache beside the frame's
/// images so that a path can be assembled without rendering anything.
#[derive(Debug, Serialize, Deserialize)]
pub struct FrameRecord {
    pub coco: CocoLines,
    /// The weather, sensor and sun values the frame drew.
    pub conditions: Value,
    /// The contact sheet's boxes: `[category, x_min, y_min, x_max, y_max]` of each kept
    /// annotation.
    pub sheet: Vec<[u32; 5]>,
    /// The frame's COCO panoptic segments, when the path writes Cityscapes-format files.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub panoptic: Option<Vec<Segment>>,
    /// With moving traffic, where it stands: `poses.json`'s `traffic` of the frame.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub traffic: Option<Value>,
}

impl<'a> PathFrames<'a> {
    pub fn new(input: &'a PathInput<'a>, poses: &'a [CameraPose]) -> PathFrames<'a> {
        let camera = input.camera;
        let measured = input
            .labels
            .iter()
            .zip(1u32..)
            .filter(|(label, _)| {
                listed(input.categories, label.category)
                    || listed(
                        input.categories,
                        label.sign.as_ref().and_then(|s| s.back_category),
                    )
            })
            .map(|(_, id)| id)
            .collect();
        PathFrames {
            input,
            poses,
            intrinsics: camera_intrinsics(camera),
            measured,
            has_text: input
                .labels
                .iter()
                .any(|l| l.text.is_some() && l.category.is_some()),
            dir: format!("frames/{}", camera.name),
            median_step: sensor::median_step(poses),
        }
    }

    /// Builds what every frame reads ahead of the frames, side by side: the shadow map
    /// frame `i` is lit by (weather does not move the sun), and the cloud field when the
    /// path may draw clouds. Frames rendered side by side then find them built, instead
    /// of waiting for the first of them to build one.
    pub fn warm(&self, i: usize) {
        rayon::join(
            || {
                let drawn_sun = self.input.relight.map(|f| f(i));
                let lighting = drawn_sun.as_ref().map_or(self.input.lighting, |(l, _)| l);
                if self.input.traffic.is_some() {
                    // The map of what stands still, which every posed frame copies.
                    self.posed(i, lighting);
                } else {
                    render::warm_shadow_map(self.input.scene, lighting);
                }
            },
            || sensor::warm_clouds(self.input.weather.clouds.ends()[1]),
        );
    }

    /// Frame `i`'s scene: with traffic, posed at the frame's time (its shadow map made for
    /// `lighting`'s sun, when it casts shadows).
    fn posed(&self, i: usize, lighting: &Lighting) -> FrameScene<'a> {
        let built = self.input.scene;
        let Some(traffic) = self.input.traffic else {
            return FrameScene {
                movement: None,
                posed: None,
                built,
            };
        };
        let movement = traffic.at(self.poses[i].time.unwrap_or(0.0));
        let sun = lighting
            .shadows
            .then_some((lighting.sun_direction, lighting.shadow_map_side));
        let posed = built.posed(&movement, sun);
        FrameScene {
            movement: Some(movement),
            posed: Some(posed),
            built,
        }
    }

    /// The headlights of the car a `roads` camera rides in, aimed along frame `i`'s
    /// `travel`, when they are on: the camera asks for them and the lamps are lit
    /// (`emission` above 0). None otherwise.
    fn headlights(&self, emission: f32, i: usize, travel: Option<[f64; 3]>) -> Vec<Light> {
        let camera = self.input.camera;
        if camera.path != CameraPath::Roads || !camera.headlights || emission <= 0.0 {
            return Vec::new();
        }
        let Some(travel) = travel else {
            return Vec::new();
        };
        let pose = &self.poses[i];
        let height = pose.angles.map_or(pose.eye[1], |a| a.height);
        render::ego_headlights(pose.eye, height, travel, emission)
    }

    /// What annotating frame `i` reads besides the labels: its instance image, the
    /// objects' unoccluded footprints, the text objects' word quads projected and, when
    /// the path writes keypoints, its depth.
    fn annotation_input<'f>(
        &self,
        i: usize,
        (frame, rgb): (&'f render::Frame, &'f RgbImage),
        footprints: &[render::Footprint],
        movement: Option<&Movement>,
    ) -> FrameInput<'f> {
        let (intrinsics, pose) = (&self.intrinsics, &self.poses[i]);
        let k = [intrinsics.fx, intrinsics.fy, intrinsics.cx, intrinsics.cy];
        FrameInput {
            file_name: format!("rgb/{i:06}.png"),
            instance: &frame.instance,
            rgb: Some(rgb),
            intrinsics: k,
            pose: *pose,
            full: footprints
                .iter()
                .map(|f| (f.id, (f.bbox().map(|v| v as f64), f.pixels)))
                .collect(),
            quads: self
                .input
                .corners
                .iter()
                .filter_map(|(id, words)| {
                    let o = movement.map_or([0.0; 3], |m| m.offset(*id));
                    let quads = words.iter().map(|c| {
                        let c = c.map(|p| std::array::from_fn(|j| p[j] + o[j]));
                        annotate::project_quad(pose, k, intrinsics.near, &c)
                    });
                    Some((*id, quads.collect::<Option<Vec<_>>>()?))
                })
                .collect(),
            depth: self.input.camera.keypoints.then_some(&frame.depth),
        }
    }

    /// Frame `i`'s YOLO, ICDAR and KITTI files, when the path writes them.
    fn label_files(&self, i: usize, summary: &annotate::FrameAnnotations) -> Vec<(String, String)> {
        let dir = &self.dir;
        let mut files = Vec::new();
        if let Some(classes) = self.input.yolo {
            files.push((
                format!("{dir}/yolo/{i:06}.txt"),
                annotate::yolo(classes, summary),
            ));
        }
        if self.has_text {
            files.push((
                format!("{dir}/icdar/gt_{i:06}.txt"),
                annotate::icdar(summary),
            ));
        }
        if self.input.camera.kitti {
            let kitti = annotate::kitti(summary, self.input.categories);
            files.push((format!("{dir}/label_2/{i:06}.txt"), kitti.label));
            files.push((format!("{dir}/calib/{i:06}.txt"), kitti.calib));
        }
        files
    }

    /// Frame `i`'s files made from the scene's geometry besides the render: its flow to
    /// the next frame (from its `depth`) with `flow = true`, and its LiDAR scan in the air
    /// `conditions` drew when the camera has a LiDAR.
    fn geometry_files(
        &self,
        i: usize,
        frame: &render::Frame,
        scene: &FrameScene,
        conditions: &sensor::Conditions,
    ) -> Vec<(String, Vec<u8>)> {
        let (camera, dir, pose) = (self.input.camera, &self.dir, &self.poses[i]);
        let mut files = Vec::new();
        if let Some(next) = self.poses.get(i + 1).filter(|_| camera.flow) {
            let (k, depth) = (&self.intrinsics, &frame.depth);
            let flow = match (&scene.movement, self.input.traffic) {
                (Some(now), Some(traffic)) => {
                    let later = traffic.at(next.time.unwrap_or(0.0));
                    let motion = render::Motion {
                        instance: &frame.instance,
                        now,
                        next: &later,
                    };
                    let seen = scene.built.posed(&later, None);
                    render::flow(&seen, depth, Some(&motion), pose, next, k)
                }
                _ => render::flow(scene.built, depth, None, pose, next, k),
            };
            files.push((format!("{dir}/flow/{i:06}.png"), flow.kitti_png()));
        }
        files.extend(self.lidar_files(i, scene, conditions));
        files
    }

    /// Frame `i`'s LiDAR files, when the camera has a LiDAR: one turn from the eye, in
    /// the air `conditions` drew.
    fn lidar_files(
        &self,
        i: usize,
        scene: &FrameScene,
        conditions: &sensor::Conditions,
    ) -> Vec<(String, Vec<u8>)> {
        let (camera, dir) = (self.input.camera, &self.dir);
        let (Some(spec), Some(target)) = (&camera.lidar, self.input.lidar) else {
            return Vec::new();
        };
        let pose = &self.poses[i];
        let scanner = lidar::Scanner::of(spec, sensor::air_extinction(conditions, pose.eye[1]));
        let seed = self.input.conditions_seed;
        // What moves, where the frame has it (the path's target holds what stands still).
        let moving = scene
            .movement
            .as_ref()
            .map(|m| lidar::Target::of_objects(scene.scene(), self.input.kinds, |id| m.moves(id)));
        let name = &camera.name;
        let points = lidar::scan(
            target,
            moving.as_ref(),
            &scanner,
            pose,
            seed,
            name,
            i as u64,
        );
        let mut files = vec![
            (
                format!("{dir}/velodyne/{i:06}.bin"),
                lidar::velodyne_bytes(&points),
            ),
            (
                format!("{dir}/labels/{i:06}.label"),
                lidar::label_bytes(&points),
            ),
        ];
        if spec.ply {
            files.push((format!("{dir}/lidar/{i:06}.ply"), lidar::ply_bytes(&points)));
        }
        files
    }

    /// On a timed drive with moving traffic and motion blur, how far the eye and each
    /// object move while frame `i`'s shutter is open: `motion_blur` metres at the drive's
    /// speed (`speed_kmh`) give the shutter's time; the eye's motion comes from the
    /// neighbouring frames' poses and times, the objects' from the traffic at the
    /// shutter's opening and closing. `(eye, moved by instance id)`.
    fn shutter_motion(
        &self,
        i: usize,
        scene: &FrameScene,
        conditions: &sensor::Conditions,
    ) -> Option<ShutterShift> {
        let (traffic, _) = self.input.traffic.zip(scene.movement.as_ref())?;
        let t = self.poses[i].time?;
        let speed = self
            .input
            .camera
            .speed_kmh
            .unwrap_or(crate::views::DRIVE_KMH)
            / 3.6;
        let shutter = conditions.motion_blur / speed;
        if shutter.is_nan() || shutter <= 0.0 {
            return None;
        }
        let (open, close) = (traffic.at(t - 0.5 * shutter), traffic.at(t + 0.5 * shutter));
        let last = close.moves.last().map_or(0, |m| m.0 as usize);
        let mut moved = vec![[0.0f32; 3]; last + 1];
        for (id, to) in &close.moves {
            let from = open.offset(*id);
            moved[*id as usize] = std::array::from_fn(|k| (to[k] - from[k]) as f32);
        }
        let timed = |j: usize| self.poses.get(j).and_then(|p| Some((p.eye, p.time?)));
        let (a, b) = (timed(i.saturating_sub(1))?, timed(i + 1).or(timed(i))?);
        let eye = if b.1 > a.1 {
            std::array::from_fn(|k| ((b.0[k] - a.0[k]) / (b.1 - a.1) * shutter) as f32)
        } else {
            [0.0; 3]
        };
        Some((eye, moved))
    }

    /// The RGB image the camera's sensor makes of `frame` under `conditions` (`shutter`:
    /// [`PathFrames::shutter_motion`]).
    fn develop(
        &self,
        frame: &render::Frame,
        pose: &CameraPose,
        (travel, shutter): (Option<[f64; 3]>, Option<ShutterShift>),
        lighting: &Lighting,
        conditions: &sensor::Conditions,
    ) -> sensor::Developed {
        let (intrinsics, camera) = (&self.intrinsics, self.input.camera);
        let shutter = shutter.as_ref().map(|(eye, moved)| sensor::ShutterMotion {
            eye: *eye,
            instance: frame.instance.as_raw(),
            moved,
        });
        sensor::develop(
            &SensorFrame {
                width: camera.resolution[0],
                height: camera.resolution[1],
                linear: &frame.linear,
                depth: frame.depth.as_raw(),
                pose: *pose,
                intrinsics: [intrinsics.fx, intrinsics.fy, intrinsics.cx, intrinsics.cy],
                motion: travel,
                shutter,
                horizon: lighting.sky.horizon(),
                clouds: cloud_light(lighting),
                scene_exposure: lighting.exposure,
            },
            conditions,
        )
    }

    /// Hands frame `i`'s images to `emit`: RGB, ids, depth, normals and the Cityscapes
    /// files; returns the depth file's name (in the camera's folder) and the panoptic
    /// segments.
    fn emit_images<E>(
        &self,
        i: usize,
        pngs: render::FramePngs,
        semantic: Option<SemanticFiles>,
        emit: &mut impl FnMut(String, Vec<u8>) -> Result<(), E>,
    ) -> Result<(String, Option<Vec<Segment>>), E> {
        let dir = &self.dir;
        let depth_name = format!("depth/{i:06}.{}", self.input.camera.depth.extension());
        emit(format!("{dir}/rgb/{i:06}.png"), pngs.rgb)?;
        emit(format!("{dir}/ids/{i:06}.png"), pngs.instance)?;
        emit(format!("{dir}/{depth_name}"), pngs.depth)?;
        if let Some(normals) = pngs.normals {
            emit(format!("{dir}/normals/{i:06}.png"), normals)?;
        }
        let (semantic, panoptic) = semantic.unzip();
        for (suffix, png) in semantic.into_iter().flatten() {
            emit(format!("{dir}/semantic/{i:06}_{suffix}.png"), png)?;
        }
        Ok((depth_name, panoptic))
    }

    /// Renders and annotates frame `i`, handing each of its files to `emit` (name, bytes)
    /// as soon as it is ready; stops at the first error `emit` returns.
    pub fn render<E>(
        &self,
        i: usize,
        mut emit: impl FnMut(String, Vec<u8>) -> Result<(), E>,
    ) -> Result<FrameRecord, E> {
        let (input, intrinsics) = (self.input, &self.intrinsics);
        let camera = input.camera;
        let depth_format = camera.depth;
        let pose = &self.poses[i];
        let drawn_sun = input.relight.map(|f| f(i));
        let (lighting, sun) = match &drawn_sun {
            Some((lighting, sun)) => (lighting, *sun),
            None => (input.lighting, input.sun),
        };
        let seed = input.conditions_seed;
        let conditions = sensor::draw(input.weather, &camera.sensor, seed, i as u64);
        let scene = self.posed(i, lighting);
        let movement = scene.movement.as_ref();
        let carried = movement.and_then(|m| lighting.moved(m));
        let lighting = carried.as_ref().unwrap_or(lighting);
        let moved_labels = movement.map(|m| annotate::moved_labels(input.labels, m));
        let labels = moved_labels.as_deref().unwrap_or(input.labels);
        let travel = sensor::travel_direction_with(self.poses, i, self.median_step);
        let headlights = self.headlights(lighting.emission, i, travel);
        let headlit = !headlights.is_empty();
        let (adjusted, shade) = weathered(lighting, &conditions, pose, headlights);
        let lighting = adjusted.as_ref().unwrap_or(lighting);
        let (frame, footprints) = render::render_with(
            scene.scene(),
            pose,
            intrinsics,
            lighting,
            camera.supersample,
            &self.measured,
            camera.normals,
        );
        // The sensor stage replaces the RGB image only: ids and depth stay as rendered; the
        // labels read the final image only to drop what it does not show.
        let shutter = self.shutter_motion(i, &scene, &conditions);
        let developed = self.develop(&frame, pose, (travel, shutter), lighting, &conditions);
        let headlit = (camera.path == CameraPath::Roads).then_some(headlit);
        let drawn = drawn_json(&conditions, developed.exposure, &sun, shade, headlit);
        let frame_input = self.annotation_input(i, (&frame, &developed.rgb), &footprints, movement);
        let ((pngs, semantic), mut summary) = rayon::join(
            || {
                rayon::join(
                    || frame.encode(&developed.rgb, depth_format),
                    || input.semantic.map(|c| semantic_files(c, &frame.instance)),
                )
            },
            || annotate::summarize(labels, &frame_input, input.thresholds),
        );
        let (depth_name, panoptic) = self.emit_images(i, pngs, semantic, &mut emit)?;
        summary.depth = Some(DepthFile {
            file_name: depth_name,
            format: depth_format.name(),
            scale: depth_format.scale(),
        });
        for (name, text) in self.label_files(i, &summary) {
            emit(name, text.into_bytes())?;
        }
        for (name, bytes) in self.geometry_files(i, &frame, &scene, &conditions) {
            emit(name, bytes)?;
        }
        let sheet = ContactSheet::boxes(&summary, input.categories)
            .into_iter()
            .map(|(category, b)| [category, b.x_min, b.y_min, b.x_max, b.y_max])
            .collect();
        Ok(FrameRecord {
            coco: CocoLines::of(input.categories, &summary, &drawn, i as u64 + 1),
            conditions: drawn,
            sheet,
            panoptic,
            traffic: movement.map(traffic_json),
        })
    }
}

/// Where the traffic stands in a frame, as `poses.json` records it: each moving object's
/// offset from where `city.obj` has it (world metres, to the micrometre), and what each
/// signal head shows.
fn traffic_json(movement: &Movement) -> Value {
    let r = |v: f64| (v * 1e6).round() / 1e6;
    let objects: serde_json::Map<String, Value> = movement
        .moves
        .iter()
        .map(|(id, o)| (id.to_string(), json!(o.map(r))))
        .collect();
    let signals: serde_json::Map<String, Value> = movement
        .signals
        .iter()
        .map(|(id, state)| (id.to_string(), json!(state)))
        .collect();
    json!({"objects": objects, "signals": signals})
}

/// A frame's Cityscapes-format PNGs by suffix, and its panoptic segments.
type SemanticFiles = (Vec<(&'static str, Vec<u8>)>, Vec<Segment>);

/// The Cityscapes suffixes of a frame's `semantic/` files, in the order
/// [`semantic_files`] makes them.
pub const SEMANTIC_SUFFIXES: [&str; 4] = ["labelIds", "instanceIds", "color", "panoptic"];

/// A frame's Cityscapes-format PNGs (by [`SEMANTIC_SUFFIXES`]) and panoptic segments.
fn semantic_files(
    classes: &SemanticClasses,
    instance: &image::ImageBuffer<image::Luma<u32>, Vec<u32>>,
) -> SemanticFiles {
    use crate::model::image_file::{PngEffort, encode_png};
    let frame = annotate::semantic(classes, instance);
    let pngs = [
        encode_png(&frame.label_ids, PngEffort::Fast),
        encode_png(&frame.instance_ids, PngEffort::Fast),
        encode_png(&frame.color, PngEffort::Fast),
        encode_png(&frame.panoptic, PngEffort::Fast),
    ];
    (
        SEMANTIC_SUFFIXES.into_iter().zip(pngs).collect(),
        frame.segments,
    )
}

/// A frame's lighting under its drawn `conditions` (clouds, weather) and with `extra`
/// lights, when that differs from the path's `lighting`, and how much a cloud shades the
/// sun (0–1) at the camera's ground.
fn weathered(
    lighting: &Lighting,
    conditions: &sensor::Conditions,
    pose: &CameraPose,
    extra: Vec<Light>,
) -> (Option<Lighting>, f32) {
    // A cloud between the camera's ground and the sun dims the sun for the whole frame.
    let shade = sensor::sun_shade(
        conditions.clouds as f32,
        conditions.cloud_offset,
        [pose.eye[0], 0.0, pose.eye[2]],
        lighting.sun_direction,
    );
    let weather = sensor::weather_light(conditions).under_cloud(shade);
    let adjusted = lighting.under_weather(
        weather.sun_scale,
        weather.sky_scale,
        weather.shadow_strength,
        extra,
    );
    (adjusted, shade)
}

/// What frame's `conditions` record: the drawn weather and sensor values, the exposure,
/// the sun, how much a cloud shades it, and (on roads) whether the headlights are on.
fn drawn_json(
    conditions: &sensor::Conditions,
    exposure: f32,
    sun: &Sun,
    shade: f32,
    headlit: Option<bool>,
) -> Value {
    let mut drawn = conditions.to_json(exposure);
    drawn["sun"] = sun_json(sun);
    drawn["sun_shaded"] = json!((f64::from(shade) * 1e3).round() / 1e3);
    if let Some(headlit) = headlit {
        drawn["headlights"] = json!(headlit);
    }
    drawn
}

/// The light the sensor's clouds are lit by.
fn cloud_light(lighting: &Lighting) -> CloudLight {
    CloudLight {
        sun_direction: lighting.sun_direction,
        sun_colour: lighting.sun_colour,
        sky: lighting.ambient,
    }
}

/// Whether category `c` is one the path annotates.
fn listed(categories: &[Category], c: Option<u32>) -> bool {
    c.is_some_and(|c| categories.iter().any(|k| k.id == c))
}

/// A camera's intrinsics: its resolution and field of view, the default clip planes.
pub(super) fn camera_intrinsics(camera: &CameraSpec) -> Intrinsics {
    let (width, height) = (camera.resolution[0], camera.resolution[1]);
    Intrinsics::from_fov(width, height, tan_half_degrees(camera.fov))
}

/// `poses.json`: the intrinsics, the depth format (and with normals, their encoding) and
/// every frame's pose and drawn conditions, the sun among them (`conditions` in frame
/// order).
pub fn poses_json(
    camera: &CameraSpec,
    poses: &[CameraPose],
    conditions: impl IntoIterator<Item = (Value, Option<Value>)>,
) -> Vec<u8> {
    let mut moving = false;
    let (width, height) = (camera.resolution[0], camera.resolution[1]);
    let intrinsics = camera_intrinsics(camera);
    let depth_format = camera.depth;
    let mut poses_json = json!({
        "intrinsics": {"width": width, "height": height, "fx": intrinsics.fx, "fy": intrinsics.fy,
                       "cx": intrinsics.cx, "cy": intrinsics.cy},
        "depth": {"format": depth_format.name(), "scale": depth_format.scale(),
                  "extension": depth_format.extension(), "sky": 0},
        "frames": poses.iter().zip(conditions).enumerate().map(|(i, (p, (c, traffic)))| {
            let mut frame = json!({
                "file_name": format!("rgb/{i:06}.png"), "eye": p.eye, "target": p.target,
                "up": p.up, "angles": p.angles, "conditions": c
            });
            if let Some(traffic) = traffic {
                frame["traffic"] = traffic;
                moving = true;
            }
            if let Some(t) = p.time {
                frame["time"] = json!(t);
            }
            if camera.lidar.is_some() {
                frame["velodyne_to_world"] = json!(lidar::to_world(p));
            }
            frame
        }).collect::<Vec<_>>(),
    });
    if let Some(fps) = camera.fps {
        poses_json["fps"] = json!(fps);
    }
    if moving {
        poses_json["traffic"] = json!({
            "objects": "per frame, each moving object's instance id and its offset [x, y, z] in world metres from where city.obj has it (lane vehicles, their plates and riders, walking people)",
            "signals": "per frame, each signal head's instance id and the lamp it shows (red, amber or green)",
        });
    }
    if camera.normals {
        poses_json["normals"] = json!({
            "folder": "normals", "extension": "png", "axes": "x right, y down, z forward",
            "decode": "n = value / 65535 * 2 - 1", "sky": [0, 0, 0]
        });
    }
    if let Some(spec) = &camera.lidar {
        poses_json["lidar"] = lidar_json(spec);
    }
    if camera.flow {
        poses_json["flow"] = json!({
            "folder": "flow", "extension": "png", "to": "the next frame (none for the last)",
            "decode": "u = (R - 32768) / 64, v = (G - 32768) / 64, valid = B (KITTI flow)",
            "pixel": "from the centre of pixel (x, y) to where its point lands, in pixels",
        });
    }
    codec::to_pretty_json(&poses_json)
}

/// `poses.json`'s `lidar`: the scanner, its files and frame, and its labels.
fn lidar_json(spec: &crate::spec::LidarSpec) -> Value {
    let scanner = lidar::Scanner::of(spec, 0.0);
    let kinds: serde_json::Map<String, Value> = crate::model::ObjectKind::ALL
        .iter()
        .map(|k| (k.name().to_string(), json!(lidar::semantic_id(*k))))
        .collect();
    let names: serde_json::Map<String, Value> = lidar::SEMANTIC_NAMES
        .iter()
        .map(|(id, name)| (id.to_string(), json!(name)))
        .collect();
    json!({
        "frame": "KITTI velodyne: x forward (the camera's level heading), y left, z up, metres, origin at the camera's eye",
        "velodyne": {"folder": "velodyne", "extension": "bin", "record": "float32 x, y, z, intensity, little-endian"},
        "labels": {"folder": "labels", "extension": "label", "record": "uint32 semantic | instance << 16, little-endian"},
        "ply": spec.ply.then_some("lidar"),
        "beams": spec.beams, "columns": spec.columns, "elevations": scanner.elevations,
        "range": spec.range, "noise": spec.noise, "dropout": spec.dropout,
        "detection_floor": lidar::DETECTION_FLOOR,
        "semantic_names": names, "kind_semantic_ids": kinds,
    })
}

/// `preview.png` from the picked frames' RGB images and their records' boxes.
pub fn preview_png(frames: Vec<(RgbImage, Vec<[u32; 5]>)>, categories: &[Category]) -> Vec<u8> {
    let mut sheet = ContactSheet::new(frames.len());
    for (rgb, boxes) in frames {
        sheet.add(rgb, boxes);
    }
    codec::encode_png(&sheet.draw(categories))
}

/// The sun a frame was lit by, as its `conditions` record it (degrees, 6 decimals; the
/// hour only when the sun was set by one).
fn sun_json(sun: &Sun) -> serde_json::Value {
    let r = |v: f64| (v * 1e6).round() / 1e6;
    let mut out = json!({"elevation": r(sun.elevation), "azimuth": r(sun.azimuth)});
    if let Some(hour) = sun.hour {
        out["hour"] = json!(r(hour));
    }
    out
}
