//! Roads → the places traffic signs stand by rule: every crossing's mouths (a road's zebra
//! crossing on its way into a crossing, and the traffic driving towards it), which of the
//! two roads has priority there, and for each sign type where along a mouth it goes.
//!
//! A road ending at the crossing (a T junction's stem) gives way; otherwise the wider
//! road has priority, and between equals a draw from the seed decides, one per crossing.
//! Approaches without a zebra crossing (a stretch too short for one) have no mouth.

use rand::RngExt;

use crate::model::geometry::RoadRect;
use crate::model::geometry::zebras::{CROSSING_MARGIN, road_stretches};
use crate::model::{Axis, ParsedLayout};
use crate::spec::SignKind;

/// Where a sign type stands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Rule {
    /// At a mouth's stop line, facing the traffic driving in; `true`: on the road with
    /// priority (priority road), `false`: on the road that gives way (stop, yield). One
    /// such sign a mouth.
    Mouth(bool),
    /// Beside a mouth's zebra crossing (the crossing's own sign), one a mouth.
    Zebra,
    /// `[low, high]` metres before a mouth's stop line, facing the traffic driving in;
    /// `Some(true)`: only where that road has priority.
    Before([f64; 2], Option<bool>),
    /// `[low, high]` metres past a mouth's zebra crossing, facing the traffic leaving the
    /// crossing.
    After([f64; 2]),
    /// Anywhere on the strips.
    Free,
}

/// Distance before a zebra crossing that its warnings stand, metres.
pub const WARNING_BEFORE: [f64; 2] = [30.0, 50.0];
/// Distance past a crossing's zebra that a speed limit stands, metres.
pub const LIMIT_AFTER: [f64; 2] = [5.0, 15.0];

/// The rule a sign type is placed by.
pub fn rule(kind: SignKind) -> Rule {
    match kind {
        SignKind::Stop | SignKind::Yield => Rule::Mouth(false),
        SignKind::PriorityRoad => Rule::Mouth(true),
        SignKind::PedestrianCrossing => Rule::Zebra,
        SignKind::Pedestrians | SignKind::Children => Rule::Before(WARNING_BEFORE, None),
        SignKind::PriorityJunction => Rule::Before(WARNING_BEFORE, Some(true)),
        SignKind::SpeedLimit => Rule::After(LIMIT_AFTER),
        _ => Rule::Free,
    }
}

/// One road's way into a crossing, in metres along its axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mouth {
    pub road: u32,
    pub axis: Axis,
    /// The zebra crossing's along-axis range.
    pub zebra: [f64; 2],
    /// Its edge away from the crossing, where the traffic stops.
    pub stop: f64,
    /// +1 when the traffic driving in runs towards larger along-axis values, else −1.
    pub dir: f64,
    /// The road it meets.
    pub other: u32,
    /// Whether this road has priority over `other` here.
    pub priority: bool,
}

impl Mouth {
    /// The side of the road (as [`super::ground_spots::travel`]'s `high`) of the traffic
    /// driving in.
    pub fn in_high(&self) -> bool {
        (self.dir > 0.0) == (self.axis == Axis::Horizontal)
    }

    /// Along-axis metres `metres` before the stop line (negative: past it, towards the
    /// crossing).
    pub fn before(&self, metres: f64) -> f64 {
        self.stop - self.dir * metres
    }
}

/// Every mouth of `layout` (`mpp` metres per pixel), road by road, zebra by zebra.
pub fn mouths(layout: &ParsedLayout, mpp: f64, seed: u64) -> Vec<Mouth> {
    let rects: Vec<RoadRect> = layout.roads.iter().map(RoadRect::of).collect();
    let mut out = Vec::new();
    for (i, stretches) in road_stretches(layout, mpp).into_iter().enumerate() {
        let road = &layout.roads[i];
        for (zebra, at_start) in stretches.zebras {
            // At the stretch's start the crossing lies before it, at lower values.
            let dir = if at_start { -1.0 } else { 1.0 };
            let stop = if at_start { zebra[1] } else { zebra[0] };
            let probe = if at_start {
                zebra[0] - CROSSING_MARGIN - 0.5
            } else {
                zebra[1] + CROSSING_MARGIN + 0.5
            } / mpp;
            let p = match road.axis {
                Axis::Horizontal => [probe, road.line],
                Axis::Vertical => [road.line, probe],
            };
            let Some(other) = (0..rects.len()).find(|&j| {
                j != i
                    && (rects[j].x[0]..=rects[j].x[1]).contains(&p[0])
                    && (rects[j].y[0]..=rects[j].y[1]).contains(&p[1])
            }) else {
                continue;
            };
            out.push(Mouth {
                road: road.id,
                axis: road.axis,
                zebra,
                stop,
                dir,
                other: layout.roads[other].id,
                priority: false,
            });
        }
    }
    let priority: Vec<bool> = out
        .iter()
        .map(|m| has_priority(layout, &out, m.road, m.other, seed))
        .collect();
    for (m, p) in out.iter_mut().zip(priority) {
        m.priority = p;
    }
    out
}

/// Whether `road` has priority over `other` where they cross: a road with fewer mouths
/// there (it ends at the crossing) gives way, then the narrower one, then a draw.
fn has_priority(layout: &ParsedLayout, mouths: &[Mouth], road: u32, other: u32, seed: u64) -> bool {
    let count = |r: u32, o: u32| {
        mouths
            .iter()
            .filter(|m| m.road == r && m.other == o)
            .count()
    };
    let width = |r: u32| {
        layout
            .roads
            .iter()
            .find(|x| x.id == r)
            .map_or(0.0, |x| x.width())
    };
    let by_count = count(road, other).cmp(&count(other, road));
    let by_width = width(road).total_cmp(&width(other));
    match by_count.then(by_width) {
        std::cmp::Ordering::Greater => true,
        std::cmp::Ordering::Less => false,
        std::cmp::Ordering::Equal => {
            let (a, b) = (road.min(other), road.max(other));
            let mut rng =
                crate::rng::stream(seed, "sign_priority", (u64::from(a) << 32) | u64::from(b));
            let first: bool = rng.random();
            first == (road == a)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn at_each_crossing_one_road_has_priority_and_mouths_face_it() {
        let city = crate::test_support::test_city(42, &[10.0, 14.0, 18.0]);
        let mouths = mouths(&city.layout, 1.0, 42);
        assert!(mouths.len() >= 8, "{}", mouths.len());
        for m in &mouths {
            for n in mouths
                .iter()
                .filter(|n| n.road == m.other && n.other == m.road)
            {
                assert_ne!(m.priority, n.priority, "{m:?} {n:?}");
            }
            // The crossing lies ahead of the traffic driving in.
            let ahead = m.before(-(m.zebra[1] - m.zebra[0]) - CROSSING_MARGIN - 0.5);
            let road = &city.layout.roads[m.other as usize];
            let across = RoadRect::of(road);
            let a = match m.axis {
                Axis::Horizontal => across.x,
                Axis::Vertical => across.y,
            };
            assert!(
                (a[0]..=a[1]).contains(&ahead),
                "{m:?}: {ahead} not in {a:?}"
            );
        }
        assert!(mouths.iter().any(|m| m.priority));
        assert!(mouths.iter().any(|m| !m.priority));
    }
}
