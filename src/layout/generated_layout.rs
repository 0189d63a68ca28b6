//! `generate`: `GenerateSpec` + palette + the layout stream → a random layout image
//! (paper 3.1) with the roads and blue blocks it drew ([`GeneratedLayout`]).

use image::{Rgb, RgbImage};
use rand::RngExt;
use rand_pcg::Pcg64;

use crate::model::{Axis, GeneratedLayout, PxRect, Road};
use crate::spec::{Color, GenerateSpec, Palette};

/// Paper 3.1. `rng` is the layout stage's stream.
///
/// Full-span horizontal and vertical roads at random positions: each road's top (or left)
/// edge is drawn uniformly among the placements that keep every block's blue area at least
/// `min_block` px high (or wide) and keep roads off the image edge. Road pixels are
/// `palette.road`; a 1-px `palette.line` centre line runs along every road at offset
/// `road_width / 2` from its top/left edge, drawn through the crossings; every block's blue
/// area is ringed by `strip_width` px of `palette.strip`, also along the image border.
///
/// If the requested number of roads cannot fit, as many as fit are drawn (the spec stage
/// rejects impossible counts before this runs). With no room for a road across a side, that
/// side is one block, even if narrower than `min_block`; a side of at most `2·strip_width`
/// px has no blue at all. Horizontal positions are drawn before vertical ones.
pub fn generate(spec: &GenerateSpec, palette: &Palette, rng: &mut Pcg64) -> GeneratedLayout {
    let (width, height) = (spec.width, spec.height);
    let rows = place_roads(height, spec.horizontal_roads, spec, rng);
    let columns = place_roads(width, spec.vertical_roads, spec, rng);
    let rw = spec.road_width;

    let mut image = RgbImage::from_pixel(width, height, Rgb(palette.strip.0));
    let blocks = fill_blocks(&mut image, &rows, &columns, spec, palette);
    let crossing = [(Axis::Horizontal, &rows), (Axis::Vertical, &columns)];
    let mut roads = Vec::with_capacity(rows.len() + columns.len());
    for (axis, starts) in crossing {
        let length = match axis {
            Axis::Horizontal => width,
            Axis::Vertical => height,
        };
        for &at in starts {
            fill(
                &mut image,
                band(axis, at, rw, [width, height]),
                palette.road,
            );
            roads.push(full_span_road(axis, at, rw, length));
        }
    }
    // Lines last, so that they run unbroken through the crossings.
    for (axis, starts) in crossing {
        for &at in starts {
            let line = band(axis, at + rw / 2, 1, [width, height]);
            fill(&mut image, line, palette.line);
        }
    }
    for (id, road) in roads.iter_mut().enumerate() {
        road.id = id as u32;
    }

    GeneratedLayout {
        image,
        roads,
        blocks,
    }
}

/// Fills the blue of every block between the roads (`rows` and `columns`: their top or
/// left edges), `strip_width` in from its edges; returns the blocks, row by row.
fn fill_blocks(
    image: &mut RgbImage,
    rows: &[u32],
    columns: &[u32],
    spec: &GenerateSpec,
    palette: &Palette,
) -> Vec<PxRect> {
    let (rw, strip) = (spec.road_width, spec.strip_width);
    let mut blocks = Vec::new();
    for &(y0, y1) in &gaps(rows, rw, spec.height) {
        for &(x0, x1) in &gaps(columns, rw, spec.width) {
            let blue = PxRect {
                x0: x0 + strip,
                y0: y0 + strip,
                x1: x1.saturating_sub(strip),
                y1: y1.saturating_sub(strip),
            };
            if blue.x0 < blue.x1 && blue.y0 < blue.y1 {
                fill(image, blue, palette.block);
                blocks.push(blue);
            }
        }
    }
    blocks
}

/// The band `thickness` px thick from `at` across the whole `[width, height]` image:
/// rows for a horizontal road, columns for a vertical one.
fn band(axis: Axis, at: u32, thickness: u32, [width, height]: [u32; 2]) -> PxRect {
    match axis {
        Axis::Horizontal => PxRect {
            x0: 0,
            y0: at,
            x1: width,
            y1: at + thickness,
        },
        Axis::Vertical => PxRect {
            x0: at,
            y0: 0,
            x1: at + thickness,
            y1: height,
        },
    }
}

