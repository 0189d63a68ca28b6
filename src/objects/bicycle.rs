//! Bicycle specs + road slots and sidewalk strip spots → `bicycle_NNNN` objects, and a
//! `rider_NNNN` (class `rider`) on each bicycle ridden in the road: low-poly city bicycles
//! with seeded frame paint, and riders seeded in height, build, clothes and helmet.
//!
//! A bicycle (local frame: `u` forward, `y` up, `v` to the right; the origin on the ground
//! midway between the hubs) has two wheels of 0.68 m as rings of [`RIM_SEGMENTS`]
//! segments with hubs, a diamond frame of tubes (chain and seat stays, seat, top and down
//! tubes, fork), a seat post and saddle, a stem and a handlebar 0.56 m wide, and cranks
//! with pedals at a seeded angle: 396 triangles. Its saddle height follows its rider.
//!
//! A rider sits on the saddle leaning forward, hands on the grips, each foot on a pedal
//! (the knee found from the thigh and shin lengths), head up: the same proportions,
//! palettes and flat-shaded parts as a pedestrian's ([`super::person`]), with a helmet on
//! two riders in three.
//!
//! Where: `parked` of them stand in the sidewalk strips, parallel to the curb, a metre
//! from it, on the ground a walker leaves free; the others are ridden in the driving lanes
//! with the traffic, right of a lane's middle, in the lanes lane cars may use (clear of the
//! line a default roads camera drives, [`CAMERA_LANE`]), behind the stop lines. A ridden
//! bicycle and its rider take one rectangle of the road ([`RIDDEN_HALF`]), a parked one a
//! circle of [`PARKED_ROOM`]: they never overlap cars, people, lamps, trees or each other.

use rand::RngExt;
use rand_pcg::Pcg64;

use super::car::{CAMERA_CLEARANCE, CAMERA_LANE};
use super::ground_spots::{RoadSlot, StripSpots};
use super::person::{self, Cap, HAIR, SHIRTS, SHOES, SKIN, TROUSERS, WALKER_ROOM};
use super::person_pose::{ANKLE, ELBOW, HIP, KNEE, SHOULDER, WRIST};
use super::vehicle_parts::{Frame, Solid, finish_all};
use super::{ATTEMPTS, GIVE_UP, Placing, trig};
use crate::model::Mesh;
use crate::model::geometry::{KERB_Y, ROAD_Y, STOP_LINE_END, StreetProfile, WALK_SHARE};
use crate::spec::{ObjectSpec, RIDER_CLASS};

/// Half the length and half the width of the road a ridden bicycle and its rider take,
/// metres (the wheels' 1.72 m and the handlebar's 0.56 m, with a little room).
pub const RIDDEN_HALF: [f64; 2] = [0.92, 0.34];
/// Ground a parked bicycle takes: the radius of its circle, metres.
pub const PARKED_ROOM: f64 = 0.95;
/// How far right of its lane's middle a ridden bicycle keeps, metres.
pub const RIGHT_OF_MIDDLE: f64 = 0.6;
/// Segments of a wheel's rim.
pub const RIM_SEGMENTS: u32 = 12;

/// Wheel radius (tyre included) and the rim's radial depth, metres.
const WHEEL: f64 = 0.34;
const RIM: f64 = 0.045;
/// Hubs, `u` metres from the origin, at the wheel's height.
const HUB_U: f64 = 0.52;
/// The bottom bracket (where the cranks turn), `(u, y)`.
const BRACKET: [f64; 2] = [-0.06, 0.28];
const CRANK: f64 = 0.17;
/// Head tube: bottom and top, `(u, y)`.
const HEAD_BOTTOM: [f64; 2] = [0.36, 0.64];
const HEAD_TOP: [f64; 2] = [0.32, 0.8];
/// Tubes' thickness, and the frame's and wheels' half width across.
const TUBE: f64 = 0.035;
const FRAME_HALF: f64 = 0.02;
const HANDLEBAR_HALF: f64 = 0.28;

