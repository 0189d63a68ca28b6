//! A map read from an OpenStreetMap extract (`osm::read`), in metres.

use serde::{Deserialize, Serialize};

/// What cityspec reads from an OpenStreetMap extract: building footprints, road
/// centrelines and the map's street furniture, projected to metres around the box's
/// centre. Coordinates are `[x, z]`: x east and z south, as in [`crate::model::CityPlan`].
/// Every list is sorted by OSM id (and part), so the same extract and box give the same
/// map, whatever order the file holds its elements in.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct OsmMap {
    /// The box read, in degrees: the one asked for, else the file's own bounds, else the
    /// extent of its nodes.
    pub bounds: GeoBox,
    /// Latitude and longitude (degrees) of the origin `[0, 0]`: the box's centre.
    pub origin: [f64; 2],
    /// Metres per degree of longitude and of latitude at the origin (the projection,
    /// see `osm::Projection`).
    pub metres_per_degree: [f64; 2],
    /// The box in metres: `[min_x, min_z, max_x, max_z]`.
    pub extent: [f64; 4],
    /// Buildings wholly inside the box, by OSM id.
    pub buildings: Vec<MapBuilding>,
    /// Roads and paths, clipped to the box, by way id and piece.
    pub roads: Vec<MapRoad>,
    /// Street furniture the map places (signals, lamps, trees, benches, signs,
    /// crossings), inside the box, by node id.
    pub features: Vec<MapFeature>,
    /// The carriageways of the roads with a surface, as one set of polygons (junctions,
    /// bends and roundabouts where they overlap), clear of every building.
    pub carriageway: Vec<MapPolygon>,
    /// The sidewalks beside them, less the carriageway, clear of every building.
    pub sidewalks: Vec<MapPolygon>,
    /// The city blocks: the box less carriageways and sidewalks.
    pub blocks: Vec<MapPolygon>,
    /// The green ground the map has on the blocks (parks, gardens, grass, woods), cut to
    /// each block, in block order.
    #[serde(default)]
    pub green: Vec<MapArea>,
    /// The paths across the green ground (footways, paths, cycleways, bridleways and
    /// tracks on the ground, each stroked to its width), cut to the green and to each
    /// block, in block order. They lie on the green: [`OsmMap::green`] holds them too.
    #[serde(default)]
    pub paths: Vec<MapArea>,
    /// The paved open ground the map has on the blocks (squares, pedestrian areas, car
    /// parks) less the green, cut to each block, in block order.
    #[serde(default)]
    pub squares: Vec<MapArea>,
    /// What was in the file and left out, and why.
    pub left_out: LeftOut,
}

/// The farthest right of a two-way road's centreline a camera drives on a map, metres (on
/// a one-way road see [`camera_lane`]); vehicles standing on a map's roads keep their near
/// side this much farther out, so the camera's lane stays clear.
pub const CAMERA_LANE: f64 = 1.5;

/// The narrowest vehicle standing on a map's roads, metres (a small car's width).
pub const NARROWEST_VEHICLE: f64 = 1.6;

/// Whether the road cameras drive a paved segment `width` metres wide back as well,
/// against its way, [`CAMERA_LANE`] left of its centreline: a two-way road whose halves
/// each hold that lane, [`CAMERA_LANE`] of clearance and the narrowest vehicle at the
/// kerb (9.2 m or wider). On a narrower two-way road the cameras drive the way's direction
/// only, and vehicles stand anywhere in its other half.
pub fn driven_back(width: f64, oneway: bool) -> bool {
    !oneway && width / 2.0 >= 2.0 * CAMERA_LANE + NARROWEST_VEHICLE
}

/// The narrowest lane a map's carriageway is divided into, metres: a carriageway `w`
/// metres wide holds `⌊w / LANE⌋` lanes (at least one). Its markings split it so, and the
/// cameras drive in its lanes.
pub const LANE: f64 = 2.75;

/// The lanes of a carriageway `width` metres wide ([`LANE`]).
pub fn lanes(width: f64) -> u32 {
    (width / LANE).floor().max(1.0) as u32
}

