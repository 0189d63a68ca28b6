//! Person specs + sidewalk strip spots → `person_NNNN` objects: low-poly pedestrians,
//! walking along the street or standing, seeded in height, build, pose and clothes.
//!
//! A person is twelve flat-shaded parts in five materials (164 triangles): two legs ending
//! in shoes, a torso, two arms (sleeves and bare forearms, or long sleeves), a neck, a
//! rounded head and a hair cap. Proportions follow the figure's height `h`: hips at 0.5 h, shoulders at
//! 0.82 h, the head the top 0.13 h; width and depth scale with `h / 1.75` and a seeded build.
//! A walker faces along the street (either way) mid-stride, legs and arms swung opposite;
//! a standing figure faces any way, limbs nearly straight.
//!
//! People stand in the sidewalk strips between the curb and the line a `sidewalks` camera
//! walks ([`WALKER_ROOM`] clear of it; it runs [`WALK_SHARE`] of the strip from the shop
//! fronts), each taking a circle of [`ROOM`] of ground, so they never overlap lamps, signs,
//! trees, benches, cars or each other. The entry's `crossing` share walk across the zebra
//! crossings instead, on the zebra's paint, within [`ZEBRA_REACH`] of the road's centre
//! line (lane cars wait behind the stop lines, clear of them). Its `waiting` share of the
//! others stand at the zebras' ends, at the curb, facing the road as if about to cross (as
//! many as the ends hold; the rest join the strips).

use rand::RngExt;
use rand_pcg::Pcg64;

use super::car::{CAMERA_CLEARANCE, CAMERA_LANE};
use super::ground_spots::GroundSpots;
use super::vehicle_parts::{Frame, Solid, finish_all};
use super::{ATTEMPTS, GIVE_UP, Placing};
use crate::model::Mesh;
use crate::model::geometry::{KERB_Y, MARKING_Y, WALK_SHARE, trig};
use crate::spec::ObjectSpec;

/// Ground a person takes: the radius of its circle in metres (a tall walker's stride and
/// arms stay inside it).
pub const ROOM: f64 = 0.6;
/// Nearest a person stands to the curb, metres.
pub const CURB_ROOM: f64 = 0.45;
/// Room kept from the line a sidewalks camera walks, metres.
pub const WALKER_ROOM: f64 = 0.6;
/// Share of the people walking (the others stand); every one on a zebra crossing walks.
pub const WALKING: f64 = 0.7;
/// Farthest a person crossing a road on a zebra walks from its centre line, metres: a
/// default roads camera's line ([`CAMERA_LANE`]) stays [`CAMERA_CLEARANCE`] beyond their
/// [`ROOM`], as lane cars keep it.
pub const ZEBRA_REACH: f64 = CAMERA_LANE - CAMERA_CLEARANCE - ROOM;
/// People waiting to cross stand at a zebra's end, [`CURB_ROOM`] to this much farther from
/// the curb, metres…
pub const WAITING_DEPTH: f64 = 0.8;
/// …facing the road, turned up to this many degrees either way.
const WAITING_TURN: f64 = 25.0;

/// Clothes, linear RGB.
pub(super) const SHIRTS: [[f32; 3]; 10] = [
    [0.7, 0.7, 0.68],
    [0.02, 0.02, 0.025],
    [0.02, 0.03, 0.12],
    [0.45, 0.03, 0.03],
    [0.18, 0.18, 0.19],
    [0.05, 0.2, 0.06],
    [0.6, 0.45, 0.05],
    [0.25, 0.4, 0.7],
    [0.2, 0.1, 0.04],
    [0.6, 0.2, 0.3],
];
pub(super) const TROUSERS: [[f32; 3]; 5] = [
    [0.05, 0.08, 0.18],
    [0.02, 0.02, 0.025],
    [0.15, 0.15, 0.16],
    [0.45, 0.38, 0.25],
    [0.1, 0.06, 0.03],
];
pub(super) const SKIN: [[f32; 3]; 5] = [
    [0.62, 0.42, 0.32],
    [0.55, 0.36, 0.25],
    [0.4, 0.24, 0.15],
    [0.22, 0.12, 0.07],
    [0.11, 0.06, 0.035],
];
pub(super) const HAIR: [[f32; 3]; 5] = [
    [0.02, 0.015, 0.01],
    [0.05, 0.03, 0.015],
    [0.12, 0.07, 0.03],
    [0.45, 0.33, 0.15],
    [0.35, 0.34, 0.33],
];
pub(super) const SHOES: [[f32; 3]; 3] = [[0.02, 0.02, 0.02], [0.6, 0.6, 0.58], [0.12, 0.06, 0.025]];