/// Frame paints, linear RGB.
const PAINTS: [[f32; 3]; 8] = [
    [0.02, 0.02, 0.022],
    [0.6, 0.6, 0.58],
    [0.35, 0.02, 0.02],
    [0.02, 0.06, 0.3],
    [0.03, 0.15, 0.05],
    [0.42, 0.42, 0.44],
    [0.65, 0.42, 0.03],
    [0.08, 0.25, 0.35],
];
const BLACK: [f32; 3] = [0.015, 0.015, 0.015];
/// Helmet shells, linear RGB.
const HELMETS: [[f32; 3]; 4] = [
    [0.7, 0.7, 0.68],
    [0.02, 0.02, 0.02],
    [0.5, 0.03, 0.02],
    [0.03, 0.1, 0.4],
];

/// One bicycle's looks: the pedals' angle and the saddle's height.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bike {
    /// Crank angle, degrees (0: the right pedal forward).
    pub crank: f64,
    /// Top of the saddle above the ground, metres.
    pub saddle: f64,
}

/// One rider's looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rider {
    /// Height standing, metres.
    pub height: f64,
    /// Width and depth factor around 1.
    pub build: f64,
    /// Forward lean of the back from the vertical, degrees.
    pub lean: f64,
}

/// Materials of a bicycle and of its rider.
#[derive(Clone, Copy, Debug)]
pub struct BikeMaterials {
    pub paint: u32,
    pub black: u32,
}

#[derive(Clone, Copy, Debug)]
pub struct RiderMaterials {
    pub shirt: u32,
    pub trousers: u32,
    pub skin: u32,
    /// The helmet's shell, or the hair.
    pub head: u32,
    pub shoes: u32,
}

/// The saddle height that suits a rider of `height` metres: the hips a little above it,
/// the leg nearly straight at the lower pedal.
pub fn saddle_for(height: f64) -> f64 {
    0.3 + 0.35 * height
}

