//! Linear colour → 8-bit RGB, one channel value at a time, rows in parallel: the shape of
//! every development (the renderer's default one, the sensor's).

use image::RgbImage;
use rayon::prelude::*;

/// `encode` applied to every channel of `linear` (row-major, `width × height`), rows in
/// parallel; each byte depends on its own value only, so the bytes do not depend on
/// threads. A black image when `linear` does not hold `width × height` pixels.
pub fn rgb8_by_channel(
    linear: &[[f32; 3]],
    width: u32,
    height: u32,
    encode: impl Fn(f32) -> u8 + Sync,
) -> RgbImage {
    if linear.len() != width as usize * height as usize {
        return RgbImage::new(width, height);
    }
    let mut bytes = vec![0u8; linear.len() * 3];
    bytes
        .par_chunks_mut(width.max(1) as usize * 3)
        .zip(linear.par_chunks(width.max(1) as usize))
        .for_each(|(out, row)| {
            for (o, c) in out.chunks_exact_mut(3).zip(row) {
                for k in 0..3 {
                    o[k] = encode(c[k]);
                }
            }
        });
    RgbImage::from_raw(width, height, bytes).unwrap_or_else(|| RgbImage::new(width, height))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_channel_is_encoded_in_place_and_a_wrong_size_is_black() {
        let linear = [[0.0, 0.5, 1.0], [0.25, 0.75, 2.0]];
        let image = rgb8_by_channel(&linear, 2, 1, |v| (v * 100.0) as u8);
        assert_eq!(image.as_raw(), &[0, 50, 100, 25, 75, 200]);
        let black = rgb8_by_channel(&linear, 3, 1, |_| 255);
        assert_eq!(black.as_raw(), &[0; 9]);
    }
}
