//! Layout stage: `spec.layout` + the layout stream → a layout image (paper 3.1), generated
//! at random ([`generate`]) or decoded from the user's PNG/JPEG ([`decode`]).
//!
//! A generated layout is drawn with the spec's palette: grey roads of `road_width` px that
//! span the whole image, horizontally and vertically, at random positions; a 1-px yellow
//! centre line along every road (drawn through crossings); and between the roads, blue
//! building blocks ringed by `strip_width` px of green lamp strip (the ring also runs along
//! the image border). [`GeneratedLayout`] carries, beside the image, the roads and blue
//! rectangles it drew: exactly what the parse stage must read back.

/// Bump when this stage's output bytes change: it is part of the stage's cache key.
pub const VERSION: u32 = 1;

mod decode;
mod generated_layout;
mod image_end;
mod layout_error;

pub use decode::{MAX_PIXELS, MAX_SIDE, decode};
pub use generated_layout::{GeneratedLayout, generate};
pub use image_end::check_complete;
pub use layout_error::LayoutError;