/// Places the entry's bicycles (and riders); returns how many bicycles.
// Long on purpose: one placement loop, whose random draws must stay in this order (each
// changes every later object's); split, the order would be spread over functions.
pub fn place(
    spec: &ObjectSpec,
    rng: &mut Pcg64,
    spots: &mut impl StripSpots,
    placing: &mut Placing,
) -> u32 {
    let mut placed = 0;
    let [low, high] = spec.height_range();
    // Parked: a metre from the curb, clear of the line a sidewalks camera walks, on a
    // sidewalk `strip` metres wide.
    let from_curb = |strip: f64| {
        let far = strip * (1.0 - WALK_SHARE) - WALKER_ROOM - PARKED_ROOM;
        PARKED_ROOM.max(1.0).min(far.max(PARKED_ROOM))
    };
    let mut misses = 0;
    for _ in 0..spec.count {
        if misses >= GIVE_UP {
            break;
        }
        misses += 1;
        let parked = rng.random::<f64>() < spec.parked;
        let lane_pick: f64 = rng.random();
        let mut lane = None;
        let (frame, ridden) = if parked {
            let Some(spot) =
                (0..ATTEMPTS).find_map(|_| spots.strip_at(rng, PARKED_ROOM, from_curb, 1))
            else {
                continue;
            };
            let back = rng.random::<bool>();
            let forward = spot.travel.map(|t| if back { -t } else { t });
            let origin = [spot.position[0], KERB_Y, spot.position[1]];
            (Frame { origin, forward }, false)
        } else {
            let slot = |width: f64| {
                let profile = StreetProfile::of(width);
                let free: Vec<f64> = (0..profile.lanes)
                    .map(|k| profile.lane_centre(k) + RIGHT_OF_MIDDLE)
                    .filter(|c| (c - CAMERA_LANE).abs() >= RIDDEN_HALF[1] + CAMERA_CLEARANCE)
                    .filter(|c| c + RIDDEN_HALF[1] <= profile.half - profile.parking)
                    .collect();
                let offset = *free.get((lane_pick * free.len() as f64) as usize)?;
                Some(RoadSlot {
                    half: RIDDEN_HALF,
                    offset,
                    crossing_clearance: STOP_LINE_END,
                    gap: 1.5,
                    parked: false,
                })
            };
            let Some(spot) = spots.road(rng, ATTEMPTS, slot) else {
                continue;
            };
            let origin = [spot.position[0], ROAD_Y, spot.position[1]];
            let forward = spot.travel;
            lane = Some(crate::model::LaneVehicle {
                road: spot.road,
                travel: spot.travel,
                centre: spot.position,
                half: RIDDEN_HALF,
                bicycle: true,
            });
            (Frame { origin, forward }, true)
        };
        misses = 0;
        placed += 1;
        let rider = Rider {
            height: low + rng.random::<f64>() * (high - low),
            build: 0.88 + 0.2 * rng.random::<f64>(),
            lean: 25.0 + 20.0 * rng.random::<f64>(),
        };
        let bike = Bike {
            crank: rng.random::<f64>() * 360.0,
            saddle: saddle_for(rider.height),
        };
        let paint = rng.random_range(0..PAINTS.len());
        let materials = BikeMaterials {
            paint: placing.material(&format!("bicycle_paint_{paint:02}"), || {
                (PAINTS[paint], None)
            }),
            black: placing.material("bicycle_black", || (BLACK, None)),
        };
        let name = placing.name("bicycle");
        placing.push_plain(
            crate::model::ObjectKind::Bicycle,
            name,
            &spec.label,
            bicycle_meshes(&frame, &bike, materials),
        );
        if let Some(lane) = lane {
            placing.set_traffic(crate::model::TrafficRole::Vehicle(lane));
        }
        if ridden {
            let helmet = rng.random::<f64>() < 2.0 / 3.0;
            let mut pick =
                |name: &str, palette: &[[f32; 3]]| placing.palette_material(rng, name, palette);
            let clothes = RiderMaterials {
                shirt: pick("person_shirt", &SHIRTS),
                trousers: pick("person_trousers", &TROUSERS),
                skin: pick("person_skin", &SKIN),
                shoes: pick("person_shoes", &SHOES),
                head: if helmet {
                    pick("rider_helmet", &HELMETS)
                } else {
                    pick("person_hair", &HAIR)
                },
            };
            let name = placing.name("rider");
            placing.push_figure(
                crate::model::ObjectKind::Rider,
                name,
                RIDER_CLASS,
                rider_meshes(&frame, &bike, &rider, clothes),
                std::collections::BTreeMap::new(),
                Some(rider_keypoints(&frame, &bike, &rider)),
            );
            placing.set_traffic(crate::model::TrafficRole::Carried { back: 1 });
        }
    }
    placed
}

/// The right pedal's position `(u, y)` (the left one is opposite it about the bracket).
fn pedal(bike: &Bike, side: f64) -> [f64; 2] {
    let (c, s) = trig::cos_sin_deg(bike.crank);
    [BRACKET[0] + side * CRANK * c, BRACKET[1] + side * CRANK * s]
}

/// The handlebar's grips `(u, y)`.
fn grips(bike: &Bike) -> [f64; 2] {
    [HEAD_TOP[0] - 0.04, bike.saddle + 0.06]
}

/// The saddle's middle `(u, y)`, on its top.
fn saddle_point(bike: &Bike) -> [f64; 2] {
    let rise = bike.saddle - BRACKET[1];
    // The seat tube leans back at about 17°: 0.3 of the rise.
    [BRACKET[0] - 0.3 * rise, bike.saddle]
}

