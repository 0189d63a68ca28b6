//! Blocks + roads → the lamp strip's width in layout pixels, measured from the layout.
//!
//! The scene stage raises the strip into sidewalks, the objects stage keeps text and signs
//! within reach of it, and the build driver places street cameras on it: all three measure
//! it here.

use super::RoadRect;
use crate::model::{Block, ParsedLayout};

/// Strip width when the layout gives nothing to measure (the paper's 8 px).
pub const DEFAULT_STRIP_PX: u32 = 8;

/// Where across the strip a pedestrian camera walks, as a share of its width from the
/// block's edge: nearer the shop fronts than the lamps, signs and benches standing
/// mid-strip. The cameras stage walks this line; the objects stage keeps people off it.
pub const WALK_SHARE: f64 = 0.3;

/// The lamp strip's width in pixels, measured: for each block, the distance from its
/// bounding box to the nearest road edge that runs alongside it (a road parallel to one of
/// the box's sides, on the outside of it, overlapping it lengthwise); the lower median of
/// those distances over all blocks, rounded. `DEFAULT_STRIP_PX` when no block has a road
/// beside it.
pub fn strip_width_px(layout: &ParsedLayout) -> u32 {
    let mut gaps: Vec<f64> = layout
        .blocks
        .iter()
        .filter_map(|block| nearest_road_gap(block, layout))
        .collect();
    if gaps.is_empty() {
        return DEFAULT_STRIP_PX;
    }
    gaps.sort_by(f64::total_cmp);
    let median = gaps[(gaps.len() - 1) / 2];
    // Non-negative and finite by construction; the cast saturates for absurd layouts.
    median.round() as u32
}

fn nearest_road_gap(block: &Block, layout: &ParsedLayout) -> Option<f64> {
    let b = block.bbox;
    let (bx, by) = (
        [f64::from(b.x0), f64::from(b.x1)],
        [f64::from(b.y0), f64::from(b.y1)],
    );
    let overlaps = |a: [f64; 2], c: [f64; 2]| a[0] < c[1] && c[0] < a[1];
    layout
        .roads
        .iter()
        .filter_map(|road| {
            let r = RoadRect::of(road);
            let gap = if overlaps(r.x, bx) && r.y[1] <= by[0] {
                by[0] - r.y[1]
            } else if overlaps(r.x, bx) && r.y[0] >= by[1] {
                r.y[0] - by[1]
            } else if overlaps(r.y, by) && r.x[1] <= bx[0] {
                bx[0] - r.x[1]
            } else if overlaps(r.y, by) && r.x[0] >= bx[1] {
                r.x[0] - bx[1]
            } else {
                return None;
            };
            gap.is_finite().then_some(gap)
        })
        .min_by(f64::total_cmp)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::{GenerateSpec, Palette};

    #[test]
    fn strip_width_is_measured_from_generated_layouts() {
        for strip in [4, 8, 13] {
            let spec = GenerateSpec {
                strip_width: strip,
                ..GenerateSpec::default()
            };
            let palette = Palette::default();
            let image = crate::test_support::generated(&spec, 5).image;
            let layout = crate::test_support::parsed(&image, &palette);
            assert_eq!(strip_width_px(&layout), strip);
        }
    }

    #[test]
    fn strip_width_defaults_without_roads() {
        let layout = ParsedLayout {
            width: 10,
            height: 10,
            blocks: Vec::new(),
            roads: Vec::new(),
        };
        assert_eq!(strip_width_px(&layout), DEFAULT_STRIP_PX);
    }
}
