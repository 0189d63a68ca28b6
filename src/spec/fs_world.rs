//! FsWorld: the build driver's [`SpecWorld`] — image paths → sizes read from file headers.

use std::io::{BufReader, ErrorKind, Read, Seek, SeekFrom};
use std::path::Path;

use image::ImageReader;

use super::SpecWorld;
use super::input_file::{
    InputFileError, MAX_IMAGE_BYTES, MAX_MODEL_BYTES, MAX_SPEC_BYTES, check_file, open_capped,
    read_capped, read_text_capped,
};

/// The real file system: reads only the header of each image.
#[derive(Clone, Copy, Debug, Default)]
pub struct FsWorld;

impl SpecWorld for FsWorld {
    fn folder(&self, path: &Path) -> Result<(), String> {
        // Folders are listed, never read whole; their files go through the caps.
        match std::fs::metadata(path) {
            Ok(meta) if meta.is_dir() => Ok(()),
            Ok(_) => Err("a file, not a folder".to_string()),
            Err(e) if e.kind() == ErrorKind::NotFound => Err("no such folder".to_string()),
            Err(e) => Err(format!("an unreadable folder ({e})")),
        }
    }

    fn file(&self, path: &Path) -> Result<(), String> {
        // Every file a spec names is read through a cap; the largest cap is the model's.
        check_file(path, MAX_MODEL_BYTES)
            .map(|_| ())
            .map_err(|e| e.to_string())
    }

    fn spec_text(&self, path: &Path) -> Result<String, String> {
        read_text_capped(path, MAX_SPEC_BYTES).map_err(|e| e.to_string())
    }

    fn image_dimensions(&self, path: &Path) -> Result<(u32, u32), String> {
        if path.is_dir() {
            return Err("a directory".to_string());
        }
        // One open, through `regular_file`: a FIFO is refused at once, never waited on.
        let (mut file, _) = open_capped(path, MAX_IMAGE_BYTES).map_err(|e| e.to_string())?;
        let unreadable = |e: std::io::Error| InputFileError::of_io(e).to_string();
        // Judge by content, not by name: `with_guessed_format` would fall back to the
        // extension and blame a garbage `.png` on the PNG decoder.
        let mut head = Vec::with_capacity(32);
        (&mut file)
            .take(32)
            .read_to_end(&mut head)
            .map_err(unreadable)?;
        if image::guess_format(&head).is_err() {
            return Err("a file that is not a PNG or JPEG image".to_string());
        }
        file.seek(SeekFrom::Start(0)).map_err(unreadable)?;
        ImageReader::new(BufReader::new(file))
            .with_guessed_format()
            .map_err(unreadable)?
            .into_dimensions()
            .map_err(|e| format!("an unreadable image ({e})"))
    }

    fn layout_pixels(&self, path: &Path) -> Option<Result<image::RgbImage, String>> {
        // The same reading and decoding as the build's, so `validate` refuses what `build`
        // would (a truncated or corrupt image).
        Some(
            read_capped(path, MAX_IMAGE_BYTES)
                .map_err(|e| e.to_string())
                .and_then(|bytes| {
                    crate::model::image_file::decode(&bytes).map_err(|e| match e {
                        crate::model::image_file::LayoutError::Truncated(why) => why,
                        other => other.to_string(),
                    })
                }),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_sizes_and_explains_failures() {
        let dir = tempfile::tempdir().unwrap();
        let png = dir.path().join("a.png");
        image::RgbImage::new(5, 3).save(&png).unwrap();
        let garbage = dir.path().join("b.png");
        std::fs::write(&garbage, b"this is not an image at all").unwrap();
        let world = FsWorld;
        assert_eq!(world.image_dimensions(&png), Ok((5, 3)));
        assert_eq!(
            world.image_dimensions(&garbage),
            Err("a file that is not a PNG or JPEG image".to_string())
        );
        assert_eq!(
            world.image_dimensions(&dir.path().join("missing.png")),
            Err("no such file".to_string())
        );
        assert_eq!(
            world.image_dimensions(dir.path()),
            Err("a directory".to_string())
        );
    }
}