/// Top (or left) edges of up to `count` roads across an `extent`-px side, ascending.
///
/// Every gap between roads (and between a road and the image edge) holds a strip, a blue
/// area of at least `min_block` px and another strip. The slack left after the minimum gaps
/// is cut at `count` uniform random points, so every valid placement is possible.
fn place_roads(extent: u32, count: u32, spec: &GenerateSpec, rng: &mut Pcg64) -> Vec<u32> {
    let rw = u64::from(spec.road_width);
    let cell = 2 * u64::from(spec.strip_width) + u64::from(spec.min_block);
    let extent = u64::from(extent);
    let need = |n: u64| n * rw + (n + 1) * cell;
    let mut n = u64::from(count);
    while n > 0 && need(n) > extent {
        n -= 1;
    }
    if n == 0 {
        return Vec::new();
    }
    let slack = extent - need(n);
    let mut cuts: Vec<u64> = (0..n).map(|_| rng.random_range(0..=slack)).collect();
    cuts.sort_unstable();
    cuts.iter()
        .enumerate()
        .map(|(i, &cut)| {
            let i = i as u64;
            ((i + 1) * cell + i * rw + cut) as u32
        })
        .collect()
}

/// The `[start, end)` intervals between roads (and the image edges) along one side.
fn gaps(starts: &[u32], rw: u32, extent: u32) -> Vec<(u32, u32)> {
    let mut out = Vec::with_capacity(starts.len() + 1);
    let mut from = 0;
    for &start in starts {
        out.push((from, start));
        from = start + rw;
    }
    out.push((from, extent));
    out
}

/// The road a full-span road with top/left edge `edge` must parse to.
fn full_span_road(axis: Axis, edge: u32, rw: u32, length: u32) -> Road {
    Road {
        id: 0,
        axis,
        start: 0.0,
        end: f64::from(length),
        line: f64::from(edge + rw / 2) + 0.5,
        edges: [f64::from(edge), f64::from(edge + rw)],
    }
}

