//! One camera path's dataset: scene + poses + lighting → frames (RGB, RGB-packed instance
//! ids, depth in the camera's format), COCO, optional YOLO (with `yolo/classes.txt`), ICDAR
//! for text, poses, and a `preview.png` contact sheet.
//!
//! Glue between the cameras, render, sensor and annotate stages: every choice of how a
//! frame looks or is labelled lives in those stages (and is covered by their `VERSION`s,
//! all in the frames key); the file names and the `poses.json` layout are the driver's. It streams: each frame's files go
//! to the caller's `emit` as soon as they are encoded, and the frame is then dropped, so
//! memory does not grow with the number of frames (only the COCO text does, a few hundred
//! bytes per annotation). Pure: the driver decides where emitted files go. File names are
//! relative to the output folder.

use std::collections::BTreeMap;

use serde_json::json;

use super::codec;
use crate::annotate::{
    self, Category, CocoWriter, ContactSheet, DepthFile, FrameInput, ObjectLabel, Thresholds,
    YoloClasses,
};
use crate::cameras::tan_half_degrees;
use crate::model::CameraPose;
use crate::render::{self, Intrinsics, Lighting, PreparedScene, Sun};
use crate::sensor::{self, SensorFrame, WeatherLight};
use crate::spec::{CameraSpec, WeatherSpec};

/// Everything one camera path needs besides its poses.
pub struct PathInput<'a> {
    /// Per text object by instance id: its words' world corners, for ICDAR quads.
    pub corners: &'a BTreeMap<u32, Vec<[[f64; 3]; 4]>>,
    pub camera: &'a CameraSpec,
    pub scene: &'a PreparedScene,
    pub lighting: &'a Lighting,
    /// The sun `lighting` was made for, written into poses.json.
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
}

