//! A map's ground as places for what stands on it: vehicles on its paved segments
//! ([`RoadSpots`]) and people and parked bicycles on its sidewalks ([`StripSpots`]),
//! clear of the lamps, the trees and everything placed before.
//!
//! A sidewalk spot lies on one side of a paved segment (drawn by the sidewalk's length),
//! the distance from the kerb its entry asks for that sidewalk's width: the spot's centre
//! on the sidewalk, no carriageway nearer to it than its own kerb (so not where the
//! sidewalk meets a junction or a road ending on it), out of the buildings by the
//! object's radius and inside the map's box. Its `travel` is the traffic's in the lane
//! next to it: the way's on a one-way road, else the way with the sidewalk on its right.
//! A map places no one on its zebras yet (the spec refuses `crossing` and `waiting` on
//! a map), and its traffic does not move, so its walkers are not marked.

use rand::RngExt;
use rand_pcg::Pcg64;

use super::footprint_grid::FootprintGrid;
use super::ground_spots::{
    CrossingSpot, Footprint, GRID_CELL, LAMP_CLEARANCE, RoadSlot, RoadSpots, Spot, StripSpots,
};
use super::tree;
use crate::model::geometry::polygon::{direction, distance, left_normal, nearest};
use crate::model::{FeatureKind, Lamp, MAP_CAMERA_LANE, OsmMap, PavedSegment, map_camera_lane};

/// Metres a car keeps, beyond its half length, from every other road's carriageway: the
/// mouth of a junction stays clear.
pub const JUNCTION_CLEARANCE: f64 = 3.0;
/// Ground a mapped crossing or signal keeps free of cars, radius in metres.
const CROSSING_ROOM: f64 = 4.0;
/// The narrowest vehicle's width, metres (a small car's).
const NARROWEST: f64 = 1.6;
/// The narrowest sidewalk anyone stands on, metres (as the sidewalks camera's).
const MIN_SIDEWALK: f64 = 1.5;

/// One side of a paved segment with a sidewalk: the way along it with the block on the
/// right (`a → b` for the right sidewalk, `b → a` for the left).
#[derive(Clone, Copy, Debug)]
struct Sidewalk {
    /// Index in [`MapSpots::all`].
    segment: usize,
    from: [f64; 2],
    to: [f64; 2],
    width: f64,
}

/// The map's paved segments and sidewalks as places for vehicles, people and bicycles.
pub struct MapSpots<'a> {
    map: &'a OsmMap,
    /// Every paved segment (the roads a vehicle keeps clear of).
    all: Vec<PavedSegment>,
    /// The segments a vehicle may stand on.
    segments: Vec<PavedSegment>,
    /// Arc length at each segment's end, segments end to end.
    ends: Vec<f64>,
    /// Whether each segment's road is one-way (driven `a → b` only).
    oneway: Vec<bool>,
    /// What stands: lamps, trees and what entries placed.
    taken: FootprintGrid,
    /// The ground around mapped crossings and signals, kept free of vehicles only (a
    /// signal's own poles stand in it).
    rooms: FootprintGrid,
    /// Every sidewalk at least [`MIN_SIDEWALK`] wide, in segment order (right, left).
    sidewalks: Vec<Sidewalk>,
    /// Arc length at each sidewalk's end, sidewalks end to end.
    sidewalk_ends: Vec<f64>,
}

