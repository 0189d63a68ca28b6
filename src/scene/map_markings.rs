//! A map's paved roads → `marking_NNNN` objects (NNNN: the road's index in the map):
//! where each road's marks go, painted by the one painter layouts use too
//! ([`paint`](super::paint)). White dashes along each road's centreline and between its
//! lanes, and a zebra crossing where the map has a marked crossing on the road. Markings
//! follow the centreline through its bends, and stay out of junctions.
//!
//! - **Lanes.** A segment of carriageway `w` metres wide holds `⌊w / LANE⌋` lanes (at least
//!   one, [`MAP_LANE`](crate::model::MAP_LANE)). A two-way road of two lanes or more gets
//!   a dashed centre line, and its halves dashed lines between their own lanes; a one-way
//!   road of `n` lanes gets `n − 1` dashed lines splitting it evenly. Lines are
//!   [`LINE_WIDTH`] wide.
//! - **Dashes.** [`DASH`](crate::model::geometry::zebras::DASH) long and
//!   [`GAP`](super::paint::GAP) apart, counted along the road's centreline (so
//!   they run on through a bend) and centred in each stretch the road leaves them:
//!   a run of paved segments less its junctions and zebras.
//! - **Junctions.** Where three or more arms of paved roads meet (a road ending on
//!   another, two roads crossing at a shared node; a way simply continuing into the next
//!   is not a junction), each road's lines stop [`LINE_CLEARANCE`] before the other
//!   roads' carriageways: `h' / sin θ + h / tan θ` along the road from the junction, `h`
//!   and `h'` the half-widths and θ the angle between the roads. An arm whose sine is
//!   under [`MIN_SINE`](crate::model::geometry::map_lines::MIN_SINE) (about 17°) carries
//!   the road on (ways are split at junctions) and sets no clearance.
//! - **Zebras.** A `highway=crossing` node within [`ON_ROAD`] of a paved road's
//!   centreline, unless the map says it has no markings (`crossing=unmarked`,
//!   `crossing:markings=no`), gets bars [`BAR`](super::paint::BAR) wide and
//!   [`ZEBRA_DEPTH`] long, parallel to the road, [`BAR_GAP`](super::paint::BAR_GAP) apart
//!   and centred from kerb to kerb (less [`CURB_CLEARANCE`]), centred on the node. A zebra
//!   that would reach into a junction's carriageway is left out. Lines stop
//!   [`LINE_CLEARANCE`] before a zebra.
//!
//! - **Stop lines.** At each `highway=traffic_signals` or `highway=stop` node, on each
//!   paved road within [`ON_ROAD`] of it, a line [`STOP_LINE`] wide crosses the lanes of
//!   each direction of traffic coming to the node (both halves of a two-way road, one each
//!   way, or the one way a `traffic_signals:direction` tag names; a one-way road's whole
//!   width), ending [`STOP_GAP`] before the node, before the zebras
//!   within [`SIGNAL_ZEBRA`] of it, and before the carriageway of a junction the node lies
//!   in, whichever the traffic meets first. A line that would lie in a junction or off its
//!   paved run is left out. The dashes keep [`LINE_CLEARANCE`] from it.
//! - **Give-way lines.** At each `highway=give_way` node the same way, a row of
//!   triangles (the Vienna Convention's "shark teeth", as Finland paints them)
//!   [`TOOTH_LENGTH`] long in place of the stop line: bases
//!   [`TOOTH_BASE`](super::paint::TOOTH_BASE) wide on the node's side,
//!   [`TOOTH_GAP`](super::paint::TOOTH_GAP) apart and centred across the lanes, apexes
//!   pointing at the coming traffic.
//!
//! Not drawn on maps yet: parking-lane edges, arrows.

use super::object;
use super::paint::{
    CURB_CLEARANCE, Line, Path, RoadMarks, STOP_LINE, StopMark, TOOTH_LENGTH, ZebraMark, paint,
};
use crate::model::geometry::MeshBuilder;
use crate::model::geometry::map_lines::{Centreline, Junction, MapLines, ON_ROAD, Zebra};
use crate::model::geometry::zebras::{LINE_CLEARANCE, LINE_WIDTH, ZEBRA_DEPTH, free_stretches};
use crate::model::{FeatureKind, ObjectKind, OsmMap, SceneObject, map_lanes};

