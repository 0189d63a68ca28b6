//! Test specs changed through their parsed value, by key path, never by a text replace.
//!
//! A text replace that matches nothing leaves the spec as it was, and the test then checks
//! nothing (or, matching a longer line, `frames = 12` in `frames = 120`, something else).
//! Here each change says what it needs and panics, naming the spec and the key path, when
//! that is not so: [`SpecEdit::set`] needs the key there and holding another value,
//! [`SpecEdit::insert`] needs it absent and its table there, [`SpecEdit::remove`] needs it
//! there. The spec is parsed with `toml_edit`, so its comments and layout are kept.
//!
//! Key paths are dotted, with `[i]` for an item of an array or array of tables:
//! `cameras[0].frames`, `layout.generate.width`, `objects[2].count`, `cameras[0].sensor`.
//! Its own tests are in `tests/integration/spec_edit.rs`.

use toml_edit::{Array, DocumentMut, Item, Table, Value};

/// A value a spec key can be set to: an integer, a float, a boolean, a string (`&str` is a
/// TOML string, not TOML text) or an array of them.
pub trait SpecValue {
    fn into_value(self) -> Value;
}

impl SpecValue for i64 {
    fn into_value(self) -> Value {
        Value::from(self)
    }
}

impl SpecValue for i32 {
    fn into_value(self) -> Value {
        Value::from(i64::from(self))
    }
}

impl SpecValue for u32 {
    fn into_value(self) -> Value {
        Value::from(i64::from(self))
    }
}

impl SpecValue for f64 {
    fn into_value(self) -> Value {
        Value::from(self)
    }
}

impl SpecValue for bool {
    fn into_value(self) -> Value {
        Value::from(self)
    }
}

impl SpecValue for &str {
    fn into_value(self) -> Value {
        Value::from(self)
    }
}

impl<T: SpecValue, const N: usize> SpecValue for [T; N] {
    fn into_value(self) -> Value {
        Value::Array(
            self.into_iter()
                .map(SpecValue::into_value)
                .collect::<Array>(),
        )
    }
}

/// One step of a key path.
#[derive(Clone, Debug)]
enum Step {
    Key(String),
    Index(usize),
}

/// `cameras[0].frames` → `cameras`, `[0]`, `frames`.
fn steps(path: &str) -> Vec<Step> {
    let mut steps = Vec::new();
    for part in path.split('.') {
        let (key, mut rest) = part.split_once('[').map_or((part, ""), |(k, r)| (k, r));
        assert!(!key.is_empty(), "key path {path:?}: an empty key");
        steps.push(Step::Key(key.to_owned()));
        while !rest.is_empty() {
            let (index, tail) = rest
                .split_once(']')
                .unwrap_or_else(|| panic!("key path {path:?}: `[` without `]`"));
            let index = index
                .parse()
                .unwrap_or_else(|_| panic!("key path {path:?}: [{index}] is not an index"));
            steps.push(Step::Index(index));
            rest = tail.strip_prefix('[').unwrap_or(tail);
            assert!(
                tail.is_empty() || tail.starts_with('['),
                "key path {path:?}: {tail:?} after an index"
            );
        }
    }
    steps
}

/// A value as TOML text without its spacing and comments, to compare two values.
fn bare(value: &Value) -> String {
    let mut value = value.clone();
    value.decor_mut().clear();
    let text = format!("v = {value}");
    let parsed: toml::Table = text.parse().unwrap();
    parsed["v"].to_string()
}

/// A spec's text parsed to be changed by key path; [`SpecEdit::text`] gives it back.
pub struct SpecEdit {
    doc: DocumentMut,
    /// The spec's name or file, for the panics.
    what: String,
}

impl SpecEdit {
    /// Parses `text`, the spec `what` (named in every panic).
    pub fn parse(what: &str, text: &str) -> SpecEdit {
        let doc = text
            .parse()
            .unwrap_or_else(|e| panic!("{what} is not TOML: {e}"));
        SpecEdit {
            doc,
            what: what.to_owned(),
        }
    }

    /// The item at `path`, if there is one.
    pub fn get(&self, path: &str) -> Option<&Item> {
        let mut item = self.doc.as_item();
        for step in steps(path) {
            item = match step {
                Step::Key(key) => item.get(key.as_str())?,
                Step::Index(i) => item.get(i)?,
            };
        }
        Some(item)
    }

