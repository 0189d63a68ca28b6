//! The stage boundary of ARCHITECTURE.md, checked: no stage names another stage, except
//! along the graph's declared edges ([`EDGES`]).
//!
//! Every `.rs` file under `src/<module>/` (and `src/<module>.rs`) is scanned for paths that
//! start with `crate::` — in `use` lines, in `use crate::{a, b}` groups spread over lines
//! and inline (`crate::layout::generate(…)`). Comments are skipped (doc links do not make
//! a dependency). A stage may name only itself and the shared modules; a shared module only
//! other shared modules; `test_support` alone may call stages, so that a stage's tests can
//! get another stage's output without importing it. The cache knows no stage and no
//! driver. Only the driver (`driver`, `out_dir`) and `cli`
//! may name everything.
//!
//! A new top-level module must be added to one of the lists below, so the rule cannot be
//! dodged by forgetting it. Not caught: `super::super::…` climbing out of a stage folder
//! (no file does that today) and paths written inside macros' string arguments.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The pipeline's stages: each one a function from the previous stage's type to its own.
const STAGES: &[&str] = &[
    "layout", "parse", "mirror", "lamps", "place", "plan", "preview", "facades", "scene",
    "objects", "export", "cameras", "render", "annotate", "sensor", "stats", "views", "dataset",
    "lidar", "traffic", "osm",
];

/// The stages a stage may read besides itself and the shared modules: the graph's
/// declared edges. `views` chooses among the cameras stage's draws by rendering them in
/// the scene; `dataset` writes its COCO documents with the annotate stage's writer;
/// `traffic` switches the signal heads' lamps the objects stage made.
const EDGES: &[(&str, &[&str])] = &[
    ("views", &["cameras", "render", "scene"]),
    ("dataset", &["annotate"]),
    ("lidar", &["render"]),
    ("traffic", &["objects"]),
];

/// What every stage may use: types and geometry (`model`), the spec, seeded randomness, hashing,
/// image-file checks, the diagnostics stages report and regular-file opening.
const SHARED: &[&str] = &[
    "model",
    "spec",
    "rng",
    "hash",
    "test_seed",
    "diagnostic",
    "regular_file",
];

/// Test fakes and fixtures: shared by every stage's tests, and the one place (besides the
/// driver) that may run stages, to hand one stage's tests another stage's output.
const TEST_SUPPORT: &str = "test_support";

/// The content-addressed cache and atomic file writing: below the driver, and knowing
/// no stage (a cache entry's stage is a name the driver hands it) and no driver.
const STORES: &[&str] = &["cache", "atomic_file"];

/// The build driver (the evaluator), the output folder it writes and the CLI: they wire
/// the stages together.
const DRIVERS: &[&str] = &["driver", "out_dir", "cli"];

/// Modules a file under `module` may not name.
fn forbidden(module: &str) -> Vec<&'static str> {
    let stages_and_drivers = STAGES.iter().chain(DRIVERS);
    if STORES.contains(&module) {
        stages_and_drivers.copied().collect()
    } else if STAGES.contains(&module) || SHARED.contains(&module) {
        let allowed: &[&str] = EDGES
            .iter()
            .find(|(from, _)| *from == module)
            .map_or(&[], |(_, to)| to);
        stages_and_drivers
            .chain(STORES)
            .copied()
            .filter(|m| *m != module && !allowed.contains(m))
            .collect()
    } else if module == TEST_SUPPORT {
        DRIVERS.to_vec()
    } else {
        Vec::new()
    }
}

/// `text` with `//` comments blanked (string literals kept), line breaks preserved.
fn without_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        let mut in_string = false;
        let mut escaped = false;
        let mut chars = line.char_indices().peekable();
        let mut end = line.len();
        while let Some((i, c)) = chars.next() {
            if in_string {
                match c {
                    _ if escaped => escaped = false,
                    '\\' => escaped = true,
                    '"' => in_string = false,
                    _ => {}
                }
            } else if c == '"' {
                in_string = true;
            } else if c == '/' && chars.peek().is_some_and(|(_, n)| *n == '/') {
                end = i;
                break;
            }
        }
        out.push_str(&line[..end]);
        out.push('\n');
    }
    out
}

/// Each `(line, first path segment after crate::)` in `code`, groups expanded.
fn crate_paths(code: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    let line_of = |at: usize| code[..at].matches('\n').count() + 1;
    let mut from = 0;
    while let Some(pos) = code[from..].find("crate::") {
        let start = from + pos;
        from = start + "crate::".len();
        // `crate::` inside a longer word (`my_crate::`) is not our crate.
        let before = code[..start].chars().next_back();
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let rest = &code[from..];
        if rest.starts_with('{') {
            // A group: its top-level items, each starting with a module name.
            let mut depth = 0;
            let mut item_start = from + 1;
            for (i, c) in rest.char_indices() {
                let at = from + i;
                match c {
                    '{' => depth += 1,
                    '}' | ',' if depth == 1 => {
                        push_first_segment(code, item_start, at, &line_of, &mut found);
                        item_start = at + 1;
                        if c == '}' {
                            break;
                        }
                    }
                    '}' => depth -= 1,
                    _ => {}
                }
            }
        } else {
            push_first_segment(code, from, code.len(), &line_of, &mut found);
        }
    }
    found
}

