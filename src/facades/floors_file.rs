//! FloorsFile: the floors side file's text → floors per facade name.
//!
//! The paper counted each CMP facade's floors by hand; cityspec reads such counts from a
//! side file of `name floors` lines. `#` starts a comment; blank lines are fine. A name given
//! twice is an error (one of the two would silently lose).

use std::collections::BTreeMap;

use super::FacadeError;

/// The most floors a line may give: more is a typo, not a building.
const MAX_FLOORS: u32 = 200;

/// Floors by facade name.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FloorsFile {
    pub floors: BTreeMap<String, u32>,
}

impl FloorsFile {
    /// Parses the side file's text; `origin` names the facade folder in errors.
    pub fn parse(text: &str, origin: &str) -> Result<FloorsFile, FacadeError> {
        let mut floors = BTreeMap::new();
        for (i, raw) in text.lines().enumerate() {
            let bad = |message: String| FacadeError::BadFloorsLine {
                origin: origin.to_string(),
                line: i + 1,
                message,
            };
            let line = raw.split('#').next().unwrap_or("").trim();
            if line.is_empty() {
                continue;
            }
            let fields: Vec<&str> = line.split_whitespace().collect();
            let [name, count] = fields[..] else {
                return Err(bad(format!(
                    "expected `name floors`, found `{line}` ({} fields)",
                    fields.len()
                )));
            };
            let count: u32 = count
                .parse()
                .ok()
                .filter(|n| (1..=MAX_FLOORS).contains(n))
                .ok_or_else(|| {
                    bad(format!(
                        "floors of `{name}` is `{count}`; expected a whole number from 1 to {MAX_FLOORS}"
                    ))
                })?;
            if floors.insert(name.to_string(), count).is_some() {
                return Err(bad(format!("`{name}` is listed a second time")));
            }
        }
        Ok(FloorsFile { floors })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_comments_and_blanks() {
        let text = "# hand counts\ncmp_b0001 4\n\n  cmp_b0002\t7  # tall one\n";
        let file = FloorsFile::parse(text, "cmp").unwrap();
        let expected: BTreeMap<String, u32> =
            [("cmp_b0001".to_string(), 4), ("cmp_b0002".to_string(), 7)].into();
        assert_eq!(file.floors, expected);
    }

    #[test]
    fn bad_lines_name_the_file_and_line() {
        let cases = [
            (
                "a 3\nb\n",
                2,
                "expected `name floors`, found `b` (1 fields)",
            ),
            ("a 3 4\n", 1, "(3 fields)"),
            ("\n\na three\n", 3, "floors of `a` is `three`"),
            ("a 0\n", 1, "floors of `a` is `0`"),
            ("a -2\n", 1, "is `-2`"),
            ("a 3\n# x\na 4\n", 3, "`a` is listed a second time"),
        ];
        for (text, line, expected) in cases {
            let err = FloorsFile::parse(text, "data/cmp").unwrap_err();
            let message = err.to_string();
            assert!(
                message.starts_with(&format!(
                    "data/cmp: floors file (facades.floors), line {line}: "
                )),
                "{text:?}: {message}"
            );
            assert!(message.contains(expected), "{text:?}: {message}");
        }
    }
}
