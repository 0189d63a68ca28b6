//! Findings: semantic checks' problems, by key path → diagnostics pointing at the source.

use super::diagnostic::Diagnostic;
use super::key_path::KeyPath;
use super::locator::Locator;

/// Collects the semantic problems of one spec, locating each key in the source.
pub(crate) struct Findings<'a, 'i> {
    locator: &'a Locator<'i>,
    text: &'a str,
    diagnostics: Vec<Diagnostic>,
}

impl<'a, 'i> Findings<'a, 'i> {
    pub(crate) fn new(locator: &'a Locator<'i>, text: &'a str) -> Findings<'a, 'i> {
        Findings {
            locator,
            text,
            diagnostics: Vec::new(),
        }
    }

    /// Whether the dotted `key` is written in the file (not a default).
    pub(crate) fn written(&self, key: &str) -> bool {
        self.locator.contains(&KeyPath::parse(key))
    }

    /// `value` as the message should show it: marked as the default when `key` is not
    /// written, so the user sees where a value they never typed came from.
    pub(crate) fn shown(&self, key: &str, value: impl std::fmt::Display) -> String {
        if self.written(key) {
            value.to_string()
        } else {
            format!("the default {value}")
        }
    }

    /// The 1-based line `key` is written on (or its nearest written table's line).
    pub(crate) fn line_of(&self, key: &str) -> usize {
        let span = self.locator.span(&KeyPath::parse(key));
        self.text[..span.start.min(self.text.len())]
            .matches('\n')
            .count()
            + 1
    }

    /// A problem with the value at the dotted `key` (or its nearest written ancestor).
    pub(crate) fn error(&mut self, key: &str, message: impl Into<String>) {
        let path = KeyPath::parse(key);
        let span = self.locator.span(&path);
        self.diagnostics
            .push(Diagnostic::new(self.text, span, path, message));
    }

    pub(crate) fn into_diagnostics(self) -> Vec<Diagnostic> {
        self.diagnostics
    }
}
