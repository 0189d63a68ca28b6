//! What is wrong with an input file a spec names, beyond "it cannot be read": the
//! `source` of [`BuildError::Input`](super::error::BuildError::Input).

use std::io;
use std::str::Utf8Error;

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
    /// The OBJ does not parse; `line` when it is known.
    #[error("{}not a valid OBJ model: {source}", line_prefix(*line))]
    Obj {
        line: Option<usize>,
        #[source]
        source: tobj::LoadError,
    },
    /// The MTL does not parse; `line` when it is known.
    #[error("{}not a valid MTL file: {source}", line_prefix(*line))]
    Mtl {
        line: Option<usize>,
        #[source]
        source: tobj::LoadError,
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

/// `line N: ` when the line is known (the error names the file).
fn line_prefix(line: Option<usize>) -> String {
    line.map(|n| format!("line {n}: ")).unwrap_or_default()
}
