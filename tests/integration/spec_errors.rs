//! Spec errors, end to end: the committed schema matches the types, every bad fixture gives
//! exactly the diagnostics written at its top, and every good fixture loads.
//!
//! A bad fixture states its expected output in comment lines at the top:
//!
//! ```toml
//! # expect: 7:14 layout.generate.road_width: expected an integer at most 256, found 1000
//! ```
//!
//! (`line:col key: message-substring`, one line per diagnostic). The test loads each with
//! the build's world ([`BuildWorld`]: the file system and the parse stage) and requires, for each expectation, a line of the report starting
//! `{fixture path}:{line}:{col}: error: {key}: ` that contains the message, and exactly as
//! many diagnostics as expectations.

use std::cell::RefCell;
use std::path::{Path, PathBuf};

use cityspec::driver::BuildWorld;
use cityspec::spec::{self, FsWorld, SpecSource, SpecWorld};

const SCHEMA_PATH: &str = "schemas/cityspec.schema.json";

fn source(path: &Path) -> SpecSource {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    SpecSource {
        path: path.to_path_buf(),
        text,
    }
}

fn fixtures(folder: &str) -> Vec<PathBuf> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(folder)
        .unwrap_or_else(|e| panic!("cannot list {folder}: {e}"))
        .map(|entry| entry.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    paths.sort();
    paths
}

#[test]
fn committed_schema_matches_the_types() {
    let generated = spec::schema_json();
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR")).join(SCHEMA_PATH);
    if std::env::var_os("CITYSPEC_BLESS").is_some_and(|v| v == "1") {
        std::fs::write(&manifest, &generated).unwrap();
    }
    let committed = std::fs::read_to_string(&manifest).unwrap_or_default();
    assert!(
        committed == generated,
        "{SCHEMA_PATH} differs from the schema the spec types generate.\n\
         Regenerate it with `cargo run -- schema > {SCHEMA_PATH}` \
         (or `CITYSPEC_BLESS=1 cargo test --test spec_errors`)."
    );
}

/// `(line, column, key, message substring)` from a fixture's `# expect:` lines.
fn expectations(text: &str) -> Result<Vec<(usize, usize, String, String)>, String> {
    let mut out = Vec::new();
    for line in text.lines() {
        let Some(rest) = line.strip_prefix("# expect: ") else {
            continue;
        };
        let parsed = (|| {
            let (position, rest) = rest.split_once(' ')?;
            let (l, c) = position.split_once(':')?;
            let (key, message) = rest.split_once(": ")?;
            Some((
                l.parse().ok()?,
                c.parse().ok()?,
                key.to_string(),
                message.to_string(),
            ))
        })();
        out.push(parsed.ok_or_else(|| format!("malformed expect line {line:?}"))?);
    }
    Ok(out)
}

/// What is wrong with one bad fixture's report, if anything.
fn check_bad_fixture(path: &Path) -> Option<String> {
    let source = source(path);
    let expected = match expectations(&source.text) {
        Ok(e) if e.is_empty() => return Some("has no `# expect:` lines".to_string()),
        Ok(e) => e,
        Err(e) => return Some(e),
    };
    let errors = match spec::load(&source, &BuildWorld) {
        Ok(_) => return Some("loaded without errors".to_string()),
        Err(errors) => errors,
    };
    let report = errors.to_string();
    let mut problems = Vec::new();
    for (line, column, key, message) in &expected {
        let prefix = format!("{}:{line}:{column}: error: {key}: ", path.display());
        let found = report.lines().any(|l| {
            l.strip_prefix(&prefix)
                .is_some_and(|m| m.contains(message.as_str()))
        });
        if !found {
            problems.push(format!("missing `{prefix}…{message}…`"));
        }
    }
    if errors.diagnostics.len() != expected.len() {
        problems.push(format!(
            "{} diagnostics for {} expect lines",
            errors.diagnostics.len(),
            expected.len()
        ));
    }
    (!problems.is_empty()).then(|| {
        format!(
            "{}\n  got:\n    {}",
            problems.join("\n  "),
            report.replace('\n', "\n    ")
        )
    })
}

#[test]
fn bad_fixtures_give_their_expected_errors() {
    let paths = fixtures("tests/fixtures/bad");
    assert!(paths.len() >= 25, "only {} bad fixtures", paths.len());
    let failures: Vec<String> = paths
        .iter()
        .filter_map(|p| check_bad_fixture(p).map(|why| format!("{}: {why}", p.display())))
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} bad fixtures failed:\n\n{}",
        failures.len(),
        paths.len(),
        failures.join("\n\n")
    );
}

