//! A building placed in a block: a square footprint (paper Algorithm 1).

use serde::{Deserialize, Serialize};

use super::PxRect;

/// A placed building in layout pixels.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Building {
    /// Index in the building list: blocks in id order, buildings in placement order.
    pub id: u32,
    /// The block it stands in.
    pub block: u32,
    /// Square footprint.
    pub footprint: PxRect,
    /// Which of the spec's building sizes it is (index into the width list).
    pub kind: u32,
}
