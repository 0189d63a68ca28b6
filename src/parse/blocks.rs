//! Blocks: class map → the building blocks, one per 4-connected region of block pixels.

use super::class_map::ClassMap;
use super::run_table::{Run, RunRule, RunTable};
use crate::model::PixelClass;
use crate::model::{Band, Block, PxRect};

/// Regions of fewer block pixels than this are specks (JPEG noise, stray anti-aliasing) and
/// are dropped. A real block is at least `min_block`² ≥ 64 px; 16 px is a 4×4 square.
pub const MIN_BLOCK_AREA: u64 = 16;

/// The blocks of `map`, in raster order of their first pixel, with ids in that order.
///
/// Regions come from row runs of block pixels joined where they share a column with a run in
/// the next row (4-connectivity): the runs are the block's exact pixels, so the bands fall
/// out directly, and no per-pixel label image is needed.
pub fn find_blocks(map: &ClassMap) -> Vec<Block> {
    let rule = RunRule {
        classes: &[PixelClass::Block],
        bridge: 0,
        min_len: 1,
    };
    RunTable::rows(map, rule)
        .groups()
        .into_iter()
        .filter(|runs| area(runs) >= MIN_BLOCK_AREA)
        .enumerate()
        .map(|(id, runs)| block(id as u32, &runs))
        .collect()
}

fn area(runs: &[(u32, Run)]) -> u64 {
    runs.iter().map(|(_, r)| u64::from(r[1] - r[0])).sum()
}

/// The block made of `runs` (row, span), in raster order.
fn block(id: u32, runs: &[(u32, Run)]) -> Block {
    let bbox = PxRect {
        x0: runs.iter().map(|(_, r)| r[0]).min().unwrap_or(0),
        y0: runs.first().map_or(0, |(y, _)| *y),
        x1: runs.iter().map(|(_, r)| r[1]).max().unwrap_or(0),
        y1: runs.last().map_or(0, |(y, _)| y + 1),
    };
    Block {
        id,
        bbox,
        area: area(runs),
        outline: outline(runs, bbox),
        bands: bands(runs),
    }
}

/// Rows merged into bands while their spans are identical.
fn bands(runs: &[(u32, Run)]) -> Vec<Band> {
    let mut bands: Vec<Band> = Vec::new();
    for row in runs.chunk_by(|a, b| a.0 == b.0) {
        let y = row[0].0;
        let spans: Vec<[u32; 2]> = row.iter().map(|(_, r)| *r).collect();
        match bands.last_mut() {
            Some(band) if band.y1 == y && band.spans == spans => band.y1 += 1,
            _ => bands.push(Band {
                y0: y,
                y1: y + 1,
                spans,
            }),
        }
    }
    bands
}

/// The 8 neighbour offsets, clockwise on screen starting west (Suzuki–Abe's order).
const NEIGHBOURS: [[i64; 2]; 8] = [
    [-1, 0],
    [-1, -1],
    [0, -1],
    [1, -1],
    [1, 0],
    [1, 1],
    [0, 1],
    [-1, 1],
];

/// The outer contour, simplified to its corners.
///
/// The contour is the outer border of Suzuki and Abe's border following, as OpenCV's
/// `findContours` and imageproc's `find_contours` trace it (a test checks the points are
/// the same as imageproc's), but followed on the runs: the cost is the perimeter, not the
/// bounding box, and no mask image is needed.
fn outline(runs: &[(u32, Run)], bbox: PxRect) -> Vec<[u32; 2]> {
    let shape = Shape::new(runs, bbox);
    corners(&shape.outer_border())
        .into_iter()
        .map(|[x, y]| [x as u32, y as u32])
        .collect()
}

/// A block's pixels, row by row, for membership tests.
struct Shape<'a> {
    y0: i64,
    /// `rows[y - y0]` is the spans of row `y`.
    rows: Vec<&'a [(u32, Run)]>,
}