impl<'a> MapSpots<'a> {
    /// The map's ground with the lamps and the trees (position, crown radius) standing.
    pub fn new(map: &'a OsmMap, lamps: &[Lamp], trees: &[([f64; 2], f64)]) -> MapSpots<'a> {
        // Only segments where the narrowest vehicle can stand clear of the cameras' lane
        // (see `near_side`): on a two-way road's far half, on a one-way road's right.
        let all: Vec<PavedSegment> = map.paved_segments().collect();
        let segments: Vec<PavedSegment> = all
            .iter()
            .copied()
            .filter(|s| {
                let near = if map.roads[s.road].oneway {
                    map_camera_lane(s.width) + MAP_CAMERA_LANE
                } else {
                    0.0
                };
                s.width / 2.0 >= near + NARROWEST
            })
            .collect();
        let ends = segments
            .iter()
            .scan(0.0, |at, s| {
                *at += distance(s.a, s.b);
                Some(*at)
            })
            .collect();
        let oneway = segments.iter().map(|s| map.roads[s.road].oneway).collect();
        let mut taken = FootprintGrid::new(GRID_CELL);
        for l in lamps {
            taken.push(Footprint::Circle(l.position, LAMP_CLEARANCE));
        }
        for (at, _) in trees {
            taken.push(Footprint::Circle(*at, tree::TRUNK_ROOM));
        }
        let mut rooms = FootprintGrid::new(GRID_CELL);
        let kept = [FeatureKind::Crossing, FeatureKind::TrafficSignals];
        for f in map.features.iter().filter(|f| kept.contains(&f.kind)) {
            rooms.push(Footprint::Circle(f.at, CROSSING_ROOM));
        }
        let sidewalks: Vec<Sidewalk> = (all.iter().enumerate())
            .flat_map(|(segment, s)| {
                [(1, s.a, s.b), (0, s.b, s.a)].map(|(side, from, to)| Sidewalk {
                    segment,
                    from,
                    to,
                    width: s.sidewalks[side],
                })
            })
            .filter(|w| w.width >= MIN_SIDEWALK && direction(w.from, w.to).is_some())
            .collect();
        let sidewalk_ends = sidewalks
            .iter()
            .scan(0.0, |at, w| {
                *at += distance(w.from, w.to);
                Some(*at)
            })
            .collect();
        MapSpots {
            map,
            sidewalks,
            sidewalk_ends,
            all,
            segments,
            ends,
            oneway,
            taken,
            rooms,
        }
    }

    /// Takes `footprint` when it is clear of everything taken; whether it was.
    pub fn claim(&mut self, footprint: Footprint) -> bool {
        if self.taken.overlaps(&footprint) {
            return false;
        }
        self.taken.push(footprint);
        true
    }

    /// How far right of segment `k`'s centreline a vehicle driving along it (`forward`:
    /// from `a` to `b`) keeps its near side, so that it stays [`MAP_CAMERA_LANE`] clear
    /// of the cameras' lane: cameras drive `a → b` only, on a one-way road in the lane
    /// [`map_camera_lane`] gives, and [`MAP_CAMERA_LANE`] right of a two-way road's (so on its far side, a vehicle
    /// driving the other way needs only to keep to its own half).
    fn near_side(&self, k: usize, forward: bool) -> f64 {
        let camera = if self.oneway[k] {
            map_camera_lane(self.segments[k].width)
        } else {
            MAP_CAMERA_LANE
        };
        if forward {
            camera + MAP_CAMERA_LANE
        } else {
            MAP_CAMERA_LANE - camera
        }
    }

    /// Whether a footprint centred at `p` with half length `half` is clear of every road
    /// but `road`.
    fn clear_of_other_roads(&self, road: usize, p: [f64; 2], half: f64) -> bool {
        self.all
            .iter()
            .filter(|s| s.road != road)
            .all(|s| distance(p, nearest(s.a, s.b, p)) > s.width / 2.0 + half + JUNCTION_CLEARANCE)
    }

    /// The circles covering a `half`-sized box at `p` along `dir`, grown by `grow` along it.
    fn circles(p: [f64; 2], dir: [f64; 2], half: [f64; 2], grow: f64) -> Vec<Footprint> {
        let r = half[1];
        let reach = (half[0] + grow - r).max(0.0);
        let n = (reach / r).ceil() as usize;
        (0..=2 * n)
            .map(|k| {
                let t = if n == 0 {
                    0.0
                } else {
                    -reach + reach * k as f64 / n as f64
                };
                Footprint::Circle([p[0] + dir[0] * t, p[1] + dir[1] * t], r)
            })
            .collect()
    }
}

impl RoadSpots for MapSpots<'_> {
    /// A paved segment drawn by length, a direction (one-way roads: theirs; else either),
    /// and a place along it where `slot` fits wholly on the segment.
    fn road(
        &mut self,
        rng: &mut Pcg64,
        attempts: u32,
        slot: impl Fn(f64) -> Option<RoadSlot>,
    ) -> Option<Spot> {
        let total = *self.ends.last()?;
        (0..attempts).find_map(|_| {
            let at = rng.random::<f64>() * total;
            let k = self
                .ends
                .partition_point(|&e| e <= at)
                .min(self.ends.len() - 1);
            let forward = self.oneway[k] || rng.random::<bool>();
            let along: f64 = rng.random();
            let s = self.segments[k];
            let r = slot(s.width)?;
            if r.offset - r.half[1] < self.near_side(k, forward) {
                return None;
            }
            let (a, b) = if forward { (s.a, s.b) } else { (s.b, s.a) };
            let len = distance(a, b);
            let room = len - 2.0 * r.half[0];
            let n = left_normal(a, b)?;
            if room <= 0.0 {
                return None;
            }
            let dir = [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
            let t = r.half[0] + along * room;
            // Right of the direction of travel: the left normal turned round.
            let p = [
                a[0] + dir[0] * t - n[0] * r.offset,
                a[1] + dir[1] * t - n[1] * r.offset,
            ];
            if !self.clear_of_other_roads(s.road, p, r.half[0]) {
                return None;
            }
            let probe = Self::circles(p, dir, r.half, r.gap);
            if probe
                .iter()
                .any(|c| self.taken.overlaps(c) || self.rooms.overlaps(c))
            {
                return None;
            }
            for c in Self::circles(p, dir, r.half, 0.0) {
                self.taken.push(c);
            }
            Some(Spot {
                position: p,
                travel: dir,
                road: s.road as u32,
            })
        })
    }
}

impl StripSpots for MapSpots<'_> {
    /// A sidewalk drawn by length, a place along it, `from_curb` of its width from the
    /// kerb: see the module's note.
    fn strip_at(
        &mut self,
        rng: &mut Pcg64,
        radius: f64,
        from_curb: impl Fn(f64) -> f64,
        attempts: u32,
    ) -> Option<Spot> {
        let total = *self.sidewalk_ends.last()?;
        (0..attempts).find_map(|_| {
            let at = rng.random::<f64>() * total;
            let k = (self.sidewalk_ends.partition_point(|&e| e <= at))
                .min(self.sidewalk_ends.len() - 1);
            let along: f64 = rng.random();
            let w = self.sidewalks[k];
            let s = self.all[w.segment];
            let from = from_curb(w.width);
            let dir = direction(w.from, w.to)?;
            if !(from >= 0.0 && from < w.width) {
                return None;
            }
            let (t, out) = (along * distance(w.from, w.to), s.width / 2.0 + from);
            let p = [
                w.from[0] + dir[0] * t - dir[1] * out,
                w.from[1] + dir[1] * t + dir[0] * out,
            ];
            let foot = Footprint::Circle(p, radius);
            let [x0, z0, x1, z1] = self.map.extent;
            let inside = p[0] - radius > x0
                && p[0] + radius < x1
                && p[1] - radius > z0
                && p[1] + radius < z1;
            if !inside
                || self.taken.overlaps(&foot)
                || (self.all.iter())
                    .any(|o| distance(p, nearest(o.a, o.b, p)) < o.width / 2.0 + from - 1e-9)
                || self.map.in_building(p)
                || self.map.building_distance(p) < radius
            {
                return None;
            }
            self.taken.push(foot);
            let oneway = self.map.roads[s.road].oneway;
            Some(Spot {
                position: p,
                travel: if oneway { direction(s.a, s.b)? } else { dir },
                road: s.road as u32,
            })
        })
    }

