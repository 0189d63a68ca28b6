//! Sensor stage: a frame's linear radiance + depth + camera + drawn [`Conditions`] → the
//! RGB image a camera would save under that weather and with that sensor.
//!
//! [`develop`] is the one entry; [`draw`] makes a frame's conditions from `[weather]`, the
//! camera's `sensor` table, a seed and the frame index (domain randomization in one
//! place). The passes, in the order light meets them:
//!
//! | pass | module | space |
//! |---|---|---|
//! | weather: overcast sky, fog, wet surfaces and rain streaks | `weather` | scene radiance |
//! | motion blur from the camera's travel (and, on a timed drive with traffic, every moving object's) | `optics` | scene radiance |
//! | chromatic aberration, vignetting | `optics` | on the sensor |
//! | exposure (scene: the lighting's; auto: log-average luminance → mid grey, less in dim frames; or fixed), × 2^ev | `tone` | exposed |
//! | shot and read noise | `noise` | exposed |
//! | filmic tone curve, sRGB | `tone` | display |
//! | JPEG round trip | here | 8-bit |
//!
//! Only the RGB image changes: ids, depth and labels stay geometric, so an object deep in
//! fog or behind rain streaks keeps its box and its `visible_fraction` (which counts
//! occlusion by geometry, not contrast). Pure and deterministic: per-pixel randomness is a
//! counter-based hash of the frame's seed, transcendental functions come from `libm`.

/// Bump when this stage's output bytes change: it is part of the frames stage's key.
pub const VERSION: u32 = 6;

mod clouds;
mod conditions;
mod noise;
mod optics;
mod rays;
mod tone;
mod weather;

pub use clouds::{CloudLight, sun_shade, warm as warm_clouds};
pub use conditions::{CLOUD_TILE, Conditions, draw};
pub use tone::{auto_exposure, decode_srgb, tone_map};
pub use weather::{WeatherLight, air_extinction, weather_light};

use image::{ImageFormat, RgbImage};

use crate::model::CameraPose;
use crate::model::geometry::dot;
use crate::spec::ExposureMode;
use rays::Rays;

/// One rendered frame as the sensor sees it.
#[derive(Clone, Copy, Debug)]
pub struct SensorFrame<'a> {
    pub width: u32,
    pub height: u32,
    /// Linear-light radiance, row-major, before exposure.
    pub linear: &'a [[f32; 3]],
    /// Metres along the view axis per pixel, 0 for sky.
    pub depth: &'a [f32],
    pub pose: CameraPose,
    /// `[fx, fy, cx, cy]` in pixels.
    pub intrinsics: [f64; 4],
    /// Unit direction the camera travels in (for motion blur), if known.
    pub motion: Option<[f64; 3]>,
    /// On a timed drive with moving traffic, what moves while the shutter is open: motion
    /// blur then follows it instead of `motion`.
    pub shutter: Option<ShutterMotion<'a>>,
    /// The sky's linear colour at the horizon (fog and grey skies take their colour from it).
    pub horizon: [f32; 3],
    /// The sun's and the sky's light on the clouds.
    pub clouds: CloudLight,
    /// The lighting's own exposure for its time of day (`exposure = "scene"`).
    pub scene_exposure: f32,
}

/// How far the camera and each object move while the shutter is open (a timed drive with
/// moving traffic; the shutter's time is [`Conditions::motion_blur`] metres at the drive's
/// speed).
#[derive(Clone, Copy, Debug)]
pub struct ShutterMotion<'a> {
    /// How far the eye moves, world metres (x, y, z).
    pub eye: [f32; 3],
    /// The frame's instance ids, row-major.
    pub instance: &'a [u32],
    /// How far object `id` moves, by id (index 0, the sky, and ids beyond: nothing).
    pub moved: &'a [[f32; 3]],
}

/// The developed frame and the exposure multiplier it was taken with.
#[derive(Clone, Debug, PartialEq)]
pub struct Developed {
    pub rgb: RgbImage,
    pub exposure: f32,
}

