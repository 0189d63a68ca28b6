//! `[weather]` + a camera's `sensor` table + seed + frame index → the [`Conditions`] one
//! frame is made under: domain randomization in one place.
//!
//! Every parameter is drawn from its own stream, `rng::stream(camera seed,
//! "conditions.<name>", frame)`, whether or not the frame's weather uses it: adding a
//! parameter or changing one range never shifts another's draws, and a frame's weather
//! does not change its noise.

use rand::Rng;
use serde_json::{Value, json};

use crate::rng;
use crate::spec::{ExposureMode, SensorSpec, ValueRange, Weather, WeatherSpec};

/// The cloud layer's pattern repeats every this many metres (what `cloud_offset` spans).
pub const CLOUD_TILE: f64 = 8192.0;

/// The values one frame drew.
#[derive(Clone, Debug, PartialEq)]
pub struct Conditions {
    pub weather: Weather,
    /// 0–1.
    pub strength: f64,
    /// Fog's extinction per metre at the ground at strength 1 (used when the weather is fog).
    pub fog_density: f64,
    /// Fog's scale height in metres (used when the weather is fog).
    pub fog_height: f64,
    /// Share of the sky under clouds, 0–1.
    pub clouds: f64,
    /// Where the cloud layer's pattern starts, metres east and south: the same for every
    /// frame of a path (the clouds stand still as the camera moves), another per path.
    pub cloud_offset: [f64; 2],
    pub exposure: ExposureMode,
    /// Stops: the exposure (`fixed`) or its compensation (`auto`).
    pub ev: f64,
    pub noise: f64,
    pub shot_noise: f64,
    /// JPEG quality, when the frame is compressed.
    pub jpeg_quality: Option<u8>,
    pub vignetting: f64,
    pub chromatic_aberration: f64,
    /// Metres travelled while the shutter is open.
    pub motion_blur: f64,
    /// Seed of the frame's per-pixel noise and rain streaks.
    pub seed: u64,
}

impl Conditions {
    /// No weather and a plain sensor: automatic exposure and the tone curve only.
    pub fn plain() -> Conditions {
        draw(&WeatherSpec::default(), &SensorSpec::default(), 0, 0)
    }

    /// The values as the annotations record them (`exposure_scale` is the multiplier the
    /// frame was finally exposed with), numbers rounded to 6 decimals.
    pub fn to_json(&self, exposure_scale: f32) -> Value {
        let r = |v: f64| {
            let x = (v * 1e6).round() / 1e6;
            if x.is_finite() { json!(x) } else { Value::Null }
        };
        json!({
            "weather": self.weather.name(),
            "strength": r(self.strength),
            "fog_density": r(self.fog_density),
            "fog_height": r(self.fog_height),
            "clouds": r(self.clouds),
            "exposure": match self.exposure {
                ExposureMode::Scene => "scene",
                ExposureMode::Auto => "auto",
                ExposureMode::Fixed => "fixed",
            },
            "ev": r(self.ev),
            "exposure_scale": r(f64::from(exposure_scale)),
            "noise": r(self.noise),
            "shot_noise": r(self.shot_noise),
            "jpeg_quality": self.jpeg_quality,
            "vignetting": r(self.vignetting),
            "chromatic_aberration": r(self.chromatic_aberration),
            "motion_blur": r(self.motion_blur),
        })
    }
}

