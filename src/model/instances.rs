//! `instances.json`'s document: every instance id of a camera path's `ids/` images → what
//! the object is. Written by the annotate stage, read by `cityspec stats` and users' tools.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::ObjectKind;

/// One scene object, as instance id `id` in the path's `ids/` images.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Instance {
    pub id: u32,
    pub name: String,
    pub kind: ObjectKind,
    pub class: String,
    /// The COCO category this path labels it as (by name), if any.
    pub category: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub text: Option<String>,
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub attributes: BTreeMap<String, String>,
}

/// `instances.json`'s document.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Instances {
    pub instances: Vec<Instance>,
}
