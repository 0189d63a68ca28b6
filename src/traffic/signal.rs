//! A junction's signal cycle: the horizontal road green, amber, then red for all; the
//! vertical road the same in the other half of the cycle.

use crate::model::Axis;
use crate::model::geometry::rounding::floor;
use crate::objects::Signal;

/// Seconds of amber at the end of each road's green.
pub const AMBER: f64 = 3.0;
/// Seconds of red for both roads after each amber, so that what entered on green clears
/// the junction before the other road goes.
pub const ALL_RED: f64 = 2.0;

/// One junction's cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Schedule {
    /// When the horizontal road's green starts (and again every `cycle` seconds).
    pub phase: f64,
    pub cycle: f64,
}

impl Schedule {
    /// Seconds of green each road gets per cycle.
    pub fn green(&self) -> f64 {
        self.cycle / 2.0 - AMBER - ALL_RED
    }

    /// When the green of the road along `axis` starts, in the cycle `phase` begins.
    fn start(&self, axis: Axis) -> f64 {
        match axis {
            Axis::Horizontal => self.phase,
            Axis::Vertical => self.phase + self.cycle / 2.0,
        }
    }

    /// What a road along `axis` is shown at time `t`.
    pub fn state(&self, axis: Axis, t: f64) -> Signal {
        let u = (t - self.start(axis)).rem_euclid(self.cycle);
        if u < self.green() {
            Signal::Green
        } else if u < self.green() + AMBER {
            Signal::Amber
        } else {
            Signal::Red
        }
    }

    /// The earliest time from `t` on at which a vehicle on the road along `axis` may cross
    /// the stop line: its road is green, and it clears the junction (`clear` seconds)
    /// before the other road's green starts. For a vehicle too slow to clear in half a
    /// cycle, the start of the next green (where it cannot clear either).
    pub fn entry(&self, axis: Axis, t: f64, clear: f64) -> f64 {
        let open = self.green().min(self.cycle / 2.0 - clear);
        let start = self.start(axis);
        let k = floor((t - start) / self.cycle);
        let window = start + k * self.cycle;
        if open > 0.0 && t < window + open {
            t.max(window)
        } else {
            window + self.cycle
        }
    }

    /// When the other road's green starts after the green of the road along `axis` that
    /// time `t` falls in (or follows): what entered by then must have left.
    pub fn closes(&self, axis: Axis, t: f64) -> f64 {
        let start = self.start(axis);
        let k = floor((t - start) / self.cycle);
        start + k * self.cycle + self.cycle / 2.0
    }

    /// The cycle whose green for `axis` is centred on time `t`.
    pub fn green_at(axis: Axis, t: f64, cycle: f64) -> Schedule {
        let probe = Schedule { phase: 0.0, cycle };
        let phase = t - probe.green() / 2.0 - probe.start(axis);
        Schedule { phase, cycle }
    }
}
