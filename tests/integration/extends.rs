//! Specs that build on specs: `extends`, the example variants, errors placed in the file
//! that wrote the value.

use crate::common;

use std::fs;
use std::path::Path;

use cityspec::spec::{self, FsWorld, SpecSource};
use common::{Workspace, cityspec, stderr};

/// The example specs rewritten as short variants of `specs/day.toml`. Their long texts
/// from before the rewrite (copies of day.toml with a few changes, as committed then) are
/// kept in `tests/fixtures/before_extends/` only for this comparison.
const VARIANTS: [&str; 5] = ["dusk", "fog", "night", "rain", "randomized"];

#[test]
fn each_example_variant_loads_to_the_spec_its_long_text_gave() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    for name in VARIANTS {
        let path = repo.join("specs").join(format!("{name}.toml"));
        let short = fs::read_to_string(&path).unwrap();
        assert!(short.contains("extends = \"day.toml\""), "{name}");
        let long = fs::read_to_string(
            repo.join("tests/fixtures/before_extends")
                .join(format!("{name}.toml")),
        )
        .unwrap();
        assert!(!long.contains("extends"), "{name}");
        assert!(short.lines().count() * 3 < long.lines().count(), "{name}");
        let merged = cityspec::driver::load_spec(&path).unwrap();
        // The long text as if it still stood at specs/<name>.toml, so its relative paths
        // resolve as they did.
        let before = spec::load(&SpecSource { path, text: long }, &FsWorld).unwrap();
        assert_eq!(merged, before, "{name}");
        assert_eq!(merged.name, name);
    }
}

/// Writes `files` (name, text) into `specs/` of a workspace holding the examples.
fn with_files(files: &[(&str, &str)]) -> Workspace {
    let ws = Workspace::with_spec("day");
    for (name, text) in files {
        fs::write(ws.path().join("specs").join(name), text).unwrap();
    }
    ws
}

