//! Streets as polylines → seeded [`Lamp`]s: the paper's rule, "every `spacing` along each
//! road on both sides, none inside a crossing, of two too close one removed", once for
//! both inputs. A layout hands its roads (one straight segment each, in pixels) and reads
//! where a lamp stands off its strip pixels; a map hands its joined streets (in metres)
//! and its fitted sidewalks. Both are [`PavedSegment`]s, so the candidates, their order,
//! positions and facings, and the pruning are this one code.

use std::collections::HashMap;

use crate::model::geometry::polygon::{direction, distance, left_normal};
use crate::model::{Lamp, PavedSegment};

/// The sides of a street: index 0 is left of its segments' direction, 1 right.
pub(crate) type SideIndex = usize;

/// A street lamps are seeded along: paved segments end to end, and the order its sides
/// are seeded in.
pub(crate) struct Street {
    pub segments: Vec<PavedSegment>,
    pub sides: [SideIndex; 2],
}

/// The candidates (id 0) along every street, street by street, each side in the street's
/// order, in order along it: at `spacing/2 + k·spacing` along the centreline (computed as
/// `spacing · (k + ½)`, so no error adds up along a long street). `offset(segment, side,
/// q)` says how far out from the centreline point `q` the lamp stands on that side, or
/// None where none stands; each lamp faces its centreline point. The caller checks that
/// `spacing` is a positive finite number.
pub(crate) fn candidates(
    streets: &[Street],
    spacing: f64,
    offset: impl Fn(&PavedSegment, SideIndex, [f64; 2]) -> Option<f64>,
) -> Vec<Lamp> {
    let mut lamps = Vec::new();
    for street in streets {
        for &side in &street.sides {
            let mut k = 0u64;
            let mut passed = 0.0;
            for s in &street.segments {
                let (Some(d), Some(n)) = (direction(s.a, s.b), left_normal(s.a, s.b)) else {
                    continue;
                };
                let length = distance(s.a, s.b);
                loop {
                    let along = spacing * (k as f64 + 0.5);
                    if along >= passed + length {
                        break;
                    }
                    k += 1;
                    let t = along - passed;
                    let q = [s.a[0] + d[0] * t, s.a[1] + d[1] * t];
                    let Some(off) = offset(s, side, q) else {
                        continue;
                    };
                    let out = if side == 0 { n } else { [-n[0], -n[1]] };
                    lamps.push(Lamp {
                        id: 0,
                        position: [q[0] + out[0] * off, q[1] + out[1] * off],
                        road: s.road as u32,
                        // `0.0 -` rather than a negation: no `-0.0` reaches the JSON.
                        facing: [0.0 - out[0], 0.0 - out[1]],
                    });
                }
                passed += length;
            }
        }
    }
    lamps
}

/// The rule's last step: `kept` (the map's own lamps, if any) and then each candidate in
/// order that is no closer than `keep_off_kept` to any of those, no closer than
/// `min_distance` to a candidate kept before it, and `clear` (the cheap distance tests
/// run first). A `min_distance` that is not positive removes none. Ids count the list.
pub(crate) fn keep(
    kept: Vec<Lamp>,
    candidates: impl IntoIterator<Item = Lamp>,
    keep_off_kept: f64,
    min_distance: f64,
    clear: impl Fn([f64; 2]) -> bool,
) -> Vec<Lamp> {
    let too_near = |a: [f64; 2], b: [f64; 2], least: f64| {
        (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) < least * least
    };
    let prune = min_distance > 0.0;
    // Buckets of side `min_distance`: a lamp closer than that lies in one of the 3×3
    // cells around. The map is only looked up, never iterated, so its order cannot leak.
    let cell = |v: f64| (v / min_distance).floor() as i64;
    let mut grid: HashMap<(i64, i64), Vec<[f64; 2]>> = HashMap::new();
    let first = kept.len();
    let mut lamps = kept;
    for lamp in candidates {
        let p = lamp.position;
        if lamps[..first]
            .iter()
            .any(|l| too_near(l.position, p, keep_off_kept))
        {
            continue;
        }
        let (cx, cy) = (cell(p[0]), cell(p[1]));
        let crowded = prune
            && (cx.saturating_sub(1)..=cx.saturating_add(1)).any(|i| {
                (cy.saturating_sub(1)..=cy.saturating_add(1)).any(|j| {
                    (grid.get(&(i, j)))
                        .is_some_and(|ps| ps.iter().any(|&o| too_near(o, p, min_distance)))
                })
            });
        if crowded || !clear(p) {
            continue;
        }
        if prune {
            grid.entry((cx, cy)).or_default().push(p);
        }
        lamps.push(Lamp {
            id: lamps.len() as u32,
            ..lamp
        });
    }
    lamps
}

