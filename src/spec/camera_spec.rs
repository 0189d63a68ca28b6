//! The dataset part of a spec: camera paths, lighting and annotation settings.

use schemars::{JsonSchema, Schema, SchemaGenerator};
use serde::{Deserialize, Serialize};

use super::lidar_spec::LidarSpec;
use super::lighting_spec::LightingSpec;
use super::sensor_spec::SensorSpec;
use super::value_range::{ValueRange, range_schema};
use super::weather_spec::WeatherSpec;

/// One camera path; its frames and annotations go to `frames/<name>/`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CameraSpec {
    /// Name of the path (a folder name).
    #[schemars(regex(pattern = r"^[A-Za-z0-9][A-Za-z0-9_-]{0,63}$"))]
    pub name: String,
    /// `"roads"` drives along the roads in the right-hand lane, through crossings;
    /// `"sidewalks"` walks the sidewalks clockwise around each block (the block on the
    /// right); `"objects"` looks at objects of `classes` from free space around them;
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
    /// Eye height in metres (roads: a driver's eye; sidewalks, objects: a pedestrian's;
    /// orbit: the flight height): a number, or a range `[low, high]` drawn per frame.
    #[serde(default = "default_height")]
    #[schemars(schema_with = "height_schema", extend("default" = 1.6))]
    pub height: ValueRange,
    /// Yaw in degrees, a number or a range drawn per frame, positive to the right: roads
    /// and sidewalks turn from the direction of travel (default 0 on roads, [-120, 120] on
    /// sidewalks, so a walk looks at shop fronts on the right and the street on the
    /// left); objects turn the aim from the line of sight to the target (default
    /// [-15, 15], so the target is not always in the centre). Orbit: unused. On roads, a
    /// drawn aim whose view one vehicle within 8 m fills more than half of is drawn again
    /// (up to 8 draws, then the least filled); on sidewalks, one whose view is more than
    /// 30 % nearer than 2 m (a wall, a trunk, a car door).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(schema_with = "heading_schema")]
    pub heading: Option<ValueRange>,
    /// Pitch in degrees, positive up, a number or a range drawn per frame: from the
    /// horizontal on roads (default -5.7, a tenth of the look-ahead down) and sidewalks
    /// (default [-10, 10]); objects tilt the aim from the line of sight to the target
    /// (default [-8, 8]). Orbit: unused.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(schema_with = "pitch_schema")]
    pub pitch: Option<ValueRange>,
    /// Roll in degrees about the view direction, positive clockwise (the horizon tilts
    /// anticlockwise in the image), a number or a range drawn per frame. Default 0.
    /// Orbit: unused.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(schema_with = "roll_schema")]
    pub roll: Option<ValueRange>,
    /// Objects path: the classes (the scene's `lamp`, … and `[[objects]]` labels) whose
    /// objects the frames aim at, one object per frame, drawn.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub classes: Vec<String>,
    /// Objects path: the eye's horizontal distance from the target in metres, a number or
    /// a range drawn per frame.
    #[serde(default = "default_distance")]
    #[schemars(schema_with = "distance_schema", extend("default" = [4.0, 12.0]))]
    pub distance: ValueRange,
    /// Objects path: the bearing in degrees of the eye around the target, from the
    /// target's front (the way its textured face looks; any bearing for an object without
    /// one), a number or a range drawn per frame.
    #[serde(default = "default_angle")]
    #[schemars(schema_with = "angle_schema", extend("default" = [-60.0, 60.0]))]
    pub angle: ValueRange,
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
    /// Roads path: a timed drive at this many frames a second. Frame `i` is at `i / fps`
    /// seconds, `speed_kmh · i / fps` metres along one road from a seeded start, so
    /// consecutive frames are one time step apart; the aim (heading, pitch, roll, height)
    /// and the jitter are drawn once for the whole drive, and no frame is skipped for a
    /// vehicle in front (it may pass close to parked cars). The time is written in
    /// `poses.json` and in COCO `images[].time`, and the path's folder is a MOT Challenge
    /// sequence (`gt/gt.txt`, `seqinfo.ini`). Without it, frames are spread over the
    /// whole tour.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.1, max = 120.0))]
    pub fps: Option<f64>,
    /// Roads path with `fps`: the speed of the drive, km/h (default 30).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 1.0, max = 200.0), extend("default" = 30.0))]
    pub speed_kmh: Option<f64>,
    /// Roads path: whether the camera's own car shines its headlights (two dipped beams
    /// along the direction of travel, lighting the road ahead) once the street lamps come
    /// on; off by day whatever this says. Other paths have none.
    #[serde(default = "default_headlights")]
    pub headlights: bool,
    /// Samples per pixel side for the colour image (1 = none, 2 = 2×2).
    #[serde(default = "default_supersample")]
    #[schemars(range(min = 1, max = 4))]
    pub supersample: u32,
    /// How `depth/` is written: `"cm16"` (16-bit PNG, centimetres, up to 655.35 m),
    /// `"mm16"` (16-bit PNG, millimetres, up to 65.535 m) or `"f32"` (32-bit float metres
    /// in a `.npy`, any distance). 0 is the sky in all three.
    #[serde(default)]
    pub depth: DepthFormat,
    /// Also write surface normals, `normals/NNNNNN.png`: per pixel the face normal of the
    /// rendered triangle there, in camera axes (x right, y down, z forward), turned towards
    /// the camera, as a 16-bit RGB PNG with `n = value / 65535 · 2 − 1`; `(0, 0, 0)` is the
    /// sky. Off, nothing is worked out and it stays out of the stage keys.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub normals: bool,
    /// Also write 3D boxes of the annotated objects in the KITTI object format,
    /// `label_2/NNNNNN.txt` and `calib/NNNNNN.txt`, and each box as COCO
    /// `attributes.box3d`. Off, no box is worked out and it stays out of the stage keys.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub kitti: bool,
    /// Also write the 17 COCO keypoints of every person and rider annotated, in COCO's
    /// `person_keypoints` form (`keypoints`, `num_keypoints`; the category's `keypoints`
    /// and `skeleton`), each flagged visible or hidden by the depth image. Off, none is
    /// worked out and it stays out of the stage keys.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub keypoints: bool,
    /// Roads path with `fps` (a timed drive): also write each frame's forward optical flow
    /// to the next frame, `flow/NNNNNN.png` in the KITTI flow encoding (16-bit RGB,
    /// `u = (R − 2¹⁵) / 64`, `v = (G − 2¹⁵) / 64`, B = 1 where valid), for every frame but
    /// the last: the camera's motion over the frame's depth and, with `[traffic]`, each
    /// point moving with its object; a point the next frame does not see is not valid. Off, nothing is
    /// worked out and it stays out of the stage keys.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub flow: bool,
    /// A rotating LiDAR at the camera's eye, scanning once a frame (see its table). Off,
    /// nothing is ray-cast and it stays out of the stage keys.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lidar: Option<LidarSpec>,
    /// Classes this path annotates, instead of `[annotations] classes` (for example
    /// `["building", "road"]` for a camera looking down on the city).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub label_classes: Option<Vec<String>>,
    /// Exposure, tone curve, noise, compression and lens effects of the RGB image.
    #[serde(default)]
    pub sensor: SensorSpec,
    /// This path's lighting instead of the spec's `[lighting]`: it replaces that table
    /// whole (keys it does not write take their defaults, not the spec-wide values).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lighting: Option<LightingSpec>,
    /// This path's weather instead of the spec's `[weather]`, replacing it whole.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weather: Option<WeatherSpec>,
}

