//! SourceFrame: an input file's text + the line to blame → that line shown under an
//! error the way spec errors show theirs (codespan-reporting): `file:line:col`, the line,
//! carets under the part at fault.
//!
//! Only the one line is kept, not the file (a model may be 256 MB), and it is rendered
//! through a one-line [`Files`] that reports its true line number.

use std::ops::Range;
use std::path::{Path, PathBuf};

use codespan_reporting::diagnostic::{Diagnostic, Label};
use codespan_reporting::files::{Error, Files};
use codespan_reporting::term::{self, Config, termcolor::Ansi};

use super::BuildError;

/// One line of an input file (an OBJ, an MTL) that an error is about.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SourceFrame {
    /// The file, as the build names it.
    pub path: PathBuf,
    /// The line, 1-based.
    pub line: usize,
    /// The line's text, without its line break.
    pub text: String,
    /// The bytes of `text` at fault.
    pub span: Range<usize>,
}

impl SourceFrame {
    /// Line `line` (1-based) of `text`, all of it but its indentation at fault; None when
    /// the text has no such line.
    pub fn line(path: &Path, text: &str, line: usize) -> Option<SourceFrame> {
        let content = text.lines().nth(line.checked_sub(1)?)?;
        let start = content.len() - content.trim_start().len();
        let end = content.trim_end().len().max(start);
        Some(SourceFrame {
            path: path.to_path_buf(),
            line,
            text: content.to_string(),
            span: start..end,
        })
    }

    /// The first line of `text` whose first word is `keyword` and which names `name`, with
    /// the name at fault: where an OBJ's `mtllib` or an MTL's `map_Kd` names a file.
    pub fn naming(path: &Path, text: &str, keywords: &[&str], name: &str) -> Option<SourceFrame> {
        text.lines().enumerate().find_map(|(index, content)| {
            let mut words = content.split_whitespace();
            if !keywords.contains(&words.next()?) {
                return None;
            }
            let start = content.rfind(name)?;
            Some(SourceFrame {
                path: path.to_path_buf(),
                line: index + 1,
                text: content.to_string(),
                span: start..start + name.len(),
            })
        })
    }

    /// `path:line:col` of the part at fault.
    pub fn location(&self) -> String {
        let column = self.text[..self.span.start.min(self.text.len())]
            .chars()
            .count()
            + 1;
        format!("{}:{}:{column}", self.path.display(), self.line)
    }

    /// `error: {message}` over the line, with `label` by the carets; ANSI-coloured when
    /// `color` is set.
    pub fn render(&self, message: &str, label: &str, color: bool) -> String {
        let report = Diagnostic::error().with_message(message).with_labels(vec![
            Label::primary((), self.span.clone()).with_message(label),
        ]);
        let config = Config::default();
        let mut out = Vec::new();
        let written = if color {
            term::emit_to_write_style(&mut Ansi::new(&mut out), &config, self, &report)
        } else {
            term::emit_to_io_write(&mut out, &config, self, &report)
        };
        if written.is_err() {
            // Only a span outside the line gets here; the message alone still says it all.
            return format!("error: {message}\n");
        }
        String::from_utf8_lossy(&out).into_owned()
    }
}

/// `error` as the CLI shows it when it is about a line of a model's own files: the
/// spec, its `objects[N].model` entry and the problem, over that line with carets; None
/// for every other error (they print as one line).
pub fn framed_report(error: &BuildError, color: bool) -> Option<String> {
    let BuildError::Input {
        spec,
        key,
        entry,
        source,
        ..
    } = error
    else {
        return None;
    };
    let frame = source.frame()?;
    let message = format!(
        "{}: {}: {source}",
        spec.display(),
        entry.as_deref().unwrap_or(key)
    );
    Some(frame.render(&message, &source.frame_label(), color))
}

impl<'a> Files<'a> for SourceFrame {
    type FileId = ();
    type Name = String;
    type Source = &'a str;

    fn name(&'a self, (): ()) -> Result<String, Error> {
        Ok(self.path.display().to_string())
    }

    fn source(&'a self, (): ()) -> Result<&'a str, Error> {
        Ok(&self.text)
    }

    fn line_index(&'a self, (): (), byte_index: usize) -> Result<usize, Error> {
        if byte_index > self.text.len() {
            return Err(Error::IndexTooLarge {
                given: byte_index,
                max: self.text.len(),
            });
        }
        Ok(0)
    }

    fn line_number(&'a self, (): (), line_index: usize) -> Result<usize, Error> {
        Ok(self.line + line_index)
    }

    fn line_range(&'a self, (): (), line_index: usize) -> Result<Range<usize>, Error> {
        match line_index {
            0 => Ok(0..self.text.len()),
            given => Err(Error::LineTooLarge { given, max: 0 }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_renders_with_its_own_number_and_carets() {
        let text = "# a model\nmtllib bench.mtl\nv 1 2 x\n";
        let path = Path::new("models/bench.obj");
        let bad = SourceFrame::line(path, text, 3).unwrap();
        assert_eq!(bad.location(), "models/bench.obj:3:1");
        let out = bad.render(
            "objects[0].model: not a valid OBJ model",
            "this line",
            false,
        );
        assert!(
            out.starts_with("error: objects[0].model: not a valid OBJ model\n"),
            "{out}"
        );
        assert!(out.contains("models/bench.obj:3:1"), "{out}");
        assert!(out.contains("3 │ v 1 2 x"), "{out}");
        assert!(out.contains("^^^^^^^ this line"), "{out}");
        let mtllib = SourceFrame::naming(path, text, &["mtllib"], "bench.mtl").unwrap();
        assert_eq!(mtllib.location(), "models/bench.obj:2:8");
        assert_eq!(&mtllib.text[mtllib.span.clone()], "bench.mtl");
        assert_eq!(SourceFrame::line(path, text, 9), None);
        assert_eq!(SourceFrame::line(path, text, 0), None);
        assert!(
            bad.render("m", "l", true).contains('\u{1b}'),
            "colour on request"
        );
    }
}