/// How far before its node (or the zebra, or the junction, the traffic meets first) a
/// stop line ends, metres.
pub const STOP_GAP: f64 = 1.0;
/// Zebras this close to a signal along its road, metres, are the signal's: its stop lines
/// stand before them.
pub const SIGNAL_ZEBRA: f64 = 8.0;
/// The markings of every paved road of `map`, in road order; roads without any are left
/// out. Pure and deterministic.
pub fn map_marking_objects(map: &OsmMap, material: u32) -> Vec<SceneObject> {
    let MapLines {
        lines,
        junctions,
        zebras,
    } = MapLines::of(map);
    let stops = stop_lines(map, &lines, &zebras, &junctions);
    lines
        .iter()
        .filter_map(|line| {
            let mut mesh = MeshBuilder::new(material);
            let marks = road_marks(line, &junctions, &zebras, &stops);
            paint(&mut mesh, &Path::new(line.points().to_vec()), &marks);
            (!mesh.is_empty()).then(|| {
                object(
                    ObjectKind::Marking,
                    format!("marking_{:04}", line.road),
                    vec![mesh],
                )
            })
        })
        .collect()
}

/// What is painted on the road of `line`: its lane lines on each paved segment, over its
/// paved runs less the `junctions`, `zebras` and `stops` on it (and [`LINE_CLEARANCE`]
/// either side); its zebras kerb to kerb; its stop and give-way lines.
fn road_marks(
    line: &Centreline,
    junctions: &[Junction],
    zebras: &[Zebra],
    stops: &[StopLine],
) -> RoadMarks {
    let mut blocked: Vec<[f64; 2]> = junctions
        .iter()
        .filter(|j| j.road == line.road)
        .map(|j| {
            [
                j.at - j.reach - LINE_CLEARANCE,
                j.at + j.reach + LINE_CLEARANCE,
            ]
        })
        .collect();
    let mut marks = RoadMarks::default();
    for z in zebras.iter().filter(|z| z.road == line.road) {
        let half = line.width(z.segment) / 2.0 - CURB_CLEARANCE;
        marks.zebras.push(ZebraMark {
            segment: z.segment,
            along: [z.at - ZEBRA_DEPTH / 2.0, z.at + ZEBRA_DEPTH / 2.0],
            across: [-half, half],
        });
        let half = ZEBRA_DEPTH / 2.0 + LINE_CLEARANCE;
        blocked.push([z.at - half, z.at + half]);
    }
    for stop in stops.iter().filter(|l| l.road == line.road) {
        marks.stops.push(stop.mark);
        blocked.push([
            stop.mark.along[0] - LINE_CLEARANCE,
            stop.mark.along[1] + LINE_CLEARANCE,
        ]);
    }
    marks.lines = (0..line.at.len() - 1)
        .map(|s| {
            let width = line.width(s);
            if width <= 0.0 {
                return Vec::new();
            }
            lane_lines(width, line.map_road.oneway)
                .into_iter()
                .map(|offset| Line {
                    offset,
                    solid: false,
                })
                .collect()
        })
        .collect();
    marks.stretches = line
        .runs()
        .into_iter()
        .flat_map(|run| free_stretches(run, blocked.clone()))
        .collect();
    marks
}

/// The offsets (metres right of the centreline) of the dashed lines of a carriageway
/// `width` metres wide: the centre line and lane lines of a two-way road, the lane lines of
/// a one-way one.
pub fn lane_lines(width: f64, oneway: bool) -> Vec<f64> {
    let lanes = map_lanes(width);
    if oneway {
        let lane = width / f64::from(lanes);
        return (1..lanes)
            .map(|k| -width / 2.0 + f64::from(k) * lane)
            .collect();
    }
    if lanes < 2 {
        return Vec::new();
    }
    let per_side = lanes / 2;
    let lane = width / 2.0 / f64::from(per_side);
    let mut lines = vec![0.0];
    for k in 1..per_side {
        lines.extend([-f64::from(k) * lane, f64::from(k) * lane]);
    }
    lines
}

