//! Objects on a map's streets: the entries of a spec whose layout is an OpenStreetMap
//! extract ([`insert_map`]).
//!
//! | kind | where |
//! |---|---|
//! | tree | at the map's `natural=tree` nodes, in node order, up to `count`: a node on a carriageway or in a building gets none; the crown keeps [`tree::BUILDING_CLEARANCE`] from every wall |
//! | traffic_light | a signal pole at the map's `highway=traffic_signals` nodes on a carriageway, in node order, up to `count` poles: [`POLE_BEHIND_KERB`] behind the right kerb, its head looking back at the traffic coming along the road, and a second one behind the left kerb of a two-way road; a pole in or within its radius of a building, on another road, or on ground a lamp, tree or earlier entry holds is left out |
//! | car | parked at a kerb or standing in a lane of a paved segment (drawn by length), as on a layout's roads, [`MAP_CAMERA_LANE`] clear of the cameras' lane (`MapSpots::near_side`), clear of lamps, mapped trees, crossings and signals, and [`JUNCTION_CLEARANCE`] plus its half length from every other road's carriageway |
//!
//! Other kinds are not placed on maps yet: the spec refuses them, and [`insert_map`]
//! returns [`ObjectsError::NotOnMap`]. Entry `i` draws from `rng::stream(seed, "objects",
//! i)` as on a layout.

use std::collections::BTreeMap;

use rand::RngExt;
use rand_pcg::Pcg64;

use super::footprint_grid::FootprintGrid;
use super::ground_spots::{Footprint, GRID_CELL, LAMP_CLEARANCE, RoadSlot, RoadSpots, Spot};
use super::{Inserted, ObjectsError, ObjectsInput, Placing, car, traffic_lights, tree};
use crate::model::geometry::polygon::{direction, distance, left_normal, nearest};
use crate::model::{
    FacadeSet, FeatureKind, Lamp, MAP_CAMERA_LANE, OsmMap, ParsedLayout, PavedSegment,
    map_camera_lane,
};
use crate::spec::{EntryKind, ObjectSpec};

/// Metres a car keeps, beyond its half length, from every other road's carriageway: the
/// mouth of a junction stays clear.
pub const JUNCTION_CLEARANCE: f64 = 3.0;
/// How far behind the kerb a mapped signal's pole stands, metres.
pub const POLE_BEHIND_KERB: f64 = 0.5;
/// Ground a mapped crossing or signal keeps free of cars, radius in metres.
const CROSSING_ROOM: f64 = 4.0;
/// The narrowest vehicle's width, metres (a small car's).
const NARROWEST: f64 = 1.6;
/// Largest crown radius of a mapped tree, metres.
const MAX_CROWN: f64 = 4.0;

/// Everything placing objects on a map reads.
pub struct MapObjectsInput<'a> {
    pub specs: &'a [ObjectSpec],
    pub map: &'a OsmMap,
    /// The map's lamps (`lamps::map_lamps`), positions in metres.
    pub lamps: &'a [Lamp],
    pub facades: &'a FacadeSet,
    pub seed: u64,
}

/// Places every entry of `input.specs` on the map, in entry order. Pure and deterministic.
pub fn insert_map(input: &MapObjectsInput) -> Result<Inserted, ObjectsError> {
    if let Some(spec) = input.specs.iter().find(|s| {
        !matches!(
            s.kind,
            EntryKind::Tree | EntryKind::Car | EntryKind::TrafficLight
        )
    }) {
        return Err(ObjectsError::NotOnMap {
            kind: spec.kind.name().to_owned(),
        });
    }
    let layout = ParsedLayout {
        width: 0,
        height: 0,
        blocks: Vec::new(),
        roads: Vec::new(),
    };
    let meshes = BTreeMap::new();
    // What `Placing` reads of a layout's input: the specs, the seed and a metre a unit.
    let objects = ObjectsInput {
        specs: input.specs,
        layout: &layout,
        lamps: input.lamps,
        buildings: &[],
        facades: input.facades,
        widths: None,
        meshes: &meshes,
        metres_per_pixel: 1.0,
        seed: input.seed,
    };
    let mut placing = Placing::new(&objects);
    let sites = tree_sites(input.map);
    let mut spots = MapSpots::new(input.map, input.lamps, &sites);
    let signals = signal_sites(input.map);
    let mut placed = Vec::new();
    for (i, spec) in input.specs.iter().enumerate() {
        let mut rng = crate::rng::stream(input.seed, "objects", i as u64);
        let before = placing.out.objects.len();
        let count = match spec.kind {
            EntryKind::Car => car::place(spec, &mut rng, &mut spots, &mut placing),
            EntryKind::TrafficLight => traffic_lights::place_mapped(
                spec,
                &mut rng,
                &signals,
                &mut |f| spots.claim(f),
                &mut placing,
            ),
            _ => {
                tree::place_mapped(spec, &mut rng, &sites, &mut placing);
                (placing.out.objects.len() - before) as u32
            }
        };
        placed.push(count);
    }
    let (textures, materials) = placing.book.finish();
    Ok(Inserted {
        textures,
        materials,
        objects: placing.out.objects,
        info: placing.out.info,
        sign_faces: BTreeMap::new(),
        placed,
    })
}

