//! A map's paved roads as lines along their centrelines, the one reading the markings
//! (`scene::map_markings`) and the people on the zebras (`objects::map_spots`) share:
//! arc lengths along each road, the junctions where three or more arms meet and how far
//! their carriageways reach along each road, and the zebra crossings clear of them.

use super::polygon::{direction, distance, nearest};
use super::zebras::ZEBRA_DEPTH;
use crate::model::{FeatureKind, MapRoad, OsmMap};

/// How close to a paved centreline a crossing node lies to be that road's crossing, metres.
pub const ON_ROAD: f64 = 0.5;
/// The least sine of the angle between two roads at a junction that sets a clearance: a
/// shallower arm carries the road on (about 17°).
pub const MIN_SINE: f64 = 0.3;
/// Points closer than this are one node, metres (projected nodes of one OSM node are
/// equal; this only absorbs rounding).
const SAME_POINT: f64 = 0.01;
/// The tags of a crossing the map says has no markings (`osm::read` keeps them).
pub const UNMARKED_CROSSING: [&str; 2] = ["crossing=unmarked", "crossing:markings=no"];

/// A paved road's centreline as its markings are laid out: arc length at each point.
pub struct Centreline<'a> {
    pub road: usize,
    pub map_road: &'a MapRoad,
    /// Arc length (metres from the first point) of each point of the centreline.
    pub at: Vec<f64>,
    /// The centreline's bounding box, `[min_x, min_z, max_x, max_z]`.
    pub bounds: [f64; 4],
}

/// Where a junction lies on a road and how far its other roads' carriageways reach along
/// it either way, metres.
pub struct Junction {
    pub road: usize,
    pub at: f64,
    pub reach: f64,
}

/// A zebra crossing on a road: where along it, on which segment.
pub struct Zebra {
    pub road: usize,
    pub segment: usize,
    pub at: f64,
}

