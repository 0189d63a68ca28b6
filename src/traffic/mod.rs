//! Traffic stage: the lane vehicles, signal heads and walking people the objects stage
//! placed (their [`TrafficRole`]s), the roads, `[traffic]`, the seed and a timed drive's
//! poses → [`Traffic`]; [`Traffic::at`] gives the [`Movement`] at any time.
//!
//! # The model
//!
//! - **Lanes.** A vehicle (a car standing in a lane, a ridden bicycle) keeps its lane and
//!   goes straight on along its road. Vehicles on the same road, driving the same way,
//!   whose strips of road overlap share a lane.
//! - **Junctions** are where a horizontal and a vertical road share area. Each runs one
//!   signal cycle (`[traffic] cycle`): the horizontal road green, amber ([`AMBER`]), red
//!   for all ([`ALL_RED`]), then the same for the vertical road; its phase is seeded per
//!   junction. Signal heads show their junction's cycle for the road they look along.
//!   Junctions without heads keep the same cycle (as if controlled).
//! - **A vehicle** drives at its cruising speed (drawn per vehicle from `car_kmh` or
//!   `bicycle_kmh`) to the next stop line (its front [`STOP_LINE_END`] before the
//!   junction), and crosses only while its road is green, early enough that it clears the
//!   junction before the other road's green (at its own speed, and behind the vehicle
//!   ahead); otherwise it waits at the line. At the end of its road (the map's edge or a
//!   dead end) it stops ([`END_GAP`] short of it). Speed changes are instant (a kinematic
//!   model).
//! - **Following** is Newell's simplified car-following model: a vehicle is never further
//!   along than the vehicle ahead was [`FOLLOW_DELAY`] seconds earlier, less a spacing (the
//!   two half-lengths and [`JAM_GAP`], or the gap they stood at, if smaller).
//! - **Closed form.** Each vehicle's way is a piecewise-linear function of time, worked
//!   out once from the front of its lane backwards (each from the one ahead's), not
//!   stepped frame by frame: every position is a function of the seed and the time alone,
//!   and any frame renders on its own.
//! - **People** walk along the sidewalks and across the zebra crossings (the
//!   `pedestrians` module): straight on, kept apart from each other and, by the signals
//!   and the stop lines, from the vehicles.
//! - **Time 0** is where the scene has every vehicle: before it, all stand still.
//! - **A timed drive** crosses junctions with the traffic: a junction the drive's camera
//!   passes through is phased so that its road's green is centred on the moment the
//!   camera is in it (the camera's car does not stop; cross traffic waits for it).
//!
//! Pure: positions, cycles and speeds are worked out with + − × ÷ and floor only.

/// Bump when the traffic's positions or signal states change for the same inputs.
pub const VERSION: u32 = 2;

mod junctions;
mod path;
mod pedestrians;
mod signal;
#[cfg(test)]
mod tests;

pub use signal::{ALL_RED, AMBER};

use rand::RngExt;

use crate::model::geometry::STOP_LINE_END;
use crate::model::{Axis, LaneVehicle, Movement, ParsedLayout, Recolour, TrafficRole, Walk};
use crate::objects::Signal;
use crate::spec::TrafficSpec;
use junctions::Junction;
use path::{Path, Stop};
use signal::Schedule;

/// Newell's delay: how long after the vehicle ahead a follower repeats its moves, seconds.
pub const FOLLOW_DELAY: f64 = 1.2;
/// The gap between two vehicles standing in a queue, metres.
pub const JAM_GAP: f64 = 2.0;
/// How far short of its road's end a vehicle stops, metres.
pub const END_GAP: f64 = 1.0;

/// What the traffic is made from.
pub struct TrafficInput<'a> {
    pub spec: &'a TrafficSpec,
    pub layout: &'a ParsedLayout,
    pub metres_per_pixel: f64,
    /// Per scene object, in order, what it is to the traffic.
    pub roles: &'a [Option<TrafficRole>],
    /// The signal lamps' materials, red, amber and green, each `[lit, dark]`; `None` when
    /// the scene has no signal head.
    pub lamps: Option<[[u32; 2]; 3]>,
    pub seed: u64,
    /// A timed drive's camera: `(time, eye (x, z))` per frame; empty for other paths.
    pub ego: &'a [(f64, [f64; 2])],
}

