//! Roads → `road_NNNN` objects: each road's rectangle minus the rectangles of the roads
//! before it, so a crossing is paved once (by the road with the lower id).

use super::{object, procedural};
use crate::model::ObjectKind;
use crate::model::geometry::{MeshBuilder, ROAD_Y, RoadRect};
use crate::model::{ParsedLayout, SceneObject};

pub fn road_objects(layout: &ParsedLayout, mpp: f64, material: u32) -> Vec<SceneObject> {
    let rects: Vec<RoadRect> = layout.roads.iter().map(RoadRect::of).collect();
    layout
        .roads
        .iter()
        .enumerate()
        .map(|(i, road)| {
            let mut mesh = MeshBuilder::new(material);
            for piece in rects[i].minus_all(&rects[..i]) {
                let x = piece.x.map(|v| v * mpp);
                let z = piece.y.map(|v| v * mpp);
                mesh.floor(x, z, ROAD_Y, procedural::ASPHALT_TILE);
            }
            object(ObjectKind::Road, format!("road_{:04}", road.id), vec![mesh])
        })
        .collect()
}
