//! Lamp sites → `lamp_NNNN` objects: an octagonal pole, an arm reaching towards the road
//! along the lamp's `facing`, and a head with the emissive `lamp_head` material under the
//! arm's end.
//!
//! The octagon is built from the facing vector and its perpendicular (with the constant
//! `1/√2`), not from `sin`/`cos`, so it is the same bit for bit everywhere. A lamp whose
//! facing is zero or not finite faces east.

use std::f64::consts::FRAC_1_SQRT_2;

use super::object;
use super::surfaces::Surfaces;
use crate::model::ObjectKind;
use crate::model::geometry::{KERB_Y, MeshBuilder, UP};
use crate::model::{Lamp, SceneObject};

/// Pole height above the sidewalk, its radius, the arm's reach from the pole's axis, in
/// metres. Lamps stand mid-strip, 4 m from the road with the default 8 m strip: the arm
/// carries the head out over the road's edge, where a street lamp lights the road.
pub const POLE_HEIGHT: f64 = 6.0;
pub const POLE_RADIUS: f64 = crate::model::LAMP_POLE_RADIUS;
pub const ARM_LENGTH: f64 = 4.5;
const ARM_THICKNESS: f64 = 0.08;
/// How far the arm's top sits below the pole's cap.
const ARM_DROP: f64 = 0.05;
const HEAD_SIZE: [f64; 3] = [0.6, 0.28, 0.14];

/// Where a lamp's light is, in metres: 5 cm under the middle of its head (`y` up), so the
/// night lighting shines from the glowing head and not from the pole.
pub fn light_position(lamp: &Lamp, mpp: f64) -> [f64; 3] {
    let foot = [lamp.position[0] * mpp, lamp.position[1] * mpp];
    let f = unit(lamp.facing);
    let reach = ARM_LENGTH + 0.02 - HEAD_SIZE[0] / 2.0;
    [
        foot[0] + f[0] * reach,
        head_bottom() - 0.05,
        foot[1] + f[1] * reach,
    ]
}

/// Height of the underside of a lamp head.
fn head_bottom() -> f64 {
    arm_y() + 0.01 - HEAD_SIZE[2]
}

/// Height of the underside of a lamp's arm: its top stays below the pole's cap, so the two
/// never share a plane.
fn arm_y() -> f64 {
    KERB_Y + POLE_HEIGHT - ARM_DROP - ARM_THICKNESS
}

pub fn lamp_objects(lamps: &[Lamp], mpp: f64, surfaces: &Surfaces) -> Vec<SceneObject> {
    lamps
        .iter()
        .map(|lamp| {
            let foot = [lamp.position[0] * mpp, lamp.position[1] * mpp];
            let f = unit(lamp.facing);
            let top = KERB_Y + POLE_HEIGHT;
            let mut metal = MeshBuilder::new(surfaces.lamp_metal);
            pole(&mut metal, foot, f, top);
            // The arm starts inside the pole and reaches ARM_LENGTH from its axis.
            let arm_y = arm_y();
            let arm_base = [
                foot[0] + f[0] * ARM_LENGTH / 2.0,
                arm_y,
                foot[1] + f[1] * ARM_LENGTH / 2.0,
            ];
            metal.oriented_box(
                arm_base,
                f,
                [ARM_LENGTH / 2.0, ARM_THICKNESS / 2.0],
                ARM_THICKNESS,
            );
            // The head hangs under the arm's end: its top sinks into the arm by 1 cm and
            // it reaches 2 cm past the arm's end, so no two faces share a plane.
            let reach = ARM_LENGTH + 0.02 - HEAD_SIZE[0] / 2.0;
            let head_base = [
                foot[0] + f[0] * reach,
                head_bottom(),
                foot[1] + f[1] * reach,
            ];
            let mut head = MeshBuilder::new(surfaces.lamp_head);
            head.oriented_box(
                head_base,
                f,
                [HEAD_SIZE[0] / 2.0, HEAD_SIZE[1] / 2.0],
                HEAD_SIZE[2],
            );
            object(
                ObjectKind::Lamp,
                format!("lamp_{:04}", lamp.id),
                vec![metal, head],
            )
        })
        .collect()
}

/// `v` scaled to unit length; east for a zero or non-finite vector.
fn unit(v: [f64; 2]) -> [f64; 2] {
    let len = (v[0] * v[0] + v[1] * v[1]).sqrt();
    if len.is_finite() && len > 1e-9 {
        [v[0] / len, v[1] / len]
    } else {
        [1.0, 0.0]
    }
}

/// An eight-sided prism from the ground to `top`, one corner pointing along `f`, capped.
fn pole(mesh: &mut MeshBuilder, foot: [f64; 2], f: [f64; 2], top: f64) {
    let s = [-f[1], f[0]];
    let h = FRAC_1_SQRT_2;
    // The eight corner directions, counter-clockwise seen from above (f, then towards -s:
    // with x east and z south, turning from f towards -s is counter-clockwise from +y).
    let dirs: [[f64; 2]; 8] = [
        f,
        [h * (f[0] - s[0]), h * (f[1] - s[1])],
        [-s[0], -s[1]],
        [h * (-f[0] - s[0]), h * (-f[1] - s[1])],
        [-f[0], -f[1]],
        [h * (s[0] - f[0]), h * (s[1] - f[1])],
        s,
        [h * (f[0] + s[0]), h * (f[1] + s[1])],
    ];
    let corner = |k: usize| {
        [
            foot[0] + POLE_RADIUS * dirs[k % 8][0],
            foot[1] + POLE_RADIUS * dirs[k % 8][1],
        ]
    };
    for k in 0..8 {
        let (a, b) = (dirs[k], dirs[(k + 1) % 8]);
        let mid = [a[0] + b[0], a[1] + b[1]];
        let n = unit(mid);
        let side = POLE_RADIUS * (2.0 - 2.0 * (a[0] * b[0] + a[1] * b[1])).sqrt();
        mesh.wall(
            corner(k),
            corner(k + 1),
            [0.0, top],
            [n[0], 0.0, n[1]],
            [0.0, side],
            [0.0, top],
        );
    }
    // Cap: the octagon as three planar quads.
    let at = |k: usize| {
        let c = corner(k);
        [c[0], top, c[1]]
    };
    for [a, b, c, d] in [[0, 1, 2, 3], [0, 3, 4, 7], [4, 5, 6, 7]] {
        let corners = [at(a), at(b), at(c), at(d)];
        let uvs = corners.map(|p| [p[0] - foot[0], p[2] - foot[1]]);
        mesh.quad(corners, UP, uvs);
    }
}
