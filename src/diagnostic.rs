//! [`Diagnostic`]: what a stage tells besides its result (a skipped facade, objects placed
//! short of their count, a camera path with no frames).
//!
//! A diagnostic is part of its stage's result: the driver stores the diagnostics with the
//! stage's cache entry, together with those of the stages it read, and replays them on
//! every build, cached or not. So `build`, `build --strict` and a warm or cold cache all
//! say the same thing. Only the CLI renders them.

use std::fmt;

use serde::{Deserialize, Serialize};

/// How bad it is. Errors stop a build through typed errors, not diagnostics; a diagnostic
/// is a warning (fails `--strict`) or a note (never does).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    Note,
    Warning,
}

/// One message of a stage: severity, a stable code, the text, and where it points.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct Diagnostic {
    pub severity: Severity,
    /// A stable, kebab-case name of the problem (`facade-skipped`, `objects-short`,
    /// `camera-no-frames`), for scripts and for `--strict` reports.
    pub code: String,
    pub message: String,
    /// The input file it is about, as the spec names it (relative to the spec's folder),
    /// when it is about one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// The spec key it is about (`objects[2].count`, `cameras[0]`): its span, which the
    /// CLI turns into the key's line and column in the spec file (the spec's text is not
    /// part of any key, so a position would not survive the cache).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub key: Option<String>,
}

impl Diagnostic {
    /// A warning with `code` and `message`, pointing nowhere yet.
    pub fn warning(code: &str, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Warning,
            code: code.to_owned(),
            message: message.into(),
            file: None,
            key: None,
        }
    }

    /// The same, about the spec key `key`.
    pub fn at(mut self, key: impl Into<String>) -> Diagnostic {
        self.key = Some(key.into());
        self
    }

    /// The same, about the input file `file`.
    pub fn in_file(mut self, file: impl Into<String>) -> Diagnostic {
        self.file = Some(file.into());
        self
    }

    /// Whether `--strict` fails on it.
    pub fn is_warning(&self) -> bool {
        self.severity == Severity::Warning
    }
}

/// `warning[code]: message` (the key and file are the renderer's to place).
impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let severity = match self.severity {
            Severity::Note => "note",
            Severity::Warning => "warning",
        };
        write!(f, "{severity}[{}]: {}", self.code, self.message)
    }
}

/// Appends `more` to `all`, each diagnostic once, in first-seen order.
pub fn extend_unique(all: &mut Vec<Diagnostic>, more: &[Diagnostic]) {
    for d in more {
        if !all.contains(d) {
            all.push(d.clone());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diagnostics_round_trip_and_merge_once() {
        let short = Diagnostic::warning("objects-short", "placed 3 of 5").at("objects[1].count");
        let text = serde_json::to_string(&short).unwrap();
        assert_eq!(
            text,
            r#"{"severity":"warning","code":"objects-short","message":"placed 3 of 5","key":"objects[1].count"}"#
        );
        assert_eq!(serde_json::from_str::<Diagnostic>(&text).unwrap(), short);
        assert_eq!(short.to_string(), "warning[objects-short]: placed 3 of 5");
        let skipped = Diagnostic::warning("facade-skipped", "bad").in_file("f/a.jpg");
        let mut all = vec![short.clone()];
        extend_unique(&mut all, &[skipped.clone(), short.clone()]);
        assert_eq!(all, vec![short, skipped]);
    }
}
