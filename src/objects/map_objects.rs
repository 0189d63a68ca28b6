//! Objects on a map's streets: the entries of a spec whose layout is an OpenStreetMap
//! extract ([`insert_map`]).
//!
//! | kind | where |
//! |---|---|
//! | text | planes of words on the walls of the map's buildings that face a paved road (`map_walls`), as on a layout's walls (`wall_text`): the facade laid as the scene lays it, so painted text shows the wall's own pixels and plates keep clear of its windows |
//! | tree | at the map's `natural=tree` nodes, in node order, then on the map's green ground where it plants none (`green_tree_sites`, about one per 12 m square, in a seeded order), up to `count`: a node on a carriageway or in a building gets none; the crown keeps [`tree::BUILDING_CLEARANCE`] from every wall |
//! | traffic_light | a signal pole at the map's `highway=traffic_signals` nodes on a carriageway, in node order, up to `count` poles: [`POLE_BEHIND_KERB`] behind the right kerb, its head looking back at the traffic coming along the road, and a second one behind the left kerb of a two-way road (one only where `traffic_signals:direction` names a direction); a pole in or within its radius of a building, on another road, or on ground a lamp, tree or earlier entry holds is left out |
//! | sign | at the map's `traffic_sign=*` (and `highway=stop` / `give_way`) nodes whose code we have a design for (`sign_codes`), in node order, up to `count` plates, of the types `signs` lists, a plate a code one above the other (a repeated code back to back): beside the nearest paved road where the map has the post, facing the traffic on its side (`sign_sites`), or on the pole of the lamp its node also is; a post in a building, on another road, or on ground a lamp, tree or earlier entry holds is left out |
//! | car | parked at a kerb or standing in a lane of a paved segment (drawn by length), as on a layout's roads, [`MAP_CAMERA_LANE`](crate::model::MAP_CAMERA_LANE) clear of the cameras' lane (`MapSpots::near_side`), clear of lamps, mapped trees, crossings and signals, and [`JUNCTION_CLEARANCE`](super::map_spots::JUNCTION_CLEARANCE) plus its half length from every other road's carriageway; a parked one not at a kerb the map's parking tags forbid (`MapRoad::parking`) |
//! | person | standing or walking on a sidewalk (drawn by length) as in a layout's strips, between the kerb and the sidewalks camera's line, clear of the carriageways, the buildings and everything standing; `crossing` on the zebras the markings draw, clear of the roads cameras' lane, `waiting` at their ends ([`MapSpots`]) |
//! | bicycle | parked on a sidewalk as a person stands, or ridden in a lane as a car stands |
//! | street_name | a pole at the map's street corners (`map_corners`: where two paved roads with different `name`s meet, half the sidewalk from both kerbs), in a seeded order, its two plates naming the streets as the map does, each along its street |
//!
//! Entry `i` draws from `rng::stream(seed, "objects", i)` as on a layout.

use std::collections::BTreeMap;

use rand::RngExt;

use super::ground_spots::{Footprint, LAMP_CLEARANCE, Spot};
use super::map_spots::MapSpots;
use super::traffic_signs::{self, MappedSign, Post};
use super::{
    Inserted, MeshFiles, ObjectsError, ObjectsInput, Placing, bicycle, car, map_corners, map_walls,
    person, sign_codes, street_names, traffic_lights, tree, user_mesh, wall_text,
};
use crate::model::geometry::polygon::{direction, distance};
use crate::model::{
    FacadeSet, FeatureKind, LAMP_POLE_RADIUS, Lamp, OsmMap, ParsedLayout, PavedSegment,
};
use crate::spec::{EntryKind, ObjectSpec, SignKind};

/// How far behind the kerb a mapped signal's pole stands, metres.
pub const POLE_BEHIND_KERB: f64 = 0.5;
/// Largest crown radius of a mapped tree, metres.
const MAX_CROWN: f64 = 4.0;
/// Spacing of the trees seeded on green ground, metres: one to a square this wide, and
/// none this near a tree the map has.
const GREEN_TREE_SPACING: f64 = 12.0;
/// How far a tree seeded on green ground stands inside its edge, metres (off the paths
/// and sidewalks around it).
const GREEN_TREE_INSET: f64 = 1.5;

/// Everything placing objects on a map reads.
pub struct MapObjectsInput<'a> {
    pub specs: &'a [ObjectSpec],
    pub map: &'a OsmMap,
    /// The map's lamps (`lamps::map_lamps`), positions in metres.
    pub lamps: &'a [Lamp],
    pub facades: &'a FacadeSet,
    /// The mesh entries' model files, by the spec's model string.
    pub meshes: &'a BTreeMap<String, MeshFiles>,
    pub seed: u64,
}

/// Places every entry of `input.specs` on the map, in entry order. Pure and deterministic.
pub fn insert_map(input: &MapObjectsInput) -> Result<Inserted, ObjectsError> {
    let layout = ParsedLayout {
        width: 0,
        height: 0,
        blocks: Vec::new(),
        roads: Vec::new(),
    };
    // What `Placing` reads of a layout's input: the specs, the seed and a metre a unit.
    let objects = ObjectsInput {
        specs: input.specs,
        layout: &layout,
        lamps: input.lamps,
        buildings: &[],
        facades: input.facades,
        widths: None,
        meshes: input.meshes,
        metres_per_pixel: 1.0,
        seed: input.seed,
    };
    let mut placing = Placing::new(&objects);
    let mut ground = MapGround::new(input);
    let mut placed = Vec::new();
    for (i, spec) in input.specs.iter().enumerate() {
        let mut rng = crate::rng::stream(input.seed, "objects", i as u64);
        placed.push(ground.place(input, spec, &mut rng, &mut placing)?);
    }
    let (textures, materials) = placing.book.finish();
    Ok(Inserted {
        textures,
        materials,
        objects: placing.out.objects,
        info: placing.out.info,
        sign_faces: placing.out.sign_faces,
        placed,
    })
}

/// Where a map's entries stand: its trees' sites (mapped, then seeded on its green), its
/// signals' poles and signs' posts, and the ground the entries take.
struct MapGround<'a> {
    trees: Vec<([f64; 2], f64)>,
    signals: Vec<Vec<([f64; 2], [f64; 2])>>,
    signs: Vec<MappedSign>,
    spots: MapSpots<'a>,
    /// The walls facing roads, found when a text entry first asks.
    walls: Option<wall_text::Walls>,
}

