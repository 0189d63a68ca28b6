//! A map's paved roads → `marking_NNNN` objects (NNNN: the road's index in the map):
//! white dashes along each road's centreline and between its lanes, and a zebra crossing
//! where the map has a marked crossing on the road. Markings follow the centreline through
//! its bends, and stay out of junctions.
//!
//! - **Lanes.** A segment of carriageway `w` metres wide holds `⌊w / LANE⌋` lanes (at least
//!   one, [`MAP_LANE`](crate::model::MAP_LANE)). A two-way road of two lanes or more gets a dashed centre line, and its halves
//!   dashed lines between their own lanes; a one-way road of `n` lanes gets `n − 1` dashed
//!   lines splitting it evenly. Lines are [`LINE_WIDTH`] wide.
//! - **Dashes.** [`DASH`](crate::model::geometry::zebras::DASH) long and
//!   [`GAP`](super::markings::GAP) apart, counted along the road's centreline (so
//!   they run on through a bend) and centred in each stretch the road leaves them:
//!   a run of paved segments less its junctions and zebras.
//! - **Junctions.** Where three or more arms of paved roads meet (a road ending on
//!   another, two roads crossing at a shared node; a way simply continuing into the next
//!   is not a junction), each road's lines stop [`LINE_CLEARANCE`] before the other
//!   roads' carriageways: `h' / sin θ + h / tan θ` along the road from the junction, `h`
//!   and `h'` the half-widths and θ the angle between the roads. An arm whose sine is
//!   under [`MIN_SINE`](crate::model::geometry::map_lines::MIN_SINE) (about 17°) carries the road on (ways are split at junctions) and
//!   sets no clearance.
//! - **Zebras.** A `highway=crossing` node within [`ON_ROAD`] of a paved road's
//!   centreline, unless the map says it has no markings (`crossing=unmarked`,
//!   `crossing:markings=no`), gets bars [`BAR`] wide and
//!   [`ZEBRA_DEPTH`] long, parallel to the road, [`BAR_GAP`] apart and centred from kerb
//!   to kerb (less [`CURB_CLEARANCE`]), centred on the node. A zebra that would reach into a
//!   junction's carriageway is left out. Lines stop [`LINE_CLEARANCE`] before a zebra.
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
//!   [`TOOTH_LENGTH`] long in place of the stop line: bases [`TOOTH_BASE`] wide on the
//!   node's side, [`TOOTH_GAP`] apart and centred across the lanes, apexes pointing at the
//!   coming traffic.
//!
//! Not drawn on maps yet: parking-lane edges, arrows.

use super::markings::{BAR, BAR_GAP, CURB_CLEARANCE, STOP_LINE, centred_dashes, centred_pieces};
use super::object;
use crate::model::geometry::map_lines::{Centreline, Junction, MapLines, ON_ROAD, Zebra};
use crate::model::geometry::polygon::direction;
use crate::model::geometry::zebras::{LINE_CLEARANCE, LINE_WIDTH, ZEBRA_DEPTH};
use crate::model::geometry::{MARKING_Y, MeshBuilder, UP};
use crate::model::{FeatureKind, ObjectKind, OsmMap, SceneObject, map_lanes};

/// How far before its node (or the zebra, or the junction, the traffic meets first) a
/// stop line ends, metres.
pub const STOP_GAP: f64 = 1.0;
/// A give-way line's triangles: their length along the road, metres (the Vienna
/// Convention's 0.60–0.70 m, Annex 2 §33).
pub const TOOTH_LENGTH: f64 = 0.6;
/// A give-way triangle's base across the road, metres (0.40–0.60 m, the same).
pub const TOOTH_BASE: f64 = 0.5;
/// The gap between two give-way triangles' bases, metres.
pub const TOOTH_GAP: f64 = 0.25;
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
            for z in zebras.iter().filter(|z| z.road == line.road) {
                line.zebra(&mut mesh, z);
                let half = ZEBRA_DEPTH / 2.0 + LINE_CLEARANCE;
                blocked.push([z.at - half, z.at + half]);
            }
            for stop in stops.iter().filter(|l| l.road == line.road) {
                let s = stop.segment;
                let along = stop.along.map(|a| a - line.at[s]);
                if stop.give_way {
                    line.teeth(&mut mesh, s, along, stop.across, stop.sign);
                } else {
                    line.rect(&mut mesh, s, along, stop.across);
                }
                blocked.push([
                    stop.along[0] - LINE_CLEARANCE,
                    stop.along[1] + LINE_CLEARANCE,
                ]);
            }
            for run in line.runs() {
                for stretch in free(run, &blocked) {
                    for dash in centred_dashes(stretch) {
                        line.dash(&mut mesh, dash);
                    }
                }
            }
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

/// A stop line on a road: on which segment, over which arc lengths, and across which
/// offsets (metres right of the centreline).
struct StopLine {
    road: usize,
    segment: usize,
    along: [f64; 2],
    across: [f64; 2],
    /// 1: it stops the traffic running along the road; −1: against it.
    sign: f64,
    /// A give-way line (triangles), not a stop line (a bar).
    give_way: bool,
}