/// How a camera path's depth images are written.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum DepthFormat {
    // Plain comments: the schema stays a simple enum.
    // 16-bit PNG, centimetres (0.01 m per unit), saturating at 655.35 m.
    #[default]
    Cm16,
    // 16-bit PNG, millimetres (0.001 m per unit), saturating at 65.535 m.
    Mm16,
    // .npy of little-endian float32 metres, shape (height, width).
    F32,
}

impl DepthFormat {
    /// The spec's name of the format.
    pub fn name(self) -> &'static str {
        match self {
            DepthFormat::Cm16 => "cm16",
            DepthFormat::Mm16 => "mm16",
            DepthFormat::F32 => "f32",
        }
    }

    /// Metres per stored unit: depth in metres = stored value × scale.
    pub fn scale(self) -> f64 {
        match self {
            DepthFormat::Cm16 => 0.01,
            DepthFormat::Mm16 => 0.001,
            DepthFormat::F32 => 1.0,
        }
    }

    /// File extension of the depth images.
    pub fn extension(self) -> &'static str {
        match self {
            DepthFormat::Cm16 | DepthFormat::Mm16 => "png",
            DepthFormat::F32 => "npy",
        }
    }
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
    Sidewalks,
    Objects,
    Orbit,
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
    /// Also write YOLO txt files (`class cx cy w h`, normalised) beside the frames, and
    /// `yolo/classes.txt` naming the class ids.
    #[serde(default)]
    pub yolo: bool,
    /// YOLO: one class per sign type (`traffic_sign/stop`, `traffic_sign/yield`, …)
    /// instead of one per sign label. COCO always has the type as `attributes.sign_type`.
    #[serde(default)]
    pub yolo_sign_types: bool,
    /// COCO and YOLO: one category per sign type, named `<label>/<type>`
    /// (`traffic_sign/stop`, …), in place of each sign label's one category. Every type
    /// of the catalogue gets its category, drawn or not, in catalogue order, so a type's
    /// id stays the same whatever the entries' `signs` lists; YOLO's classes are then the
    /// COCO categories one to one. Off, it stays out of the stage keys.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub sign_categories: bool,
    /// Also write Cityscapes-format labels per frame (`frames/<camera>/semantic/`: label
    /// ids, instance ids, colours, COCO panoptic) and `panoptic.json`, and with `[splits]`
    /// the Cityscapes folder `cityscapes/` (`leftImg8bit/`, `gtFine/`).
    /// Off, it stays out of the stage keys (which are then as before the switch existed).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub cityscapes: bool,
}