impl<'a> Shape<'a> {
    fn new(runs: &'a [(u32, Run)], bbox: PxRect) -> Shape<'a> {
        let rows = runs.chunk_by(|a, b| a.0 == b.0).collect();
        Shape {
            y0: i64::from(bbox.y0),
            rows,
        }
    }

    fn contains(&self, [x, y]: [i64; 2]) -> bool {
        let Ok(row) = usize::try_from(y - self.y0) else {
            return false;
        };
        let Some(spans) = self.rows.get(row) else {
            return false;
        };
        let after = spans.partition_point(|(_, r)| i64::from(r[0]) <= x);
        after > 0 && x < i64::from(spans[after - 1].1[1])
    }

    /// Suzuki–Abe border following from the first pixel in raster order (whose west
    /// neighbour is background), clockwise on screen.
    fn outer_border(&self) -> Vec<[i64; 2]> {
        let Some(&(_, [x, _])) = self.rows.first().and_then(|r| r.first()) else {
            return Vec::new();
        };
        let start = [i64::from(x), self.y0];
        let step = |p: [i64; 2], k: usize| [p[0] + NEIGHBOURS[k][0], p[1] + NEIGHBOURS[k][1]];
        let direction = |from: [i64; 2], to: [i64; 2]| {
            let d = [to[0] - from[0], to[1] - from[1]];
            NEIGHBOURS.iter().position(|&n| n == d).unwrap_or(0)
        };
        // The first neighbour clockwise from the west.
        let Some(first) = (0..8).map(|k| step(start, k)).find(|&p| self.contains(p)) else {
            return vec![start];
        };
        let (mut previous, mut current) = (first, start);
        let mut border = Vec::new();
        // Every border pixel is visited at most four times, and every border pixel is one
        // of the block's pixels: the bound only guards the loop. (It once counted runs, not
        // pixels, and cut the border of long thin blocks short: issue 8, case 8.)
        let pixels: i64 = self
            .rows
            .iter()
            .flat_map(|row| row.iter())
            .map(|(_, r)| i64::from(r[1]) - i64::from(r[0]))
            .sum();
        let limit = 4 * usize::try_from(pixels).unwrap_or(usize::MAX / 8) + 8;
        loop {
            border.push(current);
            let back = direction(current, previous);
            // Counter-clockwise from just past `previous`; `previous` itself is inside.
            let next = (1..=8)
                .map(|i| step(current, (back + 8 - i) % 8))
                .find(|&p| self.contains(p))
                .unwrap_or(previous);
            if (next == start && current == first) || border.len() > limit {
                break;
            }
            previous = current;
            current = next;
        }
        border
    }
}

/// The points of a closed polygon where it turns: a point is dropped when it lies on the
/// straight segment from its predecessor to its successor. Reversals (the tip of a 1-px
/// spur) are kept.
fn corners(points: &[[i64; 2]]) -> Vec<[i64; 2]> {
    let n = points.len();
    if n < 3 {
        return points.to_vec();
    }
    let kept: Vec<[i64; 2]> = (0..n)
        .filter(|&i| {
            let (a, b, c) = (points[(i + n - 1) % n], points[i], points[(i + 1) % n]);
            let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - b[0], c[1] - b[1]]);
            let cross = u[0] * v[1] - u[1] * v[0];
            let dot = u[0] * v[0] + u[1] * v[1];
            cross != 0 || dot <= 0
        })
        .map(|i| points[i])
        .collect();
    if kept.is_empty() {
        points.to_vec()
    } else {
        kept
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pixels(block: &Block, width: u32, height: u32) -> Vec<(u32, u32)> {
        (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .filter(|&(x, y)| block.contains_pixel(x, y))
            .collect()
    }

    #[test]
    fn an_l_shaped_block_has_exact_bands_and_its_corners() {
        let rows = [
            "..........",
            ".####.....",
            ".####.....",
            ".########.",
            ".########.",
            "..........",
        ];
        let blocks = find_blocks(&ClassMap::drawn(&rows));
        assert_eq!(blocks.len(), 1);
        let b = &blocks[0];
        assert_eq!(
            b.bbox,
            PxRect {
                x0: 1,
                y0: 1,
                x1: 9,
                y1: 5
            }
        );
        assert_eq!(b.area, 24);
        assert_eq!(
            b.bands,
            vec![
                Band {
                    y0: 1,
                    y1: 3,
                    spans: vec![[1, 5]]
                },
                Band {
                    y0: 3,
                    y1: 5,
                    spans: vec![[1, 9]]
                },
            ]
        );
        let mut outline = b.outline.clone();
        outline.sort();
        // Border-pixel centres: the inner corner is cut by a diagonal step, as in OpenCV.
        assert_eq!(
            outline,
            vec![[1, 1], [1, 4], [4, 1], [4, 2], [5, 3], [8, 3], [8, 4]]
        );
        let expected: Vec<(u32, u32)> = (0..6u32)
            .flat_map(|y| (0..10u32).map(move |x| (x, y)))
            .filter(|&(x, y)| rows[y as usize].as_bytes()[x as usize] == b'#')
            .collect();
        assert_eq!(pixels(b, 10, 6), expected);
    }

    #[test]
    fn blocks_are_numbered_in_raster_order_and_specks_dropped() {
        let rows = [
            "....####....####",
            "....####.##.####", // a 2-px speck between
            "....####....####",
            "....####....####",
            "#...............", // a 1-px speck
            "....####........",
            "..######........", // first pixel later than its bbox corner
            "....####........",
            "....####........",
        ];
        let blocks = find_blocks(&ClassMap::drawn(&rows));
        let summary: Vec<(u32, PxRect, u64)> =
            blocks.iter().map(|b| (b.id, b.bbox, b.area)).collect();
        assert_eq!(
            summary,
            vec![
                (
                    0,
                    PxRect {
                        x0: 4,
                        y0: 0,
                        x1: 8,
                        y1: 4
                    },
                    16
                ),
                (
                    1,
                    PxRect {
                        x0: 12,
                        y0: 0,
                        x1: 16,
                        y1: 4
                    },
                    16
                ),
                (
                    2,
                    PxRect {
                        x0: 2,
                        y0: 5,
                        x1: 8,
                        y1: 9
                    },
                    18
                ),
            ]
        );
    }

    #[test]
    fn holes_and_notches_stay_out_of_the_bands() {
        let rows = [
            "######", //
            "#..###", // a hole
            "######", "###.##", // a notch from below
            "###.##",
        ];
        let blocks = find_blocks(&ClassMap::drawn(&rows));
        assert_eq!(blocks.len(), 1);
        let b = &blocks[0];
        assert_eq!(b.area, 30 - 4);
        assert_eq!(b.bands.len(), 4);
        assert_eq!(
            b.bands[3],
            Band {
                y0: 3,
                y1: 5,
                spans: vec![[0, 3], [4, 6]]
            }
        );
        assert!(!b.contains_pixel(1, 1) && !b.contains_pixel(3, 4) && b.contains_pixel(4, 4));
        // The outline goes round the notch, not the hole.
        assert!(b.outline.contains(&[3, 2]) || b.outline.contains(&[2, 4]));
        assert!(!b.outline.contains(&[1, 1]));
    }

    /// The outer border imageproc traces on a mask of `block` (with a 1-px margin).
    fn imageproc_outer_border(block: &Block) -> Vec<[i64; 2]> {
        use imageproc::contours::{BorderType, find_contours};
        let r = block.bbox;
        let mask = image::GrayImage::from_fn(r.width() + 2, r.height() + 2, |x, y| {
            let inside = x >= 1 && y >= 1 && block.contains_pixel(x - 1 + r.x0, y - 1 + r.y0);
            image::Luma([if inside { 255 } else { 0 }])
        });
        let contour = find_contours::<i64>(&mask)
            .into_iter()
            .find(|c| c.border_type == BorderType::Outer && c.parent.is_none())
            .unwrap();
        let (dx, dy) = (i64::from(r.x0) - 1, i64::from(r.y0) - 1);
        contour
            .points
            .iter()
            .map(|p| [p.x + dx, p.y + dy])
            .collect()
    }

    proptest::proptest! {
        #![proptest_config(crate::test_seed::proptest_config(256))]
        #[test]
        fn outer_borders_match_imageprocs(
            cells in proptest::collection::vec(proptest::bool::weighted(0.6), 12 * 9),
            scale in 1usize..=2,
        ) {
            // Random 12×9 blobs, each cell a square of `scale`² block pixels: 1-px spurs,
            // diagonal touches and holes all turn up.
            let rows: Vec<String> = (0..9 * scale)
                .map(|y| {
                    (0..12 * scale)
                        .map(|x| if cells[y / scale * 12 + x / scale] { '#' } else { '.' })
                        .collect()
                })
                .collect();
            let rows: Vec<&str> = rows.iter().map(String::as_str).collect();
            let map = ClassMap::drawn(&rows);
            for block in find_blocks(&map) {
                let runs: Vec<(u32, Run)> = block
                    .bands
                    .iter()
                    .flat_map(|b| (b.y0..b.y1).flat_map(move |y| b.spans.iter().map(move |s| (y, *s))))
                    .collect();
                let ours = Shape::new(&runs, block.bbox).outer_border();
                proptest::prop_assert_eq!(&ours, &imageproc_outer_border(&block));
                let corners: Vec<[u32; 2]> =
                    corners(&ours).into_iter().map(|[x, y]| [x as u32, y as u32]).collect();
                proptest::prop_assert_eq!(&block.outline, &corners);
            }
        }
    }

    #[test]
    fn a_single_pixel_and_a_line_have_outlines() {
        let blocks = find_blocks(&ClassMap::drawn(&[
            "..........",
            ".########.",
            "....#.....",
        ]));
        // Area 9 is a speck; call the tracer directly.
        assert!(blocks.is_empty());
        let runs = [(1, [1, 9]), (2, [4, 5])];
        let bbox = PxRect {
            x0: 1,
            y0: 1,
            x1: 9,
            y1: 3,
        };
        // Out along the top, down to the stem and back (8-connected steps), then straight
        // back along the top.
        assert_eq!(
            outline(&runs, bbox),
            vec![[1, 1], [3, 1], [4, 2], [5, 1], [8, 1]]
        );
        let dot = [(5, [7, 8])];
        assert_eq!(
            outline(
                &dot,
                PxRect {
                    x0: 7,
                    y0: 5,
                    x1: 8,
                    y1: 6
                }
            ),
            vec![[7, 5]]
        );
    }

    #[test]
    fn a_long_thin_block_keeps_its_four_corners() {
        // Issue 8, case 8: a block 422 px wide and 13 rows high lost its far corners.
        let runs: Vec<(u32, Run)> = (6..19).map(|y| (y, [6, 428])).collect();
        let bbox = PxRect {
            x0: 6,
            y0: 6,
            x1: 428,
            y1: 19,
        };
        let mut got = outline(&runs, bbox);
        got.sort();
        assert_eq!(got, vec![[6, 6], [6, 18], [427, 6], [427, 18]]);
    }

    #[test]
    fn corners_drop_only_straight_through_points() {
        let square = [
            [0, 0],
            [1, 0],
            [2, 0],
            [2, 1],
            [2, 2],
            [1, 2],
            [0, 2],
            [0, 1],
        ];
        assert_eq!(corners(&square), vec![[0, 0], [2, 0], [2, 2], [0, 2]]);
        let spur = [[0, 0], [1, 0], [2, 0], [1, 0]];
        assert_eq!(corners(&spur), vec![[0, 0], [2, 0]]);
        let diagonal = [[0, 0], [1, 1], [2, 2], [1, 2], [0, 2], [0, 1]];
        assert_eq!(corners(&diagonal), vec![[0, 0], [2, 2], [0, 2]]);
    }
}
