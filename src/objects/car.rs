//! Car specs + road slots → `car_NNNN` objects: low-poly sedans, hatchbacks, estates,
//! coupes, SUVs, minivans, pickups, vans, buses and trucks with seeded paint, dark glass,
//! wheels, head and tail lights and a number plate at each end. A car in a driving lane
//! has its lights on: they glow at night (emissive, like the lamp heads) and the renderer
//! lights the road from them, and a lamp lights its rear plate. A parked car's lights are
//! off.
//!
//! A car is a side profile extruded across its width (the lower body), a narrower cabin on
//! it whose windscreen and rear window are glass, inset side windows, octagonal wheels and
//! four light quads; a truck adds a cargo box. About 150–190 triangles each.
//!
//! Plates ([`number_plate`]: EU, 520 × 110 mm, a seeded German registration, the same at
//! both ends) hang 2.5 cm in front of the body's front and rear faces, below the
//! headlights and between the tail lights. When some entry of the spec makes objects of
//! class [`PLATE_CLASS`] (`text`), each plate is a text object of that class of its own
//! (`text_style` `plate`, the registration its transcription, a word a group), pushed
//! after its car: its pixels are its own, not the car's. Otherwise it is a textured quad
//! of the car.
//!
//! Where: `parked` of them along the curbs (in the parking lane of the road's
//! [`StreetProfile`], or against the curb when there is none), the others standing in a
//! driving lane with the traffic. Cars are axis-aligned rectangles on the ground
//! ([`Footprint::Rect`]): they never overlap each other or anything else standing, keep
//! clear of crossings (parked ones 5 m, lane ones behind the zebra crossing's stop line,
//! [`STOP_LINE_END`]), and no lane car stands within [`CAMERA_CLEARANCE`] of the line a
//! roads camera drives by default ([`CAMERA_LANE`] right of the centre line), so a default
//! drive never passes through a car.

use rand::RngExt;
use rand_pcg::Pcg64;

use super::ground_spots::{RoadSlot, RoadSpots};
use super::number_plate::{self, registration};
use super::plate_light::PlateLight;
use super::text_plate::Background;
use super::vehicle_parts::{Frame, Solid, centroid, finish_all};
use super::wall_text::{self, Placed};
use super::{ATTEMPTS, GIVE_UP, Placing, trig};
use crate::model::geometry::{ROAD_Y, STOP_LINE_END, StreetProfile};
use crate::model::{LaneVehicle, Mesh, TrafficRole};
use crate::spec::{CarBody, ObjectSpec};

/// The roads camera's default `lane_offset`, metres right of the centre line.
pub const CAMERA_LANE: f64 = 4.0;
/// Room a lane car keeps from that line, metres.
pub const CAMERA_CLEARANCE: f64 = 1.0;
/// Draws of a vehicle (body, paint, parked or not) tried before one is left out.
pub const REDRAWS: u32 = 12;
/// Gap a parked car keeps from the curb, metres.
pub const CURB_GAP: f64 = 0.25;

/// The body mix when the spec lists none: mostly cars, a few vans, buses and trucks.
const DEFAULT_MIX: [CarBody; 18] = [
    CarBody::Sedan,
    CarBody::Sedan,
    CarBody::Sedan,
    CarBody::Sedan,
    CarBody::Hatchback,
    CarBody::Hatchback,
    CarBody::Hatchback,
    CarBody::Estate,
    CarBody::Estate,
    CarBody::Coupe,
    CarBody::Suv,
    CarBody::Suv,
    CarBody::Minivan,
    CarBody::Pickup,
    CarBody::Van,
    CarBody::Van,
    CarBody::Bus,
    CarBody::Truck,
];

/// The class a car's number plates take as text objects, when some entry of the spec
/// makes objects of it; else a plate is part of its car.
pub const PLATE_CLASS: &str = "text";
/// Height of the front and the rear plate's bottom edge above the body's underside,
/// metres: below the headlights, between the tail lights.
const PLATE_UP: [f64; 2] = [0.17, 0.2];

