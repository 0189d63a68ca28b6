//! Bytes of stage outputs: PNG for images, JSON for values. Deterministic encoders only.

use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ImageEncoder, RgbImage};
use serde::Serialize;
use serde::de::DeserializeOwned;

/// PNG bytes of an RGB image. The encoder settings are fixed, so the bytes are too.
pub fn encode_png(image: &RgbImage) -> Vec<u8> {
    let mut bytes = Vec::new();
    PngEncoder::new_with_quality(&mut bytes, CompressionType::Fast, FilterType::Adaptive)
        .write_image(
            image.as_raw(),
            image.width(),
            image.height(),
            image::ExtendedColorType::Rgb8,
        )
        .expect("encoding a PNG into memory cannot fail");
    bytes
}

/// Decodes PNG bytes this module wrote.
pub fn decode_png(bytes: &[u8]) -> Result<RgbImage, String> {
    image::load_from_memory_with_format(bytes, image::ImageFormat::Png)
        .map(|image| image.to_rgb8())
        .map_err(|e| e.to_string())
}

/// Compact JSON for values only the cache reads.
pub fn to_json(value: &impl Serialize) -> Vec<u8> {
    serde_json::to_vec(value).expect("stage values serialize to JSON")
}

/// Pretty JSON with a trailing newline, for artifacts people read.
pub fn to_pretty_json(value: &impl Serialize) -> Vec<u8> {
    let mut bytes = serde_json::to_vec_pretty(value).expect("stage values serialize to JSON");
    bytes.push(b'\n');
    bytes
}

pub fn from_json<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, String> {
    serde_json::from_slice(bytes).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_round_trips_and_is_stable() {
        let image = RgbImage::from_fn(7, 5, |x, y| image::Rgb([x as u8 * 30, y as u8 * 40, 9]));
        let bytes = encode_png(&image);
        assert_eq!(bytes, encode_png(&image));
        assert_eq!(decode_png(&bytes).unwrap(), image);
        assert!(decode_png(b"not a png").is_err());
    }
}
