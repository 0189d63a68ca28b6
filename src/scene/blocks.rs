//! Blocks → `block_NNNN` objects: the block's exact pixels (one quad per band span) as a
//! paved surface at kerb height.

use super::{object, procedural};
use crate::model::ObjectKind;
use crate::model::geometry::{KERB_Y, MeshBuilder};
use crate::model::{ParsedLayout, SceneObject};

pub fn block_objects(layout: &ParsedLayout, mpp: f64, material: u32) -> Vec<SceneObject> {
    layout
        .blocks
        .iter()
        .map(|block| {
            let mut mesh = MeshBuilder::new(material);
            for band in &block.bands {
                let z = [f64::from(band.y0) * mpp, f64::from(band.y1) * mpp];
                for span in &band.spans {
                    let x = [f64::from(span[0]) * mpp, f64::from(span[1]) * mpp];
                    mesh.floor(x, z, KERB_Y, procedural::PAVING_TILE);
                }
            }
            object(
                ObjectKind::Block,
                format!("block_{:04}", block.id),
                vec![mesh],
            )
        })
        .collect()
}