/// A stop or give-way line on a road.
struct StopLine {
    road: usize,
    mark: StopMark,
}

impl Centreline<'_> {
    /// The stop line over arc lengths `along` for the traffic running `sign` (1: along
    /// the road), across its lanes (`give_way`: triangles pointing at that traffic); None
    /// when it would leave its paved run or touch one of the road's `junctions`.
    fn stop_line(
        &self,
        along: [f64; 2],
        sign: f64,
        give_way: bool,
        junctions: &[&Junction],
    ) -> Option<StopLine> {
        self.runs()
            .iter()
            .find(|r| r[0] <= along[0] && along[1] <= r[1])?;
        if junctions
            .iter()
            .any(|j| along[1] > j.at - j.reach && along[0] < j.at + j.reach)
        {
            return None;
        }
        let mid = (along[0] + along[1]) / 2.0;
        let segment = (0..self.at.len() - 1)
            .find(|&s| self.at[s] <= mid && mid <= self.at[s + 1] && self.width(s) > 0.0)?;
        let reach = self.width(segment) / 2.0 - CURB_CLEARANCE;
        let across = match (self.map_road.oneway, sign > 0.0) {
            (true, _) => [-reach, reach],
            // Traffic keeps right: along the road on its right half.
            (false, true) => [LINE_WIDTH / 2.0, reach],
            (false, false) => [-reach, -LINE_WIDTH / 2.0],
        };
        Some(StopLine {
            road: self.road,
            mark: StopMark {
                segment,
                along,
                across,
                give_way: give_way.then_some(sign),
            },
        })
    }
}

/// The stop and give-way lines of the map's signals, stop and give-way nodes on the
/// paved roads `lines` (see the module's docs): per node, per road through it in road
/// order, the traffic running along the road before the traffic running against it (a
/// line that would lie off the road's paved run is the traffic leaving the node: none).
fn stop_lines(
    map: &OsmMap,
    lines: &[Centreline],
    zebras: &[Zebra],
    junctions: &[Junction],
) -> Vec<StopLine> {
    let stops = |f: &&crate::model::MapFeature| {
        f.kind == FeatureKind::TrafficSignals || f.tag == "highway=stop" || f.tag == GIVE_WAY
    };
    let mut out = Vec::new();
    // Every road through the node: ways are split at junctions, so traffic comes to a
    // signal at a junction along the pieces that end there.
    let through = map.features.iter().filter(stops).flat_map(|f| {
        lines
            .iter()
            .filter_map(move |line| Some((f, line, line.locate(f.at, ON_ROAD)?.1)))
    });
    for (f, line, at) in through {
        let road = line.road;
        let own: Vec<&Junction> = junctions.iter().filter(|j| j.road == road).collect();
        // A one-way road's traffic runs along it, whatever the signal's tag says.
        let oneway = line.map_road.oneway;
        let [along, against] = f.stops();
        for (sign, stopped) in [(1.0, along || oneway), (-1.0, against && !oneway)] {
            if !stopped {
                continue;
            }
            // What the traffic meets first: the node, its zebras, the junction it is in.
            let mut front = at;
            for z in zebras.iter().filter(|z| z.road == road) {
                if (z.at - at).abs() <= SIGNAL_ZEBRA {
                    front = first(sign, front, z.at - sign * ZEBRA_DEPTH / 2.0);
                }
            }
            for j in own.iter().filter(|j| (j.at - at).abs() <= j.reach) {
                front = first(sign, front, j.at - sign * j.reach);
            }
            let give_way = f.tag == GIVE_WAY;
            let depth = if give_way { TOOTH_LENGTH } else { STOP_LINE };
            let near = front - sign * STOP_GAP;
            let far = near - sign * depth;
            let along = [near.min(far), near.max(far)];
            out.extend(line.stop_line(along, sign, give_way, &own));
        }
    }
    out
}

/// The tag of a give-way node.
const GIVE_WAY: &str = "highway=give_way";

/// Of two arc lengths, the one traffic running `sign` (1: along the road, −1: against it)
/// reaches first.
fn first(sign: f64, a: f64, b: f64) -> f64 {
    if sign > 0.0 { a.min(b) } else { a.max(b) }
}
