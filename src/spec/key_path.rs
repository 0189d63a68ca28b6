//! Key paths: a JSON pointer or a walk through the TOML tree → the dotted path users read.
//!
//! `layout.generate.road_width`, `layout.mirror[1]`; keys that are not bare TOML keys are
//! quoted (`layout."odd key"`), so the path can be pasted back into a spec.

use std::fmt;

/// One step of a [`KeyPath`]: a table key or an array index.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Segment {
    Key(String),
    Index(usize),
}

/// A path from the document root to a value, printed dotted with `[i]` for array items.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct KeyPath(pub(crate) Vec<Segment>);

impl KeyPath {
    /// The root of the document.
    pub(crate) fn root() -> KeyPath {
        KeyPath(Vec::new())
    }

    /// Parses a dotted path of bare keys with optional `[i]` suffixes, as written in code.
    pub(crate) fn parse(dotted: &str) -> KeyPath {
        let mut segments = Vec::new();
        for part in dotted.split('.').filter(|p| !p.is_empty()) {
            let (name, mut rest) = part.split_once('[').map_or((part, ""), |(n, r)| (n, r));
            segments.push(Segment::Key(name.to_string()));
            while let Some((index, tail)) = rest.split_once(']') {
                if let Ok(i) = index.parse() {
                    segments.push(Segment::Index(i));
                }
                rest = tail.strip_prefix('[').unwrap_or(tail);
            }
        }
        KeyPath(segments)
    }

    /// This path with one more key.
    pub(crate) fn key(&self, name: &str) -> KeyPath {
        let mut segments = self.0.clone();
        segments.push(Segment::Key(name.to_string()));
        KeyPath(segments)
    }

    /// This path with one more array index.
    pub(crate) fn index(&self, i: usize) -> KeyPath {
        let mut segments = self.0.clone();
        segments.push(Segment::Index(i));
        KeyPath(segments)
    }
}

impl fmt::Display for KeyPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, segment) in self.0.iter().enumerate() {
            match segment {
                Segment::Key(k) => {
                    if i > 0 {
                        f.write_str(".")?;
                    }
                    if is_bare_key(k) {
                        f.write_str(k)?;
                    } else {
                        write!(f, "{k:?}")?;
                    }
                }
                Segment::Index(n) => write!(f, "[{n}]")?,
            }
        }
        Ok(())
    }
}

/// Whether `key` may be written unquoted in TOML.
fn is_bare_key(key: &str) -> bool {
    !key.is_empty()
        && key
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-')
}

/// Splits a JSON pointer (`/layout/mirror/1`) into its unescaped reference tokens.
pub(crate) fn pointer_tokens(pointer: &str) -> Vec<String> {
    pointer
        .split('/')
        .skip(1)
        .map(|t| t.replace("~1", "/").replace("~0", "~"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_print_dotted_with_indices_and_quotes() {
        let cases = [
            (
                KeyPath::root()
                    .key("layout")
                    .key("generate")
                    .key("road_width"),
                "layout.generate.road_width",
            ),
            (
                KeyPath::root().key("layout").key("mirror").index(1),
                "layout.mirror[1]",
            ),
            (KeyPath::root().key("a b").key("c"), "\"a b\".c"),
            (KeyPath::root(), ""),
        ];
        for (path, want) in cases {
            assert_eq!(path.to_string(), want);
        }
    }

    #[test]
    fn parse_round_trips_display() {
        for text in ["layout.generate.road_width", "buildings.widths[3]", "name"] {
            assert_eq!(KeyPath::parse(text).to_string(), text);
        }
        assert_eq!(KeyPath::parse("a[1][2]").0.len(), 3);
    }

    #[test]
    fn pointer_tokens_unescape() {
        assert_eq!(
            pointer_tokens("/layout/mirror/1"),
            ["layout", "mirror", "1"]
        );
        assert_eq!(pointer_tokens("/a~1b/c~0d"), ["a/b", "c~d"]);
        assert!(pointer_tokens("").is_empty());
    }
}
