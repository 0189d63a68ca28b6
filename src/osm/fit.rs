//! Roads fitted between the mapped buildings: each paved segment's carriageway and
//! sidewalks narrowed where a building stands closer than the road's nominal
//! cross-section, so no building stands on a road or a sidewalk.
//!
//! Per segment of a road with a surface: the nearest building on its left and on its
//! right (each building edge counts on the side its closest point lies), less a
//! [`MARGIN`]; the carriageway keeps its nominal half-width or the nearer of the two,
//! whichever is less, and each sidewalk what is left on its side. A carriageway narrower
//! than [`MIN_CARRIAGEWAY`] (a building across the road: a passage the map does not tag, or
//! a mapping error) is not paved.

use crate::model::geometry::polygon::{contains, nearest};
use crate::model::{LeftOut, MapBuilding, MapRoad};

/// Clearance kept between a paved surface and a building, metres.
pub const MARGIN: f64 = 0.1;
/// The narrowest carriageway paved, metres.
pub const MIN_CARRIAGEWAY: f64 = 2.5;
/// Side of the grid cells buildings are looked up in, metres.
const CELL: f64 = 32.0;

/// Building edges by grid cell.
struct Grid {
    origin: [f64; 2],
    columns: usize,
    rows: usize,
    /// Per cell: (building, ring, edge start index).
    cells: Vec<Vec<(u32, u32, u32)>>,
}

impl Grid {
    fn new(extent: [f64; 4], buildings: &[MapBuilding]) -> Grid {
        let columns = (((extent[2] - extent[0]) / CELL).ceil() as usize).max(1);
        let rows = (((extent[3] - extent[1]) / CELL).ceil() as usize).max(1);
        let mut grid = Grid {
            origin: [extent[0], extent[1]],
            columns,
            rows,
            cells: vec![Vec::new(); columns * rows],
        };
        for (b, building) in buildings.iter().enumerate() {
            for (r, ring) in rings(building).enumerate() {
                for e in 0..ring.len() {
                    let (p, q) = (ring[e], ring[(e + 1) % ring.len()]);
                    for cell in grid.cells_of(p, q, 0.0) {
                        grid.cells[cell].push((b as u32, r as u32, e as u32));
                    }
                }
            }
        }
        grid
    }

    /// The cells the box of `p`–`q`, grown by `reach`, touches.
    fn cells_of(
        &self,
        p: [f64; 2],
        q: [f64; 2],
        reach: f64,
    ) -> impl Iterator<Item = usize> + use<> {
        let cell =
            |v: f64, o: f64, n: usize| (((v - o) / CELL).floor().max(0.0) as usize).min(n - 1);
        let (c0, c1) = (
            cell(p[0].min(q[0]) - reach, self.origin[0], self.columns),
            cell(p[0].max(q[0]) + reach, self.origin[0], self.columns),
        );
        let (r0, r1) = (
            cell(p[1].min(q[1]) - reach, self.origin[1], self.rows),
            cell(p[1].max(q[1]) + reach, self.origin[1], self.rows),
        );
        let columns = self.columns;
        (r0..=r1).flat_map(move |r| (c0..=c1).map(move |c| r * columns + c))
    }
}

fn rings(b: &MapBuilding) -> impl Iterator<Item = &Vec<[f64; 2]>> {
    std::iter::once(&b.outer).chain(&b.holes)
}

