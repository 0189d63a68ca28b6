//! Parse stage: layout image + palette → [`ParsedLayout`]: the building blocks and roads
//! drawn on it (paper 3.1, "layout parsing").
//!
//! Three steps, each in its own file:
//!
//! 1. `ClassMap`: every pixel becomes road, line, block, strip or
//!    other: the nearest palette colour within `palette.tolerance`, plus faded road/line
//!    blends as line so that anti-aliased or JPEG-saved 1-px lines survive. Rows in parallel.
//! 2. `find_blocks`: 4-connected regions of block pixels of at least
//!    [`MIN_BLOCK_AREA`] px, with bounding box, area, exact pixels as bands and the outer
//!    contour's corners; ids in raster order of each block's first pixel.
//! 3. `find_roads`: centre lines from line-pixel runs longer than 5 px
//!    (gaps up to [`LINE_GAP`] px bridged, runs on neighbouring rows/columns merged), road
//!    edges from the road-or-line runs across each line.
//!
//! Blocks and roads are found in parallel; every parallel step writes to index-addressed
//! slots, so the result is the same with any number of threads.

/// Bump when this stage's output bytes change: it is part of the stage's cache key.
pub const VERSION: u32 = 1;

mod blocks;
mod class_map;
mod roads;
mod run_table;

#[cfg(test)]
mod tests;

use image::RgbImage;

use crate::model::ParsedLayout;
use crate::spec::Palette;

pub use blocks::MIN_BLOCK_AREA;
pub use roads::{LINE_GAP, MIN_LINE_RUN};

/// Reads the blocks and roads off a layout image drawn with `palette`. Any image parses;
/// one with nothing in the palette's colours gives no blocks and no roads.
pub fn parse(image: &RgbImage, palette: &Palette) -> ParsedLayout {
    let map = class_map::ClassMap::classify(image, palette);
    let (blocks, roads) = rayon::join(|| blocks::find_blocks(&map), || roads::find_roads(&map));
    ParsedLayout {
        width: map.width(),
        height: map.height(),
        blocks,
        roads,
    }
}
