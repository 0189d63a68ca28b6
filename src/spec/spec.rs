//! The spec's Rust types: what a `cityspec` TOML file may say, with defaults and ranges.
//!
//! These types are the single source of truth: `schemas/cityspec.schema.json` is generated
//! from them (and a test keeps the committed copy in sync). Every table denies unknown keys.
//! Lengths on the layout image are in pixels; lengths in the world are in metres.

use std::borrow::Cow;
use std::fmt;

use schemars::{JsonSchema, Schema, SchemaGenerator, json_schema};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::camera_spec::{AnnotationsSpec, CameraSpec};
use super::lighting_spec::LightingSpec;
use super::limits_spec::LimitsSpec;
use super::object_spec::ObjectSpec;
use super::output_spec::OutputSpec;
use super::splits_spec::SplitsSpec;
use super::traffic_spec::TrafficSpec;
use super::weather_spec::WeatherSpec;
use crate::model::PixelClass;

/// The spec format version this build of cityspec reads.
pub const SPEC_VERSION: u32 = 1;

/// A cityspec spec: one city, one dataset.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(title = "cityspec spec")]
pub struct Spec {
    /// Spec format version. This cityspec reads version 1.
    #[schemars(range(min = 1, max = 1))]
    pub version: u32,
    /// Name of the city; the build writes to `out/<name>/` by default.
    #[schemars(regex(pattern = r"^[A-Za-z0-9][A-Za-z0-9_.-]{0,63}$"))]
    pub name: String,
    /// Seed of every random choice. The same seed gives the same bytes.
    #[serde(default)]
    pub seed: u64,
    /// Where the layout image comes from and how it is read.
    pub layout: LayoutSpec,
    /// Facades that clad the buildings and set their size (paper 3.2).
    #[serde(default)]
    pub facades: FacadesSpec,
    /// Building placement (paper Algorithm 1).
    #[serde(default)]
    pub buildings: BuildingsSpec,
    /// Inserted object classes: text on walls, traffic signs, user meshes.
    #[serde(default)]
    #[schemars(length(max = 64))]
    pub objects: Vec<ObjectSpec>,
    /// Street lamp sites along the roads.
    #[serde(default)]
    pub lamps: LampsSpec,
    /// Camera paths: each renders frames with annotations into `frames/<name>/`.
    #[serde(default)]
    #[schemars(length(max = 64))]
    pub cameras: Vec<CameraSpec>,
    /// Day or night.
    #[serde(default)]
    pub lighting: LightingSpec,
    /// Clear, overcast, fog or rain, fixed or drawn per frame.
    #[serde(default)]
    pub weather: WeatherSpec,
    /// What the annotations keep.
    #[serde(default)]
    pub annotations: AnnotationsSpec,
    /// What a build may cost (memory, frame bytes) before validation refuses it.
    #[serde(default)]
    pub limits: LimitsSpec,
    /// How the frames are written: one file per image, or WebDataset tar shards.
    #[serde(default)]
    pub output: OutputSpec,
    /// Train, val and test: the dataset-level files (`coco/<split>.json`, and with
    /// `[annotations] yolo = true` the ultralytics folder `yolo/`). Absent: neither.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "SplitsSpec")]
    pub splits: Option<SplitsSpec>,
    /// Traffic that moves on timed drives: lane cars and ridden bicycles along their
    /// lanes, through signalled junctions. Absent: nothing moves.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "TrafficSpec")]
    pub traffic: Option<TrafficSpec>,
}

