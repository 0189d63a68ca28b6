//! The fixed materials every scene has → their indices: ground, paving, asphalt, marking,
//! concrete, lamp metal, the emissive lamp head and the woods on the hills.

use super::procedural;
use crate::model::Texture;
use crate::model::geometry::MaterialBook;

/// Indices of the fixed materials, registered first and always in this order.
pub struct Surfaces {
    pub grass: u32,
    pub paving: u32,
    pub asphalt: u32,
    pub marking: u32,
    pub concrete: u32,
    pub lamp_metal: u32,
    pub lamp_head: u32,
    pub woods: u32,
}

/// Warm white light of a lamp head (linear RGB).
pub const LAMP_EMISSIVE: [f32; 3] = [1.0, 0.82, 0.56];

impl Surfaces {
    pub fn register(book: &mut MaterialBook) -> Surfaces {
        let white = [1.0; 3];
        let none = [0.0; 3];
        let textured = |book: &mut MaterialBook, name: &str, image| {
            book.add(name, white, Some(&Texture::from_rgb(name, image)), none)
        };
        Surfaces {
            grass: textured(book, "grass", procedural::grass()),
            paving: textured(book, "paving", procedural::paving()),
            asphalt: textured(book, "asphalt", procedural::asphalt()),
            marking: book.add("marking", [0.85, 0.85, 0.82], None, none),
            concrete: textured(book, "concrete", procedural::concrete()),
            lamp_metal: book.add("lamp_metal", [0.05, 0.055, 0.06], None, none),
            lamp_head: book.add("lamp_head", [1.0, 0.95, 0.85], None, LAMP_EMISSIVE),
            woods: textured(book, "woods", procedural::woods()),
        }
    }
}
