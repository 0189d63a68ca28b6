//! Model files: a mesh object's `model` → its OBJ, the MTL its `mtllib` names and the
//! textures that MTL names, read and checked, or an error that points into the model's
//! own files.
//!
//! tobj parses both files (nothing else here reads OBJ or MTL), so a model that would fail
//! in the scene fails here, before any stage runs or caches. A parse error points at the
//! line of the OBJ or MTL that makes it fail (`model.obj:4:1`, the line shown under the
//! message); a missing or unreadable MTL or texture is named by its own path and pointed
//! at by the line that names it (the OBJ's `mtllib`, the MTL's `map_Kd`). The MTL and its
//! textures must lie inside the model's folder: no absolute paths, no `..`, no symlink
//! out, so a model cannot copy any image on the machine into `out/textures/`.

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::fs;
use std::io::Cursor;
use std::path::{Component, Path, PathBuf};

use super::BuildError;
use super::input_problem::InputProblem;
use super::source_frame::SourceFrame;
use crate::objects::MeshFiles;
use crate::objects::obj_lines::{mtl_error_line, obj_error_line};
use crate::spec::{self, InputFileError};

/// The OBJ `model` (as the spec writes it, for `objects[index].model`), its MTL and the
/// MTL's textures.
pub fn read(
    spec_path: &Path,
    model: &str,
    index: usize,
    read: &mut Vec<PathBuf>,
) -> Result<MeshFiles, BuildError> {
    let file = spec::resolve(spec_path, model);
    let fail = |source: InputProblem| BuildError::Input {
        spec: spec_path.to_path_buf(),
        key: "objects.model",
        file: file.clone(),
        entry: Some(format!("objects[{index}].model")),
        source: Box::new(source),
    };
    let obj = spec::read_capped(&file, spec::MAX_MODEL_BYTES).map_err(|source| {
        fail(InputProblem::Read {
            expected: "an OBJ model",
            source,
        })
    })?;
    read.push(file.clone());
    let folder = file.parent().map(Path::to_path_buf).unwrap_or_default();
    let obj_text = String::from_utf8_lossy(&obj);
    let mtl_names = obj_mtl_names(&file, &obj, &obj_text).map_err(&fail)?;
    let Some(mtl_name) = mtl_names.into_iter().next() else {
        return Ok(MeshFiles {
            obj,
            mtl: None,
            textures: BTreeMap::new(),
        });
    };
    let mtllib = SourceFrame::naming(&file, &obj_text, &["mtllib"], &mtl_name);
    let mtl_path = inside(&folder, &mtl_name).map_err(&fail)?;
    let mtl = spec::read_capped(&mtl_path, spec::MAX_MTL_BYTES)
        .map_err(|source| fail(named("an MTL file", &mtl_path, mtllib.clone(), source)))?;
    read.push(mtl_path.clone());
    let mtl_text = String::from_utf8_lossy(&mtl);
    let (materials, _) = tobj::load_mtl_buf(&mut Cursor::new(&mtl[..])).map_err(|source| {
        let at = mtl_error_line(&mtl_text, &source)
            .and_then(|line| SourceFrame::line(&mtl_path, &mtl_text, line))
            .or(mtllib.clone());
        fail(InputProblem::Mtl {
            at: at.map(Box::new),
            source,
        })
    })?;
    let names = materials.iter().flat_map(|m| {
        [&m.diffuse_texture, &m.ambient_texture, &m.dissolve_texture]
            .into_iter()
            .flatten()
    });
    let mut textures = BTreeMap::new();
    for name in names {
        if name.is_empty() || textures.contains_key(name) {
            continue;
        }
        let path = inside(&folder, name).map_err(&fail)?;
        let bytes = spec::read_capped(&path, spec::MAX_TEXTURE_BYTES).map_err(|source| {
            let at = SourceFrame::naming(&mtl_path, &mtl_text, TEXTURE_KEYWORDS, name);
            fail(named("a texture image", &path, at, source))
        })?;
        textures.insert(name.clone(), bytes);
        read.push(path);
    }
    Ok(MeshFiles {
        obj,
        mtl: Some(mtl),
        textures,
    })
}

/// The MTL libraries an OBJ model names, once it is known to parse (only whether it
/// parses: the scene stage loads the models from these bytes).
fn obj_mtl_names(file: &Path, obj: &[u8], obj_text: &str) -> Result<Vec<String>, InputProblem> {
    let mtl_names = RefCell::new(Vec::new());
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    tobj::load_obj_buf(&mut Cursor::new(obj), &options, |name| {
        mtl_names
            .borrow_mut()
            .push(name.to_string_lossy().into_owned());
        Ok((Vec::new(), Default::default()))
    })
    .map(|_| ())
    .map_err(|source| {
        let at = obj_error_line(obj_text, &source)
            .and_then(|line| SourceFrame::line(file, obj_text, line));
        InputProblem::Obj {
            at: at.map(Box::new),
            source,
        }
    })?;
    Ok(mtl_names.into_inner())
}

/// The MTL statements that name the textures tobj reads.
const TEXTURE_KEYWORDS: &[&str] = &["map_Kd", "map_Ka", "map_d"];

fn named(
    expected: &'static str,
    file: &Path,
    named_at: Option<SourceFrame>,
    source: InputFileError,
) -> InputProblem {
    InputProblem::Named {
        expected,
        file: file.to_path_buf(),
        named_at: named_at.map(Box::new),
        source,
    }
}

/// `name` (from an OBJ or MTL) resolved in `folder`, if it stays inside it: relative, no
/// `..`, and not leading out through a symlink.
fn inside(folder: &Path, name: &str) -> Result<PathBuf, InputProblem> {
    let relative = Path::new(name);
    let escapes = relative.is_absolute()
        || relative
            .components()
            .any(|c| !matches!(c, Component::Normal(_) | Component::CurDir));
    if escapes {
        return Err(InputProblem::Escapes(name.to_owned()));
    }
    let path = folder.join(relative);
    let base = fs::canonicalize(if folder.as_os_str().is_empty() {
        Path::new(".")
    } else {
        folder
    });
    if let (Ok(base), Ok(real)) = (base, fs::canonicalize(&path))
        && !real.starts_with(&base)
    {
        return Err(InputProblem::LinksOut {
            name: name.to_owned(),
            target: real.display().to_string(),
        });
    }
    Ok(path)
}
