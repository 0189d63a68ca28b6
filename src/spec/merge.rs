//! Merge: a base spec's TOML tree + a child's (or a `--set`'s) → one tree, the child winning.
//!
//! The rules, applied key by key from the root:
//!
//! | base value | child value | result |
//! |---|---|---|
//! | table | table | merged key by key (these rules, one level down) |
//! | array of tables, each with a unique string `name` | the same | merged by `name`: an entry whose name is in the base merges onto that entry (in the base's place); a new name is appended; `{ name = "x", remove = true }` removes entry `x` |
//! | anything else | anything | the child's value replaces the base's (arrays whole: `[[objects]]` has no names, so a child that writes `[[objects]]` writes all of them) |
//!
//! Every node keeps the span it was written at, and spans point into one combined text of
//! all the files (see [`super::sources`]), so each merged value still names the file and
//! line that set it: that is the key path → (file, span) map diagnostics are placed with.

use std::ops::Range;

use toml::Spanned;
use toml::de::{DeArray, DeString, DeTable, DeValue};

use super::key_path::KeyPath;

/// A problem found while merging: where, which key, what.
pub(crate) type MergeProblem = (Range<usize>, KeyPath, String);

/// The key that, set to `true` in a named array entry, removes that entry from the base.
pub(crate) const REMOVE: &str = "remove";

/// Merges `child` onto `base` (see the module docs); problems (a `remove` that names no
/// entry, or holds more than `name`) are pushed to `problems`.
pub(crate) fn merge_tables<'i>(
    base: &mut DeTable<'i>,
    child: DeTable<'i>,
    path: &KeyPath,
    problems: &mut Vec<MergeProblem>,
) {
    for (key, value) in child {
        let here = path.key(key.get_ref());
        let Some(existing) = base.get_mut(key.get_ref().as_ref()) else {
            base.insert(key, value);
            continue;
        };
        let span = value.span();
        let both_named = matches!(
            (existing.get_ref(), value.get_ref()),
            (DeValue::Array(old), DeValue::Array(new)) if names(old).is_some() && names(new).is_some()
        );
        match (existing.get_mut(), value.into_inner()) {
            (DeValue::Table(old), DeValue::Table(new)) => {
                merge_tables(old, new, &here, problems);
                // The table now holds keys of both files; point at the child's header.
                let merged = std::mem::take(old);
                *existing = Spanned::new(span, DeValue::Table(merged));
                replace_key(base, key);
            }
            (DeValue::Array(old), DeValue::Array(new)) if both_named => {
                let merged =
                    merge_named(std::mem::replace(old, DeArray::new()), new, &here, problems);
                *existing = Spanned::new(span, DeValue::Array(merged));
                replace_key(base, key);
            }
            (_, new) => {
                base.remove(key.get_ref().as_ref());
                base.insert(key, Spanned::new(span, new));
            }
        }
    }
}

/// Re-inserts `base[key]` under the child's key, so the key's span is the child's.
fn replace_key<'i>(base: &mut DeTable<'i>, key: Spanned<DeString<'i>>) {
    if let Some(value) = base.remove(key.get_ref().as_ref()) {
        base.insert(key, value);
    }
}

/// The `name` of each entry when every entry is a table with a string `name` and no two
/// share one; `None` otherwise (an empty array counts as named: it can be merged onto).
fn names<'a, 'i>(array: &'a DeArray<'i>) -> Option<Vec<&'a str>> {
    let mut names = Vec::new();
    for item in array.iter() {
        let name = item.get_ref().as_table()?.get("name")?.get_ref().as_str()?;
        if names.contains(&name) {
            return None;
        }
        names.push(name);
    }
    Some(names)
}

fn entry_name<'a>(item: &'a Spanned<DeValue<'_>>) -> &'a str {
    item.get_ref()
        .as_table()
        .and_then(|t| t.get("name"))
        .and_then(|n| n.get_ref().as_str())
        .unwrap_or_default()
}

/// `remove = true` in a child entry: Some(span of the `remove` value) when written so.
fn removal(item: &Spanned<DeValue<'_>>) -> Option<Range<usize>> {
    let value = item.get_ref().as_table()?.get(REMOVE)?;
    (value.get_ref().as_bool() == Some(true)).then(|| value.span())
}

