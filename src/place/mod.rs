//! Place stage: blocks + building widths + gap + seed → [`Building`]s (paper Algorithm 1).
//!
//! Every block is filled on its own (in parallel), from its own random stream
//! `crate::rng::stream(seed, "place", block.id)`, so changing one block never moves the
//! buildings of another. Results are collected in block order and numbered consecutively,
//! so the output is the same for any number of threads.
//!
//! What "fits" means is spelled out in the `filler` module. The gap rule, exactly: for any two
//! buildings of one block, the footprint of one grown by `gap_px` on every side shares no
//! pixel with the other; that is, they are at least `gap_px` pixels apart along x or along
//! y. Buildings of different blocks never meet because they stand on block pixels only.

/// Bump when this stage's output bytes change: it is part of the stage's cache key.
pub const VERSION: u32 = 1;

mod block_mask;
mod filler;
mod map_blocks;
mod widths;

pub use map_blocks::{CELL, Sizes, place_map};
pub use widths::widths_px;

use rayon::prelude::*;

use crate::model::{Block, Building, FacadeSet, MapBuilding, OsmMap, PxRect};
use crate::spec::BuildingsSpec;

/// The city's buildings: `spec`'s widths, or (paper 3.2) one building size per facade of
/// `facades` when the spec gives none; its gap; metres turned into layout pixels.
pub fn place_city(
    blocks: &[Block],
    spec: &BuildingsSpec,
    facades: Option<&FacadeSet>,
    metres_per_pixel: f64,
    seed: u64,
) -> Vec<Building> {
    let (widths_m, _) = sizes_m(spec, facades);
    let widths = widths_px(&widths_m, metres_per_pixel);
    let gap = (spec.gap / metres_per_pixel).round() as u32;
    place(blocks, &widths, gap, seed)
}
/// A map's buildings where it has none (`map_blocks`): `spec`'s widths and gap, or (paper
/// 3.2) one building size per facade of `facades`, which then gives the building its
/// facade and its height.
pub fn place_map_city(
    map: &OsmMap,
    spec: &BuildingsSpec,
    facades: Option<&FacadeSet>,
    seed: u64,
) -> Vec<MapBuilding> {
    let (widths, heights) = sizes_m(spec, facades);
    let sizes = Sizes {
        widths: &widths,
        facade_heights: heights.as_deref(),
        gap: spec.gap,
    };
    place_map(map, &sizes, seed)
}

/// Building widths in metres: `spec`'s, or (paper 3.2) one per facade of `facades`, then
/// with the facades' heights, in the same order.
fn sizes_m(spec: &BuildingsSpec, facades: Option<&FacadeSet>) -> (Vec<f64>, Option<Vec<f64>>) {
    match (&spec.widths, facades) {
        (Some(widths), _) => (widths.clone(), None),
        (None, Some(set)) => {
            let (widths, heights) = set.facades.iter().map(|f| (f.width, f.height)).unzip();
            (widths, Some(heights))
        }
        (None, None) => (Vec::new(), None),
    }
}

use block_mask::BlockMask;
use filler::Filler;

/// Buildings for every block. `widths_px[k]` is the side of building kind k; `gap_px` the
/// gap between neighbours. Each block draws from `crate::rng::stream(seed, "place", block.id)`.
///
/// Widths of 0 never fit; an empty width list places nothing.
pub fn place(blocks: &[Block], widths_px: &[u32], gap_px: u32, seed: u64) -> Vec<Building> {
    let per_block: Vec<Vec<Building>> = blocks
        .par_iter()
        .map(|block| place_in_block(block, widths_px, gap_px, seed))
        .collect();
    let mut buildings: Vec<Building> = per_block.into_iter().flatten().collect();
    for (id, building) in buildings.iter_mut().enumerate() {
        building.id = id as u32;
    }
    buildings
}