/// How one person looks, drawn from the spec's stream.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Figure {
    /// Height in metres.
    pub height: f64,
    /// Width and depth factor around 1 (slim to broad).
    pub build: f64,
    /// Leg swing from the vertical, degrees: the left leg forward, the right back (a
    /// standing figure's is small).
    pub stride: f64,
    /// Share of the arm in sleeve, from the shoulder (0.35 short, 0.9 long).
    pub sleeve: f64,
}

pub fn place(spec: &ObjectSpec, rng: &mut Pcg64, spots: &mut GroundSpots, placing: &mut Placing) {
    let [low, high] = spec.height_range();
    let strip = 2.0 * spots.strip_half();
    // Between the curb and the sidewalk camera's line, clear of both.
    let far = (strip * (1.0 - WALK_SHARE) - WALKER_ROOM).max(CURB_ROOM);
    let mut misses = 0;
    for _ in 0..spec.count {
        if misses >= GIVE_UP {
            break;
        }
        misses += 1;
        // Only an entry with crossers (or people waiting) draws whether each is one (the
        // others keep their draws).
        let crossing = spec.crossing > 0.0 && rng.random::<f64>() < spec.crossing;
        let mut waiting = !crossing && spec.waiting > 0.0 && rng.random::<f64>() < spec.waiting;
        let mut spot = None;
        if crossing {
            spot = (0..ATTEMPTS).find_map(|_| spots.zebra(rng, ROOM, ZEBRA_REACH, 1));
        } else if waiting {
            let from_curb = CURB_ROOM + rng.random::<f64>() * WAITING_DEPTH;
            spot = (0..ATTEMPTS).find_map(|_| spots.zebra_kerb(rng, ROOM, from_curb, 1));
            // With the zebras' ends full, this one stands in a strip like the others.
            waiting = spot.is_some();
        }
        if spot.is_none() && !crossing {
            let from_curb = CURB_ROOM + rng.random::<f64>() * (far - CURB_ROOM);
            spot = (0..ATTEMPTS).find_map(|_| spots.strip_at(rng, ROOM, from_curb, 1));
        }
        let Some(spot) = spot else {
            continue;
        };
        let walking = crossing || !waiting && rng.random::<f64>() < WALKING;
        let forward = if waiting {
            // Facing the road, give or take a glance along it.
            let (c, s) = trig::cos_sin_deg((2.0 * rng.random::<f64>() - 1.0) * WAITING_TURN);
            let t = spot.travel;
            [t[0] * c - t[1] * s, t[0] * s + t[1] * c]
        } else if walking {
            let back = rng.random::<bool>();
            spot.travel.map(|t| if back { -t } else { t })
        } else {
            let (c, s) = trig::cos_sin_deg(rng.random::<f64>() * 360.0);
            [c, s]
        };
        let figure = Figure {
            height: low + rng.random::<f64>() * (high - low),
            build: 0.88 + 0.24 * rng.random::<f64>(),
            stride: if walking {
                10.0 + 8.0 * rng.random::<f64>()
            } else {
                3.0 * rng.random::<f64>()
            },
            sleeve: if rng.random::<bool>() { 0.35 } else { 0.9 },
        };
        let mut pick = |name: &str, palette: &[[f32; 3]]| placing.palette_pick(rng, name, palette);
        let (shirt, trousers) = (
            pick("person_shirt", &SHIRTS),
            pick("person_trousers", &TROUSERS),
        );
        let materials = Clothes {
            shirt: shirt.1,
            trousers: trousers.1,
            skin: pick("person_skin", &SKIN).1,
            hair: pick("person_hair", &HAIR).1,
            shoes: pick("person_shoes", &SHOES).1,
        };
        let appearance = Some(("appearance", appearance(&figure, shirt.0, trousers.0)));
        let ground = if crossing { MARKING_Y } else { KERB_Y };
        let frame = Frame {
            origin: [spot.position[0], ground, spot.position[1]],
            forward,
        };
        let name = placing.name("person");
        let meshes = person_meshes(&frame, &figure, materials);
        let person = crate::model::ObjectKind::Person;
        placing.push_variant(person, name, &spec.label, meshes, appearance);
        misses = 0;
    }
}

/// The variant a person was drawn as (its `appearance` attribute): sleeves, and the
/// palette indices of shirt and trousers, e.g. `short_shirt03_trousers01`.
fn appearance(figure: &Figure, shirt: usize, trousers: usize) -> String {
    let sleeves = if figure.sleeve < 0.5 { "short" } else { "long" };
    format!("{sleeves}_shirt{shirt:02}_trousers{trousers:02}")
}