/// The solids of `bike` standing at `frame`'s origin, facing its forward: the frame paint,
/// then the black parts (tyres, saddle, handlebar, cranks and pedals).
// Long on purpose: builds one figure part by part from a dozen shared dimensions, in the
// order its meshes are listed; split, each part would take them all as arguments.
pub fn bicycle_meshes(frame: &Frame, bike: &Bike, m: BikeMaterials) -> Vec<Mesh> {
    let mut paint = Solid::new(m.paint);
    let mut black = Solid::new(m.black);
    let wide = [-FRAME_HALF, FRAME_HALF];
    // Wheels: rings of straight segments, outer radius WHEEL.
    for hub_u in [-HUB_U, HUB_U] {
        for k in 0..RIM_SEGMENTS {
            let at = |j: u32, r: f64| {
                let (c, s) = trig::cos_sin_deg(360.0 * f64::from(j) / f64::from(RIM_SEGMENTS));
                [hub_u + r * c, WHEEL + r * s]
            };
            let profile = [
                at(k, WHEEL - RIM),
                at(k, WHEEL),
                at(k + 1, WHEEL),
                at(k + 1, WHEEL - RIM),
            ];
            // Without the faces between segments (edges 0 and 2), which nothing sees.
            black.prism(frame, &profile, [-0.018, 0.018], &[0, 2]);
        }
        // The hub (spokes are under a pixel wide at street distances: left out).
        paint.bar(
            frame,
            [hub_u - 0.03, WHEEL],
            [hub_u + 0.03, WHEEL],
            0.06,
            [-0.04, 0.04],
        );
    }
    let (rear, front) = ([-HUB_U, WHEEL], [HUB_U, WHEEL]);
    let seat_top = {
        // The seat tube's top, just under the saddle's post.
        let s = saddle_point(bike);
        let t = (0.78 - BRACKET[1]) / (s[1] - BRACKET[1]);
        [
            BRACKET[0] + (s[0] - BRACKET[0]) * t,
            BRACKET[1] + (s[1] - BRACKET[1]) * t,
        ]
    };
    for (a, b) in [
        (rear, BRACKET),        // chain stays
        (rear, seat_top),       // seat stays
        (BRACKET, seat_top),    // seat tube
        (seat_top, HEAD_TOP),   // top tube
        (BRACKET, HEAD_BOTTOM), // down tube
        (HEAD_BOTTOM, HEAD_TOP),
        (HEAD_BOTTOM, front), // fork
    ] {
        paint.bar(frame, a, b, TUBE, wide);
    }
    // Seat post and saddle.
    let saddle = saddle_point(bike);
    black.bar(frame, seat_top, [saddle[0], saddle[1] - 0.04], 0.025, wide);
    black.cuboid(
        frame,
        [saddle[0] - 0.12, saddle[0] + 0.1],
        [saddle[1] - 0.05, saddle[1]],
        [-0.07, 0.07],
    );
    // Stem and handlebar.
    let grip = grips(bike);
    black.bar(frame, HEAD_TOP, grip, 0.03, wide);
    black.bar(
        frame,
        [grip[0] - 0.015, grip[1]],
        [grip[0] + 0.015, grip[1]],
        0.03,
        [-HANDLEBAR_HALF, HANDLEBAR_HALF],
    );
    // Cranks and pedals, the right ones outside the frame's right side.
    for side in [-1.0, 1.0] {
        let p = pedal(bike, side);
        let v = [side * 0.03, side * 0.05];
        let v = [v[0].min(v[1]), v[0].max(v[1])];
        black.bar(frame, BRACKET, p, 0.025, v);
        let pv = [side * 0.05, side * 0.14];
        black.cuboid(
            frame,
            [p[0] - 0.05, p[0] + 0.05],
            [p[1] - 0.012, p[1] + 0.012],
            [pv[0].min(pv[1]), pv[0].max(pv[1])],
        );
    }
    finish_all(vec![paint, black])
}