#[test]
fn a_missing_base_is_an_invalid_spec_naming_the_file_and_extends() {
    let ws = with_files(&[("child.toml", "# a variant\nextends = \"gone.toml\"\n")]);
    let out = cityspec(&ws, &["validate", "specs/child.toml"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let text = stderr(&out);
    assert!(
        text.contains("specs/child.toml:2:11")
            && text.contains("invalid `extends`")
            && text.contains("expected a spec file to extend at specs/gone.toml")
            && text.contains("found no such file"),
        "{text}"
    );
}

#[test]
fn a_cycle_of_bases_is_refused_naming_its_files() {
    let ws = with_files(&[
        ("a.toml", "extends = \"b.toml\"\nname = \"a\"\n"),
        ("b.toml", "extends = \"a.toml\"\n"),
    ]);
    let out = cityspec(&ws, &["build", "specs/a.toml"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let text = stderr(&out);
    assert!(
        text.contains("specs/b.toml:1:11")
            && text.contains("found a cycle: specs/a.toml → specs/b.toml → specs/a.toml"),
        "{text}"
    );
}

#[test]
fn an_error_points_at_the_base_or_the_child_whichever_wrote_the_value() {
    let ws = with_files(&[
        (
            "base.toml",
            "version = 1\nname = \"base\"\n[layout.generate]\nwidth = 384\nheight = 384\n\
             road_width = 300\n",
        ),
        ("in_base.toml", "extends = \"base.toml\"\nname = \"b\"\n"),
        (
            "in_child.toml",
            "extends = \"base.toml\"\nname = \"c\"\n\n[layout.generate]\nroad_width = 32\n\
             strip_width = -1\n",
        ),
    ]);
    let out = cityspec(&ws, &["validate", "specs/in_base.toml"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let text = stderr(&out);
    assert!(
        text.contains("specs/base.toml:6:14") && text.contains("road_width = 300"),
        "{text}"
    );
    assert!(
        text.contains("specs/in_base.toml is not a valid spec"),
        "{text}"
    );
    let out = cityspec(&ws, &["validate", "specs/in_child.toml"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let text = stderr(&out);
    assert!(
        text.contains("specs/in_child.toml:6:15") && text.contains("strip_width = -1"),
        "{text}"
    );
    // The child's road width replaced the base's bad one.
    assert!(!text.contains("road_width"), "{text}");
}

#[test]
fn set_overrides_a_value_after_extends_in_validate_and_explain() {
    let ws = Workspace::with_spec("night");
    let out = cityspec(
        &ws,
        &[
            "validate",
            "specs/night.toml",
            "--set",
            "cameras.street.frames=3",
            "--set",
            "name=night_short",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("ok (night_short)"),
        "{}",
        stderr(&out)
    );
    // The street path's key changes with its frames; the city's does not.
    let explain = |extra: &[&str]| {
        let mut args = vec!["explain", "--json", "specs/night.toml"];
        args.extend_from_slice(extra);
        let out = cityspec(&ws, &args);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let keys: Vec<(String, String)> = json[0]["stages"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| {
                (
                    format!("{} {}", s["stage"], s["camera"]),
                    s["key"].to_string(),
                )
            })
            .collect();
        keys
    };
    let plain = explain(&[]);
    let set = explain(&["--set", "cameras.street.frames=3"]);
    assert_eq!(plain.len(), set.len());
    let changed: Vec<&String> = plain
        .iter()
        .zip(&set)
        .filter(|(a, b)| a != b)
        .map(|((stage, _), _)| stage)
        .collect();
    assert!(!changed.is_empty());
    // The street camera's frames, and the dataset stage that reads every camera's.
    assert!(
        changed
            .iter()
            .all(|s| s.contains("street") || s.starts_with("\"dataset\"")),
        "{changed:?}"
    );
}

#[test]
fn an_unknown_set_key_is_an_invalid_spec_naming_set() {
    let ws = Workspace::with_spec("day");
    let out = cityspec(
        &ws,
        &[
            "build",
            "specs/day.toml",
            "--set",
            "cameras.street.framez=3",
        ],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let text = stderr(&out);
    assert!(
        text.contains("--set:1:1")
            && text.contains("cameras[0].framez")
            && text.contains("did you mean `frames`?"),
        "{text}"
    );
    assert!(!ws.path().join("out/day").exists());
}

#[test]
fn a_cameras_own_weather_changes_only_its_own_frames_rgb() {
    let ws = Workspace::with_spec("day");
    ws.shrink_day();
    fs::write(
        ws.spec("fogged_street"),
        "extends = \"day.toml\"\nname = \"fogged_street\"\n\n[[cameras]]\nname = \"street\"\n\n\
         [cameras.weather]\nkind = \"fog\"\nstrength = 1.0\nfog_density = 0.05\n",
    )
    .unwrap();
    let fogged = cityspec::driver::load_spec(&ws.spec("fogged_street")).unwrap();
    assert!(fogged.cameras[0].weather.is_some());
    assert!(fogged.cameras[1].weather.is_none());
    let options = ws.options();
    cityspec::driver::build(&ws.spec("day"), &options).unwrap();
    cityspec::driver::build(&ws.spec("fogged_street"), &options).unwrap();
    let frames =
        |spec: &str, camera: &str| common::tree(&ws.out().join(spec).join("frames").join(camera));
    // The other camera's frames: every byte the same.
    let (plain, other) = (frames("day", "aerial"), frames("fogged_street", "aerial"));
    assert!(!plain.is_empty());
    assert_eq!(plain, other);
    // The fogged camera: the same files, the RGB images changed, ids and depth not.
    let (plain, fog) = (frames("day", "street"), frames("fogged_street", "street"));
    assert_eq!(
        plain.keys().collect::<Vec<_>>(),
        fog.keys().collect::<Vec<_>>()
    );
    let mut rgb = 0;
    for (name, bytes) in &fog {
        if name.starts_with("ids/") || name.starts_with("depth/") {
            assert!(bytes == &plain[name], "{name} changed");
        } else if name.starts_with("rgb/") {
            assert!(
                bytes != &plain[name],
                "{name} unchanged by the camera's fog"
            );
            rgb += 1;
        }
    }
    assert_eq!(rgb, 2);
    // Labels: the same objects; fog decides only which stand out enough to be positives.
    common::same_objects_but_for_contrast(&plain["coco.json"], &fog["coco.json"]);
}