/// Develops `frame` under `c`. A frame whose buffers do not match its size is developed
/// as black.
pub fn develop(frame: &SensorFrame, c: &Conditions) -> Developed {
    let (w, h) = (frame.width, frame.height);
    let n = w as usize * h as usize;
    if frame.linear.len() != n || frame.depth.len() != n || n == 0 {
        return Developed {
            rgb: RgbImage::new(w, h),
            exposure: 1.0,
        };
    }
    let mut light = frame.linear.to_vec();
    if let Some(rays) = Rays::new(&frame.pose, frame.intrinsics) {
        clouds::draw_clouds(
            &mut light,
            frame.depth,
            w,
            &rays,
            &frame.clouds,
            c.clouds as f32,
            c.cloud_offset,
        );
        weather::apply_weather(&mut light, frame.depth, w, &rays, frame.horizon, c);
        if let Some(m) = frame.shutter {
            let moved = (m.instance, m.moved);
            optics::moving_blur(&mut light, frame.depth, w, &rays, m.eye, moved);
        } else {
            let motion = frame
                .motion
                .unwrap_or(frame.pose.basis().map_or([0.0; 3], |b| b.forward));
            optics::motion_blur(
                &mut light,
                frame.depth,
                w,
                &rays,
                motion.map(|v| v as f32),
                c.motion_blur as f32,
            );
        }
    }
    optics::chromatic_aberration(&mut light, w, c.chromatic_aberration as f32);
    optics::vignette(&mut light, w, c.vignetting as f32);
    let stops = libm::exp2(c.ev) as f32;
    let exposure = match c.exposure {
        ExposureMode::Scene => frame.scene_exposure * stops,
        ExposureMode::Auto => auto_exposure(&light, w) * stops,
        ExposureMode::Fixed => stops,
    };
    for p in &mut light {
        *p = p.map(|v| v * exposure);
    }
    noise::add_noise(&mut light, w, c.noise as f32, c.shot_noise as f32, c.seed);
    let mut rgb = tone_map(&light, w, h);
    if let Some(quality) = c.jpeg_quality {
        rgb = jpeg_round_trip(rgb, quality);
    }
    Developed { rgb, exposure }
}

/// The image after JPEG compression at `quality` and decompression, in memory.
fn jpeg_round_trip(rgb: RgbImage, quality: u8) -> RgbImage {
    let mut bytes = Vec::new();
    let encoder = image::codecs::jpeg::JpegEncoder::new_with_quality(&mut bytes, quality);
    if rgb.write_with_encoder(encoder).is_err() {
        return rgb;
    }
    match image::load_from_memory_with_format(&bytes, ImageFormat::Jpeg) {
        Ok(decoded) => decoded.into_rgb8(),
        Err(_) => rgb,
    }
}

/// The unit direction the camera of frame `i` travels in, from its neighbours on the path.
/// A neighbour counts when it is a step of the path, no longer than twice the path's
/// median step (a road tour jumps between roads); of two steps that disagree, the one
/// nearer the view direction wins; with none, the view direction stands in. `None` for a
/// pose without a view direction. [`travel_direction_with`] takes the median step worked
/// out once for the path, where a caller asks for each of its frames.
pub fn travel_direction(poses: &[CameraPose], i: usize) -> Option<[f64; 3]> {
    travel_direction_with(poses, i, median_step(poses))
}

/// The median length of a path's steps between consecutive poses; `None` for fewer than
/// two poses.
pub fn median_step(poses: &[CameraPose]) -> Option<f64> {
    let mut lengths: Vec<f64> = poses
        .windows(2)
        .map(|p| {
            let d = [0, 1, 2].map(|k| p[1].eye[k] - p[0].eye[k]);
            dot(d, d).sqrt()
        })
        .collect();
    lengths.sort_by(f64::total_cmp);
    lengths.get(lengths.len() / 2).copied()
}

/// [`travel_direction`] with the path's [`median_step`] given.
pub fn travel_direction_with(
    poses: &[CameraPose],
    i: usize,
    median: Option<f64>,
) -> Option<[f64; 3]> {
    let step = |a: &CameraPose, b: &CameraPose| [0, 1, 2].map(|k| b.eye[k] - a.eye[k]);
    let pose = poses.get(i)?;
    let forward = pose.basis()?.forward;
    let Some(median) = median else {
        return Some(forward);
    };
    let unit = |d: [f64; 3]| {
        let len = dot(d, d).sqrt();
        (len > 0.0 && len <= 2.0 * median + 1e-9).then(|| d.map(|v| v / len))
    };
    let back = i.checked_sub(1).and_then(|j| unit(step(&poses[j], pose)));
    let ahead = poses.get(i + 1).and_then(|next| unit(step(pose, next)));
    let d = match (back, ahead) {
        (Some(a), Some(b)) if dot(a, b) > 0.7 => [0, 1, 2].map(|k| a[k] + b[k]),
        (Some(a), Some(b)) if dot(a, forward).abs() >= dot(b, forward).abs() => a,
        (Some(_), Some(b)) => b,
        (Some(a), None) | (None, Some(a)) => a,
        (None, None) => forward,
    };
    let len = dot(d, d).sqrt();
    Some(if len > 0.0 {
        d.map(|v| v / len)
    } else {
        forward
    })
}

#[cfg(test)]
mod tests;
