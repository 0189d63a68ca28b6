//! Decoding a user's layout image: PNG or JPEG bytes → RGB pixels.

use std::io::Cursor;

use image::{DynamicImage, ImageDecoder, ImageFormat, ImageReader, Limits, RgbImage};

use super::LayoutError;

/// Largest accepted width or height of a layout image, in pixels.
pub const MAX_SIDE: u32 = 16384;
/// Largest accepted pixel count of a layout image (64 Mpx).
pub const MAX_PIXELS: u64 = 64 * 1024 * 1024;

/// Decodes a user's layout image (PNG or JPEG bytes) to RGB; alpha is composited over white.
///
/// The size is checked from the header before any pixel is decoded: images over
/// [`MAX_SIDE`] px a side or [`MAX_PIXELS`] pixels are refused (and `image::Limits` caps the
/// decoder's own allocations as a second guard).
pub fn decode(bytes: &[u8]) -> Result<RgbImage, LayoutError> {
    let reader = ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| LayoutError::Decode(image::ImageError::IoError(e)))?;
    match reader.format() {
        Some(ImageFormat::Png | ImageFormat::Jpeg) => {}
        _ => return Err(LayoutError::UnknownFormat),
    }
    let mut reader = reader;
    let mut limits = Limits::default();
    limits.max_image_width = Some(MAX_SIDE);
    limits.max_image_height = Some(MAX_SIDE);
    // Room for the largest accepted image at 16 bits per channel with alpha.
    limits.max_alloc = Some(MAX_PIXELS * 8);
    reader.limits(limits);
    let decoder = reader.into_decoder().map_err(|e| size_error(e, bytes))?;
    let (width, height) = decoder.dimensions();
    check_size(width, height)?;
    // The decoder fills a cut-off JPEG with grey rows without a word: refuse it here.
    super::check_complete(bytes).map_err(LayoutError::Truncated)?;
    let image = DynamicImage::from_decoder(decoder).map_err(|e| size_error(e, bytes))?;
    Ok(flatten(image))
}

/// Refuses sizes over the limits, and empty images.
fn check_size(width: u32, height: u32) -> Result<(), LayoutError> {
    if width > MAX_SIDE || height > MAX_SIDE || u64::from(width) * u64::from(height) > MAX_PIXELS {
        return Err(LayoutError::TooLarge {
            width,
            height,
            max_side: MAX_SIDE,
            max_pixels: MAX_PIXELS,
        });
    }
    if width == 0 || height == 0 {
        return Err(LayoutError::Empty);
    }
    Ok(())
}

/// Maps an `image` error to [`LayoutError`], turning a limit error into `TooLarge` when the
/// header's size can still be read (so the user learns the size, not just "limit exceeded").
fn size_error(error: image::ImageError, bytes: &[u8]) -> LayoutError {
    if let image::ImageError::Limits(_) = error {
        let size = ImageReader::new(Cursor::new(bytes))
            .with_guessed_format()
            .ok()
            .and_then(|r| r.into_dimensions().ok());
        if let Some((width, height)) = size
            && let Err(too_large) = check_size(width, height)
        {
            return too_large;
        }
    }
    LayoutError::Decode(error)
}