#[test]
fn good_fixtures_load() {
    let paths = fixtures("tests/fixtures/good");
    assert!(paths.len() >= 3, "only {} good fixtures", paths.len());
    let failures: Vec<String> = paths
        .iter()
        .filter_map(|p| {
            spec::load(&source(p), &BuildWorld)
                .err()
                .map(|e| e.to_string())
        })
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn examples_point_editors_at_the_committed_schema() {
    for path in fixtures("tests/fixtures/good") {
        let text = source(&path).text;
        let first = text.lines().next().unwrap_or_default();
        let schema = first
            .strip_prefix("#:schema ")
            .unwrap_or_else(|| panic!("{} does not start with `#:schema …`", path.display()));
        let resolved = spec::resolve(&path, schema);
        assert!(
            resolved.is_file(),
            "{}: {} is not a file",
            path.display(),
            resolved.display()
        );
    }
}

/// A world of fixed images that records which paths the spec stage asked about.
struct FakeWorld {
    images: Vec<(PathBuf, (u32, u32))>,
    asked: RefCell<Vec<PathBuf>>,
}

impl SpecWorld for FakeWorld {
    fn folder(&self, path: &Path) -> Result<(), String> {
        Err(format!("no folder {} in this fake world", path.display()))
    }

    fn file(&self, path: &Path) -> Result<(), String> {
        Err(format!("no file {} in this fake world", path.display()))
    }

    fn spec_text(&self, path: &Path) -> Result<String, String> {
        Err(format!("no spec {} in this fake world", path.display()))
    }

    fn image_dimensions(&self, path: &Path) -> Result<(u32, u32), String> {
        self.asked.borrow_mut().push(path.to_path_buf());
        self.images
            .iter()
            .find(|(p, _)| p == path)
            .map(|(_, dims)| *dims)
            .ok_or_else(|| "no such file".to_string())
    }
}

#[test]
fn image_paths_resolve_against_the_spec_folder() {
    let world = FakeWorld {
        images: vec![(PathBuf::from("specs/day/layouts/a.png"), (512, 256))],
        asked: RefCell::new(Vec::new()),
    };
    let text = "version = 1\nname = \"day\"\n[layout]\nimage = \"layouts/a.png\"\nmirror = [2]\n";
    let source = SpecSource {
        path: PathBuf::from("specs/day/city.toml"),
        text: text.to_string(),
    };
    let spec = spec::load(&source, &world).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(spec.layout.image.as_deref(), Some("layouts/a.png"));
    assert_eq!(
        *world.asked.borrow(),
        [PathBuf::from("specs/day/layouts/a.png")]
    );

    let elsewhere = SpecSource {
        path: PathBuf::from("other/city.toml"),
        ..source
    };
    let errors = spec::load(&elsewhere, &world).unwrap_err();
    assert_eq!(
        errors.to_string(),
        "other/city.toml:4:9: error: layout.image: expected a PNG or JPEG layout image at \
         other/layouts/a.png, found no such file"
    );
}

#[test]
fn resolve_joins_the_spec_folder() {
    let cases = [
        ("city.toml", "a.png", "a.png"),
        ("specs/city.toml", "a.png", "specs/a.png"),
        ("specs/city.toml", "../img/a.png", "specs/../img/a.png"),
        ("specs/city.toml", "/abs/a.png", "/abs/a.png"),
    ];
    for (spec_path, relative, want) in cases {
        assert_eq!(
            spec::resolve(Path::new(spec_path), relative),
            PathBuf::from(want)
        );
    }
}

#[test]
fn a_spec_with_only_version_name_and_generate_gets_every_default() {
    let source = SpecSource {
        path: PathBuf::from("min.toml"),
        text: "version = 1\nname = \"min\"\n[layout.generate]\n".to_string(),
    };
    let spec = spec::load(&source, &FsWorld).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(spec.seed, 0);
    assert_eq!(spec.layout.generate, Some(spec::GenerateSpec::default()));
    assert_eq!(spec.layout.palette, spec::Palette::default());
    assert_eq!(spec.buildings, spec::BuildingsSpec::default());
    assert_eq!(spec.lamps, spec::LampsSpec::default());
    assert!(spec.layout.mirror.is_empty());
    assert_eq!(spec.layout.metres_per_pixel, 0.55);
}

#[test]
fn render_points_at_every_error_of_a_file() {
    let path = Path::new("tests/fixtures/bad/several_errors.toml");
    let errors = spec::load(&source(path), &FsWorld).unwrap_err();
    let out = spec::report(&errors, false);
    let count = errors.diagnostics.len();
    assert!(count >= 3, "{out}");
    assert_eq!(out.matches("error: invalid `").count(), count, "{out}");
    for d in &errors.diagnostics {
        assert!(out.contains(&d.message), "{out}");
        assert!(
            out.contains(&format!("{}:{}:{}", path.display(), d.line, d.column)),
            "{out}"
        );
    }
    assert!(out.ends_with(&format!("{count} errors\n")), "{out}");
}
