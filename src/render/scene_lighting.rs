//! `[lighting]` + the drawn [`Sun`] + lamp heads + facades → the [`Lighting`] of a camera
//! path (or frame): the spec's sun, sky and shadows, a point light at every lamp head and
//! a seeded share of lit windows once the sun is low with the light they spill onto the
//! pavement, and the headlight beam and tail-light glow of every car in a driving lane
//! (a parked car's lights are off: its lenses are other materials).

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
        .map(|p| Light::street_lamp(p.map(|v| v as f32), LAMP_COLOUR, range))
        .collect();
    lights.extend(vehicle_lights(scene));
    let windows =
        LitWindows::from_facades(scene, facades, spec.lit_windows as f32, seed, WINDOW_COLOUR);
    lights.extend(windows.spill_lights(scene));
    let mut lighting = Lighting::from_sun(sun, spec.turbidity, lights, Some(windows));
    lighting.shadows = spec.shadows;
    lighting
}

/// Headlights: a warm white beam about 37° wide (half angle), aimed along the car and a
/// little down, lighting the road up to [`HEAD_RANGE`] metres ahead; about 1 on the road
/// 4 m ahead, under a tenth of that at 12 m (the road is lit at a grazing angle).
const HEAD_LIGHT: [f32; 3] = [10.0, 9.2, 7.5];
const HEAD_RANGE: f32 = 30.0;
const HEAD_NEAR: f32 = 6.0;
const HEAD_EDGE: f32 = 0.8;
/// How far down the headlights aim (the beam's axis falls this much per metre).
const HEAD_DIP: f64 = 0.06;
/// Tail lights' red glow on the road and the car just behind, all round.
const TAIL_LIGHT: [f32; 3] = [0.5, 0.03, 0.015];
const TAIL_RANGE: f32 = 3.0;
const TAIL_NEAR: f32 = 1.0;

/// Per vehicle: a beam from the centre of its headlight meshes (the `car_headlight`
/// material) aimed away from its tail lights (`car_taillight`), and a small red light at
/// the tail lights; in scene order.
fn vehicle_lights(scene: &Scene) -> Vec<Light> {
    let mut out = Vec::new();
    for object in &scene.objects {
        let centre = |name: &str| {
            let (mut sum, mut n) = ([0f64; 3], 0usize);
            for mesh in &object.meshes {
                if scene
                    .materials
                    .get(mesh.material as usize)
                    .is_some_and(|m| m.name == name)
                {
                    for p in &mesh.positions {
                        for k in 0..3 {
                            sum[k] += f64::from(p[k]);
                        }
                    }
                    n += mesh.positions.len();
                }
            }
            (n > 0).then(|| sum.map(|v| v / n as f64))
        };
        let (head, tail) = (centre("car_headlight"), centre("car_taillight"));
        if let Some(head) = head {
            // Along the car, level, then dipped; a car without tail lights shines all round.
            let aim = tail.map_or([0.0; 3], |tail| {
                let (x, z) = (head[0] - tail[0], head[2] - tail[2]);
                let len = (x * x + z * z).sqrt();
                if len > 1e-6 {
                    [(x / len) as f32, -HEAD_DIP as f32, (z / len) as f32]
                } else {
                    [0.0; 3]
                }
            });
            out.push(Light {
                position: head.map(|v| v as f32),
                colour: HEAD_LIGHT,
                range: HEAD_RANGE,
                near: HEAD_NEAR,
                aim,
                edge: HEAD_EDGE,
            });
        }
        if let Some(tail) = tail {
            out.push(Light {
                position: tail.map(|v| v as f32),
                colour: TAIL_LIGHT,
                range: TAIL_RANGE,
                near: TAIL_NEAR,
                aim: [0.0; 3],
                edge: -1.0,
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Material, Mesh, SceneObject};

    fn lamp_mesh(material: u32, x: f32) -> Mesh {
        Mesh {
            material,
            positions: vec![[x, 0.7, -0.5], [x, 0.7, 0.5], [x, 0.9, 0.0]],
            normals: vec![[1.0, 0.0, 0.0]; 3],
            uvs: Vec::new(),
            indices: vec![0, 1, 2],
        }
    }

    #[test]
    fn headlights_beam_forward_and_tail_lights_glow_all_round() {
        let material = |name: &str| Material {
            name: name.into(),
            colour: [1.0; 3],
            texture: None,
            emissive: [1.0; 3],
        };
        // A car facing +x: headlights at its front (x = 2), tail lights at its back.
        let scene = Scene {
            textures: Vec::new(),
            materials: vec![material("car_headlight"), material("car_taillight")],
            objects: vec![SceneObject {
                name: "car_0000".into(),
                class: "car".into(),
                meshes: vec![lamp_mesh(0, 2.0), lamp_mesh(1, -2.0)],
            }],
        };
        let lights = vehicle_lights(&scene);
        assert_eq!(lights.len(), 2);
        let (head, tail) = (&lights[0], &lights[1]);
        assert!((head.position[0] - 2.0).abs() < 1e-6, "{:?}", head.position);
        assert_eq!(head.aim, [1.0, -HEAD_DIP as f32, 0.0]);
        assert!(head.range > 20.0 && head.edge > 0.5);
        assert_eq!(tail.aim, [0.0; 3]);
        assert!(
            tail.colour[0] > 10.0 * tail.colour[1],
            "red: {:?}",
            tail.colour
        );
    }
}
