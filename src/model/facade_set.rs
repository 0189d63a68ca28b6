//! A processed facade set: textures with their metric size, floors, molding colour, roof.

use serde::{Deserialize, Serialize};

use super::Texture;

/// Facades ready to clad buildings, and the roofs they choose from (paper 3.2).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FacadeSet {
    pub facades: Vec<Facade>,
    pub roofs: Vec<Roof>,
}

/// One facade, cropped below its first molding.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Facade {
    /// The source's base name (`cmp_b0001`, `builtin_07`).
    pub name: String,
    /// Floors of the cropped facade.
    pub floors: u32,
    /// Building height in metres: floors × floor height.
    pub height: f64,
    /// Building width in metres: cropped width / cropped height × `height`.
    pub width: f64,
    /// Mean colour of the first molding (or of the facade's top when it has none), sRGB.
    pub molding: [u8; 3],
    /// Mean colour of the cropped facade, sRGB: what a map's `building:colour` is matched
    /// by (`model::map_cladding`).
    #[serde(default)]
    pub colour: [u8; 3],
    /// Index into [`FacadeSet::roofs`] of the roof whose colour best matches `molding`.
    pub roof: u32,
    /// Window boxes in texture coordinates `[u0, v0, u1, v1]` (v down from the top edge),
    /// for lit windows at night.
    pub windows: Vec<[f32; 4]>,
    /// The cropped facade image.
    pub texture: Texture,
}

/// A roof texture and the colour it is matched by.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Roof {
    pub name: String,
    /// Mean colour, sRGB.
    pub colour: [u8; 3],
    /// Metres one texture repeat covers.
    pub tile: f64,
    pub texture: Texture,
}
