//! `cityspec osm` as a user meets it: the committed extract read, its map and picture
//! written, and bad input refused with exit code 2, naming the file, writing nothing.

use std::fs;
use std::path::Path;
use std::process::{Command, Output};

fn osm(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cityspec"))
        .current_dir(dir)
        .arg("osm")
        .args(args)
        .output()
        .unwrap()
}

fn text(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn extract() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets/osm/helsinki.osm.pbf")
        .display()
        .to_string()
}

#[test]
fn the_helsinki_extract_reads_into_a_map_and_a_picture() {
    let dir = tempfile::tempdir().unwrap();
    let out = osm(
        dir.path(),
        &[
            &extract(),
            "--json",
            "map.json",
            "--picture",
            "map.png",
            "--picture-size",
            "300",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    let said = text(&out);
    assert!(
        said.contains("441 buildings (154 with a height from the map, 51 with 127 parts)"),
        "{said}"
    );
    assert!(said.contains("933 road pieces"), "{said}");
    let map: serde_json::Value =
        serde_json::from_slice(&fs::read(dir.path().join("map.json")).unwrap()).unwrap();
    // The cathedral's domes and six other areas tagged both `building` and `building:part`
    // are parts.
    assert_eq!(map["buildings"].as_array().unwrap().len(), 441);
    let picture = image::open(dir.path().join("map.png")).unwrap();
    assert_eq!(picture.height(), 300);
    // The same extract, the same bytes.
    let again = tempfile::tempdir().unwrap();
    let out = osm(again.path(), &[&extract(), "--json", "map.json"]);
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(
        fs::read(again.path().join("map.json")).unwrap(),
        fs::read(dir.path().join("map.json")).unwrap()
    );
}

#[test]
fn the_overview_is_the_maps_3d_city_from_the_air() {
    let dir = tempfile::tempdir().unwrap();
    let cut = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/osm/kamppi.osm.pbf");
    let out = osm(
        dir.path(),
        &[cut.to_str().unwrap(), "--overview", "city.png"],
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    let city = image::open(dir.path().join("city.png")).unwrap().to_rgb8();
    assert_eq!(city.dimensions(), (1280, 960));
    // Sky, grass, asphalt, facades and roofs: far more than a handful of colours.
    let colours: std::collections::BTreeSet<[u8; 3]> = city.pixels().map(|p| p.0).collect();
    assert!(colours.len() > 5_000, "{} colours", colours.len());
    let again = tempfile::tempdir().unwrap();
    osm(
        again.path(),
        &[cut.to_str().unwrap(), "--overview", "city.png"],
    );
    assert_eq!(
        fs::read(again.path().join("city.png")).unwrap(),
        fs::read(dir.path().join("city.png")).unwrap()
    );
}

#[test]
fn a_box_narrows_the_map() {
    let dir = tempfile::tempdir().unwrap();
    let out = osm(
        dir.path(),
        &[&extract(), "--bbox", "60.1665,24.938,60.17,24.946"],
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    assert!(text(&out).contains("44 buildings"), "{}", text(&out));
}

#[test]
fn bad_input_is_exit_code_2_and_names_the_file() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("photo.osm"), b"\x89PNG\r\n\x1a\n not a map").unwrap();
    fs::write(
        dir.path().join("broken.osm"),
        "<osm><node id=\"1\" lat=\"60\"/></osm>",
    )
    .unwrap();
    let cases: &[(&[&str], &str)] = &[
        (
            &["missing.osm.pbf"],
            "cannot read the extract missing.osm.pbf: no such file",
        ),
        (&["photo.osm"], "photo.osm: not an OpenStreetMap extract"),
        (
            &["broken.osm"],
            "broken.osm: broken OSM XML at byte 5: <node> has no lon",
        ),
        (&["broken.osm", "--bbox", "60,25,59,26"], "is empty"),
        (&["broken.osm", "--bbox", "60,25"], "expected four numbers"),
        (&["broken.osm", "--bbox", "95,25,96,26"], "off the globe"),
        (
            &[&extract(), "--bbox", "-33.9,18.4,-33.8,18.5"],
            "no node of the extract lies in the box -33.9,18.4,-33.8,18.5",
        ),
        (&["."], "not a regular file"),
    ];
    for (args, expected) in cases {
        let mut args = args.to_vec();
        args.extend(["--json", "map.json"]);
        let out = osm(dir.path(), &args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", text(&out));
        assert!(text(&out).contains(expected), "{args:?}: {}", text(&out));
        assert!(
            !dir.path().join("map.json").exists(),
            "{args:?} wrote a map"
        );
    }
}

/// A spec whose layout is `extract` (relative to the spec's folder), with `frames` street
/// frames, trees and cars.
fn map_spec(extract: &str, frames: u32) -> String {
    format!(
        "version = 1\nname = 'kamppi'\nseed = 3\n\
         [layout.osm]\nfile = '{extract}'\n\
         [[objects]]\nkind = 'tree'\ncount = 100\n\
         [[objects]]\nkind = 'car'\ncount = 4\n\
         [[cameras]]\nname = 'street'\npath = 'roads'\nframes = {frames}\n\
         resolution = [160, 120]\nlane_offset = 2.0\n\
         [annotations]\nclasses = ['building', 'lamp', 'tree', 'car']\nyolo = true\n"
    )
}

/// `spec` (a [`map_spec`] of `kamppi.osm.pbf`) with `line` added to its `[layout.osm]`.
fn with_osm_option(spec: &str, line: &str) -> String {
    let file = "file = 'kamppi.osm.pbf'\n";
    assert!(spec.contains(file), "{spec}");
    spec.replace(file, &format!("{file}{line}\n"))
}

/// A temporary folder holding the Kamppi extract as `kamppi.osm.pbf`.
fn with_kamppi() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/osm/kamppi.osm.pbf");
    fs::copy(&fixture, dir.path().join("kamppi.osm.pbf")).unwrap();
    dir
}

/// [`build`] with `-v`, which must succeed: what it said of each stage.
fn build_saying(dir: &Path, spec: &str, out: &str) -> String {
    let done = Command::new(env!("CARGO_BIN_EXE_cityspec"))
        .current_dir(dir)
        .args(["build", "-v", spec, "--out", out, "--cache", "cache"])
        .output()
        .unwrap();
    assert_eq!(done.status.code(), Some(0), "{}", text(&done));
    format!("{}{}", text(&done), String::from_utf8_lossy(&done.stdout))
}

/// How many objects named `prefix…` the city built into `out` has.
fn objects_named(dir: &Path, out: &str, prefix: &str) -> usize {
    let obj = fs::read_to_string(dir.join(out).join("kamppi/city.obj")).unwrap();
    obj.lines()
        .filter(|l| l.strip_prefix("o ").is_some_and(|n| n.starts_with(prefix)))
        .count()
}

fn build(dir: &Path, spec: &str, out: &str) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cityspec"))
        .current_dir(dir)
        .args(["build", "-q", spec, "--out", out, "--cache", "cache"])
        .output()
        .unwrap()
}

#[test]
fn a_spec_builds_a_city_with_labelled_frames_from_a_map() {
    let dir = with_kamppi();
    fs::write(dir.path().join("map.toml"), map_spec("kamppi.osm.pbf", 6)).unwrap();
    let out = build(dir.path(), "map.toml", "a");
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    let city = dir.path().join("a/kamppi");
    for file in [
        "city.glb",
        "overview.png",
        "plan.png",
        "frames/street/coco.json",
    ] {
        assert!(city.join(file).is_file(), "{file} is written");
    }
    let coco: serde_json::Value =
        serde_json::from_slice(&fs::read(city.join("frames/street/coco.json")).unwrap()).unwrap();
    assert_eq!(coco["images"].as_array().unwrap().len(), 6);
    let named = |id: &serde_json::Value| {
        coco["categories"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["id"] == *id)
            .map(|c| c["name"].as_str().unwrap().to_owned())
            .unwrap()
    };
    let seen: std::collections::BTreeSet<String> = coco["annotations"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| named(&a["category_id"]))
        .collect();
    assert!(
        seen.contains("building") && seen.contains("tree"),
        "{seen:?}"
    );
    // Built again from an empty cache: the same bytes.
    fs::remove_dir_all(dir.path().join("cache")).unwrap();
    let out = build(dir.path(), "map.toml", "b");
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    let b = dir.path().join("b/kamppi");
    for file in [
        "city.glb",
        "overview.png",
        "frames/street/coco.json",
        "frames/street/rgb/000000.png",
    ] {
        assert_eq!(
            fs::read(city.join(file)).unwrap(),
            fs::read(b.join(file)).unwrap(),
            "{file}"
        );
    }
}

#[test]
fn a_map_spec_whose_extract_is_broken_is_exit_code_2_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(
        dir.path().join("broken.osm"),
        "<osm><node id='1' lat='60.1'",
    )
    .unwrap();
    fs::write(dir.path().join("map.toml"), map_spec("broken.osm", 1)).unwrap();
    let out = build(dir.path(), "map.toml", "out");
    assert_eq!(out.status.code(), Some(2), "{}", text(&out));
    assert!(text(&out).contains("broken.osm"), "{}", text(&out));
    assert!(!dir.path().join("out/kamppi/city.glb").exists());
}