/// Where a camera drives on a map's one-way carriageway `width` metres wide, metres right
/// of its centreline: in the middle of the lane left of the centreline when the lanes are
/// even (the centreline is a lane line then; the right kerb stays for parking), else on
/// the centreline (the middle lane).
pub fn camera_lane(width: f64) -> f64 {
    let n = lanes(width);
    if n.is_multiple_of(2) {
        -width / f64::from(n) / 2.0
    } else {
        0.0
    }
}

/// One paved segment of a road: a piece of its centreline, `a → b` in the way's
/// direction, with the cross-section it was fitted to ([`MapRoad::fitted`]). A layout's
/// roads are paved segments too ([`crate::model::Road::paved`]), in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PavedSegment {
    /// Index of the road in [`OsmMap::roads`] (a layout's: its id).
    pub road: usize,
    pub a: [f64; 2],
    pub b: [f64; 2],
    /// Carriageway width, metres (a layout's: pixels).
    pub width: f64,
    /// Sidewalk widths left and right of `a → b`, metres (a layout's: pixels).
    pub sidewalks: [f64; 2],
}

impl PavedSegment {
    /// The segment the other way round: `b → a`, its sidewalks swapped.
    pub fn turned(&self) -> PavedSegment {
        PavedSegment {
            a: self.b,
            b: self.a,
            sidewalks: [self.sidewalks[1], self.sidewalks[0]],
            ..*self
        }
    }
}

/// `segments` in runs, as [`OsmMap::paved_runs`] groups a map's.
pub fn paved_runs(segments: impl IntoIterator<Item = PavedSegment>) -> Vec<Vec<PavedSegment>> {
    let mut runs: Vec<Vec<PavedSegment>> = Vec::new();
    for s in segments {
        match runs.last_mut() {
            Some(run) if run.last().is_some_and(|l| l.road == s.road && l.b == s.a) => {
                run.push(s);
            }
            _ => runs.push(vec![s]),
        }
    }
    runs
}

