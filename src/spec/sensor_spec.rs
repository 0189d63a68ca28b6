//! A camera's `sensor` table: exposure, tone curve, noise, compression and lens effects,
//! each value fixed or a range drawn per frame. They change the RGB image only.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::sensor_ranges;
use super::value_range::ValueRange;

/// What the camera's sensor and lens do to the light. Defaults: the lighting's exposure and
/// the filmic tone curve, nothing else.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SensorSpec {
    /// `"scene"` (the default): the exposure the lighting sets for its time of day (so
    /// night stays dark), × 2^`ev`; `"auto"`: exposure from the frame's mean log
    /// luminance, shifted by `ev`; `"fixed"`: radiance × 2^`ev`.
    #[serde(default)]
    pub exposure: ExposureMode,
    /// Exposure value in stops (a compensation for `"auto"`).
    #[serde(default = "zero")]
    #[schemars(schema_with = "sensor_ranges::ev")]
    pub ev: ValueRange,
    /// Gaussian read noise: standard deviation in exposed linear units (0.01 is subtle).
    #[serde(default = "zero")]
    #[schemars(schema_with = "sensor_ranges::noise")]
    pub noise: ValueRange,
    /// Shot (photon) noise: its variance is this × the exposed linear signal.
    #[serde(default = "zero")]
    #[schemars(schema_with = "sensor_ranges::noise")]
    pub shot_noise: ValueRange,
    /// JPEG quality 1–100 of a compression round trip before the PNG is saved; absent: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(schema_with = "sensor_ranges::jpeg_quality")]
    pub jpeg_quality: Option<ValueRange>,
    /// Darkening at the image corners, 0–1 (0.3 is a typical lens).
    #[serde(default = "zero")]
    #[schemars(schema_with = "sensor_ranges::unit")]
    pub vignetting: ValueRange,
    /// Lateral chromatic aberration: red and blue shift apart by this many pixels at the
    /// image corners.
    #[serde(default = "zero")]
    #[schemars(schema_with = "sensor_ranges::aberration")]
    pub chromatic_aberration: ValueRange,
    /// Motion blur: metres the camera travels while the shutter is open, along its path
    /// (from the neighbouring frames' poses). A car at 36 km/h with a 1/30 s shutter: 0.33.
    /// On a timed drive with `[traffic]` it sets the shutter's time (these metres at the
    /// drive's `speed_kmh`), and the camera (as its poses move) and every moving vehicle
    /// and person blur over that time.
    #[serde(default = "zero")]
    #[schemars(schema_with = "sensor_ranges::travel")]
    pub motion_blur: ValueRange,
}

impl Default for SensorSpec {
    fn default() -> Self {
        SensorSpec {
            exposure: ExposureMode::Scene,
            ev: zero(),
            noise: zero(),
            shot_noise: zero(),
            jpeg_quality: None,
            vignetting: zero(),
            chromatic_aberration: zero(),
            motion_blur: zero(),
        }
    }
}

/// How exposure is set.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ExposureMode {
    // Plain comments: the schema stays a simple enum.
    #[default]
    Scene,
    Auto,
    Fixed,
}

fn zero() -> ValueRange {
    ValueRange::Fixed(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_and_ranges() {
        let s: SensorSpec = toml::from_str("").unwrap();
        assert_eq!(s, SensorSpec::default());
        let s: SensorSpec =
            toml::from_str("exposure = \"fixed\"\nev = [-1, 1]\njpeg_quality = [60, 90]").unwrap();
        assert_eq!(s.exposure, ExposureMode::Fixed);
        assert_eq!(s.ev, ValueRange::Between([-1.0, 1.0]));
        assert_eq!(s.jpeg_quality, Some(ValueRange::Between([60.0, 90.0])));
    }
}