/// Paint colours (linear RGB), common ones listed more than once so they come up more.
const PAINTS: [[f32; 3]; 16] = [
    [0.78, 0.78, 0.76], // white
    [0.80, 0.80, 0.80],
    [0.42, 0.43, 0.45], // silver
    [0.40, 0.40, 0.40],
    [0.14, 0.14, 0.15],   // grey
    [0.035, 0.035, 0.04], // black
    [0.05, 0.05, 0.05],
    [0.02, 0.04, 0.13],  // dark blue
    [0.04, 0.13, 0.42],  // blue
    [0.45, 0.02, 0.02],  // red
    [0.18, 0.01, 0.015], // dark red
    [0.03, 0.10, 0.05],  // green
    [0.45, 0.38, 0.26],  // beige
    [0.70, 0.48, 0.04],  // yellow
    [0.25, 0.22, 0.20],  // brown grey
    [0.60, 0.22, 0.03],  // orange
];

const GLASS: [f32; 3] = [0.012, 0.016, 0.022];
const TYRE: [f32; 3] = [0.012, 0.012, 0.012];
const HEAD_COLOUR: [f32; 3] = [0.85, 0.85, 0.8];
const HEAD_GLOW: [f32; 3] = [1.0, 0.93, 0.78];
const TAIL_COLOUR: [f32; 3] = [0.35, 0.01, 0.01];
const TAIL_GLOW: [f32; 3] = [0.9, 0.04, 0.02];
/// A parked car's lights are off: its lenses are materials of their own
/// (`car_headlight_off`, `car_taillight_off`) that neither glow nor become point lights.
const HEAD_OFF_COLOUR: [f32; 3] = [0.6, 0.6, 0.58];
const TAIL_OFF_COLOUR: [f32; 3] = [0.25, 0.02, 0.02];

/// A body's dimensions, metres: `u` from the rear (0) to the front (`length`), `y` up from
/// the ground.
#[derive(Clone, Copy, Debug)]
pub struct Shape {
    pub length: f64,
    pub width: f64,
    /// Underside of the body.
    pub sill: f64,
    /// Top of the body at the rear and under the side windows.
    pub belt: f64,
    /// Top of the body at the front (the bonnet).
    pub hood: f64,
    pub roof: f64,
    /// Cabin `u`: rear at the belt, rear at the roof, front at the roof, front at the belt.
    pub cabin: [f64; 4],
    /// How much narrower than the body the cabin is on each side.
    pub inset: f64,
    pub wheel: f64,
    pub axles: [f64; 2],
    /// Side windows per side.
    pub panes: u32,
    /// Trucks: the cargo box's `u` range and top.
    pub cargo: Option<([f64; 2], f64)>,
}

