//! The `[weather]` table: which weather the frames show and how strong, each value fixed
//! or a range drawn per frame.

use schemars::{JsonSchema, Schema, SchemaGenerator, json_schema};
use serde::{Deserialize, Serialize};

use super::sensor_ranges;
use super::value_range::ValueRange;

/// Weather of every camera path's frames. Fog and rain change only the RGB image: ids,
/// depth and labels stay geometric (an object in thick fog is still annotated).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WeatherSpec {
    /// `"clear"`, `"overcast"` (grey sky, soft light, weak shadows), `"fog"` (distance and
    /// height fog) or `"rain"` (wet dark surfaces, streaks, low contrast); or a list of
    /// them, one drawn per frame (repeat a name to weight it).
    #[serde(default)]
    #[schemars(schema_with = "kinds_schema")]
    pub kind: WeatherKinds,
    /// Strength of the weather, 0–1, fixed or `[low, high]` drawn per frame.
    #[serde(default = "default_strength")]
    #[schemars(schema_with = "sensor_ranges::unit")]
    pub strength: ValueRange,
    /// Fog: extinction per metre at the ground at strength 1 (meteorological visibility ≈
    /// 3 / density metres: 0.03 is about 100 m).
    #[serde(default = "default_fog_density")]
    #[schemars(schema_with = "sensor_ranges::density")]
    pub fog_density: ValueRange,
    /// Fog: height in metres over which the fog's density falls by a factor e.
    #[serde(default = "default_fog_height")]
    #[schemars(schema_with = "sensor_ranges::fog_height")]
    pub fog_height: ValueRange,
    /// Share of the sky covered by clouds, 0–1, fixed or `[low, high]` drawn per frame: a
    /// layer 1.2 km up, lit by the sun and the sky, fading towards the horizon (overcast,
    /// fog and rain grey the sky over them as they strengthen).
    #[serde(default = "default_clouds")]
    #[schemars(schema_with = "sensor_ranges::unit")]
    pub clouds: ValueRange,
}

impl Default for WeatherSpec {
    fn default() -> Self {
        WeatherSpec {
            kind: WeatherKinds::default(),
            strength: default_strength(),
            fog_density: default_fog_density(),
            fog_height: default_fog_height(),
            clouds: default_clouds(),
        }
    }
}

/// One weather.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Weather {
    #[default]
    Clear,
    Overcast,
    Fog,
    Rain,
}

impl Weather {
    /// The name a spec and the annotations use.
    pub fn name(self) -> &'static str {
        match self {
            Weather::Clear => "clear",
            Weather::Overcast => "overcast",
            Weather::Fog => "fog",
            Weather::Rain => "rain",
        }
    }
}

/// One weather, or a list to draw one from per frame.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum WeatherKinds {
    One(Weather),
    Mix(Vec<Weather>),
}

impl Default for WeatherKinds {
    fn default() -> Self {
        WeatherKinds::One(Weather::Clear)
    }
}

impl WeatherKinds {
    /// The weathers to draw from (never empty: an empty list means clear).
    pub fn choices(&self) -> Vec<Weather> {
        match self {
            WeatherKinds::One(w) => vec![*w],
            WeatherKinds::Mix(list) if list.is_empty() => vec![Weather::Clear],
            WeatherKinds::Mix(list) => list.clone(),
        }
    }
}

/// A name, or a list of names. `pattern` applies to strings only and `items` to arrays
/// only, so a wrong name is reported at the name.
fn kinds_schema(_: &mut SchemaGenerator) -> Schema {
    let names = "^(clear|overcast|fog|rain)$";
    json_schema!({
        "description": "\"clear\", \"overcast\", \"fog\" or \"rain\", or a list of them drawn from per frame.",
        "type": ["string", "array"],
        "pattern": names,
        "items": {"type": "string", "pattern": names},
        "minItems": 1,
        "maxItems": 64,
        "default": "clear"
    })
}

fn default_strength() -> ValueRange {
    ValueRange::Fixed(1.0)
}
fn default_fog_density() -> ValueRange {
    ValueRange::Fixed(0.03)
}
fn default_fog_height() -> ValueRange {
    ValueRange::Fixed(30.0)
}
fn default_clouds() -> ValueRange {
    ValueRange::Between([0.0, 0.6])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_kind_or_a_mix() {
        let w: WeatherSpec = toml::from_str("kind = \"fog\"\nstrength = [0.2, 0.6]").unwrap();
        assert_eq!(w.kind.choices(), [Weather::Fog]);
        assert_eq!(w.strength, ValueRange::Between([0.2, 0.6]));
        let w: WeatherSpec = toml::from_str("kind = [\"clear\", \"rain\", \"rain\"]").unwrap();
        assert_eq!(
            w.kind.choices(),
            [Weather::Clear, Weather::Rain, Weather::Rain]
        );
        let w: WeatherSpec = toml::from_str("").unwrap();
        assert_eq!(w, WeatherSpec::default());
        assert_eq!(w.kind.choices(), [Weather::Clear]);
        assert!(toml::from_str::<WeatherSpec>("kind = \"snow\"").is_err());
    }
}
