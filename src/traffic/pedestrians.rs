//! People walking: along the sidewalks, and across the zebra crossings.
//!
//! - **Along a sidewalk** a person walks straight on at its speed (drawn from `walk_kmh`)
//!   as far as the objects stage found the way clear ([`Walk::reach`]: up to the first
//!   thing standing in its way, or its block's corner). People walking the same way in
//!   overlapping bands form a queue and follow by Newell's model as vehicles do; two
//!   walking towards each other in overlapping bands both stop before they would touch,
//!   halfway between where they stand.
//! - **Across a zebra** a person walks to its place on the far side (the objects stage
//!   kept the whole way clear; people crossing either way keep to the half of the zebra on
//!   their right, so they never meet). One already on the zebra walks on at once (unless
//!   a timed drive's camera is about to pass: then it waits where it stands, clear of the
//!   camera's lane, until the camera has passed); the vehicles of the road it crosses wait
//!   until it is off the road. One waiting at the zebra's end crosses in its junction's
//!   green for the other road (the road it crosses has red), early enough to be over before
//!   the road it crosses gets green again; vehicles clear the zebras before that green.

use super::junctions::Junction;
use super::path::{Path, Stop};
use super::signal::Schedule;
use super::{Driver, Lane, Placed, TrafficInput};
use crate::model::{Axis, Walk};

/// How long a person on a zebra waits after a timed drive's camera has passed, and how
/// long before it comes it must be off the camera's way, seconds.
const CAMERA_MARGIN: f64 = 1.0;
/// How close to a crossing person's way the camera's eye counts as passing, metres.
const CAMERA_REACH: f64 = 1.5;

/// A person crossing a road: its one-person lane and, for one on the zebra at time 0,
/// when it is off the road it crossed.
pub(super) struct Crosser {
    pub lane: Lane,
    /// The road crossed and the junction whose cycle it keeps.
    pub road: u32,
    pub junction: usize,
    /// When the vehicles of that road may cross the zebra: 0 for a person waiting at its
    /// end (who crosses only while they have red).
    pub clear: f64,
}

/// A walking person's speed, m/s.
fn speed(input: &TrafficInput, instance: u32) -> f64 {
    super::drawn_speed(input.seed, "traffic-walk", instance, input.spec.walk_kmh)
}

/// Along and across coordinates of `p` for a walk along `travel` (a unit vector along x
/// or z): `(sign, along × sign, across)`.
fn frame(travel: [f64; 2], p: [f64; 2]) -> (i8, f64, f64) {
    let (k, across) = match walk_axis(travel) {
        Axis::Horizontal => (0, p[1]),
        Axis::Vertical => (1, p[0]),
    };
    let sign = if travel[k] >= 0.0 { 1 } else { -1 };
    (sign, f64::from(sign) * p[k], across)
}

/// The people walking along sidewalks (`(instance, walk)`), ready to be put in lanes:
/// each stops where its way ends, and before anyone walking towards it.
pub(super) fn sidewalks(input: &TrafficInput, walks: &[(u32, Walk)]) -> Vec<Placed> {
    let mut placed: Vec<Placed> = walks
        .iter()
        .map(|&(instance, w)| {
            let (sign, s0, across) = frame(w.travel, w.centre);
            Placed {
                instance,
                road: w.road,
                sign,
                band: [across - w.room, across + w.room],
                s0,
                half: w.room,
                speed: speed(input, instance),
                stops: Vec::new(),
                end: s0 + w.reach,
                travel: w.travel,
            }
        })
        .collect();
    // Two walking towards each other, bands overlapping: both stop short of the middle.
    let ends: Vec<f64> = placed
        .iter()
        .map(|a| {
            placed
                .iter()
                .filter(|b| {
                    b.road == a.road && b.sign == -a.sign && a.travel[0].abs() == b.travel[0].abs()
                })
                .filter_map(|b| {
                    // b's position in a's along coordinate, and how far across apart.
                    let b_at = -b.s0;
                    let gap = ((a.band[0] + a.band[1]) - (b.band[0] + b.band[1])).abs() / 2.0;
                    let touch = a.half + b.half;
                    (b_at > a.s0 && gap < touch).then(|| {
                        let apart = (touch * touch - gap * gap).sqrt();
                        (a.s0 + b_at) / 2.0 - apart / 2.0
                    })
                })
                .fold(a.end, f64::min)
                .max(a.s0)
        })
        .collect();
    for (p, end) in placed.iter_mut().zip(ends) {
        p.end = end;
    }
    placed
}

