//! A map's street lamps → [`Lamp`] sites: each `highway=street_lamp` node at the kerb of
//! the road it lights; where the map has none, the paper's rule along its paved roads.
//!
//! - **Mapped.** A lamp at every `street_lamp` node within [`REACH`] of a paved road: where
//!   the map puts it, or, when that is on the carriageway (a lamp hung over the street, or
//!   mapped on the centreline), [`KERB_SETBACK`] behind the kerb on the same side of the
//!   centreline. One inside a building is left out.
//! - **Seeded** (with `[lamps]`, unless the spec turns it off): the layouts' rule, "every
//!   `spacing` along each road on both sides, none inside a crossing, of two too close one
//!   removed", on the map's polylines, by the layouts' code (`seed.rs`). The runs of
//!   consecutive paved segments are joined into streets where one goes straight on from
//!   another (OSM splits a street's way at many nodes); each street takes candidates at
//!   `spacing/2 + k·spacing` metres along its centreline, on its left and then its right,
//!   [`KERB_SETBACK`] behind the kerb of the segment there. A candidate is left out where that side has less than [`MIN_SIDEWALK`] of sidewalk, where it
//!   stands on any carriageway (a junction, the inside of a bend) or within
//!   [`CLEARANCE`] of a building, a node the map puts something at, or the box's edge;
//!   within `spacing / 2` of a mapped lamp (the map lights that stretch itself); or
//!   within `min_distance` of a lamp kept before it.
//!
//! Each lamp faces the nearest point of its road's centreline, and `road` is that road's
//! index in `map.roads`. Ids count the mapped lamps in node order, then the seeded ones
//! by street (in the order of their first runs), side and distance along.

use crate::model::geometry::map_lines::MIN_SINE;
use crate::model::geometry::polygon::{direction, distance, left_normal, nearest};
use crate::model::{FeatureKind, Lamp, OsmMap, PavedSegment, paved_runs};
use crate::spec::LampsSpec;

use super::seed::{self, Street};

/// The farthest a mapped lamp stands from the road it lights, metres: lamps farther out
/// light paths and parks, not a street, and are left out.
pub const REACH: f64 = 25.0;
/// How far behind the kerb a lamp mapped on the carriageway (hung over the street, or
/// mapped on the centreline) stands, and a seeded lamp, metres.
pub const KERB_SETBACK: f64 = 0.5;
/// The least sidewalk a seeded lamp stands on, metres.
pub const MIN_SIDEWALK: f64 = 1.0;
/// How far a seeded lamp keeps from buildings, from the nodes the map puts things at
/// (trees, signals, signs, benches, …) and from the box's edge, metres.
pub const CLEARANCE: f64 = 1.0;

/// The lamps of `map`: the mapped ones, then, with `seeded`, the ones seeded along its
/// roads (see the module's rules), positions in metres (a metre per "pixel"). A
/// `spacing` that is not a positive finite number seeds none. Pure and deterministic.
pub fn map_lamps(map: &OsmMap, seeded: Option<&LampsSpec>) -> Vec<Lamp> {
    let lamps = mapped(map);
    let Some(spec) = seeded.filter(|s| s.spacing.is_finite() && s.spacing > 0.0) else {
        return lamps;
    };
    let paved: Vec<PavedSegment> = map.paved_segments().collect();
    let clear = |p: [f64; 2]| {
        map.holds(p, CLEARANCE)
            && map.features.iter().all(|f| distance(f.at, p) >= CLEARANCE)
            && (paved.iter())
                .all(|o| distance(p, nearest(o.a, o.b, p)) >= o.width / 2.0 + KERB_SETBACK - 1e-6)
            && map.out_of_buildings(p, CLEARANCE)
    };
    seed::keep(
        lamps,
        candidates(&paved, spec.spacing),
        (spec.spacing / 2.0).max(spec.min_distance),
        spec.min_distance,
        clear,
    )
}

