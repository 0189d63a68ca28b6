//! Buildings + facades → `building_NNNN` objects: a cuboid on the block surface, the facade
//! on all four walls and a flat roof.
//!
//! Which facade: the balanced choice of [`FacadeChoice::all`](crate::model::geometry::FacadeChoice::all)
//! (the least used among those that fit the wall). With no spec widths the facade repeats a
//! whole number of times along the wall, stretched by at most ±20 % (u 0..k); with spec
//! widths it repeats at its own width (u 0..wall width / facade width), so windows keep
//! their size. In both cases v runs 0 at the roof line to 1 at the ground and the building
//! is the facade's height, so the texture is never stretched vertically.
//!
//! Fallbacks (bad input never panics): a facade with a non-positive height or width is
//! treated as [`PLAIN_HEIGHT`](crate::model::geometry::PLAIN_HEIGHT) high and spans each
//! wall once; with no facades at all buildings are plain
//! ([`PLAIN_HEIGHT`](crate::model::geometry::PLAIN_HEIGHT), material `facade_plain`); a facade whose roof index is out of range
//! gets the `roof_plain` material.

use super::{SceneInput, object};
use crate::model::ObjectKind;
use crate::model::geometry::{KERB_Y, MaterialBook, MeshBuilder, facade_height, usable};
use crate::model::{Facade, SceneObject, Texture};
use rand::RngExt;

/// Metres one repeat of the plain roof covers (and of a roof whose `tile` is unusable).
const PLAIN_TILE: f64 = 4.0;

/// Colour factors a building's facade or roof texture is multiplied by, one drawn per
/// building from `crate::rng::stream(seed, "building-tint", building.id)` (wall, then
/// roof): plain, warmer, cooler, darker, sandier. At most 1 (a glTF base colour factor).
pub const TINTS: [[f32; 3]; 5] = [
    [1.0, 1.0, 1.0],
    [0.94, 0.88, 0.8],
    [0.84, 0.88, 0.94],
    [0.8, 0.8, 0.8],
    [0.97, 0.93, 0.84],
];

/// Per texture (a facade or a roof) and tint, its material if some building uses it.
type Tinted = Vec<[Option<u32>; TINTS.len()]>;

/// Each building's facade and tints, and the materials the buildings use.
pub struct Cladding {
    /// Per building, in input order: its facade index, or None when there are no facades.
    choice: Vec<Option<usize>>,
    /// Per building, in input order: its wall tint and its roof tint (indices of [`TINTS`]).
    tint: Vec<[usize; 2]>,
    /// Per facade index and wall tint: its wall material.
    wall: Tinted,
    /// Per roof index and roof tint: its material.
    roof: Tinted,
    plain_wall: Option<u32>,
    plain_roof: Option<u32>,
}

impl Cladding {
    /// Chooses every building's facade and tints and registers the materials they need:
    /// facades in facade order (each tint used after its untinted material, which holds the
    /// texture), then roofs in roof order likewise, then the plain fallbacks if needed.
    pub fn register(input: &SceneInput, book: &mut MaterialBook) -> Cladding {
        let facades = &input.facades.facades;
        let roofs = &input.facades.roofs;
        let choice = input.facade_choice().all(input.buildings);
        let tint: Vec<[usize; 2]> = input
            .buildings
            .iter()
            .map(|b| {
                let mut rng = crate::rng::stream(input.seed, "building-tint", u64::from(b.id));
                [0; 2].map(|_| rng.random_range(0..TINTS.len()))
            })
            .collect();
        let mut wall_used = vec![[false; TINTS.len()]; facades.len()];
        let mut roof_used = vec![[false; TINTS.len()]; roofs.len()];
        let mut need_plain_roof = false;
        for (c, t) in choice.iter().zip(&tint) {
            let Some(f) = *c else {
                need_plain_roof = true;
                continue;
            };
            wall_used[f][t[0]] = true;
            match roof_used.get_mut(facades[f].roof as usize) {
                Some(r) => r[t[1]] = true,
                None => need_plain_roof = true,
            }
        }
        let wall = register_tinted(
            book,
            "facade",
            facades.iter().map(|f| (&f.name, &f.texture)),
            &wall_used,
        );
        let roof = register_tinted(
            book,
            "roof",
            roofs.iter().map(|r| (&r.name, &r.texture)),
            &roof_used,
        );
        let none = [0.0; 3];
        let plain_wall = choice
            .iter()
            .any(Option::is_none)
            .then(|| book.add("facade_plain", [0.55, 0.5, 0.45], None, none));
        let plain_roof =
            need_plain_roof.then(|| book.add("roof_plain", [0.3, 0.3, 0.3], None, none));
        Cladding {
            choice,
            tint,
            wall,
            roof,
            plain_wall,
            plain_roof,
        }
    }
}

/// Registers `<prefix>_<name>` for every texture with a used tint (white, holding the
/// texture), then `<prefix>_<name>_tint<k>` for each other used tint, sharing it.
fn register_tinted<'a>(
    book: &mut MaterialBook,
    prefix: &str,
    textures: impl Iterator<Item = (&'a String, &'a Texture)>,
    used: &[[bool; TINTS.len()]],
) -> Tinted {
    textures
        .zip(used)
        .map(|((name, texture), used)| {
            let mut out = [None; TINTS.len()];
            if !used.iter().any(|&u| u) {
                return out;
            }
            let base = book.add(
                &format!("{prefix}_{name}"),
                TINTS[0],
                Some(texture),
                [0.0; 3],
            );
            out[0] = Some(base);
            for (k, _) in used.iter().enumerate().skip(1).filter(|(_, u)| **u) {
                out[k] =
                    Some(book.add_sharing(&format!("{prefix}_{name}_tint{k}"), TINTS[k], base));
            }
            out
        })
        .collect()
}

/// The object name of building `id`: `building_NNNN`.
pub fn building_name(id: u32) -> String {
    format!("building_{id:04}")
}

pub fn building_objects(input: &SceneInput, clad: &Cladding) -> Vec<SceneObject> {
    let mpp = input.metres_per_pixel;
    input
        .buildings
        .iter()
        .zip(clad.choice.iter().zip(&clad.tint))
        .map(|(building, (&choice, tint))| {
            let facade: Option<&Facade> = choice.map(|c| &input.facades.facades[c]);
            let fp = building.footprint;
            let x = [f64::from(fp.x0) * mpp, f64::from(fp.x1) * mpp];
            let z = [f64::from(fp.y0) * mpp, f64::from(fp.y1) * mpp];
            let height = facade_height(facade);
            let choose = input.facade_choice();
            let u_end = |wall: f64| wall / choose.repeat(facade, wall);
            let wall_material = choice
                .and_then(|c| clad.wall[c][tint[0]])
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
                .and_then(|r| clad.roof.get(r).and_then(|t| t[tint[1]]))
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
                building_name(building.id),
                vec![walls, top],
            )
        })
        .collect()
}
