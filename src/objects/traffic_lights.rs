//! Traffic-light specs + street corners → `signal_pole_NNNN` poles (class `pole`), each
//! carrying two `traffic_light_NNNN` signal heads (class: the entry's label).
//!
//! A pole stands at a street corner, half a strip from both curbs
//! ([`GroundSpots::corners`]), in a random order of the corners; a corner whose circle is
//! taken (a lamp, a street-name pole of an earlier entry) is skipped. Of its two heads,
//! one looks out along the horizontal road and one along the vertical road, each away from
//! the crossing: at the traffic coming towards the crossing on that side. A head is a
//! box of the body's colour (black or traffic yellow, drawn per pole) with three lamps
//! on its front, red over amber over green, and a short arm to the pole.
//!
//! Each pole draws one phase, and its two heads show it as a crossing does: the road whose
//! traffic goes shows green or amber, the other red. The lit lamp is bright by day and
//! glows at night (an emissive material, like car lights); the others are dark glass. The
//! head's COCO attribute `state` is its lit colour (`red`, `amber` or `green`).

use std::collections::BTreeMap;

use rand::RngExt;
use rand_pcg::Pcg64;

use super::ground_spots::{Footprint, GroundSpots};
use super::street_names::POLE_GREY;
use super::{ObjectInfo, Placing};
use crate::model::geometry::{KERB_Y, MeshBuilder};
use crate::model::{Axis, Mesh, SceneObject, TrafficRole};
use crate::spec::ObjectSpec;

/// Height of the pole above the sidewalk, metres.
pub const POLE_HEIGHT: f64 = 3.4;
/// Half the pole's thickness, metres.
pub const POLE_HALF: f64 = 0.06;
/// Height of a head's bottom above the sidewalk, metres.
pub const HEAD_BOTTOM: f64 = 2.4;
/// A head's height, width and depth, metres.
pub const HEAD_SIZE: [f64; 3] = [0.95, 0.34, 0.24];
/// Distance from the pole's axis to a head's centre, along the way the head looks:
/// enough for the two heads of a pole, looking along different roads, not to touch.
pub const HEAD_OFFSET: f64 = 0.36;
/// A lamp's side (square lenses) and how far it stands out of the head's front, metres.
pub const LAMP: f64 = 0.22;
pub const LAMP_DEPTH: f64 = 0.03;
/// Ground a pole keeps free around itself, metres.
pub const RADIUS: f64 = 0.6;

/// What a head shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Signal {
    Red,
    Amber,
    Green,
}

impl Signal {
    /// Top to bottom on the head.
    pub const ALL: [Signal; 3] = [Signal::Red, Signal::Amber, Signal::Green];

    /// The COCO attribute value.
    pub fn name(self) -> &'static str {
        match self {
            Signal::Red => "red",
            Signal::Amber => "amber",
            Signal::Green => "green",
        }
    }

    /// Linear albedo of the lens lit (bright by day) and dark, and its glow at night.
    fn colours(self) -> ([f32; 3], [f32; 3], [f32; 3]) {
        match self {
            Signal::Red => ([1.0, 0.06, 0.03], [0.06, 0.01, 0.01], [1.0, 0.05, 0.02]),
            Signal::Amber => ([1.0, 0.45, 0.02], [0.06, 0.03, 0.005], [1.0, 0.45, 0.02]),
            Signal::Green => ([0.05, 0.9, 0.45], [0.005, 0.05, 0.03], [0.05, 1.0, 0.5]),
        }
    }
}

/// Body colours of the heads: black, traffic yellow (linear albedo).
const BODIES: [[f32; 3]; 2] = [[0.025, 0.025, 0.027], [0.62, 0.42, 0.02]];

/// Places up to `spec.count` signal poles; returns how many stand.
pub fn place(
    spec: &ObjectSpec,
    rng: &mut Pcg64,
    spots: &mut GroundSpots,
    placing: &mut Placing,
) -> u32 {
    let corners = spots.shuffled_corners(rng);
    let pole_material = placing.material("signal_pole", || (POLE_GREY, None));
    let mut poles = 0u32;
    for corner in corners {
        if poles >= spec.count {
            break;
        }
        let body = rng.random_range(0..BODIES.len());
        // Which road goes (0: the horizontal one), and whether it is already amber.
        let goes = rng.random_range(0..2usize);
        let amber = rng.random::<f64>() < 0.2;
        if !spots.claim(Footprint::Circle(corner.position, RADIUS)) {
            continue;
        }
        poles += 1;
        push_pole(placing, corner.position, pole_material);
        // Along the horizontal road (x), then the vertical one (z), away from the crossing.
        let looks = [[corner.sides[0], 0.0], [0.0, corner.sides[1]]];
        for (road, facing) in looks.into_iter().enumerate() {
            let signal = match (road == goes, amber) {
                (false, _) => Signal::Red,
                (true, false) => Signal::Green,
                (true, true) => Signal::Amber,
            };
            push_head(placing, spec, corner.position, facing, signal, body);
            let axis = [Axis::Horizontal, Axis::Vertical][road];
            placing.set_traffic(TrafficRole::Signal {
                corner: corner.position,
                axis,
            });
        }
    }
    if poles > 0 {
        register_lamps(placing);
    }
    poles
}