    /// None: a map places no one on its zebras yet.
    fn zebra(&mut self, _: &mut Pcg64, _: f64, _: f64, _: f64, _: u32) -> Option<CrossingSpot> {
        None
    }

    /// None: a map places no one at its zebras yet.
    fn zebra_kerb(&mut self, _: &mut Pcg64, _: f64, _: f64, _: u32) -> Option<CrossingSpot> {
        None
    }

    /// Nothing: a map's traffic does not move, so no one walks on.
    fn mark_walker(&mut self) {}
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::street_map;

    /// The distance from `p` to the nearest carriageway's edge (negative inside one) and
    /// that segment.
    fn kerb_distance(map: &OsmMap, p: [f64; 2]) -> (f64, PavedSegment) {
        map.paved_segments()
            .map(|s| (distance(p, nearest(s.a, s.b, p)) - s.width / 2.0, s))
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .expect("a paved segment")
    }

    /// `n` spots `from` metres from the kerb (at most `most` of the sidewalk's width) for
    /// a radius of `radius`, from seed 7.
    fn spots(map: &OsmMap, n: usize, radius: f64, from: f64) -> Vec<Spot> {
        let mut ground = MapSpots::new(map, &[], &[]);
        let mut rng = crate::rng::stream(7, "test", 0);
        (0..n)
            .filter_map(|_| ground.strip_at(&mut rng, radius, |_| from, 40))
            .collect()
    }