/// Materials of one person's parts.
#[derive(Clone, Copy, Debug)]
pub struct Clothes {
    pub shirt: u32,
    pub trousers: u32,
    pub skin: u32,
    pub hair: u32,
    pub shoes: u32,
}

/// The solids of `figure` standing at `frame`'s origin, facing its forward: one mesh per
/// material used.
// Long on purpose: builds one figure part by part from a dozen shared dimensions, in the
// order its meshes are listed; split, each part would take them all as arguments.
pub fn person_meshes(frame: &Frame, figure: &Figure, m: Clothes) -> Vec<Mesh> {
    let h = figure.height;
    let s = h / 1.75 * figure.build;
    let hip = 0.5 * h;
    let shoulder = 0.82 * h;
    let (mut shirt, mut trousers, mut skin, mut hair, mut shoes) = (
        Solid::new(m.shirt),
        Solid::new(m.trousers),
        Solid::new(m.skin),
        Solid::new(m.hair),
        Solid::new(m.shoes),
    );
    // Legs: parallelograms in the (forward, up) plane from the hip to the ground, the left
    // (−v) swung forward, the right back; the lowest 0.06 h is the shoe, its toe ahead.
    let leg = 0.14 * s;
    let shoe_top = 0.06 * h;
    for (side, swing) in [(-1.0, figure.stride), (1.0, -figure.stride)] {
        let (cos, sin) = trig::cos_sin_deg(swing);
        let foot = hip * sin / cos;
        let u_at = |y: f64| foot * (1.0 - y / hip);
        let v = [side * 0.09 * s - 0.065 * s, side * 0.09 * s + 0.065 * s];
        let top = hip + 0.03 * h;
        let (ut, us) = (u_at(top), u_at(shoe_top));
        trousers.prism(
            frame,
            &[
                [ut - leg / 2.0, top],
                [us - leg / 2.0, shoe_top],
                [us + leg / 2.0, shoe_top],
                [ut + leg / 2.0, top],
            ],
            v,
            &[],
        );
        shoes.prism(
            frame,
            &[
                [us - leg / 2.0, shoe_top],
                [foot - leg / 2.0 - 0.02 * s, 0.0],
                [foot + leg / 2.0 + 0.05 * s, 0.0],
                [us + leg / 2.0, shoe_top],
            ],
            [v[0] - 0.005 * s, v[1] + 0.005 * s],
            &[],
        );
    }
    // Torso, hips to shoulders; the neck above it.
    shirt.cuboid(
        frame,
        [-0.11 * s, 0.11 * s],
        [hip - 0.02 * h, shoulder],
        [-0.19 * s, 0.19 * s],
    );
    skin.cuboid(
        frame,
        [-0.045 * s, 0.045 * s],
        [shoulder - 0.01 * h, 0.88 * h],
        [-0.045 * s, 0.045 * s],
    );
    // Arms from the shoulders, swung against the legs, the sleeve's share in the shirt.
    let arm = 0.085 * s;
    let pivot = shoulder - 0.02 * h;
    let length = 0.36 * h;
    for (side, swing) in [(-1.0, -figure.stride), (1.0, figure.stride)] {
        let (cos, sin) = trig::cos_sin_deg(swing);
        let at = |t: f64| [length * sin * t, pivot - length * cos * t];
        let limb = |a: [f64; 2], b: [f64; 2]| {
            [
                [a[0] - arm / 2.0, a[1]],
                [b[0] - arm / 2.0, b[1]],
                [b[0] + arm / 2.0, b[1]],
                [a[0] + arm / 2.0, a[1]],
            ]
        };
        let inner = side * (0.19 * s + 0.005 * s);
        let v = if side < 0.0 {
            [inner - 0.08 * s, inner]
        } else {
            [inner, inner + 0.08 * s]
        };
        let top = [0.0, pivot + 0.02 * h];
        shirt.prism(frame, &limb(top, at(figure.sleeve)), v, &[]);
        skin.prism(frame, &limb(at(figure.sleeve), at(1.0)), v, &[]);
    }
    // Head: over the neck; hair a cap over its top and back.
    let cap = Cap {
        scale: 1.1,
        nape: 0.6,
        half_width: 0.082 * s,
    };
    head(
        frame,
        [0.01 * s, 0.935 * h],
        s,
        h,
        (&mut skin, &mut hair),
        cap,
    );
    finish_all(vec![trousers, shoes, shirt, skin, hair])
}

/// The cap over a head: hair or a helmet.
#[derive(Clone, Copy, Debug)]
pub(super) struct Cap {
    /// Size against the head's octagon.
    pub scale: f64,
    /// How far down the back it reaches, in halves of the head's height below its centre.
    pub nape: f64,
    /// Half its width across the face, metres.
    pub half_width: f64,
}