/// The layout: generated (paper 3.1) or drawn by the user, then mirrored (paper 3.3).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LayoutSpec {
    /// Generate a layout at random from the seed. Give either `generate` or `image`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "GenerateSpec")]
    pub generate: Option<GenerateSpec>,
    /// A layout image drawn with the palette (PNG or JPEG), relative to the spec's folder.
    /// Give either `generate` or `image`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "String", length(min = 1))]
    pub image: Option<String>,
    /// An OpenStreetMap extract to build a real place from (issue 43): its buildings on
    /// their footprints at their heights, its roads at any angle. Give one of `generate`,
    /// `image` and `osm`. With a map, `metres_per_pixel`, `mirror` and `palette` do not
    /// apply (the map is in metres), nor `[buildings]` unless `fill_empty_blocks` is on;
    /// lamps stand where the map has them and `[lamps]` seeds the stretches it has none on
    /// (unless `seed_lamps` is off); cameras take the `roads`, `sidewalks` and `objects`
    /// paths, and `[traffic]` does not apply (see docs/osm.md).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub osm: Option<OsmLayoutSpec>,
    /// Mirror operations applied in order, each appending a flipped copy:
    /// 1 flips vertically (copy below), 2 horizontally (copy to the right), 3 both (2 then 1).
    /// `[2, 1]` turns one layout into a 2×2 city.
    #[serde(default)]
    #[schemars(inner(range(min = 1, max = 3)), length(max = 8))]
    pub mirror: Vec<u8>,
    /// Colours the layout is drawn with.
    #[serde(default)]
    pub palette: Palette,
    /// Metres per layout pixel. The default, 0.55, makes the paper's 32 px roads 17.6 m
    /// streets (2 + 2 lanes of 3.1 m and a 2.6 m parking lane at each curb) and its 8 px
    /// lamp strips 4.4 m sidewalks; the paper itself draws 1 px = 1 m (32 m carriageways,
    /// 8 m sidewalks).
    #[serde(default = "default_metres_per_pixel")]
    #[schemars(range(min = 0.05, max = 100.0))]
    pub metres_per_pixel: f64,
}

/// An OpenStreetMap extract as a layout.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OsmLayoutSpec {
    /// The extract, `.osm.pbf` or OSM XML, relative to the spec's folder.
    #[schemars(length(min = 1))]
    pub file: String,
    /// The box to build, `[south, west, north, east]` in degrees; without it the file's
    /// own bounds (else the extent of its nodes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bbox: Option<[f64; 4]>,
    /// Fills every block the map has no building in with buildings placed by the paper's
    /// Algorithm 1, sized as `[buildings]` says (by default one size per facade, which
    /// then gives the building its facade and height), keeping off the map's open ground
    /// (parks, lawns, woods, squares, car parks). Off by default: in a well-mapped city such a block is a
    /// park, a square or a yard; turn it on where the map is sparse and its houses are not
    /// mapped.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub fill_empty_blocks: bool,
    /// Seeds street lamps along the stretches of paved road the map has no lamp on, as
    /// `[lamps]` says (every `spacing` metres on both sides, behind the kerb). On by
    /// default, as few cities map their lamps; off, lamps stand only where the map has
    /// them.
    #[serde(default = "default_true", skip_serializing_if = "is_true")]
    pub seed_lamps: bool,
}

fn default_true() -> bool {
    true
}

fn is_true(value: &bool) -> bool {
    *value
}

impl OsmLayoutSpec {
    /// The box, if given.
    pub fn geo_box(&self) -> Option<crate::model::GeoBox> {
        self.bbox
            .map(|[south, west, north, east]| crate::model::GeoBox {
                south,
                west,
                north,
                east,
            })
    }
}

/// Parameters of the random layout generator (paper 3.1). Lengths in pixels.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GenerateSpec {
    /// Image width.
    #[serde(default = "default_size")]
    #[schemars(range(min = 64, max = 8192))]
    pub width: u32,
    /// Image height.
    #[serde(default = "default_size")]
    #[schemars(range(min = 64, max = 8192))]
    pub height: u32,
    /// Width of every road.
    #[serde(default = "default_road_width")]
    #[schemars(range(min = 4, max = 256))]
    pub road_width: u32,
    /// Width of the lamp strip ringing every block.
    #[serde(default = "default_strip_width")]
    #[schemars(range(min = 2, max = 64))]
    pub strip_width: u32,
    /// Number of roads running left to right.
    #[serde(default = "default_roads")]
    #[schemars(range(max = 64))]
    pub horizontal_roads: u32,
    /// Number of roads running top to bottom.
    #[serde(default = "default_roads")]
    #[schemars(range(max = 64))]
    pub vertical_roads: u32,
    /// Smallest side of a block's blue area.
    #[serde(default = "default_min_block")]
    #[schemars(range(min = 8, max = 4096))]
    pub min_block: u32,
}

impl Default for GenerateSpec {
    fn default() -> Self {
        GenerateSpec {
            width: default_size(),
            height: default_size(),
            road_width: default_road_width(),
            strip_width: default_strip_width(),
            horizontal_roads: default_roads(),
            vertical_roads: default_roads(),
            min_block: default_min_block(),
        }
    }
}

