//! The docs stay true: the README stays a newcomer's page (STYLE.md, "Docs"): short, the
//! two commands first, and every relative link in it and in `docs/` pointing at a file
//! that exists; and the module map in `src/lib.rs` names every public module.

use std::fs;
use std::path::{Path, PathBuf};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// The README's hard limit, in lines.
const MAX_LINES: usize = 220;

#[test]
fn the_readme_stays_a_newcomers_page() {
    let root = Path::new(ROOT);
    let readme = fs::read_to_string(root.join("README.md")).expect("README.md");

    let lines = readme.lines().count();
    assert!(
        lines <= MAX_LINES,
        "README.md has {lines} lines, more than {MAX_LINES}: move detail to docs/"
    );

    let first = first_code_block(&readme).expect("README.md has no code block");
    assert!(
        first.contains("cargo test"),
        "the README's first code block has no `cargo test`:\n{first}"
    );
    assert!(
        first.contains("build specs/"),
        "the README's first code block has no `build specs/…` command:\n{first}"
    );

    let mut pages = vec![root.join("README.md")];
    let mut docs: Vec<PathBuf> = fs::read_dir(root.join("docs"))
        .expect("docs/")
        .map(|e| e.expect("docs/ entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    assert!(!docs.is_empty(), "docs/ holds no .md page");
    pages.extend(docs);

    let (mut checked, mut broken) = (0, Vec::new());
    for page in &pages {
        let text = fs::read_to_string(page).expect("a page");
        let links = relative_links(&text);
        checked += links.len();
        let folder = page.parent().expect("a page's folder");
        for link in links {
            let path = link.split('#').next().unwrap_or_default();
            if !folder.join(path).exists() {
                broken.push(format!("{}: ]({link})", page.display()));
            }
        }
    }
    assert!(
        checked > 0,
        "no relative link found: the link parser is broken"
    );
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

/// The text of the first fenced code block.
fn first_code_block(text: &str) -> Option<String> {
    let mut lines = text.lines().skip_while(|l| !l.starts_with("```"));
    lines.next()?;
    let block: Vec<&str> = lines.take_while(|l| !l.starts_with("```")).collect();
    Some(block.join("\n"))
}

/// The targets of the markdown links `](target)` outside fenced code blocks that are not
/// web addresses or anchors on the same page.
fn relative_links(text: &str) -> Vec<String> {
    let mut links = Vec::new();
    let mut in_code = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            in_code = !in_code;
            continue;
        }
        if in_code {
            continue;
        }
        for (i, _) in line.match_indices("](") {
            let rest = &line[i + 2..];
            let end = rest.find([')', ' ']).unwrap_or(rest.len());
            let target = &rest[..end];
            let external = ["http://", "https://", "mailto:", "#"]
                .iter()
                .any(|p| target.starts_with(p));
            if !external {
                links.push(target.to_owned());
            }
        }
    }
    links
}

/// Every `pub mod` of `src/lib.rs` is named as a link (`` [`name`] ``) in its module docs:
/// in the stage table, or in the paragraph on shared modules (a hidden one is exempt).
#[test]
fn the_lib_rs_map_names_every_public_module() {
    let lib = fs::read_to_string(Path::new(ROOT).join("src/lib.rs")).expect("src/lib.rs");
    let docs: String = lib
        .lines()
        .filter_map(|line| line.strip_prefix("//!"))
        .collect::<Vec<_>>()
        .join("\n");
    let mut hidden = false;
    let mut missing = Vec::new();
    let mut modules = 0;
    for line in lib.lines() {
        if line.starts_with("#[doc(hidden)]") {
            hidden = true;
            continue;
        }
        if let Some(name) = line
            .strip_prefix("pub mod ")
            .and_then(|l| l.strip_suffix(';'))
        {
            modules += 1;
            if !hidden && !docs.contains(&format!("[`{name}`]")) {
                missing.push(name.to_owned());
            }
        }
        hidden = false;
    }
    assert!(
        modules > 10,
        "found only {modules} `pub mod` lines in src/lib.rs"
    );
    assert!(
        missing.is_empty(),
        "src/lib.rs's module docs do not name {missing:?}: add each to the stage table or \
         the paragraph on shared modules"
    );
}

const TABLE_START: &str = "<!-- stage table: made by cityspec::driver::key_table; \
                           CITYSPEC_BLESS=1 cargo test --test readme rewrites it -->\n";
const TABLE_END: &str = "<!-- end of stage table -->";

/// ARCHITECTURE's table of stages and what their keys hold is the stage table's own
/// account of itself, so it cannot go stale.
#[test]
fn architecture_s_stage_table_is_the_stage_table() {
    let path = Path::new(ROOT).join("ARCHITECTURE.md");
    let text = fs::read_to_string(&path).expect("ARCHITECTURE.md");
    let spec_text = fs::read_to_string(Path::new(ROOT).join("specs/day.toml")).expect("day.toml");
    let spec: cityspec::spec::Spec = toml::from_str(&spec_text).expect("day.toml parses");
    let table = cityspec::driver::key_table(&spec);
    let start = text
        .find(TABLE_START)
        .expect("ARCHITECTURE.md has the stage table's start marker")
        + TABLE_START.len();
    let end = start
        + text[start..]
            .find(TABLE_END)
            .expect("ARCHITECTURE.md has the stage table's end marker");
    if std::env::var_os("CITYSPEC_BLESS").is_some() {
        let renewed = format!("{}{table}{}", &text[..start], &text[end..]);
        fs::write(&path, renewed).expect("ARCHITECTURE.md written");
        return;
    }
    assert_eq!(
        text[start..end],
        table,
        "ARCHITECTURE.md's stage table is stale: CITYSPEC_BLESS=1 cargo test --test readme"
    );
}
