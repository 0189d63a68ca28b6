//! Image ends: PNG or JPEG bytes → whether the file is whole, or how it was cut short.
//!
//! The `image` crate decodes a truncated JPEG without complaint (the missing rows come out
//! grey), so a cut-off layout or facade photo would build silently. A whole JPEG ends its
//! last scan with an EOI marker (`FF D9`); entropy-coded data never holds `FF` followed by
//! anything but `00` or a restart marker, so walking the segments and scans finds the EOI
//! exactly, without decoding. PNG's decoder already refuses a file without its image data
//! end; [`check_complete`] also requires the `IEND` chunk so both formats fail the same way.

/// Ok when `bytes` is a whole JPEG or PNG (other formats pass unchecked); otherwise what is
/// wrong, completing "found {…}".
pub fn check_complete(bytes: &[u8]) -> Result<(), String> {
    if bytes.starts_with(&[0xff, 0xd8]) {
        jpeg_complete(bytes)
    } else if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        png_complete(bytes)
    } else {
        Ok(())
    }
}

fn truncated(what: &str, size: usize) -> String {
    format!("a truncated {what} ({size} bytes, cut off before its end marker)")
}

fn jpeg_complete(b: &[u8]) -> Result<(), String> {
    let n = b.len();
    let mut i = 2;
    while i + 1 < n {
        if b[i] != 0xff {
            // Stray bytes between segments: some writers pad; look for the next marker.
            i += 1;
            continue;
        }
        let marker = b[i + 1];
        match marker {
            0xd9 => return Ok(()),
            // Fill bytes, restart markers and TEM stand alone.
            0xff => i += 1,
            0xd0..=0xd7 | 0x01 => i += 2,
            0x00 => i += 2,
            _ => {
                if i + 3 >= n {
                    break;
                }
                let length = usize::from(u16::from_be_bytes([b[i + 2], b[i + 3]]));
                let end = i + 2 + length;
                if length < 2 || end > n {
                    break;
                }
                i = end;
                if marker == 0xda {
                    // Entropy-coded data runs to the next marker that is not a restart.
                    while i + 1 < n
                        && !(b[i] == 0xff && b[i + 1] != 0 && !(0xd0..=0xd7).contains(&b[i + 1]))
                    {
                        i += 1;
                    }
                }
            }
        }
    }
    Err(truncated("JPEG", n))
}

fn png_complete(b: &[u8]) -> Result<(), String> {
    let n = b.len();
    let mut i = 8;
    while i + 8 <= n {
        let length = u32::from_be_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]) as usize;
        if &b[i + 4..i + 8] == b"IEND" && i + 12 <= n {
            return Ok(());
        }
        // length + type + data + CRC
        match i.checked_add(12).and_then(|x| x.checked_add(length)) {
            Some(next) if next <= n => i = next,
            _ => break,
        }
    }
    Err(truncated("PNG", n))
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::{ImageEncoder, RgbImage};

    fn jpeg(image: &RgbImage, progressive_like_restarts: bool) -> Vec<u8> {
        let mut out = Vec::new();
        let mut encoder = image::codecs::jpeg::JpegEncoder::new_with_quality(&mut out, 90);
        if progressive_like_restarts {
            encoder
                .set_exif_metadata(vec![0xff, 0xd9, 0xff, 0xd9])
                .unwrap();
        }
        encoder
            .write_image(
                image.as_raw(),
                image.width(),
                image.height(),
                image::ExtendedColorType::Rgb8,
            )
            .unwrap();
        out
    }

    fn noisy(w: u32, h: u32) -> RgbImage {
        RgbImage::from_fn(w, h, |x, y| {
            let v = (x * 7919 + y * 104_729) % 251;
            image::Rgb([v as u8, (v * 3 % 256) as u8, (x ^ y) as u8])
        })
    }

    #[test]
    fn whole_files_pass_and_every_cut_is_found() {
        let image = noisy(64, 48);
        for bytes in [jpeg(&image, false), jpeg(&image, true)] {
            assert_eq!(check_complete(&bytes), Ok(()));
            // Every cut, including one that keeps an EOI-looking pair inside the EXIF block.
            for cut in (2..bytes.len()).step_by(7).chain([bytes.len() - 1]) {
                let error = check_complete(&bytes[..cut]).unwrap_err();
                assert!(error.starts_with("a truncated JPEG"), "{cut}: {error}");
            }
            // The image crate itself accepts a cut JPEG: the reason for this check.
            let half = &bytes[..bytes.len() * 2 / 3];
            assert!(image::load_from_memory(half).is_ok());
        }
        let mut png = Vec::new();
        image::codecs::png::PngEncoder::new(&mut png)
            .write_image(image.as_raw(), 64, 48, image::ExtendedColorType::Rgb8)
            .unwrap();
        assert_eq!(check_complete(&png), Ok(()));
        for cut in (8..png.len()).step_by(5) {
            assert!(check_complete(&png[..cut]).is_err(), "{cut}");
        }
        assert_eq!(check_complete(b"GIF89a"), Ok(()));
    }
}