/// The traffic of a scene, ready to be placed at any time.
#[derive(Clone, Debug)]
pub struct Traffic {
    lanes: Vec<Lane>,
    /// `(instance, carrier's instance)`: a plate or rider and its vehicle.
    carried: Vec<(u32, u32)>,
    heads: Vec<Head>,
    schedules: Vec<Schedule>,
    lamps: Option<[[u32; 2]; 3]>,
}

/// Vehicles sharing a lane, the front one first.
#[derive(Clone, Debug)]
struct Lane {
    /// Unit direction of travel (x, z).
    travel: [f64; 2],
    drivers: Vec<Driver>,
}

#[derive(Clone, Debug)]
struct Driver {
    instance: u32,
    /// Where the scene has it along the lane.
    s0: f64,
    /// Its way, behind the vehicles ahead.
    path: Path,
}

#[derive(Clone, Copy, Debug)]
struct Head {
    instance: u32,
    junction: usize,
    axis: Axis,
}

/// A vehicle before it is put in its lane.
struct Placed {
    instance: u32,
    road: u32,
    sign: i8,
    band: [f64; 2],
    s0: f64,
    half: f64,
    speed: f64,
    stops: Vec<Stop>,
    end: f64,
    travel: [f64; 2],
}

/// The scene's traffic.
pub fn plan(input: &TrafficInput) -> Traffic {
    let junctions = junctions::junctions(input.layout, input.metres_per_pixel);
    let schedules = schedules(input, &junctions);
    let walks: Vec<(u32, Walk)> = input
        .roles
        .iter()
        .enumerate()
        .filter_map(|(index, role)| match role {
            Some(TrafficRole::Pedestrian(w)) => Some((index as u32 + 1, *w)),
            _ => None,
        })
        .collect();
    let (on_zebras, on_sidewalks): (Vec<_>, Vec<_>) =
        walks.into_iter().partition(|(_, w)| w.crossing.is_some());
    let crossers = pedestrians::crossings(input, &junctions, &schedules, &on_zebras);
    let ahead = Ahead {
        junctions: &junctions,
        schedules: &schedules,
        crossers: &crossers,
    };
    let mut placed = Vec::new();
    let mut carried = Vec::new();
    let mut heads = Vec::new();
    for (index, role) in input.roles.iter().enumerate() {
        let instance = index as u32 + 1;
        match role {
            Some(TrafficRole::Vehicle(v)) => {
                if let Some(p) = place(input, &ahead, instance, v) {
                    placed.push(p);
                }
            }
            Some(TrafficRole::Carried { back }) if *back < instance => {
                carried.push((instance, instance - back));
            }
            Some(TrafficRole::Signal { corner, axis }) => {
                if let Some(junction) = junctions::nearest(&junctions, *corner) {
                    heads.push(Head {
                        instance,
                        junction,
                        axis: *axis,
                    });
                }
            }
            _ => {}
        }
    }
    let mut all = lanes(placed);
    all.extend(lanes(pedestrians::sidewalks(input, &on_sidewalks)));
    all.extend(crossers.into_iter().map(|c| c.lane));
    Traffic {
        lanes: all,
        carried,
        heads,
        schedules,
        lamps: input.lamps,
    }
}

/// What a vehicle meets on its road: the junctions, their cycles, and the people crossing.
struct Ahead<'a> {
    junctions: &'a [Junction],
    schedules: &'a [Schedule],
    crossers: &'a [pedestrians::Crosser],
}