impl<'a> MapGround<'a> {
    fn new(input: &MapObjectsInput<'a>) -> MapGround<'a> {
        let mut trees = tree_sites(input.map);
        trees.extend(green_tree_sites(input.map, input.lamps, &trees, input.seed));
        MapGround {
            spots: MapSpots::new(input.map, input.lamps, &trees),
            signals: signal_sites(input.map),
            signs: sign_sites(input.map, input.lamps),
            trees,
            walls: None,
        }
    }

    /// Places entry `spec`'s objects; returns how many it counts (as a layout's entry).
    fn place(
        &mut self,
        input: &MapObjectsInput,
        spec: &ObjectSpec,
        rng: &mut rand_pcg::Pcg64,
        placing: &mut Placing,
    ) -> Result<u32, ObjectsError> {
        let before = placing.out.objects.len();
        let spots = &mut self.spots;
        Ok(match spec.kind {
            EntryKind::Text => {
                let (map, facades) = (input.map, input.facades);
                (self.walls)
                    .get_or_insert_with(|| {
                        wall_text::Walls::of(map_walls::map_facing_walls(map, facades, input.seed))
                    })
                    .place(spec, rng, placing)?;
                (placing.out.objects.len() - before) as u32
            }
            EntryKind::StreetName => {
                let mut corners = map_corners::map_corners(input.map, spec.case);
                rand::seq::SliceRandom::shuffle(corners.as_mut_slice(), rng);
                // The plates' circle keeps out of the buildings too: a map's walls stand
                // at its sidewalks' backs, and a plate must not reach into one.
                let claim = &mut |f: Footprint| {
                    let Footprint::Circle(p, r) = f else {
                        return false;
                    };
                    input.map.building_distance(p) >= r && spots.claim(f)
                };
                street_names::place_at(spec, rng, &corners, claim, placing)
            }
            EntryKind::Car => car::place(spec, rng, spots, placing),
            EntryKind::Bicycle => bicycle::place(spec, rng, spots, placing),
            EntryKind::Person => {
                person::place(spec, rng, spots, placing);
                (placing.out.objects.len() - before) as u32
            }
            EntryKind::TrafficLight => {
                let claim = &mut |f| spots.claim(f);
                traffic_lights::place_mapped(spec, rng, &self.signals, claim, placing)
            }
            EntryKind::Mesh if spec.at.is_none() => user_mesh::place(spec, rng, spots, placing)?,
            EntryKind::Mesh => {
                let tag = spec.at.as_deref().unwrap_or_default();
                let paved: Vec<PavedSegment> = input.map.paved_segments().collect();
                let clear = |p: [f64; 2], r: f64| input.map.clear_ground(&paved, None, p, r);
                let sites = node_sites(input.map, tag);
                user_mesh::place_mapped(
                    spec,
                    rng,
                    &sites,
                    &clear,
                    &mut |f| spots.claim(f),
                    placing,
                )?
            }
            EntryKind::Sign => {
                traffic_signs::place_mapped(spec, &self.signs, &mut |f| spots.claim(f), placing)
            }
            _ => {
                tree::place_mapped(spec, rng, &self.trees, placing);
                (placing.out.objects.len() - before) as u32
            }
        })
    }
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

/// Trees seeded on the map's green ground where it plants none, in a seeded order (so an
/// entry's `count` thins them evenly): on each piece of green ground, one per
/// [`GREEN_TREE_SPACING`] square of a grid in metres, at a point drawn in the middle
/// third of the square (`rng::stream(seed, "map-green-trees", piece)`), kept when it lies
/// on the piece [`GREEN_TREE_INSET`] inside its edges, off the paths across it
/// (`OsmMap::paths`) as far from theirs, [`GREEN_TREE_SPACING`] from every
/// tree of `mapped`, clear of the lamps and out of the buildings; the crown has the room
/// `tree_sites` gives.
fn green_tree_sites(
    map: &OsmMap,
    lamps: &[Lamp],
    mapped: &[([f64; 2], f64)],
    seed: u64,
) -> Vec<([f64; 2], f64)> {
    use crate::model::geometry::polygon::contains;
    let s = GREEN_TREE_SPACING;
    let mut out = Vec::new();
    for (i, green) in map.green.iter().enumerate() {
        let mut rng = crate::rng::stream(seed, "map-green-trees", i as u64);
        let shape = &green.shape;
        let rings: Vec<&Vec<[f64; 2]>> =
            std::iter::once(&shape.outer).chain(&shape.holes).collect();
        // The paths across it are holes in it too.
        let paths: Vec<&crate::model::MapPolygon> = (map.paths.iter())
            .filter(|p| p.block == green.block)
            .map(|p| &p.shape)
            .collect();
        let rings: Vec<&Vec<[f64; 2]>> = (rings.into_iter())
            .chain(
                paths
                    .iter()
                    .flat_map(|p| std::iter::once(&p.outer).chain(&p.holes)),
            )
            .collect();
        let on_path = |p: [f64; 2]| {
            (paths.iter()).any(|q| contains(&q.outer, p) && !q.holes.iter().any(|h| contains(h, p)))
        };
        let edge = |p: [f64; 2]| {
            (rings.iter())
                .map(|r| crate::model::geometry::polygon::ring_distance(r, p))
                .fold(f64::INFINITY, f64::min)
        };
        let [x0, z0, x1, z1] = crate::model::geometry::polygon::bounds(&shape.outer);
        for gz in (z0 / s).floor() as i64..=(z1 / s).floor() as i64 {
            for gx in (x0 / s).floor() as i64..=(x1 / s).floor() as i64 {
                let jitter = [rng.random_range(1.0..2.0), rng.random_range(1.0..2.0)];
                let p = [
                    (gx as f64 + jitter[0] / 3.0) * s,
                    (gz as f64 + jitter[1] / 3.0) * s,
                ];
                let on = contains(&shape.outer, p)
                    && !shape.holes.iter().any(|h| contains(h, p))
                    && !on_path(p)
                    && edge(p) >= GREEN_TREE_INSET;
                let clear = on
                    && mapped.iter().all(|(t, _)| distance(*t, p) >= s)
                    && lamps
                        .iter()
                        .all(|l| distance(l.position, p) >= LAMP_CLEARANCE + tree::TRUNK_ROOM)
                    && !map.in_building(p);
                if clear {
                    let room = map.building_distance(p) - tree::BUILDING_CLEARANCE;
                    out.push((p, room.min(MAX_CROWN)));
                }
            }
        }
    }
    let mut rng = crate::rng::stream(seed, "map-green-trees", u64::MAX);
    rand::seq::SliceRandom::shuffle(out.as_mut_slice(), &mut rng);
    out
}

/// The map's signals that can stand, in node order: per `highway=traffic_signals` node on
/// a carriageway, its poles (foot, facing) [`POLE_BEHIND_KERB`] behind the kerbs of the
/// nearest paved segment at the node: behind the right kerb (of the way's direction)
/// looking back along it, and on a two-way road behind the left kerb looking ahead (only
/// the one for the direction a `traffic_signals:direction` tag names); each clear of
/// buildings and of every other road's carriageway by the pole's radius.
fn signal_sites(map: &OsmMap) -> Vec<Vec<([f64; 2], [f64; 2])>> {
    let paved: Vec<PavedSegment> = map.paved_segments().collect();
    let clear = |s: &PavedSegment, foot: [f64; 2]| {
        map.clear_ground(&paved, Some(s.road), foot, traffic_lights::RADIUS)
    };
    map.features
        .iter()
        .filter(|f| f.kind == FeatureKind::TrafficSignals)
        .filter_map(|f| {
            let (s, q, d) = map.nearest_paved(f.at)?;
            let t = direction(s.a, s.b).filter(|_| d <= s.width / 2.0)?;
            let right = [-t[1], t[0]];
            let out = s.width / 2.0 + POLE_BEHIND_KERB;
            // A one-way road's traffic runs along it, whatever the signal's tag says.
            let oneway = map.roads[s.road].oneway;
            let [along, against] = f.stops();
            let mut poles = Vec::new();
            if along || oneway {
                let foot = [q[0] + right[0] * out, q[1] + right[1] * out];
                poles.push((foot, [-t[0], -t[1]]));
            }
            if against && !oneway {
                poles.push(([q[0] - right[0] * out, q[1] - right[1] * out], t));
            }
            poles.retain(|&(foot, _)| clear(&s, foot));
            (!poles.is_empty()).then_some(poles)
        })
        .collect()
}

/// The map's nodes tagged `tag` (a feature's `key=value`), in node order: each with the
/// way a model there faces, towards the nearest point of a paved road's centreline within
/// [`SIGN_REACH`] (none farther off).
fn node_sites(map: &OsmMap, tag: &str) -> Vec<([f64; 2], Option<[f64; 2]>)> {
    map.features
        .iter()
        .filter(|f| f.tag == tag)
        .map(|f| {
            let towards = map
                .nearest_paved(f.at)
                .filter(|(_, _, d)| *d <= SIGN_REACH)
                .and_then(|(_, q, _)| direction(f.at, q));
            (f.at, towards)
        })
        .collect()
}

/// How far from the nearest paved road's centreline a mapped sign may stand and still be
/// that road's, metres: its carriageway's half, a sidewalk and a verge. Signs farther
/// off stand on paths and squares, whose traffic the map does not pave.
const SIGN_REACH: f64 = 15.0;

/// The map's plates that can stand, in node order: each `traffic_sign` (and
/// `highway=stop` / `give_way`) node with a design ([`sign_codes::designs`]) within
/// [`SIGN_REACH`] of a paved road. A post beside the road stands where the map has it
/// (pushed out to [`POLE_BEHIND_KERB`] behind the kerb when it is nearer), facing the
/// traffic on its side: on a one-way road the road's, on a two-way road the traffic
/// driving on the right. A node on the carriageway (a node of the way) stands behind the
/// right kerb of the way's direction. Posts in or at a building or on another road's
/// carriageway are left out. A sign whose node is a lamp's too (a sign on a lamp post)
/// hangs on that lamp's pole, facing the traffic on the lamp's side, its plate just
/// outside the pole.
///
/// A post carries a plate for each code with a design, one above the other in the tag's
/// order (up to [`traffic_signs::MAX_LEVELS`]); a code the tag repeats is the first's
/// twin, back to back with it at its level, facing the other way (`FI:511;FI:511`: a
/// crossing signed for both directions).
fn sign_sites(map: &OsmMap, lamps: &[Lamp]) -> Vec<MappedSign> {
    let paved: Vec<PavedSegment> = map.paved_segments().collect();
    let clear = |s: &PavedSegment, foot: [f64; 2]| {
        map.clear_ground(&paved, Some(s.road), foot, traffic_signs::MAPPED_RADIUS)
    };
    let lamp_nodes: std::collections::BTreeSet<i64> = (map.features.iter())
        .filter(|f| f.kind == FeatureKind::StreetLamp)
        .map(|f| f.node)
        .collect();
    let mut signs = Vec::new();
    for f in (map.features.iter()).filter(|f| f.kind == FeatureKind::TrafficSign) {
        let designs = sign_codes::designs(&f.tag);
        let Some(&(kind, speed)) = designs.first() else {
            continue;
        };
        let Some((s, q, d)) = map.nearest_paved(f.at) else {
            continue;
        };
        let Some(t) = direction(s.a, s.b).filter(|_| d <= SIGN_REACH) else {
            continue;
        };
        // The lamp `lamps::map_lamps` stood for the node: at it, or moved out to its
        // kerb, so no farther from it than that kerb.
        let reach = s.width / 2.0 + POLE_BEHIND_KERB + 0.01;
        let lamp = (lamp_nodes.contains(&f.node))
            .then(|| {
                (lamps.iter())
                    .map(|l| (distance(l.position, f.at), l))
                    .filter(|(d, _)| *d <= reach)
                    .min_by(|a, b| a.0.total_cmp(&b.0))
            })
            .flatten();
        let first = match lamp {
            Some((_, l)) => on_lamp(map, kind, speed, l, (s, q, t)),
            None => {
                let spot = beside_road(map, f.at, (s, q, d, t));
                if !clear(&s, spot.position) {
                    continue;
                }
                MappedSign {
                    kind,
                    speed,
                    spot,
                    on_lamp: false,
                    post: Post::SINGLE,
                    stacked: false,
                }
            }
        };
        signs.extend(stack(first, &designs, lamp.map(|(_, l)| l.position)));
    }
    signs
}

/// Where a post the map has at `at` stands beside paved segment `s` (`q` the nearest
/// point of its centreline, `d` the distance to it, `t` its direction), and the traffic
/// it faces (see [`sign_sites`]).
fn beside_road(
    map: &OsmMap,
    at: [f64; 2],
    (s, q, d, t): (PavedSegment, [f64; 2], f64, [f64; 2]),
) -> Spot {
    let right = [-t[1], t[0]];
    let kerb = s.width / 2.0 + POLE_BEHIND_KERB;
    let on_right =
        d <= s.width / 2.0 || (at[0] - q[0]) * right[0] + (at[1] - q[1]) * right[1] >= 0.0;
    let out = if on_right {
        right
    } else {
        [-right[0], -right[1]]
    };
    let foot = if d < kerb {
        [q[0] + out[0] * kerb, q[1] + out[1] * kerb]
    } else {
        at
    };
    let travel = if on_right || map.roads[s.road].oneway {
        t
    } else {
        [-t[0], -t[1]]
    };
    Spot {
        position: foot,
        travel,
        road: s.road as u32,
    }
}

/// The plates of a post whose first plate is `first`: one a design, levels in order,
/// repeats back to back with their first (see [`sign_sites`]).
fn stack(
    first: MappedSign,
    designs: &[(SignKind, u32)],
    lamp: Option<[f64; 2]>,
) -> Vec<MappedSign> {
    // Each level's design, and whether it has its twin yet.
    let mut levels: Vec<((SignKind, u32), bool)> = Vec::new();
    let mut plates = Vec::new();
    for &design in designs {
        match levels.iter().position(|(d, _)| *d == design) {
            Some(level) if !levels[level].1 => {
                levels[level].1 = true;
                plates.push((design, level, true));
            }
            Some(_) => {}
            None if levels.len() < traffic_signs::MAX_LEVELS as usize => {
                plates.push((design, levels.len(), false));
                levels.push((design, false));
            }
            None => {}
        }
    }
    let levels = levels.len() as u32;
    (plates.into_iter().enumerate())
        .map(|(i, ((kind, speed), level, twin))| {
            let mut spot = first.spot;
            if twin {
                spot.travel = [-spot.travel[0], -spot.travel[1]];
                if let Some(l) = lamp {
                    // Mirrored about the lamp's pole: outside it on the other side.
                    spot.position = [2.0 * l[0] - spot.position[0], 2.0 * l[1] - spot.position[1]];
                }
            }
            MappedSign {
                kind,
                speed,
                spot,
                on_lamp: first.on_lamp,
                post: Post {
                    level: level as u32,
                    levels,
                },
                stacked: i > 0,
            }
        })
        .collect()
}

/// A sign of `kind` hung on lamp `l`'s pole beside paved segment `s` (`q` the nearest
/// point of its centreline to the node, `t` its direction): facing the traffic on the
/// lamp's side (a one-way road's own), its plate [`LAMP_POLE_RADIUS`] plus the plate's
/// gap out from the pole's axis.
fn on_lamp(
    map: &OsmMap,
    kind: crate::spec::SignKind,
    speed: u32,
    l: &Lamp,
    (s, q, t): (PavedSegment, [f64; 2], [f64; 2]),
) -> MappedSign {
    let right = [-t[1], t[0]];
    let on_right = (l.position[0] - q[0]) * right[0] + (l.position[1] - q[1]) * right[1] >= 0.0;
    let travel = if on_right || map.roads[s.road].oneway {
        t
    } else {
        [-t[0], -t[1]]
    };
    // The plate faces against the traffic; `push_sign` sets it `FACE_OFFSET` out from
    // the spot, so the spot lies that much short of the lamp pole's face.
    let out = LAMP_POLE_RADIUS - traffic_signs::POLE_HALF;
    MappedSign {
        kind,
        speed,
        spot: Spot {
            position: [
                l.position[0] - travel[0] * out,
                l.position[1] - travel[1] * out,
            ],
            travel,
            road: s.road as u32,
        },
        on_lamp: true,
        post: Post::SINGLE,
        stacked: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::geometry::KERB_Y;
    use crate::model::geometry::polygon::left_normal;
    use crate::model::geometry::polygon::nearest;
    use crate::model::{MAP_CAMERA_LANE, ObjectKind, SceneObject, map_camera_lane};
    use crate::spec::SignKind;

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
        place_with(map, specs, &BTreeMap::new())
    }

    /// [`place_on`] with the mesh entries' model files.
    fn place_with(
        map: &OsmMap,
        specs: &[ObjectSpec],
        meshes: &BTreeMap<String, MeshFiles>,
    ) -> Result<Inserted, ObjectsError> {
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
            meshes,
            seed: 5,
        })
    }

