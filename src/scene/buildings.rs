//! Buildings + facades → `building_NNNN` objects: a cuboid on the block surface, the facade
//! on all four walls and a flat roof.
//!
//! Which facade: with no spec widths, `building.kind` is the facade index (paper), and the
//! facade spans each wall once (u 0..1). With spec widths, the facade is drawn from
//! `crate::rng::stream(seed, "facade", building.id)` and repeats along the wall: u runs
//! 0..wall width / facade width, so windows keep their size. In both cases v runs 0 at the
//! roof line to 1 at the ground and the building is the facade's height, so the texture is
//! never stretched vertically.
//!
//! Fallbacks (bad input never panics): a kind beyond the facade list takes facade
//! `kind % n`; a facade with a non-positive height or width is treated as [`PLAIN_HEIGHT`](crate::model::geometry::PLAIN_HEIGHT)
//! high and spans each wall once; with no facades at all buildings are plain
//! ([`PLAIN_HEIGHT`](crate::model::geometry::PLAIN_HEIGHT), material `facade_plain`); a facade whose roof index is out of range
//! gets the `roof_plain` material.

use super::{SceneInput, object};
use crate::model::ObjectKind;
use crate::model::geometry::{KERB_Y, MaterialBook, MeshBuilder, facade_height, usable};
use crate::model::{Facade, SceneObject};

/// Metres one repeat of the plain roof covers (and of a roof whose `tile` is unusable).
const PLAIN_TILE: f64 = 4.0;

/// Each building's facade and the materials the buildings use.
pub struct Cladding {
    /// Per building, in input order: its facade index, or None when there are no facades.
    choice: Vec<Option<usize>>,
    /// Per facade index: its wall material, if some building uses it.
    wall: Vec<Option<u32>>,
    /// Per roof index: its material, if some used facade points at it.
    roof: Vec<Option<u32>>,
    plain_wall: Option<u32>,
    plain_roof: Option<u32>,
}

impl Cladding {
    /// Chooses every building's facade and registers the materials they need: facades in
    /// facade order, then roofs in roof order, then the plain fallbacks if any are needed.
    pub fn register(input: &SceneInput, book: &mut MaterialBook) -> Cladding {
        let facades = &input.facades.facades;
        let roofs = &input.facades.roofs;
        let choice: Vec<Option<usize>> = input
            .buildings
            .iter()
            .map(|b| input.facade_choice().of(b))
            .collect();
        let mut facade_used = vec![false; facades.len()];
        for &c in choice.iter().flatten() {
            facade_used[c] = true;
        }
        let mut roof_used = vec![false; roofs.len()];
        let mut need_plain_roof = choice.iter().any(Option::is_none);
        for (f, _) in facade_used.iter().enumerate().filter(|(_, u)| **u) {
            match roofs.get(facades[f].roof as usize) {
                Some(_) => roof_used[facades[f].roof as usize] = true,
                None => need_plain_roof = true,
            }
        }
        let white = [1.0; 3];
        let none = [0.0; 3];
        let wall = facades
            .iter()
            .zip(&facade_used)
            .map(|(f, &used)| {
                used.then(|| book.add(&format!("facade_{}", f.name), white, Some(&f.texture), none))
            })
            .collect();
        let roof = roofs
            .iter()
            .zip(&roof_used)
            .map(|(r, &used)| {
                used.then(|| book.add(&format!("roof_{}", r.name), white, Some(&r.texture), none))
            })
            .collect();
        let plain_wall = choice
            .iter()
            .any(Option::is_none)
            .then(|| book.add("facade_plain", [0.55, 0.5, 0.45], None, none));
        let plain_roof =
            need_plain_roof.then(|| book.add("roof_plain", [0.3, 0.3, 0.3], None, none));
        Cladding {
            choice,
            wall,
            roof,
            plain_wall,
            plain_roof,
        }
    }
}

pub fn building_objects(input: &SceneInput, clad: &Cladding) -> Vec<SceneObject> {
    let mpp = input.metres_per_pixel;
    input
        .buildings
        .iter()
        .zip(&clad.choice)
        .map(|(building, &choice)| {
            let facade: Option<&Facade> = choice.map(|c| &input.facades.facades[c]);
            let fp = building.footprint;
            let x = [f64::from(fp.x0) * mpp, f64::from(fp.x1) * mpp];
            let z = [f64::from(fp.y0) * mpp, f64::from(fp.y1) * mpp];
            let height = facade_height(facade);
            let tiled = input.widths.is_some();
            let u_end = |wall: f64| match facade {
                Some(f) if tiled && usable(f.width) => wall / f.width,
                _ => 1.0,
            };
            let wall_material = choice
                .and_then(|c| clad.wall[c])
                .or(clad.plain_wall)
                .expect("every building's wall material is registered");
            let mut walls = MeshBuilder::new(wall_material);
            let y = [KERB_Y, KERB_Y + height];
            let v = [0.0, 1.0];
            let (wx, wz) = (x[1] - x[0], z[1] - z[0]);
            walls.wall(
                [x[0], z[0]],
                [x[1], z[0]],
                y,
                [0.0, 0.0, -1.0],
                [0.0, u_end(wx)],
                v,
            );
            walls.wall(
                [x[1], z[0]],
                [x[1], z[1]],
                y,
                [1.0, 0.0, 0.0],
                [0.0, u_end(wz)],
                v,
            );
            walls.wall(
                [x[1], z[1]],
                [x[0], z[1]],
                y,
                [0.0, 0.0, 1.0],
                [0.0, u_end(wx)],
                v,
            );
            walls.wall(
                [x[0], z[1]],
                [x[0], z[0]],
                y,
                [-1.0, 0.0, 0.0],
                [0.0, u_end(wz)],
                v,
            );

            let roof_index = facade.map(|f| f.roof as usize);
            let roof = roof_index.and_then(|r| input.facades.roofs.get(r));
            let roof_material = roof_index
                .and_then(|r| clad.roof.get(r).copied().flatten())
                .or(clad.plain_roof)
                .expect("every building's roof material is registered");
            let tile = roof.map_or(
                PLAIN_TILE,
                |r| if usable(r.tile) { r.tile } else { PLAIN_TILE },
            );
            let mut top = MeshBuilder::new(roof_material);
            top.floor(x, z, y[1], tile);
            object(
                ObjectKind::Building,
                format!("building_{:04}", building.id),
                vec![walls, top],
            )
        })
        .collect()
}