/// The lamps at the map's `street_lamp` nodes, in node order.
fn mapped(map: &OsmMap) -> Vec<Lamp> {
    let mut lamps = Vec::new();
    for f in map
        .features
        .iter()
        .filter(|f| f.kind == FeatureKind::StreetLamp)
    {
        let Some((segment, q, d)) = map.nearest_paved(f.at) else {
            break;
        };
        if d > REACH {
            continue;
        }
        let kerb = segment.width / 2.0 + KERB_SETBACK;
        let foot = if d >= kerb {
            f.at
        } else {
            // Out from the centreline on the lamp's side (on the line itself: the right).
            let out = if d > 0.0 {
                [(f.at[0] - q[0]) / d, (f.at[1] - q[1]) / d]
            } else {
                left_normal(segment.a, segment.b).map_or([1.0, 0.0], |n| [-n[0], -n[1]])
            };
            [q[0] + out[0] * kerb, q[1] + out[1] * kerb]
        };
        let to_road = distance(foot, q);
        if map.in_building(foot) || to_road == 0.0 {
            continue;
        }
        lamps.push(Lamp {
            id: lamps.len() as u32,
            position: foot,
            road: segment.road as u32,
            facing: [(q[0] - foot[0]) / to_road, (q[1] - foot[1]) / to_road],
        });
    }
    lamps
}

/// The seeded candidates (id 0) along every street ([`seed::candidates`]): per street the
/// left side, then the right, [`KERB_SETBACK`] behind the kerb where that side has
/// [`MIN_SIDEWALK`]. Streets are in the order of their first run.
fn candidates(paved: &[PavedSegment], spacing: f64) -> Vec<Lamp> {
    let streets: Vec<Street> = (streets(paved).into_iter())
        .map(|segments| Street {
            segments,
            sides: [0, 1],
        })
        .collect();
    seed::candidates(&streets, spacing, |s, side, _| {
        (s.sidewalks[side] >= MIN_SIDEWALK).then_some(s.width / 2.0 + KERB_SETBACK)
    })
}

