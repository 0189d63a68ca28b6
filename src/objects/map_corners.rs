//! A map's street corners: where two paved roads with different `name`s meet at a node,
//! the corners between them (four where they cross, two at a T), each half the
//! sidewalk's width from both kerbs, for
//! street-name signs (`street_names::place_at`) naming the two streets as the map does.
//!
//! Roads meeting at an angle whose sine is under [`MIN_SINE`] (about 17°) make no corner,
//! nor a side without a sidewalk [`MIN_SIDEWALK`] wide. A corner is kept when it stands
//! [`POLE_ROOM`] off every carriageway, out of the buildings and [`POLE_ROOM`] from their
//! walls, and inside the box; its sign stands when its plates' circle keeps out of the
//! buildings too (`map_objects`).

use std::collections::BTreeMap;

use super::street_names::NamedCorner;
use crate::model::geometry::map_lines::MIN_SINE;
use crate::model::geometry::polygon::{direction, distance};
use crate::model::{OsmMap, PavedSegment};
use crate::spec::TextCase;

/// How far a corner's pole keeps from a carriageway's edge and a building's wall, metres.
pub const POLE_ROOM: f64 = 0.3;
/// The narrowest sidewalk a corner's pole stands on, metres.
pub const MIN_SIDEWALK: f64 = 1.0;

/// A paved road at a node: its road, the unit direction of its segment there, half its
/// carriageway and its sidewalks (left, right of the direction), and where it ends at the
/// node, the direction it leaves in.
#[derive(Clone, Copy)]
struct Arm {
    road: usize,
    along: [f64; 2],
    half: f64,
    sidewalks: [f64; 2],
    away: Option<[f64; 2]>,
}

/// Every corner of `map` between two differently named paved roads, node by node (in
/// the order of their positions), pair by pair in road order, the four quadrants in a
/// fixed order; names in `case` (title and mixed: as the map spells them).
pub fn map_corners(map: &OsmMap, case: TextCase) -> Vec<NamedCorner> {
    // The nodes of the named paved roads, keyed by their position in centimetres.
    let mut nodes: BTreeMap<(i64, i64), ([f64; 2], Vec<Arm>)> = BTreeMap::new();
    for (road, r) in map.roads.iter().enumerate() {
        if !r.surface || r.name.is_none() {
            continue;
        }
        let line = &r.centreline;
        let (first, last) = (line[0], line[line.len() - 1]);
        let closed = distance(first, last) < 0.01;
        for (w, f) in line.windows(2).zip(&r.fitted) {
            let Some(along) = direction(w[0], w[1]).filter(|_| f[0] > 0.0) else {
                continue;
            };
            for (p, out) in [(w[0], along), (w[1], [-along[0], -along[1]])] {
                let key = ((p[0] * 100.0).round() as i64, (p[1] * 100.0).round() as i64);
                let arms = &mut nodes.entry(key).or_insert((p, Vec::new())).1;
                let ends = !closed && (p == first || p == last);
                if arms.iter().all(|a| a.road != road) {
                    let (half, sidewalks) = (f[0] / 2.0, [f[1], f[2]]);
                    let away = ends.then_some(out);
                    arms.push(Arm {
                        road,
                        along,
                        half,
                        sidewalks,
                        away,
                    });
                }
            }
        }
    }
    let name = |road: usize| {
        let name = map.roads[road].name.clone().unwrap_or_default();
        match case {
            TextCase::Upper => name.to_uppercase(),
            TextCase::Lower => name.to_lowercase(),
            _ => name,
        }
    };
    // A pole stands off every carriageway and out of the buildings by `POLE_ROOM`, inside
    // the box.
    let paved: Vec<PavedSegment> = map.paved_segments().collect();
    let clear = |p: [f64; 2]| map.holds(p, 0.0) && map.clear_ground(&paved, None, p, POLE_ROOM);
    let mut out = Vec::new();
    for (p, arms) in nodes.values() {
        for (i, a) in arms.iter().enumerate() {
            for b in &arms[i + 1..] {
                if map.roads[a.road].name == map.roads[b.road].name {
                    continue;
                }
                for position in quadrants(*p, a, b) {
                    if clear(position) {
                        out.push(NamedCorner {
                            position,
                            streets: [(name(a.road), a.along), (name(b.road), b.along)],
                        });
                    }
                }
            }
        }
    }
    out
}

