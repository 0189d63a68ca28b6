//! What the parse stage reads off a layout image.

use serde::{Deserialize, Serialize};

use super::{Block, Road};

/// Blocks and roads found in a layout image, in layout pixels.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ParsedLayout {
    pub width: u32,
    pub height: u32,
    pub blocks: Vec<Block>,
    pub roads: Vec<Road>,
}
