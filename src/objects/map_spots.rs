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
//! People cross on the zebras the markings draw (`MapLines::zebras`) and wait at their
//! ends, as on a layout's zebras, clear of the roads cameras' lane, and stand or walk on
//! the paths across its parks and on its squares (`OsmMap::paths`, `OsmMap::squares`:
//! [`StripSpots::park`], [`StripSpots::square`]). A map's traffic does not move, so its
//! walkers are not marked.

use rand::RngExt;
use rand_pcg::Pcg64;

use super::car::CAMERA_CLEARANCE;
use super::footprint_grid::FootprintGrid;
use super::ground_spots::{
    CrossingSpot, Footprint, GRID_CELL, LAMP_CLEARANCE, RoadSlot, RoadSpots, Spot, StripSpots,
};
use super::open_ground::OpenGround;
use super::tree;
use crate::model::geometry::cos_sin_deg;
use crate::model::geometry::map_lines::MapLines;
use crate::model::geometry::polygon::{direction, distance, left_normal, nearest, ring_distance};
use crate::model::geometry::zebras::ZEBRA_DEPTH;
use crate::model::{
    Crossing, FeatureKind, Lamp, MAP_CAMERA_LANE, NARROWEST_VEHICLE, OsmMap, PavedSegment,
    driven_back, map_camera_lane,
};

/// Metres a car keeps, beyond its half length, from every other road's carriageway: the
/// mouth of a junction stays clear.
pub const JUNCTION_CLEARANCE: f64 = 3.0;
/// Ground a mapped crossing or signal keeps free of cars, radius in metres.
const CROSSING_ROOM: f64 = 4.0;
/// The narrowest vehicle's width, metres (a small car's).
const NARROWEST: f64 = NARROWEST_VEHICLE;
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

/// A zebra the map's markings draw (`MapLines::zebras`), as a place for people.
#[derive(Clone, Copy, Debug)]
struct MapZebra {
    road: usize,
    /// Its middle on the centreline, and the unit direction of the road there.
    centre: [f64; 2],
    along: [f64; 2],
    /// Carriageway width, and sidewalk widths left and right of `along`, metres.
    width: f64,
    sidewalks: [f64; 2],
    /// Its range along the road, arc length in metres.
    range: [f64; 2],
    /// The roads cameras' lane, metres right of `along` (see `MapSpots::near_side`).
    camera: f64,
    /// Whether the cameras drive the road back as well, `camera` left of `along`.
    driven_back: bool,
}

impl MapZebra {
    /// The point `along` metres along the road from its middle and `across` right of it.
    fn at(&self, along: f64, across: f64) -> [f64; 2] {
        let (t, n) = (self.along, [-self.along[1], self.along[0]]);
        [
            self.centre[0] + t[0] * along + n[0] * across,
            self.centre[1] + t[1] * along + n[1] * across,
        ]
    }

    /// The unit direction across the road towards its side `sign` (1: right of `along`).
    fn across(&self, sign: f64) -> [f64; 2] {
        [-self.along[1] * sign, self.along[0] * sign]
    }

    /// The spot of a person `along` the zebra from its middle, crossing from `way[0]` to
    /// `way[1]` (metres right of the road), waiting or on its way.
    fn spot(&self, along: f64, way: [f64; 2], waiting: bool) -> CrossingSpot {
        CrossingSpot {
            spot: Spot {
                position: self.at(along, way[0]),
                travel: self.across((way[1] - way[0]).signum()),
                road: self.road as u32,
            },
            crossing: Crossing {
                zebra: self.range,
                waiting,
            },
            reach: (way[1] - way[0]).abs(),
        }
    }

    /// Where along the zebra (from its middle) a person of `radius` crossing towards side
    /// `sign` walks: in the half on its right (back along the road when it crosses to
    /// the right), at `u` (0 to 1) of the room there. None when the half is too narrow.
    fn keep_right(&self, sign: f64, radius: f64, u: f64) -> Option<f64> {
        let room = ZEBRA_DEPTH / 2.0 - 2.0 * radius;
        (room >= 0.0 && u.is_finite()).then(|| -sign * (radius + u * room))
    }
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
    /// The zebras the markings draw.
    zebras: Vec<MapZebra>,
    /// The paths across the parks (`OsmMap::paths`).
    paths: OpenGround,
    /// The squares (`OsmMap::squares`).
    squares: OpenGround,
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
            zebras: map_zebras(map),
            paths: OpenGround::of(&map.paths),
            squares: OpenGround::of(&map.squares),
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