/// The map's trees that can stand: each `natural=tree` node off the carriageways and out
/// of the buildings, with the crown radius it has room for (at most [`MAX_CROWN`],
/// [`tree::BUILDING_CLEARANCE`] short of the nearest wall).
fn tree_sites(map: &OsmMap) -> Vec<([f64; 2], f64)> {
    map.features
        .iter()
        .filter(|f| f.kind == FeatureKind::Tree)
        .filter(|f| {
            map.nearest_paved(f.at)
                .is_none_or(|(s, _, d)| d > s.width / 2.0 + tree::TRUNK_ROOM)
        })
        .filter(|f| !map.in_building(f.at))
        .map(|f| {
            let room = map.building_distance(f.at) - tree::BUILDING_CLEARANCE;
            (f.at, room.min(MAX_CROWN))
        })
        .collect()
}

/// The map's signals that can stand, in node order: per `highway=traffic_signals` node on
/// a carriageway, its poles (foot, facing) [`POLE_BEHIND_KERB`] behind the kerbs of the
/// nearest paved segment at the node: behind the right kerb (of the way's direction)
/// looking back along it, and on a two-way road behind the left kerb looking ahead; each
/// clear of buildings and of every other road's carriageway by the pole's radius.
fn signal_sites(map: &OsmMap) -> Vec<Vec<([f64; 2], [f64; 2])>> {
    let paved: Vec<PavedSegment> = map.paved_segments().collect();
    let room = traffic_lights::RADIUS;
    let clear = |s: &PavedSegment, foot: [f64; 2]| {
        !map.in_building(foot)
            && map.building_distance(foot) >= room
            && paved
                .iter()
                .filter(|o| o.road != s.road)
                .all(|o| distance(foot, nearest(o.a, o.b, foot)) >= o.width / 2.0 + room)
    };
    map.features
        .iter()
        .filter(|f| f.kind == FeatureKind::TrafficSignals)
        .filter_map(|f| {
            let (s, q, d) = map.nearest_paved(f.at)?;
            let t = direction(s.a, s.b).filter(|_| d <= s.width / 2.0)?;
            let right = [-t[1], t[0]];
            let out = s.width / 2.0 + POLE_BEHIND_KERB;
            let mut poles = vec![(
                [q[0] + right[0] * out, q[1] + right[1] * out],
                [-t[0], -t[1]],
            )];
            if !map.roads[s.road].oneway {
                poles.push(([q[0] - right[0] * out, q[1] - right[1] * out], t));
            }
            poles.retain(|&(foot, _)| clear(&s, foot));
            (!poles.is_empty()).then_some(poles)
        })
        .collect()
}

/// The map's paved segments as places for vehicles.
struct MapSpots {
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
}

impl MapSpots {
    fn new(map: &OsmMap, lamps: &[Lamp], trees: &[([f64; 2], f64)]) -> MapSpots {
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
        MapSpots {
            all,
            segments,
            ends,
            oneway,
            taken,
            rooms,
        }
    }