/// A speed in m/s drawn uniformly from `kmh` (km/h) by `instance`'s own stream.
fn drawn_speed(seed: u64, stream: &str, instance: u32, kmh: [f64; 2]) -> f64 {
    let mut rng = crate::rng::stream(seed, stream, u64::from(instance));
    (kmh[0] + rng.random::<f64>() * (kmh[1] - kmh[0])) / 3.6
}

/// Each junction's cycle: a seeded phase, or green centred on the drive's camera.
fn schedules(input: &TrafficInput, junctions: &[Junction]) -> Vec<Schedule> {
    let cycle = input.spec.cycle;
    let ego_axis = ego_axis(input.ego);
    junctions
        .iter()
        .enumerate()
        .map(|(j, junction)| {
            let mut rng = crate::rng::stream(input.seed, "traffic", j as u64);
            let seeded = Schedule {
                phase: rng.random::<f64>() * cycle,
                cycle,
            };
            let inside: Vec<f64> = input
                .ego
                .iter()
                .filter(|(_, eye)| junction.distance(*eye) == 0.0)
                .map(|(t, _)| *t)
                .collect();
            match (ego_axis, inside.first(), inside.last()) {
                (Some(axis), Some(t0), Some(t1)) => {
                    Schedule::green_at(axis, (t0 + t1) / 2.0, cycle)
                }
                _ => seeded,
            }
        })
        .collect()
}

/// The road a timed drive follows: along x or along z, by its whole displacement.
fn ego_axis(ego: &[(f64, [f64; 2])]) -> Option<Axis> {
    let (first, last) = (ego.first()?.1, ego.last()?.1);
    let (dx, dz) = ((last[0] - first[0]).abs(), (last[1] - first[1]).abs());
    (dx + dz > 0.0).then_some(if dx >= dz {
        Axis::Horizontal
    } else {
        Axis::Vertical
    })
}

/// A lane vehicle's way on its own; `None` when its road is not in the layout.
fn place(input: &TrafficInput, ahead: &Ahead, instance: u32, v: &LaneVehicle) -> Option<Placed> {
    let road = input.layout.roads.iter().find(|r| r.id == v.road)?;
    let mpp = input.metres_per_pixel;
    let (along, across, travel_along) = match road.axis {
        Axis::Horizontal => (v.centre[0], v.centre[1], v.travel[0]),
        Axis::Vertical => (v.centre[1], v.centre[0], v.travel[1]),
    };
    let sign: i8 = if travel_along >= 0.0 { 1 } else { -1 };
    let sf = f64::from(sign);
    let s0 = sf * along;
    let band = [across - v.half[1], across + v.half[1]];
    let kmh = if v.bicycle {
        input.spec.bicycle_kmh
    } else {
        input.spec.car_kmh
    };
    let speed = drawn_speed(input.seed, "traffic-speed", instance, kmh);
    let mut stops: Vec<Stop> = ahead
        .junctions
        .iter()
        .zip(ahead.schedules)
        .enumerate()
        .filter(|(_, (j, _))| j.roads.contains(&road.id))
        .filter_map(|(k, (j, schedule))| {
            let (al, ac) = j.along_across(road.axis);
            if !(ac[0] < band[1] && band[0] < ac[1]) {
                return None;
            }
            let entry = if sign > 0 { al[0] } else { -al[1] };
            let at = entry - STOP_LINE_END - v.half[0];
            // Until the people on its zebras there are off the road.
            let not_before = ahead
                .crossers
                .iter()
                .filter(|c| c.road == road.id && c.junction == k)
                .map(|c| c.clear)
                .fold(0.0, f64::max);
            (at >= s0 - 1e-9).then_some(Stop {
                at,
                // Over the zebra before the junction, through it, and over the one after.
                length: al[1] - al[0] + 2.0 * STOP_LINE_END + 2.0 * v.half[0],
                schedule: *schedule,
                axis: road.axis,
                not_before,
            })
        })
        .collect();
    stops.sort_by(|a, b| a.at.total_cmp(&b.at));
    let road_end = if sign > 0 {
        road.start.max(road.end) * mpp
    } else {
        -road.start.min(road.end) * mpp
    };
    let end = (road_end - END_GAP - v.half[0]).max(s0);
    Some(Placed {
        instance,
        road: road.id,
        sign,
        band,
        s0,
        half: v.half[0],
        speed,
        stops,
        end,
        travel: v.travel,
    })
}

