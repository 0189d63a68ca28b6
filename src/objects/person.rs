//! Person specs + sidewalk strip spots → `person_NNNN` objects: low-poly pedestrians,
//! walking along the street or standing, seeded in height, build, pose and clothes.
//!
//! A person is flat-shaded boxes on a [`Skeleton`] (`person_pose`, whose joints include
//! the 17 COCO keypoints) in five materials (236 triangles), and a sixth for a prop (248):
//! two legs of thigh and shin, shoes, a torso, two arms of upper arm, forearm and hand
//! (sleeves and bare forearms, or long sleeves), a neck, a rounded head and a hair cap.
//! Proportions follow the figure's height `h`: hips at 0.5 h, shoulders at 0.8 h, the head
//! the top 0.13 h; width and depth scale with `h / 1.75` and a seeded build.
//!
//! A walker faces along the street (either way) mid-stride, legs swung opposite and arms
//! against them; a standing figure faces any way, legs nearly straight. Each draws a
//! [`Pose`] for its arms (the `pose` attribute): walkers swing them (half of them), look at
//! a phone held before the chest, hold one to the ear, carry a bag or keep their hands in
//! their pockets; standing people let them hang (three in ten), hold a phone either way or
//! a bag, cross their arms or keep their hands in their pockets. A phone or bag is in the
//! right hand, one time in eight the left.
//!
//! People stand in the sidewalk strips between the curb and the line a `sidewalks` camera
//! walks ([`WALKER_ROOM`] clear of it; it runs [`WALK_SHARE`] of the strip from the shop
//! fronts), each taking a circle of [`ROOM`] of ground, so they never overlap lamps, signs,
//! trees, benches, cars or each other. The entry's `crossing` share walk across the zebra
//! crossings instead, on the zebra's paint, within [`ZEBRA_REACH`] of the road's centre
//! line (lane cars wait behind the stop lines, clear of them). Its `waiting` share of the
//! others stand at the zebras' ends, at the curb, facing the road as if about to cross (as
//! many as the ends hold; the rest join the strips). On a map, its `parks` share of the
//! rest stand or walk on the paths across the parks, [`ROOM`] inside their edges, walkers
//! along the path, and its `squares` share of the rest after them on the squares, facing
//! any way (as many as the paths and squares hold; the rest join the strips).
//!
//! For moving traffic each walking person gets a [`TrafficRole::Pedestrian`]: a person
//! crossing (or waiting to) keeps to the half of its zebra on its right and takes its
//! whole way over to its place on the far side, [`CURB_ROOM`] past the far curb (or as far
//! past it as it waits); a person walking along a strip may walk as far as nothing that
//! stands is in its way, up to its block's corner ([`walk_on`], once every entry is
//! placed).

use rand::RngExt;
use rand_pcg::Pcg64;

use std::collections::BTreeMap;

use super::car::{CAMERA_CLEARANCE, CAMERA_LANE};
use super::ground_spots::{GroundSpots, Spot, StripSpots};
use super::person_pose::{
    self, ANKLE, ELBOW, HIP, KNEE, Pose, Prop, SHOULDER, Skeleton, WRIST, along,
};
use super::vehicle_parts::{Frame, Solid, finish_all};
use super::{ATTEMPTS, GIVE_UP, Placing};
use crate::model::geometry::{KERB_Y, MARKING_Y, WALK_SHARE, cross, dot, normalize, sub, trig};
use crate::model::{Crossing, Mesh, TrafficRole, Walk};
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
/// Bags: black, brown leather, tan, navy, red, a white shopping bag.
const BAGS: [[f32; 3]; 6] = [
    [0.02, 0.02, 0.02],
    [0.12, 0.05, 0.02],
    [0.4, 0.25, 0.12],
    [0.02, 0.03, 0.1],
    [0.4, 0.03, 0.03],
    [0.7, 0.7, 0.68],
];
/// A phone's dark case.
const PHONE: [f32; 3] = [0.015, 0.015, 0.02];

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
    /// Share of the arm (to the wrist) in sleeve, from the shoulder (0.35 short, 0.9 long).
    pub sleeve: f64,
    /// What the figure is doing.
    pub pose: Pose,
    /// The side of the hand holding a prop (a phone, a bag): −1 left, 1 right.
    pub holding: f64,
}

impl Figure {
    /// Its width and depth factor `s`: `h / 1.75` times the build.
    fn width(&self) -> f64 {
        self.height / 1.75 * self.build
    }

