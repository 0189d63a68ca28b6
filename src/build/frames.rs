//! One camera path's dataset: scene + poses + lighting → frames (RGB, RGB-packed instance
//! ids, depth in the camera's format), COCO, optional YOLO (with `yolo/classes.txt`), ICDAR
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

use ab_glyph::FontRef;
use image::{Rgb, RgbImage, imageops};
use imageproc::drawing::{draw_hollow_rect_mut, draw_text_mut};
use imageproc::rect::Rect;
use serde::{Deserialize, Serialize};
use serde_json::{Value, json};

use super::codec;
use crate::annotate::{
    self, Category, CocoLines, DepthFile, FrameInput, ObjectLabel, Thresholds, YoloClasses,
};
use crate::model::{CameraPose, PixelBox};
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
}

/// What one rendered frame leaves for its path's `coco.json`, `poses.json` and
/// `preview.png`: a few hundred bytes per annotation, kept in the cache beside the frame's
/// images so that a path can be assembled without rendering anything.
#[derive(Debug, Serialize, Deserialize)]
pub struct FrameRecord {
    pub coco: CocoLines,
    pub sun: Sun,
    /// The weather and sensor values the frame drew.
    pub conditions: Value,
    /// The contact sheet's boxes: `[category, x0, y0, x1, y1]` of each kept annotation.
    pub sheet: Vec<[u32; 5]>,
}

impl<'a> PathFrames<'a> {
    pub fn new(input: &'a PathInput<'a>, poses: &'a [CameraPose]) -> PathFrames<'a> {
        let camera = input.camera;
        let (width, height) = (camera.resolution[0], camera.resolution[1]);
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
            intrinsics: Intrinsics::from_fov(width, height, tan_half_degrees(camera.fov)),
            measured,
            has_text: input
                .labels
                .iter()
                .any(|l| l.text.is_some() && l.category.is_some()),
            dir: format!("frames/{}", camera.name),
        }
    }

    /// Renders and annotates frame `i`, handing each of its files to `emit` (name, bytes)
    /// as soon as it is ready; stops at the first error `emit` returns.
    pub fn render<E>(
        &self,
        i: usize,
        mut emit: impl FnMut(String, Vec<u8>) -> Result<(), E>,
    ) -> Result<FrameRecord, E> {
        let (input, intrinsics, dir) = (self.input, &self.intrinsics, &self.dir);
        let camera = input.camera;
        let (width, height) = (camera.resolution[0], camera.resolution[1]);
        let depth_format = camera.depth;
        let pose = &self.poses[i];
        let drawn_sun = input.relight.map(|f| f(i));
        let (lighting, sun) = match &drawn_sun {
            Some((lighting, sun)) => (lighting, *sun),
            None => (input.lighting, input.sun),
        };
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
            intrinsics,
            lighting,
            camera.supersample,
            &self.measured,
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
                motion: sensor::travel_direction(self.poses, i),
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
                    let quads = words.iter().map(|c| project_quad(pose, intrinsics, c));
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
        if let Some(classes) = input.yolo {
            let text = annotate::yolo(classes, &summary);
            emit(format!("{dir}/yolo/{i:06}.txt"), text.into_bytes())?;
        }
        if self.has_text {
            let text = annotate::icdar(&summary);
            emit(format!("{dir}/icdar/gt_{i:06}.txt"), text.into_bytes())?;
        }
        let sheet = summary
            .objects
            .iter()
            .filter(|o| o.passes && listed(input.categories, o.category))
            .filter_map(|o| {
                let b = o.visible.bounds;
                Some([o.category?, b.x0, b.y0, b.x1, b.y1])
            })
            .collect();
        Ok(FrameRecord {
            coco: CocoLines::of(input.categories, &summary, &drawn, i as u64 + 1),
            sun,
            conditions: drawn,
            sheet,
        })
    }
}

/// Whether category `c` is one the path annotates.
fn listed(categories: &[Category], c: Option<u32>) -> bool {
    c.is_some_and(|c| categories.iter().any(|k| k.id == c))
}

/// `poses.json`: the intrinsics, the depth format and every frame's pose, sun and drawn
/// conditions (`frames` in frame order).
pub fn poses_json(
    camera: &CameraSpec,
    poses: &[CameraPose],
    frames: impl IntoIterator<Item = (Sun, Value)>,
) -> Vec<u8> {
    let (width, height) = (camera.resolution[0], camera.resolution[1]);
    let intrinsics = Intrinsics::from_fov(width, height, tan_half_degrees(camera.fov));
    let depth_format = camera.depth;
    let poses_json = json!({
        "intrinsics": {"width": width, "height": height, "fx": intrinsics.fx, "fy": intrinsics.fy,
                       "cx": intrinsics.cx, "cy": intrinsics.cy},
        "depth": {"format": depth_format.name(), "scale": depth_format.scale(),
                  "extension": depth_format.extension(), "sky": 0},
        "frames": poses.iter().zip(frames).enumerate().map(|(i, (p, (sun, c)))| json!({
            "file_name": format!("rgb/{i:06}.png"), "eye": p.eye, "target": p.target,
            "up": p.up, "angles": p.angles, "sun": sun, "conditions": c
        })).collect::<Vec<_>>(),
    });
    codec::to_pretty_json(&poses_json)
}

