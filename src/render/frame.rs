//! One rendered frame → its three images, and their PNG encodings.

use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{DynamicImage, ImageBuffer, Luma, RgbImage};

/// A rendered frame: sRGB colour, instance ids (0 = sky, object index + 1 otherwise) and
/// depth along the view axis in millimetres (0 = sky, clamped to 65535).
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// The default development of `linear`: the lighting's exposure, the filmic tone
    /// curve, sRGB ([`super::develop`]).
    pub rgb: RgbImage,
    /// Linear scene radiance per pixel, row-major, before exposure and tone mapping,
    /// unclamped (HDR).
    pub linear: Vec<[f32; 3]>,
    pub instance: ImageBuffer<Luma<u16>, Vec<u16>>,
    pub depth_mm: ImageBuffer<Luma<u16>, Vec<u16>>,
}

/// PNG bytes of a frame's images: 8-bit RGB, 16-bit grey instance ids, 16-bit grey depth.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FramePngs {
    pub rgb: Vec<u8>,
    pub instance: Vec<u8>,
    pub depth_mm: Vec<u8>,
}

impl Frame {
    /// Encodes the three images (in parallel) with fixed settings: the same frame gives
    /// the same bytes.
    pub fn encode_png(&self) -> FramePngs {
        let (rgb, (instance, depth_mm)) = rayon::join(
            || encode(DynamicImage::ImageRgb8(self.rgb.clone())),
            || {
                rayon::join(
                    || encode(DynamicImage::ImageLuma16(self.instance.clone())),
                    || encode(DynamicImage::ImageLuma16(self.depth_mm.clone())),
                )
            },
        );
        FramePngs {
            rgb,
            instance,
            depth_mm,
        }
    }
}

fn encode(image: DynamicImage) -> Vec<u8> {
    let mut png = Vec::new();
    image
        .write_with_encoder(PngEncoder::new_with_quality(
            &mut png,
            CompressionType::Fast,
            FilterType::Adaptive,
        ))
        .expect("encoding a PNG into memory cannot fail");
    png
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sixteen_bit_images_round_trip_through_png() {
        let instance = ImageBuffer::from_fn(5, 3, |x, y| Luma([(x * 1000 + y) as u16 + 300]));
        let depth_mm = ImageBuffer::from_fn(5, 3, |x, _| Luma([65535 - x as u16]));
        let frame = Frame {
            rgb: RgbImage::new(5, 3),
            linear: vec![[0.0; 3]; 15],
            instance: instance.clone(),
            depth_mm: depth_mm.clone(),
        };
        let png = frame.encode_png();
        assert_eq!(png, frame.encode_png());
        let back = image::load_from_memory(&png.instance)
            .unwrap()
            .into_luma16();
        assert_eq!(back, instance);
        let back = image::load_from_memory(&png.depth_mm)
            .unwrap()
            .into_luma16();
        assert_eq!(back, depth_mm);
    }
}
