//! FacadeSource: a facade set's files as the build driver read them (or the generator made
//! them), in the CMP Facade Database layout.

/// One facade's files from a CMP-layout folder (or generated).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FacadeFile {
    /// Base name, e.g. `cmp_b0001`.
    pub name: String,
    /// `<name>.jpg` bytes.
    pub photo: Vec<u8>,
    /// `<name>.xml` text (`None` when the file is missing).
    pub xml: Option<String>,
    /// `<name>.png` label mask bytes, if present. Carried for users of the set; the stage
    /// reads the XML boxes, not the mask.
    pub labels: Option<Vec<u8>>,
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
            out.push((format!("{}.jpg", file.name), file.photo.clone()));
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
                    photo: vec![1],
                    xml: None,
                    labels: Some(vec![2]),
                },
                FacadeFile {
                    name: "a".into(),
                    photo: vec![3],
                    xml: Some("<object/>".into()),
                    labels: None,
                },
            ],
            floors: Some("a 3\n".into()),
        };
        let names: Vec<String> = source.to_files().into_iter().map(|f| f.0).collect();
        assert_eq!(names, ["a.jpg", "a.xml", "b.jpg", "b.png", "floors.txt"]);
        assert_eq!(source.path("a", "xml"), "data/cmp/a.xml");
    }
}