/// The knee between `hip` and `foot` for a thigh and a shin of the given lengths, ahead of
/// the line between them (a straight leg when they are too far apart).
fn knee(hip: [f64; 2], foot: [f64; 2], thigh: f64, shin: f64) -> [f64; 2] {
    let d = [foot[0] - hip[0], foot[1] - hip[1]];
    let len = (d[0] * d[0] + d[1] * d[1]).sqrt().max(1e-9);
    let dir = [d[0] / len, d[1] / len];
    let along = ((len * len + thigh * thigh - shin * shin) / (2.0 * len)).clamp(0.0, thigh);
    let out = (thigh * thigh - along * along).max(0.0).sqrt();
    // Ahead: the normal of the hip-to-foot line that points forward (+u).
    let mut n = [-dir[1], dir[0]];
    if n[0] < 0.0 {
        n = [-n[0], -n[1]];
    }
    [
        hip[0] + dir[0] * along + n[0] * out,
        hip[1] + dir[1] * along + n[1] * out,
    ]
}

/// Where a rider's joints are on its bike, in the bike's `(u, y)` plane: hips on the
/// saddle, the back leaning forward, feet on the pedals, hands on the grips.
struct RiderRig {
    /// Its width and depth factor `s`: `h / 1.75` times the build.
    s: f64,
    hip: [f64; 2],
    shoulder: [f64; 2],
    /// Left (on the pedal at `side` −1), then right: knee and ankle.
    knees: [[f64; 2]; 2],
    ankles: [[f64; 2]; 2],
    elbow: [f64; 2],
    grip: [f64; 2],
    /// The head's centre.
    head: [f64; 2],
}

impl RiderRig {
    fn of(bike: &Bike, rider: &Rider) -> RiderRig {
        let h = rider.height;
        let s = h / 1.75 * rider.build;
        let saddle = saddle_point(bike);
        let hip = [saddle[0] - 0.02, saddle[1] + 0.06];
        let (lc, ls) = trig::cos_sin_deg(rider.lean);
        let back = 0.32 * h;
        let shoulder = [hip[0] + ls * back, hip[1] + lc * back];
        let (thigh, shin) = (0.25 * h, 0.25 * h);
        let ankles = [-1.0, 1.0].map(|side| {
            let foot = pedal(bike, side);
            [foot[0] - 0.03, foot[1] + 0.05]
        });
        let grip = grips(bike);
        RiderRig {
            s,
            hip,
            shoulder,
            knees: ankles.map(|ankle| knee(hip, ankle, thigh, shin)),
            ankles,
            elbow: [
                shoulder[0] + (grip[0] - shoulder[0]) * 0.5,
                shoulder[1] + (grip[1] - shoulder[1]) * 0.5,
            ],
            grip,
            head: [shoulder[0] + 0.07 * s, shoulder[1] + 0.1 * h],
        }
    }

    /// The middle across (`v`) of a leg on `side` (−1 left, 1 right).
    fn leg_v(&self, side: f64) -> f64 {
        side * (0.05 + 0.06 * self.s)
    }

    /// The middle across (`v`) of an arm on `side`.
    fn arm_v(&self, side: f64) -> f64 {
        side * 0.21 * self.s
    }
}

