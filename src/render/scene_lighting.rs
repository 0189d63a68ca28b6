//! `[lighting]` + the drawn [`Sun`] + lamp heads + facades → the [`Lighting`] of a camera
//! path (or frame): the spec's sun, sky and shadows, a point light at every lamp head and
//! a seeded share of lit windows once the sun is low with the light they spill onto the
//! pavement, and the headlight beam and tail-light glow of every car in a driving lane
//! (a parked car's lights are off: its lenses are other materials), and a small lamp over
//! every lamp-lit sign (a mesh whose material's name holds
//! [`crate::model::LAMP_LIT_SUFFIX`]). A driving camera's own car adds its headlights per
//! frame ([`ego_headlights`]).

use super::lighting::{LAMP_COLOUR, WINDOW_COLOUR};
use super::{Light, Lighting, LitWindows, Sun};
use crate::model::{FacadeSet, LAMP_LIT_SUFFIX, Mesh, Scene};
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
    let mut carried = Vec::new();
    for (light, instance) in vehicle_lights(scene).into_iter().chain(sign_lamps(scene)) {
        carried.push((lights.len() as u32, instance));
        lights.push(light);
    }
    let windows =
        LitWindows::from_facades(scene, facades, spec.lit_windows as f32, seed, WINDOW_COLOUR);
    lights.extend(windows.spill_lights(scene));
    let mut lighting = Lighting::from_sun(sun, spec.turbidity, lights, Some(windows));
    lighting.shadows = spec.shadows;
    lighting.carried = carried;
    lighting
}

/// A sign lamp: a warm light [`SIGN_LAMP_OUT`] in front of the sign's face and
/// [`SIGN_LAMP_UP`] above its top edge, aimed at the face's middle, one per
/// [`SIGN_LAMP_SPACING`] of the sign's width. About 1.2 (the noon sun's strength) on the
/// middle of a sign 0.6 m tall, fading towards its ends and gone [`SIGN_LAMP_RANGE`] away.
const SIGN_LAMP: [f32; 3] = [4.0, 3.5, 2.8];
const SIGN_LAMP_OUT: f64 = 0.5;
const SIGN_LAMP_UP: f64 = 0.2;
const SIGN_LAMP_SPACING: f64 = 1.5;
const SIGN_LAMP_NEAR: f32 = 0.6;
const SIGN_LAMP_RANGE: f32 = 3.0;
const SIGN_LAMP_EDGE: f32 = 0.0;

/// The lamps over every mesh of a lamp-lit material, in scene order, each with its
/// object's instance id.
pub(crate) fn sign_lamps(scene: &Scene) -> Vec<(Light, u32)> {
    let lamp_lit: Vec<bool> = scene
        .materials
        .iter()
        .map(|m| m.name.contains(LAMP_LIT_SUFFIX))
        .collect();
    let mut out = Vec::new();
    for (object, instance) in scene.objects.iter().zip(1u32..) {
        for mesh in &object.meshes {
            if lamp_lit
                .get(mesh.material as usize)
                .copied()
                .unwrap_or(false)
            {
                out.extend(lamps_over(mesh).into_iter().map(|l| (l, instance)));
            }
        }
    }
    out
}

