//! One vehicle's way along its lane: at its speed, never closer to the vehicle ahead than
//! Newell's model allows, waiting at each stop line until its road may go and it can
//! clear the junction, on to the end of its road. A piecewise-linear function of time,
//! worked out once per vehicle (the front one first), never stepped frame by frame.

use super::signal::Schedule;
use crate::model::Axis;

/// Positions along the lane (metres, growing the way it drives) over time (seconds):
/// non-decreasing.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Path {
    /// `(time, position)` corners, time non-decreasing; before the first the position is
    /// the first's, after the last the last's.
    knots: Vec<(f64, f64)>,
}

/// A stop line on the way.
#[derive(Clone, Copy, Debug)]
pub(super) struct Stop {
    /// Where the vehicle's middle stands when it waits at the line.
    pub at: f64,
    /// How far it drives from there to have left the junction.
    pub length: f64,
    pub schedule: Schedule,
    /// The axis of its road.
    pub axis: Axis,
    /// The earliest it may cross (people still on a zebra it crosses).
    pub not_before: f64,
}

/// The most signal cycles a vehicle waits for the one ahead to clear a junction before it
/// is taken to wait for good.
const MAX_CYCLES: u32 = 1000;

impl Path {
    /// The way of a vehicle standing at `s0` at time 0, driving at `speed` m/s through
    /// `stops` (ascending) to `end`, never beyond `lead` (the vehicle ahead's way, shifted
    /// by Newell's delay and the spacing), if there is one.
    pub fn drive(s0: f64, speed: f64, stops: &[Stop], end: f64, lead: Option<&Path>) -> Path {
        let mut path = Path {
            knots: vec![(0.0, s0)],
        };
        let (mut t, mut s) = (0.0, s0);
        for stop in stops.iter().filter(|stop| stop.at >= s0) {
            let Some(arrive) = path.run(t, s, speed, stop.at, lead) else {
                return path;
            };
            let Some(go) = entry(stop, arrive, speed, lead) else {
                // The vehicle ahead never clears the junction: wait at the line for good.
                return path;
            };
            if go > arrive {
                path.knots.push((go, stop.at));
            }
            (t, s) = (go, stop.at);
        }
        if end > s {
            path.run(t, s, speed, end, lead);
        }
        path
    }

    /// Appends the run from `(t0, s0)` at `speed` under `lead` until the position reaches
    /// `target`, and returns when; `None` (after appending the run for good) when `lead`
    /// never lets it get there.
    fn run(
        &mut self,
        t0: f64,
        s0: f64,
        speed: f64,
        target: f64,
        lead: Option<&Path>,
    ) -> Option<f64> {
        let free = t0 + (target - s0) / speed;
        let Some(lead) = lead else {
            self.knots.push((free, target));
            return Some(free);
        };
        let reached = lead.reach(target);
        // Where the run ends: at the target, or (held for good) where the line meets the
        // lead's last position.
        let last = *lead.knots.last().expect("a path has knots");
        let until = match reached {
            Some(t) => free.max(t),
            None => last.0.max(t0 + (last.1 - s0).max(0.0) / speed),
        };
        let line = |t: f64| s0 + speed * (t - t0);
        let mut times: Vec<f64> = vec![t0];
        times.extend(
            lead.knots
                .iter()
                .map(|k| k.0)
                .filter(|&t| t > t0 && t < until),
        );
        times.push(until);
        // Where the line crosses the lead between two of those times.
        let mut all = Vec::with_capacity(times.len() * 2);
        for w in times.windows(2) {
            all.push(w[0]);
            let (fa, fb) = (line(w[0]) - lead.at(w[0]), line(w[1]) - lead.at(w[1]));
            if (fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0) {
                all.push(w[0] + (w[1] - w[0]) * fa / (fa - fb));
            }
        }
        all.push(until);
        for &t in &all[1..] {
            let s = line(t).min(lead.at(t));
            let previous = self.knots.last().map_or(f64::NEG_INFINITY, |k| k.1);
            self.knots.push((t, s.max(previous)));
        }
        match reached {
            Some(_) => {
                let last = self.knots.last_mut().expect("just pushed");
                last.1 = target;
                Some(until)
            }
            None => None,
        }
    }

    /// The way of a person standing at `s0` who walks `reach` at `speed` from time
    /// `start` on.
    pub fn walk(s0: f64, start: f64, speed: f64, reach: f64) -> Path {
        let mut knots = vec![(0.0, s0)];
        if start > 0.0 {
            knots.push((start, s0));
        }
        knots.push((start + reach / speed, s0 + reach));
        Path { knots }
    }

    /// The position at time `t`.
    pub fn at(&self, t: f64) -> f64 {
        let k = self.knots.partition_point(|(kt, _)| *kt <= t);
        if k == 0 {
            return self.knots[0].1;
        }
        let (t0, s0) = self.knots[k - 1];
        let Some(&(t1, s1)) = self.knots.get(k) else {
            return s0;
        };
        s0 + (s1 - s0) * (t - t0) / (t1 - t0)
    }

    /// The first time the position reaches `s` (minus infinity when it starts there);
    /// `None` when it never does.
    pub fn reach(&self, s: f64) -> Option<f64> {
        if self.knots[0].1 >= s {
            return Some(f64::NEG_INFINITY);
        }
        let k = self.knots.iter().position(|k| k.1 >= s)?;
        let ((t0, s0), (t1, s1)) = (self.knots[k - 1], self.knots[k]);
        Some(t0 + (t1 - t0) * (s - s0) / (s1 - s0))
    }

    /// This way `delay` seconds later and `back` metres behind: the bound it sets the
    /// vehicle behind.
    pub fn following(&self, delay: f64, back: f64) -> Path {
        Path {
            knots: self
                .knots
                .iter()
                .map(|&(t, s)| (t + delay, s - back))
                .collect(),
        }
    }
}

/// When a vehicle that reached `stop` at `arrive` crosses it: the first time its road is
/// green with time to clear the junction, at its own `speed` and behind `lead`, before
/// the other road's green. `None` when the lead never leaves room to clear.
fn entry(stop: &Stop, arrive: f64, speed: f64, lead: Option<&Path>) -> Option<f64> {
    let own = stop.length / speed;
    let held = match lead {
        Some(lead) => lead.reach(stop.at + stop.length)?,
        None => f64::NEG_INFINITY,
    };
    let mut go = stop
        .schedule
        .entry(stop.axis, arrive.max(stop.not_before), own);
    for _ in 0..MAX_CYCLES {
        if (go + own).max(held) <= stop.schedule.closes(stop.axis, go) {
            return Some(go);
        }
        go = stop
            .schedule
            .entry(stop.axis, stop.schedule.closes(stop.axis, go), own);
    }
    None
}