fn push_first_segment(
    code: &str,
    start: usize,
    end: usize,
    line_of: &dyn Fn(usize) -> usize,
    found: &mut Vec<(usize, String)>,
) {
    let item = &code[start..end];
    let offset = item.len() - item.trim_start().len();
    let name: String = item
        .trim_start()
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect();
    if !name.is_empty() {
        found.push((line_of(start + offset), name));
    }
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Every violation under `src`, one `file:line: ...` line each.
fn violations(src: &Path) -> Vec<String> {
    let mut found = Vec::new();
    let mut modules: Vec<PathBuf> = std::fs::read_dir(src)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    modules.sort();
    for path in modules {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        if name == "lib" || name == "main" {
            continue;
        }
        let known = STAGES.contains(&name.as_str())
            || SHARED.contains(&name.as_str())
            || STORES.contains(&name.as_str())
            || DRIVERS.contains(&name.as_str())
            || name == TEST_SUPPORT;
        if !known {
            found.push(format!(
                "{}: module `{name}` is in no list of tests/integration/stage_imports.rs: is it a stage or shared?",
                path.display()
            ));
            continue;
        }
        let banned = forbidden(&name);
        let mut files = Vec::new();
        if path.is_dir() {
            rust_files(&path, &mut files);
        } else {
            files.push(path.clone());
        }
        for file in files {
            let text = std::fs::read_to_string(&file).unwrap();
            let code = without_comments(&text);
            let lines: Vec<&str> = text.lines().collect();
            for (line, target) in crate_paths(&code) {
                if banned.contains(&target.as_str()) {
                    let shown = lines.get(line - 1).map_or("", |l| l.trim());
                    found.push(format!(
                        "{}:{line}: `{name}` uses `crate::{target}`: {shown}",
                        file.display()
                    ));
                }
            }
        }
    }
    found
}

#[test]
fn no_stage_imports_another_stage() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let found = violations(&src);
    if !found.is_empty() {
        let mut message = format!(
            "{} import(s) cross a stage boundary. Move what both sides need into a shared \
             module ({}), or get another stage's output in tests through `{TEST_SUPPORT}`:\n",
            found.len(),
            SHARED.join(", ")
        );
        for v in &found {
            writeln!(message, "  {v}").unwrap();
        }
        panic!("{message}");
    }
}

#[test]
fn the_scanner_sees_groups_inline_paths_and_skips_comments() {
    let code = without_comments(
        "use crate::model::Block;\n\
         use crate::{\n    lamps,\n    scene::KERB_Y,\n};\n\
         let x = crate::layout::generate(); // crate::render in a comment\n\
         /// [`crate::parse`] in a doc comment\n\
         let s = \"// not a comment\"; crate::objects::run();\n\
         other_crate::stats::x();\n",
    );
    let found: Vec<(usize, String)> = crate_paths(&code);
    let want: Vec<(usize, String)> = [
        (1, "model"),
        (3, "lamps"),
        (4, "scene"),
        (6, "layout"),
        (8, "objects"),
    ]
    .map(|(l, n)| (l, n.to_string()))
    .to_vec();
    assert_eq!(found, want);
}

#[test]
fn a_stage_naming_another_is_reported_with_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path();
    std::fs::create_dir_all(src.join("objects")).unwrap();
    std::fs::create_dir_all(src.join("test_support")).unwrap();
    std::fs::write(
        src.join("objects/car.rs"),
        "use crate::model::Mesh;\n\nuse crate::scene::KERB_Y;\n",
    )
    .unwrap();
    // test_support may run stages; shared modules may not; unknown modules are reported.
    std::fs::write(
        src.join("test_support/mod.rs"),
        "use crate::layout::generate;\n",
    )
    .unwrap();
    std::fs::write(src.join("model.rs"), "use crate::render::Frame;\n").unwrap();
    std::fs::write(src.join("weather.rs"), "").unwrap();
    let found = violations(src);
    assert_eq!(found.len(), 3, "{found:#?}");
    assert!(
        found[0].ends_with("model.rs:1: `model` uses `crate::render`: use crate::render::Frame;")
    );
    assert!(
        found[1].ends_with(
            "objects/car.rs:3: `objects` uses `crate::scene`: use crate::scene::KERB_Y;"
        )
    );
    assert!(found[2].contains("module `weather` is in no list"));
}