impl OsmMap {
    /// Every paved segment, road by road in map order, along each road's centreline.
    pub fn paved_segments(&self) -> impl Iterator<Item = PavedSegment> + '_ {
        self.roads
            .iter()
            .enumerate()
            .filter(|(_, r)| r.surface)
            .flat_map(|(i, r)| {
                r.centreline
                    .windows(2)
                    .zip(&r.fitted)
                    .filter(|(_, f)| f[0] > 0.0)
                    .map(move |(w, f)| PavedSegment {
                        road: i,
                        a: w[0],
                        b: w[1],
                        width: f[0],
                        sidewalks: [f[1], f[2]],
                    })
            })
    }

    /// The paved segments in runs: consecutive segments of one road, each beginning where
    /// the one before ends (an unpaved segment ends a run), in map order.
    pub fn paved_runs(&self) -> Vec<Vec<PavedSegment>> {
        paved_runs(self.paved_segments())
    }

    /// The paved segment nearest to `p`, the point of its centreline nearest to `p` and
    /// the distance to it; the first of equals in map order. None without paved segments.
    pub fn nearest_paved(&self, p: [f64; 2]) -> Option<(PavedSegment, [f64; 2], f64)> {
        use super::geometry::polygon::{distance, nearest};
        self.paved_segments()
            .map(|s| {
                let q = nearest(s.a, s.b, p);
                (s, q, distance(p, q))
            })
            .fold(None, |best, c| match best {
                Some(b) if b.2 <= c.2 => Some(b),
                _ => Some(c),
            })
    }

    /// The paved segment whose carriageway's edge lies nearest to `p`, and that distance
    /// (negative inside the carriageway); the first such in map order on a tie.
    pub fn nearest_kerb(&self, p: [f64; 2]) -> Option<(f64, PavedSegment)> {
        use super::geometry::polygon::{distance, nearest};
        self.paved_segments()
            .map(|s| (distance(p, nearest(s.a, s.b, p)) - s.width / 2.0, s))
            .min_by(|a, b| a.0.total_cmp(&b.0))
    }

    /// The distance from `p` to the nearest building wall (infinite without buildings).
    pub fn building_distance(&self, p: [f64; 2]) -> f64 {
        self.buildings
            .iter()
            .flat_map(|b| std::iter::once(&b.outer).chain(&b.holes))
            .map(|ring| super::geometry::polygon::ring_distance(ring, p))
            .fold(f64::INFINITY, f64::min)
    }

    /// Whether block `block` has a mapped building in it (the first corner of its outer
    /// ring inside the block's outer ring and outside its holes). One without is a park, a
    /// square or a yard, or, where the map is sparse, unmapped houses.
    pub fn block_is_built(&self, block: &MapPolygon) -> bool {
        use super::geometry::polygon::contains;
        self.buildings.iter().any(|b| {
            contains(&block.outer, b.outer[0])
                && !block.holes.iter().any(|h| contains(h, b.outer[0]))
        })
    }

    /// The open ground on block `n` (an index into [`OsmMap::blocks`]): its green
    /// ground, then its squares.
    pub fn open_on(&self, n: usize) -> Vec<&MapPolygon> {
        (self.green.iter().chain(&self.squares))
            .filter(|g| g.block as usize == n)
            .map(|g| &g.shape)
            .collect()
    }

    /// Whether `p` lies inside a building's footprint (not in one of its courtyards).
    pub fn in_building(&self, p: [f64; 2]) -> bool {
        use super::geometry::polygon::contains;
        self.buildings
            .iter()
            .any(|b| contains(&b.outer, p) && !b.holes.iter().any(|h| contains(h, p)))
    }

    /// Whether a disc of `radius` metres at `p` lies inside the box.
    pub fn holds(&self, p: [f64; 2], radius: f64) -> bool {
        let [x0, z0, x1, z1] = self.extent;
        p[0] - radius > x0 && p[0] + radius < x1 && p[1] - radius > z0 && p[1] + radius < z1
    }

    /// Whether a disc of `radius` metres at `p` stands out of every building: its centre
    /// in none, its edge short of every wall.
    pub fn out_of_buildings(&self, p: [f64; 2], radius: f64) -> bool {
        !self.in_building(p) && self.building_distance(p) >= radius
    }

    /// Whether a disc of `radius` metres at `p` stands out of every building and off the
    /// carriageways of the `paved` segments, but those of road `own` when given.
    pub fn clear_ground(
        &self,
        paved: &[PavedSegment],
        own: Option<usize>,
        p: [f64; 2],
        radius: f64,
    ) -> bool {
        use super::geometry::polygon::{distance, nearest};
        self.out_of_buildings(p, radius)
            && (paved.iter().filter(|o| Some(o.road) != own))
                .all(|o| distance(p, nearest(o.a, o.b, p)) >= o.width / 2.0 + radius)
    }
}

/// A box in degrees.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct GeoBox {
    pub south: f64,
    pub west: f64,
    pub north: f64,
    pub east: f64,
}

impl GeoBox {
    /// What is wrong with the box, if anything: off the globe, or empty or inverted.
    pub fn problem(&self) -> Option<String> {
        let b = self;
        let on_globe = [b.south, b.north].iter().all(|l| l.abs() <= 90.0)
            && [b.west, b.east].iter().all(|l| l.abs() <= 180.0);
        if !on_globe {
            return Some(format!(
                "{},{},{},{} is off the globe: latitudes lie in [-90, 90], longitudes in \
                 [-180, 180]",
                b.south, b.west, b.north, b.east
            ));
        }
        (b.south >= b.north || b.west >= b.east).then(|| {
            format!(
                "{},{},{},{} is empty: give south,west,north,east with south < north and \
                 west < east",
                b.south, b.west, b.north, b.east
            )
        })
    }

    /// Whether `(lat, lon)` lies in the box (edges included).
    pub fn contains(&self, lat: f64, lon: f64) -> bool {
        (self.south..=self.north).contains(&lat) && (self.west..=self.east).contains(&lon)
    }
}

/// The OSM element a map item comes from; for a building the map does not have,
/// `Placed`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OsmElement {
    Way(i64),
    Relation(i64),
    /// Not in the map: placed by Algorithm 1 in block number `n` of [`OsmMap::blocks`], a
    /// block the map has no building in (`place::place_map`).
    Placed(u32),
}

