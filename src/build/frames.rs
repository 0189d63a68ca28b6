//! One camera path's dataset: scene + poses + lighting → frames (RGB, RGB-packed instance
//! ids, depth in the camera's format), COCO, optional YOLO (with `yolo/classes.txt`), ICDAR
//! for text, poses, and a `preview.png` contact sheet.
//!
//! Glue between the cameras, render and annotate stages. It streams: each frame's files go
//! to the caller's `emit` as soon as they are encoded, and the frame is then dropped, so
//! memory does not grow with the number of frames (only the COCO text does, a few hundred
//! bytes per annotation). Pure: the driver decides where emitted files go. File names are
//! relative to the output folder.

use std::collections::BTreeMap;

use ab_glyph::FontRef;
use image::{Rgb, RgbImage, imageops};
use imageproc::drawing::{draw_hollow_rect_mut, draw_text_mut};
use imageproc::rect::Rect;
use serde_json::json;

use super::codec;
use crate::annotate::{
    self, Category, CocoWriter, DepthFile, FrameInput, ObjectLabel, Thresholds, YoloClasses,
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
}

/// A box drawn on the contact sheet: category and visible box.
struct SheetBox {
    category: u32,
    bounds: PixelBox,
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
    let picks = contact_sheet_picks(poses.len());
    let mut sheet = Vec::with_capacity(picks.len());
    let mut coco = CocoWriter::new(input.categories);
    let mut conditions_json = Vec::with_capacity(poses.len());
    for (i, pose) in poses.iter().enumerate() {
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
        let mut drawn = conditions.to_json(developed.exposure);
        drawn["sun"] = sun_json(&sun);
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
                    let quads = words.iter().map(|c| project_quad(pose, &intrinsics, c));
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
        if picks.contains(&i) {
            let boxes = summary
                .objects
                .iter()
                .filter(|o| o.passes && listed(o.category))
                .filter_map(|o| {
                    let v = &o.visible;
                    Some(SheetBox {
                        category: o.category?,
                        bounds: v.bounds,
                    })
                })
                .collect::<Vec<_>>();
            sheet.push((frame.rgb, boxes));
        }
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
        "frames": poses.iter().zip(conditions_json).enumerate().map(|(i, (p, c))| json!({
            "file_name": format!("rgb/{i:06}.png"), "eye": p.eye, "target": p.target,
            "up": p.up, "angles": p.angles, "conditions": c
        })).collect::<Vec<_>>(),
    });
    emit(
        format!("{dir}/poses.json"),
        codec::to_pretty_json(&poses_json),
    )?;
    let picture = contact_sheet(&sheet, input.categories);
    emit(format!("{dir}/preview.png"), codec::encode_png(&picture))
}

/// The lighting under a frame's weather, when it differs from the path's: the sun and
/// the sky light scaled, shadows weakened.
fn weathered(lighting: &Lighting, light: &WeatherLight) -> Option<Lighting> {
    if light.sun_scale == 1.0 && light.sky_scale == 1.0 && light.shadow_strength == 1.0 {
        return None;
    }
    let mut out = lighting.clone();
    out.sun_colour = out.sun_colour.map(|c| c * light.sun_scale);
    out.ambient = out.ambient.map(|c| c * light.sky_scale);
    out.shadow_strength *= light.shadow_strength;
    Some(out)
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
fn contact_sheet_picks(frames: usize) -> Vec<usize> {
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
