//! The spec-editing helper the other tests change their specs with
//! (`tests/common/spec_edit.rs`): each change takes effect, or panics naming what is missing.

use crate::common::{SpecEdit, set};

const SPEC: &str = "version = 1\nname = \"small\"   # a comment\n\n\
                    [[cameras]]\nname = \"street\"\nframes = 43       # per path\n\
                    resolution = [64, 48]\n\n[cameras.sensor]\nnoise = [0.0, 0.01]\n";

#[test]
fn set_changes_the_value_and_keeps_the_comments() {
    let text = set(SPEC, "cameras[0].frames", 3);
    let frames = "frames = 3       # per path\n";
    assert!(text.contains(frames), "{text}");
    assert_eq!(text.len(), SPEC.len() - 1, "{text}");
    let text = set(&text, "cameras[0].resolution", [256, 192]);
    assert!(text.contains("resolution = [256, 192]\n"), "{text}");
    let text = set(&text, "name", "other");
    assert!(text.contains("name = \"other\"   # a comment\n"), "{text}");
}

#[test]
fn insert_and_remove_add_and_drop_keys_and_tables() {
    let mut spec = SpecEdit::parse("spec", SPEC);
    spec.insert("cameras[0].headlights", false)
        .remove("cameras[0].sensor")
        .insert_table("cameras", 0, "name = \"extra\"\nframes = 2");
    let parsed: toml::Table = spec.text().parse().unwrap();
    let cameras = parsed["cameras"].as_array().unwrap();
    assert_eq!(cameras[0]["name"].as_str(), Some("extra"));
    assert_eq!(cameras[1]["headlights"].as_bool(), Some(false));
    assert!(cameras[1].get("sensor").is_none());
}

#[test]
fn the_example_specs_and_the_shards_fixture_come_back_byte_for_byte_when_unchanged() {
    let repo = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let examples = std::fs::read_dir(repo.join("specs")).unwrap();
    let fixture = repo.join("tests/fixtures/shards.toml");
    for path in examples.map(|e| e.unwrap().path()).chain([fixture]) {
        let text = std::fs::read_to_string(&path).unwrap();
        let what = path.display().to_string();
        assert_eq!(SpecEdit::parse(&what, &text).text(), text, "{what}");
    }
}

#[test]
#[should_panic(expected = "the spec has no `cameras[1]`: cannot change `cameras[1].frames`")]
fn setting_a_missing_key_panics_naming_it() {
    set(SPEC, "cameras[1].frames", 3);
}

#[test]
#[should_panic(expected = "`cameras[0].frames` is already 43: setting it changes nothing")]
fn setting_a_key_to_its_value_panics() {
    set(SPEC, "cameras[0].frames", 43);
}

#[test]
#[should_panic(expected = "spec: `name` is there already")]
fn inserting_a_key_that_is_there_panics() {
    SpecEdit::parse("spec", SPEC).insert("name", "x");
}

#[test]
#[should_panic(expected = "spec has no `cameras[0].fov` to remove")]
fn removing_a_missing_key_panics() {
    SpecEdit::parse("spec", SPEC).remove("cameras[0].fov");
}