/// The layout's colours. Parsing maps every pixel to the nearest palette colour within
/// `tolerance`, so anti-aliased or JPEG-saved drawings still parse.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Palette {
    /// Road surface.
    #[serde(default = "default_road")]
    pub road: Color,
    /// One-pixel centre line of each road.
    #[serde(default = "default_line")]
    pub line: Color,
    /// Building blocks.
    #[serde(default = "default_block")]
    pub block: Color,
    /// Lamp strips around the blocks.
    #[serde(default = "default_strip")]
    pub strip: Color,
    /// Largest RGB distance (Euclidean, 0–441) at which a pixel still takes a palette colour.
    #[serde(default = "default_tolerance")]
    #[schemars(range(min = 0, max = 441))]
    pub tolerance: u32,
}

impl Default for Palette {
    fn default() -> Self {
        Palette {
            road: default_road(),
            line: default_line(),
            block: default_block(),
            strip: default_strip(),
            tolerance: default_tolerance(),
        }
    }
}

impl Palette {
    /// The class of the palette colour nearest to `rgb` (never [`PixelClass::Other`];
    /// Euclidean RGB; ties go to the earlier of road, line, block, strip) and its squared
    /// distance. The one rule every stage that reads a layout image shares.
    pub fn nearest(&self, rgb: [u8; 3]) -> (PixelClass, u32) {
        let candidates = [
            (PixelClass::Road, self.road),
            (PixelClass::Line, self.line),
            (PixelClass::Block, self.block),
            (PixelClass::Strip, self.strip),
        ];
        let mut best = (PixelClass::Road, u32::MAX);
        for (colour, Color(c)) in candidates {
            let d: u32 = (0..3)
                .map(|i| (i32::from(rgb[i]) - i32::from(c[i])).pow(2) as u32)
                .sum();
            if d < best.1 {
                best = (colour, d);
            }
        }
        best
    }

    /// The class `rgb` shows: the nearest palette colour's if within `tolerance`, else
    /// [`PixelClass::Other`].
    pub fn classify(&self, rgb: [u8; 3]) -> PixelClass {
        let (class, d) = self.nearest(rgb);
        if u64::from(d) <= u64::from(self.tolerance).pow(2) {
            class
        } else {
            PixelClass::Other
        }
    }
}

/// Buildings for paper Algorithm 1. Lengths in metres.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BuildingsSpec {
    /// Footprint widths (square footprints) to choose from. When absent, as in the paper,
    /// every facade of the facade set is one building size: its metric width. When given,
    /// buildings take these sizes and a seeded choice of facade, tiled along the wall.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(
        with = "Vec<f64>",
        length(min = 1, max = 256),
        inner(range(min = 1.0, max = 500.0))
    )]
    pub widths: Option<Vec<f64>>,
    /// Gap between neighbouring buildings.
    #[serde(default = "default_gap")]
    #[schemars(range(min = 0.0, max = 100.0))]
    pub gap: f64,
}

impl Default for BuildingsSpec {
    fn default() -> Self {
        BuildingsSpec {
            widths: None,
            gap: default_gap(),
        }
    }
}

/// The `facades.source` that names cityspec's own generated facade set.
pub const BUILTIN_FACADES: &str = "builtin";

/// Facades (paper 3.2): cityspec's generated set, or a folder in the CMP Facade Database
/// layout (`<name>.jpg` photo + `<name>.xml` boxes, optional `<name>.png` label mask).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FacadesSpec {
    /// `"builtin"`, or a folder in the CMP layout, relative to the spec's folder.
    #[serde(default = "default_facade_source")]
    #[schemars(length(min = 1))]
    pub source: String,
    /// Height of one floor in metres: a facade of h floors makes a building h × this tall.
    #[serde(default = "default_floor_height")]
    #[schemars(range(min = 2.0, max = 10.0))]
    pub floor_height: f64,
    /// A side file in the facade folder giving each facade's floors, one `name floors` per
    /// line (the paper counted floors by hand). Facades it does not list get their floors
    /// estimated from the rows of their window boxes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "String", length(min = 1))]
    pub floors: Option<String>,
    /// A facade with bad data (no XML, no window boxes, an unreadable image): `"error"`
    /// stops the build naming the file; `"skip"` warns and leaves the facade out.
    #[serde(default)]
    pub on_error: OnError,
}

