//! A map's blocks without buildings + building widths + gap + seed → buildings on them:
//! paper Algorithm 1, generalised to polygons.
//!
//! A map's block is a polygon at any angle, with holes. Each is filled in a frame of its
//! own: `u` along its longest outer edge (the street it most likely fronts), `v` across.
//! In that frame the block is cut into square cells of [`CELL`] metres (coarser for a
//! block so large it would need more than [`MAX_CELLS`]), and a cell belongs to the block
//! when it lies wholly inside it:
//!
//! - no ring edge touches it: each edge marks every cell it passes through, row by row,
//!   from its exact extent across the row (padded by a hair against rounding);
//! - its centre is inside (even-odd over the outer ring and the holes, by scanline).
//!
//! The map's open ground on the block (`OsmMap::green`: parks, grass, woods;
//! `OsmMap::squares`: squares, pedestrian areas, car parks) counts as more holes, so a
//! park keeps its grass, a square stays open, and buildings fill only the rest.
//!
//! Algorithm 1 then runs on those cells exactly as on a layout's pixels (`filler`), with
//! the widths and the gap in cells (rounded, at least one), from the block's own stream
//! `rng::stream(seed, "place", n)`, `n` the block's index in the map. Each square it places
//! becomes a footprint in metres, a square turned to the block's frame. So no building
//! leaves its block or meets a courtyard of it, and two of a block are at least the gap
//! apart along `u` or along `v`.

use rayon::prelude::*;

use super::{place_in_block, widths_px};
use crate::model::geometry::polygon::longest_side;
use crate::model::{Band, Block, MapBuilding, MapPolygon, OsmElement, OsmMap, PxRect};

/// Side of a cell, metres.
pub const CELL: f64 = 0.5;
/// Most cells one block is cut into; a larger block gets larger cells.
pub const MAX_CELLS: f64 = 4.0e6;

/// What the buildings are sized by: the widths in metres, and, when each width is a
/// facade's (the paper's rule), the facade heights that go with them.
pub struct Sizes<'a> {
    pub widths: &'a [f64],
    pub facade_heights: Option<&'a [f64]>,
    pub gap: f64,
}

/// Buildings on every block of `map` that has none (`OsmMap::block_is_built`), in block
/// order then placing order. Pure; the same for any number of threads.
pub fn place_map(map: &OsmMap, sizes: &Sizes, seed: u64) -> Vec<MapBuilding> {
    let per_block: Vec<Vec<MapBuilding>> = map
        .blocks
        .par_iter()
        .enumerate()
        .map(|(n, block)| {
            if map.block_is_built(block) {
                return Vec::new();
            }
            let open = map.open_on(n);
            fill_block(block, &open, n as u32, sizes, seed)
        })
        .collect();
    per_block.into_iter().flatten().collect()
}

/// Algorithm 1 on one block polygon, number `n` of the map's, less its `open` ground.
fn fill_block(
    block: &MapPolygon,
    open: &[&MapPolygon],
    n: u32,
    sizes: &Sizes,
    seed: u64,
) -> Vec<MapBuilding> {
    let Some(frame) = Frame::of(&block.outer) else {
        return Vec::new();
    };
    // Open ground lies inside its block, so its rings are more holes to the even-odd
    // test (and a hole in it, block again).
    let rings: Vec<Vec<[f64; 2]>> = std::iter::once(&block.outer)
        .chain(&block.holes)
        .chain(
            open.iter()
                .flat_map(|g| std::iter::once(&g.outer).chain(&g.holes)),
        )
        .map(|ring| ring.iter().map(|&p| frame.to_uv(p)).collect())
        .collect();
    let Some(grid) = Grid::of(&rings) else {
        return Vec::new();
    };
    let bands = grid.bands(&rings);
    let cells = Block {
        id: n,
        bbox: PxRect {
            x0: 0,
            y0: 0,
            x1: grid.w as u32,
            y1: grid.h as u32,
        },
        area: (bands.iter().flat_map(|b| &b.spans))
            .map(|s| u64::from(s[1] - s[0]))
            .sum(),
        outline: Vec::new(),
        bands,
    };
    let widths = widths_px(sizes.widths, grid.cell);
    let gap = (sizes.gap / grid.cell).round() as u32;
    place_in_block(&cells, &widths, gap, seed)
        .into_iter()
        .enumerate()
        .map(|(part, b)| {
            let f = b.footprint;
            let corner = |x: u32, y: u32| {
                frame.to_world([
                    grid.u0 + f64::from(x) * grid.cell,
                    grid.v0 + f64::from(y) * grid.cell,
                ])
            };
            let outer = vec![
                corner(f.x0, f.y0),
                corner(f.x1, f.y0),
                corner(f.x1, f.y1),
                corner(f.x0, f.y1),
            ];
            let height = sizes.facade_heights.map(|h| h[b.kind as usize]);
            MapBuilding {
                height,
                height_from: if height.is_some() { "facade" } else { "none" }.to_owned(),
                facade: sizes.facade_heights.map(|_| b.kind),
                ..MapBuilding::new(OsmElement::Placed(n), part as u32, outer, Vec::new())
            }
        })
        .collect()
}