/// The paved segments as streets: runs of consecutive paved segments of one road, joined
/// where one run ends at the node another begins or ends at and the street goes on
/// straight (turning less than `asin(MIN_SINE)`, about 17°: OSM splits a street's way at
/// many of its nodes), each turned to run the first's way (its sidewalks swapped with
/// it). A run joins the straightest of those, the first in map order on a tie; each run
/// is in one street.
fn streets(paved: &[PavedSegment]) -> Vec<Vec<PavedSegment>> {
    let runs = paved_runs(paved.iter().copied());
    let oriented = |run: &[PavedSegment], reversed: bool| -> Vec<PavedSegment> {
        if reversed {
            run.iter().rev().map(PavedSegment::turned).collect()
        } else {
            run.to_vec()
        }
    };
    // The unused run that carries on straightest from `end` heading `heading`: its index
    // and whether it runs the other way.
    let next = |used: &[bool], end: [f64; 2], heading: [f64; 2]| -> Option<(usize, bool)> {
        let mut best: Option<(usize, bool, f64)> = None;
        for (j, run) in runs.iter().enumerate().filter(|(j, _)| !used[*j]) {
            let (first, last) = (run[0], run[run.len() - 1]);
            for (reversed, from, to) in [(false, first.a, first.b), (true, last.b, last.a)] {
                let Some(d) = direction(from, to).filter(|_| from == end) else {
                    continue;
                };
                let cos = d[0] * heading[0] + d[1] * heading[1];
                let straight = cos > 0.0 && (1.0 - cos * cos).max(0.0).sqrt() < MIN_SINE;
                if straight && best.is_none_or(|b| cos > b.2) {
                    best = Some((j, reversed, cos));
                }
            }
        }
        best.map(|(j, reversed, _)| (j, reversed))
    };
    let mut used = vec![false; runs.len()];
    let mut streets = Vec::new();
    for i in 0..runs.len() {
        if used[i] {
            continue;
        }
        used[i] = true;
        let mut street = runs[i].to_vec();
        // On ahead from the last point, then back from the first (turned around).
        for back in [false, true] {
            loop {
                let tail = if back {
                    street[0].turned()
                } else {
                    street[street.len() - 1]
                };
                let Some(heading) = direction(tail.a, tail.b) else {
                    break;
                };
                let Some((j, reversed)) = next(&used, tail.b, heading) else {
                    break;
                };
                used[j] = true;
                if back {
                    let mut before = oriented(&runs[j], !reversed);
                    before.extend(street);
                    street = before;
                } else {
                    street.extend(oriented(&runs[j], reversed));
                }
            }
        }
        streets.push(street);
    }
    streets
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spacing(spacing: f64, min_distance: f64) -> LampsSpec {
        LampsSpec {
            spacing,
            min_distance,
        }
    }

    #[test]
    fn lamps_stand_at_the_kerb_facing_their_road() {
        let map = crate::test_support::street_map();
        let lamps = map_lamps(&map, None);
        // Beside the road: where the map puts it. On the centreline: half the 12 m
        // carriageway and the setback to the right. 60 m from any road: none.
        let expected = vec![
            Lamp {
                id: 0,
                position: [-100.0, -8.0],
                road: 0,
                facing: [0.0, 1.0],
            },
            Lamp {
                id: 1,
                position: [-20.0, 6.0 + KERB_SETBACK],
                road: 0,
                facing: [0.0, -1.0],
            },
        ];
        assert_eq!(lamps, expected);
        // A spacing that is no length seeds none.
        assert_eq!(map_lamps(&map, Some(&spacing(f64::NAN, 10.0))), expected);
        assert_eq!(map_lamps(&map, Some(&spacing(0.0, 10.0))), expected);
    }

    /// Road 10 runs east along z = 0 for 150 m, then 141 m north-east; 12 m wide with
    /// 3 m sidewalks. One-way road 11 (8 m, 2 m sidewalks) leaves it south at x = −50.
    /// Lamps are mapped at (−100, −8) and on road 10's centreline at x = −20.
    #[test]
    fn seeded_lamps_follow_the_papers_rule_along_the_polylines() {
        let map = crate::test_support::street_map();
        // Road 11's lamps stand 9 m apart across it: kept at 5 m.
        let lamps = map_lamps(&map, Some(&spacing(40.0, 5.0)));
        assert_eq!(&lamps[..2], &map_lamps(&map, None)[..]);
        let h = 6.0 + KERB_SETBACK;
        let r = std::f64::consts::FRAC_1_SQRT_2;
        // Candidates every 40 m from 20 m along road 10: x = −130, −90, −50, −10 on its
        // first segment, then 30, 70 and 110 m along the diagonal.
        let diagonal = |along: f64, side: f64| {
            let q = [along * r, -along * r];
            let out = [-r * side, -r * side];
            ([q[0] + out[0] * h, q[1] + out[1] * h], [-out[0], -out[1]])
        };
        let mut expected = vec![
            // Left (north): −90 and −10 lie within 20 m (half the spacing) of a mapped lamp.
            ([-130.0, -h], [0.0, 1.0]),
            ([-50.0, -h], [0.0, 1.0]),
        ];
        expected.extend([30.0, 70.0, 110.0].map(|a| diagonal(a, 1.0)));
        // Right (south): −90 and −10 near mapped lamps, −50 in road 11's carriageway.
        expected.push(([-130.0, h], [0.0, -1.0]));
        expected.extend([30.0, 70.0, 110.0].map(|a| diagonal(a, -1.0)));
        let seeded_10 = expected.len();
        // Road 11, running south: its left is east; 20 and 60 m along.
        let k = 4.0 + KERB_SETBACK;
        for x in [-50.0 + k, -50.0 - k] {
            for z in [20.0, 60.0] {
                expected.push(([x, z], [if x > -50.0 { -1.0 } else { 1.0 }, 0.0]));
            }
        }
        let seeded = &lamps[2..];
        assert_eq!(seeded.len(), expected.len(), "{seeded:?}");
        for (i, (lamp, (at, facing))) in seeded.iter().zip(&expected).enumerate() {
            assert_eq!(lamp.id as usize, i + 2);
            assert_eq!(lamp.road, if i < seeded_10 { 0 } else { 1 });
            assert!(distance(lamp.position, *at) < 1e-9, "{lamp:?} {at:?}");
            assert!(distance(lamp.facing, *facing) < 1e-9, "{lamp:?} {facing:?}");
        }
    }

    #[test]
    fn seeded_lamps_keep_their_distance_and_need_a_sidewalk() {
        let mut map = crate::test_support::street_map();
        let near = map_lamps(&map, Some(&spacing(40.0, 10.0)));
        // 13 m across road 10 at x = −130: kept at 10 m, one removed at 30 m (the first,
        // on the left, stays). 9 m across road 11: one removed at 10 m.
        let far = map_lamps(&map, Some(&spacing(40.0, 30.0)));
        let at = |lamps: &[Lamp], p: [f64; 2]| lamps.iter().any(|l| distance(l.position, p) < 1e-9);
        assert!(at(&near, [-130.0, 6.5]) && at(&near, [-130.0, -6.5]));
        assert!(at(&near, [-45.5, 20.0]) && !at(&near, [-54.5, 20.0]));
        assert!(at(&far, [-130.0, -6.5]) && !at(&far, [-130.0, 6.5]));
        for (i, a) in far.iter().enumerate().skip(2) {
            for b in &far[2..i] {
                assert!(distance(a.position, b.position) >= 30.0, "{a:?} {b:?}");
            }
        }
        // Without a metre of sidewalk on its left, road 11 has lamps on its right only.
        for f in &mut map.roads[1].fitted {
            f[1] = 0.9;
        }
        let lamps = map_lamps(&map, Some(&spacing(40.0, 10.0)));
        let on_11: Vec<[f64; 2]> = (lamps.iter().filter(|l| l.road == 1))
            .map(|l| l.position)
            .collect();
        assert_eq!(on_11, vec![[-54.5, 20.0], [-54.5, 60.0]]);
    }

    /// A street mapped as two ways meeting head to head, a side road leaving it square and
    /// a road going on at 45°: the two ways are one street, turned the first's way, its
    /// candidates counted on through the node; the others are streets of their own.
    #[test]
    fn a_street_split_into_ways_is_one_street() {
        let segment = |road, a, b, sidewalks| PavedSegment {
            road,
            a,
            b,
            width: 12.0,
            sidewalks,
        };
        let paved = [
            segment(0, [-150.0, 0.0], [-50.0, 0.0], [3.0, 0.5]),
            segment(1, [0.0, 0.0], [-50.0, 0.0], [0.5, 3.0]),
            segment(2, [-50.0, 0.0], [-50.0, 100.0], [3.0, 3.0]),
            segment(3, [0.0, 0.0], [100.0, -100.0], [3.0, 3.0]),
        ];
        let streets = streets(&paved);
        let roads: Vec<Vec<usize>> = (streets.iter())
            .map(|s| s.iter().map(|p| p.road).collect())
            .collect();
        assert_eq!(roads, vec![vec![0, 1], vec![2], vec![3]]);
        assert_eq!(streets[0][1].a, [-50.0, 0.0]);
        assert_eq!(streets[0][1].sidewalks, [3.0, 0.5]);
        // Every 40 m from 20 m along the 150 m street, its left (north) side only: the
        // right has half a metre of sidewalk.
        let h = 6.0 + KERB_SETBACK;
        let first: Vec<([f64; 2], u32)> = candidates(&paved, 40.0)
            .iter()
            .take_while(|l| l.road <= 1)
            .map(|l| (l.position, l.road))
            .collect();
        assert_eq!(
            first,
            vec![
                ([-130.0, -h], 0),
                ([-90.0, -h], 0),
                ([-50.0, -h], 1),
                ([-10.0, -h], 1),
            ]
        );
    }
}