    /// Takes `footprint` when it is clear of everything taken; whether it was.
    fn claim(&mut self, footprint: Footprint) -> bool {
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

impl RoadSpots for MapSpots {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{ObjectKind, SceneObject};

    fn entries(text: &str) -> Vec<ObjectSpec> {
        #[derive(serde::Deserialize)]
        struct Entries {
            objects: Vec<ObjectSpec>,
        }
        toml::from_str::<Entries>(text)
            .expect("entries parse")
            .objects
    }

    fn place(specs: &[ObjectSpec]) -> Result<Inserted, ObjectsError> {
        place_on(&crate::test_support::street_map(), specs)
    }

    fn place_on(map: &OsmMap, specs: &[ObjectSpec]) -> Result<Inserted, ObjectsError> {
        // Where `lamps::map_lamps` puts the map's lamps.
        let lamp = |id, position, facing| Lamp {
            id,
            position,
            road: 0,
            facing,
        };
        let lamps = [
            lamp(0, [-100.0, -8.0], [0.0, 1.0]),
            lamp(1, [-20.0, 6.5], [0.0, -1.0]),
        ];
        insert_map(&MapObjectsInput {
            specs,
            map,
            lamps: &lamps,
            facades: &crate::model::FacadeSet {
                facades: Vec::new(),
                roofs: Vec::new(),
            },
            seed: 5,
        })
    }

    /// The corners of an object's footprint: its vertices' (x, z).
    fn footprint(object: &SceneObject) -> Vec<[f64; 2]> {
        object
            .meshes
            .iter()
            .flat_map(|m| {
                m.positions
                    .iter()
                    .map(|p| [f64::from(p[0]), f64::from(p[2])])
            })
            .collect()
    }

    #[test]
    fn trees_stand_where_the_map_has_them_off_roads_and_buildings() {
        let specs =
            entries("[[objects]]\nkind = 'tree'\nlabel = 'tree'\ncount = 10\nheight = [8, 10]\n");
        let inserted = place(&specs).expect("trees place");
        // Of the three mapped trees, one is on a carriageway and one in a building.
        assert_eq!(inserted.placed, vec![1]);
        let tree = &inserted.objects[0];
        assert_eq!((tree.kind, tree.class.as_str()), (ObjectKind::Tree, "tree"));
        let trunk_foot = footprint(tree)
            .into_iter()
            .fold([0.0f64, f64::INFINITY], |best, p| {
                let d = distance(p, [-80.0, 8.5]);
                if d < best[1] { [0.0, d] } else { best }
            });
        assert!(trunk_foot[1] < 0.5, "the tree stands at its node");
    }

    #[test]
    fn cars_stand_on_their_carriageway_clear_of_the_cameras_lane() {
        let specs = entries("[[objects]]\nkind = 'car'\ncount = 40\nparked = 0.7\n");
        let a = place(&specs).expect("cars place");
        assert_eq!(a, place(&specs).expect("cars place"), "deterministic");
        let map = crate::test_support::street_map();
        let cars: Vec<&SceneObject> = a
            .objects
            .iter()
            .filter(|o| o.kind == ObjectKind::Car)
            .collect();
        assert!(cars.len() >= 10, "{} cars", cars.len());
        for car in cars {
            let points = footprint(car);
            let n = points.len() as f64;
            let centre = points
                .iter()
                .fold([0.0, 0.0], |c, p| [c[0] + p[0] / n, c[1] + p[1] / n]);
            let (segment, _, _) = map.nearest_paved(centre).expect("a road");
            // The cameras' lane, signed right of the segment's direction.
            let lane = if map.roads[segment.road].oneway {
                map_camera_lane(segment.width)
            } else {
                MAP_CAMERA_LANE
            };
            let n = left_normal(segment.a, segment.b).expect("a segment");
            for p in points {
                let d = distance(p, nearest(segment.a, segment.b, p));
                assert!(d <= segment.width / 2.0 + 1e-3, "{} off its road", car.name);
                let right = -((p[0] - segment.a[0]) * n[0] + (p[1] - segment.a[1]) * n[1]);
                assert!(
                    (right - lane).abs() >= MAP_CAMERA_LANE - 1e-3,
                    "{} in the cameras' lane: {right} m right of the centreline",
                    car.name
                );
            }
        }
    }

    #[test]
    fn signal_poles_stand_behind_the_kerbs_looking_at_the_traffic() {
        let mut map = crate::test_support::street_map();
        let signal = |node, at| crate::model::MapFeature {
            node,
            kind: FeatureKind::TrafficSignals,
            at,
            tag: "highway=traffic_signals".to_owned(),
        };
        map.features.extend([
            // Road 0, two-way, 12 m, eastwards: a pole each side.
            signal(30, [-90.0, 0.0]),
            // Road 1, one-way southwards, 8 m: one pole, behind its right (west) kerb.
            signal(31, [-50.0, 60.0]),
            // In the junction: its pole would stand on road 0's carriageway.
            signal(32, [-50.0, 0.5]),
            // Off every road.
            signal(33, [0.0, 30.0]),
            // Its right pole's ground is the lamp's at (−20, 6.5): the left pole only.
            signal(34, [-20.0, 0.0]),
        ]);
        let specs = entries(
            "[[objects]]\nkind = 'traffic_light'\nlabel = 'light'\ncount = 10\n\n\
             [[objects]]\nkind = 'car'\ncount = 40\nparked = 0.7\n",
        );
        let inserted = place_on(&map, &specs).expect("signals place");
        assert_eq!(inserted.placed[0], 4);
        assert_eq!(inserted, place_on(&map, &specs).expect("signals place"));
        let poles: Vec<&SceneObject> = inserted
            .objects
            .iter()
            .filter(|o| o.kind == ObjectKind::SignalPole)
            .collect();
        let heads: Vec<(&SceneObject, &crate::objects::ObjectInfo)> = inserted
            .objects
            .iter()
            .zip(&inserted.info)
            .filter(|(o, _)| o.kind == ObjectKind::TrafficLight)
            .collect();
        assert_eq!((poles.len(), heads.len()), (4, 4));
        let centre = |o: &SceneObject| {
            let p = footprint(o);
            let n = p.len() as f64;
            p.iter()
                .fold([0.0, 0.0], |c, q| [c[0] + q[0] / n, c[1] + q[1] / n])
        };
        // (foot, facing) per pole, in node order.
        let expected = [
            ([-90.0, 6.5], [-1.0, 0.0]),
            ([-90.0, -6.5], [1.0, 0.0]),
            ([-54.5, 60.0], [0.0, -1.0]),
            ([-20.0, -6.5], [1.0, 0.0]),
        ];
        for ((pole, (head, info)), (foot, facing)) in poles.iter().zip(&heads).zip(expected) {
            assert!(distance(centre(pole), foot) < 1e-3, "{:?}", centre(pole));
            assert_eq!(
                (head.class.as_str(), info.label.as_str()),
                ("light", "light")
            );
            assert!(["red", "amber", "green"].contains(&info.attributes["state"].as_str()));
            // The head hangs out from the pole towards the traffic it faces.
            let h = centre(head);
            let out = [h[0] - foot[0], h[1] - foot[1]];
            assert!(out[0] * facing[0] + out[1] * facing[1] > 0.2, "{out:?}");
            assert!(
                (out[0] * facing[1] - out[1] * facing[0]).abs() < 0.05,
                "{out:?}"
            );
        }
        // The later cars keep off the poles' ground.
        for car in inserted
            .objects
            .iter()
            .filter(|o| o.kind == ObjectKind::Car)
        {
            for p in footprint(car) {
                for (foot, _) in expected {
                    assert!(
                        distance(p, foot) >= traffic_lights::RADIUS - 1e-3,
                        "{}",
                        car.name
                    );
                }
            }
        }
        // `count` caps the poles.
        let three = entries("[[objects]]\nkind = 'traffic_light'\nlabel = 'light'\ncount = 3\n");
        assert_eq!(
            place_on(&map, &three).expect("signals place").placed,
            vec![3]
        );
    }

    #[test]
    fn kinds_not_placed_on_maps_are_refused() {
        let specs = entries("[[objects]]\nkind = 'text'\nlabel = 'text'\n");
        assert!(matches!(
            place(&specs),
            Err(ObjectsError::NotOnMap { kind }) if kind == "text"
        ));
    }
}
