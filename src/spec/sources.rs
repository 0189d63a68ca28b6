//! Sources: a spec file, the bases it `extends` and the `--set` lines → one spanned TOML
//! tree, every span pointing at the file and line that wrote the value.
//!
//! `extends = "day.toml"` (relative to the spec's folder) names a base spec; the base is
//! read first (and its own base, and so on; a cycle is refused, naming its files), then
//! each file is merged onto the one it extends ([`super::merge`]), and the `--set` lines
//! last of all. The texts are laid end to end in one combined text: file `i` starts at
//! offset `start_i`, and every span of the merged tree is an offset into the combined text,
//! so a span alone says which file wrote a value. [`Sources::localize`] turns a diagnostic
//! placed in the combined text back into a file, line and column.

use std::ops::Range;
use std::path::{Component, Path, PathBuf};

use toml::Spanned;
use toml::de::{DeArray, DeTable, DeValue};

use super::diagnostic::Diagnostic;
use super::key_path::KeyPath;
use super::merge::{MergeProblem, merge_tables};
use super::{SpecSource, SpecWorld};

/// The key that names a spec's base.
pub(crate) const EXTENDS: &str = "extends";

/// The most files one chain of `extends` may hold: a chain through a symlinked folder
/// (`extends = "link/a.toml"`, `link` → `.`) names a new path at every step and would
/// never close into a cycle.
pub(crate) const MAX_CHAIN: usize = 16;

/// The name `--set` lines are reported under.
pub const SET_FILE: &str = "--set";

/// One file of a spec's chain: the spec, one of its bases, or the `--set` lines.
#[derive(Clone, Debug)]
pub(crate) struct SourceFile {
    pub(crate) path: PathBuf,
    pub(crate) text: String,
    /// Offset of this file's text in the combined text.
    pub(crate) start: usize,
}

/// Every file a spec is made of, the spec first, then its bases, then `--set`.
#[derive(Clone, Debug)]
pub(crate) struct Sources {
    pub(crate) files: Vec<SourceFile>,
    /// The texts end to end, each followed by a newline; spans index into it.
    pub(crate) combined: String,
}

impl Sources {
    /// The spec's file and every base it extends, read through `world`, and `sets` (TOML
    /// lines `key.path = value`) as a last file. Err: the diagnostics (already localized)
    /// of a file that does not parse, a bad `extends`, a missing base or a cycle.
    pub(crate) fn read(
        source: &SpecSource,
        sets: &[String],
        world: &dyn SpecWorld,
    ) -> Result<Sources, (Sources, Vec<Diagnostic>)> {
        let mut sources = Sources {
            files: Vec::new(),
            combined: String::new(),
        };
        sources.push(source.path.clone(), source.text.clone());
        loop {
            let last = sources.files.len() - 1;
            let (path, extends) = {
                let file = &sources.files[last];
                let table = match DeTable::parse(&file.text) {
                    Ok(table) => table.into_inner(),
                    Err(error) => {
                        let d = super::syntax_diagnostic(&file.text, &error);
                        let d = sources.shifted(last, d);
                        return Err((sources, vec![d]));
                    }
                };
                let Some(value) = table.get(EXTENDS) else {
                    break;
                };
                let span = value.span();
                let Some(relative) = value.get_ref().as_str() else {
                    let message = format!(
                        "expected the path of a spec file to extend, found {}",
                        super::toml_json::describe(value.get_ref())
                    );
                    return Err(sources.fail(last, span, message));
                };
                (
                    normalize(&super::resolve(&file.path, relative)),
                    (span, relative.to_string()),
                )
            };
            let (span, relative) = extends;
            if sources.files.len() >= MAX_CHAIN {
                let message = format!(
                    "expected at most {MAX_CHAIN} specs in a chain of `extends`, found more \
                     (a chain through a symlinked folder never closes into a cycle)"
                );
                return Err(sources.fail(last, span, message));
            }
            if let Some(cycle) = sources.cycle_through(&path) {
                let message = format!(
                    "expected a base that does not extend this spec again, found a cycle: {cycle}"
                );
                return Err(sources.fail(last, span, message));
            }
            match world.spec_text(&path) {
                Ok(text) => sources.push(path, text),
                Err(why) => {
                    let message = format!(
                        "expected a spec file to extend at {} (\"{relative}\" from this \
                         spec's folder), found {why}",
                        path.display()
                    );
                    return Err(sources.fail(last, span, message));
                }
            }
        }
        if !sets.is_empty() {
            let mut text = sets.join("\n");
            text.push('\n');
            sources.push(PathBuf::from(SET_FILE), text);
        }
        Ok(sources)
    }

    /// The chain `a → b → … → path` when extending `path` would close a cycle.
    fn cycle_through(&self, path: &Path) -> Option<String> {
        let first = self.files.iter().position(|f| normalize(&f.path) == path)?;
        let cycle: Vec<String> = self.files[first..]
            .iter()
            .map(|f| f.path.display().to_string())
            .chain([path.display().to_string()])
            .collect();
        Some(cycle.join(" → "))
    }

