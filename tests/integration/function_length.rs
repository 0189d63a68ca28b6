//! Readable code: no non-test function in `src/` runs over [`MAX_LINES`] lines unless a
//! comment right above it says why (`// Long on purpose: …`).
//!
//! A function is a line starting (after indentation and `pub`/`pub(…)`, `const`, `async`,
//! `unsafe`) with `fn name`, up to the first line at its indentation that closes it with
//! `}`. Files under a `tests/` folder, `tests.rs` files, `test_support` and everything after
//! a file's `#[cfg(test)]` are tests.

use std::path::{Path, PathBuf};

/// The longest a function may be without a reason.
const MAX_LINES: usize = 80;

/// What the comment above a long function starts with.
const REASON: &str = "// Long on purpose:";

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            if name != "tests" && name != "test_support" {
                rust_files(&path, out);
            }
        } else if name.ends_with(".rs") && name != "tests.rs" && !name.ends_with("_tests.rs") {
            out.push(path);
        }
    }
}

/// `(first line, length, name)` of each function of `text` longer than `MAX_LINES` that
/// has no reason above it.
fn unexplained(text: &str) -> Vec<(usize, usize, String)> {
    let lines: Vec<&str> = text.lines().collect();
    let end = lines
        .iter()
        .position(|l| l.trim_start().starts_with("#[cfg(test)]"))
        .unwrap_or(lines.len());
    let mut found = Vec::new();
    for i in 0..end {
        let line = lines[i];
        let indent = line.len() - line.trim_start().len();
        let mut rest = line.trim_start();
        for prefix in [
            "pub(crate) ",
            "pub(super) ",
            "pub ",
            "const ",
            "async ",
            "unsafe ",
        ] {
            rest = rest.strip_prefix(prefix).unwrap_or(rest);
        }
        let Some(after) = rest.strip_prefix("fn ") else {
            continue;
        };
        if line.trim_end().ends_with(';') {
            continue;
        }
        let name: String = after
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        let close = format!("{}}}", " ".repeat(indent));
        let Some(last) = (i..end).find(|&j| lines[j].trim_end() == close) else {
            continue;
        };
        let length = last - i + 1;
        if length <= MAX_LINES {
            continue;
        }
        // The comments and attributes right above the function.
        let explained = lines[..i]
            .iter()
            .rev()
            .take_while(|l| {
                let t = l.trim_start();
                t.starts_with("//") || t.starts_with("#[")
            })
            .any(|l| l.trim_start().starts_with(REASON));
        if !explained {
            found.push((i + 1, length, name));
        }
    }
    found
}

#[test]
fn no_function_runs_over_80_lines_without_a_reason() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut problems = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        for (line, length, name) in unexplained(&text) {
            problems.push(format!(
                "{}:{line}: fn {name} runs {length} lines",
                file.display()
            ));
        }
    }
    assert!(
        problems.is_empty(),
        "split these into named steps, or say why not in a `{REASON} …` comment above:\n  {}",
        problems.join("\n  ")
    );
}

#[test]
fn the_scanner_measures_functions_and_reads_the_reason() {
    let body = "    let x = 1;\n".repeat(MAX_LINES);
    let long = format!("pub fn long() {{\n{body}}}\n");
    let reasoned = format!("/// Doc.\n{REASON} a table.\nfn table() {{\n{body}}}\n");
    let short = "fn short() {\n    1;\n}\n";
    let tests = format!("#[cfg(test)]\nmod tests {{\n    fn in_tests() {{\n{body}    }}\n}}\n");
    let text = format!("{short}{long}{reasoned}{tests}");
    assert_eq!(
        unexplained(&text),
        vec![(4, MAX_LINES + 2, "long".to_owned())]
    );
}
