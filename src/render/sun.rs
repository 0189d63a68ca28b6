//! `[lighting]` + seed + camera/frame → [`Sun`]: the sun's elevation and azimuth, from
//! presets, from given (or drawn) angles, or from an hour through the NOAA solar-position
//! equations.
//!
//! Trigonometry comes from the pure-Rust `libm` crate, which gives the same bits on every
//! platform (the platform's `sin`/`cos` may not).

use rand::RngExt;
use serde::{Deserialize, Serialize};

use crate::rng;
use crate::spec::{LightingSpec, Span, TimeOfDay, TimePreset, Vary};

/// The sun's place in the sky, and the hour it came from (if it came from one).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Sun {
    /// Degrees above the horizon (negative: below it).
    pub elevation: f64,
    /// Degrees clockwise from north (90 = east, 180 = south).
    pub azimuth: f64,
    /// Local solar hour, when the sun was set by `time`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hour: Option<f64>,
}

/// The `day` preset's sun: high in the south-east (the renderer's sun before `[lighting]`
/// had angles: direction (0.4, 0.8, 0.45)).
pub const DAY: Sun = Sun {
    elevation: 53.0,
    azimuth: 138.4,
    hour: None,
};
/// The `dusk` preset's sun: just above the horizon in the west-north-west.
pub const DUSK: Sun = Sun {
    elevation: 2.0,
    azimuth: 295.0,
    hour: None,
};
/// The `night` preset's sun: well below the horizon.
pub const NIGHT: Sun = Sun {
    elevation: -30.0,
    azimuth: 0.0,
    hour: None,
};

/// The sun stream of the overview (camera paths use their index): with `[lighting] sun`
/// drawn, the overview's sun is a draw of its own.
const OVERVIEW_SUN: u32 = u32::MAX;

impl Sun {
    /// The overview's sun: [`Sun::draw`] on a stream of its own.
    pub fn overview(spec: &LightingSpec, seed: u64) -> Sun {
        Sun::draw(spec, seed, OVERVIEW_SUN, 0)
    }

    /// Unit vector towards the sun in world coordinates (x east, y up, z south).
    pub fn direction(&self) -> [f64; 3] {
        let (e, a) = (self.elevation.to_radians(), self.azimuth.to_radians());
        let (ce, se) = (libm::cos(e), libm::sin(e));
        [ce * libm::sin(a), se, -ce * libm::cos(a)]
    }

    /// The sun of `lighting` for frame `frame` of camera `camera`: ranges are drawn from
    /// the stream `("sun", camera)` once per path, or `("sun", camera · 2³² + frame)` per
    /// frame when `vary = "frame"`.
    pub fn draw(lighting: &LightingSpec, seed: u64, camera: u32, frame: u32) -> Sun {
        let item = match lighting.vary {
            Vary::Path => u64::from(camera),
            Vary::Frame => (u64::from(camera) << 32) | u64::from(frame),
        };
        let mut stream = rng::stream(seed, "sun", item);
        let mut draw = |span: Span| {
            let t: f64 = stream.random_range(0.0..1.0);
            span.at(t)
        };
        if let (Some(e), Some(a)) = (lighting.sun_elevation, lighting.sun_azimuth) {
            return Sun {
                elevation: draw(e),
                azimuth: draw(a),
                hour: None,
            };
        }
        let hour = match lighting.time {
            TimeOfDay::Preset(TimePreset::Day) => return DAY,
            TimeOfDay::Preset(TimePreset::Dusk) => return DUSK,
            TimeOfDay::Preset(TimePreset::Night) => return NIGHT,
            TimeOfDay::Hour(h) => h,
            TimeOfDay::Hours(r) => draw(Span::Range(r)),
        };
        solar_position(hour, lighting.day_of_year, lighting.latitude)
    }
}

