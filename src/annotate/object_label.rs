//! What the scene knows of each object, and the categories annotations use.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// A COCO category.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Category {
    /// COCO category id (use 1 and up: some tools treat 0 as "none").
    pub id: u32,
    pub name: String,
}

/// One object of the scene, at index `instance id − 1`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ObjectLabel {
    /// Stable object name (`building_0042`), written into each annotation.
    pub name: String,
    /// Its [`Category::id`]; objects without one (ground, sky) are never annotated.
    pub category: Option<u32>,
    /// The words on a text object; text objects also go into the ICDAR lines.
    pub text: Option<String>,
    /// Extra attributes written into the object's COCO annotation as `attributes` (text:
    /// `text_style`, `text_font`); none written when empty.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub attributes: BTreeMap<String, String>,
}