/// Converts to 8-bit RGB, compositing any alpha over white.
fn flatten(image: DynamicImage) -> RgbImage {
    if !image.color().has_alpha() {
        return image.to_rgb8();
    }
    let rgba = image.to_rgba8();
    let (width, height) = rgba.dimensions();
    let mut out = RgbImage::new(width, height);
    for (dst, src) in out.chunks_exact_mut(3).zip(rgba.chunks_exact(4)) {
        let alpha = u32::from(src[3]);
        for c in 0..3 {
            // Rounded (c·a + 255·(255 − a)) / 255.
            let value = u32::from(src[c]) * alpha + 255 * (255 - alpha);
            dst[c] = ((value + 127) / 255) as u8;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::{ImageEncoder, Rgb, Rgba, RgbaImage};

    fn png_bytes(image: &RgbaImage) -> Vec<u8> {
        let mut out = Vec::new();
        image::codecs::png::PngEncoder::new(&mut out)
            .write_image(
                image.as_raw(),
                image.width(),
                image.height(),
                image::ExtendedColorType::Rgba8,
            )
            .unwrap();
        out
    }

    /// CRC-32 (PNG's polynomial), to forge a valid header.
    fn crc32(data: &[u8]) -> u32 {
        let mut crc = 0xffff_ffffu32;
        for &byte in data {
            crc ^= u32::from(byte);
            for _ in 0..8 {
                crc = if crc & 1 != 0 {
                    (crc >> 1) ^ 0xedb8_8320
                } else {
                    crc >> 1
                };
            }
        }
        !crc
    }

    /// A small valid PNG whose IHDR then claims `width`×`height`.
    fn forged_png(width: u32, height: u32) -> Vec<u8> {
        let mut bytes = png_bytes(&RgbaImage::new(2, 2));
        // Signature (8), length (4), "IHDR" (4), then width and height.
        bytes[16..20].copy_from_slice(&width.to_be_bytes());
        bytes[20..24].copy_from_slice(&height.to_be_bytes());
        let crc = crc32(&bytes[12..29]);
        bytes[29..33].copy_from_slice(&crc.to_be_bytes());
        bytes
    }

    #[test]
    fn decodes_png_and_composites_alpha_over_white() {
        let mut image = RgbaImage::new(3, 1);
        image.put_pixel(0, 0, Rgba([10, 20, 30, 255]));
        image.put_pixel(1, 0, Rgba([0, 0, 0, 0]));
        image.put_pixel(2, 0, Rgba([0, 0, 0, 128]));
        let rgb = decode(&png_bytes(&image)).unwrap();
        assert_eq!(rgb.get_pixel(0, 0), &Rgb([10, 20, 30]));
        assert_eq!(rgb.get_pixel(1, 0), &Rgb([255, 255, 255]));
        assert_eq!(rgb.get_pixel(2, 0), &Rgb([127, 127, 127]));
    }

    #[test]
    fn decodes_jpeg() {
        let image = RgbImage::from_pixel(16, 8, Rgb([128, 128, 128]));
        let mut bytes = Vec::new();
        image::codecs::jpeg::JpegEncoder::new_with_quality(&mut bytes, 90)
            .encode_image(&image)
            .unwrap();
        let rgb = decode(&bytes).unwrap();
        assert_eq!(rgb.dimensions(), (16, 8));
        assert!(
            rgb.pixels()
                .all(|p| p.0.iter().all(|&c| c.abs_diff(128) <= 2))
        );
    }

    #[test]
    fn forged_header_is_valid_at_its_true_size() {
        // Guards the forgery itself: with the true size the bytes still decode.
        assert_eq!(decode(&forged_png(2, 2)).unwrap().dimensions(), (2, 2));
    }

    #[test]
    fn bad_inputs_are_errors_not_panics() {
        type Expect = fn(&LayoutError) -> bool;
        let cases: &[(&str, Vec<u8>, Expect)] = &[
            ("empty", vec![], |e| matches!(e, LayoutError::UnknownFormat)),
            ("garbage", b"not an image at all".to_vec(), |e| {
                matches!(e, LayoutError::UnknownFormat)
            }),
            (
                "truncated png",
                png_bytes(&RgbaImage::new(8, 8))[..40].to_vec(),
                |e| matches!(e, LayoutError::Decode(_) | LayoutError::Truncated(_)),
            ),
            (
                "too wide",
                forged_png(MAX_SIDE + 1, 4),
                |e| matches!(e, LayoutError::TooLarge { width, .. } if *width == MAX_SIDE + 1),
            ),
            ("too many pixels", forged_png(9000, 9000), |e| {
                matches!(e, LayoutError::TooLarge { height: 9000, .. })
            }),
            ("huge", forged_png(1 << 30, 1 << 30), |e| {
                matches!(e, LayoutError::TooLarge { .. } | LayoutError::Decode(_))
            }),
        ];
        for (name, bytes, expected) in cases {
            match decode(bytes) {
                Ok(_) => panic!("{name}: decoded"),
                Err(e) => assert!(expected(&e), "{name}: unexpected error {e:?}"),
            }
        }
    }
}