/// Vehicles grouped into lanes (same road and way, strips overlapping), front first, with
/// their spacings.
fn lanes(mut placed: Vec<Placed>) -> Vec<Lane> {
    placed.sort_by(|a, b| {
        (a.road, a.sign)
            .cmp(&(b.road, b.sign))
            .then(a.band[0].total_cmp(&b.band[0]))
            .then(a.instance.cmp(&b.instance))
    });
    let mut groups: Vec<Vec<Placed>> = Vec::new();
    for p in placed {
        let joins = groups.last().is_some_and(|g| {
            let last = &g[0];
            let reach = g
                .iter()
                .map(|q| q.band[1])
                .fold(f64::NEG_INFINITY, f64::max);
            (last.road, last.sign) == (p.road, p.sign) && p.band[0] < reach
        });
        if joins {
            groups.last_mut().expect("joins a group").push(p);
        } else {
            groups.push(vec![p]);
        }
    }
    groups
        .into_iter()
        .map(|mut group| {
            group.sort_by(|a, b| b.s0.total_cmp(&a.s0).then(a.instance.cmp(&b.instance)));
            let travel = group[0].travel;
            let mut drivers: Vec<Driver> = Vec::with_capacity(group.len());
            for (m, p) in group.iter().enumerate() {
                // Newell: behind the one ahead by the delay and the spacing (the two
                // half-lengths and the jam gap, or the gap they stand at if smaller).
                let lead = m.checked_sub(1).map(|k| {
                    let ahead = &group[k];
                    let spacing = (ahead.half + p.half + JAM_GAP).min(ahead.s0 - p.s0);
                    drivers[k].path.following(FOLLOW_DELAY, spacing)
                });
                drivers.push(Driver {
                    instance: p.instance,
                    s0: p.s0,
                    path: Path::drive(p.s0, p.speed, &p.stops, p.end, lead.as_ref()),
                });
            }
            Lane { travel, drivers }
        })
        .collect()
}

impl Traffic {
    /// Whether nothing moves or changes (no lane vehicle and no signal head).
    pub fn is_empty(&self) -> bool {
        self.lanes.is_empty() && self.heads.is_empty()
    }

    /// Where every vehicle (and what it carries) stands at time `t` (seconds), and what
    /// every signal head shows.
    pub fn at(&self, t: f64) -> Movement {
        let mut moves = Vec::new();
        for lane in &self.lanes {
            for d in &lane.drivers {
                let run = d.path.at(t) - d.s0;
                moves.push((
                    d.instance,
                    [lane.travel[0] * run, 0.0, lane.travel[1] * run],
                ));
            }
        }
        moves.sort_by_key(|(id, _)| *id);
        let carried: Vec<(u32, [f64; 3])> = self
            .carried
            .iter()
            .filter_map(|&(id, carrier)| {
                let k = moves.binary_search_by_key(&carrier, |(c, _)| *c).ok()?;
                Some((id, moves[k].1))
            })
            .collect();
        moves.extend(carried);
        moves.sort_by_key(|(id, _)| *id);
        let mut recolour = Vec::new();
        let mut signals = Vec::new();
        for head in &self.heads {
            let state = self.schedules[head.junction].state(head.axis, t);
            signals.push((head.instance, state.name()));
            let Some(lamps) = self.lamps else {
                continue;
            };
            for (lamp, [lit, dark]) in Signal::ALL.into_iter().zip(lamps) {
                let (from, to) = if lamp == state {
                    (dark, lit)
                } else {
                    (lit, dark)
                };
                recolour.push(Recolour {
                    instance: head.instance,
                    from,
                    to,
                });
            }
        }
        Movement {
            moves,
            recolour,
            signals,
        }
    }
}
