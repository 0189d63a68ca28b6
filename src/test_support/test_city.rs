//! Other stages' outputs for a stage's tests: generated layouts, parsed layouts, the
//! default city (layout → parse → lamps → place) and its scene.

use image::RgbImage;

use crate::model::geometry::widths_px;
use crate::model::{Building, FacadeSet, GeneratedLayout, Lamp, ParsedLayout, Scene};
use crate::rng::stream;
use crate::spec::{GenerateSpec, Palette};

/// The layout generated from `spec` with the default palette and `seed`'s layout stream.
pub fn generated(spec: &GenerateSpec, seed: u64) -> GeneratedLayout {
    crate::layout::generate(spec, &Palette::default(), &mut stream(seed, "layout", 0))
}

/// `image` parsed with `palette`.
pub fn parsed(image: &RgbImage, palette: &Palette) -> ParsedLayout {
    crate::parse::parse(image, palette)
}

/// `image` after the mirror stage's `ops`.
pub fn mirrored(image: &RgbImage, ops: &[u8]) -> RgbImage {
    crate::mirror::mirror(image, ops)
}

/// PNG or JPEG bytes decoded as the layout stage decodes a user's image.
pub fn decoded(bytes: &[u8]) -> RgbImage {
    crate::model::image_file::decode(bytes).expect("a decodable test image")
}

/// The default 768 × 768 city at 1 m per pixel: its layout image, parsed layout, lamps
/// (every 20 m, 100 m apart at most) and buildings of the given widths in metres, 2 px
/// apart.
pub struct TestCity {
    pub image: RgbImage,
    pub layout: ParsedLayout,
    pub lamps: Vec<Lamp>,
    pub buildings: Vec<Building>,
}

/// The default city of `seed` with buildings `widths_m` metres wide.
pub fn test_city(seed: u64, widths_m: &[f64]) -> TestCity {
    let palette = Palette::default();
    let image = generated(&GenerateSpec::default(), seed).image;
    let layout = parsed(&image, &palette);
    let lamps = crate::lamps::site_lamps(&image, &layout, &palette, 100.0, 20.0);
    let buildings = crate::place::place(&layout.blocks, &widths_px(widths_m, 1.0), 2, seed);
    TestCity {
        image,
        layout,
        lamps,
        buildings,
    }
}

/// The scene stage's city of these parts at 1 m per pixel, buildings sized by their
/// facades (no spec widths).
pub fn scene(
    layout: &ParsedLayout,
    lamps: &[Lamp],
    buildings: &[Building],
    facades: &FacadeSet,
    seed: u64,
) -> Scene {
    crate::scene::build(&crate::scene::SceneInput {
        layout,
        lamps,
        buildings,
        facades,
        widths: None,
        metres_per_pixel: 1.0,
        seed,
    })
}