    /// Its joints in its own frame (`u` forward, `y` up from the soles, `v` to its right),
    /// the 17 COCO keypoints among them; `Frame::at` places them in the world.
    pub fn skeleton(&self) -> Skeleton {
        let s = self.width();
        person_pose::skeleton(self.pose, self.height, s, self.stride, self.holding)
    }

    /// Its 17 COCO keypoints standing at `frame`'s origin, facing its forward, in world
    /// metres.
    pub fn keypoints(&self, frame: &Frame) -> [[f64; 3]; 17] {
        self.skeleton().keypoints.map(|[u, y, v]| frame.at(u, y, v))
    }
}

// Long on purpose: one placement loop, whose random draws must stay in this order (each
// changes every later object's); split, the order would be spread over functions.
pub fn place(
    spec: &ObjectSpec,
    rng: &mut Pcg64,
    spots: &mut impl StripSpots,
    placing: &mut Placing,
) {
    let [low, high] = spec.height_range();
    // Between the curb and the sidewalk camera's line, clear of both, on a sidewalk
    // `strip` metres wide.
    let far = |strip: f64| (strip * (1.0 - WALK_SHARE) - WALKER_ROOM).max(CURB_ROOM);
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
        let mut way = None;
        if crossing {
            way = (0..ATTEMPTS).find_map(|_| spots.zebra(rng, ROOM, ZEBRA_REACH, CURB_ROOM, 1));
        } else if waiting {
            let from_curb = CURB_ROOM + rng.random::<f64>() * WAITING_DEPTH;
            way = (0..ATTEMPTS).find_map(|_| spots.zebra_kerb(rng, ROOM, from_curb, 1));
            // With the zebras' ends full, this one stands in a strip like the others.
            waiting = way.is_some();
        }
        let mut spot = way.map(|w| w.spot);
        // Only an entry with people in the parks (on the squares) draws whether each is
        // one.
        if spot.is_none() && !crossing && spec.parks > 0.0 && rng.random::<f64>() < spec.parks {
            spot = (0..ATTEMPTS).find_map(|_| spots.park(rng, ROOM, 1));
        }
        if spot.is_none() && !crossing && spec.squares > 0.0 && rng.random::<f64>() < spec.squares {
            spot = (0..ATTEMPTS).find_map(|_| spots.square(rng, ROOM, 1));
        }
        if spot.is_none() && !crossing {
            let share = rng.random::<f64>();
            let from_curb = |strip: f64| CURB_ROOM + share * (far(strip) - CURB_ROOM);
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
        } else if crossing {
            spot.travel
        } else if walking {
            let back = rng.random::<bool>();
            spot.travel.map(|t| if back { -t } else { t })
        } else {
            let (c, s) = trig::cos_sin_deg(rng.random::<f64>() * 360.0);
            [c, s]
        };
        let figure = draw_figure(rng, walking, [low, high]);
        let (materials, attributes) = dress(rng, placing, &figure);
        let ground = if crossing { MARKING_Y } else { KERB_Y };
        let frame = Frame {
            origin: [spot.position[0], ground, spot.position[1]],
            forward,
        };
        let name = placing.name("person");
        let meshes = person_meshes(&frame, &figure, materials);
        let keypoints = figure.keypoints(&frame);
        let person = crate::model::ObjectKind::Person;
        placing.push_figure(
            person,
            name,
            &spec.label,
            meshes,
            attributes,
            Some(keypoints),
        );
        if let Some(way) = way {
            placing.set_traffic(walk(&spot, spot.travel, way.reach, Some(way.crossing)));
        } else if walking {
            // How far it walks is known once everything stands: [`walk_on`].
            placing.set_traffic(walk(&spot, forward, 0.0, None));
            spots.mark_walker();
        }
        misses = 0;
    }
}

/// The part in moving traffic of a person at `spot` walking along `travel`.
fn walk(spot: &Spot, travel: [f64; 2], reach: f64, crossing: Option<Crossing>) -> TrafficRole {
    TrafficRole::Pedestrian(Walk {
        travel,
        centre: spot.position,
        room: ROOM,
        road: spot.road,
        reach,
        crossing,
    })
}

