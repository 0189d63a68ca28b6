//! `[lighting]` + the drawn [`Sun`] + lamp heads + facades → the [`Lighting`] of a camera
//! path (or frame): the spec's sun, sky and shadows, a point light at every lamp head and
//! a seeded share of lit windows once the sun is low, and small lights at the head and
//! tail lights of every vehicle (their pools on the road and on what stands near).

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
    let mut lights: Vec<Light> = lamp_heads
        .iter()
        .map(|p| Light {
            position: p.map(|v| v as f32),
            colour: LAMP_COLOUR,
            range,
        })
        .collect();
    lights.extend(vehicle_lights(scene));
    let windows =
        LitWindows::from_facades(scene, facades, spec.lit_windows as f32, seed, WINDOW_COLOUR);
    let mut lighting = Lighting::from_sun(sun, spec.turbidity, lights, Some(windows));
    lighting.shadows = spec.shadows;
    lighting
}

/// Headlights' pool: warm white, reaching [`HEAD_RANGE`] metres.
const HEAD_LIGHT: [f32; 3] = [0.9, 0.84, 0.7];
const HEAD_RANGE: f32 = 9.0;
/// Tail lights' red glow on the road just behind.
const TAIL_LIGHT: [f32; 3] = [0.35, 0.02, 0.01];
const TAIL_RANGE: f32 = 3.0;

/// A point light at the centre of each vehicle's headlight and tail-light meshes (the
/// `car_headlight` and `car_taillight` materials), in scene order.
fn vehicle_lights(scene: &Scene) -> Vec<Light> {
    let mut out = Vec::new();
    for object in &scene.objects {
        for mesh in &object.meshes {
            let Some(material) = scene.materials.get(mesh.material as usize) else {
                continue;
            };
            let (colour, range) = match material.name.as_str() {
                "car_headlight" => (HEAD_LIGHT, HEAD_RANGE),
                "car_taillight" => (TAIL_LIGHT, TAIL_RANGE),
                _ => continue,
            };
            if mesh.positions.is_empty() {
                continue;
            }
            let n = mesh.positions.len() as f64;
            let sum = mesh.positions.iter().fold([0f64; 3], |s, p| {
                [
                    s[0] + f64::from(p[0]),
                    s[1] + f64::from(p[1]),
                    s[2] + f64::from(p[2]),
                ]
            });
            out.push(Light {
                position: sum.map(|v| (v / n) as f32),
                colour,
                range,
            });
        }
    }
    out
}
