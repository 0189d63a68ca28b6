//! The reader's one pass: what an extract's elements leave behind, resolved into an
//! [`OsmMap`] once the file ends (so files in any element order read the same).

use std::collections::HashMap;

use super::OsmError;
use super::clip::clip;
use super::elements::Sink;
use super::projection::Projection;
use super::rings::join;
use super::tags;
use crate::model::geometry::polygon::{contains, signed_area, triangle_area, triangles};
use crate::model::{
    FeatureKind, GeoBox, LeftOut, MapBuilding, MapFeature, MapRoad, OsmElement, OsmMap,
};

/// A building's or building part's tags, as read.
struct BuildingTags {
    kind: String,
    height: Option<f64>,
    height_from: &'static str,
    roof_shape: Option<String>,
    roof_height: Option<f64>,
    roof_across: bool,
    roof_direction: Option<f64>,
    colour: Option<[u8; 3]>,
    roof_colour: Option<[u8; 3]>,
    min_height: Option<f64>,
    /// Tagged `building:part=*` (not `no`): a part of the building it stands in, whatever
    /// its `building` tag says.
    part: bool,
}

impl BuildingTags {
    /// The building or building part a way or relation's tags make it, if any.
    fn of(tags: &[(&str, &str)]) -> Option<BuildingTags> {
        let yes = |key| tags::get(tags, key).filter(|b| *b != "no");
        let part = yes("building:part");
        let kind = yes("building").or(part)?;
        let (height, height_from) = tags::height(tags);
        Some(BuildingTags {
            kind: kind.to_owned(),
            height,
            height_from,
            roof_shape: tags::get(tags, "roof:shape").map(str::to_owned),
            roof_height: tags::get(tags, "roof:height").and_then(tags::height_metres),
            roof_across: tags::get(tags, "roof:orientation") == Some("across"),
            roof_direction: tags::get(tags, "roof:direction").and_then(tags::bearing),
            colour: tags::get(tags, "building:colour").and_then(tags::colour),
            roof_colour: tags::get(tags, "roof:colour").and_then(tags::colour),
            min_height: tags::min_height(tags),
            part: part.is_some(),
        })
    }
}

/// A road's tags, as read.
struct RoadTags {
    class: String,
    width: (f64, &'static str),
    sidewalks: [f64; 2],
    parking: [Option<bool>; 2],
    oneway: bool,
    /// `oneway=-1`: the traffic runs against the way's nodes, so the road's centreline is
    /// theirs reversed (and its sides swapped).
    reversed: bool,
    roundabout: bool,
    surface: bool,
    /// A footway, path, cycleway, bridleway or track on the ground (`tags::ground_path`):
    /// drawn where it crosses the green ground.
    ground_path: bool,
    name: Option<String>,
}

/// A multipolygon relation tagged `building=*`: its id, its member ways (`true`: an
/// outer ring's) and its tags.
type BuildingRelation = (i64, Vec<(i64, bool)>, BuildingTags);

/// A multipolygon relation that is open ground: its id, its member ways (`true`: an outer
/// ring's) and which ground.
type OpenRelation = (i64, Vec<(i64, bool)>, Open);

/// Rings as node ids: the outer ones and the inner ones.
type Rings = (Vec<Vec<i64>>, Vec<Vec<i64>>);

/// Everything kept from the elements: node positions, every way's nodes (a multipolygon
/// may name any of them) and the tags of the ways and nodes the map uses.
#[derive(Default)]
pub struct Collector {
    file_bounds: Option<GeoBox>,
    nodes: HashMap<i64, [i32; 2]>,
    way_nodes: HashMap<i64, Vec<i64>>,
    features: Vec<(i64, FeatureKind, String)>,
    buildings: Vec<(i64, BuildingTags)>,
    roads: Vec<(i64, RoadTags)>,
    relations: Vec<BuildingRelation>,
    /// Ways and multipolygons tagged `building:part=*`.
    parts: Vec<(i64, BuildingTags)>,
    part_relations: Vec<BuildingRelation>,
    /// Closed ways that are open ground, by id: green (`tags::green`) or a square
    /// (`tags::square`).
    open_ways: Vec<(i64, Open)>,
    /// Multipolygons that are open ground: id, member ways (`true`: outer) and which.
    open_relations: Vec<OpenRelation>,
}

/// Which open ground an area is.
#[derive(Clone, Copy, PartialEq)]
enum Open {
    Green,
    Square,
}

impl Open {
    fn of(tags: &[(&str, &str)]) -> Option<Open> {
        if tags::green(tags) {
            Some(Open::Green)
        } else {
            tags::square(tags).then_some(Open::Square)
        }
    }
}

impl Sink for Collector {
    fn bounds(&mut self, south: f64, west: f64, north: f64, east: f64) {
        self.file_bounds = Some(GeoBox {
            south,
            west,
            north,
            east,
        });
    }

