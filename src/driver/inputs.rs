//! The build driver's reading of a spec's input files: layout image, facade folder.
//!
//! Stages never touch files; the driver reads what a spec names here, hashes it for the
//! stage keys and hands the bytes on.

use std::fs;
use std::path::{Path, PathBuf};

use sha2::{Digest, Sha256};

use super::BuildError;
use super::input_problem::InputProblem;
use super::model_files;
use std::collections::BTreeMap;

use crate::facades::{FacadeFile, FacadeSource, Photo};
use crate::hash::hex;
use crate::objects::MeshFiles;
use crate::spec::EntryKind;
use crate::spec::{self, BUILTIN_FACADES, InputFileError, Spec};

/// Every input file a spec names, read and hashed: what the stage keys and the stages need
/// besides the spec itself.
pub struct SpecInputs {
    pub layout: LayoutSource,
    pub facades: FacadeInput,
    /// Mesh models and word files, by the spec's string.
    pub meshes: BTreeMap<String, MeshFiles>,
    /// A digest of every mesh model and word file, for the export key.
    pub meshes_digest: String,
    /// Every file read, in the order it was read (`cityspec pack` ships them).
    pub files: Vec<PathBuf>,
}

impl SpecInputs {
    /// Reads the layout image, the facade folder and the mesh and word files `spec` names
    /// (relative to `spec_path`).
    pub fn read(spec_path: &Path, spec: &Spec) -> Result<SpecInputs, BuildError> {
        let mut files = Vec::new();
        let layout = layout_source(spec_path, spec)?;
        if let LayoutSource::Image { path, .. } | LayoutSource::Osm { path, .. } = &layout {
            files.push(path.clone());
        }
        let facades = facade_input(spec_path, spec, &mut files)?;
        let (meshes, meshes_digest) = mesh_files(spec_path, spec, &mut files)?;
        Ok(SpecInputs {
            layout,
            facades,
            meshes,
            meshes_digest,
            files,
        })
    }

    /// A spec's inputs when it names no file: a generated layout, the built-in facades and
    /// no models.
    #[cfg(test)]
    pub fn generated() -> SpecInputs {
        SpecInputs {
            layout: LayoutSource::Generate,
            facades: FacadeInput::Builtin,
            meshes: BTreeMap::new(),
            meshes_digest: hex(&Sha256::new().finalize()),
            files: Vec::new(),
        }
    }
}

/// Where the layout comes from.
pub enum LayoutSource {
    Generate,
    /// The user's image: its path (for messages) and bytes.
    Image {
        path: PathBuf,
        bytes: Vec<u8>,
    },
    /// An OpenStreetMap extract: its path (for messages), bytes and the box to build.
    Osm {
        path: PathBuf,
        bytes: Vec<u8>,
        bbox: Option<crate::model::GeoBox>,
    },
}

/// Where the facades come from.
pub enum FacadeInput {
    /// cityspec's own set, generated when the facades stage runs.
    Builtin,
    /// A CMP-layout folder, read whole; `digest` covers every file's name and bytes.
    Folder {
        source: FacadeSource,
        digest: String,
    },
}

/// Reads the layout image a spec names, if any.
pub fn layout_source(spec_path: &Path, spec: &Spec) -> Result<LayoutSource, BuildError> {
    if let Some(osm) = &spec.layout.osm {
        let file = spec::resolve(spec_path, &osm.file);
        let bytes =
            spec::read_capped(&file, super::osm_map::MAX_EXTRACT_BYTES).map_err(|source| {
                BuildError::Input {
                    spec: spec_path.to_path_buf(),
                    key: "layout.osm.file",
                    file: file.clone(),
                    entry: None,
                    source: Box::new(InputProblem::Read {
                        expected: "an OpenStreetMap extract",
                        source,
                    }),
                }
            })?;
        return Ok(LayoutSource::Osm {
            path: file,
            bytes,
            bbox: osm.geo_box(),
        });
    }
    let Some(relative) = &spec.layout.image else {
        return Ok(LayoutSource::Generate);
    };
    let file = spec::resolve(spec_path, relative);
    let bytes =
        spec::read_capped(&file, spec::MAX_IMAGE_BYTES).map_err(|source| BuildError::Input {
            spec: spec_path.to_path_buf(),
            key: "layout.image",
            file: file.clone(),
            entry: None,
            source: Box::new(InputProblem::Read {
                expected: "a layout image",
                source,
            }),
        })?;
    Ok(LayoutSource::Image { path: file, bytes })
}

