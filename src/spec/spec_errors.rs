//! SpecErrors: every diagnostic of one spec file, printed one per line as
//! `{path}:{line}:{col}: error: {key}: {message}`.

use std::fmt;
use std::path::PathBuf;

use super::diagnostic::Diagnostic;

/// All the problems of one spec file (never empty when returned by [`super::load`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SpecErrors {
    /// The spec's path as the user gave it.
    pub path: PathBuf,
    /// The spec's text, for rendering.
    pub text: String,
    /// Every file read for it, `(path, text)`: the spec, the bases it extends, `--set`.
    pub files: Vec<(PathBuf, String)>,
    /// The problems, in source order.
    pub diagnostics: Vec<Diagnostic>,
}

impl fmt::Display for SpecErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, d) in self.diagnostics.iter().enumerate() {
            if i > 0 {
                f.write_str("\n")?;
            }
            write!(
                f,
                "{}:{}:{}: error: {}: {}",
                d.file.as_ref().unwrap_or(&self.path).display(),
                d.line,
                d.column,
                d.key,
                d.message
            )?;
        }
        Ok(())
    }
}

impl std::error::Error for SpecErrors {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_prints_one_line_per_diagnostic() {
        let text = "name = 1\nseed = -1\n";
        let errors = SpecErrors {
            path: PathBuf::from("specs/a.toml"),
            text: text.to_string(),
            files: vec![(PathBuf::from("specs/a.toml"), text.to_string())],
            diagnostics: vec![
                Diagnostic::new(text, 7..8, "name", "expected a string, found an integer 1"),
                Diagnostic::new(
                    text,
                    16..18,
                    "seed",
                    "expected an integer at least 0, found -1",
                ),
            ],
        };
        assert_eq!(
            errors.to_string(),
            "specs/a.toml:1:8: error: name: expected a string, found an integer 1\n\
             specs/a.toml:2:8: error: seed: expected an integer at least 0, found -1"
        );
    }
}