/// Paints `rect` (clipped to the image) with `color`.
fn fill(image: &mut RgbImage, rect: PxRect, color: Color) {
    let (width, height) = image.dimensions();
    let (x0, x1) = (rect.x0.min(width) as usize, rect.x1.min(width) as usize);
    let (y0, y1) = (rect.y0.min(height), rect.y1.min(height));
    if x0 >= x1 {
        return;
    }
    let stride = width as usize * 3;
    for y in y0..y1 {
        let row = &mut image.as_mut()[y as usize * stride..][..stride];
        for px in row[x0 * 3..x1 * 3].chunks_exact_mut(3) {
            px.copy_from_slice(&color.0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::stream;

    fn spec(width: u32, height: u32, h: u32, v: u32) -> GenerateSpec {
        GenerateSpec {
            width,
            height,
            horizontal_roads: h,
            vertical_roads: v,
            ..GenerateSpec::default()
        }
    }

    fn layout(spec: &GenerateSpec, seed: u64) -> GeneratedLayout {
        generate(spec, &Palette::default(), &mut stream(seed, "layout", 0))
    }

    #[test]
    fn same_seed_same_bytes_other_seed_other_layout() {
        let spec = GenerateSpec::default();
        let a = layout(&spec, 1);
        let b = layout(&spec, 1);
        let c = layout(&spec, 2);
        assert_eq!(a.image.as_raw(), b.image.as_raw());
        assert_eq!(a, b);
        assert_ne!(a.roads, c.roads);
        assert_ne!(a.image.as_raw(), c.image.as_raw());
    }

    #[test]
    fn default_layout_has_the_papers_shape() {
        let spec = GenerateSpec::default();
        let palette = Palette::default();
        let out = layout(&spec, 7);
        assert_eq!(out.image.dimensions(), (768, 768));
        assert_eq!(out.roads.len(), 6);
        assert_eq!(out.blocks.len(), 16);
        let px = |x: u32, y: u32| Color(out.image.get_pixel(x, y).0);
        // The image border is lamp strip, except where the roads run off the image.
        let on_road = |x: u32, y: u32| {
            out.roads.iter().any(|r| {
                let across = if r.axis == Axis::Horizontal { y } else { x };
                r.edges[0] <= f64::from(across) && f64::from(across) < r.edges[1]
            })
        };
        for i in 0..768 {
            for (x, y) in [(i, 0), (0, i), (i, 767), (767, i)] {
                let expected = if on_road(x, y) {
                    [palette.road, palette.line]
                } else {
                    [palette.strip; 2]
                };
                assert!(expected.contains(&px(x, y)), "({x},{y}) is {}", px(x, y));
            }
        }
        // No road is at the image edge.
        for road in &out.roads {
            assert!(
                road.edges[0] >= 80.0 && road.edges[1] <= 768.0 - 80.0,
                "{road:?}"
            );
        }
        for road in &out.roads {
            assert_eq!(road.width(), 32.0);
            let line = road.line.floor() as u32;
            let low = road.edges[0] as u32;
            assert_eq!(line - low, 16);
            // Along a road away from crossings: edge rows grey, line yellow, strip outside.
            let probe = out.blocks[0].x0 + 1; // a position inside no crossing
            let at = |across: u32| match road.axis {
                Axis::Horizontal => px(probe.min(767), across),
                Axis::Vertical => px(across, out.blocks[0].y0 + 1),
            };
            assert_eq!(at(line), palette.line);
            assert_eq!(at(low), palette.road);
            assert_eq!(at(low + 31), palette.road);
            assert_eq!(at(low - 1), palette.strip);
            assert_eq!(at(low + 32), palette.strip);
        }
        for block in &out.blocks {
            assert!(block.width() >= spec.min_block && block.height() >= spec.min_block);
            assert_eq!(px(block.x0, block.y0), palette.block);
            assert_eq!(px(block.x1 - 1, block.y1 - 1), palette.block);
            for (x, y) in [(block.x0 - 1, block.y0), (block.x0, block.y0 - 1)] {
                assert_eq!(px(x, y), palette.strip);
            }
            // Eight px of strip, then road or the border.
            let below = block.y1 + spec.strip_width;
            assert_eq!(px(block.x0, below - 1), palette.strip);
            assert!(below == 768 || px(block.x0, below) == palette.road);
        }
    }

    #[test]
    fn fits_as_many_roads_as_there_is_room_for() {
        // (width, height, requested h, requested v, expected h, expected v)
        // A gap needs 2·8 + 64 = 80 px, a road 32: n roads need 32n + 80(n + 1).
        let cases = [
            (768, 768, 3, 3, 3, 3),
            (768, 768, 64, 0, 6, 0),
            (192, 192, 1, 1, 1, 1),
            (191, 300, 1, 2, 1, 0),
            (79, 79, 2, 2, 0, 0),
            (64, 80, 0, 0, 0, 0),
        ];
        for (w, h, rh, rv, eh, ev) in cases {
            let out = layout(&spec(w, h, rh, rv), 3);
            let count = |axis| out.roads.iter().filter(|r| r.axis == axis).count() as u32;
            assert_eq!(
                (count(Axis::Horizontal), count(Axis::Vertical)),
                (eh, ev),
                "{w}×{h} asking {rh}+{rv}"
            );
            let blues = out.image.pixels().filter(|p| p.0 == [40, 80, 220]).count() as u64;
            let area: u64 = out
                .blocks
                .iter()
                .map(|b| u64::from(b.width() * b.height()))
                .sum();
            assert_eq!(blues, area);
            // Without roads the whole image is one block, even below `min_block`.
            assert_eq!(out.blocks.len() as u32, (eh + 1) * (ev + 1));
        }
    }

    #[test]
    fn placements_vary_over_the_whole_slack() {
        // One road in 192 px: 80 px above, 80 below, 32 of road and no slack → always at 80.
        // In 200 px there are 8 px of slack, so the 9 positions 80..=88 should all turn up.
        let mut seen = [false; 9];
        for seed in 0..200 {
            let out = layout(&spec(64, 200, 1, 0), seed);
            let top = out.roads[0].edges[0] as usize;
            assert!((80..=88).contains(&top), "top {top}");
            seen[top - 80] = true;
        }
        assert!(seen.iter().all(|&s| s), "{seen:?}");
        assert_eq!(
            layout(&spec(64, 192, 1, 0), 5).roads[0].edges,
            [80.0, 112.0]
        );
    }
}