/// `preview.png` from the picked frames' RGB images and their records' boxes.
pub fn preview_png(frames: Vec<(RgbImage, Vec<[u32; 5]>)>, categories: &[Category]) -> Vec<u8> {
    let sheet: Vec<(RgbImage, Vec<SheetBox>)> = frames
        .into_iter()
        .map(|(rgb, boxes)| {
            let boxes = boxes
                .iter()
                .map(|&[category, x0, y0, x1, y1]| SheetBox {
                    category,
                    bounds: PixelBox { x0, y0, x1, y1 },
                })
                .collect();
            (rgb, boxes)
        })
        .collect();
    codec::encode_png(&contact_sheet(&sheet, categories))
}

/// A box drawn on the contact sheet: category and visible box.
struct SheetBox {
    category: u32,
    bounds: PixelBox,
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

/// tan(θ/2) for θ in degrees, from Taylor series of sin and cos (only + − × ÷, so the
/// same bits on every platform; θ ≤ 120° keeps θ/2 ≤ 1.05 rad where 14 terms are exact to
/// the last bit's neighbourhood).
pub fn tan_half_degrees(degrees: f64) -> f64 {
    let x = degrees / 2.0 * (std::f64::consts::PI / 180.0);
    let (mut sin, mut cos) = (0.0, 0.0);
    let (mut term_s, mut term_c) = (x, 1.0);
    for n in 0..14 {
        sin += term_s;
        cos += term_c;
        let k = 2.0 * f64::from(n);
        term_s *= -x * x / ((k + 2.0) * (k + 3.0));
        term_c *= -x * x / ((k + 1.0) * (k + 2.0));
    }
    sin / cos
}

/// The image positions of four world points, if all are in front of the camera.
fn project_quad(
    pose: &CameraPose,
    k: &Intrinsics,
    corners: &[[f64; 3]; 4],
) -> Option<[[f64; 2]; 4]> {
    let basis = pose.basis()?;
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let mut out = [[0.0; 2]; 4];
    for (slot, c) in out.iter_mut().zip(corners) {
        let d = [c[0] - pose.eye[0], c[1] - pose.eye[1], c[2] - pose.eye[2]];
        let z = dot(basis.forward, d);
        if z < k.near {
            return None;
        }
        *slot = [
            k.cx + k.fx * dot(basis.right, d) / z,
            k.cy - k.fy * dot(basis.up, d) / z,
        ];
    }
    Some(out)
}

/// Up to 12 frames spread over the path.
pub fn contact_sheet_picks(frames: usize) -> Vec<usize> {
    let n = frames.min(12);
    (0..n).map(|k| k * frames / n.max(1)).collect()
}

/// The picked frames at half size in a grid, each kept annotation's box and class drawn.
fn contact_sheet(frames: &[(RgbImage, Vec<SheetBox>)], categories: &[Category]) -> RgbImage {
    let Some((first, _)) = frames.first() else {
        return RgbImage::new(1, 1);
    };
    let (w, h) = (first.width() / 2, first.height() / 2);
    let columns = 3u32.min(frames.len() as u32);
    let rows = (frames.len() as u32).div_ceil(columns);
    let mut sheet = RgbImage::from_pixel(
        columns * w + (columns + 1) * 4,
        rows * h + (rows + 1) * 4,
        Rgb([20, 20, 20]),
    );
    let font = FontRef::try_from_slice(notosans::REGULAR_TTF).expect("the embedded font parses");
    let names: BTreeMap<u32, &str> = categories.iter().map(|c| (c.id, c.name.as_str())).collect();
    for (slot, (rgb, boxes)) in frames.iter().enumerate() {
        let mut small = imageops::resize(rgb, w, h, imageops::FilterType::Triangle);
        for b in boxes {
            let PixelBox { x0, y0, x1, y1 } = b.bounds;
            let (bx, by) = ((x0 / 2) as i32, (y0 / 2) as i32);
            let (bw, bh) = (((x1 - x0) / 2).max(1), ((y1 - y0) / 2).max(1));
            let colour = palette(b.category);
            draw_hollow_rect_mut(&mut small, Rect::at(bx, by).of_size(bw, bh), colour);
            let name = names.get(&b.category).copied().unwrap_or("?");
            draw_text_mut(&mut small, colour, bx, (by - 12).max(0), 11.0, &font, name);
        }
        let (col, row) = (slot as u32 % columns, slot as u32 / columns);
        imageops::overlay(
            &mut sheet,
            &small,
            i64::from(4 + col * (w + 4)),
            i64::from(4 + row * (h + 4)),
        );
    }
    sheet
}

fn palette(category: u32) -> Rgb<u8> {
    const COLOURS: [[u8; 3]; 6] = [
        [255, 220, 0],
        [0, 230, 255],
        [255, 80, 200],
        [120, 255, 80],
        [255, 140, 0],
        [200, 160, 255],
    ];
    Rgb(COLOURS[category as usize % COLOURS.len()])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tan_half_matches_known_values() {
        for (degrees, expected) in [
            (90.0, 1.0),
            (60.0, 0.577_350_269_189_625_8),
            (120.0, 1.732_050_807_568_877_2),
        ] {
            let got = tan_half_degrees(degrees);
            assert!((got - expected).abs() < 1e-12, "{degrees}: {got}");
        }
    }

    #[test]
    fn contact_sheet_picks_spread_over_the_path() {
        assert_eq!(contact_sheet_picks(3), [0, 1, 2]);
        assert_eq!(
            contact_sheet_picks(24),
            [0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22]
        );
        assert!(contact_sheet_picks(0).is_empty());
    }
}