impl Shape {
    pub fn of(body: CarBody) -> Shape {
        let car = |length, width, sill, belt, hood, roof, cabin, wheel, axles, panes| Shape {
            length,
            width,
            sill,
            belt,
            hood,
            roof,
            cabin,
            inset: 0.09,
            wheel,
            axles,
            panes,
            cargo: None,
        };
        // One body a row: length, width, sill, belt, hood, roof, cabin, wheel, axles, panes.
        #[rustfmt::skip]
        let shape = match body {
            CarBody::Sedan => car(4.6, 1.8, 0.3, 0.95, 0.85, 1.45, [1.0, 1.5, 2.95, 3.55], 0.32, [0.95, 3.65], 2),
            CarBody::Hatchback => car(4.0, 1.75, 0.3, 0.95, 0.85, 1.5, [0.12, 0.4, 2.35, 3.0], 0.31, [0.75, 3.25], 2),
            // The roof runs to a near-upright tailgate over a long load floor.
            CarBody::Estate => car(4.8, 1.82, 0.3, 0.95, 0.85, 1.48, [0.1, 0.3, 3.0, 3.65], 0.32, [0.95, 3.8], 3),
            // Low, a short cabin far back, one long door window a side.
            CarBody::Coupe => car(4.5, 1.85, 0.28, 0.9, 0.78, 1.32, [0.9, 1.75, 2.85, 3.5], 0.33, [0.95, 3.6], 1),
            CarBody::Suv => car(4.7, 1.9, 0.4, 1.1, 1.0, 1.78, [0.1, 0.28, 3.05, 3.65], 0.38, [0.95, 3.75], 3),
            // Tall, a long sloping windscreen reaching far forward, a short bonnet.
            CarBody::Minivan => car(4.9, 1.9, 0.32, 1.0, 0.92, 1.75, [0.1, 0.2, 3.2, 4.1], 0.33, [0.9, 3.95], 3),
            // A cab up front, the covered load bed behind it at rail height.
            CarBody::Pickup => car(5.3, 1.9, 0.45, 1.15, 1.1, 1.85, [2.2, 2.35, 3.85, 4.35], 0.4, [1.0, 4.2], 2),
            CarBody::Van => car(5.0, 1.95, 0.35, 1.05, 0.95, 2.1, [0.05, 0.1, 3.85, 4.5], 0.34, [0.9, 4.1], 3),
            CarBody::Bus => Shape {
                inset: 0.03,
                ..car(11.0, 2.5, 0.35, 1.2, 1.2, 3.0, [0.05, 0.08, 10.85, 10.96], 0.5, [2.6, 8.9], 7)
            },
            CarBody::Truck => Shape {
                inset: 0.05,
                cargo: Some(([0.1, 5.3], 3.4)),
                ..car(7.5, 2.35, 0.45, 1.25, 1.15, 2.85, [5.45, 5.5, 7.15, 7.45], 0.48, [1.6, 6.1], 1)
            },
        };
        shape
    }

    /// The lower body's side profile, convex, counter-clockwise.
    pub fn body_profile(&self) -> Vec<[f64; 2]> {
        let (l, s) = (self.length, self.sill);
        vec![
            [0.08, s],
            [l - 0.15, s],
            [l, s + 0.15],
            [l, self.hood - 0.08],
            [l - 0.35, self.hood],
            [0.08, self.belt],
            [0.0, self.belt - 0.08],
            [0.0, s + 0.08],
        ]
    }

    /// The cabin's side profile (bottom, front slope, roof, rear slope), its bottom sunk
    /// 10 cm into the body along the slopes so no gap shows under the windscreen.
    pub fn cabin_profile(&self) -> [[f64; 2]; 4] {
        let [r0, r1, f1, f0] = self.cabin;
        let rise = self.roof - self.belt;
        let sink = 0.1;
        [
            [r0 - (r1 - r0) * sink / rise, self.belt - sink],
            [f0 + (f0 - f1) * sink / rise, self.belt - sink],
            [f1, self.roof],
            [r1, self.roof],
        ]
    }
}

/// The materials a car is made of.
struct Paints {
    paint: u32,
    cargo: u32,
    glass: u32,
    tyre: u32,
    head: u32,
    tail: u32,
}