impl Centreline<'_> {
    /// One dash over arc lengths `along` on every lane line of each segment it crosses.
    fn dash(&self, mesh: &mut MeshBuilder, along: [f64; 2]) {
        let points = self.points();
        for s in 0..points.len() - 1 {
            let (a, b) = (self.at[s].max(along[0]), self.at[s + 1].min(along[1]));
            let width = self.width(s);
            if a >= b || width <= 0.0 {
                continue;
            }
            for offset in lane_lines(width, self.map_road.oneway) {
                let half = LINE_WIDTH / 2.0;
                self.rect(
                    mesh,
                    s,
                    [a - self.at[s], b - self.at[s]],
                    [offset - half, offset + half],
                );
            }
        }
    }

    /// The stop line over arc lengths `along` for the traffic running `sign` (1: along
    /// the road), across its lanes; None when it would leave its paved run or touch one of
    /// the road's `junctions`.
    fn stop_line(&self, along: [f64; 2], sign: f64, junctions: &[&Junction]) -> Option<StopLine> {
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
            segment,
            along,
            across,
            sign,
            give_way: false,
        })
    }

    /// The bars of `zebra`, along its segment, kerb to kerb.
    fn zebra(&self, mesh: &mut MeshBuilder, zebra: &Zebra) {
        let s = zebra.segment;
        let half = self.width(s) / 2.0 - CURB_CLEARANCE;
        let centre = zebra.at - self.at[s];
        let along = [centre - ZEBRA_DEPTH / 2.0, centre + ZEBRA_DEPTH / 2.0];
        for bar in centred_pieces([-half, half], BAR, BAR_GAP) {
            self.rect(mesh, s, along, bar);
        }
    }

    /// The marking point on segment `s` at `l` metres along it from its first point and
    /// `c` metres right of it (x east, z south); None for a segment of no length.
    fn on_segment(&self, s: usize) -> Option<impl Fn(f64, f64) -> [f64; 3]> {
        let (a, b) = (self.points()[s], self.points()[s + 1]);
        let t = direction(a, b)?;
        // Right of a → b.
        let n = [-t[1], t[0]];
        Some(move |l: f64, c: f64| {
            [
                a[0] + t[0] * l + n[0] * c,
                MARKING_Y,
                a[1] + t[1] * l + n[1] * c,
            ]
        })
    }

    /// A marking quad on segment `s`: `along` it (metres from its first point) and
    /// `across` it (metres right of it).
    fn rect(&self, mesh: &mut MeshBuilder, s: usize, along: [f64; 2], across: [f64; 2]) {
        let Some(at) = self.on_segment(s) else {
            return;
        };
        let corners = [
            at(along[0], across[0]),
            at(along[1], across[0]),
            at(along[1], across[1]),
            at(along[0], across[1]),
        ];
        // The whole mark is one white quad; uv 0..1 over it.
        let uvs = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        mesh.quad(corners, UP, uvs);
    }

    /// A give-way line's triangles over arc lengths `along` (from segment `s`'s start)
    /// and `across` (metres right of the centreline), for traffic running `sign`: bases
    /// on the side it drives to, apexes towards it.
    fn teeth(
        &self,
        mesh: &mut MeshBuilder,
        s: usize,
        along: [f64; 2],
        across: [f64; 2],
        sign: f64,
    ) {
        let Some(at) = self.on_segment(s) else {
            return;
        };
        let (base, apex) = if sign > 0.0 {
            (along[1], along[0])
        } else {
            (along[0], along[1])
        };
        let width = across[1] - across[0];
        let count = ((width + TOOTH_GAP) / (TOOTH_BASE + TOOTH_GAP)).floor();
        let used = count * TOOTH_BASE + (count - 1.0) * TOOTH_GAP;
        let mut c = across[0] + (width - used) / 2.0;
        for _ in 0..count.max(0.0) as u32 {
            let corners = [
                at(base, c),
                at(base, c + TOOTH_BASE),
                at(apex, c + TOOTH_BASE / 2.0),
            ];
            mesh.triangle(corners, UP, [[0.0, 0.0], [1.0, 0.0], [0.5, 1.0]]);
            c += TOOTH_BASE + TOOTH_GAP;
        }
    }
}

/// The stop and give-way lines of the map's signals, stop and give-way nodes on the
/// paved roads `lines` (see the module's docs): per node, per road through it in road order, the traffic running along
/// the road before the traffic running against it (a line that would lie off the road's
/// paved run is the traffic leaving the node: none).
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
            if let Some(stop) = line.stop_line(along, sign, &own) {
                out.push(StopLine { give_way, ..stop });
            }
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

/// What is left of `run` (arc lengths) outside the `blocked` ranges, in order.
fn free(run: [f64; 2], blocked: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut cuts: Vec<[f64; 2]> = blocked
        .iter()
        .filter(|b| b[1] > run[0] && b[0] < run[1])
        .copied()
        .collect();
    cuts.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let mut out = Vec::new();
    let mut from = run[0];
    for cut in cuts {
        if cut[0] > from {
            out.push([from, cut[0].min(run[1])]);
        }
        from = from.max(cut[1]);
    }
    if from < run[1] {
        out.push([from, run[1]]);
    }
    out
}