impl Default for AnnotationsSpec {
    fn default() -> Self {
        AnnotationsSpec {
            classes: Vec::new(),
            min_pixels: default_min_pixels(),
            min_fraction: default_min_fraction(),
            yolo: false,
            yolo_sign_types: false,
            sign_categories: false,
            cityscapes: false,
        }
    }
}

fn default_height() -> ValueRange {
    ValueRange::Fixed(1.6)
}
fn default_distance() -> ValueRange {
    ValueRange::Between([4.0, 12.0])
}
fn default_angle() -> ValueRange {
    ValueRange::Between([-60.0, 60.0])
}
fn height_schema(_: &mut SchemaGenerator) -> Schema {
    range_schema(0.3, 5000.0)
}
fn heading_schema(_: &mut SchemaGenerator) -> Schema {
    range_schema(-180.0, 180.0)
}
fn pitch_schema(_: &mut SchemaGenerator) -> Schema {
    range_schema(-89.0, 89.0)
}
fn roll_schema(_: &mut SchemaGenerator) -> Schema {
    range_schema(-90.0, 90.0)
}
fn distance_schema(_: &mut SchemaGenerator) -> Schema {
    range_schema(0.5, 1000.0)
}
fn angle_schema(_: &mut SchemaGenerator) -> Schema {
    range_schema(-180.0, 180.0)
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
fn default_headlights() -> bool {
    true
}
fn default_lane_offset() -> f64 {
    4.0
}
fn default_supersample() -> u32 {
    1
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
