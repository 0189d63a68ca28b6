//! The dataset part of a spec: camera paths, lighting and annotation settings.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::sensor_spec::SensorSpec;

/// One camera path; its frames and annotations go to `frames/<name>/`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CameraSpec {
    /// Name of the path (a folder name).
    #[schemars(regex(pattern = r"^[A-Za-z0-9][A-Za-z0-9_-]{0,63}$"))]
    pub name: String,
    /// `"roads"` drives along the roads in the right-hand lane, through crossings;
    /// `"orbit"` circles the city looking at its centre (an overview).
    #[serde(default)]
    pub path: CameraPath,
    /// Frames on the path, evenly spaced by arc length. Give `frames` or `spacing`, not
    /// both; with neither, 100 frames.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "u32", range(min = 1, max = 100000), extend("default" = 100))]
    pub frames: Option<u32>,
    /// Metres between frames along the path, instead of `frames`: the path takes
    /// max(1, ⌊length / spacing⌋) frames, at most 100000 (a smaller spacing on a long path
    /// is capped there). The length is the driven tour for `"roads"` (every road's stretch
    /// the camera drives, see `look_ahead`), the circle for `"orbit"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.01, max = 100000.0))]
    pub spacing: Option<f64>,
    /// Eye height in metres (roads: a driver's eye; orbit: the flight height).
    #[serde(default = "default_height")]
    #[schemars(range(min = 0.3, max = 5000.0))]
    pub height: f64,
    /// Vertical field of view in degrees.
    #[serde(default = "default_fov")]
    #[schemars(range(min = 10.0, max = 120.0))]
    pub fov: f64,
    /// Image width and height in pixels.
    #[serde(default = "default_resolution")]
    #[schemars(length(min = 2, max = 2), inner(range(min = 16, max = 4096)))]
    pub resolution: Vec<u32>,
    /// How far ahead a roads camera looks, in metres. The camera stops this far before a
    /// road's end, so it never looks past the end; a road shorter than this is skipped
    /// (unless every road is, then all are driven whole).
    #[serde(default = "default_look_ahead")]
    #[schemars(range(min = 1.0, max = 1000.0))]
    pub look_ahead: f64,
    /// Seeded random offset of the look-at point, in metres (yaw and pitch jitter).
    #[serde(default = "default_jitter")]
    #[schemars(range(min = 0.0, max = 50.0))]
    pub jitter: f64,
    /// Distance of a roads camera from the centre line, to the right, in metres.
    #[serde(default = "default_lane_offset")]
    #[schemars(range(min = 0.0, max = 50.0))]
    pub lane_offset: f64,
    /// Samples per pixel side for the colour image (1 = none, 2 = 2×2).
    #[serde(default = "default_supersample")]
    #[schemars(range(min = 1, max = 4))]
    pub supersample: u32,
    /// Exposure, tone curve, noise, compression and lens effects of the RGB image.
    #[serde(default)]
    pub sensor: SensorSpec,
}

/// The most frames one camera path takes (the schema's bound on `frames`, and the cap on
/// a path's frames from `spacing`).
pub const MAX_FRAMES: u32 = 100_000;

/// Frames a path takes with no `frames` and no `spacing`.
pub const DEFAULT_FRAMES: u32 = 100;

impl CameraSpec {
    /// How many frames this path takes: `frames`, or one every `spacing` metres, or the
    /// default count. The semantic checks reject a spec giving both.
    pub fn frame_rule(&self) -> FrameRule {
        match (self.frames, self.spacing) {
            (Some(count), _) => FrameRule::Count(count),
            (None, Some(spacing)) => FrameRule::Spacing(spacing),
            (None, None) => FrameRule::Count(DEFAULT_FRAMES),
        }
    }
}

/// How many frames a camera path takes.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FrameRule {
    /// Exactly this many frames.
    Count(u32),
    /// One frame every this many metres of path.
    Spacing(f64),
}

impl FrameRule {
    /// Frames over a path `length` metres long: the count as given, or
    /// max(1, ⌊length / spacing⌋) capped at [`MAX_FRAMES`]. A spacing that is not a
    /// positive finite number gives 0 frames (no poses).
    pub fn frames(self, length: f64) -> u32 {
        match self {
            FrameRule::Count(count) => count,
            FrameRule::Spacing(spacing) if spacing.is_finite() && spacing > 0.0 => {
                let n = (length / spacing).floor();
                // Comparisons with NaN are false: a NaN length gives one frame.
                if n >= f64::from(MAX_FRAMES) {
                    MAX_FRAMES
                } else if n >= 1.0 {
                    n as u32
                } else {
                    1
                }
            }
            FrameRule::Spacing(_) => 0,
        }
    }
}