fn merge_named<'i>(
    base: DeArray<'i>,
    child: DeArray<'i>,
    path: &KeyPath,
    problems: &mut Vec<MergeProblem>,
) -> DeArray<'i> {
    let mut items: Vec<Spanned<DeValue<'i>>> = base.iter().cloned().collect();
    for (index, item) in child.iter().cloned().enumerate() {
        let name = entry_name(&item).to_string();
        let at = items.iter().position(|old| entry_name(old) == name);
        if let Some(span) = removal(&item) {
            let here = path.index(index).key(REMOVE);
            let extra = item.get_ref().as_table().is_some_and(|t| {
                t.keys()
                    .any(|k| !["name", REMOVE].contains(&k.get_ref().as_ref()))
            });
            match at {
                _ if extra => problems.push((
                    span,
                    here,
                    format!(
                        "expected only `name` beside `remove = true` (an entry is removed \
                         whole), found more keys in entry \"{name}\""
                    ),
                )),
                Some(at) => {
                    items.remove(at);
                }
                None => problems.push((
                    span,
                    here,
                    format!(
                        "expected the name of an entry of the base's `{path}` to remove, \
                         found \"{name}\", which the base does not have"
                    ),
                )),
            }
            continue;
        }
        match at {
            Some(at) => {
                let span = item.span();
                let old = &mut items[at];
                if let (DeValue::Table(old), DeValue::Table(new)) =
                    (old.get_mut(), item.into_inner())
                {
                    merge_tables(old, new, &path.index(at), problems);
                }
                let merged = std::mem::replace(items[at].get_mut(), DeValue::Boolean(false));
                items[at] = Spanned::new(span, merged);
            }
            None => items.push(item),
        }
    }
    let mut merged = DeArray::new();
    for item in items {
        merged.push(item);
    }
    merged
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::toml_json::to_json;

    /// `child` merged onto `base`, as JSON text, and the problems as `key: message`.
    fn merged(base: &str, child: &str) -> (String, Vec<String>) {
        let mut tree = DeTable::parse(base).unwrap().into_inner();
        let child = DeTable::parse(child).unwrap().into_inner();
        let mut problems = Vec::new();
        merge_tables(&mut tree, child, &KeyPath::root(), &mut problems);
        let problems = problems
            .into_iter()
            .map(|(_, key, message)| format!("{key}: {message}"))
            .collect();
        (to_json(&tree).0.to_string(), problems)
    }

    #[test]
    fn tables_merge_key_by_key_and_scalars_and_arrays_replace() {
        let cases = [
            ("a = 1\nb = 2\n", "b = 3\n", r#"{"a":1,"b":3}"#),
            (
                "[t]\nx = 1\ny = 2\n",
                "[t]\ny = 5\nz = 6\n",
                r#"{"t":{"x":1,"y":5,"z":6}}"#,
            ),
            (
                "[t.u]\nx = 1\n",
                "t.u.y = 2\n",
                r#"{"t":{"u":{"x":1,"y":2}}}"#,
            ),
            ("xs = [1, 2, 3]\n", "xs = [4]\n", r#"{"xs":[4]}"#),
            // A table over a scalar and a scalar over a table: the child's value wins.
            ("t = 1\n", "[t]\nx = 1\n", r#"{"t":{"x":1}}"#),
            ("[t]\nx = 1\n", "t = 2\n", r#"{"t":2}"#),
            // Tables without names: the whole array is replaced.
            (
                "[[o]]\nk = 1\n[[o]]\nk = 2\n",
                "[[o]]\nk = 3\n",
                r#"{"o":[{"k":3}]}"#,
            ),
        ];
        for (base, child, want) in cases {
            let (got, problems) = merged(base, child);
            assert_eq!(got, want, "{base} + {child}");
            assert!(problems.is_empty(), "{problems:?}");
        }
    }

    #[test]
    fn named_tables_merge_by_name_append_and_remove() {
        let base = "[[c]]\nname = 'a'\nf = 1\ng = 1\n[[c]]\nname = 'b'\nf = 2\n";
        let cases = [
            (
                "[[c]]\nname = 'a'\nf = 9\n",
                r#"{"c":[{"f":9,"g":1,"name":"a"},{"f":2,"name":"b"}]}"#,
            ),
            (
                "[[c]]\nname = 'z'\nf = 3\n",
                r#"{"c":[{"f":1,"g":1,"name":"a"},{"f":2,"name":"b"},{"f":3,"name":"z"}]}"#,
            ),
            (
                "[[c]]\nname = 'a'\nremove = true\n",
                r#"{"c":[{"f":2,"name":"b"}]}"#,
            ),
            // Order stays the base's; nested tables of an entry merge too.
            (
                "[[c]]\nname = 'b'\n[c.s]\nq = 1\n[[c]]\nname = 'a'\ng = 5\n",
                r#"{"c":[{"f":1,"g":5,"name":"a"},{"f":2,"name":"b","s":{"q":1}}]}"#,
            ),
        ];
        for (child, want) in cases {
            let (got, problems) = merged(base, child);
            assert_eq!(got, want, "{child}");
            assert!(problems.is_empty(), "{problems:?}");
        }
    }

    #[test]
    fn a_removal_must_name_a_base_entry_and_nothing_else() {
        let base = "[[c]]\nname = 'a'\n";
        let (_, problems) = merged(base, "[[c]]\nname = 'x'\nremove = true\n");
        assert_eq!(
            problems,
            [
                "c[0].remove: expected the name of an entry of the base's `c` to remove, found \
              \"x\", which the base does not have"
            ]
        );
        let (got, problems) = merged(base, "[[c]]\nname = 'a'\nremove = true\nf = 1\n");
        assert_eq!(
            problems,
            [
                "c[0].remove: expected only `name` beside `remove = true` (an entry is removed \
              whole), found more keys in entry \"a\""
            ]
        );
        assert_eq!(got, r#"{"c":[{"name":"a"}]}"#);
    }

    #[test]
    fn merged_values_keep_the_span_they_were_written_at() {
        let base = "[t]\nx = 1\ny = 2\n";
        let child = "[t]\ny = 3\n";
        let mut tree = DeTable::parse(base).unwrap().into_inner();
        // The child's spans as if its text came after the base's.
        let offset = base.len();
        let padded = format!("{}{child}", " ".repeat(offset));
        let child_tree = DeTable::parse(&padded).unwrap().into_inner();
        merge_tables(&mut tree, child_tree, &KeyPath::root(), &mut Vec::new());
        let t = tree.get("t").unwrap().get_ref().as_table().unwrap();
        assert_eq!(t.get("x").unwrap().span(), 8..9);
        assert_eq!(t.get("y").unwrap().span(), offset + 8..offset + 9);
    }
}
