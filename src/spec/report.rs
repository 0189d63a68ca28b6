//! Report: [`SpecErrors`] → a terminal report with the source line and carets under each
//! problem (codespan-reporting), the key path in the header, expected/found in the label.

use codespan_reporting::diagnostic::{Diagnostic as Report, Label};
use codespan_reporting::files::SimpleFiles;
use codespan_reporting::term::{self, Config, termcolor::Ansi};

use super::SpecErrors;

/// The errors rendered for a terminal, ANSI-coloured when `color` is set.
pub fn report(errors: &SpecErrors, color: bool) -> String {
    let mut files = SimpleFiles::new();
    let main = files.add(errors.path.display().to_string(), errors.text.as_str());
    let ids: Vec<(&std::path::Path, usize)> = errors
        .files
        .iter()
        .map(|(path, text)| {
            (
                path.as_path(),
                files.add(path.display().to_string(), text.as_str()),
            )
        })
        .collect();
    let config = Config::default();
    let mut out = Vec::new();
    for d in &errors.diagnostics {
        let file = d
            .file
            .as_deref()
            .and_then(|path| ids.iter().find(|(p, _)| *p == path))
            .map_or(main, |(_, id)| *id);
        let report = Report::error()
            .with_message(format!("invalid `{}`", display_key(&d.key)))
            .with_labels(vec![
                Label::primary(file, d.span.clone()).with_message(&d.message),
            ]);
        let written = if color {
            let mut ansi = Ansi::new(&mut out);
            term::emit_to_write_style(&mut ansi, &config, &files, &report)
        } else {
            term::emit_to_io_write(&mut out, &config, &files, &report)
        };
        if let Err(e) = written {
            // Only a span outside the text gets here; fall back to the one-line form.
            out.extend_from_slice(
                format!("error: {}: {} ({e})\n", display_key(&d.key), d.message).as_bytes(),
            );
        }
    }
    let count = errors.diagnostics.len();
    let plural = if count == 1 { "" } else { "s" };
    out.extend_from_slice(
        format!(
            "error: {} is not a valid spec: {count} error{plural}\n",
            errors.path.display()
        )
        .as_bytes(),
    );
    String::from_utf8_lossy(&out).into_owned()
}

fn display_key(key: &str) -> &str {
    if key.is_empty() { "spec" } else { key }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::Diagnostic;
    use std::path::PathBuf;

    fn errors() -> SpecErrors {
        let text = "version = 1\n[layout.generate]\nroad_width = 1000\n";
        SpecErrors {
            path: PathBuf::from("city.toml"),
            text: text.to_string(),
            files: Vec::new(),
            diagnostics: vec![Diagnostic::new(
                text,
                43..47,
                "layout.generate.road_width",
                "expected an integer at most 256, found 1000",
            )],
        }
    }

    #[test]
    fn plain_render_shows_location_carets_key_and_message() {
        let out = report(&errors(), false);
        assert!(
            out.contains("error: invalid `layout.generate.road_width`"),
            "{out}"
        );
        assert!(out.contains("city.toml:3:14"), "{out}");
        assert!(out.contains("road_width = 1000"), "{out}");
        assert!(
            out.contains("^^^^ expected an integer at most 256, found 1000"),
            "{out}"
        );
        assert!(
            out.ends_with("error: city.toml is not a valid spec: 1 error\n"),
            "{out}"
        );
        assert!(!out.contains('\u{1b}'), "{out}");
    }

    #[test]
    fn colour_render_uses_ansi_escapes() {
        let out = report(&errors(), true);
        assert!(out.contains('\u{1b}'), "{out}");
        assert!(
            out.contains("expected an integer at most 256, found 1000"),
            "{out}"
        );
    }
}