#[cfg(test)]
mod tests {
    use super::*;

    fn segment(road: usize, a: [f64; 2], b: [f64; 2]) -> PavedSegment {
        PavedSegment {
            road,
            a,
            b,
            width: 10.0,
            sidewalks: [2.0, 2.0],
        }
    }

    /// A street east 30 m then north 30 m, candidates every 20 m: at 10 along the first
    /// segment, then 30 and 50 (0 and 20 along the second); sides in the street's order,
    /// each `offset` out, facing back.
    #[test]
    fn candidates_run_on_through_the_corners_side_by_side() {
        let street = Street {
            segments: vec![
                segment(3, [0.0, 0.0], [30.0, 0.0]),
                segment(4, [30.0, 0.0], [30.0, -30.0]),
            ],
            sides: [1, 0],
        };
        let lamps = candidates(&[street], 20.0, |s, side, _| {
            Some(s.width / 2.0 + if side == 0 { 1.0 } else { 2.0 })
        });
        let got: Vec<([f64; 2], u32, [f64; 2])> = (lamps.iter())
            .map(|l| (l.position, l.road, l.facing))
            .collect();
        assert_eq!(
            got,
            vec![
                // Right (south, then east) first.
                ([10.0, 7.0], 3, [0.0, -1.0]),
                ([37.0, 0.0], 4, [-1.0, 0.0]),
                ([37.0, -20.0], 4, [-1.0, 0.0]),
                ([10.0, -6.0], 3, [0.0, 1.0]),
                ([24.0, 0.0], 4, [1.0, 0.0]),
                ([24.0, -20.0], 4, [1.0, 0.0]),
            ]
        );
        assert!(lamps.iter().all(|l| l.id == 0));
        // No `-0.0` in a facing.
        assert!((lamps.iter().flat_map(|l| l.facing)).all(|v| v != 0.0 || v.is_sign_positive()));
    }

    #[test]
    fn an_offset_of_none_leaves_a_candidate_out_and_the_count_goes_on() {
        let street = Street {
            segments: vec![segment(0, [0.0, 0.0], [100.0, 0.0])],
            sides: [0, 1],
        };
        let lamps = candidates(&[street], 20.0, |_, side, q| {
            (side == 0 && q[0] != 50.0).then_some(5.0)
        });
        let xs: Vec<f64> = lamps.iter().map(|l| l.position[0]).collect();
        assert_eq!(xs, vec![10.0, 30.0, 70.0, 90.0]);
    }

    #[test]
    fn kept_lamps_come_first_and_candidates_keep_their_distances() {
        let lamp = |x: f64| Lamp {
            id: 9,
            position: [x, 0.0],
            road: 0,
            facing: [0.0, 1.0],
        };
        let mapped = vec![Lamp { id: 0, ..lamp(0.0) }];
        let candidates = [5.0, 15.0, 20.0, 28.0, 40.0, 60.0].map(lamp);
        // 5 within 10 of the mapped lamp; 20 within 8 of 15; 60 not clear.
        let kept = keep(mapped, candidates.clone(), 10.0, 8.0, |p| p[0] < 50.0);
        let xs: Vec<(u32, f64)> = kept.iter().map(|l| (l.id, l.position[0])).collect();
        assert_eq!(xs, vec![(0, 0.0), (1, 15.0), (2, 28.0), (3, 40.0)]);
        // Without a positive distance every candidate stays.
        for none in [0.0, -1.0, f64::NAN] {
            assert_eq!(
                keep(vec![], candidates.clone(), 0.0, none, |_| true).len(),
                6
            );
        }
    }
}
