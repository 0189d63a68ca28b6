//! Lighting of a frame: sky, ambient, sun, point lights, emission and lit windows.

use serde::{Deserialize, Serialize};

use super::LitWindows;

/// A point light with a smooth falloff to zero at `range`:
/// `colour · (1 − (d / range)²)²` at distance `d < range`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Light {
    pub position: [f32; 3],
    pub colour: [f32; 3],
    pub range: f32,
}

/// Everything about a frame's light; all colours linear RGB.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Lighting {
    /// Background colour where nothing is drawn.
    pub sky: [f32; 3],
    pub ambient: [f32; 3],
    /// Towards the sun, unit length.
    pub sun_direction: [f32; 3],
    /// Zero at night.
    pub sun_colour: [f32; 3],
    /// Lamp lights at night (empty by day).
    pub lights: Vec<Light>,
    /// Scale of the materials' emissive colours: 1 at night (lamp heads glow), 0 by day.
    pub emission: f32,
    /// Lit windows at night; `None` by day.
    pub windows: Option<LitWindows>,
}

impl Lighting {
    /// A clear day: blue sky, sun from the south-east and high, soft ambient, no emission.
    pub fn day() -> Lighting {
        // (0.4, 0.8, 0.45) normalised by hand: length √(0.16 + 0.64 + 0.2025) ≈ 1.001248.
        let inv = 1.0 / 1.001_248_4;
        Lighting {
            sky: [0.45, 0.62, 0.9],
            ambient: [0.32, 0.34, 0.38],
            sun_direction: [0.4 * inv, 0.8 * inv, 0.45 * inv],
            sun_colour: [0.95, 0.9, 0.82],
            lights: Vec::new(),
            emission: 0.0,
            windows: None,
        }
    }

    /// Night: a dark sky, a faint ambient, no sun, the given lamp lights, glowing emissive
    /// materials and (optionally) lit windows.
    pub fn night(lights: Vec<Light>, windows: Option<LitWindows>) -> Lighting {
        Lighting {
            sky: [0.005, 0.007, 0.02],
            ambient: [0.02, 0.022, 0.03],
            sun_direction: [0.0, 1.0, 0.0],
            sun_colour: [0.0; 3],
            lights,
            emission: 1.0,
            windows,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_sane() {
        let day = Lighting::day();
        let d = day.sun_direction;
        let len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        assert!((len2 - 1.0).abs() < 1e-5, "{len2}");
        assert_eq!(day.emission, 0.0);
        let night = Lighting::night(Vec::new(), None);
        assert_eq!(night.sun_colour, [0.0; 3]);
        assert!(night.sky.iter().zip(day.sky).all(|(n, d)| *n < d));
    }
}