    fn node(&mut self, id: i64, lat: i32, lon: i32, tags: &[(&str, &str)]) {
        self.nodes.insert(id, [lat, lon]);
        for (kind, tag) in tags::features(tags) {
            self.features.push((id, kind, tag));
        }
    }

    fn way(&mut self, id: i64, refs: &[i64], tags: &[(&str, &str)]) {
        self.way_nodes.insert(id, refs.to_vec());
        if let Some(building) = BuildingTags::of(tags) {
            match building.part {
                true => self.parts.push((id, building)),
                false => self.buildings.push((id, building)),
            }
        } else if let Some(open) = Open::of(tags) {
            self.open_ways.push((id, open));
        }
        let area = tags::get(tags, "area") == Some("yes");
        if let Some(class) = tags::get(tags, "highway").filter(|c| !tags::not_a_way(c) && !area) {
            let roundabout = tags::get(tags, "junction") == Some("roundabout");
            let reversed = tags::get(tags, "oneway") == Some("-1");
            let oneway = matches!(tags::get(tags, "oneway"), Some("yes" | "1"))
                || reversed
                || roundabout
                || class == "motorway";

            let below = tags::get(tags, "tunnel").is_some_and(|t| t != "no")
                || tags::get(tags, "covered").is_some_and(|c| c != "no")
                || tags::get(tags, "indoor").is_some_and(|i| i != "no")
                || tags::get(tags, "location") == Some("underground")
                || tags::get(tags, "layer")
                    .and_then(|l| l.trim().parse::<i32>().ok())
                    .is_some_and(|l| l < 0);
            self.roads.push((
                id,
                RoadTags {
                    surface: tags::drivable(class) && !below,
                    ground_path: tags::ground_path(class, tags) && !below,
                    class: class.to_owned(),
                    width: tags::width(class, tags),
                    sidewalks: traffic_sides(tags::sidewalks(class, tags), reversed),
                    parking: traffic_sides(tags::parking(tags), reversed),
                    oneway,
                    reversed,
                    roundabout,
                    name: tags::get(tags, "name").map(str::to_owned),
                },
            ));
        }
    }

