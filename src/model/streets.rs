//! The streets a city's cameras and objects follow: a parsed layout's axis-aligned roads,
//! or a map's road polylines.

use super::{OsmMap, ParsedLayout};

/// Where a city's streets come from.
#[derive(Clone, Copy, Debug)]
pub enum Streets<'a> {
    /// A generated or drawn layout (metres per pixel apart).
    Layout(&'a ParsedLayout),
    /// An OpenStreetMap extract, in metres.
    Map(&'a OsmMap),
}