/// A block's frame: `u` along its longest outer edge, `v` to its left (a turn, so rings
/// keep their orientation).
struct Frame {
    d: [f64; 2],
}

impl Frame {
    fn of(outer: &[[f64; 2]]) -> Option<Frame> {
        let d = longest_side(outer).filter(|_| outer.len() >= 3)?;
        Some(Frame { d })
    }

    fn to_uv(&self, p: [f64; 2]) -> [f64; 2] {
        let d = self.d;
        [p[0] * d[0] + p[1] * d[1], p[1] * d[0] - p[0] * d[1]]
    }

    fn to_world(&self, [u, v]: [f64; 2]) -> [f64; 2] {
        let d = self.d;
        [u * d[0] - v * d[1], u * d[1] + v * d[0]]
    }
}

/// The cells over a block's box in its frame.
struct Grid {
    u0: f64,
    v0: f64,
    cell: f64,
    w: usize,
    h: usize,
}

/// Rounding allowance when marking the cells an edge touches, metres.
const HAIR: f64 = 1e-9;

impl Grid {
    fn of(rings: &[Vec<[f64; 2]>]) -> Option<Grid> {
        let points = || rings.iter().flatten();
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in points() {
            lo = [lo[0].min(p[0]), lo[1].min(p[1])];
            hi = [hi[0].max(p[0]), hi[1].max(p[1])];
        }
        let (du, dv) = (hi[0] - lo[0], hi[1] - lo[1]);
        if !(du > 0.0 && dv > 0.0 && du.is_finite() && dv.is_finite()) {
            return None;
        }
        let cell = CELL.max((du * dv / MAX_CELLS).sqrt());
        Some(Grid {
            u0: lo[0],
            v0: lo[1],
            cell,
            w: (du / cell).ceil() as usize,
            h: (dv / cell).ceil() as usize,
        })
    }

    /// Cell column of `u` (may be outside the grid).
    fn column(&self, u: f64) -> i64 {
        ((u - self.u0) / self.cell).floor() as i64
    }

    /// The cells wholly inside the rings, as one band per row.
    fn bands(&self, rings: &[Vec<[f64; 2]>]) -> Vec<Band> {
        let mut touched = vec![false; self.w * self.h];
        for ring in rings {
            for (i, &a) in ring.iter().enumerate() {
                self.mark(a, ring[(i + 1) % ring.len()], &mut touched);
            }
        }
        (0..self.h)
            .map(|j| {
                let v = self.v0 + (j as f64 + 0.5) * self.cell;
                let mut crossings: Vec<f64> = Vec::new();
                for ring in rings {
                    for (i, &a) in ring.iter().enumerate() {
                        let b = ring[(i + 1) % ring.len()];
                        if (a[1] > v) != (b[1] > v) {
                            crossings.push(a[0] + (b[0] - a[0]) * (v - a[1]) / (b[1] - a[1]));
                        }
                    }
                }
                crossings.sort_by(f64::total_cmp);
                let row = &touched[j * self.w..][..self.w];
                let inside = |i: usize| {
                    let u = self.u0 + (i as f64 + 0.5) * self.cell;
                    !row[i] && crossings.iter().filter(|&&c| c <= u).count() % 2 == 1
                };
                let mut spans = Vec::new();
                let mut i = 0;
                while i < self.w {
                    if inside(i) {
                        let start = i;
                        while i < self.w && inside(i) {
                            i += 1;
                        }
                        spans.push([start as u32, i as u32]);
                    }
                    i += 1;
                }
                Band {
                    y0: j as u32,
                    y1: j as u32 + 1,
                    spans,
                }
            })
            .collect()
    }