/// The sun at local solar `hour` (0–24) on `day_of_year` at `latitude` degrees, by the
/// NOAA solar calculator's equations (fractional year, equation of time, declination,
/// hour angle). The hour is local *mean* solar time: the equation of time shifts noon by
/// up to ±16 minutes over the year; longitude and time zone play no part.
pub fn solar_position(hour: f64, day_of_year: f64, latitude: f64) -> Sun {
    use std::f64::consts::PI;
    let g = 2.0 * PI / 365.0 * (day_of_year - 1.0 + (hour - 12.0) / 24.0);
    let (c1, s1, c2, s2, c3, s3) = (
        libm::cos(g),
        libm::sin(g),
        libm::cos(2.0 * g),
        libm::sin(2.0 * g),
        libm::cos(3.0 * g),
        libm::sin(3.0 * g),
    );
    let eqtime =
        229.18 * (0.000075 + 0.001868 * c1 - 0.032077 * s1 - 0.014615 * c2 - 0.040849 * s2);
    let decl = 0.006918 - 0.399912 * c1 + 0.070257 * s1 - 0.006758 * c2 + 0.000907 * s2
        - 0.002697 * c3
        + 0.00148 * s3;
    let true_solar_minutes = hour * 60.0 + eqtime;
    let ha = (true_solar_minutes / 4.0 - 180.0).to_radians();
    let lat = latitude.to_radians();
    let cos_zenith = (libm::sin(lat) * libm::sin(decl)
        + libm::cos(lat) * libm::cos(decl) * libm::cos(ha))
    .clamp(-1.0, 1.0);
    let zenith = libm::acos(cos_zenith);
    // Azimuth clockwise from north, from the east and north components of the direction.
    let east = -libm::sin(ha) * libm::cos(decl);
    let north = libm::cos(lat) * libm::sin(decl) - libm::sin(lat) * libm::cos(decl) * libm::cos(ha);
    let mut azimuth = libm::atan2(east, north).to_degrees();
    if azimuth < 0.0 {
        azimuth += 360.0;
    }
    Sun {
        elevation: 90.0 - zenith.to_degrees(),
        azimuth,
        hour: Some(hour),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noaa_matches_known_positions() {
        // Equinox noon on the equator: the sun is (nearly) overhead.
        let s = solar_position(12.0, 80.0, 0.0);
        assert!(s.elevation > 88.0, "{s:?}");
        // June solstice noon at 45° N: elevation 90 − 45 + 23.44 ≈ 68.4°, due south.
        let s = solar_position(12.0, 172.0, 45.0);
        assert!((s.elevation - 68.4).abs() < 0.3, "{s:?}");
        assert!((s.azimuth - 180.0).abs() < 3.0, "{s:?}");
        // Morning sun is in the east, evening sun in the west; midnight sun is down.
        let morning = solar_position(8.0, 172.0, 45.0);
        assert!(
            morning.azimuth > 60.0 && morning.azimuth < 120.0,
            "{morning:?}"
        );
        let evening = solar_position(18.0, 172.0, 45.0);
        assert!(
            evening.azimuth > 240.0 && evening.azimuth < 300.0,
            "{evening:?}"
        );
        assert!(solar_position(0.0, 172.0, 45.0).elevation < -15.0);
        // Winter noon at 45° N: 90 − 45 − 23.44 ≈ 21.6°.
        let s = solar_position(12.0, 355.0, 45.0);
        assert!((s.elevation - 21.6).abs() < 0.4, "{s:?}");
    }

    #[test]
    fn direction_points_at_the_sun() {
        let d = DAY.direction();
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        assert!((len - 1.0).abs() < 1e-12);
        // South-east and high: +x (east), +z (south), +y.
        assert!(d[0] > 0.3 && d[2] > 0.3 && d[1] > 0.75, "{d:?}");
        let east = Sun {
            elevation: 0.0,
            azimuth: 90.0,
            hour: None,
        }
        .direction();
        assert!((east[0] - 1.0).abs() < 1e-12 && east[1].abs() < 1e-12);
    }

    #[test]
    fn ranges_draw_per_path_or_per_frame() {
        let mut spec = LightingSpec {
            sun_elevation: Some(Span::Range([10.0, 60.0])),
            sun_azimuth: Some(Span::Range([0.0, 360.0])),
            ..LightingSpec::default()
        };
        let a = Sun::draw(&spec, 7, 0, 0);
        assert!((10.0..=60.0).contains(&a.elevation));
        assert_eq!(a, Sun::draw(&spec, 7, 0, 5), "one draw per path");
        assert_ne!(a, Sun::draw(&spec, 7, 1, 0), "each path its own");
        spec.vary = Vary::Frame;
        assert_ne!(Sun::draw(&spec, 7, 0, 0), Sun::draw(&spec, 7, 0, 5));
        assert_eq!(Sun::draw(&spec, 7, 0, 5), Sun::draw(&spec, 7, 0, 5));
        let hours = LightingSpec {
            time: TimeOfDay::Hours([7.0, 9.0]),
            ..LightingSpec::default()
        };
        let h = Sun::draw(&hours, 7, 0, 0).hour.unwrap();
        assert!((7.0..9.0).contains(&h));
    }
}