/// The conditions of frame `frame` of the camera whose conditions seed is `seed`.
pub fn draw(weather: &WeatherSpec, sensor: &SensorSpec, seed: u64, frame: u64) -> Conditions {
    let uniform = |name: &str| {
        let mut stream = rng::stream(seed, &format!("conditions.{name}"), frame);
        // 53 random bits → [0, 1).
        (stream.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    };
    let value = |name: &str, range: ValueRange| match range {
        ValueRange::Fixed(v) => v,
        ValueRange::Between(_) => range.at(uniform(name)),
    };
    let choices = weather.kind.choices();
    let pick = ((uniform("weather") * choices.len() as f64) as usize).min(choices.len() - 1);
    Conditions {
        weather: choices[pick],
        strength: value("strength", weather.strength),
        fog_density: value("fog_density", weather.fog_density),
        fog_height: value("fog_height", weather.fog_height),
        clouds: value("clouds", weather.clouds),
        cloud_offset: {
            let mut stream = rng::stream(seed, "conditions.cloud_offset", 0);
            let mut metres =
                || (stream.next_u64() >> 40) as f64 * (CLOUD_TILE / (1u64 << 24) as f64);
            [metres(), metres()]
        },
        exposure: sensor.exposure,
        ev: value("ev", sensor.ev),
        noise: value("noise", sensor.noise),
        shot_noise: value("shot_noise", sensor.shot_noise),
        jpeg_quality: sensor
            .jpeg_quality
            .map(|q| value("jpeg_quality", q).round().clamp(1.0, 100.0) as u8),
        vignetting: value("vignetting", sensor.vignetting),
        chromatic_aberration: value("chromatic_aberration", sensor.chromatic_aberration),
        motion_blur: value("motion_blur", sensor.motion_blur),
        seed: rng::stream(seed, "conditions.pixels", frame).next_u64(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn weather(text: &str) -> WeatherSpec {
        toml::from_str(text).unwrap()
    }

    #[test]
    fn draws_are_reproducible_within_ranges_and_independent() {
        let w = weather("kind = [\"clear\", \"fog\", \"rain\"]\nstrength = [0.2, 0.9]");
        let s: SensorSpec = toml::from_str("noise = [0.0, 0.02]\njpeg_quality = [50, 90]").unwrap();
        let mut kinds = std::collections::BTreeSet::new();
        for frame in 0..60 {
            let c = draw(&w, &s, 9, frame);
            assert_eq!(c, draw(&w, &s, 9, frame));
            assert!((0.2..=0.9).contains(&c.strength));
            assert!((0.0..=0.02).contains(&c.noise));
            assert!((50..=90).contains(&c.jpeg_quality.unwrap()));
            kinds.insert(c.weather.name());
        }
        assert_eq!(kinds.len(), 3, "{kinds:?}");
        // Another camera seed draws other values.
        assert_ne!(draw(&w, &s, 9, 0).strength, draw(&w, &s, 10, 0).strength);
        // Giving another parameter a range does not shift the strength drawn.
        let s2: SensorSpec = toml::from_str("ev = [-1, 1]").unwrap();
        let w2 = weather("kind = \"fog\"\nstrength = [0.2, 0.9]\nfog_height = [5, 50]");
        for frame in 0..10 {
            assert_eq!(
                draw(&w, &s, 9, frame).strength,
                draw(&w2, &s2, 9, frame).strength
            );
            assert_eq!(draw(&w, &s, 9, frame).seed, draw(&w2, &s2, 9, frame).seed);
        }
    }

    #[test]
    fn fixed_values_are_taken_as_given() {
        let c = Conditions::plain();
        assert_eq!(c.weather, Weather::Clear);
        assert_eq!(
            (c.strength, c.ev, c.noise, c.jpeg_quality),
            (1.0, 0.0, 0.0, None)
        );
        let j = c.to_json(1.25);
        assert_eq!(j["weather"], "clear");
        assert_eq!(j["exposure_scale"], 1.25);
        assert_eq!(j["jpeg_quality"], Value::Null);
    }

    #[test]
    fn clouds_are_drawn_per_frame_over_one_pattern_per_path() {
        let w = WeatherSpec::default();
        let s = SensorSpec::default();
        let frames: Vec<Conditions> = (0..40).map(|f| draw(&w, &s, 3, f)).collect();
        // The default cover is a range, 0–0.6, drawn per frame.
        assert!(frames.iter().all(|c| (0.0..=0.6).contains(&c.clouds)));
        assert!(frames.iter().any(|c| c.clouds != frames[0].clouds));
        // One offset for the whole path, inside the pattern's tile; another path, another.
        assert!(
            frames
                .iter()
                .all(|c| c.cloud_offset == frames[0].cloud_offset)
        );
        assert!(
            frames[0]
                .cloud_offset
                .iter()
                .all(|o| (0.0..CLOUD_TILE).contains(o))
        );
        assert_ne!(frames[0].cloud_offset, draw(&w, &s, 4, 0).cloud_offset);
        // A fixed cover is taken as given, and recorded.
        let fixed: WeatherSpec = toml::from_str("clouds = 0.25").unwrap();
        let c = draw(&fixed, &s, 3, 7);
        assert_eq!(c.clouds, 0.25);
        assert_eq!(c.to_json(1.0)["clouds"], 0.25);
    }
}
