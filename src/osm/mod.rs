//! The OpenStreetMap stage: an extract (`.osm` XML or `.osm.pbf`) → [`OsmMap`]: building
//! footprints with their holes and heights, road centrelines with widths and sidewalks,
//! open ground (parks, lawns, woods; squares, car parks),
//! and the street furniture the map places, in metres around the box's centre.
//!
//! Entry: [`read`]. The driver reads the file's bytes; this stage streams them once
//! (`elements`: PBF blocks decoded one at a time, XML event by event) into what the map
//! needs (`collect`: node positions, every way's nodes, the tags it uses), then resolves
//! ways and multipolygons, projects (`projection`, documented there), cuts roads to the
//! box (`clip`), fits each paved road segment between the buildings (`fit`) and builds the
//! street surface: carriageway, sidewalks and blocks as polygons (`surfaces`). [`draw`]
//! pictures the map. The rules (which tags, which defaults) are in
//! `docs/osm.md`.
//!
//! In a build, this is the layout stage of a spec with `[layout.osm]`: its map
//! (`map.json`) replaces the mirror, parse and plan stages, and the city is built from it
//! by `lamps::map_lamps` (the lamps stage), `scene::map_city`, `objects::insert_map` and
//! `cameras::map_road_path`.

/// Bump when the map read from an extract changes: it is part of the layout stage's key for
/// a map layout.
pub const VERSION: u32 = 16;

mod clip;
mod collect;
mod draw;
mod elements;
mod fit;
mod projection;
mod rings;
mod surfaces;
mod tags;
#[cfg(test)]
mod tests;

pub use draw::draw;
pub use projection::Projection;
pub use tags::{FLOOR_HEIGHT, LANE_WIDTH, SIDEWALK_WIDTH};

use crate::model::{GeoBox, OsmMap};

/// Why an extract could not be read.
#[derive(Debug, thiserror::Error)]
pub enum OsmError {
    /// Neither a PBF file nor XML with an `<osm>` root.
    #[error("not an OpenStreetMap extract: expected an .osm.pbf file or OSM XML (<osm>)")]
    NotOsm,
    /// The PBF decoder refused a block.
    #[error("broken .osm.pbf: {0}")]
    Pbf(String),
    /// The XML is malformed, or an element lacks what OSM requires.
    #[error("broken OSM XML at byte {offset}: {message}")]
    Xml { offset: u64, message: String },
    /// The extract holds no node, and no box was given.
    #[error("the extract holds no nodes")]
    NoNodes,
    /// No node of the extract lies in the box asked for.
    #[error(
        "no node of the extract lies in the box {}: the extract's nodes span {}",
        fmt_box(asked),
        fmt_box(held)
    )]
    BoxMissesExtract { asked: GeoBox, held: GeoBox },
    /// The box is empty, inverted or off the globe.
    #[error("the box {0}")]
    Box(String),
}

/// Reads the extract `bytes` (PBF or XML, told apart by their first bytes) and returns
/// what lies inside `bbox` (else the file's own bounds, else its nodes' extent).
pub fn read(bytes: &[u8], bbox: Option<GeoBox>) -> Result<OsmMap, OsmError> {
    if let Some(b) = bbox {
        check_box(&b)?;
    }
    let mut sink = collect::Collector::default();
    if elements::is_pbf(bytes) {
        elements::read_pbf(bytes, &mut sink)?;
    } else {
        elements::read_xml(bytes, &mut sink)?;
    }
    sink.finish(bbox)
}

/// `south,west,north,east`, as `--bbox` takes it.
fn fmt_box(b: &GeoBox) -> String {
    format!("{},{},{},{}", b.south, b.west, b.north, b.east)
}

/// A box must have its south below its north and its west left of its east, on the globe.
pub fn check_box(b: &GeoBox) -> Result<(), OsmError> {
    b.problem().map_or(Ok(()), |p| Err(OsmError::Box(p)))
}