/// The solids of `rider` on `bike` at `frame`: trousers, shoes, shirt, skin, and the
/// helmet or hair.
pub fn rider_meshes(frame: &Frame, bike: &Bike, rider: &Rider, m: RiderMaterials) -> Vec<Mesh> {
    let h = rider.height;
    let rig = RiderRig::of(bike, rider);
    let s = rig.s;
    let (mut shirt, mut trousers, mut skin, mut head, mut shoes) = (
        Solid::new(m.shirt),
        Solid::new(m.trousers),
        Solid::new(m.skin),
        Solid::new(m.head),
        Solid::new(m.shoes),
    );
    let (hip, shoulder) = (rig.hip, rig.shoulder);
    // Legs: thigh and shin to each pedal, the shoe along the pedal.
    let leg = 0.13 * s;
    for (i, side) in [(0, -1.0), (1, 1.0)] {
        let foot = pedal(bike, side);
        let (k, ankle) = (rig.knees[i], rig.ankles[i]);
        let inner = side * 0.05;
        let outer = side * (0.05 + 0.12 * s);
        let v = [inner.min(outer), inner.max(outer)];
        trousers.bar(frame, hip, k, leg, v);
        trousers.bar(frame, k, ankle, 0.8 * leg, v);
        shoes.bar(
            frame,
            [foot[0] - 0.08, foot[1] + 0.03],
            [foot[0] + 0.1, foot[1] + 0.03],
            0.07,
            v,
        );
    }
    // Torso from the hips to the shoulders, leaning forward.
    shirt.bar(frame, hip, shoulder, 0.22 * s, [-0.18 * s, 0.18 * s]);
    // Arms straight from the shoulders to the grips: sleeve, then forearm.
    let (elbow, grip) = (rig.elbow, rig.grip);
    for side in [-1.0, 1.0] {
        let inner = side * 0.17 * s;
        let outer = side * (0.17 * s + 0.08 * s);
        let v = [inner.min(outer), inner.max(outer)];
        shirt.bar(frame, shoulder, elbow, 0.085 * s, v);
        skin.bar(frame, elbow, grip, 0.075 * s, v);
    }
    // Neck and head, the face looking ahead; a helmet or hair over its top and back.
    let centre = rig.head;
    skin.bar(frame, shoulder, centre, 0.09 * s, [-0.045 * s, 0.045 * s]);
    let cap = Cap {
        scale: 1.15,
        nape: 0.5,
        half_width: 0.085 * s,
    };
    person::head(frame, centre, s, h, (&mut skin, &mut head), cap);
    finish_all(vec![trousers, shoes, shirt, skin, head])
}

/// The 17 COCO keypoints of `rider` on `bike` at `frame`, in world metres: the face's as
/// on a pedestrian's head ([`super::person_pose`]), the joints of its limbs in the middle
/// of each limb across; the wrist a hand's length (0.065 h) short of the grip.
pub fn rider_keypoints(frame: &Frame, bike: &Bike, rider: &Rider) -> [[f64; 3]; 17] {
    let (h, rig) = (rider.height, RiderRig::of(bike, rider));
    let s = rig.s;
    let [hu, hy] = rig.head;
    let forearm = [rig.grip[0] - rig.elbow[0], rig.grip[1] - rig.elbow[1]];
    let length = (forearm[0] * forearm[0] + forearm[1] * forearm[1])
        .sqrt()
        .max(1e-9);
    let back = (0.065 * h).min(length) / length;
    let wrist = [
        rig.grip[0] - forearm[0] * back,
        rig.grip[1] - forearm[1] * back,
    ];
    let mut k = [[0.0; 3]; 17];
    k[0] = [hu + 0.09 * s, hy - 0.01 * h, 0.0];
    for (i, side) in [(0, -1.0), (1, 1.0)] {
        k[1 + i] = [hu + 0.075 * s, hy + 0.01 * h, side * 0.035 * s];
        k[3 + i] = [hu, hy, side * 0.075 * s];
        let (arm, leg) = (rig.arm_v(side), rig.leg_v(side));
        k[SHOULDER + i] = [rig.shoulder[0], rig.shoulder[1], arm];
        k[ELBOW + i] = [rig.elbow[0], rig.elbow[1], arm];
        k[WRIST + i] = [wrist[0], wrist[1], arm];
        k[HIP + i] = [rig.hip[0], rig.hip[1], leg];
        k[KNEE + i] = [rig.knees[i][0], rig.knees[i][1], leg];
        k[ANKLE + i] = [rig.ankles[i][0], rig.ankles[i][1], leg];
    }
    k.map(|[u, y, v]| frame.at(u, y, v))
}

