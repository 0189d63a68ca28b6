//! `cityspec pack SPEC`: the spec and every file it reads, in one tar, so that a build on
//! another machine (a Kubernetes job, `deploy/k8s/run.sh`) reads the spec as written.
//!
//! The files are the ones a build reads: the spec and every spec it `extends` (as the
//! spec loader asks for them), and [`SpecInputs::files`] (the layout image, the facade
//! folder's photos, boxes, masks and floors file, the mesh models with their MTL files and
//! textures, the word files), so nothing a build needs can be left out. Each is
//! stored under its path relative to the folder all of them share, so relative paths in
//! the spec (`../assets/models/bench.obj`) resolve the same inside the unpacked archive.
//! One more entry, [`SPEC_ENTRY`], holds the spec's path inside the archive, so a job that
//! unpacks it finds the spec without being told. The tar is the same bytes every time:
//! entries sorted by name, mode 0644, owner 0, mtime 0.

use std::cell::RefCell;
use std::path::{Component, Path, PathBuf};

use image::RgbImage;

use super::build_world::BuildWorld;
use super::inputs::SpecInputs;
use super::{BuildError, load_spec_in};
use crate::spec::{Palette, SpecWorld};

/// [`BuildWorld`], noting every spec file the loader reads (the spec's `extends` chain).
#[derive(Default)]
struct SpecsRead(RefCell<Vec<PathBuf>>);

impl SpecWorld for SpecsRead {
    fn image_dimensions(&self, path: &Path) -> Result<(u32, u32), String> {
        BuildWorld.image_dimensions(path)
    }

    fn folder(&self, path: &Path) -> Result<(), String> {
        BuildWorld.folder(path)
    }

    fn file(&self, path: &Path) -> Result<(), String> {
        BuildWorld.file(path)
    }

    fn spec_text(&self, path: &Path) -> Result<String, String> {
        self.0.borrow_mut().push(path.to_path_buf());
        BuildWorld.spec_text(path)
    }

    fn layout_pixels(&self, path: &Path) -> Option<Result<RgbImage, String>> {
        BuildWorld.layout_pixels(path)
    }

    fn parsed_layout(&self, pixels: &RgbImage, palette: &Palette) -> Option<(usize, usize)> {
        BuildWorld.parsed_layout(pixels, palette)
    }
}

/// The entry that names the spec inside the archive (one line, `/`-separated).
pub const SPEC_ENTRY: &str = "CITYSPEC_SPEC";

/// A packed spec.
pub struct Packed {
    /// The tar's bytes.
    pub bytes: Vec<u8>,
    /// The spec's name inside the tar (where `cityspec build` finds it once unpacked).
    pub spec: String,
    /// Every entry's name, sorted.
    pub entries: Vec<String>,
}

/// Packs the spec at `spec_path` with every file a build of it reads.
pub fn pack(spec_path: &Path) -> Result<Packed, BuildError> {
    let bases = SpecsRead::default();
    let spec = load_spec_in(spec_path, &[], &bases)?;
    let inputs = SpecInputs::read(spec_path, &spec)?;
    let io_err = |path: &Path| {
        let path = path.to_path_buf();
        move |source| BuildError::Pack { path, source }
    };
    let mut files: Vec<PathBuf> = Vec::new();
    let specs = std::iter::once(spec_path.to_path_buf()).chain(bases.0.into_inner());
    for file in specs.chain(inputs.files) {
        let absolute = std::fs::canonicalize(&file).map_err(io_err(&file))?;
        if !files.contains(&absolute) {
            files.push(absolute);
        }
    }
    let root = common_folder(&files);
    let relative = |file: &Path| -> String {
        let inside = file.strip_prefix(&root).unwrap_or(file);
        inside
            .components()
            .filter_map(|c| match c {
                Component::Normal(part) => Some(part.to_string_lossy().into_owned()),
                _ => None,
            })
            .collect::<Vec<_>>()
            .join("/")
    };
    let spec_entry = relative(&files[0]);
    let mut entries: Vec<(String, Option<&PathBuf>)> =
        files.iter().map(|f| (relative(f), Some(f))).collect();
    entries.push((SPEC_ENTRY.to_owned(), None));
    entries.sort();
    let mut builder = tar::Builder::new(Vec::new());
    builder.mode(tar::HeaderMode::Deterministic);
    for (name, file) in &entries {
        let bytes = match file {
            Some(file) => crate::regular_file::read(file, crate::regular_file::Follow::Yes)
                .map_err(io_err(file))?,
            None => format!("{spec_entry}\n").into_bytes(),
        };
        let mut header = tar::Header::new_ustar();
        header.set_size(bytes.len() as u64);
        header.set_mode(0o644);
        header.set_mtime(0);
        header.set_uid(0);
        header.set_gid(0);
        header.set_entry_type(tar::EntryType::Regular);
        builder
            .append_data(&mut header, name, &bytes[..])
            .map_err(io_err(spec_path))?;
    }
    let bytes = builder.into_inner().map_err(io_err(spec_path))?;
    Ok(Packed {
        bytes,
        spec: spec_entry,
        entries: entries.into_iter().map(|(name, _)| name).collect(),
    })
}

/// The deepest folder that holds every one of `files` (absolute paths).
fn common_folder(files: &[PathBuf]) -> PathBuf {
    let mut root: Option<PathBuf> = None;
    for file in files {
        let folder = file.parent().unwrap_or(file).to_path_buf();
        root = Some(match root {
            None => folder,
            Some(root) => root
                .components()
                .zip(folder.components())
                .take_while(|(a, b)| a == b)
                .map(|(a, _)| a)
                .collect(),
        });
    }
    root.unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_common_folder_is_the_deepest_shared_one() {
        let files = [
            PathBuf::from("/r/specs/day.toml"),
            PathBuf::from("/r/assets/models/bench.obj"),
            PathBuf::from("/r/assets/models/bench.mtl"),
        ];
        assert_eq!(common_folder(&files), PathBuf::from("/r"));
        assert_eq!(common_folder(&files[..1]), PathBuf::from("/r/specs"));
        assert_eq!(
            common_folder(&files[1..]),
            PathBuf::from("/r/assets/models")
        );
    }
}