/// The lamps over one sign face: a flat, upright mesh facing along its first normal.
fn lamps_over(mesh: &Mesh) -> Vec<Light> {
    let (Some(normal), false) = (mesh.normals.first(), mesh.positions.is_empty()) else {
        return Vec::new();
    };
    let n = [f64::from(normal[0]), 0.0, f64::from(normal[2])];
    let len = (n[0] * n[0] + n[2] * n[2]).sqrt();
    if len.is_nan() || len <= 1e-6 {
        return Vec::new();
    }
    let n = n.map(|v| v / len);
    // Along the face, to its right seen from the front.
    let along = [n[2], 0.0, -n[0]];
    let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
    let mut centre = [0.0f64; 3];
    for p in &mesh.positions {
        let p = p.map(f64::from);
        let s = p[0] * along[0] + p[2] * along[2];
        lo = [lo[0].min(s), lo[1].min(p[1])];
        hi = [hi[0].max(s), hi[1].max(p[1])];
        for k in 0..3 {
            centre[k] += p[k];
        }
    }
    let centre = centre.map(|v| v / mesh.positions.len() as f64);
    let width = hi[0] - lo[0];
    let middle_y = (lo[1] + hi[1]) / 2.0;
    let count = (width / SIGN_LAMP_SPACING).ceil().max(1.0) as usize;
    let centre_s = centre[0] * along[0] + centre[2] * along[2];
    (0..count)
        .map(|i| {
            let offset = lo[0] + width * (i as f64 + 0.5) / count as f64 - centre_s;
            let at = [
                centre[0] + along[0] * offset + n[0] * SIGN_LAMP_OUT,
                hi[1] + SIGN_LAMP_UP,
                centre[2] + along[2] * offset + n[2] * SIGN_LAMP_OUT,
            ];
            let aim = [
                -n[0] * SIGN_LAMP_OUT,
                middle_y - at[1],
                -n[2] * SIGN_LAMP_OUT,
            ];
            let aim_len = (aim[0] * aim[0] + aim[1] * aim[1] + aim[2] * aim[2]).sqrt();
            Light {
                position: at.map(|v| v as f32),
                colour: SIGN_LAMP,
                range: SIGN_LAMP_RANGE,
                near: SIGN_LAMP_NEAR,
                aim: aim.map(|v| (v / aim_len) as f32),
                edge: SIGN_LAMP_EDGE,
                cutoff: None,
            }
        })
        .collect()
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
/// A dipped beam sends nothing above the horizontal through the lamp, nearly: full light
/// up to 0.6° below it, none from 0.3° above ([`crate::render::CUTOFF_BAND`]). The road
/// is lit out to the beam's reach (30 m ahead it lies 1.3° below a lamp 0.7 m up), but a
/// wall or a truck's back a few metres ahead only up to the lamps' height, with the sharp
/// line a dipped beam draws, instead of a glaring disc as high as the beam is wide.
const HEAD_CUTOFF: f32 = 0.005;
/// Tail lights' red glow on the road and the car just behind, all round.
const TAIL_LIGHT: [f32; 3] = [0.5, 0.03, 0.015];
const TAIL_RANGE: f32 = 3.0;
const TAIL_NEAR: f32 = 1.0;

/// Per vehicle: a beam from the centre of its headlight meshes (the `car_headlight`
/// material) aimed away from its tail lights (`car_taillight`), and a small red light at
/// the tail lights; in scene order, each with its vehicle's instance id.
fn vehicle_lights(scene: &Scene) -> Vec<(Light, u32)> {
    let mut out = Vec::new();
    for (object, instance) in scene.objects.iter().zip(1u32..) {
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
            out.push((head_beam(head.map(|v| v as f32), aim, HEAD_LIGHT), instance));
        }
        if let Some(tail) = tail {
            let light = Light {
                position: tail.map(|v| v as f32),
                colour: TAIL_LIGHT,
                range: TAIL_RANGE,
                near: TAIL_NEAR,
                aim: [0.0; 3],
                edge: -1.0,
                cutoff: None,
            };
            out.push((light, instance));
        }
    }
    out
}

/// A headlight's dipped beam from `position` along `aim`, in `colour`, cut off just above
/// the horizontal ([`HEAD_CUTOFF`]).
fn head_beam(position: [f32; 3], aim: [f32; 3], colour: [f32; 3]) -> Light {
    Light {
        position,
        colour,
        range: HEAD_RANGE,
        near: HEAD_NEAR,
        aim,
        edge: HEAD_EDGE,
        cutoff: Some(HEAD_CUTOFF),
    }
}

/// The camera car's headlights: each lamp this far ahead of the driver's eye, metres. A
/// real car's are about 2 m ahead, but its bonnet hides the road below them, and the
/// camera has no bonnet: from here the beams' lower edge falls on the road about 1 m
/// ahead of the eye, under the frame's lower edge, so the pool has no hard near edge…
const EGO_AHEAD: f64 = 0.5;
/// …this high above the road…
const EGO_LAMP_HEIGHT: f64 = 0.7;
/// …this far either side of the car's centre line…
const EGO_HALF_TRACK: f64 = 0.75;
/// …which is this far right of the eye (a driver sits left of centre in right-hand
/// traffic, as the roads camera drives).
const EGO_DRIVER_OFFSET: f64 = 0.4;
/// Each lamp's share of [`HEAD_LIGHT`]: the pair lights the road 4 m ahead about as
/// brightly as one other car's beam does 4 m ahead of it (about 1, the noon sun's
/// strength), and twice that at the frame's lower edge.
const EGO_SHARE: f32 = 0.45;