/// Sets how far each person walking along a strip may walk (its [`Walk::reach`]), now
/// that everything standing on the ground is placed: up to the first thing in its way,
/// the strip's end, or 200 m (`MAX_WALK`).
pub fn walk_on(spots: &GroundSpots, placing: &mut Placing) {
    for info in &mut placing.out.info {
        if let Some(TrafficRole::Pedestrian(w)) = &mut info.traffic
            && w.crossing.is_none()
        {
            w.reach = spots.free_run(w.centre, w.travel, w.room, w.road);
        }
    }
}

/// A figure of height in `[low, high]`, walking or standing, in a pose drawn by weight.
fn draw_figure(rng: &mut Pcg64, walking: bool, [low, high]: [f64; 2]) -> Figure {
    let poses: &[(Pose, f64)] = if walking {
        &Pose::WALKING
    } else {
        &Pose::STANDING
    };
    Figure {
        height: low + rng.random::<f64>() * (high - low),
        build: 0.88 + 0.24 * rng.random::<f64>(),
        stride: if walking {
            10.0 + 8.0 * rng.random::<f64>()
        } else {
            3.0 * rng.random::<f64>()
        },
        sleeve: if rng.random::<bool>() { 0.35 } else { 0.9 },
        pose: Pose::pick(poses, rng.random::<f64>()),
        // One in eight holds it in the left hand.
        holding: if rng.random::<f64>() < 0.125 {
            -1.0
        } else {
            1.0
        },
    }
}

/// The materials of `figure`'s clothes, skin, hair and prop, drawn from the palettes, and
/// its attributes: `appearance` and `pose`.
fn dress(
    rng: &mut Pcg64,
    placing: &mut Placing,
    figure: &Figure,
) -> (Clothes, BTreeMap<String, String>) {
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
        prop: match figure.pose.prop() {
            Some(Prop::Bag) => Some(pick("person_bag", &BAGS).1),
            Some(Prop::Phone) => Some(placing.material("person_phone", || (PHONE, None))),
            None => None,
        },
    };
    let attributes = BTreeMap::from([
        (
            "appearance".to_owned(),
            appearance(figure, shirt.0, trousers.0),
        ),
        ("pose".to_owned(), figure.pose.name().to_owned()),
    ]);
    (materials, attributes)
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
    /// The held prop's, when the pose holds one.
    pub prop: Option<u32>,
}

