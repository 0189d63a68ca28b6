//! Locator: the spanned TOML tree + a key path (or JSON pointer) → the byte span to point at.
//!
//! Every diagnostic names a key path and points at source text. The path may name a key
//! the user never wrote (a default, a missing required key); then the span falls back to
//! the nearest ancestor that is written, so the caret still lands on the responsible table.

use std::ops::Range;

use toml::Spanned;
use toml::de::{DeTable, DeValue};

use super::key_path::{KeyPath, Segment, pointer_tokens};

/// The spanned tree of one spec file, queried by key path.
pub(crate) struct Locator<'i> {
    root: DeTable<'i>,
}

/// A node still to visit when searching the tree: its path, value and key span.
type Pending<'a, 'i> = (KeyPath, &'a Spanned<DeValue<'i>>, Option<Range<usize>>);

/// One written node on the way down a key path.
struct Step<'a, 'i> {
    value: &'a Spanned<DeValue<'i>>,
    /// The span of the key that led here (`None` for array items).
    key_span: Option<Range<usize>>,
}

impl<'i> Locator<'i> {
    pub(crate) fn new(root: DeTable<'i>) -> Locator<'i> {
        Locator { root }
    }

    /// The root table.
    pub(crate) fn root(&self) -> &DeTable<'i> {
        &self.root
    }

    /// The written nodes along `path`, from the top; shorter than the path if part is missing.
    fn walk<'a>(&'a self, path: &KeyPath) -> Vec<Step<'a, 'i>> {
        let mut steps: Vec<Step<'a, 'i>> = Vec::new();
        for segment in &path.0 {
            let next = match (steps.last().map(|s| s.value.get_ref()), segment) {
                (None, Segment::Key(k)) => entry(&self.root, k),
                (Some(DeValue::Table(t)), Segment::Key(k)) => entry(t, k),
                (Some(DeValue::Array(a)), Segment::Index(i)) => a.get(*i).map(|value| Step {
                    value,
                    key_span: None,
                }),
                _ => None,
            };
            match next {
                Some(step) => steps.push(step),
                None => break,
            }
        }
        steps
    }

    /// The value written at `path`, if the whole path is written.
    pub(crate) fn value(&self, path: &KeyPath) -> Option<&Spanned<DeValue<'i>>> {
        let steps = self.walk(path);
        (steps.len() == path.0.len() && !path.0.is_empty())
            .then(|| steps.last().map(|s| s.value))?
    }

    /// Whether the whole of `path` is written in the file.
    pub(crate) fn contains(&self, path: &KeyPath) -> bool {
        self.value(path).is_some()
    }

    /// The span of the value at `path`, or of its nearest written ancestor.
    pub(crate) fn span(&self, path: &KeyPath) -> Range<usize> {
        match self.walk(path).last() {
            Some(step) => step.value.span(),
            None => self.first_content(),
        }
    }

    /// The span of the key that ends `path` if it is written, else as [`Locator::span`].
    pub(crate) fn key_span(&self, path: &KeyPath) -> Range<usize> {
        let steps = self.walk(path);
        match steps.last() {
            Some(Step {
                key_span: Some(span),
                ..
            }) if steps.len() == path.0.len() => span.clone(),
            Some(step) => step.value.span(),
            None => self.first_content(),
        }
    }

    /// The key path a JSON pointer names, typing each token by the tree (array → index).
    pub(crate) fn pointer_path(&self, pointer: &str) -> KeyPath {
        let mut path = KeyPath::root();
        for token in pointer_tokens(pointer) {
            let in_array = matches!(
                self.value(&path).map(|v| v.get_ref()),
                Some(DeValue::Array(_))
            );
            path = match token.parse::<usize>() {
                Ok(i) if in_array => path.index(i),
                _ => path.key(&token),
            };
        }
        path
    }

    /// The innermost written key path whose key or value covers byte `offset`.
    ///
    /// Searches the whole tree: a `[table]`'s span is its header only, so its keys are not
    /// inside its span.
    pub(crate) fn path_at(&self, offset: usize) -> KeyPath {
        let mut best = KeyPath::root();
        let mut stack: Vec<Pending<'_, 'i>> = self
            .root
            .iter()
            .map(|(k, v)| (KeyPath::root().key(k.get_ref()), v, Some(k.span())))
            .collect();
        while let Some((path, value, key_span)) = stack.pop() {
            let hit = covers(&value.span(), offset) || key_span.is_some_and(|s| covers(&s, offset));
            if hit && path.0.len() > best.0.len() {
                best = path.clone();
            }
            match value.get_ref() {
                DeValue::Table(t) => stack.extend(
                    t.iter()
                        .map(|(k, v)| (path.key(k.get_ref()), v, Some(k.span()))),
                ),
                DeValue::Array(a) => {
                    stack.extend(a.iter().enumerate().map(|(i, v)| (path.index(i), v, None)))
                }
                _ => {}
            }
        }
        best
    }

    /// The path of the last key named `name` written before `offset` (for a duplicate key,
    /// its first occurrence).
    pub(crate) fn last_key_before(&self, name: &str, offset: usize) -> Option<KeyPath> {
        let mut best: Option<(usize, KeyPath)> = None;
        let mut stack: Vec<Pending<'_, 'i>> = self
            .root
            .iter()
            .map(|(k, v)| (KeyPath::root().key(k.get_ref()), v, Some(k.span())))
            .collect();
        while let Some((path, value, key_span)) = stack.pop() {
            if let (Some(span), Some(Segment::Key(key))) = (key_span, path.0.last())
                && key == name
                && span.start < offset
                && best.as_ref().is_none_or(|(s, _)| span.start > *s)
            {
                best = Some((span.start, path.clone()));
            }
            match value.get_ref() {
                DeValue::Table(t) => stack.extend(
                    t.iter()
                        .map(|(k, v)| (path.key(k.get_ref()), v, Some(k.span()))),
                ),
                DeValue::Array(a) => {
                    stack.extend(a.iter().enumerate().map(|(i, v)| (path.index(i), v, None)))
                }
                _ => {}
            }
        }
        best.map(|(_, path)| path)
    }

    /// Where the document's content starts: the first written key, or the file start.
    pub(crate) fn first_content(&self) -> Range<usize> {
        self.root
            .iter()
            .flat_map(|(k, v)| [k.span(), v.span()])
            .min_by_key(|s| s.start)
            .unwrap_or(0..0)
    }
}