    fn relation(&mut self, id: i64, ways: &[(i64, &str)], tags: &[(&str, &str)]) {
        if tags::get(tags, "type") != Some("multipolygon") {
            return;
        }
        let members = || {
            ways.iter()
                .map(|(w, role)| (*w, *role != "inner"))
                .collect()
        };
        if let Some(building) = BuildingTags::of(tags) {
            match building.part {
                true => self.part_relations.push((id, members(), building)),
                false => self.relations.push((id, members(), building)),
            }
        } else if let Some(open) = Open::of(tags) {
            self.open_relations.push((id, members(), open));
        }
    }
}

impl Collector {
    /// The map inside `bbox` (else the file's bounds, else its nodes' extent).
    pub fn finish(self, bbox: Option<GeoBox>) -> Result<OsmMap, OsmError> {
        let held = self.node_extent().ok_or(OsmError::NoNodes)?;
        let bounds = bbox.or(self.file_bounds).unwrap_or(held);
        if let Some(asked) = bbox {
            let degrees = |&[lat, lon]: &[i32; 2]| [f64::from(lat) / 1e7, f64::from(lon) / 1e7];
            if !self
                .nodes
                .values()
                .any(|n| asked.contains(degrees(n)[0], degrees(n)[1]))
            {
                return Err(OsmError::BoxMissesExtract { asked, held });
            }
        }
        let projection = Projection::new(
            (bounds.south + bounds.north) / 2.0,
            (bounds.west + bounds.east) / 2.0,
        );
        let [x0, z1] = projection.project(bounds.south, bounds.west);
        let [x1, z0] = projection.project(bounds.north, bounds.east);
        let extent = [x0, z0, x1, z1];
        let mut left_out = LeftOut::default();
        let areas = |ways, relations, left_out: &mut LeftOut| {
            let mut out = self.way_buildings(ways, &bounds, &projection, left_out);
            out.extend(self.relation_buildings(relations, &bounds, &projection, left_out));
            out.sort_by_key(|b: &MapBuilding| (b.element, b.part));
            out
        };
        let mut buildings = areas(&self.buildings, &self.relations, &mut left_out);
        // A part outside the box belongs to a building outside it: not counted.
        let parts = areas(&self.parts, &self.part_relations, &mut LeftOut::default());
        left_out.parts_alone = give_parts(&mut buildings, parts);
        let mut roads = self.roads(extent, &projection, &mut left_out);
        super::fit::fit(&mut roads, &buildings, extent, &mut left_out);
        let [carriageway, sidewalks, blocks] = super::surfaces::surfaces(&roads, extent);
        let [green, squares] = [Open::Green, Open::Square]
            .map(|open| self.open_areas(open, &projection, &mut left_out));
        let path_ways: std::collections::HashSet<i64> = (self.roads.iter())
            .filter(|(_, t)| t.ground_path)
            .map(|(id, _)| *id)
            .collect();
        let paths: Vec<&MapRoad> = roads
            .iter()
            .filter(|r| path_ways.contains(&r.way))
            .collect();
        let [green, squares, paths] =
            super::surfaces::open_ground(&green, &squares, &paths, &blocks);
        let mut features: Vec<MapFeature> = self
            .features
            .iter()
            .filter_map(|(id, kind, tag)| {
                let [lat, lon] = degrees(self.nodes[id]);
                bounds.contains(lat, lon).then(|| MapFeature {
                    node: *id,
                    kind: *kind,
                    at: projection.project(lat, lon),
                    tag: tag.clone(),
                })
            })
            .collect();
        features.sort_by_key(|f| f.node);
        Ok(OsmMap {
            bounds,
            origin: projection.origin,
            metres_per_degree: projection.metres_per_degree,
            extent,
            buildings,
            roads,
            features,
            carriageway,
            sidewalks,
            blocks,
            green,
            paths,
            squares,
            left_out,
        })
    }

    fn node_extent(&self) -> Option<GeoBox> {
        let mut it = self.nodes.values().map(|&n| degrees(n));
        let [lat, lon] = it.next()?;
        let mut b = GeoBox {
            south: lat,
            west: lon,
            north: lat,
            east: lon,
        };
        for [lat, lon] in it {
            b.south = b.south.min(lat);
            b.north = b.north.max(lat);
            b.west = b.west.min(lon);
            b.east = b.east.max(lon);
        }
        Some(b)
    }

    /// `(lat, lon)` of every node of `refs`, or `None` when the file lacks one.
    fn locate(&self, refs: &[i64]) -> Option<Vec<[f64; 2]>> {
        refs.iter()
            .map(|id| self.nodes.get(id).map(|&n| degrees(n)))
            .collect()
    }

    fn way_buildings(
        &self,
        ways: &[(i64, BuildingTags)],
        bounds: &GeoBox,
        projection: &Projection,
        left_out: &mut LeftOut,
    ) -> Vec<MapBuilding> {
        let mut out = Vec::new();
        for (id, tags) in ways {
            let refs = &self.way_nodes[id];
            if refs.len() < 4 || refs.first() != refs.last() {
                left_out.buildings_open += 1;
                continue;
            }
            let Some(points) = self.locate(&refs[..refs.len() - 1]) else {
                left_out.ways_missing_nodes += 1;
                continue;
            };
            if !points.iter().all(|&[lat, lon]| bounds.contains(lat, lon)) {
                left_out.buildings_outside += 1;
                continue;
            }
            match ring(&points, projection, true) {
                Some(outer) => out.push(building(OsmElement::Way(*id), 0, tags, outer, Vec::new())),
                None => left_out.buildings_open += 1,
            }
        }
        out
    }