/// The solids of `figure` standing at `frame`'s origin, facing its forward, built on its
/// [`Skeleton`]: one mesh per material used (trousers, shoes, shirt, skin, hair, then the
/// prop's).
pub fn person_meshes(frame: &Frame, figure: &Figure, m: Clothes) -> Vec<Mesh> {
    let h = figure.height;
    let s = figure.width();
    let bones = figure.skeleton();
    let k = &bones.keypoints;
    let (mut shirt, mut trousers, mut skin, mut hair, mut shoes) = (
        Solid::new(m.shirt),
        Solid::new(m.trousers),
        Solid::new(m.skin),
        Solid::new(m.hair),
        Solid::new(m.shoes),
    );
    // Legs: thigh and shin from just above the hip joint to the ankle, and a shoe from
    // the heel to the toe ahead of the ankle, 0.065 h high.
    let leg = [0.13 * s, 0.14 * s];
    for i in 0..2 {
        let (hip, knee, ankle) = (k[HIP + i], k[KNEE + i], k[ANKLE + i]);
        let top = [hip[0], hip[1] + 0.03 * h, hip[2]];
        limb(&mut trousers, frame, top, knee, leg);
        limb(&mut trousers, frame, knee, ankle, leg);
        shoes.cuboid(
            frame,
            [ankle[0] - 0.05 * s, ankle[0] + 0.12 * s],
            [0.0, 0.065 * h],
            [ankle[2] - 0.07 * s, ankle[2] + 0.07 * s],
        );
    }
    // Torso, hips to shoulders; the neck above it.
    shirt.cuboid(
        frame,
        [-0.11 * s, 0.11 * s],
        [0.48 * h, 0.82 * h],
        [-0.19 * s, 0.19 * s],
    );
    skin.cuboid(
        frame,
        [-0.045 * s, 0.045 * s],
        [0.81 * h, 0.88 * h],
        [-0.045 * s, 0.045 * s],
    );
    // Arms: from the top of the shoulder through elbow and wrist to the fingertips, in
    // sleeve for the `sleeve` share of the way to the wrist, bare below.
    for i in 0..2 {
        let shoulder = k[SHOULDER + i];
        let top = [shoulder[0], shoulder[1] + 0.02 * h, shoulder[2]];
        let chain = [top, k[ELBOW + i], k[WRIST + i], bones.hand_tips[i]];
        let arm = [0.085 * s, 0.085 * s];
        for (a, b, sleeved) in sleeve_split(&chain, figure.sleeve) {
            let solid = if sleeved { &mut shirt } else { &mut skin };
            limb(solid, frame, a, b, arm);
        }
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
    let mut solids = vec![trousers, shoes, shirt, skin, hair];
    if let (Some(material), Some(prop)) = (m.prop, figure.pose.prop()) {
        solids.push(held(frame, figure, &bones, prop, material));
    }
    finish_all(solids)
}

/// The `prop` `figure` holds (its `bones`), in `material`.
fn held(frame: &Frame, figure: &Figure, bones: &Skeleton, prop: Prop, material: u32) -> Solid {
    let mut held = Solid::new(material);
    let size = figure.height / 1.75;
    let side = usize::from(figure.holding > 0.0);
    let tip = bones.hand_tips[side];
    let d = bones.prop_direction;
    match prop {
        // A phone in the hand, from the wrist past the fingertips.
        Prop::Phone => {
            let wrist = bones.keypoints[WRIST + side];
            let end = along(wrist, d, 0.14 * size);
            limb(&mut held, frame, wrist, end, [0.075 * size, 0.012 * size]);
        }
        // A bag hanging from the fingers by its handles, its side to the leg.
        Prop::Bag => {
            let top = along(tip, d, -0.03 * size);
            let bottom = along(tip, d, 0.3 * size);
            limb(&mut held, frame, top, bottom, [0.1 * size, 0.32 * size]);
        }
    }
    held
}

/// The segments of an arm's `chain` (shoulder top, elbow, wrist, fingertips) with whether
/// each is in the sleeve: the first `share` of the way to the wrist is.
fn sleeve_split(chain: &[[f64; 3]; 4], share: f64) -> Vec<([f64; 3], [f64; 3], bool)> {
    let length = |a: [f64; 3], b: [f64; 3]| dot(sub(b, a), sub(b, a)).sqrt();
    let to_wrist = length(chain[0], chain[1]) + length(chain[1], chain[2]);
    let mut left = share * to_wrist;
    let mut parts = Vec::new();
    for w in chain.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = length(a, b);
        if left > 0.0 && left < len {
            let cut = along(a, normalize(sub(b, a)).unwrap_or([0.0; 3]), left);
            parts.push((a, cut, true));
            parts.push((cut, b, false));
        } else {
            parts.push((a, b, left >= len));
        }
        left -= len;
    }
    parts
}