    /// Whether a person of `radius` at `p` stands on ground off the carriageways of every
    /// road but `road`, out of the buildings by its radius and inside the box.
    fn off_other_roads(&self, road: usize, p: [f64; 2], radius: f64) -> bool {
        self.map.holds(p, radius) && self.map.clear_ground(&self.all, Some(road), p, radius)
    }

    /// Takes the way across zebra `z` at `along` from `across[0]` to `across[1]` (metres
    /// right of its road) for a person of `radius`, when its far end is on a sidewalk wide
    /// enough and nothing taken stands in the way; whether it did.
    fn crossing_way(&mut self, z: &MapZebra, along: f64, across: [f64; 2], radius: f64) -> bool {
        let sign = (across[1] - across[0]).signum();
        let side = usize::from(sign > 0.0);
        let from_curb = across[1].abs() - z.width / 2.0;
        if z.sidewalks[side] < from_curb + radius
            || !self.off_other_roads(z.road, z.at(along, across[1]), radius)
        {
            return false;
        }
        let steps = ((across[1] - across[0]).abs() / radius).ceil().max(1.0) as usize;
        let way: Vec<Footprint> = (0..=steps)
            .map(|k| {
                let c = across[0] + (across[1] - across[0]) * k as f64 / steps as f64;
                Footprint::Circle(z.at(along, c), radius)
            })
            .collect();
        if way.iter().any(|f| self.taken.overlaps(f)) {
            return false;
        }
        way.into_iter().for_each(|f| self.taken.push(f));
        true
    }

    /// Takes `footprint` when it is clear of everything taken; whether it was.
    pub fn claim(&mut self, footprint: Footprint) -> bool {
        if self.taken.overlaps(&footprint) {
            return false;
        }
        self.taken.push(footprint);
        true
    }

    /// A spot on the paths across the parks (`squares`: on the squares), drawn by area
    /// ([`OpenGround`]), whose centre lies `radius` inside its area's edges, out of the
    /// buildings, inside the box and clear of what stands; its `road` is the nearest
    /// carriageway's. Its `travel` on a path runs along the path's nearest edge; on a
    /// square it is drawn.
    fn open(&mut self, rng: &mut Pcg64, radius: f64, attempts: u32, squares: bool) -> Option<Spot> {
        (0..attempts).find_map(|_| {
            let ground = if squares { &self.squares } else { &self.paths };
            let (p, i) = ground.draw(rng)?;
            let areas = if squares {
                &self.map.squares
            } else {
                &self.map.paths
            };
            let shape = &areas[i].shape;
            let rings = || std::iter::once(&shape.outer).chain(&shape.holes);
            let foot = Footprint::Circle(p, radius);
            if rings().any(|r| ring_distance(r, p) < radius)
                || !(self.map.holds(p, radius) && self.map.out_of_buildings(p, radius))
                || self.taken.overlaps(&foot)
            {
                return None;
            }
            let travel = if squares {
                let (c, s) = cos_sin_deg(rng.random::<f64>() * 360.0);
                [c, s]
            } else {
                rings()
                    .flat_map(|r| (0..r.len()).map(|e| (r[e], r[(e + 1) % r.len()])))
                    .filter_map(|(a, b)| Some((distance(p, nearest(a, b, p)), direction(a, b)?)))
                    .min_by(|x, y| x.0.total_cmp(&y.0))?
                    .1
            };
            let road = (self.map.nearest_kerb(p)).map_or(u32::MAX, |(_, s)| s.road as u32);
            self.taken.push(foot);
            Some(Spot {
                position: p,
                travel,
                road,
            })
        })
    }

