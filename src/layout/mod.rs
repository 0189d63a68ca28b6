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

mod generated_layout;

// Decoding lives in `image_file` because `spec` must refuse the same images the build does.
pub use crate::model::GeneratedLayout;
pub use crate::model::image_file::{LayoutError, MAX_PIXELS, MAX_SIDE, decode};
pub use generated_layout::generate;