// Long on purpose: one placement loop, whose random draws must stay in this order (each
// changes every later object's); split, the order would be spread over functions.
pub fn place(
    spec: &ObjectSpec,
    rng: &mut Pcg64,
    spots: &mut impl RoadSpots,
    placing: &mut Placing,
) -> u32 {
    // Plates are text objects when the spec makes objects of their class.
    let texts = placing.input.specs.iter().any(|s| s.label == PLATE_CLASS);
    let mut faces = Vec::new();
    let mut plates = Vec::new();
    let mut cars = Vec::new();
    let bodies: &[CarBody] = if spec.bodies.is_empty() {
        &DEFAULT_MIX
    } else {
        &spec.bodies
    };
    let mut misses = 0;
    for _ in 0..spec.count {
        if misses >= GIVE_UP {
            break;
        }
        // A vehicle that finds no room (a bus needs a 12 m gap at the curb) is drawn again,
        // body, paint and lane, up to REDRAWS times: the streets' room bounds `count`, not
        // the first draw's luck (so buses and trucks thin out a little on full streets).
        let mut fitted = None;
        for _ in 0..REDRAWS {
            let body = bodies[rng.random_range(0..bodies.len())];
            let paint = rng.random_range(0..PAINTS.len());
            let cargo = if rng.random::<f64>() < 0.6 {
                0
            } else {
                rng.random_range(0..PAINTS.len())
            };
            let parked = rng.random::<f64>() < spec.parked;
            let lane_pick: f64 = rng.random();
            let shape = Shape::of(body);
            let half = [shape.length / 2.0, shape.width / 2.0];
            let slot = |width: f64| {
                let profile = StreetProfile::of(width);
                if parked {
                    let offset = profile.half - CURB_GAP - half[1];
                    (offset > half[1]).then_some(RoadSlot {
                        half,
                        offset,
                        crossing_clearance: 5.0,
                        gap: 0.4,
                        parked: true,
                    })
                } else {
                    let free: Vec<f64> = (0..profile.lanes)
                        .map(|k| profile.lane_centre(k))
                        .filter(|c| (c - CAMERA_LANE).abs() >= half[1] + CAMERA_CLEARANCE)
                        .filter(|c| c + half[1] <= profile.half - profile.parking)
                        .collect();
                    // `lane_pick` < 1, so the index is in range.
                    let offset = *free.get((lane_pick * free.len() as f64) as usize)?;
                    Some(RoadSlot {
                        half,
                        offset,
                        // Behind the stop line, as a car waits at a crossing.
                        crossing_clearance: STOP_LINE_END,
                        gap: 2.5,
                        parked: false,
                    })
                }
            };
            if let Some(spot) = spots.road(rng, ATTEMPTS, slot) {
                fitted = Some((spot, shape, half, paint, cargo, parked, body));
                break;
            }
        }
        let Some((spot, shape, half, paint, cargo, parked, body)) = fitted else {
            misses += 1;
            continue;
        };
        misses = 0;
        let paints = Paints {
            paint: paint_material(placing, paint),
            cargo: paint_material(placing, cargo),
            glass: placing.material("car_glass", || (GLASS, None)),
            tyre: placing.material("car_tyre", || (TYRE, None)),
            head: if parked {
                placing.material("car_headlight_off", || (HEAD_OFF_COLOUR, None))
            } else {
                placing.glowing("car_headlight", HEAD_COLOUR, HEAD_GLOW)
            },
            tail: if parked {
                placing.material("car_taillight_off", || (TAIL_OFF_COLOUR, None))
            } else {
                placing.glowing("car_taillight", TAIL_COLOUR, TAIL_GLOW)
            },
        };
        let frame = Frame {
            origin: [
                spot.position[0] - spot.travel[0] * half[0],
                ROAD_Y,
                spot.position[1] - spot.travel[1] * half[0],
            ],
            forward: spot.travel,
        };
        let meshes = car_meshes(&shape, &frame, &paints);
        let name = placing.name("car");
        let text = registration(placing.input.seed, spot.position);
        let plate = number_plate::measure(&text);
        let metres_per_px = number_plate::SIZE[0] / f64::from(number_plate::PIXELS[0]);
        // Front, then rear; a car in a lane has its rear plate lamp on.
        let ends = [(shape.length, 1.0, PLATE_UP[0]), (0.0, -1.0, PLATE_UP[1])];
        for (k, (u, facing, up)) in ends.into_iter().enumerate() {
            let (face, rect) = number_plate::face(&frame, u, facing, shape.sill + up);
            let corners = wall_text::word_corners(&face, rect, &plate, metres_per_px);
            let lit = k == 1 && !parked;
            faces.push(face);
            plates.push(Placed {
                name: if texts {
                    placing.name("text")
                } else {
                    String::new()
                },
                wall: faces.len() - 1,
                rect,
                plate: plate.clone(),
                background: Background::Paper(number_plate::PAPER),
                ink: number_plate::INK,
                text: text.clone(),
                corners,
                light: Some(if lit {
                    PlateLight::LampLit
                } else {
                    PlateLight::Unlit
                }),
            });
        }
        let lane = (!parked).then_some(LaneVehicle {
            road: spot.road,
            travel: spot.travel,
            centre: spot.position,
            half,
            bicycle: false,
        });
        cars.push((name, meshes, body, lane));
    }
    let page_name = format!("{}_plate_atlas", spec.label);
    let mut plates =
        wall_text::plate_objects(PLATE_CLASS, &faces, plates, &page_name, placing).into_iter();
    let placed = cars.len() as u32;
    for (name, mut meshes, body, lane) in cars {
        let two: Vec<_> = plates.by_ref().take(2).collect();
        if !texts {
            meshes.extend(two.iter().flat_map(|(object, _)| object.meshes.clone()));
        }
        let variant = Some(("body", body.name().to_owned()));
        placing.push_variant(
            crate::model::ObjectKind::Car,
            name,
            &spec.label,
            meshes,
            variant,
        );
        if let Some(lane) = lane {
            placing.set_traffic(TrafficRole::Vehicle(lane));
        }
        if texts {
            for (back, (object, info)) in (1..).zip(two) {
                placing.push(object, info);
                if lane.is_some() {
                    placing.set_traffic(TrafficRole::Carried { back });
                }
            }
        }
    }
    placed
}