/// Renders every pose and annotates the frames, handing each file to `emit` (name, bytes)
/// as soon as it is ready; stops at the first error `emit` returns. `progress` is told
/// the number of frames done.
pub fn render_path<E>(
    input: &PathInput,
    poses: &[CameraPose],
    mut emit: impl FnMut(String, Vec<u8>) -> Result<(), E>,
    mut progress: impl FnMut(usize),
) -> Result<(), E> {
    let camera = input.camera;
    let (width, height) = (camera.resolution[0], camera.resolution[1]);
    let intrinsics = Intrinsics::from_fov(width, height, tan_half_degrees(camera.fov));
    let dir = format!("frames/{}", camera.name);
    let depth_format = camera.depth;
    // Objects whose visible fraction matters: those that may be annotated (a sign by its
    // front or its back).
    let listed = |c: Option<u32>| c.is_some_and(|c| input.categories.iter().any(|k| k.id == c));
    let measured: Vec<u32> = input
        .labels
        .iter()
        .zip(1u32..)
        .filter(|(label, _)| {
            listed(label.category) || listed(label.sign.as_ref().and_then(|s| s.back_category))
        })
        .map(|(_, id)| id)
        .collect();
    let has_text = input
        .labels
        .iter()
        .any(|l| l.text.is_some() && l.category.is_some());
    let mut sheet = ContactSheet::new(poses.len());
    let mut coco = CocoWriter::new(input.categories);
    let mut suns = Vec::with_capacity(poses.len());
    let mut conditions_json = Vec::with_capacity(poses.len());
    for (i, pose) in poses.iter().enumerate() {
        let drawn_sun = input.relight.map(|f| f(i));
        let (lighting, sun) = match &drawn_sun {
            Some((lighting, sun)) => (lighting, *sun),
            None => (input.lighting, input.sun),
        };
        suns.push(sun);
        let conditions = sensor::draw(
            input.weather,
            &camera.sensor,
            input.conditions_seed,
            i as u64,
        );
        let weathered = weathered(lighting, &sensor::weather_light(&conditions));
        let lighting = weathered.as_ref().unwrap_or(lighting);
        let (mut frame, footprints) = render::render_measuring(
            input.scene,
            pose,
            &intrinsics,
            lighting,
            camera.supersample,
            &measured,
        );
        // The sensor stage replaces the RGB image only: ids, depth and labels stay as
        // rendered.
        let developed = sensor::develop(
            &SensorFrame {
                width,
                height,
                linear: &frame.linear,
                depth: frame.depth.as_raw(),
                pose: *pose,
                intrinsics: [intrinsics.fx, intrinsics.fy, intrinsics.cx, intrinsics.cy],
                motion: sensor::travel_direction(poses, i),
                horizon: lighting.sky.horizon(),
                scene_exposure: lighting.exposure,
            },
            &conditions,
        );
        frame.rgb = developed.rgb;
        let drawn = conditions.to_json(developed.exposure);
        let frame_input = FrameInput {
            file_name: format!("rgb/{i:06}.png"),
            instance: &frame.instance,
            intrinsics: [intrinsics.fx, intrinsics.fy, intrinsics.cx, intrinsics.cy],
            pose: *pose,
            full: footprints
                .iter()
                .map(|f| (f.id, (f.bbox().map(|v| v as f64), f.pixels)))
                .collect(),
            quads: input
                .corners
                .iter()
                .filter_map(|(id, words)| {
                    let k = [intrinsics.fx, intrinsics.fy, intrinsics.cx, intrinsics.cy];
                    let quads = words
                        .iter()
                        .map(|c| annotate::project_quad(pose, k, intrinsics.near, c));
                    Some((*id, quads.collect::<Option<Vec<_>>>()?))
                })
                .collect(),
        };
        let (pngs, mut summary) = rayon::join(
            || frame.encode(depth_format),
            || annotate::summarize(input.labels, &frame_input, input.thresholds),
        );
        let depth_name = format!("depth/{i:06}.{}", depth_format.extension());
        emit(format!("{dir}/rgb/{i:06}.png"), pngs.rgb)?;
        emit(format!("{dir}/ids/{i:06}.png"), pngs.instance)?;
        emit(format!("{dir}/{depth_name}"), pngs.depth)?;
        summary.depth = Some(DepthFile {
            file_name: depth_name,
            format: depth_format.name(),
            scale: depth_format.scale(),
        });
        coco.push_with_conditions(&summary, &drawn);
        conditions_json.push(drawn);
        if let Some(classes) = input.yolo {
            let text = annotate::yolo(classes, &summary);
            emit(format!("{dir}/yolo/{i:06}.txt"), text.into_bytes())?;
        }
        if has_text {
            let text = annotate::icdar(&summary);
            emit(format!("{dir}/icdar/gt_{i:06}.txt"), text.into_bytes())?;
        }
        sheet.offer(i, frame.rgb, &summary, input.categories);
        progress(i + 1);
    }
    emit(format!("{dir}/coco.json"), coco.finish())?;
    if let Some(classes) = input.yolo {
        emit(
            format!("{dir}/yolo/classes.txt"),
            classes.names_file().into_bytes(),
        )?;
    }
    let poses_json = json!({
        "intrinsics": {"width": width, "height": height, "fx": intrinsics.fx, "fy": intrinsics.fy,
                       "cx": intrinsics.cx, "cy": intrinsics.cy},
        "depth": {"format": depth_format.name(), "scale": depth_format.scale(),
                  "extension": depth_format.extension(), "sky": 0},
        "frames": poses.iter().zip(&suns).zip(conditions_json).enumerate().map(|(i, ((p, sun), c))| json!({
            "file_name": format!("rgb/{i:06}.png"), "eye": p.eye, "target": p.target,
            "up": p.up, "angles": p.angles, "sun": sun, "conditions": c
        })).collect::<Vec<_>>(),
    });
    emit(
        format!("{dir}/poses.json"),
        codec::to_pretty_json(&poses_json),
    )?;
    let picture = sheet.draw(input.categories);
    emit(format!("{dir}/preview.png"), codec::encode_png(&picture))
}

/// The frame's linear radiance, for the sensor stage.
///
/// The lighting under a frame's weather, when it differs from the path's: the sun and
/// the sky light scaled. (`shadow_strength` is for the renderer's shadows.)
fn weathered(lighting: &Lighting, light: &WeatherLight) -> Option<Lighting> {
    if light.sun_scale == 1.0 && light.sky_scale == 1.0 {
        return None;
    }
    let mut out = lighting.clone();
    out.sun_colour = out.sun_colour.map(|c| c * light.sun_scale);
    out.ambient = out.ambient.map(|c| c * light.sky_scale);
    Some(out)
}
