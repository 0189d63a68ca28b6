//! Diagnostic: one problem of a spec — byte span, 1-based line and column, key path, message.

use std::ops::Range;
use std::path::PathBuf;

/// One problem in a spec file, pointing at the text responsible for it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    /// Byte range in the spec text.
    pub span: Range<usize>,
    /// 1-based line of `span.start`.
    pub line: usize,
    /// 1-based column (in characters) of `span.start`.
    pub column: usize,
    /// Dotted key path, e.g. `layout.generate.road_width` or `layout.mirror[1]`.
    pub key: String,
    /// What was expected and what was found.
    pub message: String,
    /// The file that holds `span` when it is not the spec itself (a base it extends, or
    /// `--set`); `None` before the spec stage places it.
    pub file: Option<PathBuf>,
}

impl Diagnostic {
    /// A diagnostic at `span` of `text` (clamped to the text and to character boundaries).
    pub(crate) fn new(
        text: &str,
        span: Range<usize>,
        key: impl ToString,
        message: impl Into<String>,
    ) -> Diagnostic {
        let start = floor_char_boundary(text, span.start.min(text.len()));
        let end = floor_char_boundary(text, span.end.clamp(start, text.len()));
        let before = &text[..start];
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        Diagnostic {
            span: start..end,
            line: before.matches('\n').count() + 1,
            column: before[line_start..].chars().count() + 1,
            key: key.to_string(),
            message: message.into(),
            file: None,
        }
    }
}

fn floor_char_boundary(text: &str, mut index: usize) -> usize {
    while !text.is_char_boundary(index) {
        index -= 1;
    }
    index
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_and_columns_are_one_based_and_count_characters() {
        let text = "a = 1\nnäme = \"x\"\n";
        let cases = [
            (0, 1, 1),
            (4, 1, 5),
            (6, 2, 1),
            (14, 2, 8),
            (text.len(), 3, 1),
        ];
        for (offset, line, column) in cases {
            let d = Diagnostic::new(text, offset..offset, "k", "m");
            assert_eq!((d.line, d.column), (line, column), "offset {offset}");
        }
    }

    #[test]
    fn spans_are_clamped_into_the_text() {
        let d = Diagnostic::new("ab", 5..9, "k", "m");
        assert_eq!(d.span, 2..2);
        let d = Diagnostic::new("é", 1..2, "k", "m");
        assert_eq!(d.span, 0..2);
    }
}