    fn push(&mut self, path: PathBuf, text: String) {
        let start = self.combined.len();
        self.combined.push_str(&text);
        self.combined.push('\n');
        self.files.push(SourceFile { path, text, start });
    }

    /// A diagnostic placed in file `index`'s own text, moved into the combined text.
    fn shifted(&self, index: usize, d: Diagnostic) -> Diagnostic {
        let start = self.files[index].start;
        let span = d.span.start + start..d.span.end + start;
        self.localize(Diagnostic::new(&self.combined, span, d.key, d.message))
    }

    fn fail(
        self,
        index: usize,
        local: Range<usize>,
        message: String,
    ) -> (Sources, Vec<Diagnostic>) {
        let start = self.files[index].start;
        let span = local.start + start..local.end + start;
        let d = self.localize(Diagnostic::new(
            &self.combined,
            span,
            KeyPath::root().key(EXTENDS),
            message,
        ));
        (self, vec![d])
    }

    /// The merged tree: the last base first, each file merged onto the one it extends,
    /// `--set` last; `extends` itself is dropped. Problems of the merge come back too.
    pub(crate) fn tree(&self) -> (DeTable<'_>, Vec<MergeProblem>) {
        let mut problems = Vec::new();
        let mut merged: Option<DeTable<'_>> = None;
        let sets = self.files.last().filter(|f| f.path == Path::new(SET_FILE));
        let specs = self.files.len() - usize::from(sets.is_some());
        let order = (0..specs).rev().chain(sets.map(|_| self.files.len() - 1));
        for index in order {
            let file = &self.files[index];
            if file.path == Path::new(SET_FILE) {
                let tree = merged.get_or_insert_with(DeTable::new);
                let mut at = file.start;
                for line in file.text.lines() {
                    set(tree, line, at, &mut problems);
                    at += line.len() + 1;
                }
                continue;
            }
            // Every file parsed when it was read.
            let Ok(table) = DeTable::parse(&file.text) else {
                continue;
            };
            let mut table = shift_table(table.into_inner(), file.start);
            table.remove(EXTENDS);
            merged = Some(match merged {
                None => table,
                Some(mut base) => {
                    merge_tables(&mut base, table, &KeyPath::root(), &mut problems);
                    base
                }
            });
        }
        (merged.unwrap_or_default(), problems)
    }

    /// The file whose text holds combined offset `offset`.
    fn file_at(&self, offset: usize) -> &SourceFile {
        self.files
            .iter()
            .rev()
            .find(|f| f.start <= offset)
            .unwrap_or(&self.files[0])
    }

    /// `d`, placed in the combined text, re-placed in the file that holds its span.
    pub(crate) fn localize(&self, d: Diagnostic) -> Diagnostic {
        let file = self.file_at(d.span.start);
        let span = d.span.start - file.start..d.span.end.saturating_sub(file.start);
        let mut local = Diagnostic::new(&file.text, span, d.key, d.message);
        local.file = Some(file.path.clone());
        local
    }

    /// The combined text's `(path, text)` of each file, for rendering.
    pub(crate) fn texts(&self) -> Vec<(PathBuf, String)> {
        self.files
            .iter()
            .map(|f| (f.path.clone(), f.text.clone()))
            .collect()
    }
}

/// Applies one `--set` line, `key.path=value`, written at combined offset `at`, to `tree`:
/// the value parsed as a TOML value (a string when it is not one), merged at the key path
/// by the usual rules; a key path step into an array of named tables picks the entry of
/// that name (`cameras.street.frames=4`).
fn set<'i>(tree: &mut DeTable<'i>, line: &'i str, at: usize, problems: &mut Vec<MergeProblem>) {
    let (keys, names, value) = match parse_set(line, at) {
        Ok(parsed) => parsed,
        Err(problem) => return problems.push(problem),
    };
    // The tree to merge into, and the path shown in messages.
    let mut path = KeyPath::root();
    let mut table = tree;
    let (last, steps) = names.split_last().unwrap_or((&"", &[]));
    let mut steps = steps.iter().peekable();
    while let Some(&name) = steps.next() {
        let span = at..at + keys.len();
        path = path.key(name);
        let slot = table
            .entry(Spanned::new(span.clone(), name.into()))
            .or_insert_with(|| Spanned::new(span.clone(), DeValue::Table(DeTable::new())));
        match slot.get_mut() {
            DeValue::Table(next) => table = next,
            DeValue::Array(items) => {
                // The step after an array names one of its entries.
                let Some(&entry) = steps.next() else {
                    problems.push((
                        span,
                        path.clone(),
                        format!(
                            "expected `--set {path}.NAME.key=value` (an entry's keys are set \
                             one by one), or `--set {path}=[…]` to replace the whole array"
                        ),
                    ));
                    return;
                };
                let found = items.iter().position(|item| {
                    item.get_ref()
                        .as_table()
                        .and_then(|t| t.get("name"))
                        .and_then(|n| n.get_ref().as_str())
                        == Some(entry)
                });
                let Some(index) = found else {
                    problems.push((
                        span,
                        path.clone(),
                        format!(
                            "expected the name of an entry of `{path}` \
                             (`--set {path}.NAME.key=value`), found \"{entry}\", which no \
                             entry is named"
                        ),
                    ));
                    return;
                };
                path = path.index(index);
                // An entry with a name is a table.
                let Some(DeValue::Table(next)) = items.get_mut(index).map(Spanned::get_mut) else {
                    return;
                };
                table = next;
            }
            other => {
                problems.push((
                    span,
                    path.clone(),
                    format!(
                        "expected a table at `{path}` to set a key in, found {}",
                        super::toml_json::describe(other)
                    ),
                ));
                return;
            }
        }
    }
    let mut child = DeTable::new();
    child.insert(Spanned::new(at..at + keys.len(), (*last).into()), value);
    merge_tables(table, child, &path, problems);
}