/// Signal poles where a map has its signals: `signals` holds, per mapped signal in node
/// order, its poles (foot, and the way its head looks: at the traffic it stops), up to
/// `spec.count` poles in all. A pole whose ground `claim` refuses (a lamp, a tree, a car
/// of an earlier entry) is left out. Each signal draws what it shows (red half the time,
/// amber a tenth, else green: all its heads alike, as they stop one road both ways), each
/// pole its body colour. Returns how many poles stand.
pub fn place_mapped(
    spec: &ObjectSpec,
    rng: &mut Pcg64,
    signals: &[Vec<([f64; 2], [f64; 2])>],
    claim: &mut dyn FnMut(Footprint) -> bool,
    placing: &mut Placing,
) -> u32 {
    let pole_material = placing.material("signal_pole", || (POLE_GREY, None));
    let mut poles = 0u32;
    'signals: for signal_poles in signals {
        let signal = match rng.random_range(0..10u32) {
            0..=4 => Signal::Red,
            5 => Signal::Amber,
            _ => Signal::Green,
        };
        for &(foot, facing) in signal_poles {
            if poles >= spec.count {
                break 'signals;
            }
            let body = rng.random_range(0..BODIES.len());
            if !claim(Footprint::Circle(foot, RADIUS)) {
                continue;
            }
            poles += 1;
            push_pole(placing, foot, pole_material);
            push_head(placing, spec, foot, facing, signal, body);
        }
    }
    if poles > 0 {
        register_lamps(placing);
    }
    poles
}

/// A grey pole standing at `foot` on the sidewalk.
fn push_pole(placing: &mut Placing, foot: [f64; 2], material: u32) {
    let mut pole = MeshBuilder::new(material);
    pole.oriented_box(
        [foot[0], KERB_Y, foot[1]],
        [1.0, 0.0],
        [POLE_HALF, POLE_HALF],
        POLE_HEIGHT,
    );
    let name = placing.name("signal_pole");
    placing.push_plain(
        crate::model::ObjectKind::SignalPole,
        name,
        "pole",
        vec![pole.finish()],
    );
}

/// A labelled head on the pole at `foot`, looking along `facing` and showing `signal`
/// (its COCO attribute `state`).
fn push_head(
    placing: &mut Placing,
    spec: &ObjectSpec,
    foot: [f64; 2],
    facing: [f64; 2],
    signal: Signal,
    body: usize,
) {
    let meshes = head_meshes(foot, facing, signal, body, placing);
    let name = placing.name("traffic_light");
    let object = SceneObject {
        name,
        kind: crate::model::ObjectKind::TrafficLight,
        class: spec.label.clone(),
        meshes,
    };
    let info = ObjectInfo {
        traffic: None,
        label: spec.label.clone(),
        text: None,
        corners: Vec::new(),
        attributes: BTreeMap::from([("state".to_owned(), signal.name().to_owned())]),
        keypoints: None,
    };
    placing.push(object, info);
}

/// Every lamp's lit and dark material, so that moving traffic can switch any lamp of any
/// head (`[traffic]`): those no head shows now are added unused.
fn register_lamps(placing: &mut Placing) {
    for lamp in Signal::ALL {
        let (lit, dark, glow) = lamp.colours();
        placing.glowing(&lamp_material(lamp, true), lit, glow);
        placing.material(&lamp_material(lamp, false), || (dark, None));
    }
}

/// The name of the material of `lamp`'s lens, lit or dark.
pub fn lamp_material(lamp: Signal, lit: bool) -> String {
    let state = if lit { "lit" } else { "dark" };
    format!("signal_{}_{state}", lamp.name())
}

/// A head on the pole at `foot` looking along `facing` (unit, horizontal) and showing
/// `signal`: its body, its arm, and its three lamps (red, amber, green), in that order.
fn head_meshes(
    foot: [f64; 2],
    facing: [f64; 2],
    signal: Signal,
    body: usize,
    placing: &mut Placing,
) -> Vec<Mesh> {
    let [height, width, depth] = HEAD_SIZE;
    let body_material = placing.material(&format!("signal_body_{body}"), || (BODIES[body], None));
    let centre = [
        foot[0] + facing[0] * HEAD_OFFSET,
        foot[1] + facing[1] * HEAD_OFFSET,
    ];
    let mut shell = MeshBuilder::new(body_material);
    shell.oriented_box(
        [centre[0], KERB_Y + HEAD_BOTTOM, centre[1]],
        facing,
        [depth / 2.0, width / 2.0],
        height,
    );
    // The arm from the pole to the head's back, at mid height.
    let arm = HEAD_OFFSET - depth / 2.0;
    let mut bracket = MeshBuilder::new(body_material);
    bracket.oriented_box(
        [
            foot[0] + facing[0] * arm / 2.0,
            KERB_Y + HEAD_BOTTOM + height / 2.0 - 0.04,
            foot[1] + facing[1] * arm / 2.0,
        ],
        facing,
        [arm / 2.0, 0.04],
        0.08,
    );
    let mut meshes = vec![shell.finish(), bracket.finish()];
    // Lenses stand out of the front face, centred across it, evenly down it.
    let front = HEAD_OFFSET + depth / 2.0 + LAMP_DEPTH / 2.0;
    let step = height / 3.0;
    for (k, lamp) in Signal::ALL.into_iter().enumerate() {
        let (lit, dark, glow) = lamp.colours();
        let material = if lamp == signal {
            placing.glowing(&lamp_material(lamp, true), lit, glow)
        } else {
            placing.material(&lamp_material(lamp, false), || (dark, None))
        };
        let mut lens = MeshBuilder::new(material);
        let bottom = KERB_Y + HEAD_BOTTOM + height - step * (k as f64 + 0.5) - LAMP / 2.0;
        lens.oriented_box(
            [
                foot[0] + facing[0] * front,
                bottom,
                foot[1] + facing[1] * front,
            ],
            facing,
            [LAMP_DEPTH / 2.0, LAMP / 2.0],
            LAMP,
        );
        meshes.push(lens.finish());
    }
    meshes
}