/// Reads a CMP-layout facade folder: every `<name>.jpg` with its `<name>.xml` and
/// `<name>.png` when present, sorted by name, and the floors side file.
pub fn facade_input(
    spec_path: &Path,
    spec: &Spec,
    read: &mut Vec<PathBuf>,
) -> Result<FacadeInput, BuildError> {
    let facades = &spec.facades;
    if facades.source == BUILTIN_FACADES {
        return Ok(FacadeInput::Builtin);
    }
    let folder = spec::resolve(spec_path, &facades.source);
    let input_error = |file: &Path, source: InputProblem| BuildError::Input {
        spec: spec_path.to_path_buf(),
        key: "facades.source",
        file: file.to_path_buf(),
        entry: None,
        source: Box::new(source),
    };
    let read_error = |file: &Path, expected: &'static str, source| {
        input_error(file, InputProblem::Read { expected, source })
    };
    let mut names: Vec<String> = fs::read_dir(&folder)
        .map_err(|e| input_error(&folder, InputProblem::Folder(e)))?
        .filter_map(|entry| entry.ok())
        .filter_map(|entry| {
            let name = entry.file_name().to_string_lossy().into_owned();
            let stem = name
                .strip_suffix(".jpg")
                .or_else(|| name.strip_suffix(".jpeg"))?;
            Some(stem.to_owned())
        })
        .collect();
    names.sort();
    names.dedup();
    if names.is_empty() {
        return Err(input_error(&folder, InputProblem::NoPhotos));
    }
    let mut digest = Sha256::new();
    let mut files = Vec::with_capacity(names.len());
    for name in names {
        let photo_path = ["jpg", "jpeg"]
            .iter()
            .map(|ext| folder.join(format!("{name}.{ext}")))
            .find(|p| p.is_file())
            .unwrap_or_else(|| folder.join(format!("{name}.jpg")));
        let photo = spec::read_capped(&photo_path, spec::MAX_TEXTURE_BYTES)
            .map_err(|e| read_error(&photo_path, "a facade photo", e))?;
        read.push(photo_path);
        let mut optional = |ext: &str| {
            let path = folder.join(format!("{name}.{ext}"));
            let bytes = read_optional(&path).map_err(|e| read_error(&path, "a facade file", e))?;
            if bytes.is_some() {
                read.push(path);
            }
            Ok::<_, BuildError>(bytes)
        };
        let xml = optional("xml")?.map(|bytes| String::from_utf8_lossy(&bytes).into_owned());
        let labels = optional("png")?;
        for part in [
            Some(name.as_bytes()),
            Some(&photo[..]),
            xml.as_ref().map(|x| x.as_bytes()),
            labels.as_deref(),
        ] {
            match part {
                Some(bytes) => {
                    digest.update((bytes.len() as u64 + 1).to_le_bytes());
                    digest.update(bytes);
                }
                None => digest.update(0u64.to_le_bytes()),
            }
        }
        files.push(FacadeFile {
            name,
            photo: Photo::File(photo),
            xml,
            labels,
        });
    }
    let floors = match &facades.floors {
        Some(relative) => {
            let file = folder.join(relative);
            let text = spec::read_text_capped(&file, spec::MAX_FLOORS_BYTES).map_err(|source| {
                BuildError::Input {
                    spec: spec_path.to_path_buf(),
                    key: "facades.floors",
                    file: file.clone(),
                    entry: None,
                    source: Box::new(InputProblem::Read {
                        expected: "a floors file",
                        source,
                    }),
                }
            })?;
            digest.update((text.len() as u64 + 1).to_le_bytes());
            digest.update(text.as_bytes());
            read.push(file);
            Some(text)
        }
        None => None,
    };
    let source = FacadeSource {
        origin: facades.source.clone(),
        files,
        floors,
    };
    Ok(FacadeInput::Folder {
        source,
        digest: hex(&digest.finalize()),
    })
}