/// Algorithm 1 on one block; ids are left at 0 for [`place`] to number.
fn place_in_block(block: &Block, widths_px: &[u32], gap_px: u32, seed: u64) -> Vec<Building> {
    let mask = BlockMask::new(block);
    let rng = crate::rng::stream(seed, "place", u64::from(block.id));
    let (bx, by) = (block.bbox.x0, block.bbox.y0);
    Filler::new(&mask, widths_px, gap_px, rng)
        .fill()
        .into_iter()
        .map(|s| {
            // Local coordinates are below the bbox size, so they fit back into u32.
            let x0 = bx + s.x as u32;
            let y0 = by + s.y as u32;
            let w = s.width as u32;
            Building {
                id: 0,
                block: block.id,
                footprint: PxRect {
                    x0,
                    y0,
                    x1: x0 + w,
                    y1: y0 + w,
                },
                kind: s.kind,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Band;
    use proptest::prelude::*;

    fn rect_block(id: u32, x0: u32, y0: u32, w: u32, h: u32) -> Block {
        Block {
            id,
            bbox: PxRect {
                x0,
                y0,
                x1: x0 + w,
                y1: y0 + h,
            },
            area: u64::from(w) * u64::from(h),
            outline: vec![
                [x0, y0],
                [x0 + w - 1, y0],
                [x0 + w - 1, y0 + h - 1],
                [x0, y0 + h - 1],
            ],
            bands: vec![Band {
                y0,
                y1: y0 + h,
                spans: vec![[x0, x0 + w]],
            }],
        }
    }

    /// A `w × h` rectangle with its bottom-right `cw × ch` corner cut away (an L).
    fn l_block(id: u32, x0: u32, y0: u32, (w, h): (u32, u32), (cw, ch): (u32, u32)) -> Block {
        let split = y0 + h - ch;
        Block {
            id,
            bbox: PxRect {
                x0,
                y0,
                x1: x0 + w,
                y1: y0 + h,
            },
            area: u64::from(w) * u64::from(h) - u64::from(cw) * u64::from(ch),
            outline: vec![],
            bands: vec![
                Band {
                    y0,
                    y1: split,
                    spans: vec![[x0, x0 + w]],
                },
                Band {
                    y0: split,
                    y1: y0 + h,
                    spans: vec![[x0, x0 + w - cw]],
                },
            ],
        }
    }

    fn grown(r: &PxRect, by: u32) -> PxRect {
        PxRect {
            x0: r.x0.saturating_sub(by),
            y0: r.y0.saturating_sub(by),
            x1: r.x1 + by,
            y1: r.y1 + by,
        }
    }

    /// Every rule the stage promises, checked by brute force. Returns a message on failure.
    fn check(
        blocks: &[Block],
        widths: &[u32],
        gap: u32,
        buildings: &[Building],
    ) -> Result<(), String> {
        for (i, b) in buildings.iter().enumerate() {
            if b.id != i as u32 {
                return Err(format!("building {i} has id {}", b.id));
            }
            let Some(&w) = widths.get(b.kind as usize) else {
                return Err(format!(
                    "building {i} has kind {} of {}",
                    b.kind,
                    widths.len()
                ));
            };
            let f = b.footprint;
            if f.width() != w || f.height() != w {
                return Err(format!(
                    "building {i} is {}×{}, kind says {w}",
                    f.width(),
                    f.height()
                ));
            }
            let block = blocks
                .iter()
                .find(|k| k.id == b.block)
                .ok_or(format!("building {i}: no block"))?;
            if !block.bbox.contains(&f) {
                return Err(format!("building {i} leaves its block's bbox"));
            }
            for y in f.y0..f.y1 {
                for x in f.x0..f.x1 {
                    if !block.contains_pixel(x, y) {
                        return Err(format!(
                            "building {i} stands on ({x}, {y}), not a block pixel"
                        ));
                    }
                }
            }
        }
        if buildings.windows(2).any(|p| p[0].block > p[1].block) {
            return Err("buildings are not in block order".into());
        }
        for (i, a) in buildings.iter().enumerate() {
            for b in &buildings[i + 1..] {
                if a.block == b.block && grown(&a.footprint, gap).intersects(&b.footprint) {
                    return Err(format!("{a:?} and {b:?} are closer than the gap {gap}"));
                }
            }
        }
        Ok(())
    }

    /// No spot is left in `block` where the smallest width would still fit.
    fn check_full(
        block: &Block,
        widths: &[u32],
        gap: u32,
        buildings: &[Building],
    ) -> Result<(), String> {
        let Some(&s) = widths.iter().filter(|&&w| w > 0).min() else {
            return Ok(());
        };
        let bb = block.bbox;
        let mine: Vec<PxRect> = buildings
            .iter()
            .filter(|b| b.block == block.id)
            .map(|b| grown(&b.footprint, gap))
            .collect();
        for y in bb.y0..=bb.y1.saturating_sub(s) {
            for x in bb.x0..=bb.x1.saturating_sub(s) {
                let spot = PxRect {
                    x0: x,
                    y0: y,
                    x1: x + s,
                    y1: y + s,
                };
                if mine.iter().any(|g| g.intersects(&spot)) {
                    continue;
                }
                if (y..y + s).all(|yy| (x..x + s).all(|xx| block.contains_pixel(xx, yy))) {
                    return Err(format!("a {s}-px building still fits at ({x}, {y})"));
                }
            }
        }
        Ok(())
    }

    fn covered(buildings: &[Building]) -> u64 {
        buildings
            .iter()
            .map(|b| u64::from(b.footprint.width()) * u64::from(b.footprint.height()))
            .sum()
    }

    const DEFAULT_WIDTHS: [u32; 5] = [12, 16, 20, 24, 30];

    /// Measured over seeds 0..256 with the default widths and gap 2 (cover = building
    /// area / block area): 90×90 (3× the largest width) min 0.52, median 0.65; 120×120 min
    /// 0.51, median 0.64; 200×200 min 0.53, median 0.61; 400×400 min 0.52, median 0.58.
    /// The paper's algorithm wastes the slack at row ends and under short columns, so ~0.6
    /// is what it gives. Fail if any seed of 0..64 covers less than half the block or the
    /// mean falls below 0.57.
    #[test]
    fn rectangular_blocks_are_filled_densely() {
        for side in [90u32, 120, 200] {
            let block = rect_block(0, 10, 20, side, side);
            let covers: Vec<f64> = (0..64)
                .map(|seed| {
                    let buildings = place(std::slice::from_ref(&block), &DEFAULT_WIDTHS, 2, seed);
                    check(std::slice::from_ref(&block), &DEFAULT_WIDTHS, 2, &buildings).unwrap();
                    covered(&buildings) as f64 / block.area as f64
                })
                .collect();
            let worst = covers.iter().copied().fold(f64::INFINITY, f64::min);
            let mean = covers.iter().sum::<f64>() / covers.len() as f64;
            assert!(
                worst >= 0.50,
                "{side}×{side}: worst cover {worst:.3} < 0.50"
            );
            assert!(mean >= 0.57, "{side}×{side}: mean cover {mean:.3} < 0.57");
        }
    }

    #[test]
    fn top_left_of_a_rectangle_is_built_first() {
        let block = rect_block(3, 40, 50, 100, 70);
        let buildings = place(&[block], &DEFAULT_WIDTHS, 2, 9);
        let first = buildings[0].footprint;
        assert_eq!((first.x0, first.y0), (40, 50));
        assert!(buildings.iter().all(|b| b.block == 3));
    }

    #[test]
    fn same_seed_same_buildings_other_seed_other_buildings() {
        let blocks = [
            rect_block(0, 0, 0, 150, 100),
            l_block(1, 200, 0, (120, 140), (60, 70)),
        ];
        let a = place(&blocks, &DEFAULT_WIDTHS, 2, 5);
        let b = place(&blocks, &DEFAULT_WIDTHS, 2, 5);
        let c = place(&blocks, &DEFAULT_WIDTHS, 2, 6);
        assert!(!a.is_empty());
        assert_eq!(a, b);
        assert_ne!(a, c);
    }

    #[test]
    fn changing_one_block_leaves_another_alone() {
        let other = l_block(1, 200, 0, (120, 140), (60, 70));
        let before = place(
            &[rect_block(0, 0, 0, 150, 100), other.clone()],
            &DEFAULT_WIDTHS,
            2,
            5,
        );
        let after = place(
            &[rect_block(0, 0, 0, 90, 180), other],
            &DEFAULT_WIDTHS,
            2,
            5,
        );
        let in_block_1 = |bs: &[Building]| -> Vec<(PxRect, u32)> {
            bs.iter()
                .filter(|b| b.block == 1)
                .map(|b| (b.footprint, b.kind))
                .collect()
        };
        assert!(!in_block_1(&before).is_empty());
        assert_eq!(in_block_1(&before), in_block_1(&after));
        assert_ne!(before.iter().filter(|b| b.block == 0).count(), 0);
    }

    #[test]
    fn thread_count_does_not_change_the_result() {
        let blocks: Vec<Block> = (0..12)
            .map(|i| rect_block(i, i * 130, 0, 120, 90 + 7 * i))
            .collect();
        let run = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| place(&blocks, &DEFAULT_WIDTHS, 2, 77))
        };
        assert_eq!(run(1), run(4));
    }

    #[test]
    fn notches_of_an_l_are_filled() {
        // The leg below the bar starts at the bbox's left; the bar's right part hangs over
        // the cut-away corner. Both must hold buildings.
        let block = l_block(0, 0, 0, (100, 100), (60, 50));
        let buildings = place(std::slice::from_ref(&block), &[12], 2, 1);
        check(std::slice::from_ref(&block), &[12], 2, &buildings).unwrap();
        check_full(&block, &[12], 2, &buildings).unwrap();
        assert!(buildings.iter().any(|b| b.footprint.y0 >= 50));
        assert!(
            buildings
                .iter()
                .any(|b| b.footprint.x0 >= 40 && b.footprint.y1 <= 50)
        );
    }

    #[test]
    fn degenerate_inputs_place_nothing_and_do_not_panic() {
        let block = rect_block(0, 0, 0, 50, 50);
        let cases: [(&[u32], u32, usize); 4] = [
            (&[], 2, 0),      // no widths
            (&[0], 2, 0),     // a zero width never fits
            (&[51], 0, 0),    // too wide for the block
            (&[50, 0], 0, 1), // exactly the block, zero ignored
        ];
        for (widths, gap, count) in cases {
            let buildings = place(std::slice::from_ref(&block), widths, gap, 0);
            assert_eq!(buildings.len(), count, "widths {widths:?}");
        }
        let empty = Block {
            id: 0,
            bbox: PxRect {
                x0: 5,
                y0: 5,
                x1: 5,
                y1: 5,
            },
            area: 0,
            outline: vec![],
            bands: vec![],
        };
        assert!(place(&[empty], &DEFAULT_WIDTHS, 2, 0).is_empty());
    }

    fn block_strategy() -> impl Strategy<Value = Block> {
        let rect = (0u32..40, 0u32..40, 8u32..140, 8u32..140)
            .prop_map(|(x, y, w, h)| rect_block(0, x, y, w, h));
        let l = (
            0u32..40,
            0u32..40,
            16u32..140,
            16u32..140,
            1u32..100,
            1u32..100,
        )
            .prop_map(|(x, y, w, h, cw, ch)| {
                l_block(0, x, y, (w, h), (cw % (w - 1) + 1, ch % (h - 1) + 1))
            });
        prop_oneof![rect, l]
    }

    proptest! {
        #![proptest_config(crate::test_seed::proptest_config(96))]

        #[test]
        fn buildings_keep_every_rule(
            blocks in prop::collection::vec(block_strategy(), 1..4),
            widths in prop::collection::vec(3u32..40, 1..6),
            gap in 0u32..6,
            seed in any::<u64>(),
        ) {
            // Lay the blocks out side by side, numbered in order, so they never overlap.
            let blocks: Vec<Block> = blocks
                .into_iter()
                .enumerate()
                .map(|(i, b)| {
                    let dx = i as u32 * 200;
                    let mut b = b;
                    b.id = i as u32;
                    b.bbox.x0 += dx;
                    b.bbox.x1 += dx;
                    for band in &mut b.bands {
                        for s in &mut band.spans {
                            s[0] += dx;
                            s[1] += dx;
                        }
                    }
                    b
                })
                .collect();
            let buildings = place(&blocks, &widths, gap, seed);
            prop_assert_eq!(check(&blocks, &widths, gap, &buildings), Ok(()));
            for block in &blocks {
                prop_assert_eq!(check_full(block, &widths, gap, &buildings), Ok(()));
            }
        }
    }
}