/// How a camera moves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum CameraPath {
    // Plain comments: the schema stays a simple enum.
    #[default]
    Roads,
    Orbit,
}

/// Day or night.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LightingSpec {
    /// `"day"`: sun, blue sky. `"night"`: dark sky, lamp lights, glowing lamp heads and a
    /// share of lit windows.
    #[serde(default)]
    pub time: TimeOfDay,
    /// Night: the share of facade windows that are lit.
    #[serde(default = "default_lit_windows")]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub lit_windows: f64,
    /// Night: how far a street lamp's light reaches, in metres.
    #[serde(default = "default_lamp_range")]
    #[schemars(range(min = 1.0, max = 200.0))]
    pub lamp_range: f64,
}

impl Default for LightingSpec {
    fn default() -> Self {
        LightingSpec {
            time: TimeOfDay::Day,
            lit_windows: default_lit_windows(),
            lamp_range: default_lamp_range(),
        }
    }
}

/// Time of day.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum TimeOfDay {
    // Plain comments: the schema stays a simple enum.
    #[default]
    Day,
    Night,
}

/// What the annotations keep.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AnnotationsSpec {
    /// Object classes to annotate (the scene's `building`, `lamp`, … and the labels of
    /// `[[objects]]`). Empty: every `[[objects]]` label, and `lamp`.
    #[serde(default)]
    pub classes: Vec<String>,
    /// Objects showing fewer pixels are left out.
    #[serde(default = "default_min_pixels")]
    #[schemars(range(min = 1, max = 1000000))]
    pub min_pixels: u64,
    /// Objects showing less than this share of themselves are left out: hidden behind
    /// others or cut off by the image edge.
    #[serde(default = "default_min_fraction")]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub min_fraction: f64,
    /// Also write YOLO txt files (`class cx cy w h`, normalised) beside the frames.
    #[serde(default)]
    pub yolo: bool,
}

impl Default for AnnotationsSpec {
    fn default() -> Self {
        AnnotationsSpec {
            classes: Vec::new(),
            min_pixels: default_min_pixels(),
            min_fraction: default_min_fraction(),
            yolo: false,
        }
    }
}

fn default_height() -> f64 {
    1.6
}
fn default_fov() -> f64 {
    60.0
}
fn default_resolution() -> Vec<u32> {
    vec![640, 480]
}
fn default_look_ahead() -> f64 {
    // Far enough that the last frame before a road's end at the layout border still has
    // buildings in view: they stand some 20–28 m to the side, and a 60° × 45° view takes
    // in a building that far aside only beyond about 26 m.
    50.0
}
fn default_jitter() -> f64 {
    0.5
}
fn default_lane_offset() -> f64 {
    4.0
}
fn default_supersample() -> u32 {
    1
}
fn default_lit_windows() -> f64 {
    0.3
}
fn default_lamp_range() -> f64 {
    25.0
}
fn default_min_pixels() -> u64 {
    16
}
fn default_min_fraction() -> f64 {
    0.1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spacing_gives_whole_frames_within_bounds() {
        let cases: &[(FrameRule, f64, u32)] = &[
            (FrameRule::Count(7), 1000.0, 7),
            (FrameRule::Count(7), 0.0, 7),
            (FrameRule::Spacing(10.0), 1000.0, 100),
            // Floor: the frames are at least `spacing` apart.
            (FrameRule::Spacing(10.0), 1009.9, 100),
            (FrameRule::Spacing(3.0), 10.0, 3),
            // At least one frame, however short the path.
            (FrameRule::Spacing(10.0), 4.0, 1),
            (FrameRule::Spacing(10.0), 0.0, 1),
            (FrameRule::Spacing(10.0), f64::NAN, 1),
            // At most MAX_FRAMES, however long the path.
            (FrameRule::Spacing(0.01), 5000.0, MAX_FRAMES),
            (FrameRule::Spacing(1.0), f64::INFINITY, MAX_FRAMES),
            // A spacing that is no distance gives no frames.
            (FrameRule::Spacing(0.0), 100.0, 0),
            (FrameRule::Spacing(-1.0), 100.0, 0),
            (FrameRule::Spacing(f64::NAN), 100.0, 0),
        ];
        for &(rule, length, frames) in cases {
            assert_eq!(rule.frames(length), frames, "{rule:?} over {length} m");
        }
    }
}