    /// A node of the map tagged `tag`.
    fn feature(node: i64, kind: FeatureKind, at: [f64; 2], tag: &str) -> crate::model::MapFeature {
        crate::model::MapFeature {
            node,
            kind,
            at,
            tag: tag.to_owned(),
        }
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
    fn trees_are_seeded_on_green_ground_the_map_plants_none_on() {
        use crate::model::geometry::polygon::contains;
        let mut map = crate::test_support::street_map();
        let outer = vec![[-145.0, 10.0], [-60.0, 10.0], [-60.0, 38.0], [-145.0, 38.0]];
        map.green = vec![crate::model::MapArea {
            block: 0,
            shape: crate::model::MapPolygon {
                outer: outer.clone(),
                holes: Vec::new(),
                area: 85.0 * 28.0,
            },
        }];
        let mapped = tree_sites(&map);
        assert_eq!(mapped.len(), 1, "the tree at (−80, 8.5)");
        let lamps = [Lamp {
            id: 0,
            position: [-130.0, 30.0],
            road: 0,
            facing: [0.0, 1.0],
        }];
        let sites = green_tree_sites(&map, &lamps, &mapped, 5);
        // About one per 144 m² of the 1,980 m² beside the building, fewer near the mapped
        // tree and the lamp.
        assert!((6..=16).contains(&sites.len()), "{}", sites.len());
        let edge = |p: [f64; 2]| {
            (0..4)
                .map(|k| distance(p, nearest(outer[k], outer[(k + 1) % 4], p)))
                .fold(f64::INFINITY, f64::min)
        };
        for (i, &(p, room)) in sites.iter().enumerate() {
            assert!(contains(&outer, p) && edge(p) >= GREEN_TREE_INSET, "{p:?}");
            assert!(distance(p, [-80.0, 8.5]) >= GREEN_TREE_SPACING, "{p:?}");
            assert!(distance(p, lamps[0].position) >= LAMP_CLEARANCE, "{p:?}");
            assert!(!map.in_building(p), "{p:?}");
            assert!(room > 0.0 && room <= MAX_CROWN);
            for &(q, _) in &sites[i + 1..] {
                assert!(distance(p, q) >= GREEN_TREE_SPACING / 3.0 - 1e-9);
            }
        }
        assert_eq!(green_tree_sites(&map, &lamps, &mapped, 5), sites);
        assert_ne!(green_tree_sites(&map, &lamps, &mapped, 6), sites);
        // A tree entry takes the map's trees first, then these.
        let specs = entries("[[objects]]\nkind = 'tree'\ncount = 100\n");
        let inserted = place_on(&map, &specs).expect("trees place");
        assert!(inserted.placed[0] > 1, "{:?}", inserted.placed);
        // With no green ground, the map's one tree only.
        assert_eq!(place(&specs).expect("trees place").placed, vec![1]);
        // A path 2 m wide across the green, west to east at z 29 … 31: no tree on it or
        // nearer to it than the inset; the others stay where they were.
        let path = vec![[-145.0, 29.0], [-60.0, 29.0], [-60.0, 31.0], [-145.0, 31.0]];
        map.paths = vec![crate::model::MapArea {
            block: 0,
            shape: crate::model::MapPolygon {
                outer: path,
                holes: Vec::new(),
                area: 170.0,
            },
        }];
        let beside = green_tree_sites(&map, &lamps, &mapped, 5);
        assert!(!beside.is_empty());
        let near_path = |t: &&([f64; 2], f64)| {
            (29.0 - GREEN_TREE_INSET..=31.0 + GREEN_TREE_INSET).contains(&t.0[1])
        };
        let kept: Vec<([f64; 2], f64)> = sites.iter().filter(|t| !near_path(t)).copied().collect();
        let mut sorted = beside.clone();
        sorted.sort_by(|a, b| a.0[0].total_cmp(&b.0[0]));
        let mut kept_sorted = kept.clone();
        kept_sorted.sort_by(|a, b| a.0[0].total_cmp(&b.0[0]));
        assert_eq!(sorted, kept_sorted);
        assert!(
            kept.len() < sites.len(),
            "trees stood there without the path"
        );
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

    /// The middle of an object's footprint's bounding box.
    fn middle(object: &SceneObject) -> [f64; 2] {
        let points = footprint(object);
        let lo = points
            .iter()
            .fold([f64::INFINITY; 2], |m, p| [m[0].min(p[0]), m[1].min(p[1])]);
        let hi = points.iter().fold([f64::NEG_INFINITY; 2], |m, p| {
            [m[0].max(p[0]), m[1].max(p[1])]
        });
        [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0]
    }

    #[test]
    fn parks_and_squares_shares_of_the_people_stand_and_walk_on_them() {
        use crate::model::geometry::polygon::contains;
        let mut map = crate::test_support::street_map();
        map.paths = vec![crate::objects::map_spots::tests::l_path()];
        let path = map.paths[0].shape.outer.clone();
        // (Where each stands exactly, `map_spots`' test checks: here, the middle of its
        // figure's box, which a stride or a bag moves a little.)
        let on_path = |p: [f64; 2]| contains(&path, p);
        let people = |parks: f64| {
            let text = format!("[[objects]]\nkind = 'person'\ncount = 40\nparks = {parks}\n");
            let inserted = place_on(&map, &entries(&text)).expect("people place");
            assert_eq!(inserted.placed, vec![40]);
            let p: Vec<[f64; 2]> = (inserted.objects.iter())
                .filter(|o| o.kind == ObjectKind::Person)
                .map(middle)
                .collect();
            p.iter().filter(|&&p| on_path(p)).count()
        };
        assert_eq!(people(1.0), 40, "all on the path");
        assert_eq!(people(0.0), 0, "all on the sidewalks");
        let half = people(0.5);
        assert!((10..=30).contains(&half), "{half} of 40 on the path");
        // Without paths, a parks share stands on the sidewalks.
        let text = "[[objects]]\nkind = 'person'\ncount = 40\nparks = 1.0\n";
        assert_eq!(
            place(&entries(text)).expect("people place").placed,
            vec![40]
        );
        // A squares share of the rest stands on the squares.
        map.squares = vec![crate::objects::map_spots::tests::square_with_a_basin()];
        let square = map.squares[0].shape.outer.clone();
        let text = "[[objects]]\nkind = 'person'\ncount = 40\nparks = 0.5\nsquares = 1.0\n";
        let inserted = place_on(&map, &entries(text)).expect("people place");
        let at: Vec<[f64; 2]> = (inserted.objects.iter())
            .filter(|o| o.kind == ObjectKind::Person)
            .map(middle)
            .collect();
        let parks = at.iter().filter(|&&p| on_path(p)).count();
        let squares = at.iter().filter(|&&p| contains(&square, p)).count();
        assert_eq!(parks + squares, 40);
        assert!((10..=30).contains(&parks), "{parks} of 40 on the path");
    }

    #[test]
    fn people_and_parked_bicycles_stand_on_the_sidewalks_ridden_ones_in_the_lanes() {
        let specs = entries(
            "[[objects]]\nkind = 'person'\ncount = 60\n\
             [[objects]]\nkind = 'bicycle'\ncount = 16\nparked = 0.5\n",
        );
        let a = place(&specs).expect("people and bicycles place");
        assert_eq!(a, place(&specs).expect("they place"), "deterministic");
        // Road 0 is driven both ways, and its lane is within 3 m of its centreline: bicycles
        // ride on one-way road 1 only, whose 100 m hold about a dozen.
        assert_eq!(a.placed, vec![60, 16]);
        let map = crate::test_support::street_map();
        // Metres from `p` to the nearest carriageway's edge (negative on one).
        let kerb = |p: [f64; 2]| {
            (map.paved_segments())
                .map(|s| distance(p, nearest(s.a, s.b, p)) - s.width / 2.0)
                .fold(f64::INFINITY, f64::min)
        };
        let of = |kind| a.objects.iter().filter(move |o| o.kind == kind);
        for person in of(ObjectKind::Person) {
            let d = kerb(middle(person));
            // Between the kerb and the walk's line on a 3 m or 2 m sidewalk.
            assert!(d > 0.3 && d < 2.1, "{} {d} m from the kerb", person.name);
            assert!(!map.in_building(middle(person)), "{}", person.name);
        }
        let (mut parked, mut ridden) = (0, 0);
        for bicycle in of(ObjectKind::Bicycle) {
            let d = kerb(middle(bicycle));
            if d < 0.0 {
                ridden += 1;
            } else {
                assert!(d > 0.5 && d < 2.5, "{} {d} m from the kerb", bicycle.name);
                parked += 1;
            }
        }
        assert!(
            parked >= 5 && ridden >= 5,
            "{parked} parked, {ridden} ridden"
        );
        assert_eq!(
            of(ObjectKind::Rider).count(),
            ridden,
            "a rider on each ridden one"
        );
        for rider in of(ObjectKind::Rider) {
            assert!(kerb(middle(rider)) < 0.0, "{} off the road", rider.name);
        }
    }

    #[test]
    fn text_goes_on_the_walls_facing_the_streets() {
        let specs = entries(
            "[[objects]]\nkind = 'text'\nlabel = 'text'\ncount = 6\nletter_height = [0.4, 0.6]\n",
        );
        let a = place(&specs).expect("text places");
        assert_eq!(a, place(&specs).expect("text places"), "deterministic");
        assert_eq!(a.placed, vec![6]);
        // All on the one wall facing a road: the building's north wall (z 19, x −120…−100,
        // 12 m high), in front of it, between 2.5 m up and 1 m below the roof.
        let band = [
            KERB_Y + wall_text::MIN_HEIGHT - 1e-6,
            KERB_Y + 12.0 - wall_text::TOP_CLEARANCE + 1e-6,
        ];
        for text in &a.objects {
            assert_eq!(text.kind, ObjectKind::Text);
            for m in &text.meshes {
                for p in &m.positions {
                    let [x, y, z] = p.map(f64::from);
                    assert!((z - (19.0 - wall_text::WALL_OFFSET)).abs() < 1e-4, "{p:?}");
                    assert!((-120.0..=-100.0).contains(&x), "{p:?}");
                    assert!(y >= band[0] && y <= band[1], "{p:?}");
                }
            }
        }
    }

    #[test]
    fn street_name_signs_stand_at_the_corners_naming_the_streets_as_the_map_does() {
        // Road 1 leaves road 0 southwards at a node at x −50: a T with two corners.
        let mut map = crate::test_support::street_map();
        let road = &mut map.roads[0];
        road.centreline = vec![[-150.0, 0.0], [-50.0, 0.0], [0.0, 0.0], [100.0, -100.0]];
        road.fitted = vec![[12.0, 3.0, 3.0]; 3];
        road.name = Some("Bulevardi".to_owned());
        map.roads[1].name = Some("Fredrikinkatu".to_owned());
        let specs = entries(
            "[[objects]]\nkind = 'street_name'\nlabel = 'text'\ncount = 5\n\
             letter_height = [0.16, 0.24]\n",
        );
        let a = place_on(&map, &specs).expect("street names place");
        assert_eq!(
            a,
            place_on(&map, &specs).expect("they place"),
            "deterministic"
        );
        assert_eq!(a.placed, vec![2], "two corners, one pole each");
        let poles = a
            .objects
            .iter()
            .filter(|o| o.kind == ObjectKind::StreetPole);
        assert_eq!(poles.count(), 2);
        let mut texts: Vec<&str> = (a.objects.iter().zip(&a.info))
            .filter(|(o, _)| o.kind == ObjectKind::Text)
            .filter_map(|(_, i)| i.text.as_deref())
            .collect();
        texts.sort();
        // Two plates a pole, lettered on both faces.
        assert_eq!(texts, [["Bulevardi"; 4], ["Fredrikinkatu"; 4]].concat());
        // A building 0.5 m east of the corner at (−45, 7.5): the pole would stand, but its
        // plates (over a metre wide) would reach into it.
        map.buildings[0].outer = vec![[-44.5, 7.0], [-40.0, 7.0], [-40.0, 12.0], [-44.5, 12.0]];
        let a = place_on(&map, &specs).expect("street names place");
        assert_eq!(a.placed, vec![1]);
    }

    #[test]
    fn signal_poles_stand_behind_the_kerbs_looking_at_the_traffic() {
        let mut map = crate::test_support::street_map();
        let signal = |node, at| {
            feature(
                node,
                FeatureKind::TrafficSignals,
                at,
                "highway=traffic_signals",
            )
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
            // Stopping one direction only: the backward (westbound) traffic's pole, then
            // the forward one's.
            crate::model::MapFeature {
                tag: "traffic_signals:direction=backward".to_owned(),
                ..signal(35, [-130.0, 0.0])
            },
            crate::model::MapFeature {
                tag: "traffic_signals:direction=forward".to_owned(),
                ..signal(36, [-140.0, 0.0])
            },
        ]);
        let specs = entries(
            "[[objects]]\nkind = 'traffic_light'\nlabel = 'light'\ncount = 10\n\n\
             [[objects]]\nkind = 'car'\ncount = 40\nparked = 0.7\n",
        );
        let inserted = place_on(&map, &specs).expect("signals place");
        assert_eq!(inserted.placed[0], 6);
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
        assert_eq!((poles.len(), heads.len()), (6, 6));
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
            ([-130.0, -6.5], [1.0, 0.0]),
            ([-140.0, 6.5], [-1.0, 0.0]),
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
    fn signs_stand_at_the_mapped_posts_facing_the_traffic_on_their_side() {
        let mut map = crate::test_support::street_map();
        let sign = |node, at, tag| feature(node, FeatureKind::TrafficSign, at, tag);
        map.features.extend([
            // Road 0, two-way, 12 m, eastwards: right (south) of it, the eastbound traffic.
            sign(40, [-85.0, 8.0], "traffic_sign=DE:206"),
            // Left of it: the westbound traffic.
            sign(41, [-85.0, -8.0], "traffic_sign=FI:373;FI:372"),
            // Road 1, one-way southwards, 8 m: left of it 0.2 m from the kerb, pushed out
            // to half a metre behind it, facing the road's traffic.
            sign(42, [-45.8, 60.0], "traffic_sign=DE:274[30]"),
            // A node of road 0's way: behind its right kerb.
            sign(43, [-70.0, 1.0], "highway=give_way"),
            // No design of its meaning; too far from a paved road; on the lamp's ground.
            sign(44, [-30.0, 8.0], "traffic_sign=GB:601.1"),
            sign(45, [0.0, 30.0], "traffic_sign=DE:206"),
            sign(46, [-20.0, 8.5], "traffic_sign=DE:206"),
            // On the lamp post of node 2, which stands 0.5 m behind road 0's right kerb.
            sign(2, [-20.0, 0.0], "traffic_sign=DE:206"),
        ]);
        let specs = entries("[[objects]]\nkind = 'sign'\ncount = 10\n");
        let inserted = place_on(&map, &specs).expect("signs place");
        assert_eq!(inserted.placed, vec![5]);
        assert_eq!(inserted, place_on(&map, &specs).expect("signs place"));
        // (kind, foot, facing) per sign, in node order.
        let expected = [
            (SignKind::Stop, [-85.0, 8.0], [-1.0, 0.0]),
            (SignKind::NoStopping, [-85.0, -8.0], [1.0, 0.0]),
            (SignKind::SpeedLimit, [-45.5, 60.0], [0.0, -1.0]),
            (SignKind::Yield, [-70.0, 6.5], [-1.0, 0.0]),
        ];
        let mut faces: Vec<(&usize, &traffic_signs::SignFace)> =
            inserted.sign_faces.iter().collect();
        assert_eq!(faces.len(), expected.len() + 1);
        // The one on the lamp post: a plate on the lamp's pole (no pole of its own), facing
        // the eastbound traffic, its face just outside the pole.
        let (&index, face) = faces.pop().expect("the lamp's sign");
        assert_eq!(inserted.objects[index].kind, ObjectKind::Sign);
        assert_ne!(inserted.objects[index - 1].kind, ObjectKind::SignPole);
        assert_eq!((face.kind, face.normal), (SignKind::Stop, [-1.0, 0.0, 0.0]));
        let centre = [-20.0 - (LAMP_POLE_RADIUS + 0.015), 6.5];
        assert!(
            distance([face.centre[0], face.centre[2]], centre) < 1e-9,
            "{face:?}"
        );
        for ((&index, face), (kind, foot, facing)) in faces.into_iter().zip(expected) {
            assert_eq!(inserted.objects[index].kind, ObjectKind::Sign);
            assert_eq!(inserted.objects[index - 1].kind, ObjectKind::SignPole);
            assert_eq!(face.kind, kind);
            assert_eq!(face.normal, [facing[0], 0.0, facing[1]]);
            let out = traffic_signs::FACE_OFFSET;
            let centre = [foot[0] + facing[0] * out, foot[1] + facing[1] * out];
            assert!(
                distance([face.centre[0], face.centre[2]], centre) < 1e-9,
                "{face:?}"
            );
        }
        let speed = inserted
            .materials
            .iter()
            .any(|m| m.name == "sign_speed_limit_30");
        assert!(speed, "the limit's number comes from the tag");
        // `signs` picks the types, `count` caps them.
        let stops = entries("[[objects]]\nkind = 'sign'\nsigns = ['stop']\n");
        assert_eq!(place_on(&map, &stops).expect("signs place").placed, vec![2]);
        let two = entries("[[objects]]\nkind = 'sign'\ncount = 2\n");
        assert_eq!(place_on(&map, &two).expect("signs place").placed, vec![2]);
    }

    /// A post with six codes: stop, a limit and a crossing one above the other, the
    /// crossing's repeat back to back with it, the last two past the three levels left
    /// out. A lamp post signed twice: the twin on the far side of the lamp's pole.
    #[test]
    fn a_post_carries_a_plate_a_code_one_above_the_other_repeats_back_to_back() {
        let mut map = crate::test_support::street_map();
        let sign = |node, at, tag| feature(node, FeatureKind::TrafficSign, at, tag);
        map.features.extend([
            sign(
                60,
                [-120.0, 8.0],
                "traffic_sign=DE:206;DE:274[50];FI:511;FI:511;DE:286;DE:283",
            ),
            sign(2, [-20.0, 0.0], "traffic_sign=DE:206;DE:206"),
        ]);
        let specs = entries("[[objects]]\nkind = 'sign'\ncount = 10\n");
        let inserted = place_on(&map, &specs).expect("signs place");
        assert_eq!(inserted.placed, vec![6]);
        let kinds: Vec<ObjectKind> = inserted.objects.iter().map(|o| o.kind).collect();
        use ObjectKind::{Sign, SignPole};
        assert_eq!(kinds, [SignPole, Sign, Sign, Sign, Sign, Sign, Sign]);
        // The post stands taller by two plates and gaps, its lowest plate where a single
        // plate is.
        let step = traffic_signs::PLATE + traffic_signs::PLATE_GAP;
        let top = inserted.objects[0].meshes[0]
            .positions
            .iter()
            .map(|p| f64::from(p[1]))
            .fold(f64::NEG_INFINITY, f64::max);
        assert!((top - (KERB_Y + traffic_signs::POLE_HEIGHT + 2.0 * step)).abs() < 1e-5);
        let single = KERB_Y + traffic_signs::POLE_HEIGHT - traffic_signs::PLATE / 2.0;
        let out = traffic_signs::FACE_OFFSET;
        let on_lamp = LAMP_POLE_RADIUS + 0.015;
        // (kind, face centre x, z, y, normal x) in order.
        let expected = [
            (SignKind::Stop, -120.0 - out, 8.0, single + 2.0 * step, -1.0),
            (SignKind::SpeedLimit, -120.0 - out, 8.0, single + step, -1.0),
            (
                SignKind::PedestrianCrossing,
                -120.0 - out,
                8.0,
                single,
                -1.0,
            ),
            (SignKind::PedestrianCrossing, -120.0 + out, 8.0, single, 1.0),
            (SignKind::Stop, -20.0 - on_lamp, 6.5, single, -1.0),
            (SignKind::Stop, -20.0 + on_lamp, 6.5, single, 1.0),
        ];
        let faces: Vec<&traffic_signs::SignFace> = inserted.sign_faces.values().collect();
        assert_eq!(faces.len(), expected.len());
        for (face, (kind, x, z, y, nx)) in faces.into_iter().zip(expected) {
            assert_eq!((face.kind, face.normal), (kind, [nx, 0.0, 0.0]), "{face:?}");
            let want = [x, y, z];
            assert!(
                (0..3).all(|k| (face.centre[k] - want[k]).abs() < 1e-9),
                "{face:?} {want:?}"
            );
        }
        // A post whose first plate's type the entry leaves out stands at its first plate
        // of a listed type, on a pole of its own, at that plate's level.
        let limits = entries("[[objects]]\nkind = 'sign'\nsigns = ['speed_limit']\n");
        let inserted = place_on(&map, &limits).expect("signs place");
        assert_eq!(inserted.placed, vec![1]);
        let kinds: Vec<ObjectKind> = inserted.objects.iter().map(|o| o.kind).collect();
        assert_eq!(kinds, [SignPole, Sign]);
        let face = inserted.sign_faces.values().next().expect("the limit");
        assert!((face.centre[1] - (single + step)).abs() < 1e-9, "{face:?}");
    }

    #[test]
    fn models_stand_at_the_mapped_nodes_of_their_tag_facing_the_nearest_road() {
        let mut map = crate::test_support::street_map();
        let bench = |node, at, tag| feature(node, FeatureKind::Bench, at, tag);
        map.features.extend([
            // Beside road 0 (faces north, to it); beside road 1 (faces west, to it).
            bench(50, [-85.0, 9.5], "amenity=bench"),
            bench(51, [-43.0, 70.0], "amenity=bench"),
            // Another tag; on road 0's carriageway; in the building.
            bench(52, [-30.0, 9.5], "highway=bench"),
            bench(53, [-60.0, 2.0], "amenity=bench"),
            bench(54, [-110.0, 25.0], "amenity=bench"),
        ]);
        let files = MeshFiles {
            obj: include_bytes!("../../assets/models/bench.obj").to_vec(),
            mtl: Some(include_bytes!("../../assets/models/bench.mtl").to_vec()),
            textures: BTreeMap::new(),
        };
        let meshes = BTreeMap::from([("bench.obj".to_owned(), files.clone())]);
        let specs = entries(
            "[[objects]]\nkind = 'mesh'\nlabel = 'bench'\ncount = 10\n\
             model = 'bench.obj'\nat = 'amenity=bench'\nrotation = [0, 0]\n",
        );
        let place = || place_with(&map, &specs, &meshes).expect("benches place");
        let inserted = place();
        assert_eq!(inserted, place());
        assert_eq!(inserted.placed, vec![2]);
        let model = user_mesh::Model::load("bench.obj", &files).expect("bench loads");
        // The model's −z (its front) onto the way to the road: (cos, sin) of the turn.
        let expected = [([-85.0, 9.5], (1.0, 0.0)), ([-43.0, 70.0], (0.0, 1.0))];
        for (object, (at, (c, s))) in inserted.objects.iter().zip(expected) {
            assert_eq!(
                (object.kind, object.class.as_str()),
                (ObjectKind::Mesh, "bench")
            );
            let placed = object.meshes.iter().flat_map(|m| &m.positions);
            let own = model.parts.iter().flat_map(|p| &p.positions);
            for (p, v) in placed.zip(own) {
                let want = [
                    at[0] + c * v[0] + s * v[2],
                    crate::model::geometry::KERB_Y + v[1] - model.min_y,
                    at[1] - s * v[0] + c * v[2],
                ];
                for k in 0..3 {
                    assert!((f64::from(p[k]) - want[k]).abs() < 1e-4, "{p:?} {want:?}");
                }
            }
        }
        // A mesh entry without a model file read is an error, not a silent skip.
        let missing = place_on(&map, &specs);
        assert!(matches!(missing, Err(ObjectsError::MissingModel { .. })));
    }

    #[test]
    fn models_without_at_are_seeded_mid_sidewalk_or_at_the_kerb_of_a_lane() {
        let map = crate::test_support::street_map();
        // A box 0.4 m square: its footprint's middle is where it stands, however turned.
        let obj = "v -0.2 0 -0.2\nv 0.2 0 -0.2\nv 0.2 0.8 0.2\nv -0.2 0.8 0.2\n\
                   f 1 2 3\nf 1 3 4\n";
        let files = MeshFiles {
            obj: obj.as_bytes().to_vec(),
            mtl: None,
            textures: BTreeMap::new(),
        };
        let meshes = BTreeMap::from([("box.obj".to_owned(), files)]);
        let specs = entries(
            "[[objects]]\nkind = 'mesh'\nlabel = 'box'\ncount = 12\nmodel = 'box.obj'\n\
             [[objects]]\nkind = 'mesh'\nlabel = 'cone'\ncount = 6\nmodel = 'box.obj'\n\
             on = 'lane'\n",
        );
        let place = || place_with(&map, &specs, &meshes).expect("models place");
        let inserted = place();
        assert_eq!(inserted, place());
        assert_eq!(inserted.placed, vec![12, 6]);
        let radius = 0.2 * std::f64::consts::SQRT_2;
        for object in &inserted.objects {
            let points = object.meshes.iter().flat_map(|m| &m.positions);
            let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            for p in points {
                for (k, v) in [p[0], p[2]].into_iter().enumerate() {
                    lo[k] = lo[k].min(f64::from(v));
                    hi[k] = hi[k].max(f64::from(v));
                }
            }
            let at = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
            let (segment, _, d) = map.nearest_paved(at).expect("paved roads");
            let want = if object.class == "box" {
                // The middle of the sidewalk beside the nearest carriageway.
                segment.width / 2.0 + segment.sidewalks[0] / 2.0
            } else {
                // The kerb side of the right-hand lane, `CURB_GAP` from the kerb.
                segment.width / 2.0 - super::super::car::CURB_GAP - radius
            };
            assert!(
                (d - want).abs() < 1e-3,
                "{} at {at:?}: {d} from {segment:?}",
                object.name
            );
            assert!(map.building_distance(at) >= radius, "{at:?}");
        }
        // On a lane, a model wider than the room at the kerb takes none.
        let wide = entries(
            "[[objects]]\nkind = 'mesh'\nlabel = 'cone'\ncount = 3\nmodel = 'box.obj'\n\
             on = 'lane'\nscale = [20, 20]\n",
        );
        let none = place_with(&map, &wide, &meshes).expect("models place");
        assert_eq!(none.placed, vec![0]);
    }
}