/// The headlights of the car a `roads` camera rides in: two dipped beams like every
/// driving car's (the same cone, 30 m reach and warm white, each at 0.45 of its
/// strength), aimed along `travel` (the way the car moves, whichever way the camera
/// looks) from in front of and below the eye, which is `eye_height` metres above the
/// road. `strength` scales them: the lighting's `emission` (0 by day, so none; 1 at
/// night). Without a horizontal `travel`, none. A night drive's nearest road is lit by
/// them, as on a dashcam, instead of black between the lamps.
pub fn ego_headlights(
    eye: [f64; 3],
    eye_height: f64,
    travel: [f64; 3],
    strength: f32,
) -> Vec<Light> {
    let len = (travel[0] * travel[0] + travel[2] * travel[2]).sqrt();
    let usable = strength > 0.0 && strength.is_finite() && len > 1e-6 && len.is_finite();
    if !usable || !eye_height.is_finite() || !eye.iter().all(|v| v.is_finite()) {
        return Vec::new();
    }
    let (fx, fz) = (travel[0] / len, travel[2] / len);
    // Right of the travel direction, seen from above (x east, z south, y up).
    let (rx, rz) = (-fz, fx);
    let y = eye[1] - eye_height + EGO_LAMP_HEIGHT;
    [-EGO_HALF_TRACK, EGO_HALF_TRACK]
        .map(|side| {
            let across = EGO_DRIVER_OFFSET + side;
            head_beam(
                [
                    (eye[0] + fx * EGO_AHEAD + rx * across) as f32,
                    y as f32,
                    (eye[2] + fz * EGO_AHEAD + rz * across) as f32,
                ],
                [fx as f32, -HEAD_DIP as f32, fz as f32],
                HEAD_LIGHT.map(|c| c * EGO_SHARE * strength.min(1.0)),
            )
        })
        .to_vec()
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
            emissive_textured: false,
        };
        // A car facing +x: headlights at its front (x = 2), tail lights at its back.
        let scene = Scene {
            textures: Vec::new(),
            materials: vec![material("car_headlight"), material("car_taillight")],
            objects: vec![SceneObject {
                name: "car_0000".into(),
                kind: crate::model::ObjectKind::Car,
                class: "car".into(),
                meshes: vec![lamp_mesh(0, 2.0), lamp_mesh(1, -2.0)],
            }],
        };
        let lights = vehicle_lights(&scene);
        assert!(lights.iter().all(|(_, instance)| *instance == 1));
        let lights: Vec<Light> = lights.into_iter().map(|(l, _)| l).collect();
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

    #[test]
    fn a_lamp_lit_sign_gets_lamps_over_its_face_and_an_unlit_one_none() {
        // A sign 3 m wide and 0.6 m tall on a wall facing +z, 2.5 m up.
        let face = |material| Mesh {
            material,
            positions: vec![
                [0.0, 2.5, 0.0],
                [3.0, 2.5, 0.0],
                [3.0, 3.1, 0.0],
                [0.0, 3.1, 0.0],
            ],
            normals: vec![[0.0, 0.0, 1.0]; 4],
            uvs: Vec::new(),
            indices: vec![0, 1, 2, 0, 2, 3],
        };
        let material = |name: &str| Material {
            name: name.into(),
            colour: [1.0; 3],
            texture: None,
            emissive: [0.0; 3],
            emissive_textured: false,
        };
        let scene = Scene {
            textures: Vec::new(),
            materials: vec![
                material("text_atlas_0"),
                material(&format!("text_atlas_0{LAMP_LIT_SUFFIX}")),
            ],
            objects: vec![SceneObject {
                name: "text_0000".into(),
                kind: crate::model::ObjectKind::Text,
                class: "text".into(),
                meshes: vec![face(0), face(1)],
            }],
        };
        let lamps: Vec<Light> = sign_lamps(&scene).into_iter().map(|(l, _)| l).collect();
        assert_eq!(
            lamps.len(),
            2,
            "one lamp per 1.5 m of the lamp-lit face only"
        );
        for (lamp, x) in lamps.iter().zip([0.75, 2.25]) {
            assert!((lamp.position[0] - x).abs() < 1e-5, "{:?}", lamp.position);
            assert!((lamp.position[1] - 3.3).abs() < 1e-5);
            assert!(
                (lamp.position[2] - 0.5).abs() < 1e-6,
                "in front of the face"
            );
            assert!(
                lamp.aim[2] < 0.0 && lamp.aim[1] < 0.0,
                "aimed back and down"
            );
        }
    }

    #[test]
    fn the_camera_cars_headlights_shine_along_its_travel_from_below_the_eye() {
        // Driving north (−z) with the eye 1.5 m above a road at y = 0.
        let lights = ego_headlights([10.0, 1.5, 20.0], 1.5, [0.0, 0.0, -3.0], 1.0);
        assert_eq!(lights.len(), 2);
        for (l, x) in lights.iter().zip([10.0 - 0.35, 10.0 + 1.15]) {
            // Ahead of the eye (north), right of it by the driver's offset ± half the track.
            assert!((l.position[0] - x).abs() < 1e-5, "{:?}", l.position);
            assert!((l.position[1] - 0.7).abs() < 1e-6);
            assert!((l.position[2] - 19.5).abs() < 1e-5);
            assert_eq!(l.aim, [0.0, -HEAD_DIP as f32, -1.0]);
            assert_eq!(l.colour, HEAD_LIGHT.map(|c| c * EGO_SHARE));
        }
        // Half strength as the lamps come on; none by day, or with no direction of travel.
        let dusk = ego_headlights([0.0, 1.2, 0.0], 1.2, [1.0, 0.0, 0.0], 0.5);
        assert_eq!(dusk[0].colour, HEAD_LIGHT.map(|c| c * EGO_SHARE * 0.5));
        assert!(ego_headlights([0.0; 3], 1.5, [1.0, 0.0, 0.0], 0.0).is_empty());
        assert!(ego_headlights([0.0; 3], 1.5, [0.0, 1.0, 0.0], 1.0).is_empty());
        assert!(ego_headlights([0.0; 3], f64::NAN, [1.0, 0.0, 0.0], 1.0).is_empty());
    }
}
