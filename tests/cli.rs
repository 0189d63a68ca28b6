//! The `cityspec` binary as a user meets it: exit codes, messages, help, killed builds.

mod common;

use std::fs;
use std::process::{Command, Output, Stdio};
use std::time::Duration;

use common::{Workspace, tree};

fn cityspec(ws: &Workspace, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cityspec"))
        .current_dir(ws.path())
        .args(args)
        .output()
        .unwrap()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn build_writes_artifacts_into_out_and_says_so() {
    let ws = Workspace::with_spec("day");
    let out = cityspec(&ws, &["build", "specs/day.toml"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("day: built out/day"),
        "{}",
        stderr(&out)
    );
    for file in ["layout.png", "plan.json", "plan.png", "manifest.json"] {
        assert!(ws.path().join("out/day").join(file).is_file(), "{file}");
    }
    assert!(ws.path().join(".cityspec-cache/entries").is_dir());
    let again = cityspec(&ws, &["build", "-v", "specs/day.toml"]);
    let text = stderr(&again);
    assert!(text.contains("up to date"), "{text}");
    assert!(!text.contains(" ran "), "{text}");
}

#[test]
fn thread_count_does_not_change_bytes() {
    let ws = Workspace::with_spec("mirrored");
    let one = cityspec(
        &ws,
        &[
            "build",
            "-q",
            "-j1",
            "--out",
            "one",
            "--cache",
            "c1",
            "specs/mirrored.toml",
        ],
    );
    let eight = cityspec(
        &ws,
        &[
            "build",
            "-q",
            "-j8",
            "--out",
            "eight",
            "--cache",
            "c8",
            "specs/mirrored.toml",
        ],
    );
    assert!(one.status.success() && eight.status.success());
    assert!(stderr(&one).is_empty(), "-q prints nothing on success");
    assert_eq!(tree(&ws.path().join("one")), tree(&ws.path().join("eight")));
}

#[test]
fn invalid_spec_exits_2_with_location_and_writes_nothing() {
    let ws = Workspace::with_spec("day");
    ws.edit_spec("day", "road_width = 32", "road_width = 3200");
    let out = cityspec(&ws, &["build", "specs/day.toml"]);
    assert_eq!(out.status.code(), Some(2));
    let text = stderr(&out);
    assert!(text.contains("specs/day.toml:13:14"), "{text}");
    assert!(text.contains("layout.generate.road_width"), "{text}");
    assert!(
        !ws.path().join("out").exists(),
        "no artifact for an invalid spec"
    );
    let validate = cityspec(&ws, &["validate", "specs/day.toml"]);
    assert_eq!(validate.status.code(), Some(2));
}

#[test]
fn missing_spec_file_and_bad_usage_exit_2() {
    let ws = Workspace::with_spec("day");
    let missing = cityspec(&ws, &["build", "specs/nope.toml"]);
    assert_eq!(missing.status.code(), Some(2));
    assert!(
        stderr(&missing).contains("cannot read spec specs/nope.toml"),
        "{}",
        stderr(&missing)
    );
    assert_eq!(cityspec(&ws, &["build"]).status.code(), Some(2));
    assert_eq!(cityspec(&ws, &["frobnicate"]).status.code(), Some(2));
    assert_eq!(
        cityspec(&ws, &["build", "-j0", "specs/day.toml"])
            .status
            .code(),
        Some(2)
    );
}

#[test]
fn two_specs_with_one_name_are_refused() {
    let ws = Workspace::with_spec("day");
    fs::copy(ws.spec("day"), ws.path().join("specs/copy.toml")).unwrap();
    let out = cityspec(&ws, &["build", "specs/day.toml", "specs/copy.toml"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("both named \"day\""),
        "{}",
        stderr(&out)
    );
}

#[test]
fn validate_and_schema() {
    let ws = Workspace::with_spec("day");
    let out = cityspec(&ws, &["validate", "specs/day.toml", "specs/mirrored.toml"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let schema = cityspec(&ws, &["schema"]);
    assert!(schema.status.success());
    let committed = fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/schemas/cityspec.schema.json"
    ))
    .unwrap();
    assert_eq!(String::from_utf8(schema.stdout).unwrap(), committed);
}

#[test]
fn help_explains_with_examples() {
    let ws = Workspace::with_spec("day");
    for args in [
        &["--help"][..],
        &["build", "--help"],
        &["validate", "--help"],
        &["schema", "--help"],
    ] {
        let out = cityspec(&ws, args);
        assert!(out.status.success());
        let text = String::from_utf8(out.stdout).unwrap();
        assert!(text.contains("Example"), "{args:?}: {text}");
    }
}

#[test]
fn killed_build_leaves_no_partial_artifact() {
    let ws = Workspace::with_spec("mirrored");
    // The reference: a whole build, its artifacts' hashes.
    let reference = cityspec(
        &ws,
        &[
            "build",
            "-q",
            "--out",
            "ref",
            "--cache",
            "ref-cache",
            "specs/mirrored.toml",
        ],
    );
    assert!(reference.status.success());
    let whole = tree(&ws.path().join("ref/mirrored"));
    for delay_ms in [5u64, 30, 80, 150, 300] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_cityspec"))
            .current_dir(ws.path())
            .args(["build", "-q", "-j2", "specs/mirrored.toml"])
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(delay_ms));
        let _ = child.kill();
        let _ = child.wait();
        let out = ws.path().join("out/mirrored");
        if out.exists() {
            for (name, bytes) in tree(&out) {
                if name.starts_with('.') {
                    continue; // a temporary, swept by the next build
                }
                assert_eq!(
                    Some(&bytes),
                    whole.get(&name),
                    "{name} is partial after a kill at {delay_ms} ms"
                );
            }
        }
        // Cache entries only ever point at whole objects: whatever was recorded verifies.
        let cache = cityspec::build::Cache::new(ws.path().join(".cityspec-cache"));
        if let Ok(entries) = fs::read_dir(ws.path().join(".cityspec-cache/entries")) {
            for entry in entries {
                let name = entry.unwrap().file_name().to_string_lossy().into_owned();
                if let Some(key) = name.strip_suffix(".json") {
                    assert!(
                        cache.get(key, cityspec::build::Load::References).is_ok(),
                        "entry {key} is not whole after a kill"
                    );
                }
            }
        }
    }
    let finish = cityspec(&ws, &["build", "-q", "specs/mirrored.toml"]);
    assert!(finish.status.success());
    assert_eq!(
        tree(&ws.path().join("out/mirrored")),
        whole,
        "the next build completes and sweeps temporaries"
    );
}

#[test]
fn facades_export_writes_the_builtin_set_in_the_cmp_layout() {
    let ws = Workspace::with_spec("day");
    let out = cityspec(&ws, &["facades", "export", "facades"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let written = tree(&ws.path().join("facades"));
    let expected: std::collections::BTreeMap<String, Vec<u8>> = cityspec::facades::builtin()
        .to_files()
        .into_iter()
        .collect();
    assert_eq!(written, expected);
    for ext in ["jpg", "xml", "png"] {
        assert!(written.contains_key(&format!("builtin_00.{ext}")), "{ext}");
    }
}