    /// The item at `steps`, panicking at the first step that is not there.
    fn walk(&mut self, path: &str, steps: &[Step]) -> &mut Item {
        let what = &self.what;
        let mut item = self.doc.as_item_mut();
        for (n, step) in steps.iter().enumerate() {
            let next = match step {
                Step::Key(key) => item.get_mut(key.as_str()),
                Step::Index(i) => item.get_mut(*i),
            };
            item = next.unwrap_or_else(|| {
                let reached: Vec<String> = steps[..=n]
                    .iter()
                    .map(|s| match s {
                        Step::Key(k) => format!(".{k}"),
                        Step::Index(i) => format!("[{i}]"),
                    })
                    .collect();
                let reached = reached.concat();
                panic!(
                    "{what} has no `{}`: cannot change `{path}`",
                    reached.trim_start_matches('.')
                )
            });
        }
        item
    }

    /// The table-like item holding the last key of `path`, and that key.
    fn parent(&mut self, path: &str) -> (&mut dyn toml_edit::TableLike, String) {
        let mut steps = steps(path);
        let Some(Step::Key(key)) = steps.pop() else {
            panic!("key path {path:?} must end in a key");
        };
        let what = self.what.clone();
        let parent = self.walk(path, &steps);
        let table = parent
            .as_table_like_mut()
            .unwrap_or_else(|| panic!("{what}: `{path}` is not in a table"));
        (table, key)
    }

    /// Sets the value at `path`, which must be there and hold another value. A comment
    /// after the old value stays after the new one.
    pub fn set(&mut self, path: &str, value: impl SpecValue) -> &mut SpecEdit {
        let what = self.what.clone();
        let mut new = value.into_value();
        let item = self.walk(path, &steps(path));
        let old = item
            .as_value()
            .unwrap_or_else(|| panic!("{what}: `{path}` is a table, not a value"));
        assert_ne!(
            bare(old),
            bare(&new),
            "{what}: `{path}` is already {}: setting it changes nothing",
            bare(old)
        );
        *new.decor_mut() = old.decor().clone();
        *item = Item::Value(new);
        self
    }

    /// Asserts that the value at `path` is `value`: for a change that relies on what it finds
    /// there (`objects[3]` being the signs).
    pub fn expect(&mut self, path: &str, value: impl SpecValue) -> &mut SpecEdit {
        let found = self.get(path).and_then(Item::as_value).map(bare);
        let want = bare(&value.into_value());
        assert_eq!(
            found.as_deref(),
            Some(want.as_str()),
            "{}: `{path}` is not {want}",
            self.what
        );
        self
    }

    /// Adds the key at `path`, which must not be there, to its table, which must be.
    pub fn insert(&mut self, path: &str, value: impl SpecValue) -> &mut SpecEdit {
        let what = self.what.clone();
        let (table, key) = self.parent(path);
        assert!(
            !table.contains_key(&key),
            "{what}: `{path}` is there already: use set"
        );
        table.insert(&key, Item::Value(value.into_value()));
        self
    }

    /// Inserts a table, given as TOML text of its keys, into the array of tables at `path`
    /// before item `index` (`index` = its length appends).
    pub fn insert_table(&mut self, path: &str, index: usize, keys: &str) -> &mut SpecEdit {
        let what = self.what.clone();
        let table: Table = keys
            .parse::<DocumentMut>()
            .unwrap_or_else(|e| panic!("the table for `{path}` is not TOML: {e}"))
            .as_table()
            .clone();
        let item = self.walk(path, &steps(path));
        let array = item
            .as_array_of_tables_mut()
            .unwrap_or_else(|| panic!("{what}: `{path}` is not an array of tables"));
        assert!(
            index <= array.len(),
            "{what}: `{path}` has {} tables, none before {index}",
            array.len()
        );
        array.insert(index, table);
        self
    }

    /// Removes the key at `path` (a value or a whole table), which must be there.
    pub fn remove(&mut self, path: &str) -> &mut SpecEdit {
        let what = self.what.clone();
        let (table, key) = self.parent(path);
        table
            .remove(&key)
            .unwrap_or_else(|| panic!("{what} has no `{path}` to remove"));
        self
    }

    /// The spec's text, with every change.
    pub fn text(&self) -> String {
        self.doc.to_string()
    }
}

/// `text` with the value at `path` set to `value` (see [`SpecEdit::set`]).
pub fn set(text: &str, path: &str, value: impl SpecValue) -> String {
    SpecEdit::parse("the spec", text).set(path, value).text()
}