    /// Marks every cell segment `a → b` touches: per row of cells its extent in `v`
    /// reaches, the columns of the part of it within the row's slab.
    fn mark(&self, a: [f64; 2], b: [f64; 2], touched: &mut [bool]) {
        let row = |v: f64| ((v - self.v0) / self.cell).floor() as i64;
        let (first, last) = (
            row(a[1].min(b[1]) - HAIR).max(0),
            row(a[1].max(b[1]) + HAIR).min(self.h as i64 - 1),
        );
        for j in first..=last {
            let (lo, hi) = (
                self.v0 + j as f64 * self.cell - HAIR,
                self.v0 + (j + 1) as f64 * self.cell + HAIR,
            );
            let dv = b[1] - a[1];
            let (t0, t1) = if dv == 0.0 {
                (0.0, 1.0)
            } else {
                let (s, e) = ((lo - a[1]) / dv, (hi - a[1]) / dv);
                (s.min(e).max(0.0), s.max(e).min(1.0))
            };
            if t0 > t1 {
                continue;
            }
            let (ua, ub) = (a[0] + (b[0] - a[0]) * t0, a[0] + (b[0] - a[0]) * t1);
            let from = self.column(ua.min(ub) - HAIR).max(0);
            let to = self.column(ua.max(ub) + HAIR).min(self.w as i64 - 1);
            for i in from..=to {
                touched[j as usize * self.w + i as usize] = true;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::MapArea;
    use crate::model::geometry::polygon::{contains, signed_area};
    use crate::test_support::street_map;

    /// A rectangle `w × h` centred on `c`, turned by `deg`, counter-clockwise in `[x, z]`.
    fn turned(c: [f64; 2], (w, h): (f64, f64), deg: f64) -> Vec<[f64; 2]> {
        let (s, k) = (libm::sin(deg.to_radians()), libm::cos(deg.to_radians()));
        [[-w, -h], [w, -h], [w, h], [-w, h]]
            .map(|[x, z]| [c[0] + (x * k - z * s) / 2.0, c[1] + (x * s + z * k) / 2.0])
            .to_vec()
    }

    fn polygon(outer: Vec<[f64; 2]>, holes: Vec<Vec<[f64; 2]>>) -> MapPolygon {
        let area = signed_area(&outer) + holes.iter().map(|h| signed_area(h)).sum::<f64>();
        MapPolygon { outer, holes, area }
    }

    /// The street map with four blocks: a turned rectangle with a turned courtyard, a
    /// triangle (every cell along its long sides is cut by them), the block the map's
    /// building stands in, and one too small for any building.
    fn map() -> OsmMap {
        let mut map = street_map();
        let mut courtyard = turned([60.0, 60.0], (20.0, 14.0), 20.0);
        courtyard.reverse();
        map.blocks = vec![
            polygon(turned([60.0, 60.0], (70.0, 45.0), 20.0), vec![courtyard]),
            polygon(
                vec![[-140.0, 50.0], [-60.0, 60.0], [-130.0, 95.0]],
                Vec::new(),
            ),
            polygon(turned([-110.0, 29.0], (30.0, 30.0), 0.0), Vec::new()),
            polygon(turned([100.0, -60.0], (6.0, 6.0), 45.0), Vec::new()),
        ];
        map
    }

    const WIDTHS: [f64; 3] = [8.0, 11.5, 15.0];

    fn placed(map: &OsmMap, heights: Option<&[f64]>) -> Vec<MapBuilding> {
        let sizes = Sizes {
            widths: &WIDTHS,
            facade_heights: heights,
            gap: 2.0,
        };
        place_map(map, &sizes, 7)
    }

    /// Whether `p` is in `block` (outer ring, not a courtyard).
    fn in_block(block: &MapPolygon, p: [f64; 2]) -> bool {
        contains(&block.outer, p) && !block.holes.iter().any(|h| contains(h, p))
    }

    /// The interval a footprint's corners cover along `axis`.
    fn along(b: &MapBuilding, axis: [f64; 2]) -> [f64; 2] {
        let t: Vec<f64> = b
            .outer
            .iter()
            .map(|p| p[0] * axis[0] + p[1] * axis[1])
            .collect();
        [
            t.iter().copied().fold(f64::INFINITY, f64::min),
            t.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        ]
    }

    #[test]
    fn empty_blocks_at_any_angle_are_filled_inside_and_apart_by_the_gap() {
        let map = map();
        let buildings = placed(&map, None);
        let of = |n: u32| -> Vec<&MapBuilding> {
            buildings
                .iter()
                .filter(|b| b.element == OsmElement::Placed(n))
                .collect()
        };
        assert!(of(0).len() >= 8, "{}", of(0).len());
        assert!(of(1).len() >= 3, "{}", of(1).len());
        assert!(
            of(2).is_empty(),
            "the block with the map's building is left as mapped"
        );
        assert!(of(3).is_empty(), "a 6 m block holds no 8 m building");
        for b in &buildings {
            let OsmElement::Placed(n) = b.element else {
                panic!("{:?}", b.element)
            };
            let block = &map.blocks[n as usize];
            // A square of one of the widths (rounded to cells), anticlockwise.
            let side = crate::model::geometry::polygon::distance(b.outer[0], b.outer[1]);
            assert!(
                WIDTHS.iter().any(|w| (w - side).abs() <= CELL / 2.0 + 1e-9),
                "{side}"
            );
            assert!(
                (b.area - side * side).abs() < 1e-6,
                "{} {}",
                b.area,
                side * side
            );
            // Wholly in its block: every point of a fine grid over the square, its
            // edges included.
            for i in 0..=40 {
                for j in 0..=40 {
                    let (s, t) = (f64::from(i) / 40.0, f64::from(j) / 40.0);
                    let p = [0, 1].map(|k| {
                        b.outer[0][k]
                            + (b.outer[1][k] - b.outer[0][k]) * s
                            + (b.outer[3][k] - b.outer[0][k]) * t
                    });
                    let p = [0, 1].map(|k| p[k] + (b.outer[2][k] - p[k]) * 1e-9);
                    assert!(
                        in_block(block, p),
                        "{:?} of {:?} outside block {n}",
                        p,
                        b.outer
                    );
                }
            }
            assert_eq!(
                (b.height, b.facade, b.height_from.as_str()),
                (None, None, "none")
            );
        }
        // Two of a block: the gap apart along one of the block's axes.
        for n in 0..2 {
            let own = of(n);
            let u = [0, 1].map(|k| own[0].outer[1][k] - own[0].outer[0][k]);
            let len = (u[0] * u[0] + u[1] * u[1]).sqrt();
            let (u, v) = ([u[0] / len, u[1] / len], [-u[1] / len, u[0] / len]);
            for (i, a) in own.iter().enumerate() {
                for b in &own[i + 1..] {
                    let apart = [u, v].iter().any(|&axis| {
                        let (x, y) = (along(a, axis), along(b, axis));
                        x[1] + 2.0 - 1e-6 <= y[0] || y[1] + 2.0 - 1e-6 <= x[0]
                    });
                    assert!(apart, "{:?} and {:?}", a.outer, b.outer);
                }
            }
        }
    }

    #[test]
    fn green_ground_and_squares_stay_open_and_the_rest_of_their_block_is_filled() {
        let mut map = map();
        let plain = placed(&map, None);
        // Green: a strip across block 0's west end, 15 m of its 70.
        let (k, s) = (libm::cos(20f64.to_radians()), libm::sin(20f64.to_radians()));
        let strip = polygon(
            turned([60.0 - 27.5 * k, 60.0 - 27.5 * s], (15.0, 45.0), 20.0),
            Vec::new(),
        );
        map.green = vec![MapArea {
            block: 0,
            shape: strip.clone(),
        }];
        // Block 1 a square.
        map.squares = vec![MapArea {
            block: 1,
            shape: map.blocks[1].clone(),
        }];
        let buildings = placed(&map, None);
        let in_0 = |bs: &[MapBuilding]| {
            bs.iter()
                .filter(|b| b.element == OsmElement::Placed(0))
                .count()
        };
        assert!(in_0(&buildings) >= 5, "{}", in_0(&buildings));
        assert!(
            buildings.iter().all(|b| b.element == OsmElement::Placed(0)),
            "the block that is a square stays open"
        );
        // Whether any point of a grid over `b`'s footprint lies on the strip.
        let on_grass = |b: &MapBuilding| {
            (0..=20).any(|i| {
                (0..=20).any(|j| {
                    let (s, t) = (f64::from(i) / 20.0, f64::from(j) / 20.0);
                    let p = [0, 1].map(|k| {
                        b.outer[0][k]
                            + (b.outer[1][k] - b.outer[0][k]) * s
                            + (b.outer[3][k] - b.outer[0][k]) * t
                    });
                    contains(&strip.outer, p)
                })
            })
        };
        assert!(
            plain.iter().any(on_grass),
            "without the green, the strip is built on"
        );
        assert!(
            !buildings.iter().any(on_grass),
            "with it, nothing stands on the grass"
        );
    }

    #[test]
    fn facade_sizes_give_the_facade_and_its_height_and_the_same_on_any_thread_count() {
        let map = map();
        let heights = [9.0, 15.0, 21.0];
        let buildings = placed(&map, Some(&heights));
        assert!(!buildings.is_empty());
        for b in &buildings {
            let kind = b.facade.expect("sized by a facade") as usize;
            let side = crate::model::geometry::polygon::distance(b.outer[0], b.outer[1]);
            assert!((WIDTHS[kind] - side).abs() <= CELL / 2.0 + 1e-9);
            assert_eq!(
                (b.height, b.height_from.as_str()),
                (Some(heights[kind]), "facade")
            );
        }
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        assert_eq!(one.install(|| placed(&map, Some(&heights))), buildings);
        // Another seed, other buildings.
        let sizes = Sizes {
            widths: &WIDTHS,
            facade_heights: Some(&heights),
            gap: 2.0,
        };
        assert_ne!(place_map(&map, &sizes, 8), buildings);
    }

    #[test]
    fn cells_cut_by_an_edge_are_not_the_blocks() {
        // A thin sliver along a diagonal: its centre cells lie inside, every one of them
        // is cut by an edge, so nothing fits in it.
        let ring = vec![[0.0, 0.0], [30.0, 30.0], [29.2, 30.0]];
        let frame = Frame::of(&ring).unwrap();
        let rings = vec![ring.iter().map(|&p| frame.to_uv(p)).collect::<Vec<_>>()];
        let grid = Grid::of(&rings).unwrap();
        let bands = grid.bands(&rings);
        assert!(bands.iter().all(|b| b.spans.is_empty()), "{bands:?}");
        // A square in the same frame keeps all its inner cells.
        let square: Vec<[f64; 2]> = vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]];
        let grid = Grid::of(std::slice::from_ref(&square)).unwrap();
        let bands = grid.bands(&[square]);
        let cells: u32 = bands
            .iter()
            .flat_map(|b| &b.spans)
            .map(|s| s[1] - s[0])
            .sum();
        assert_eq!(
            cells,
            18 * 18,
            "the ring of cells its edges touch is left out"
        );
    }
}
