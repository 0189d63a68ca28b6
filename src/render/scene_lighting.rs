//! `[lighting]` + the drawn [`Sun`] + lamp heads + facades → the [`Lighting`] of a camera
//! path (or frame): the spec's sun, sky and shadows, a point light at every lamp head and
//! a seeded share of lit windows once the sun is low.

use super::lighting::{LAMP_COLOUR, WINDOW_COLOUR};
use super::{Light, Lighting, LitWindows, Sun};
use crate::model::{FacadeSet, Scene};
use crate::spec::LightingSpec;

/// The lighting of `spec` under `sun`. `lamp_heads` are the world positions of the street
/// lamps' heads; they light up (and windows glow) as the sun sets.
pub fn lighting_for(
    spec: &LightingSpec,
    sun: &Sun,
    scene: &Scene,
    facades: &FacadeSet,
    lamp_heads: &[[f64; 3]],
    seed: u64,
) -> Lighting {
    let range = spec.lamp_range as f32;
    let lights = lamp_heads
        .iter()
        .map(|p| Light {
            position: p.map(|v| v as f32),
            colour: LAMP_COLOUR,
            range,
        })
        .collect();
    let windows =
        LitWindows::from_facades(scene, facades, spec.lit_windows as f32, seed, WINDOW_COLOUR);
    let mut lighting = Lighting::from_sun(sun, spec.turbidity, lights, Some(windows));
    lighting.shadows = spec.shadows;
    lighting
}