/// A building footprint: one outer ring with its holes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MapBuilding {
    /// The closed way or multipolygon relation tagged `building=*` (or `Placed`).
    pub element: OsmElement,
    /// Which outer ring of a multipolygon (0 for a way); of a placed building, which of
    /// its block's, in placing order.
    pub part: u32,
    /// The `building` tag's value (`yes`, `apartments`, …).
    pub kind: String,
    /// The outer ring, ordered so that its shoelace area in `[x, z]` is positive, without
    /// repeating its first point.
    pub outer: Vec<[f64; 2]>,
    /// Inner rings (courtyards), ordered the other way round, without repeating first
    /// points.
    pub holes: Vec<Vec<[f64; 2]>>,
    /// Footprint area in square metres: the outer ring's less its holes'.
    pub area: f64,
    /// Height in metres where the map gives one (`height`, else `building:levels` (+
    /// `roof:levels`) × the floor height); else the city seeds one.
    pub height: Option<f64>,
    /// Where the height came from: `height`, `levels` or `none`.
    pub height_from: String,
    /// `roof:shape` where the map gives it.
    pub roof_shape: Option<String>,
    /// `roof:height` in metres where the map gives it: how far the roof rises above the
    /// walls.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roof_height: Option<f64>,
    /// `building:colour` where the map gives one (sRGB): the city clads the building in the
    /// facade nearest it in colour.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub colour: Option<[u8; 3]>,
    /// `roof:colour` where the map gives one (sRGB): the city roofs it with the roof
    /// nearest it in colour.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roof_colour: Option<[u8; 3]>,
    /// `roof:orientation=across`: a ridged roof's ridge runs across the longest side, not
    /// along it.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub roof_across: bool,
    /// `roof:direction` where the map gives it: the compass bearing, degrees clockwise from
    /// north, a skillion roof slopes down towards.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roof_direction: Option<f64>,
    /// How high above the ground its walls start, where the map says (`min_height`, else
    /// `building:min_level` × the floor height): a building or part over a passage, a
    /// canopy, a dome on a tower. `height` still counts from the ground.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_height: Option<f64>,
    /// Its parts (`building:part=*` areas whose inside point lies in its footprint, in
    /// element order; Simple 3D Buildings): each its own volume, as tall as it says,
    /// else as the building (`model::geometry::massing`). Parts have no parts.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub parts: Vec<MapBuilding>,
    /// Of a placed building sized by a facade (the paper's rule: one building size per
    /// facade), that facade's index; the city clads it with it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub facade: Option<u32>,
}

impl MapBuilding {
    /// A `building=yes` on footprint `outer` with `holes` (ring `part` of `element`), its
    /// area theirs, without a height, roof, colour, lift or parts: the fields a caller
    /// does not set.
    pub fn new(
        element: OsmElement,
        part: u32,
        outer: Vec<[f64; 2]>,
        holes: Vec<Vec<[f64; 2]>>,
    ) -> MapBuilding {
        use super::geometry::polygon::signed_area;
        let area = signed_area(&outer) + holes.iter().map(|h| signed_area(h)).sum::<f64>();
        MapBuilding {
            element,
            part,
            kind: "yes".to_owned(),
            outer,
            holes,
            area,
            height: None,
            height_from: "none".to_owned(),
            roof_shape: None,
            roof_height: None,
            roof_across: false,
            roof_direction: None,
            colour: None,
            roof_colour: None,
            min_height: None,
            parts: Vec::new(),
            facade: None,
        }
    }
}