#[test]
fn filling_empty_blocks_adds_buildings_after_the_maps_own_and_reads_the_map_from_the_cache() {
    let dir = with_kamppi();
    let plain = map_spec("kamppi.osm.pbf", 1);
    let filled = with_osm_option(&plain, "fill_empty_blocks = true");
    assert_ne!(plain, filled);
    fs::write(dir.path().join("plain.toml"), plain).unwrap();
    fs::write(dir.path().join("filled.toml"), filled).unwrap();
    let out = build(dir.path(), "plain.toml", "a");
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    let said = build_saying(dir.path(), "filled.toml", "b");
    // The map is the plain build's; only placing and what follows it run.
    assert!(said.contains("cached layout"), "{said}");
    assert!(said.contains("ran    place"), "{said}");
    let buildings = |out: &str| objects_named(dir.path(), out, "building_");
    let (mapped, all) = (buildings("a"), buildings("b"));
    assert!(
        all > mapped,
        "{mapped} mapped, {all} with the empty blocks filled"
    );
    // From an empty cache: the same city.
    fs::remove_dir_all(dir.path().join("cache")).unwrap();
    let out = build(dir.path(), "filled.toml", "c");
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    for file in ["city.obj", "plan.png", "frames/street/rgb/000000.png"] {
        assert_eq!(
            fs::read(dir.path().join("b/kamppi").join(file)).unwrap(),
            fs::read(dir.path().join("c/kamppi").join(file)).unwrap(),
            "{file}"
        );
    }
}