impl Default for FacadesSpec {
    fn default() -> Self {
        FacadesSpec {
            source: default_facade_source(),
            floor_height: default_floor_height(),
            floors: None,
            on_error: OnError::Error,
        }
    }
}

/// What to do with bad input data.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum OnError {
    // Plain comments, not doc comments: so the schema is a simple `enum` and a wrong value
    // reads "expected one of …".
    // Stop with an error naming the file.
    #[default]
    Error,
    // Warn, and leave the item out.
    Skip,
}

/// Street lamp sites. Lengths in metres.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LampsSpec {
    /// Distance between lamps along each side of a road, metres (the paper: every 100 layout
    /// pixels, which is 100 m at the default 1 m a pixel).
    #[serde(default = "default_spacing")]
    #[schemars(range(min = 1.0, max = 10000.0))]
    pub spacing: f64,
    /// Of two lamps closer than this, one is removed.
    #[serde(default = "default_min_distance")]
    #[schemars(range(min = 0.0, max = 10000.0))]
    pub min_distance: f64,
}

impl Default for LampsSpec {
    fn default() -> Self {
        LampsSpec {
            spacing: default_spacing(),
            min_distance: default_min_distance(),
        }
    }
}

/// An sRGB colour, written `"#rrggbb"`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Color(pub [u8; 3]);

impl Color {
    /// Parses `#rrggbb` (either case).
    pub fn parse(text: &str) -> Option<Color> {
        let hex = text.strip_prefix('#')?;
        if hex.len() != 6 || !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
            return None;
        }
        let channel = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).ok();
        Some(Color([channel(0)?, channel(2)?, channel(4)?]))
    }
}

impl fmt::Display for Color {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [r, g, b] = self.0;
        write!(f, "#{r:02x}{g:02x}{b:02x}")
    }
}

impl Serialize for Color {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}

impl<'de> Deserialize<'de> for Color {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let text = String::deserialize(deserializer)?;
        Color::parse(&text).ok_or_else(|| {
            serde::de::Error::custom(format!(
                "expected a colour like \"#80a0ff\", found {text:?}"
            ))
        })
    }
}

impl JsonSchema for Color {
    fn schema_name() -> Cow<'static, str> {
        "Color".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "An sRGB colour written \"#rrggbb\".",
            "type": "string",
            "pattern": "^#[0-9a-fA-F]{6}$"
        })
    }
}

fn default_metres_per_pixel() -> f64 {
    0.55
}
fn default_size() -> u32 {
    768
}
fn default_road_width() -> u32 {
    32
}
fn default_strip_width() -> u32 {
    8
}
fn default_roads() -> u32 {
    3
}
fn default_min_block() -> u32 {
    64
}
fn default_road() -> Color {
    Color([128, 128, 128])
}
fn default_line() -> Color {
    Color([255, 220, 0])
}
fn default_block() -> Color {
    Color([40, 80, 220])
}
fn default_strip() -> Color {
    Color([40, 170, 60])
}
fn default_tolerance() -> u32 {
    80
}
fn default_facade_source() -> String {
    BUILTIN_FACADES.to_owned()
}
fn default_floor_height() -> f64 {
    3.0
}
fn default_gap() -> f64 {
    2.0
}
fn default_spacing() -> f64 {
    100.0
}
fn default_min_distance() -> f64 {
    20.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn palette_classifies_by_nearest_colour_within_tolerance() {
        let palette = Palette::default();
        let cases = [
            ([128, 128, 128], PixelClass::Road),
            ([255, 220, 0], PixelClass::Line),
            ([40, 80, 220], PixelClass::Block),
            ([40, 170, 60], PixelClass::Strip),
            ([50, 160, 70], PixelClass::Strip), // JPEG-ish noise
            ([255, 255, 255], PixelClass::Other),
            ([0, 0, 0], PixelClass::Other),
        ];
        for (rgb, want) in cases {
            assert_eq!(palette.classify(rgb), want, "{rgb:?}");
        }
        let strict = Palette {
            tolerance: 0,
            ..Palette::default()
        };
        assert_eq!(strict.classify([41, 170, 60]), PixelClass::Other);
        assert_eq!(strict.classify([40, 170, 60]), PixelClass::Strip);
    }
}