/// A road or path centreline with its cross-section.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MapRoad {
    /// The way's id.
    pub way: i64,
    /// Which piece of the way inside the box (0 when the box does not cut it).
    pub piece: u32,
    /// The `highway` tag's value.
    pub class: String,
    /// Whether cars drive on it (motorway to service roads and their links).
    pub drivable: bool,
    /// The centreline, at least two points.
    pub centreline: Vec<[f64; 2]>,
    /// The centreline's length in metres.
    pub length: f64,
    /// Carriageway width in metres.
    pub width: f64,
    /// Where the width came from: `width`, `lanes` or `default`.
    pub width_from: String,
    /// Sidewalk widths in metres on the left and the right of the way's direction (0: none).
    pub sidewalks: [f64; 2],
    /// Whether cars may park at the left and the right kerb (of the way's direction), as
    /// its `parking:lane:*` or `parking:*` tags say (`osm::tags::parking`); None where
    /// the map is silent.
    #[serde(default)]
    pub parking: [Option<bool>; 2],
    /// `oneway=yes` (or a roundabout, or a motorway).
    pub oneway: bool,
    /// `junction=roundabout`.
    pub roundabout: bool,
    /// Whether it is paved into the street surface: drivable and on the ground (not in a
    /// tunnel, under a building or cover, or below ground level).
    pub surface: bool,
    /// Per centreline segment, `[carriageway width, left sidewalk, right sidewalk]` as
    /// paved, narrowed where a mapped building stands closer than the road's nominal
    /// cross-section (0 width: the segment runs through a building and is not paved).
    /// Empty when the road has no surface.
    pub fitted: Vec<[f64; 3]>,
    /// The `name` tag.
    pub name: Option<String>,
    /// Whether the box cut the way.
    pub clipped: bool,
}

/// A polygon in metres: its outer ring (positive shoelace area in `[x, z]`) and holes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MapPolygon {
    pub outer: Vec<[f64; 2]>,
    pub holes: Vec<Vec<[f64; 2]>>,
    /// Square metres: the outer ring's less its holes'.
    pub area: f64,
}

/// Open ground on one block: the part of the map's green areas (or of its squares) that
/// lies on block `block` (an index into [`OsmMap::blocks`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MapArea {
    pub block: u32,
    pub shape: MapPolygon,
}

/// A node the map tags as street furniture.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MapFeature {
    pub node: i64,
    pub kind: FeatureKind,
    pub at: [f64; 2],
    /// The tag that says what it is, `key=value` (`traffic_sign=DE:206`; a signal that
    /// stops one direction only, `traffic_signals:direction=forward` or `backward`).
    pub tag: String,
}

/// The key a signal's one direction is kept under, whether the map writes it so or as
/// `direction=forward` / `backward`.
pub const SIGNAL_DIRECTION: &str = "traffic_signals:direction";

impl MapFeature {
    /// Which traffic a signal stops, by the direction of the way it stands on: `[along
    /// the way, against it]`. Both unless its tag keeps one (`SIGNAL_DIRECTION`).
    pub fn stops(&self) -> [bool; 2] {
        match self.tag.strip_prefix(SIGNAL_DIRECTION) {
            Some("=forward") => [true, false],
            Some("=backward") => [false, true],
            _ => [true, true],
        }
    }
}

/// What a [`MapFeature`] is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FeatureKind {
    TrafficSignals,
    StreetLamp,
    Tree,
    Bench,
    TrafficSign,
    Crossing,
}

/// Counts of what the reader left out, each for the reason its name gives.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct LeftOut {
    /// Buildings with a node outside the box.
    pub buildings_outside: u32,
    /// `building=*` ways that do not close, or with fewer than three distinct points.
    pub buildings_open: u32,
    /// Multipolygon buildings whose member ways are not all in the file or do not close
    /// into rings.
    pub buildings_incomplete: u32,
    /// Ways naming a node the file does not hold.
    pub ways_missing_nodes: u32,
    /// Roads wholly outside the box.
    pub roads_outside: u32,
    /// Road segments with a surface narrowed to stay clear of a mapped building.
    pub segments_narrowed: u32,
    /// Road segments left unpaved: a mapped building stands on them (a passage through
    /// it the map does not tag, or a mapping error).
    pub segments_blocked: u32,
    /// Green areas and squares whose member ways are not all in the file or do not close
    /// into rings.
    #[serde(default)]
    pub areas_incomplete: u32,
    /// `building:part=*` areas inside the box that stand in no building's footprint
    /// (Simple 3D Buildings draws a part only with its building).
    #[serde(default)]
    pub parts_alone: u32,
}
