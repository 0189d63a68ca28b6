//! Pixels → PNG bytes, with the encoder settings fixed in one place so that the same pixels
//! give the same bytes whichever stage writes them.

use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{EncodableLayout, ImageBuffer, Pixel, PixelWithColorType};

/// How hard the encoder works. Either gives the same bytes for the same pixels; they only
/// trade time for size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PngEffort {
    /// For what is written on every build (textures, frames): quick, larger files. Every
    /// row is Paeth-filtered: on a street frame's RGB, ids and depth that gives files
    /// within 1 % of the adaptive choice per row, in a fifth less time (the encoder tries
    /// all five filters on each row to choose).
    Fast,
    /// Small files, slow: for what is written once and kept long. Adaptive row filters.
    Best,
}

/// PNG bytes of `image` (any pixel type the PNG encoder takes: RGB, grey, 16-bit grey),
/// with `effort`'s row filters and compression.
pub fn encode_png<P>(image: &ImageBuffer<P, Vec<P::Subpixel>>, effort: PngEffort) -> Vec<u8>
where
    P: Pixel + PixelWithColorType,
    [P::Subpixel]: EncodableLayout,
{
    let (compression, filter) = match effort {
        PngEffort::Fast => (CompressionType::Fast, FilterType::Paeth),
        PngEffort::Best => (CompressionType::Best, FilterType::Adaptive),
    };
    let mut png = Vec::new();
    image
        .write_with_encoder(PngEncoder::new_with_quality(&mut png, compression, filter))
        .expect("encoding a PNG into memory cannot fail");
    png
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::{GrayImage, ImageBuffer, Luma, RgbImage};

    #[test]
    fn encodes_rgb_grey_and_16_bit_grey_that_decode_back() {
        let rgb = RgbImage::from_fn(5, 3, |x, y| image::Rgb([x as u8, y as u8, 7]));
        let back = image::load_from_memory(&encode_png(&rgb, PngEffort::Fast)).unwrap();
        assert_eq!(back.to_rgb8(), rgb);
        let grey = GrayImage::from_fn(4, 4, |x, y| Luma([(x * y) as u8]));
        let fast = encode_png(&grey, PngEffort::Fast);
        let best = encode_png(&grey, PngEffort::Best);
        for bytes in [&fast, &best] {
            assert_eq!(image::load_from_memory(bytes).unwrap().to_luma8(), grey);
        }
        let deep: ImageBuffer<Luma<u16>, Vec<u16>> =
            ImageBuffer::from_fn(3, 2, |x, y| Luma([1000 * x as u16 + y as u16 + 1]));
        let back = image::load_from_memory(&encode_png(&deep, PngEffort::Fast)).unwrap();
        assert_eq!(back.to_luma16(), deep);
        assert_eq!(
            encode_png(&rgb, PngEffort::Fast),
            encode_png(&rgb, PngEffort::Fast)
        );
    }
}
