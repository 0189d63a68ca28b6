//! One rendered frame → its three images (four with normals), and their encodings (PNG,
//! and `.npy` for float depth).

use image::{ImageBuffer, Luma, Rgb, RgbImage};

use crate::model::image_file::{PngEffort, encode_png, npy_f32};
use crate::model::pack_ids;

pub use crate::spec::DepthFormat;

/// A rendered frame: linear colour, instance ids (0 = sky, object index + 1 otherwise, at
/// most 24 bits) and depth along the view axis in metres (0 = sky). [`Frame::rgb`]
/// develops the colour; a camera path develops it through its sensor instead.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// Linear scene radiance per pixel, row-major, before exposure and tone mapping,
    /// unclamped (HDR).
    pub linear: Vec<[f32; 3]>,
    pub instance: ImageBuffer<Luma<u32>, Vec<u32>>,
    pub depth: ImageBuffer<Luma<f32>, Vec<f32>>,
    /// Camera-space unit normals per pixel, row-major (x right, y down, z forward, facing
    /// the camera; `[0, 0, 0]` for the sky), when the frame was asked for them
    /// ([`super::render_with`]).
    pub normals: Option<Vec<[f32; 3]>>,
    /// The lighting's exposure, for [`Frame::rgb`].
    pub exposure: f32,
}

/// Encoded files of a frame: 8-bit RGB PNG, RGB-packed instance ids PNG, and the depth in
/// the path's [`DepthFormat`] (a 16-bit grey PNG, or a `.npy`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FramePngs {
    pub rgb: Vec<u8>,
    pub instance: Vec<u8>,
    pub depth: Vec<u8>,
    /// The normals' 16-bit RGB PNG, when the frame has normals.
    pub normals: Option<Vec<u8>>,
}

impl Frame {
    /// The default development of `linear`: the lighting's exposure, the filmic tone
    /// curve, sRGB ([`super::develop`]).
    pub fn rgb(&self) -> RgbImage {
        let (w, h) = self.instance.dimensions();
        super::develop::develop(&self.linear, w, h, self.exposure)
    }

    /// Encodes `rgb` (this frame's colour, as [`Frame::rgb`] or a sensor develops it) and
    /// the other two images (in parallel) with fixed settings: the same frame gives
    /// the same bytes.
    ///
    /// Instance ids are packed into an 8-bit RGB PNG as COCO panoptic does:
    /// `id = R + 256·G + 256²·B`. Depth follows `depth`: millimetres or centimetres
    /// rounded and clamped to 1–65535 in a 16-bit grey PNG (0 stays the sky), or float32
    /// metres in a `.npy`. Normals, when the frame has them: [`Frame::normals_rgb16`].
    pub fn encode(&self, rgb: &RgbImage, depth: DepthFormat) -> FramePngs {
        let ((rgb, normals), (instance, depth)) = rayon::join(
            || {
                rayon::join(
                    || encode_png(rgb, PngEffort::Fast),
                    || {
                        self.normals_rgb16()
                            .map(|image| encode_png(&image, PngEffort::Fast))
                    },
                )
            },
            || {
                rayon::join(
                    || encode_png(&pack_ids(&self.instance), PngEffort::Fast),
                    || match depth {
                        DepthFormat::F32 => {
                            let (w, h) = self.depth.dimensions();
                            npy_f32(w, h, self.depth.as_raw())
                        }
                        format => encode_png(&self.depth_u16(format), PngEffort::Fast),
                    },
                )
            },
        );
        FramePngs {
            rgb,
            instance,
            depth,
            normals,
        }
    }

    /// The normals as a 16-bit RGB image, when the frame has them: each component `n` of a
    /// unit normal as `round((n + 1) / 2 · 65535)` (so `n = value / 65535 · 2 − 1`), the
    /// sky `(0, 0, 0)`, which no unit normal gives.
    pub fn normals_rgb16(&self) -> Option<ImageBuffer<Rgb<u16>, Vec<u16>>> {
        let normals = self.normals.as_ref()?;
        let (w, h) = self.instance.dimensions();
        let value =
            |c: f32| ((f64::from(c) + 1.0) * 0.5 * 65535.0 + 0.5).clamp(0.0, 65535.0) as u16;
        let raw = normals
            .iter()
            .flat_map(|&n| if n == [0.0; 3] { [0; 3] } else { n.map(value) })
            .collect();
        ImageBuffer::from_raw(w, h, raw)
    }