fn paint_material(placing: &mut Placing, k: usize) -> u32 {
    placing.material(&format!("car_paint_{k:02}"), || (PAINTS[k], None))
}

/// The meshes of a car of `shape` standing in `frame` (origin: the middle of its rear on
/// the ground; `u` forward).
fn car_meshes(shape: &Shape, frame: &Frame, m: &Paints) -> Vec<Mesh> {
    let hw = shape.width / 2.0;
    let mut paint = Solid::new(m.paint);
    let mut glass = Solid::new(m.glass);
    let mut tyre = Solid::new(m.tyre);
    let mut cargo = Solid::new(m.cargo);
    let mut head = Solid::new(m.head);
    let mut tail = Solid::new(m.tail);

    paint.prism(frame, &shape.body_profile(), [-hw, hw], &[]);
    // Cabin: sides and roof painted, windscreen (edge 1) and rear window (edge 3) glass, no
    // bottom (edge 0, inside the body).
    let cabin = shape.cabin_profile();
    let cw = hw - shape.inset;
    paint.prism(frame, &cabin, [-cw, cw], &[0, 1, 3]);
    let c = centroid(&cabin);
    glass.profile_face(frame, &cabin, c, 1, [-cw, cw]);
    glass.profile_face(frame, &cabin, c, 3, [-cw, cw]);
    side_windows(&mut glass, frame, shape, cw + 0.01);
    if let Some((u, top)) = shape.cargo {
        cargo.cuboid(frame, u, [shape.sill + 0.5, top], [-hw - 0.02, hw + 0.02]);
    }
    for &axle in &shape.axles {
        for v in [[hw - 0.24, hw + 0.01], [-hw - 0.01, -hw + 0.24]] {
            tyre.prism(frame, &wheel_profile(axle, shape.wheel), v, &[]);
        }
    }
    // Lights: quads 1 cm in front of the body's vertical front and rear faces.
    let forward = frame.dir(1.0, 0.0, 0.0);
    let back = forward.map(|x| -x);
    for side in [-1.0, 1.0] {
        let v = [side * (hw - 0.42), side * (hw - 0.1)];
        let lamp = |u: f64, y: [f64; 2]| {
            [
                frame.at(u, y[0], v[0]),
                frame.at(u, y[0], v[1]),
                frame.at(u, y[1], v[1]),
                frame.at(u, y[1], v[0]),
            ]
        };
        head.polygon(
            &lamp(shape.length + 0.01, [shape.hood - 0.3, shape.hood - 0.15]),
            forward,
        );
        tail.polygon(&lamp(-0.01, [shape.belt - 0.32, shape.belt - 0.17]), back);
    }
    finish_all(vec![paint, glass, tyre, cargo, head, tail])
}