#[cfg(test)]
mod tests {
    use super::*;

    const BIKE_PAINTS: BikeMaterials = BikeMaterials { paint: 0, black: 1 };
    const CLOTHES: RiderMaterials = RiderMaterials {
        shirt: 0,
        trousers: 1,
        skin: 2,
        head: 3,
        shoes: 4,
    };

    fn points(meshes: &[Mesh]) -> Vec<[f64; 3]> {
        meshes
            .iter()
            .flat_map(|m| &m.positions)
            .map(|p| p.map(f64::from))
            .collect()
    }

    #[test]
    fn a_bicycle_stands_on_its_wheels_inside_its_rectangle() {
        let inv = std::f64::consts::FRAC_1_SQRT_2;
        for (forward, crank, height) in [
            ([1.0, 0.0], 0.0, 1.5),
            ([0.0, -1.0], 90.0, 1.95),
            ([inv, inv], 217.0, 1.75),
        ] {
            let frame = Frame {
                origin: [3.0, 0.02, -7.0],
                forward,
            };
            let bike = Bike {
                crank,
                saddle: saddle_for(height),
            };
            let meshes = bicycle_meshes(&frame, &bike, BIKE_PAINTS);
            let materials: Vec<u32> = meshes.iter().map(|m| m.material).collect();
            assert_eq!(materials, [0, 1]);
            let all = points(&meshes);
            let low = all.iter().map(|p| p[1]).fold(f64::MAX, f64::min);
            assert!((low - 0.02).abs() < 1e-5, "{low}");
            // Only the tyres touch the ground: two contact points under the hubs.
            for p in all.iter().filter(|p| p[1] < 0.03) {
                let u = (p[0] - 3.0) * forward[0] + (p[2] + 7.0) * forward[1];
                assert!((u.abs() - HUB_U).abs() < 0.1, "{p:?}");
            }
            for p in &all {
                let d = [p[0] - 3.0, p[2] + 7.0];
                let u = d[0] * forward[0] + d[1] * forward[1];
                let v = d[0] * -forward[1] + d[1] * forward[0];
                assert!(
                    u.abs() <= RIDDEN_HALF[0] && v.abs() <= RIDDEN_HALF[1],
                    "{p:?}"
                );
                assert!(
                    d[0] * d[0] + d[1] * d[1] < PARKED_ROOM * PARKED_ROOM,
                    "{p:?}"
                );
            }
            let triangles: usize = meshes.iter().map(|m| m.indices.len() / 3).sum();
            assert_eq!(triangles, 396);
        }
    }

    /// Three riders of `build` on their bikes: short, tall and middling, at three crank
    /// angles and leans.
    fn test_riders(build: f64) -> Vec<(Bike, Rider)> {
        [(1.5, 0.0, 25.0), (1.95, 130.0, 45.0), (1.75, 300.0, 35.0)]
            .into_iter()
            .map(|(height, crank, lean)| {
                let bike = Bike {
                    crank,
                    saddle: saddle_for(height),
                };
                (
                    bike,
                    Rider {
                        height,
                        build,
                        lean,
                    },
                )
            })
            .collect()
    }

