//! The assembled city plan in metres: what `plan.json` holds.

use serde::{Deserialize, Serialize};

use super::Axis;

/// The city plan: every block, road, lamp and building, in metres (x east, z south).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CityPlan {
    /// Size of the (mirrored) layout in metres, `[x extent, z extent]`.
    pub size: [f64; 2],
    /// Metres per layout pixel.
    pub metres_per_pixel: f64,
    pub blocks: Vec<PlanBlock>,
    pub roads: Vec<PlanRoad>,
    pub lamps: Vec<PlanLamp>,
    pub buildings: Vec<PlanBuilding>,
}

/// A building block in metres.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlanBlock {
    pub id: u32,
    /// Bounding box corners `[x, z]`.
    pub min: [f64; 2],
    pub max: [f64; 2],
    /// Area in square metres.
    pub area: f64,
    /// Outline corners `[x, z]` (centres of the border pixels).
    pub outline: Vec<[f64; 2]>,
}

/// A road in metres.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlanRoad {
    pub id: u32,
    pub axis: Axis,
    /// Ends of the centre line `[x, z]`.
    pub start: [f64; 2],
    pub end: [f64; 2],
    pub centre: [f64; 2],
    pub length: f64,
    pub width: f64,
}

/// A street lamp in metres.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlanLamp {
    pub id: u32,
    pub position: [f64; 2],
    pub road: u32,
    /// Unit vector `[x, z]` towards the road.
    pub facing: [f64; 2],
}

/// A building in metres: a square footprint.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlanBuilding {
    pub id: u32,
    pub block: u32,
    pub centre: [f64; 2],
    pub width: f64,
    /// Index into `buildings.widths` of the spec.
    pub kind: u32,
}