    fn relation_buildings(
        &self,
        relations: &[BuildingRelation],
        bounds: &GeoBox,
        projection: &Projection,
        left_out: &mut LeftOut,
    ) -> Vec<MapBuilding> {
        let mut out = Vec::new();
        for (id, members, tags) in relations {
            let Some(rings) = self.relation_rings(members) else {
                left_out.buildings_incomplete += 1;
                continue;
            };
            let (outers, inners) = rings;
            let located: Option<Vec<Vec<[f64; 2]>>> = outers
                .iter()
                .chain(&inners)
                .map(|r| self.locate(r))
                .collect();
            let Some(located) = located else {
                left_out.ways_missing_nodes += 1;
                continue;
            };
            let inside = located
                .iter()
                .flatten()
                .all(|&[lat, lon]| bounds.contains(lat, lon));
            if !inside {
                left_out.buildings_outside += 1;
                continue;
            }
            let projected: Vec<Option<Vec<[f64; 2]>>> = located
                .iter()
                .enumerate()
                .map(|(i, r)| ring(r, projection, i < outers.len()))
                .collect();
            let (outer_rings, inner_rings) = projected.split_at(outers.len());
            let inner_rings: Vec<&Vec<[f64; 2]>> = inner_rings.iter().flatten().collect();
            for (part, outer) in outer_rings.iter().flatten().enumerate() {
                let holes = inner_rings
                    .iter()
                    .filter(|h| contains(outer, h[0]))
                    .map(|h| (*h).clone())
                    .collect();
                let element = OsmElement::Relation(*id);
                out.push(building(element, part as u32, tags, outer.clone(), holes));
            }
        }
        out
    }

    /// The `open` areas, each as its outer ring then its holes, projected (they may reach
    /// past the box: `surfaces::open_ground` cuts them to the blocks). Ways that do not
    /// close are skipped; multipolygons that do not close are counted in `left_out`.
    fn open_areas(
        &self,
        open: Open,
        projection: &Projection,
        left_out: &mut LeftOut,
    ) -> Vec<Vec<Vec<[f64; 2]>>> {
        let mut out = Vec::new();
        let mut project = |refs: &[i64], outer: bool| -> Option<Option<Vec<[f64; 2]>>> {
            let points = self.locate(refs);
            if points.is_none() {
                left_out.ways_missing_nodes += 1;
            }
            Some(ring(&points?, projection, outer))
        };
        for (id, _) in self.open_ways.iter().filter(|w| w.1 == open) {
            let refs = &self.way_nodes[id];
            if refs.len() < 4 || refs.first() != refs.last() {
                continue;
            }
            if let Some(Some(outer)) = project(refs, true) {
                out.push(vec![outer]);
            }
        }
        for (_, members, _) in self.open_relations.iter().filter(|r| r.2 == open) {
            let Some((outers, inners)) = self.relation_rings(members) else {
                left_out.areas_incomplete += 1;
                continue;
            };
            let inners: Option<Vec<_>> = inners.iter().map(|r| project(r, false)).collect();
            let Some(inners) = inners else { continue };
            let inners: Vec<Vec<[f64; 2]>> = inners.into_iter().flatten().collect();
            for outer in &outers {
                if let Some(Some(outer)) = project(outer, true) {
                    let holes = inners.iter().filter(|h| contains(&outer, h[0])).cloned();
                    out.push(std::iter::once(outer.clone()).chain(holes).collect());
                }
            }
        }
        out
    }

    /// A multipolygon's outer and inner rings as node ids, or `None` when a member is
    /// missing or the rings do not close.
    fn relation_rings(&self, members: &[(i64, bool)]) -> Option<Rings> {
        let mut outer = Vec::new();
        let mut inner = Vec::new();
        for (way, is_outer) in members {
            let refs = self.way_nodes.get(way)?.as_slice();
            if *is_outer {
                outer.push(refs)
            } else {
                inner.push(refs)
            }
        }
        let outers = join(&outer)?;
        (!outers.is_empty()).then_some(())?;
        Some((outers, join(&inner)?))
    }

