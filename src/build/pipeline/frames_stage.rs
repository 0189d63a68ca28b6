//! The frames stage of one `[[cameras]]` entry: poses, lighting, labels → the streamed
//! frames and annotations (`super::super::frames`), each file put in the cache as it is made.

use std::collections::BTreeMap;

use rand::Rng;

use super::super::BuildError;
use super::super::cache::{Blob, Load, ObjectRef, Outputs};
use super::super::frame_labels;
use super::super::frames;
use super::super::object_views;
use super::Pipeline;
use crate::model::{FacadeSet, Lamp, Scene};
use crate::spec::{CameraPath, Spec, Vary};
use crate::{annotate, cameras, render, rng, scene};

impl Pipeline<'_> {
    /// Frames and annotations of `[[cameras]]` entry `index`.
    pub(super) fn need_frames(&mut self, index: usize) -> Result<(), BuildError> {
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
}

/// The spec's lighting under `sun`, with a light at every lamp head.
pub(super) fn lighting(
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
