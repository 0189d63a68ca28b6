//! What is wrong with an input file a spec names, beyond "it cannot be read": the
//! `source` of [`BuildError::Input`](super::error::BuildError::Input).

use std::io;
use std::path::PathBuf;
use std::str::Utf8Error;

use super::source_frame::SourceFrame;

use crate::spec::InputFileError;

/// Why an input file (or folder) the spec names is unusable.
#[derive(Debug, thiserror::Error)]
pub enum InputProblem {
    /// It cannot be read as a regular file within its cap.
    #[error("expected {expected}, found {source}")]
    Read {
        /// What the file should have been ("a layout image", "an OBJ model", …).
        expected: &'static str,
        #[source]
        source: InputFileError,
    },
    /// The facade folder cannot be listed.
    #[error("cannot list the folder: {0}")]
    Folder(#[source] io::Error),
    /// The facade folder holds no photos.
    #[error("expected facade photos (<name>.jpg), found none")]
    NoPhotos,
    /// The OBJ does not parse; `at` is the line that makes it fail, when found.
    #[error("{}not a valid OBJ model: {source}", at_prefix(at.as_deref()))]
    Obj {
        at: Option<Box<SourceFrame>>,
        #[source]
        source: tobj::LoadError,
    },
    /// The MTL does not parse; `at` is the line that makes it fail, when found.
    #[error("{}not a valid MTL file: {source}", at_prefix(at.as_deref()))]
    Mtl {
        at: Option<Box<SourceFrame>>,
        #[source]
        source: tobj::LoadError,
    },
    /// A file the model names (the MTL of its `mtllib`, a texture of that MTL) cannot be
    /// read; `named_at` is the line that names it.
    #[error("{}{} {}: expected {expected}, found {source}", at_prefix(named_at.as_deref()), naming(named_at.as_deref()), file.display())]
    Named {
        /// What the file should have been ("an MTL file", "a texture image").
        expected: &'static str,
        file: PathBuf,
        named_at: Option<Box<SourceFrame>>,
        #[source]
        source: InputFileError,
    },
    /// An MTL or texture name that leaves the model's folder (`..`, an absolute path).
    #[error("expected a file name inside the model's folder, found {0:?}")]
    Escapes(String),
    /// A name inside the folder that is a link to a file outside it.
    #[error("expected a file inside the model's folder, found {name:?}, a link to {target}")]
    LinksOut { name: String, target: String },
    /// The word file is over [`MAX_WORDS_FILE`](super::inputs::MAX_WORDS_FILE).
    #[error("the word file is {size} bytes, more than the {cap} allowed")]
    WordsTooLarge { size: u64, cap: u64 },
    /// The word file is not UTF-8.
    #[error("the word file is not UTF-8: {0}")]
    WordsNotUtf8(#[source] Utf8Error),
    /// The word file holds no word.
    #[error("the word file holds no words")]
    NoWords,
}

impl InputProblem {
    /// The line of the model's own files this problem is about, when there is one.
    pub fn frame(&self) -> Option<&SourceFrame> {
        match self {
            InputProblem::Obj { at, .. } | InputProblem::Mtl { at, .. } => at.as_deref(),
            InputProblem::Named { named_at, .. } => named_at.as_deref(),
            _ => None,
        }
    }

    /// The words under the carets of [`InputProblem::frame`].
    pub fn frame_label(&self) -> String {
        match self {
            InputProblem::Obj { source, .. } => format!("not a valid OBJ line: {source}"),
            InputProblem::Mtl { source, .. } => format!("not a valid MTL line: {source}"),
            InputProblem::Named { source, .. } => format!("found {source}"),
            other => other.to_string(),
        }
    }
}

/// `file:line:col: ` when the line is known.
fn at_prefix(at: Option<&SourceFrame>) -> String {
    at.map(|at| format!("{}: ", at.location()))
        .unwrap_or_default()
}

/// What names a file: the `mtllib` line of an OBJ, a `map_…` line of an MTL.
fn naming(at: Option<&SourceFrame>) -> String {
    match at.and_then(|at| at.text.split_whitespace().next()) {
        Some(keyword) => format!("the file its `{keyword}` names,"),
        None => "the file".to_string(),
    }
}
