//! FacadeSource: a facade set's files as the build driver read them (or the generator made
//! them), in the CMP Facade Database layout.

use image::codecs::jpeg::JpegEncoder;
use image::{ExtendedColorType, ImageEncoder, RgbImage};

/// JPEG quality of a painted photo written as a file (`cityspec facades export`).
pub const EXPORT_JPEG_QUALITY: u8 = 90;

/// One facade's files from a CMP-layout folder (or generated).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FacadeFile {
    /// Base name, e.g. `cmp_b0001`.
    pub name: String,
    /// The photo: `<name>.jpg`'s bytes, or the pixels the generator painted.
    pub photo: Photo,
    /// `<name>.xml` text (`None` when the file is missing).
    pub xml: Option<String>,
    /// `<name>.png` label mask bytes, if present. Carried for users of the set; the stage
    /// reads the XML boxes, not the mask.
    pub labels: Option<Vec<u8>>,
}

/// A facade photo as a source holds it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Photo {
    /// The bytes of a file (CMP ships JPEG; any format the image crate reads), decoded by
    /// the stage.
    File(Vec<u8>),
    /// Pixels the builtin generator painted in this process. The stage takes them as they
    /// are: encoding them to JPEG only to decode them again cost a cold build a quarter of
    /// its time and added nothing but compression noise.
    Painted(RgbImage),
}

impl Photo {
    /// The photo as file bytes: a file's own, or painted pixels as a JPEG of quality
    /// `EXPORT_JPEG_QUALITY` (90).
    pub fn file_bytes(&self) -> Vec<u8> {
        match self {
            Photo::File(bytes) => bytes.clone(),
            Photo::Painted(image) => {
                let mut jpeg = Vec::new();
                JpegEncoder::new_with_quality(&mut jpeg, EXPORT_JPEG_QUALITY)
                    .write_image(
                        image.as_raw(),
                        image.width(),
                        image.height(),
                        ExtendedColorType::Rgb8,
                    )
                    .expect("encoding a JPEG into memory cannot fail");
                jpeg
            }
        }
    }
}

/// A whole source: files sorted by name, the floors side file's text if any, and a label for
/// messages (the folder path as the user wrote it, or `builtin`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FacadeSource {
    pub origin: String,
    pub files: Vec<FacadeFile>,
    pub floors: Option<String>,
}

impl FacadeSource {
    /// The source as files of a CMP-layout folder: `(file name, bytes)` sorted by name, the
    /// floors side file (if any) as `floors.txt`. For `cityspec facades export DIR`.
    pub fn to_files(&self) -> Vec<(String, Vec<u8>)> {
        let mut out = Vec::new();
        for file in &self.files {
            out.push((format!("{}.jpg", file.name), file.photo.file_bytes()));
            if let Some(xml) = &file.xml {
                out.push((format!("{}.xml", file.name), xml.as_bytes().to_vec()));
            }
            if let Some(labels) = &file.labels {
                out.push((format!("{}.png", file.name), labels.clone()));
            }
        }
        if let Some(floors) = &self.floors {
            out.push(("floors.txt".to_string(), floors.as_bytes().to_vec()));
        }
        out.sort_by(|a, b| a.0.cmp(&b.0));
        out
    }

    /// `origin/name.ext`, the way messages name a file of this source.
    pub fn path(&self, name: &str, ext: &str) -> String {
        format!("{}/{name}.{ext}", self.origin.trim_end_matches('/'))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_are_listed_by_name_with_their_extensions() {
        let source = FacadeSource {
            origin: "data/cmp/".into(),
            files: vec![
                FacadeFile {
                    name: "b".into(),
                    photo: Photo::File(vec![1]),
                    xml: None,
                    labels: Some(vec![2]),
                },
                FacadeFile {
                    name: "a".into(),
                    photo: Photo::Painted(RgbImage::new(8, 8)),
                    xml: Some("<object/>".into()),
                    labels: None,
                },
            ],
            floors: Some("a 3\n".into()),
        };
        let names: Vec<String> = source.to_files().into_iter().map(|f| f.0).collect();
        assert_eq!(names, ["a.jpg", "a.xml", "b.jpg", "b.png", "floors.txt"]);
        let files = source.to_files();
        assert_eq!(files[2].1, [1], "a file's photo is written as it was read");
        let painted = image::load_from_memory(&files[0].1).unwrap();
        assert_eq!(
            (painted.width(), painted.height(), painted.color()),
            (8, 8, image::ColorType::Rgb8),
            "painted pixels are written as a JPEG"
        );
        assert_eq!(source.path("a", "xml"), "data/cmp/a.xml");
    }
}
