//! `[lighting]` table → [`LightingSpec`]: time of day or the sun's angles (each a value or a
//! seeded range), sky turbidity, shadows, lamps and lit windows; and its semantic checks.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::findings::Findings;

/// The light of a city's frames.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LightingSpec {
    /// `"day"` (sun high in the south-east), `"dusk"` (sun just above the western horizon,
    /// lamps on), `"night"` (dark sky, lamp lights, lit windows), or an hour of local solar
    /// time 0–24 (the sun from the NOAA solar-position equations, with `day_of_year` and
    /// `latitude`), or a range of hours `[from, to]` drawn per `vary`.
    #[serde(default)]
    pub time: TimeOfDay,
    /// Sun elevation above the horizon in degrees (−90–90), or a range `[low, high]`.
    /// Given with `sun_azimuth`, it replaces the sun that `time` sets.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sun_elevation: Option<Span>,
    /// Sun azimuth in degrees clockwise from north (0–360: 90 = east, 180 = south), or a
    /// range `[low, high]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sun_azimuth: Option<Span>,
    /// For an hour: the day of the year, 1–366.
    #[serde(default = "default_day_of_year")]
    #[schemars(range(min = 1.0, max = 366.0))]
    pub day_of_year: f64,
    /// For an hour: the latitude in degrees, −90–90 (north positive).
    #[serde(default = "default_latitude")]
    #[schemars(range(min = -90.0, max = 90.0))]
    pub latitude: f64,
    /// When a range is drawn: once per camera path (`"path"`) or for every frame
    /// (`"frame"`). Drawn values are written in each frame's COCO image entry and poses.json.
    #[serde(default)]
    pub vary: Vary,
    /// Haze of the daylight sky (Preetham's turbidity): 2 very clear, 3 clear, 6 hazy.
    #[serde(default = "default_turbidity")]
    #[schemars(range(min = 1.7, max = 10.0))]
    pub turbidity: f64,
    /// Cast sun shadows (a shadow map over the whole city).
    #[serde(default = "default_true")]
    pub shadows: bool,
    /// After dusk: the share of facade windows that are lit.
    #[serde(default = "default_lit_windows")]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub lit_windows: f64,
    /// After dusk: how far a street lamp's light reaches, in metres.
    #[serde(default = "default_lamp_range")]
    #[schemars(range(min = 1.0, max = 200.0))]
    pub lamp_range: f64,
}

impl Default for LightingSpec {
    fn default() -> Self {
        LightingSpec {
            time: TimeOfDay::default(),
            sun_elevation: None,
            sun_azimuth: None,
            day_of_year: default_day_of_year(),
            latitude: default_latitude(),
            vary: Vary::default(),
            turbidity: default_turbidity(),
            shadows: true,
            lit_windows: default_lit_windows(),
            lamp_range: default_lamp_range(),
        }
    }
}

/// A time of day: a preset, an hour, or a range of hours.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum TimeOfDay {
    Preset(TimePreset),
    Hour(f64),
    Hours([f64; 2]),
}

impl Default for TimeOfDay {
    fn default() -> Self {
        TimeOfDay::Preset(TimePreset::Day)
    }
}

/// The named times of day.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum TimePreset {
    // Plain comments: the schema stays a simple enum.
    #[default]
    Day,
    Dusk,
    Night,
}

/// A number, or a range `[low, high]` drawn uniformly from a seeded stream.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum Span {
    Value(f64),
    Range([f64; 2]),
}

impl Span {
    /// `[low, high]`; a value is a range of one.
    pub fn bounds(self) -> [f64; 2] {
        match self {
            Span::Value(v) => [v, v],
            Span::Range(r) => r,
        }
    }

    /// The value at `t` in [0, 1) across the range.
    pub fn at(self, t: f64) -> f64 {
        let [lo, hi] = self.bounds();
        lo + (hi - lo) * t
    }
}

/// When ranges of `[lighting]` are drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Vary {
    // Plain comments: the schema stays a simple enum.
    #[default]
    Path,
    Frame,
}

/// Values within their bounds, ranges with low ≤ high, and the sun's two angles together.
/// `at` is the table's key path: `lighting`, or `cameras[i].lighting` for a camera's own.
pub(crate) fn check_lighting(lighting: &LightingSpec, at: &str, findings: &mut Findings<'_, '_>) {
    let mut span = |key: &str, span: Option<Span>, lo: f64, hi: f64| {
        let Some(span) = span else { return };
        let [a, b] = span.bounds();
        if !(a >= lo && b <= hi && a.is_finite() && b.is_finite()) {
            findings.error(
                &format!("{at}.{key}"),
                format!("expected values within {lo}–{hi}, found {a}–{b}"),
            );
        } else if a > b {
            findings.error(
                &format!("{at}.{key}"),
                format!("expected a range [low, high] with low ≤ high, found [{a}, {b}]"),
            );
        }
    };
    let hours = match lighting.time {
        TimeOfDay::Preset(_) => None,
        TimeOfDay::Hour(h) => Some(Span::Value(h)),
        TimeOfDay::Hours(r) => Some(Span::Range(r)),
    };
    span("time", hours, 0.0, 24.0);
    span("sun_elevation", lighting.sun_elevation, -90.0, 90.0);
    span("sun_azimuth", lighting.sun_azimuth, 0.0, 360.0);
    match (lighting.sun_elevation, lighting.sun_azimuth) {
        (Some(_), None) => findings.error(
            &format!("{at}.sun_elevation"),
            "expected `sun_azimuth` beside `sun_elevation`, found none",
        ),
        (None, Some(_)) => findings.error(
            &format!("{at}.sun_azimuth"),
            "expected `sun_elevation` beside `sun_azimuth`, found none",
        ),
        _ => {}
    }
}

fn default_day_of_year() -> f64 {
    // The June solstice: long days, high sun.
    172.0
}
fn default_latitude() -> f64 {
    45.0
}
fn default_turbidity() -> f64 {
    3.0
}
fn default_true() -> bool {
    true
}
fn default_lit_windows() -> f64 {
    0.3
}
fn default_lamp_range() -> f64 {
    25.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> LightingSpec {
        toml::from_str(text).unwrap()
    }

    #[test]
    fn presets_hours_and_ranges_parse() {
        assert_eq!(
            parse("time = \"night\"").time,
            TimeOfDay::Preset(TimePreset::Night)
        );
        assert_eq!(parse("time = 17.5").time, TimeOfDay::Hour(17.5));
        assert_eq!(parse("time = [6, 9]").time, TimeOfDay::Hours([6.0, 9.0]));
        let sun = parse("sun_elevation = [10, 40]\nsun_azimuth = 200");
        assert_eq!(sun.sun_elevation, Some(Span::Range([10.0, 40.0])));
        assert_eq!(sun.sun_azimuth, Some(Span::Value(200.0)));
        assert_eq!(parse(""), LightingSpec::default());
        assert_eq!(Span::Range([10.0, 20.0]).at(0.25), 12.5);
    }
}