/// The corners between arms `a` and `b` at `p`: per side of each, the point half its
/// sidewalk beyond both kerbs (none at a shallow angle or beside a narrow sidewalk, and
/// where a road ends at `p`, only on the side of the other it leaves to: a T has two).
fn quadrants(p: [f64; 2], a: &Arm, b: &Arm) -> Vec<[f64; 2]> {
    let cross = a.along[0] * b.along[1] - a.along[1] * b.along[0];
    if cross.abs() < MIN_SINE {
        return Vec::new();
    }
    let right = |t: [f64; 2]| [-t[1], t[0]];
    let (na, nb) = (right(a.along), right(b.along));
    let mut out = Vec::new();
    for (sa, sb) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
        let (wa, wb) = (
            a.sidewalks[usize::from(sa > 0.0)],
            b.sidewalks[usize::from(sb > 0.0)],
        );
        let dot = |d: [f64; 2], n: [f64; 2]| d[0] * n[0] + d[1] * n[1];
        let beside =
            |arm: &Arm, n: [f64; 2], side: f64| arm.away.is_none_or(|d| dot(d, n) * side > 0.0);
        if wa < MIN_SIDEWALK || wb < MIN_SIDEWALK || !beside(b, na, sa) || !beside(a, nb, sb) {
            continue;
        }
        let (da, db) = (sa * (a.half + wa / 2.0), sb * (b.half + wb / 2.0));
        // p + da·na + λ·ta = p + db·nb + μ·tb, for λ.
        let c = [db * nb[0] - da * na[0], db * nb[1] - da * na[1]];
        let lambda = (c[0] * b.along[1] - c[1] * b.along[0]) / cross;
        out.push([
            p[0] + da * na[0] + lambda * a.along[0],
            p[1] + da * na[1] + lambda * a.along[1],
        ]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::street_map;

    /// The street map with road 0 (two-way, 12 m, 3 m sidewalks, eastwards along z = 0)
    /// noded at x −50, where road 1 (one-way, 8 m, 2 m sidewalks) leaves it southwards: a
    /// T junction; both roads named.
    fn named_map() -> OsmMap {
        let mut map = street_map();
        let road = &mut map.roads[0];
        road.centreline = vec![[-150.0, 0.0], [-50.0, 0.0], [0.0, 0.0], [100.0, -100.0]];
        road.fitted = vec![[12.0, 3.0, 3.0]; 3];
        road.name = Some("Mannerheimintie".to_owned());
        map.roads[1].name = Some("Kalevankatu".to_owned());
        map
    }

    #[test]
    fn a_t_junction_has_two_corners_half_a_sidewalk_from_both_kerbs() {
        let map = named_map();
        let corners = map_corners(&map, TextCase::Title);
        let mut at: Vec<[f64; 2]> = corners.iter().map(|c| c.position).collect();
        at.sort_by(|a, b| a.partial_cmp(b).expect("finite"));
        // South of road 0 (where road 1 goes), 6 + 1.5 m from its centreline, and 4 + 1 m
        // either side of road 1's.
        let want = [[-55.0, 7.5], [-45.0, 7.5]];
        assert_eq!(at.len(), 2, "{corners:?}");
        for (got, want) in at.iter().zip(want) {
            assert!(distance(*got, want) < 1e-9, "{got:?} != {want:?}");
        }
        for c in &corners {
            let names: Vec<&str> = c.streets.iter().map(|s| s.0.as_str()).collect();
            assert_eq!(names, ["Mannerheimintie", "Kalevankatu"]);
            assert_eq!(c.streets[0].1, [1.0, 0.0]);
            assert_eq!(c.streets[1].1, [0.0, 1.0]);
        }
        let upper = map_corners(&map, TextCase::Upper);
        assert_eq!(upper[0].streets[0].0, "MANNERHEIMINTIE");
    }

    #[test]
    fn crossing_roads_have_four_corners_and_one_name_or_none_makes_none() {
        // Road 1 carried on north across road 0: a crossing.
        let mut map = named_map();
        map.roads[1].centreline = vec![[-50.0, -60.0], [-50.0, 0.0], [-50.0, 100.0]];
        map.roads[1].fitted = vec![[8.0, 2.0, 2.0]; 2];
        assert_eq!(map_corners(&map, TextCase::Title).len(), 4);
        // The same name on both: one street, no corner.
        map.roads[1].name = map.roads[0].name.clone();
        assert!(map_corners(&map, TextCase::Title).is_empty());
        // An unnamed road: no corner.
        map.roads[1].name = None;
        assert!(map_corners(&map, TextCase::Title).is_empty());
        // Without sidewalks, nowhere to stand.
        let mut map = named_map();
        map.roads[1].fitted = vec![[8.0, 0.0, 0.0]];
        assert!(map_corners(&map, TextCase::Title).is_empty());
        // A building on the corner.
        let mut map = named_map();
        map.buildings[0].outer = vec![[-58.0, 5.0], [-53.0, 5.0], [-53.0, 10.0], [-58.0, 10.0]];
        let corners = map_corners(&map, TextCase::Title);
        assert_eq!(corners.len(), 1);
        assert!(distance(corners[0].position, [-45.0, 7.5]) < 1e-9);
    }
}