impl<'a> Centreline<'a> {
    pub fn of(road: usize, map_road: &'a MapRoad) -> Centreline<'a> {
        let mut at = vec![0.0];
        for w in map_road.centreline.windows(2) {
            at.push(at[at.len() - 1] + distance(w[0], w[1]));
        }
        let bounds = map_road.centreline.iter().fold(
            [
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            ],
            |b, p| {
                [
                    b[0].min(p[0]),
                    b[1].min(p[1]),
                    b[2].max(p[0]),
                    b[3].max(p[1]),
                ]
            },
        );
        Centreline {
            road,
            map_road,
            at,
            bounds,
        }
    }

    pub fn points(&self) -> &[[f64; 2]] {
        &self.map_road.centreline
    }

    /// Carriageway width of segment `s` as paved (0: not paved).
    pub fn width(&self, s: usize) -> f64 {
        self.map_road.fitted.get(s).map_or(0.0, |f| f[0])
    }

    /// Arc-length ranges of the runs of consecutive paved segments.
    pub fn runs(&self) -> Vec<[f64; 2]> {
        let mut runs: Vec<[f64; 2]> = Vec::new();
        let mut open: Option<f64> = None;
        for s in 0..self.at.len() - 1 {
            match (self.width(s) > 0.0, open) {
                (true, None) => open = Some(self.at[s]),
                (false, Some(start)) => {
                    runs.push([start, self.at[s]]);
                    open = None;
                }
                _ => {}
            }
        }
        if let Some(start) = open {
            runs.push([start, self.at[self.at.len() - 1]]);
        }
        runs
    }

    /// The point of the centreline nearest to `p` within `tolerance`: (segment, arc
    /// length, unit direction of the segment, distance from `p`); the first of equals.
    pub fn locate(&self, p: [f64; 2], tolerance: f64) -> Option<(usize, f64, [f64; 2], f64)> {
        let b = self.bounds;
        if p[0] < b[0] - tolerance
            || p[1] < b[1] - tolerance
            || p[0] > b[2] + tolerance
            || p[1] > b[3] + tolerance
        {
            return None;
        }
        let points = self.points();
        (0..points.len() - 1)
            .filter(|&s| self.width(s) > 0.0)
            .map(|s| {
                let q = nearest(points[s], points[s + 1], p);
                (s, distance(p, q), self.at[s] + distance(points[s], q))
            })
            .filter(|&(_, d, _)| d <= tolerance)
            .fold(None, |best: Option<(usize, f64, f64)>, c| match best {
                Some(b) if b.1 <= c.1 => Some(b),
                _ => Some(c),
            })
            .and_then(|(s, d, at)| Some((s, at, direction(points[s], points[s + 1])?, d)))
    }

    /// How many arms of this road leave `p` (on it): one at an end of an open road, two
    /// elsewhere.
    pub fn arms_at(&self, p: [f64; 2]) -> u32 {
        let points = self.points();
        let (first, last) = (points[0], points[points.len() - 1]);
        let closed = distance(first, last) <= SAME_POINT;
        let at_end = distance(p, first) <= SAME_POINT || distance(p, last) <= SAME_POINT;
        if at_end && !closed { 1 } else { 2 }
    }
}

/// Every junction of the paved roads `lines`, once per road through it, in road order and
/// then along the road: each point of a centreline where three or more arms meet.
pub fn junctions(lines: &[Centreline]) -> Vec<Junction> {
    let mut out = Vec::new();
    let mut seen: Vec<[f64; 2]> = Vec::new();
    for &p in lines.iter().flat_map(|line| line.points()) {
        if seen.iter().any(|&q| distance(p, q) <= SAME_POINT) {
            continue;
        }
        seen.push(p);
        // The roads through p: (road, arc length there, direction, half-width, arms).
        let through: Vec<(usize, f64, [f64; 2], f64, u32)> = lines
            .iter()
            .filter_map(|other| {
                let (s, at, dir, _) = other.locate(p, SAME_POINT)?;
                Some((other.road, at, dir, other.width(s) / 2.0, other.arms_at(p)))
            })
            .collect();
        if through.iter().map(|t| t.4).sum::<u32>() < 3 {
            continue;
        }
        for &(road, at, dir, half, _) in &through {
            let reach = through
                .iter()
                .filter(|o| o.0 != road)
                .filter_map(|&(_, _, other, other_half, _)| {
                    let cos = (dir[0] * other[0] + dir[1] * other[1]).abs().min(1.0);
                    let sin = (1.0 - cos * cos).sqrt();
                    // A shallower arm carries the road on (a way split at the junction).
                    (sin >= MIN_SINE).then(|| other_half / sin + half * cos / sin)
                })
                .fold(0.0, f64::max);
            out.push(Junction { road, at, reach });
        }
    }
    out.sort_by(|a, b| a.road.cmp(&b.road).then(a.at.total_cmp(&b.at)));
    out
}

/// The zebra crossings: each marked crossing node on a paved road, on the nearest road's
/// nearest segment (the first road of equals).
pub fn zebras(map: &OsmMap, lines: &[Centreline]) -> Vec<Zebra> {
    map.features
        .iter()
        .filter(|f| f.kind == FeatureKind::Crossing && !UNMARKED_CROSSING.contains(&f.tag.as_str()))
        .filter_map(|f| {
            lines
                .iter()
                .filter_map(|line| {
                    let (segment, at, _, d) = line.locate(f.at, ON_ROAD)?;
                    let road = line.road;
                    Some((d, Zebra { road, segment, at }))
                })
                .fold(None, |best: Option<(f64, Zebra)>, c| match best {
                    Some(b) if b.0 <= c.0 => Some(b),
                    _ => Some(c),
                })
                .map(|(_, z)| z)
        })
        .collect()
}

/// A map's paved roads' lines, its junctions and the zebras drawn: those clear of every
/// junction (a zebra reaching into a junction's carriageway is left out).
pub struct MapLines<'a> {
    pub lines: Vec<Centreline<'a>>,
    pub junctions: Vec<Junction>,
    pub zebras: Vec<Zebra>,
}

impl<'a> MapLines<'a> {
    pub fn of(map: &'a OsmMap) -> MapLines<'a> {
        let lines: Vec<Centreline> = (map.roads.iter().enumerate())
            .filter(|(_, r)| r.surface)
            .map(|(i, r)| Centreline::of(i, r))
            .collect();
        let junctions = junctions(&lines);
        let zebras: Vec<Zebra> = zebras(map, &lines)
            .into_iter()
            .filter(|z| {
                (junctions.iter())
                    .filter(|j| j.road == z.road)
                    .all(|j| (z.at - j.at).abs() >= j.reach + ZEBRA_DEPTH / 2.0)
            })
            .collect();
        MapLines {
            lines,
            junctions,
            zebras,
        }
    }

    /// The line of road `road`.
    pub fn line(&self, road: usize) -> Option<&Centreline<'a>> {
        self.lines.iter().find(|l| l.road == road)
    }
}