    #[test]
    fn sidewalk_spots_lie_on_a_sidewalk_off_the_carriageways_and_apart() {
        let mut map = street_map();
        // A building reaching onto road 0's south sidewalk (z 6…9) across the line 1 m
        // from its kerb: x −120…−100, z 6.5…28.
        map.buildings[0].outer = vec![[-120.0, 6.5], [-100.0, 6.5], [-100.0, 28.0], [-120.0, 28.0]];
        let radius = 0.6;
        let got = spots(&map, 300, radius, 1.0);
        assert!(got.len() >= 250, "{} spots", got.len());
        assert_eq!(got, spots(&map, 300, radius, 1.0), "deterministic");
        for (i, spot) in got.iter().enumerate() {
            let p = spot.position;
            let (d, s) = kerb_distance(&map, p);
            // Its own kerb is the nearest, 1 m off; the sidewalk (3 m or 2 m) holds it.
            assert!((d - 1.0).abs() < 1e-6, "{p:?} is {d} m from a kerb");
            assert!(
                d < s.sidewalks[0].max(s.sidewalks[1]),
                "{p:?} past its sidewalk"
            );
            assert!(
                !map.in_building(p) && map.building_distance(p) >= radius,
                "{p:?}"
            );
            let [x0, z0, x1, z1] = map.extent;
            assert!(
                p[0] - radius > x0
                    && p[0] + radius < x1
                    && p[1] - radius > z0
                    && p[1] + radius < z1
            );
            for q in &got[i + 1..] {
                assert!(
                    distance(p, q.position) >= 2.0 * radius - 1e-9,
                    "{p:?} {q:?}"
                );
            }
            // Along its road: on the one-way road the way's direction, else the way with
            // the sidewalk on the right.
            let t = direction(s.a, s.b).expect("a segment");
            let along = t[0] * spot.travel[0] + t[1] * spot.travel[1];
            assert!((along.abs() - 1.0).abs() < 1e-9, "{spot:?}");
            let right = (p[0] - s.a[0]) * -t[1] + (p[1] - s.a[1]) * t[0] > 0.0;
            let oneway = map.roads[s.road].oneway;
            assert_eq!(along > 0.0, oneway || right, "{spot:?}");
        }
        // Both sides of both roads.
        for road in [0, 1] {
            for right in [false, true] {
                assert!(
                    got.iter().any(|g| {
                        let (_, s) = kerb_distance(&map, g.position);
                        let t = direction(s.a, s.b).expect("a segment");
                        let p = g.position;
                        s.road == road
                            && ((p[0] - s.a[0]) * -t[1] + (p[1] - s.a[1]) * t[0] > 0.0) == right
                    }),
                    "none on road {road}'s {} side",
                    if right { "right" } else { "left" }
                );
            }
        }
    }

    #[test]
    fn sidewalk_spots_keep_off_lamps_trees_and_what_stands() {
        let map = street_map();
        let lamps: Vec<Lamp> = [[-100.0, 7.5], [-80.0, -7.5]]
            .map(|position| Lamp {
                id: 0,
                position,
                road: 0,
                facing: [0.0, 1.0],
            })
            .to_vec();
        let trees = [([-90.0, 7.5], 3.0)];
        let mut ground = MapSpots::new(&map, &lamps, &trees);
        assert!(ground.claim(Footprint::Circle([-70.0, 7.5], 1.0)));
        let mut rng = crate::rng::stream(7, "test", 1);
        let got: Vec<Spot> = (0..200)
            .filter_map(|_| ground.strip_at(&mut rng, 0.5, |w| w / 2.0, 40))
            .collect();
        assert!(got.len() >= 100, "{} spots", got.len());
        for spot in &got {
            let p = spot.position;
            for l in &lamps {
                assert!(
                    distance(p, l.position) >= LAMP_CLEARANCE + 0.5 - 1e-9,
                    "{p:?}"
                );
            }
            assert!(
                distance(p, trees[0].0) >= tree::TRUNK_ROOM + 0.5 - 1e-9,
                "{p:?}"
            );
            assert!(distance(p, [-70.0, 7.5]) >= 1.5 - 1e-9, "{p:?}");
        }
    }

    #[test]
    fn no_sidewalk_spot_past_the_sidewalk_or_without_one() {
        // 4 m from the kerb is past both roads' sidewalks (3 m and 2 m).
        assert!(spots(&street_map(), 20, 0.5, 4.0).is_empty());
        let mut map = street_map();
        for road in &mut map.roads {
            road.fitted
                .iter_mut()
                .for_each(|f| [f[1], f[2]] = [1.0, 1.0]);
        }
        assert!(
            spots(&map, 20, 0.5, 0.5).is_empty(),
            "sidewalks under 1.5 m"
        );
    }
}