#[test]
fn lamps_are_seeded_where_the_map_has_none_and_only_the_lamps_stage_reruns() {
    let dir = with_kamppi();
    let plain = map_spec("kamppi.osm.pbf", 1);
    let mapped_only = with_osm_option(&plain, "seed_lamps = false");
    let denser = format!("{plain}[lamps]\nspacing = 30\nmin_distance = 10\n");
    for (name, text) in [
        ("plain", &plain),
        ("mapped", &mapped_only),
        ("dense", &denser),
    ] {
        fs::write(dir.path().join(format!("{name}.toml")), text).unwrap();
    }
    let lamps = |out: &str| objects_named(dir.path(), out, "lamp_");
    let out = build(dir.path(), "mapped.toml", "a");
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    let out = build(dir.path(), "plain.toml", "b");
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    // A denser `[lamps]` reads the map from the cache and reruns the lamps and after.
    let said = build_saying(dir.path(), "dense.toml", "c");
    assert!(said.contains("cached layout"), "{said}");
    assert!(said.contains("ran    lamps"), "{said}");
    let (mapped, seeded, dense) = (lamps("a"), lamps("b"), lamps("c"));
    assert!(
        mapped < seeded && seeded < dense,
        "{mapped} mapped, {seeded} with the default spacing, {dense} every 30 m"
    );
}