fn entry<'a, 'i>(table: &'a DeTable<'i>, key: &str) -> Option<Step<'a, 'i>> {
    table
        .iter()
        .find(|(k, _)| k.get_ref() == key)
        .map(|(k, value)| Step {
            value,
            key_span: Some(k.span()),
        })
}

fn covers(span: &Range<usize>, offset: usize) -> bool {
    span.start <= offset && offset < span.end.max(span.start + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "# c\nversion = 1\nname = \"x\"\n\n[layout]\nmirror = [1, 2,\n 4]\n\
                        [layout.generate]\nroad_width = 40\n[lamps]\nsp = { a = [1, {b = 2}] }\n";

    fn at(text: &str, span: Range<usize>) -> &str {
        &text[span]
    }

    #[test]
    fn pointers_map_to_value_and_key_spans() {
        let locator = Locator::new(DeTable::parse(TEXT).unwrap().into_inner());
        let cases = [
            ("/version", "1", "version"),
            ("/layout/mirror/2", "4", "4"),
            ("/layout/generate/road_width", "40", "road_width"),
            ("/layout/generate", "[layout.generate]", "generate"),
            ("/lamps/sp/a/1/b", "2", "b"),
            // Not written: fall back to the nearest written ancestor.
            (
                "/layout/generate/width",
                "[layout.generate]",
                "[layout.generate]",
            ),
            ("/buildings/gap", "version", "version"),
        ];
        for (pointer, value, key) in cases {
            let path = locator.pointer_path(pointer);
            assert_eq!(at(TEXT, locator.span(&path)), value, "{pointer}");
            assert_eq!(at(TEXT, locator.key_span(&path)), key, "{pointer}");
        }
    }

    #[test]
    fn pointer_tokens_are_typed_by_the_tree() {
        let locator = Locator::new(DeTable::parse(TEXT).unwrap().into_inner());
        assert_eq!(
            locator.pointer_path("/layout/mirror/2").to_string(),
            "layout.mirror[2]"
        );
        assert_eq!(
            locator.pointer_path("/lamps/sp/a/1/b").to_string(),
            "lamps.sp.a[1].b"
        );
        assert_eq!(locator.pointer_path("/x/0").to_string(), "x.0");
    }

    #[test]
    fn offsets_map_to_the_innermost_key() {
        let locator = Locator::new(DeTable::parse(TEXT).unwrap().into_inner());
        let offset = |needle: &str| TEXT.find(needle).unwrap();
        assert_eq!(
            locator.path_at(offset("40")).to_string(),
            "layout.generate.road_width"
        );
        assert_eq!(
            locator.path_at(offset(" 4]") + 1).to_string(),
            "layout.mirror[2]"
        );
        assert_eq!(
            locator.path_at(offset("b = 2")).to_string(),
            "lamps.sp.a[1].b"
        );
        assert_eq!(locator.path_at(0).to_string(), "");
    }

    #[test]
    fn duplicate_keys_find_their_first_occurrence() {
        let locator = Locator::new(DeTable::parse(TEXT).unwrap().into_inner());
        let end = TEXT.len();
        assert_eq!(
            locator
                .last_key_before("road_width", end)
                .unwrap()
                .to_string(),
            "layout.generate.road_width"
        );
        assert_eq!(
            locator.last_key_before("b", end).unwrap().to_string(),
            "lamps.sp.a[1].b"
        );
        assert_eq!(locator.last_key_before("road_width", 10), None);
        assert_eq!(locator.last_key_before("nothing", end), None);
    }

    #[test]
    fn empty_document_points_at_its_start() {
        let locator = Locator::new(DeTable::parse("# nothing\n").unwrap().into_inner());
        assert_eq!(locator.first_content(), 0..0);
        assert!(!locator.contains(&KeyPath::parse("name")));
    }
}