    #[test]
    fn a_rider_sits_on_the_saddle_with_feet_on_the_pedals_and_hands_on_the_grips() {
        let frame = Frame {
            origin: [0.0; 3],
            forward: [1.0, 0.0],
        };
        for (bike, rider) in test_riders(1.08) {
            let height = rider.height;
            let meshes = rider_meshes(&frame, &bike, &rider, CLOTHES);
            let materials: Vec<u32> = meshes.iter().map(|m| m.material).collect();
            assert_eq!(materials, [1, 4, 0, 2, 3]);
            let all = points(&meshes);
            // Inside the ridden rectangle, above the ground, about as tall as standing.
            for p in &all {
                assert!(
                    p[0].abs() <= RIDDEN_HALF[0] && p[2].abs() <= RIDDEN_HALF[1],
                    "{p:?}"
                );
                assert!(p[1] > 0.0 && p[1] < height + 0.15, "{p:?}");
            }
            // Shoes reach both pedals, one on each side of the frame.
            let shoes = points(&meshes[1..2]);
            for side in [-1.0, 1.0] {
                let p = pedal(&bike, side);
                let near = shoes.iter().any(|s| {
                    s[2] * side > 0.0 && (s[0] - p[0]).abs() < 0.12 && (s[1] - p[1]).abs() < 0.08
                });
                assert!(near, "no shoe at the pedal {p:?} on side {side}");
            }
            // The thigh and shin keep their lengths: each knee joins two bars.
            let hip = [saddle_point(&bike)[0] - 0.02, bike.saddle + 0.06];
            let ankle = {
                let f = pedal(&bike, 1.0);
                [f[0] - 0.03, f[1] + 0.05]
            };
            let k = knee(hip, ankle, 0.25 * height, 0.25 * height);
            let len =
                |a: [f64; 2], b: [f64; 2]| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
            assert!((len(hip, k) - 0.25 * height).abs() < 1e-9);
            assert!(len(k, ankle) <= 0.25 * height + 1e-9);
            assert!(k[0] > hip[0].min(ankle[0]), "the knee points forward");
            // The top of the head: below standing height, above the handlebar.
            let top = all.iter().map(|p| p[1]).fold(f64::MIN, f64::max);
            assert!(top > grips(&bike)[1] + 0.4, "{top}");
        }
    }

    #[test]
    fn a_riders_keypoints_lie_on_its_body_left_and_right_where_they_belong() {
        let frame = Frame {
            origin: [2.0, 0.1, -3.0],
            forward: [0.6, -0.8],
        };
        let right = frame.dir(0.0, 0.0, 1.0);
        let across = |p: [f64; 3]| (p[0] - 2.0) * right[0] + (p[2] + 3.0) * right[2];
        let apart = |a: [f64; 3], b: [f64; 3]| {
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
        };
        for (bike, rider) in test_riders(0.95) {
            let height = rider.height;
            let meshes = rider_meshes(&frame, &bike, &rider, CLOTHES);
            let k = rider_keypoints(&frame, &bike, &rider);
            for (i, &p) in k.iter().enumerate() {
                let near = person::tests::surface_distance(&meshes, p);
                assert!(near < 0.05, "{height} keypoint {i}: {near}");
            }
            for left in [1, 3, SHOULDER, ELBOW, WRIST, HIP, KNEE, ANKLE] {
                assert!(across(k[left]) < 0.0 && across(k[left + 1]) > 0.0, "{left}");
            }
            // Hands on the grips, feet on the pedals (left on the pedal at side −1).
            let grip = grips(&bike);
            for (i, side) in [(0, -1.0), (1, 1.0)] {
                let at_grip = frame.at(grip[0], grip[1], across(k[WRIST + i]));
                assert!(apart(k[WRIST + i], at_grip) < 0.07 * height, "wrist {i}");
                let foot = pedal(&bike, side);
                let on_pedal = frame.at(foot[0], foot[1], across(k[ANKLE + i]));
                assert!(apart(k[ANKLE + i], on_pedal) < 0.07, "ankle {i}");
            }
            // The nose ahead of the ears and above the shoulders, which are above the hips
            // (the back, 0.32 h, leans up to 45°).
            let ahead = |p: [f64; 3]| (p[0] - 2.0) * 0.6 - (p[2] + 3.0) * 0.8;
            assert!(ahead(k[0]) > ahead(k[3]) && k[0][1] > k[SHOULDER][1]);
            assert!(k[SHOULDER][1] > k[HIP][1] + 0.2 * height);
        }
    }
}
