//! Instance-id images ↔ 8-bit RGB, as COCO panoptic packs them: `id = R + 256·G + 256²·B`.
//!
//! The renderer writes `instance.png` this way, and the annotations and `cityspec stats`
//! read it back, so the encoding lives with the shared types.

use image::{ImageBuffer, Luma, RgbImage};

/// Instance ids as RGB: `R = id & 255`, `G = (id >> 8) & 255`, `B = (id >> 16) & 255`.
pub fn pack_ids(ids: &ImageBuffer<Luma<u32>, Vec<u32>>) -> RgbImage {
    let (w, h) = ids.dimensions();
    let mut raw = vec![0u8; ids.as_raw().len() * 3];
    for (rgb, &id) in raw.chunks_exact_mut(3).zip(ids.as_raw()) {
        rgb.copy_from_slice(&id.to_le_bytes()[..3]);
    }
    RgbImage::from_raw(w, h, raw).expect("three bytes per pixel")
}

/// Instance ids from an RGB-packed image (the inverse of [`pack_ids`]).
pub fn unpack_ids(rgb: &RgbImage) -> ImageBuffer<Luma<u32>, Vec<u32>> {
    let (w, h) = rgb.dimensions();
    let raw = rgb
        .as_raw()
        .chunks_exact(3)
        .map(|p| u32::from(p[0]) | u32::from(p[1]) << 8 | u32::from(p[2]) << 16)
        .collect();
    ImageBuffer::from_raw(w, h, raw).expect("one id per pixel")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_round_trip_beyond_sixteen_bits() {
        let ids = ImageBuffer::from_fn(3, 2, |x, y| Luma([x * 70_001 + y * 255 + 65_536]));
        assert_eq!(unpack_ids(&pack_ids(&ids)), ids);
        // COCO panoptic's rule, written out: 65,536 is (0, 0, 1).
        let packed = pack_ids(&ImageBuffer::from_pixel(1, 1, Luma([65_536 + 2 * 256 + 3])));
        assert_eq!(packed.get_pixel(0, 0).0, [3, 2, 1]);
    }
}
