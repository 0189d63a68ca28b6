//! A street lamp site on a lamp strip beside a road.

use serde::{Deserialize, Serialize};

/// A street lamp's pole radius, metres: the scene builds it (`scene::street_lamps`), a
/// map's signs that hang on it keep their plates outside it (`objects`).
pub const LAMP_POLE_RADIUS: f64 = 0.08;

/// A lamp site in layout pixels (continuous coordinates); a map's, in metres.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Lamp {
    /// Index in the lamp list, in the order the lamps stage emits them.
    pub id: u32,
    /// Image `(x, y)` of the lamp's foot: mid-strip beside a layout's road, behind a
    /// map's kerb.
    pub position: [f64; 2],
    /// The road the lamp lights.
    pub road: u32,
    /// Unit image-space vector from the lamp towards its road.
    pub facing: [f64; 2],
}