/// The people crossing roads (`(instance, walk)` with a crossing), each its own lane, and
/// when each is off the road.
pub(super) fn crossings(
    input: &TrafficInput,
    junctions: &[Junction],
    schedules: &[Schedule],
    walks: &[(u32, Walk)],
) -> Vec<Crosser> {
    walks
        .iter()
        .filter_map(|&(instance, w)| {
            let crossing = w.crossing?;
            let j = super::junctions::nearest(junctions, w.centre)?;
            let speed = speed(input, instance);
            let (_, s0, _) = frame(w.travel, w.centre);
            let own = w.reach / speed;
            let way = Way {
                from: w.centre,
                to: [
                    w.centre[0] + w.travel[0] * w.reach,
                    w.centre[1] + w.travel[1] * w.reach,
                ],
                room: w.room,
            };
            let path = if crossing.waiting {
                let axis = walk_axis(w.travel);
                let mut from = 0.0;
                let mut go = None;
                // A second try starts after the camera's last pass: it never meets it.
                for _ in 0..2 {
                    let stop = Stop {
                        at: s0,
                        length: w.reach,
                        schedule: schedules[j],
                        axis,
                        not_before: from,
                    };
                    let path = Path::drive(s0, speed, &[stop], s0 + w.reach, None);
                    let start = path.reach(s0 + 1e-6).unwrap_or(f64::INFINITY);
                    match camera_passes(input.ego, &way, start, own) {
                        Some(after) => from = after,
                        None => {
                            go = Some(path);
                            break;
                        }
                    }
                }
                go?
            } else {
                let start = camera_passes(input.ego, &way, 0.0, own).unwrap_or(0.0);
                Path::walk(s0, start, speed, w.reach)
            };
            let clear = if crossing.waiting {
                0.0
            } else {
                path.reach(s0 + w.reach).unwrap_or(f64::INFINITY)
            };
            Some(Crosser {
                lane: Lane {
                    travel: w.travel,
                    drivers: vec![Driver { instance, s0, path }],
                },
                road: w.road,
                junction: j,
                clear,
            })
        })
        .collect()
}

/// The axis a person walking along `travel` walks along.
fn walk_axis(travel: [f64; 2]) -> Axis {
    if travel[0].abs() >= travel[1].abs() {
        Axis::Horizontal
    } else {
        Axis::Vertical
    }
}

/// A crossing person's way, world metres.
struct Way {
    from: [f64; 2],
    to: [f64; 2],
    room: f64,
}

impl Way {
    /// Distance from `p` to the way's centre segment.
    fn distance(&self, p: [f64; 2]) -> f64 {
        let d = [self.to[0] - self.from[0], self.to[1] - self.from[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        let u = if len2 > 0.0 {
            (((p[0] - self.from[0]) * d[0] + (p[1] - self.from[1]) * d[1]) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let q = [self.from[0] + u * d[0], self.from[1] + u * d[1]];
        ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt()
    }
}

/// When a timed drive's camera (`ego`: `(time, eye)`) passes `way` while a person would be
/// on it (from `start` for `own` seconds, with [`CAMERA_MARGIN`] either side): the time the
/// person may start after the camera is past. `None` when it does not.
fn camera_passes(ego: &[(f64, [f64; 2])], way: &Way, start: f64, own: f64) -> Option<f64> {
    let near: Vec<f64> = ego
        .iter()
        .filter(|(_, eye)| way.distance(*eye) < way.room + CAMERA_REACH)
        .map(|(t, _)| *t)
        .collect();
    let (first, last) = (*near.first()?, *near.last()?);
    let busy = [start - CAMERA_MARGIN, start + own + CAMERA_MARGIN];
    (first <= busy[1] && last >= busy[0]).then_some(last + CAMERA_MARGIN)
}
