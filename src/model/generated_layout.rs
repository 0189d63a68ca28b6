//! A generated layout image with the roads and blue blocks drawn on it: the layout stage's
//! output, and what the parse stage's tests check their result against.

use image::RgbImage;

use super::{PxRect, Road};

/// A generated layout and what was drawn on it.
#[derive(Clone, Debug, PartialEq)]
pub struct GeneratedLayout {
    pub image: RgbImage,
    /// The roads, as the parse stage reports them: horizontal first, each group by position.
    pub roads: Vec<Road>,
    /// The blue rectangles, in raster order of their top-left pixel.
    pub blocks: Vec<PxRect>,
}