/// A `--set` line at combined offset `at`: its key path as written and split at the dots,
/// and its value (a TOML value, or the text as a string when it is not one).
#[allow(clippy::type_complexity)]
fn parse_set<'i>(
    line: &'i str,
    at: usize,
) -> Result<(&'i str, Vec<&'i str>, Spanned<DeValue<'i>>), MergeProblem> {
    let Some((keys, raw)) = line.split_once('=') else {
        return Err((
            at..at + line.len(),
            KeyPath::root(),
            format!("expected `--set key.path=value`, found \"{line}\" (no `=`)"),
        ));
    };
    let value_at = at + keys.len() + 1;
    let trimmed = raw.trim_start();
    let value_at = value_at + raw.len() - trimmed.len();
    let trimmed = trimmed.trim_end();
    let value_span = value_at..value_at + trimmed.len();
    let value = match DeValue::parse(trimmed) {
        Ok(value) => shift(value, value_at),
        Err(_) => Spanned::new(value_span, DeValue::String(trimmed.into())),
    };
    let names: Vec<&str> = keys.trim().split('.').map(str::trim).collect();
    if names.iter().any(|n| n.is_empty()) {
        return Err((
            at..at + keys.len(),
            KeyPath::root(),
            format!("expected `--set key.path=value` with a dotted key path, found \"{keys}\""),
        ));
    }
    Ok((keys, names, value))
}

/// `path` with `.` dropped and `a/..` folded, so two spellings of one file compare equal.
fn normalize(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for component in path.components() {
        match component {
            Component::CurDir => {}
            Component::ParentDir
                if matches!(out.components().next_back(), Some(Component::Normal(_))) =>
            {
                out.pop();
            }
            other => out.push(other),
        }
    }
    out
}

fn shift<'i>(value: Spanned<DeValue<'i>>, by: usize) -> Spanned<DeValue<'i>> {
    let span = value.span();
    let value = match value.into_inner() {
        DeValue::Table(t) => DeValue::Table(shift_table(t, by)),
        DeValue::Array(a) => {
            let mut shifted = DeArray::new();
            for item in a.iter().cloned() {
                shifted.push(shift(item, by));
            }
            DeValue::Array(shifted)
        }
        other => other,
    };
    Spanned::new(span.start + by..span.end + by, value)
}

fn shift_table(table: DeTable<'_>, by: usize) -> DeTable<'_> {
    let mut shifted = DeTable::new();
    for (key, value) in table {
        let span = key.span();
        shifted.insert(
            Spanned::new(span.start + by..span.end + by, key.into_inner()),
            shift(value, by),
        );
    }
    shifted
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(unix)]
    #[test]
    fn a_chain_through_a_symlinked_folder_stops_at_its_cap() {
        let dir = tempfile::tempdir().unwrap();
        std::os::unix::fs::symlink(dir.path(), dir.path().join("link")).unwrap();
        let path = dir.path().join("a.toml");
        let text = "extends = \"link/a.toml\"\n".to_string();
        std::fs::write(&path, &text).unwrap();
        let source = SpecSource { path, text };
        let (sources, diagnostics) =
            Sources::read(&source, &[], &crate::spec::FsWorld).unwrap_err();
        assert_eq!(sources.files.len(), MAX_CHAIN);
        assert_eq!(diagnostics.len(), 1);
        assert!(
            diagnostics[0]
                .message
                .starts_with("expected at most 16 specs"),
            "{:?}",
            diagnostics[0]
        );
        assert_eq!(diagnostics[0].key, "extends");
    }

    #[test]
    fn normalize_folds_dots() {
        assert_eq!(
            normalize(Path::new("specs/./a/../day.toml")),
            Path::new("specs/day.toml")
        );
        assert_eq!(normalize(Path::new("../x.toml")), Path::new("../x.toml"));
    }
}