/// A head in side view about `centre` (`(u, y)` in `frame`) of a figure `h` tall and `s`
/// wide: an octagon 0.13 h tall and 0.2 s long, 0.15 s across, in the first solid; and
/// `cap` in the second: the upper half of a larger octagon (its corners 0–3, front to
/// back), down the back to the nape, and back up across the temple to the front corner.
pub(super) fn head(
    frame: &Frame,
    centre: [f64; 2],
    s: f64,
    h: f64,
    (skin, hair): (&mut Solid, &mut Solid),
    cap: Cap,
) {
    let (half_u, half_y) = (0.1 * s, 0.065 * h);
    let octagon = |scale: f64| -> Vec<[f64; 2]> {
        (0..8)
            .map(|k| {
                let (c, sn) = trig::cos_sin_deg(22.5 + 45.0 * f64::from(k));
                [
                    centre[0] + c * half_u * scale,
                    centre[1] + sn * half_y * scale,
                ]
            })
            .collect()
    };
    skin.prism(frame, &octagon(1.0), [-0.075 * s, 0.075 * s], &[]);
    let big = octagon(cap.scale);
    let outline = [
        big[0],
        big[1],
        big[2],
        big[3],
        [big[3][0], centre[1] - cap.nape * half_y],
    ];
    hair.prism(frame, &outline, [-cap.half_width, cap.half_width], &[]);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn figure(height: f64, stride: f64) -> Figure {
        Figure {
            height,
            build: 1.12,
            stride,
            sleeve: 0.35,
        }
    }

    const CLOTHES: Clothes = Clothes {
        shirt: 0,
        trousers: 1,
        skin: 2,
        hair: 3,
        shoes: 4,
    };

    #[test]
    fn a_figure_stands_on_the_ground_inside_its_room_and_is_as_tall_as_drawn() {
        let frame = Frame {
            origin: [10.0, 0.2, -4.0],
            forward: [0.6, 0.8],
        };
        for (height, stride) in [(1.5, 0.0), (1.95, 18.0), (2.3, 18.0), (1.7, 3.0)] {
            let meshes = person_meshes(&frame, &figure(height, stride), CLOTHES);
            // One mesh per material, in a fixed order.
            let materials: Vec<u32> = meshes.iter().map(|m| m.material).collect();
            assert_eq!(materials, [1, 4, 0, 2, 3]);
            let points: Vec<[f64; 3]> = meshes
                .iter()
                .flat_map(|m| &m.positions)
                .map(|p| p.map(f64::from))
                .collect();
            let low = points.iter().map(|p| p[1]).fold(f64::MAX, f64::min);
            let top = points.iter().map(|p| p[1]).fold(f64::MIN, f64::max);
            assert!((low - 0.2).abs() < 1e-5, "{low}");
            // The hair cap rises a little over the head's 0.13 h.
            assert!(
                top > 0.2 + 0.99 * height && top < 0.2 + 1.01 * height,
                "{top}"
            );
            for p in &points {
                let (dx, dz) = (p[0] - 10.0, p[2] + 4.0);
                assert!(dx * dx + dz * dz < ROOM * ROOM, "{p:?} at {height} m");
            }
            for m in &meshes {
                assert_eq!(m.positions.len(), m.normals.len());
                assert!(m.indices.len() % 3 == 0 && !m.indices.is_empty());
            }
            let triangles: usize = meshes.iter().map(|m| m.indices.len() / 3).sum();
            assert_eq!(triangles, 164);
        }
    }

    #[test]
    fn a_walker_swings_the_left_leg_forward_and_the_right_arm_with_it() {
        // Facing +x (east): its right is +z, its left −z.
        let frame = Frame {
            origin: [0.0; 3],
            forward: [1.0, 0.0],
        };
        let meshes = person_meshes(&frame, &figure(1.75, 20.0), CLOTHES);
        let shoes = &meshes[1];
        // Shoe soles ahead of the hips are on the left (z < 0), behind on the right.
        for p in shoes.positions.iter().filter(|p| p[1] == 0.0) {
            if p[0] > 0.25 {
                assert!(p[2] < 0.0, "{p:?}");
            }
            if p[0] < -0.25 {
                assert!(p[2] > 0.0, "{p:?}");
            }
        }
        // The hands (skin below the hips) swing the other way: the right one forward.
        let skin = &meshes[3];
        for p in skin.positions.iter().filter(|p| f64::from(p[1]) < 0.8) {
            if p[0] > 0.1 {
                assert!(p[2] > 0.0, "{p:?}");
            }
        }
    }
}