    fn roads(
        &self,
        extent: [f64; 4],
        projection: &Projection,
        left_out: &mut LeftOut,
    ) -> Vec<MapRoad> {
        let mut out = Vec::new();
        for (id, tags) in &self.roads {
            let Some(points) = self.locate(&self.way_nodes[id]) else {
                left_out.ways_missing_nodes += 1;
                continue;
            };
            let mut line: Vec<[f64; 2]> = points
                .iter()
                .map(|&[lat, lon]| projection.project(lat, lon))
                .collect();
            line.dedup();
            if line.len() < 2 {
                continue;
            }
            if tags.reversed {
                line.reverse();
            }
            let pieces = clip(&line, extent);
            if pieces.is_empty() {
                left_out.roads_outside += 1;
            }
            let clipped = pieces.len() != 1 || pieces[0] != line;
            for (piece, centreline) in pieces.into_iter().enumerate() {
                out.push(MapRoad {
                    way: *id,
                    piece: piece as u32,
                    class: tags.class.clone(),
                    drivable: tags::drivable(&tags.class),
                    length: length(&centreline),
                    centreline,
                    width: tags.width.0,
                    width_from: tags.width.1.to_owned(),
                    sidewalks: tags.sidewalks,
                    parking: tags.parking,
                    oneway: tags.oneway,
                    roundabout: tags.roundabout,
                    surface: tags.surface,
                    fitted: Vec::new(),
                    name: tags.name.clone(),
                    clipped,
                });
            }
        }
        out.sort_by_key(|r| (r.way, r.piece));
        out
    }
}

/// A way's `[left, right]` of its nodes' direction as the traffic's: swapped on a way
/// whose traffic runs against its nodes (`reversed`).
fn traffic_sides<T>([left, right]: [T; 2], reversed: bool) -> [T; 2] {
    if reversed {
        [right, left]
    } else {
        [left, right]
    }
}

/// A ring of `(lat, lon)` in metres, repeated points dropped, turned so that its
/// shoelace area is positive for an outer ring and negative for a hole; `None` when fewer
/// than three distinct points or no area remain.
fn ring(points: &[[f64; 2]], projection: &Projection, outer: bool) -> Option<Vec<[f64; 2]>> {
    let mut ring: Vec<[f64; 2]> = points
        .iter()
        .map(|&[lat, lon]| projection.project(lat, lon))
        .collect();
    ring.dedup();
    while ring.len() > 1 && ring.first() == ring.last() {
        ring.pop();
    }
    let area = signed_area(&ring);
    if ring.len() < 3 || area == 0.0 {
        return None;
    }
    if (area > 0.0) != outer {
        ring.reverse();
    }
    Some(ring)
}

fn building(
    element: OsmElement,
    part: u32,
    tags: &BuildingTags,
    outer: Vec<[f64; 2]>,
    holes: Vec<Vec<[f64; 2]>>,
) -> MapBuilding {
    MapBuilding {
        kind: tags.kind.clone(),
        height: tags.height,
        height_from: tags.height_from.to_owned(),
        roof_shape: tags.roof_shape.clone(),
        roof_height: tags.roof_height,
        roof_across: tags.roof_across,
        roof_direction: tags.roof_direction,
        colour: tags.colour,
        roof_colour: tags.roof_colour,
        min_height: tags.min_height,
        ..MapBuilding::new(element, part, outer, holes)
    }
}

/// Gives each part to the first building (in element order) whose footprint holds a point
/// inside the part (the middle of its largest triangle); returns how many parts stand in
/// no building.
fn give_parts(buildings: &mut [MapBuilding], parts: Vec<MapBuilding>) -> u32 {
    let mut alone = 0;
    for part in parts {
        let inside = triangles(&part.outer, &part.holes)
            .into_iter()
            .max_by(|a, b| triangle_area(*a).total_cmp(&triangle_area(*b)))
            .map(|[a, b, c]| [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0]);
        let owner = inside.and_then(|p| {
            (buildings.iter_mut())
                .find(|b| contains(&b.outer, p) && !b.holes.iter().any(|h| contains(h, p)))
        });
        match owner {
            Some(b) => b.parts.push(part),
            None => alone += 1,
        }
    }
    alone
}

/// `(lat, lon)` in degrees of a node's 10⁻⁷ degrees.
fn degrees([lat, lon]: [i32; 2]) -> [f64; 2] {
    [f64::from(lat) / 1e7, f64::from(lon) / 1e7]
}

/// A polyline's length.
pub fn length(line: &[[f64; 2]]) -> f64 {
    line.windows(2)
        .map(|w| {
            let (dx, dz) = (w[1][0] - w[0][0], w[1][1] - w[0][1]);
            // Not `hypot`: the platform's libm; a square root is the same bits everywhere.
            (dx * dx + dz * dz).sqrt()
        })
        .sum()
}