/// A box from `a` to `b` (local `(u, y, v)` of `frame`), `size` across: the first
/// across the forward plane (`v`, for an upright limb), the second in it (`u`). Nothing
/// for a limb of no length.
fn limb(solid: &mut Solid, frame: &Frame, a: [f64; 3], b: [f64; 3], size: [f64; 2]) {
    let Some(dir) = normalize(sub(b, a)) else {
        return;
    };
    // Across: square to the limb and to forward (or up, for a limb along forward).
    let reference = if dir[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let Some(across) = normalize(cross(dir, reference)) else {
        return;
    };
    let depth = cross(across, dir);
    let corner = |p: [f64; 3], x: f64, y: f64| {
        let q = along(
            along(p, across, x * size[0] / 2.0),
            depth,
            y * size[1] / 2.0,
        );
        frame.at(q[0], q[1], q[2])
    };
    let world = |d: [f64; 3]| frame.dir(d[0], d[1], d[2]);
    let ring = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    for (end, sign) in [(a, -1.0), (b, 1.0)] {
        let cap: Vec<[f64; 3]> = ring.iter().map(|&(x, y)| corner(end, x, y)).collect();
        solid.polygon(&cap, world(dir.map(|c| c * sign)));
    }
    for k in 0..4 {
        let (p, q) = (ring[k], ring[(k + 1) % 4]);
        let mid = [(p.0 + q.0) / 2.0, (p.1 + q.1) / 2.0];
        let out = [
            across[0] * mid[0] + depth[0] * mid[1],
            across[1] * mid[0] + depth[1] * mid[1],
            across[2] * mid[0] + depth[2] * mid[1],
        ];
        let face = [
            corner(a, p.0, p.1),
            corner(a, q.0, q.1),
            corner(b, q.0, q.1),
            corner(b, p.0, p.1),
        ];
        solid.polygon(&face, world(out));
    }
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
pub(super) mod tests {
    use super::*;

    fn figure(height: f64, stride: f64) -> Figure {
        Figure {
            height,
            build: 1.12,
            stride,
            sleeve: 0.35,
            pose: Pose::Walking,
            holding: 1.0,
        }
    }

    const CLOTHES: Clothes = Clothes {
        shirt: 0,
        trousers: 1,
        skin: 2,
        hair: 3,
        shoes: 4,
        prop: Some(5),
    };

    const POSES: [Pose; 11] = [
        Pose::Walking,
        Pose::WalkingPhone,
        Pose::WalkingCall,
        Pose::WalkingBag,
        Pose::WalkingPockets,
        Pose::Standing,
        Pose::StandingPhone,
        Pose::StandingCall,
        Pose::StandingBag,
        Pose::ArmsCrossed,
        Pose::HandsInPockets,
    ];

    fn points(meshes: &[Mesh]) -> Vec<[f64; 3]> {
        meshes
            .iter()
            .flat_map(|m| &m.positions)
            .map(|p| p.map(f64::from))
            .collect()
    }

    #[test]
    fn a_figure_stands_on_the_ground_inside_its_room_and_is_as_tall_as_drawn() {
        let frame = Frame {
            origin: [10.0, 0.2, -4.0],
            forward: [0.6, 0.8],
        };
        let mut seen = BTreeMap::new();
        for pose in POSES {
            for (height, stride, sleeve) in [
                (0.8, 3.0, 0.9),
                (1.5, 0.0, 0.35),
                (1.95, 18.0, 0.9),
                (2.3, 18.0, 0.35),
            ] {
                let figure = Figure {
                    pose,
                    sleeve,
                    holding: if height < 1.6 { -1.0 } else { 1.0 },
                    ..figure(height, stride)
                };
                let meshes = person_meshes(&frame, &figure, CLOTHES);
                // One mesh per material, in a fixed order; the prop's last, if held.
                let materials: Vec<u32> = meshes.iter().map(|m| m.material).collect();
                let held = pose.prop().is_some();
                assert_eq!(materials[..5], [1, 4, 0, 2, 3]);
                assert_eq!(materials.len(), 5 + usize::from(held), "{pose:?}");
                let points = points(&meshes);
                let low = points.iter().map(|p| p[1]).fold(f64::MAX, f64::min);
                let top = points.iter().map(|p| p[1]).fold(f64::MIN, f64::max);
                assert!((low - 0.2).abs() < 1e-5, "{pose:?} {low}");
                // The hair cap rises a little over the head's 0.13 h; no hand or phone
                // reaches over it.
                assert!(
                    top > 0.2 + 0.99 * height && top < 0.2 + 1.01 * height,
                    "{pose:?} {top}"
                );
                for p in &points {
                    let (dx, dz) = (p[0] - 10.0, p[2] + 4.0);
                    assert!(
                        dx * dx + dz * dz < ROOM * ROOM,
                        "{pose:?} {p:?} at {height} m"
                    );
                }
                for m in &meshes {
                    assert_eq!(m.positions.len(), m.normals.len());
                    assert!(m.indices.len() % 3 == 0 && !m.indices.is_empty());
                }
                // Twelve boxes of 12 triangles (legs, shoes, torso, neck, eight arm
                // pieces), the head's octagon (28) and the hair cap (16); a prop is a box.
                let triangles: usize = meshes.iter().map(|m| m.indices.len() / 3).sum();
                assert_eq!(triangles, 236 + 12 * usize::from(held), "{pose:?}");
                seen.insert(pose.name(), triangles);
            }
        }
        assert_eq!(seen.len(), POSES.len());
    }

    #[test]
    fn the_keypoints_lie_on_the_figure_left_and_right_where_they_belong() {
        let frame = Frame {
            origin: [3.0, 0.2, 5.0],
            forward: [-0.8, 0.6],
        };
        for pose in POSES {
            for holding in [-1.0, 1.0] {
                let figure = Figure {
                    pose,
                    holding,
                    ..figure(
                        1.75,
                        if pose.name().starts_with("walking") {
                            15.0
                        } else {
                            2.0
                        },
                    )
                };
                let meshes = person_meshes(&frame, &figure, CLOTHES);
                let points = points(&meshes);
                let lo = [0, 1, 2].map(|a| points.iter().map(|p| p[a]).fold(f64::MAX, f64::min));
                let hi = [0, 1, 2].map(|a| points.iter().map(|p| p[a]).fold(f64::MIN, f64::max));
                let bones = figure.skeleton();
                let k = bones.keypoints;
                for (i, &p) in figure.keypoints(&frame).iter().enumerate() {
                    for a in 0..3 {
                        assert!(lo[a] - 1e-9 <= p[a] && p[a] <= hi[a] + 1e-9, "{pose:?} {i}");
                    }
                    // On a part's surface or inside it, less than half a limb deep.
                    let near = surface_distance(&meshes, p);
                    assert!(near < 0.05, "{pose:?} keypoint {i}: {near}");
                }
                // Left (−v) and right: eyes, ears, shoulders, elbows, hips, knees, ankles.
                for left in [1, 3, SHOULDER, ELBOW, HIP, KNEE, ANKLE] {
                    assert!(k[left][2] < 0.0 && k[left + 1][2] > 0.0, "{pose:?} {left}");
                }
                // Wrists too, but for crossed arms, each before the other side's chest.
                let crossed = pose == Pose::ArmsCrossed;
                assert_eq!(k[WRIST][2] > 0.0, crossed, "{pose:?}");
                assert_eq!(k[WRIST + 1][2] < 0.0, crossed, "{pose:?}");
                // The nose ahead of the ears, above the shoulders.
                assert!(k[0][0] > k[3][0] && k[0][1] > k[SHOULDER][1], "{pose:?}");
                let hand = usize::from(holding > 0.0);
                let tip = bones.hand_tips[hand];
                let apart = |a: [f64; 3], b: [f64; 3]| dot(sub(a, b), sub(a, b)).sqrt();
                match pose {
                    Pose::WalkingCall | Pose::StandingCall => {
                        assert!(apart(tip, k[3 + hand]) < 0.15, "{pose:?} {tip:?}");
                    }
                    Pose::WalkingPhone | Pose::StandingPhone => {
                        let wrist = k[WRIST + hand];
                        assert!(wrist[0] > 0.15 && wrist[1] > k[ELBOW + hand][1], "{pose:?}");
                    }
                    Pose::WalkingPockets | Pose::HandsInPockets => {
                        for i in 0..2 {
                            assert!(apart(bones.hand_tips[i], k[HIP + i]) < 0.2, "{pose:?}");
                        }
                    }
                    _ => {}
                }
            }
        }
    }

    /// The distance from `p` to the nearest triangle of `meshes`.
    pub(in crate::objects) fn surface_distance(meshes: &[Mesh], p: [f64; 3]) -> f64 {
        let mut best = f64::MAX;
        for m in meshes {
            for t in m.indices.chunks(3) {
                let [a, b, c] = [0, 1, 2].map(|i| m.positions[t[i] as usize].map(f64::from));
                let q = closest_on_triangle(p, a, b, c);
                best = best.min(dot(sub(q, p), sub(q, p)).sqrt());
            }
        }
        best
    }

    /// The point of triangle `abc` nearest `p` (Ericson, Real-Time Collision Detection 5.1.5).
    fn closest_on_triangle(p: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> [f64; 3] {
        let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
        let at = |u: f64, v: f64| along(along(a, ab, u), ac, v);
        let (d1, d2) = (dot(ab, ap), dot(ac, ap));
        if d1 <= 0.0 && d2 <= 0.0 {
            return a;
        }
        let bp = sub(p, b);
        let (d3, d4) = (dot(ab, bp), dot(ac, bp));
        if d3 >= 0.0 && d4 <= d3 {
            return b;
        }
        let vc = d1 * d4 - d3 * d2;
        if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
            return at(d1 / (d1 - d3), 0.0);
        }
        let cp = sub(p, c);
        let (d5, d6) = (dot(ab, cp), dot(ac, cp));
        if d6 >= 0.0 && d5 <= d6 {
            return c;
        }
        let vb = d5 * d2 - d1 * d6;
        if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
            return at(0.0, d2 / (d2 - d6));
        }
        let va = d3 * d6 - d5 * d4;
        if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
            let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
            return along(b, sub(c, b), w);
        }
        let denom = 1.0 / (va + vb + vc);
        at(vb * denom, vc * denom)
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
        let hands: Vec<_> = skin
            .positions
            .iter()
            .filter(|p| f64::from(p[1]) < 0.8)
            .collect();
        assert!(!hands.is_empty());
        for p in hands {
            if p[0] > 0.1 {
                assert!(p[2] > 0.0, "{p:?}");
            }
        }
    }
}