/// `shape.panes` glass quads on each cabin side, at `|v| = v`, framed by 8 cm pillars.
fn side_windows(glass: &mut Solid, frame: &Frame, shape: &Shape, v: f64) {
    let [r0, r1, f1, f0] = shape.cabin;
    let (y0, y1) = (shape.belt + 0.07, shape.roof - 0.08);
    let t = |y: f64| (y - shape.belt) / (shape.roof - shape.belt);
    let edge = |y: f64| {
        let k = t(y);
        [r0 + (r1 - r0) * k + 0.08, f0 + (f1 - f0) * k - 0.08]
    };
    let (bottom, top) = (edge(y0), edge(y1));
    let n = f64::from(shape.panes.max(1));
    let pillar = 0.05;
    for side in [-1.0, 1.0] {
        let normal = frame.dir(0.0, 0.0, side);
        for k in 0..shape.panes.max(1) {
            let at = |span: [f64; 2], j: f64| span[0] + (span[1] - span[0]) * j / n;
            let (j0, j1) = (f64::from(k), f64::from(k + 1));
            let inner = |j: f64, s: f64| if j > 0.0 && j < n { s * pillar } else { 0.0 };
            let corners = [
                frame.at(at(bottom, j0) + inner(j0, 1.0), y0, side * v),
                frame.at(at(bottom, j1) + inner(j1, -1.0), y0, side * v),
                frame.at(at(top, j1) + inner(j1, -1.0), y1, side * v),
                frame.at(at(top, j0) + inner(j0, 1.0), y1, side * v),
            ];
            glass.polygon(&corners, normal);
        }
    }
}

/// An octagon of radius `r` standing on the ground at `axle`, in (u, y).
fn wheel_profile(axle: f64, r: f64) -> Vec<[f64; 2]> {
    (0..8)
        .map(|k| {
            let (c, s) = trig::cos_sin_deg(22.5 + 45.0 * f64::from(k));
            [axle + r * c, r + r * s]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn convex(profile: &[[f64; 2]]) -> bool {
        let n = profile.len();
        (0..n).all(|k| {
            let (a, b, c) = (profile[k], profile[(k + 1) % n], profile[(k + 2) % n]);
            (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]) > 0.0
        })
    }

    #[test]
    fn every_body_is_convex_and_low_poly() {
        let frame = Frame {
            origin: [0.0; 3],
            forward: [0.0, 1.0],
        };
        for body in CarBody::ALL {
            let shape = Shape::of(body);
            assert!(convex(&shape.body_profile()), "{body:?}");
            assert!(convex(&shape.cabin_profile()), "{body:?}");
            assert!(shape.cabin[0] < shape.cabin[1] && shape.cabin[2] < shape.cabin[3]);
            let m = Paints {
                paint: 0,
                cargo: 1,
                glass: 2,
                tyre: 3,
                head: 4,
                tail: 5,
            };
            let meshes = car_meshes(&shape, &frame, &m);
            let triangles: usize = meshes.iter().map(|m| m.indices.len() / 3).sum();
            assert!((100..=300).contains(&triangles), "{body:?}: {triangles}");
            // Every part stays within the body's length and width (wheels and lights
            // stand out by a few centimetres) and on the ground.
            for mesh in &meshes {
                for p in &mesh.positions {
                    let p = p.map(f64::from);
                    assert!(p[1] >= 0.0 && p[1] <= 3.5, "{body:?} {p:?}");
                    assert!(p[0].abs() <= shape.width / 2.0 + 0.03, "{body:?} {p:?}");
                    assert!(
                        p[2] >= -0.02 && p[2] <= shape.length + 0.02,
                        "{body:?} {p:?}"
                    );
                }
            }
        }
    }
}
