//! BuildWorld: the spec stage's world in a build — the file system ([`FsWorld`]) plus the
//! parse stage's reading of a layout image.
//!
//! The spec stage may not run another stage, yet whether a layout image means anything
//! is the parse stage's to say: a street photo has pixels near every palette colour and
//! still no road or block. So the driver, which may name every stage, hands the spec stage
//! a world that parses, and such an image is refused with the spec's other errors, pointed
//! at `layout.image`, in `validate` and `build` alike.

use std::path::Path;

use image::RgbImage;

use crate::spec::{FsWorld, Palette, SpecWorld};

/// The file system, and the parse stage for layout images.
#[derive(Clone, Copy, Debug, Default)]
pub struct BuildWorld;

impl SpecWorld for BuildWorld {
    fn image_dimensions(&self, path: &Path) -> Result<(u32, u32), String> {
        FsWorld.image_dimensions(path)
    }

    fn folder(&self, path: &Path) -> Result<(), String> {
        FsWorld.folder(path)
    }

    fn file(&self, path: &Path) -> Result<(), String> {
        FsWorld.file(path)
    }

    fn spec_text(&self, path: &Path) -> Result<String, String> {
        FsWorld.spec_text(path)
    }

    fn layout_pixels(&self, path: &Path) -> Option<Result<RgbImage, String>> {
        FsWorld.layout_pixels(path)
    }

    fn parsed_layout(&self, pixels: &RgbImage, palette: &Palette) -> Option<(usize, usize)> {
        let parsed = crate::parse::parse(pixels, palette);
        Some((parsed.roads.len(), parsed.blocks.len()))
    }
}