/// The file's bytes if it exists; a file that is there but not a regular file, or over the
/// cap, is an error rather than "absent".
fn read_optional(path: &Path) -> Result<Option<Vec<u8>>, InputFileError> {
    match spec::check_file(path, spec::MAX_TEXTURE_BYTES) {
        Err(InputFileError::NotFound) => Ok(None),
        Err(why) => Err(why),
        Ok(_) => spec::read_capped(path, spec::MAX_TEXTURE_BYTES).map(Some),
    }
}

/// Largest word file a text object may name, in bytes.
pub const MAX_WORDS_FILE: u64 = 1 << 20;

/// Reads every model a `mesh` object names: the OBJ, the MTL its `mtllib` names (beside
/// it), and the texture files that MTL names; and every `words_file` a `text` object names
/// (its bytes as the `obj`, at most [`MAX_WORDS_FILE`]). Returns them keyed by the spec's
/// `model` or `words_file` string, and a digest of all their bytes for the stage keys.
///
/// A model is read and parsed by [`model_files::read`]: an error points into the OBJ or
/// MTL itself.
pub fn mesh_files(
    spec_path: &Path,
    spec: &Spec,
    read: &mut Vec<PathBuf>,
) -> Result<(BTreeMap<String, MeshFiles>, String), BuildError> {
    let mut meshes = BTreeMap::new();
    let mut digest = Sha256::new();
    for (index, object) in spec.objects.iter().enumerate() {
        if let (EntryKind::Text | EntryKind::StreetName, Some(words)) =
            (object.kind, &object.words_file)
        {
            if !meshes.contains_key(words) {
                let bytes = words_file(spec_path, words, index)?;
                read.push(spec::resolve(spec_path, words));
                for part in [words.as_bytes(), &bytes[..]] {
                    digest.update((part.len() as u64).to_le_bytes());
                    digest.update(part);
                }
                let files = MeshFiles {
                    obj: bytes,
                    ..MeshFiles::default()
                };
                meshes.insert(words.clone(), files);
            }
            continue;
        }
        let (EntryKind::Mesh, Some(model)) = (object.kind, &object.model) else {
            continue;
        };
        if meshes.contains_key(model) {
            continue;
        }
        let MeshFiles { obj, mtl, textures } = model_files::read(spec_path, model, index, read)?;
        for part in [
            model.as_bytes(),
            &obj[..],
            mtl.as_deref().unwrap_or_default(),
        ] {
            digest.update((part.len() as u64).to_le_bytes());
            digest.update(part);
        }
        for (name, bytes) in &textures {
            digest.update(name.as_bytes());
            digest.update((bytes.len() as u64).to_le_bytes());
            digest.update(bytes);
        }
        meshes.insert(model.clone(), MeshFiles { obj, mtl, textures });
    }
    Ok((meshes, hex(&digest.finalize())))
}

/// Reads a text object's word file: at most [`MAX_WORDS_FILE`] bytes of UTF-8 holding at
/// least one word.
fn words_file(spec_path: &Path, words: &str, index: usize) -> Result<Vec<u8>, BuildError> {
    let file = spec::resolve(spec_path, words);
    let error = |source: InputProblem| BuildError::Input {
        spec: spec_path.to_path_buf(),
        key: "objects.words_file",
        file: file.clone(),
        entry: Some(format!("objects[{index}].words_file")),
        source: Box::new(source),
    };
    // Through `regular_file`, like every input: a FIFO is refused at once, never read.
    let bytes = spec::read_capped(&file, MAX_WORDS_FILE).map_err(|source| match source {
        InputFileError::TooLarge { size, cap } => error(InputProblem::WordsTooLarge { size, cap }),
        source => error(InputProblem::Read {
            expected: "a word file",
            source,
        }),
    })?;
    match std::str::from_utf8(&bytes) {
        Err(e) => Err(error(InputProblem::WordsNotUtf8(e))),
        Ok(text) if crate::objects::parse_words(text).is_empty() => {
            Err(error(InputProblem::NoWords))
        }
        Ok(_) => Ok(bytes),
    }
}