    /// The depth as 16-bit units of `format`'s scale (1 mm or 1 cm), rounded and clamped to
    /// 1–65535; 0 for the sky. `F32` counts as millimetres.
    pub fn depth_u16(&self, format: DepthFormat) -> ImageBuffer<Luma<u16>, Vec<u16>> {
        let per_metre = match format {
            DepthFormat::Cm16 => 100.0,
            DepthFormat::Mm16 | DepthFormat::F32 => 1000.0,
        };
        let (w, h) = self.depth.dimensions();
        let units = self.depth.as_raw().iter().map(|&d| {
            if d > 0.0 {
                // `round`, as adding ½ and truncating: the same for values from ½ up
                // (the sum is exact below 2^52, and the clamp caps it), and below ½
                // both end at the clamp's 1. NaN fails `d > 0`.
                (f64::from(d) * per_metre + 0.5).clamp(1.0, 65535.0) as u16
            } else {
                0
            }
        });
        ImageBuffer::from_raw(w, h, units.collect()).expect("one depth a pixel")
    }

    /// The depth in millimetres as the 16-bit PNG of [`DepthFormat::Mm16`] holds it.
    pub fn depth_mm(&self) -> ImageBuffer<Luma<u16>, Vec<u16>> {
        self.depth_u16(DepthFormat::Mm16)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::unpack_ids;
    use image::DynamicImage;

    fn frame() -> Frame {
        Frame {
            linear: vec![[0.0; 3]; 15],
            instance: ImageBuffer::from_fn(5, 3, |x, y| {
                Luma([[0, 1, 255, 256, 65_535, 65_536, 16_777_215][((x + y) % 7) as usize]])
            }),
            depth: ImageBuffer::from_fn(5, 3, |x, y| {
                Luma([[0.0, 0.0004, 1.0, 65.5354, 65.536, 655.36, 2500.25]
                    [((x + 2 * y) % 7) as usize]])
            }),
            normals: None,
            exposure: 1.0,
        }
    }

    #[test]
    fn ids_round_trip_through_the_rgb_png_beyond_sixteen_bits() {
        let frame = frame();
        let files = frame.encode(&frame.rgb(), DepthFormat::Cm16);
        assert_eq!(files, frame.encode(&frame.rgb(), DepthFormat::Cm16));
        let rgb = image::load_from_memory(&files.instance).unwrap();
        assert!(matches!(rgb, DynamicImage::ImageRgb8(_)));
        assert_eq!(unpack_ids(&rgb.into_rgb8()), frame.instance);
        // COCO panoptic's rule, written out: 65,536 is (0, 0, 1).
        let packed = pack_ids(&ImageBuffer::from_pixel(1, 1, Luma([65_536 + 2 * 256 + 3])));
        assert_eq!(packed.get_pixel(0, 0).0, [3, 2, 1]);
    }

    #[test]
    fn sixteen_bit_depth_is_scaled_rounded_and_clamped() {
        let frame = frame();
        for (format, expected) in [
            (
                DepthFormat::Mm16,
                [0u16, 1, 1000, 65535, 65535, 65535, 65535],
            ),
            (DepthFormat::Cm16, [0, 1, 100, 6554, 6554, 65535, 65535]),
        ] {
            let png = frame.encode(&frame.rgb(), format).depth;
            let back = image::load_from_memory(&png).unwrap().into_luma16();
            assert_eq!(back, frame.depth_u16(format));
            let first_row: Vec<u16> = (0..5).map(|x| back.get_pixel(x, 0).0[0]).collect();
            assert_eq!(first_row, expected[..5], "{format:?}");
            let y = 1; // (x + 2) % 7: 2, 3, 4, 5, 6
            assert_eq!(back.get_pixel(3, y).0[0], expected[5], "{format:?}");
            assert_eq!(back.get_pixel(4, y).0[0], expected[6], "{format:?}");
        }
    }

    #[test]
    fn float_depth_is_a_numpy_file() {
        let frame = frame();
        let npy = frame.encode(&frame.rgb(), DepthFormat::F32).depth;
        assert_eq!(&npy[..8], b"\x93NUMPY\x01\x00");
        let len = usize::from(u16::from_le_bytes([npy[8], npy[9]]));
        assert_eq!((10 + len) % 64, 0);
        let header = std::str::from_utf8(&npy[10..10 + len]).unwrap();
        assert!(header.starts_with("{'descr': '<f4', 'fortran_order': False, 'shape': (3, 5), }"));
        assert!(header.ends_with('\n'));
        let values: Vec<f32> = npy[10 + len..]
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        assert_eq!(values, frame.depth.as_raw().clone());
    }
}