/// Fits every road with a surface between `buildings` (inside `extent`).
pub fn fit(
    roads: &mut [MapRoad],
    buildings: &[MapBuilding],
    extent: [f64; 4],
    left_out: &mut LeftOut,
) {
    let grid = Grid::new(extent, buildings);
    let mut candidates: Vec<(u32, u32, u32)> = Vec::new();
    for road in roads.iter_mut().filter(|r| r.surface) {
        let half = road.width / 2.0;
        let [left, right] = road.sidewalks;
        let reach = half + left.max(right) + MARGIN;
        road.fitted = road
            .centreline
            .windows(2)
            .map(|w| {
                candidates.clear();
                candidates.extend(
                    grid.cells_of(w[0], w[1], reach)
                        .flat_map(|c| grid.cells[c].iter().copied()),
                );
                candidates.sort_unstable();
                candidates.dedup();
                let [dl, dr] = clearance(w[0], w[1], &candidates, buildings);
                let carriageway = half.min(dl - MARGIN).min(dr - MARGIN);
                if carriageway * 2.0 < MIN_CARRIAGEWAY {
                    left_out.segments_blocked += 1;
                    return [0.0; 3];
                }
                let l = left.min(dl - MARGIN - carriageway).max(0.0);
                let r = right.min(dr - MARGIN - carriageway).max(0.0);
                if carriageway < half || l < left || r < right {
                    left_out.segments_narrowed += 1;
                }
                [carriageway * 2.0, l, r]
            })
            .collect();
    }
}

/// The distance from segment `p`–`q` to the nearest of `edges` on its left and on its
/// right (x east, z south: left of the direction `p → q`); 0 on both sides when an edge
/// crosses the segment or the segment lies inside a building.
fn clearance(
    p: [f64; 2],
    q: [f64; 2],
    edges: &[(u32, u32, u32)],
    buildings: &[MapBuilding],
) -> [f64; 2] {
    let mut near = [f64::INFINITY; 2];
    let d = [q[0] - p[0], q[1] - p[1]];
    let mid = [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0];
    let mut last = None;
    for &(b, r, e) in edges {
        let building = &buildings[b as usize];
        if last != Some(b) {
            last = Some(b);
            let in_hole = building.holes.iter().any(|h| contains(h, mid));
            if contains(&building.outer, mid) && !in_hole {
                return [0.0; 2];
            }
        }
        let ring = rings(building).nth(r as usize).expect("the grid's ring");
        let (a, c) = (ring[e as usize], ring[(e as usize + 1) % ring.len()]);
        if crosses(p, q, a, c) {
            return [0.0; 2];
        }
        // The closest pair is an end of one segment and its nearest point on the other.
        for (road_point, building_point) in [
            (nearest(p, q, a), a),
            (nearest(p, q, c), c),
            (p, nearest(a, c, p)),
            (q, nearest(a, c, q)),
        ] {
            let v = [
                building_point[0] - road_point[0],
                building_point[1] - road_point[1],
            ];
            let dist = (v[0] * v[0] + v[1] * v[1]).sqrt();
            // Left of the direction (x east, z south): d × v < 0.
            let cross = d[0] * v[1] - d[1] * v[0];
            if cross <= 0.0 {
                near[0] = near[0].min(dist);
            }
            if cross >= 0.0 {
                near[1] = near[1].min(dist);
            }
        }
    }
    near
}

/// Whether segments `p`–`q` and `a`–`b` cross or touch.
fn crosses(p: [f64; 2], q: [f64; 2], a: [f64; 2], b: [f64; 2]) -> bool {
    let side = |o: [f64; 2], s: [f64; 2], t: [f64; 2]| {
        (s[0] - o[0]) * (t[1] - o[1]) - (s[1] - o[1]) * (t[0] - o[0])
    };
    let (d1, d2) = (side(a, b, p), side(a, b, q));
    let (d3, d4) = (side(p, q, a), side(p, q, b));
    ((d1 > 0.0) != (d2 > 0.0) || d1 == 0.0 || d2 == 0.0)
        && ((d3 > 0.0) != (d4 > 0.0) || d3 == 0.0 || d4 == 0.0)
        && boxes_meet(p, q, a, b)
}

fn boxes_meet(p: [f64; 2], q: [f64; 2], a: [f64; 2], b: [f64; 2]) -> bool {
    (0..2).all(|i| p[i].min(q[i]) <= a[i].max(b[i]) && a[i].min(b[i]) <= p[i].max(q[i]))
}
