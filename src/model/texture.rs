//! A texture as the stages hand it on: an encoded PNG with its name and size.
//!
//! Textures travel encoded: the exporter embeds the bytes as they are, the cache stores
//! them as they are, and only a stage that samples pixels (the renderer) decodes them.
//! A texture made in this process also keeps the pixels it was encoded from, so a cold
//! build samples them without decoding its own PNGs again (a tenth of its time).

use std::sync::Arc;

use image::RgbImage;
use serde::{Deserialize, Serialize};

/// A PNG texture.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Texture {
    /// Stable, file-name-safe name (e.g. `facade_builtin_07`, `asphalt`).
    pub name: String,
    pub width: u32,
    pub height: u32,
    /// The PNG bytes. Not serialized: the build driver stores them beside the JSON, as
    /// `<name>.png`, and puts them back when it reads a cached value.
    #[serde(skip)]
    pub png: Arc<Vec<u8>>,
    /// The pixels `png` encodes, when this process made it: never serialized, never
    /// compared (a texture read back from the cache is the same texture without them).
    #[serde(skip)]
    pixels: Pixels,
}

/// The decoded pixels a texture may carry beside its PNG, with the very PNG they were
/// encoded to: they stand for `png` only while `png` is still that allocation (one who
/// swaps the bytes gets them decoded; the shared `Arc` cannot be changed in place).
#[derive(Clone, Default)]
struct Pixels(Option<(Arc<Vec<u8>>, Arc<RgbImage>)>);

impl PartialEq for Pixels {
    /// Always equal: the pixels are a copy of what the PNG holds, not part of the value.
    fn eq(&self, _: &Pixels) -> bool {
        true
    }
}

impl Eq for Pixels {}

impl std::fmt::Debug for Pixels {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.0.is_some() {
            "decoded"
        } else {
            "encoded only"
        })
    }
}

use crate::model::image_file::PngEffort;

/// PNG bytes of an RGB image, as textures are stored (see [`crate::model::image_file::encode_png`]).
pub fn encode_png(image: &RgbImage) -> Vec<u8> {
    crate::model::image_file::encode_png(image, PngEffort::Fast)
}

impl Texture {
    /// Encodes `image` as a PNG with fixed settings, so the same pixels give the same bytes.
    /// Keeps `image` as the pixels it encodes (taken, not copied: a text atlas page is
    /// 6 MB).
    pub fn from_rgb(name: impl Into<String>, image: RgbImage) -> Texture {
        let png = Arc::new(encode_png(&image));
        Texture {
            name: name.into(),
            width: image.width(),
            height: image.height(),
            pixels: Pixels(Some((Arc::clone(&png), Arc::new(image)))),
            png,
        }
    }

    /// The same texture under another name.
    pub fn renamed(&self, name: String) -> Texture {
        Texture {
            name,
            ..self.clone()
        }
    }

    /// The pixels (for stages that sample them): the ones this texture was made from, else
    /// the PNG decoded.
    pub fn decode(&self) -> Result<RgbImage, image::ImageError> {
        match &self.pixels.0 {
            Some((png, pixels)) if Arc::ptr_eq(png, &self.png) => Ok(RgbImage::clone(pixels)),
            _ => image::load_from_memory_with_format(&self.png, image::ImageFormat::Png)
                .map(|i| i.to_rgb8()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encodes_deterministically_and_round_trips() {
        let image = RgbImage::from_fn(9, 4, |x, y| image::Rgb([x as u8 * 20, y as u8 * 50, 7]));
        let a = Texture::from_rgb("t", image.clone());
        let b = Texture::from_rgb("t", image.clone());
        assert_eq!(a, b);
        assert_eq!(a.png, b.png);
        assert_eq!((a.width, a.height), (9, 4));
        assert_eq!(a.decode().unwrap(), image);
        // Read back from its bytes alone (as from the cache): equal, and decodes the same.
        let cached = Texture {
            pixels: Pixels::default(),
            ..a.clone()
        };
        assert_eq!(cached, a);
        assert_eq!(cached.decode().unwrap(), image);
        // Other bytes put in its place are what decodes, not the pixels kept beside.
        let mut swapped = a.clone();
        swapped.png = Arc::new(vec![1, 2, 3]);
        assert!(swapped.decode().is_err());
    }
}