    /// How far right of segment `k`'s centreline a vehicle driving along it (`forward`:
    /// from `a` to `b`) keeps its near side, so that it stays [`MAP_CAMERA_LANE`] clear
    /// of the cameras' lanes: cameras drive `a → b` on a one-way road in the lane
    /// [`map_camera_lane`] gives, and [`MAP_CAMERA_LANE`] right of a two-way road's; they
    /// drive back [`MAP_CAMERA_LANE`] left of it where the road is [`driven_back`] (else
    /// on its far side a vehicle driving the other way needs only to keep to its own
    /// half).
    fn near_side(&self, k: usize, forward: bool) -> f64 {
        let s = &self.segments[k];
        let camera = if self.oneway[k] {
            map_camera_lane(s.width)
        } else {
            MAP_CAMERA_LANE
        };
        if forward || driven_back(s.width, self.oneway[k]) {
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
            // Parked at the kerb on the right of its way: the way's right going forward,
            // its left going back. Not where the map forbids it.
            let kerb = usize::from(forward);
            if r.parked && self.map.roads[s.road].parking[kerb] == Some(false) {
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
            if !(self.map.holds(p, radius) && self.map.out_of_buildings(p, radius))
                || self.taken.overlaps(&foot)
                || (self.all.iter())
                    .any(|o| distance(p, nearest(o.a, o.b, p)) < o.width / 2.0 + from - 1e-9)
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

    /// A zebra the markings draw (uniform among them) and a place on it: in the half on
    /// the person's right, at most `reach` either side of the centreline (on a road the
    /// cameras drive both ways, anywhere) and `radius` inside the kerbs, [`CAMERA_CLEARANCE`]
    /// plus `radius` clear of the roads cameras' lanes, crossing either way to `beyond`
    /// past the far kerb (on a sidewalk that wide); the whole way there is taken.
    fn zebra(
        &mut self,
        rng: &mut Pcg64,
        radius: f64,
        reach: f64,
        beyond: f64,
        attempts: u32,
    ) -> Option<CrossingSpot> {
        if self.zebras.is_empty() {
            return None;
        }
        (0..attempts).find_map(|_| {
            let z = self.zebras[rng.random_range(0..self.zebras.len())];
            // `reach` keeps the way's lane clear; on a road driven both ways the lanes
            // are tested below, and a person crosses anywhere outside them.
            let reach = if z.driven_back { f64::INFINITY } else { reach };
            let limit = reach.min(z.width / 2.0 - radius);
            let across = (2.0 * rng.random::<f64>() - 1.0) * limit;
            let sign = if rng.random::<bool>() { -1.0 } else { 1.0 };
            let along = z.keep_right(sign, radius, rng.random())?;
            let far = sign * (z.width / 2.0 + beyond);
            let off_lane = |lane: f64| (across - lane).abs() >= radius + CAMERA_CLEARANCE;
            let clear =
                limit >= 0.0 && off_lane(z.camera) && (!z.driven_back || off_lane(-z.camera));
            if !clear || !self.crossing_way(&z, along, [across, far], radius) {
                return None;
            }
            Some(z.spot(along, [across, far], false))
        })
    }

    /// A zebra and a place on the sidewalk at one of its ends, `from_curb` from the kerb,
    /// for a person waiting to cross (its `travel` across the road): in the half of the
    /// zebra on its right as it crosses, its end on a sidewalk that wide and its way over
    /// to the same distance past the far kerb taken.
    fn zebra_kerb(
        &mut self,
        rng: &mut Pcg64,
        radius: f64,
        from_curb: f64,
        attempts: u32,
    ) -> Option<CrossingSpot> {
        if self.zebras.is_empty() {
            return None;
        }
        (0..attempts).find_map(|_| {
            let z = self.zebras[rng.random_range(0..self.zebras.len())];
            // It crosses towards the other side.
            let sign = if rng.random::<bool>() { -1.0 } else { 1.0 };
            let along = z.keep_right(sign, radius, rng.random())?;
            let out = z.width / 2.0 + from_curb;
            let (start, far) = (-sign * out, sign * out);
            let own = usize::from(sign < 0.0);
            if z.sidewalks[own] < from_curb + radius
                || !self.off_other_roads(z.road, z.at(along, start), radius)
                || !self.crossing_way(&z, along, [start, far], radius)
            {
                return None;
            }
            Some(z.spot(along, [start, far], true))
        })
    }

    /// A path across a park ([`MapSpots::open`]), the spot's `travel` along the path's
    /// nearest edge (a path is a stroke: its long edges run along it).
    fn park(&mut self, rng: &mut Pcg64, radius: f64, attempts: u32) -> Option<Spot> {
        self.open(rng, radius, attempts, false)
    }

    /// A square ([`MapSpots::open`]), the spot's `travel` any way.
    fn square(&mut self, rng: &mut Pcg64, radius: f64, attempts: u32) -> Option<Spot> {
        self.open(rng, radius, attempts, true)
    }

    /// Nothing: a map's traffic does not move, so no one walks on.
    fn mark_walker(&mut self) {}
}

/// The zebras `scene::map_markings` draws (`MapLines::zebras`), as places for people.
fn map_zebras(map: &OsmMap) -> Vec<MapZebra> {
    let lines = MapLines::of(map);
    (lines.zebras.iter())
        .filter_map(|z| {
            let line = lines.line(z.road)?;
            let s = z.segment;
            let (a, b) = (line.points()[s], line.points()[s + 1]);
            let along = direction(a, b)?;
            let t = z.at - line.at[s];
            let fitted = line.map_road.fitted.get(s)?;
            let width = fitted[0];
            Some(MapZebra {
                road: z.road,
                centre: [a[0] + along[0] * t, a[1] + along[1] * t],
                along,
                width,
                sidewalks: [fitted[1], fitted[2]],
                range: [z.at - ZEBRA_DEPTH / 2.0, z.at + ZEBRA_DEPTH / 2.0],
                camera: if line.map_road.oneway {
                    map_camera_lane(width)
                } else {
                    MAP_CAMERA_LANE
                },
                driven_back: driven_back(width, line.map_road.oneway),
            })
        })
        .collect()
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::test_support::street_map;

    /// The distance from `p` to the nearest carriageway's edge (negative inside one) and
    /// that segment.
    fn kerb_distance(map: &OsmMap, p: [f64; 2]) -> (f64, PavedSegment) {
        map.nearest_kerb(p).expect("a paved segment")
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

    /// An L-shaped path 2 m wide: west to east along z 29 … 31 from x −145 (through the
    /// building at x −120 … −100), then north along x −62 … −60 up to z 60.
    pub(crate) fn l_path() -> crate::model::MapArea {
        let outer = vec![
            [-145.0, 29.0],
            [-60.0, 29.0],
            [-60.0, 60.0],
            [-62.0, 60.0],
            [-62.0, 31.0],
            [-145.0, 31.0],
        ];
        crate::model::MapArea {
            block: 0,
            shape: crate::model::MapPolygon {
                outer,
                holes: Vec::new(),
                area: 85.0 * 2.0 + 29.0 * 2.0,
            },
        }
    }

    #[test]
    fn park_spots_lie_on_the_paths_out_of_buildings_facing_along_them() {
        let mut map = street_map();
        let mut rng = crate::rng::stream(7, "test", 0);
        assert!(
            MapSpots::new(&map, &[], &[])
                .park(&mut rng, 0.6, 40)
                .is_none()
        );
        map.paths = vec![l_path()];
        let mut ground = MapSpots::new(&map, &[], &[]);
        let found: Vec<Spot> = (0..80)
            .filter_map(|_| ground.park(&mut rng, 0.6, 40))
            .collect();
        // The 0.8 m wide middles of the arms hold about 70 such circles, randomly fewer.
        assert!(found.len() >= 40, "{}", found.len());
        let (mut west, mut north) = (0, 0);
        for (i, s) in found.iter().enumerate() {
            let p = s.position;
            let edge = ring_distance(&map.paths[0].shape.outer, p);
            assert!(crate::model::geometry::polygon::contains(
                &map.paths[0].shape.outer,
                p
            ));
            assert!(edge >= 0.6 - 1e-9, "{p:?} {edge} m inside the path");
            assert!(map.out_of_buildings(p, 0.6), "{p:?}");
            for t in &found[i + 1..] {
                assert!(distance(p, t.position) >= 1.2 - 1e-9, "{p:?} {t:?}");
            }
            assert_eq!(s.road as usize, kerb_distance(&map, p).1.road, "{s:?}");
            // Away from the corner, along the arm it stands on.
            if p[0] < -64.0 {
                assert_eq!(s.travel[1], 0.0, "{s:?}");
                west += 1;
            } else if p[1] > 33.0 {
                assert_eq!(s.travel[0], 0.0, "{s:?}");
                north += 1;
            }
        }
        assert!(west > 10 && north > 10, "{west} west, {north} north");
    }

    /// A 30 × 20 m square south of the footway (x −95 … −65, z 45 … 65; west of
    /// [`l_path`]) around a 10 × 10 m fountain basin (x −85 … −75, z 50 … 60).
    pub(crate) fn square_with_a_basin() -> crate::model::MapArea {
        crate::model::MapArea {
            block: 0,
            shape: crate::model::MapPolygon {
                outer: vec![[-95.0, 45.0], [-65.0, 45.0], [-65.0, 65.0], [-95.0, 65.0]],
                holes: vec![vec![
                    [-85.0, 50.0],
                    [-85.0, 60.0],
                    [-75.0, 60.0],
                    [-75.0, 50.0],
                ]],
                area: 600.0 - 100.0,
            },
        }
    }

    #[test]
    fn square_spots_lie_on_the_square_off_its_holes_facing_any_way() {
        use crate::model::geometry::polygon::contains;
        let mut map = street_map();
        let mut rng = crate::rng::stream(7, "test", 0);
        assert!(
            MapSpots::new(&map, &[], &[])
                .square(&mut rng, 0.6, 40)
                .is_none()
        );
        map.squares = vec![square_with_a_basin()];
        // No paths: none on them.
        let mut ground = MapSpots::new(&map, &[], &[]);
        assert!(ground.park(&mut rng, 0.6, 40).is_none());
        let found: Vec<Spot> = (0..100)
            .filter_map(|_| ground.square(&mut rng, 0.6, 40))
            .collect();
        assert_eq!(found.len(), 100);
        let shape = &map.squares[0].shape;
        let mut quarters = [0; 4];
        for (i, s) in found.iter().enumerate() {
            let p = s.position;
            assert!(
                contains(&shape.outer, p) && !contains(&shape.holes[0], p),
                "{p:?}"
            );
            assert!(ring_distance(&shape.outer, p) >= 0.6 - 1e-9, "{p:?}");
            assert!(ring_distance(&shape.holes[0], p) >= 0.6 - 1e-9, "{p:?}");
            for t in &found[i + 1..] {
                assert!(distance(p, t.position) >= 1.2 - 1e-9, "{p:?} {t:?}");
            }
            assert!((s.travel[0] * s.travel[0] + s.travel[1] * s.travel[1] - 1.0).abs() < 1e-9);
            let q = usize::from(s.travel[0] < 0.0) + 2 * usize::from(s.travel[1] < 0.0);
            quarters[q] += 1;
        }
        assert!(quarters.iter().all(|&q| q >= 10), "facing {quarters:?}");
    }

    #[test]
    fn parked_vehicles_keep_off_the_kerbs_the_map_forbids() {
        // A car's footprint at the kerb of road 0 (12 m: its kerbs 6 m out) or road 1.
        let slot = |parked: bool| {
            move |width: f64| {
                Some(RoadSlot {
                    half: [2.2, 0.9],
                    offset: width / 2.0 - 0.25 - 0.9,
                    crossing_clearance: 5.0,
                    gap: 0.4,
                    parked,
                })
            }
        };
        // Which kerbs of road 0 (left, right of its way) the spots stand at.
        let kerbs = |map: &OsmMap, parked: bool| {
            let mut ground = MapSpots::new(map, &[], &[]);
            let mut rng = crate::rng::stream(7, "test", 0);
            let mut sides = [0, 0];
            for spot in (0..60).filter_map(|_| ground.road(&mut rng, 40, slot(parked))) {
                let (_, s) = kerb_distance(map, spot.position);
                if s.road == 0 {
                    let n = left_normal(s.a, s.b).expect("a segment");
                    let d = spot.position;
                    let left = (d[0] - s.a[0]) * n[0] + (d[1] - s.a[1]) * n[1] > 0.0;
                    sides[usize::from(!left)] += 1;
                }
            }
            sides
        };
        let mut map = street_map();
        let both = kerbs(&map, true);
        assert!(both[0] > 3 && both[1] > 3, "{both:?}");
        map.roads[0].parking = [Some(false), Some(true)];
        let right = kerbs(&map, true);
        assert!(right[0] == 0 && right[1] > 3, "{right:?}");
        map.roads[0].parking = [Some(true), Some(false)];
        let left = kerbs(&map, true);
        assert!(left[0] > 3 && left[1] == 0, "{left:?}");
        // Only parked vehicles: a footprint in the lane may stand on either side.
        map.roads[0].parking = [Some(false); 2];
        assert_eq!(kerbs(&map, true), [0, 0]);
        let unparked = kerbs(&map, false);
        assert!(unparked[0] > 3 && unparked[1] > 3, "{unparked:?}");
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
    fn people_cross_on_the_zebras_clear_of_the_cameras_and_wait_at_their_ends() {
        // A zebra across road 0 (two-way, 12 m, eastwards along z = 0 from x −150) at
        // x −120: arc length 30 m.
        let mut map = street_map();
        map.features.push(crate::model::MapFeature {
            node: 40,
            kind: FeatureKind::Crossing,
            at: [-120.0, 0.0],
            tag: String::new(),
        });
        // 12 m wide, the cameras drive it both ways, 1.5 m right and left of its
        // centreline: people cross 1.6 m clear of both lanes, to 0.6 m inside the kerbs.
        // Narrowed to 9 m, it is driven east only: within 2.4 m of the centreline, 1.6 m
        // from the lane (z 1.5: right of the road's direction), on its north half.
        let mut narrow = map.clone();
        for f in &mut narrow.roads[0].fitted {
            f[0] = 9.0;
        }
        for (map, width, [lo, hi]) in [(&map, 12.0, [3.1, 5.4]), (&narrow, 9.0, [0.1, 2.4])] {
            let mut ground = MapSpots::new(map, &[], &[]);
            let mut rng = crate::rng::stream(7, "test", 2);
            let crossing: Vec<CrossingSpot> = (0..20)
                .filter_map(|_| ground.zebra(&mut rng, 0.6, 2.4, 0.45, 40))
                .collect();
            assert!(crossing.len() >= 2, "{crossing:?}");
            let both_ways = crossing.iter().any(|c| c.spot.position[1] > 0.0);
            assert_eq!(both_ways, width > 9.0, "{crossing:?}");
            for (i, c) in crossing.iter().enumerate() {
                let p = c.spot.position;
                assert!((p[0] + 120.0).abs() <= ZEBRA_DEPTH / 2.0, "{c:?}");
                let z = if width > 9.0 { p[1].abs() } else { -p[1] };
                assert!((lo - 1e-9..=hi + 1e-9).contains(&z), "{c:?}");
                let south = c.spot.travel[1] > 0.0;
                assert!(
                    c.spot.travel[0].abs() < 1e-12 && (c.spot.travel[1].abs() - 1.0).abs() < 1e-12
                );
                // Walking south its right is west; walking north, east.
                assert_eq!(p[0] < -120.0, south, "{c:?}");
                assert_eq!(c.crossing.zebra, [28.5, 31.5]);
                assert!(!c.crossing.waiting);
                let far = (width / 2.0 + 0.45) * if south { 1.0 } else { -1.0 };
                assert!((c.reach - (far - p[1]).abs()).abs() < 1e-9, "{c:?}");
                for d in &crossing[i + 1..] {
                    assert!(distance(p, d.spot.position) >= 1.2 - 1e-9, "{c:?} {d:?}");
                }
            }
        }
        // On ground of their own: the crossing people's ways fill both halves of the zebra.
        let mut ground = MapSpots::new(&map, &[], &[]);
        let mut rng = crate::rng::stream(7, "test", 2);
        let waiting: Vec<CrossingSpot> = (0..20)
            .filter_map(|_| ground.zebra_kerb(&mut rng, 0.6, 1.0, 40))
            .collect();
        assert!(!waiting.is_empty());
        for w in &waiting {
            let p = w.spot.position;
            assert!((p[0] + 120.0).abs() <= ZEBRA_DEPTH / 2.0, "{w:?}");
            // On the sidewalk 1 m from the kerb, facing the road.
            assert!((p[1].abs() - 7.0).abs() < 1e-9, "{w:?}");
            assert!(w.spot.travel[1] * p[1] < 0.0, "{w:?}");
            assert!(w.crossing.waiting && (w.reach - 14.0).abs() < 1e-9, "{w:?}");
        }
        // Without a marked crossing, no zebra.
        let mut rng = crate::rng::stream(7, "test", 3);
        let plain = street_map();
        let mut bare = MapSpots::new(&plain, &[], &[]);
        assert!(bare.zebra(&mut rng, 0.6, 2.4, 0.45, 40).is_none());
        assert!(bare.zebra_kerb(&mut rng, 0.6, 1.0, 40).is_none());
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
