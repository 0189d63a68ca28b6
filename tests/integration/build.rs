//! The build driver and its cache, through the library API: determinism across cold and
//! warm caches and thread counts, minimal rebuilds, damaged caches.

use crate::common;

use std::fs;

use cityspec::driver::{self, StageStatus};
use common::{Workspace, tree};

fn in_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

fn statuses(report: &driver::BuildReport) -> Vec<(&'static str, StageStatus)> {
    let mut s: Vec<_> = report.stages.iter().map(|r| (r.stage, r.status)).collect();
    s.sort();
    s
}

/// A frame's file in the dataset-level folders (an image or label of `yolo/` or
/// `cityscapes/`), relative to the spec's output folder.
fn dataset_frame_file(path: &str) -> bool {
    path.starts_with("yolo/images/")
        || path.starts_with("yolo/labels/")
        || (path.starts_with("cityscapes/") && path.ends_with(".png"))
}

#[test]
fn cold_warm_one_and_eight_threads_give_identical_bytes() {
    let ws = Workspace::with_spec("day");
    let spec = ws.spec("day");
    let cold = in_pool(1, || driver::build(&spec, &ws.options())).unwrap();
    // Every stage, with each camera path's plan (poses) as its own stage.
    assert_eq!(cold.ran().count(), 16, "a cold build runs every stage");
    let first = tree(&ws.out());
    let names: Vec<&str> = first.keys().map(String::as_str).collect();
    let named: Vec<&str> = names
        .iter()
        .copied()
        .filter(|n| !n.starts_with("day/textures/") && !n.starts_with("day/frames/"))
        .filter(|n| !dataset_frame_file(n.strip_prefix("day/").unwrap_or(n)))
        .collect();
    assert_eq!(
        named,
        [
            "day/city.glb",
            "day/city.mtl",
            "day/city.obj",
            "day/cityscapes/gtFine/cityscapes_panoptic_train.json",
            "day/cityscapes/gtFine/cityscapes_panoptic_val.json",
            "day/cityscapes/labels.json",
            "day/coco/train.json",
            "day/coco/val.json",
            "day/layout.png",
            "day/manifest.json",
            "day/overview.png",
            "day/plan.json",
            "day/plan.png",
            "day/yolo/data.yaml",
            "day/yolo/dataset.yaml"
        ]
    );
    assert!(
        names.len() > named.len() + 10,
        "the facade and roof textures: {names:?}"
    );

    let warm = in_pool(8, || driver::build(&spec, &ws.options())).unwrap();
    assert!(warm.up_to_date());
    assert_eq!(tree(&ws.out()), first);

    // A second, independent cache and output folder, eight threads.
    let other = Workspace::with_spec("day");
    in_pool(8, || driver::build(&other.spec("day"), &other.options())).unwrap();
    assert_eq!(tree(&other.out()), first);
    // The caches hold the same objects too.
    for part in ["objects", "entries"] {
        assert_eq!(
            tree(&other.cache().join(part)),
            tree(&ws.cache().join(part)),
            "{part}"
        );
    }
}

#[test]
fn noop_rebuild_does_no_stage_work_and_rewrites_nothing() {
    let ws = Workspace::with_spec("day");
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let stamp = |p: &str| {
        fs::metadata(ws.out().join("day").join(p))
            .unwrap()
            .modified()
            .unwrap()
    };
    let names: Vec<String> = tree(&ws.out().join("day")).into_keys().collect();
    let before: Vec<_> = names.iter().map(|n| stamp(n)).collect();
    std::thread::sleep(std::time::Duration::from_millis(20));
    let report = driver::build(&ws.spec("day"), &ws.options()).unwrap();
    assert!(report.up_to_date());
    assert!(
        report
            .stages
            .iter()
            .all(|s| s.status == StageStatus::Cached)
    );
    assert!(report.written.is_empty());
    assert_eq!(report.unchanged.len(), names.len());
    let after: Vec<_> = names.iter().map(|n| stamp(n)).collect();
    assert_eq!(
        before, after,
        "a no-op rebuild must not rewrite any artifact"
    );
}

#[test]
fn changing_only_lamps_reruns_only_what_reads_lamps() {
    let ws = Workspace::with_spec("day");
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let plan_before = fs::read(ws.out().join("day/plan.json")).unwrap();
    ws.set("day", "lamps.spacing", 20);
    let report = driver::build(&ws.spec("day"), &ws.options()).unwrap();
    use StageStatus::{Cached, Ran};
    assert_eq!(
        statuses(&report),
        [
            ("dataset", Ran),
            ("export", Ran),
            ("facades", Cached),
            ("frames", Ran),
            ("frames", Ran),
            ("frames-plan", Ran),
            ("frames-plan", Ran),
            ("lamps", Ran),
            ("mirror", Cached),
            ("overview", Ran),
            ("parse", Cached),
            ("place", Cached),
            ("plan", Ran),
            ("preview", Ran),
            ("scene", Ran)
        ]
    );
    let written: Vec<&str> = report
        .written
        .iter()
        .map(String::as_str)
        .filter(|p| !p.starts_with("frames/"))
        .collect();
    // The lamps moved, so did the signs that keep clear of them: the city files change.
    for file in [
        "city.glb",
        "city.obj",
        "overview.png",
        "plan.json",
        "plan.png",
        "manifest.json",
    ] {
        assert!(written.contains(&file), "{file} not rewritten: {written:?}");
    }
    assert!(
        report
            .written
            .iter()
            .any(|p| p.starts_with("frames/street/rgb/")),
        "lamps show in the frames"
    );
    assert!(report.unchanged.contains(&"layout.png".to_owned()));

    let plan_after: serde_json::Value =
        serde_json::from_slice(&fs::read(ws.out().join("day/plan.json")).unwrap()).unwrap();
    let plan_before: serde_json::Value = serde_json::from_slice(&plan_before).unwrap();
    assert_eq!(
        plan_after["buildings"], plan_before["buildings"],
        "buildings must not move"
    );
    assert!(
        plan_after["lamps"].as_array().unwrap().len()
            > plan_before["lamps"].as_array().unwrap().len(),
        "closer spacing gives more lamps"
    );
}

#[test]
fn changing_buildings_leaves_lamps_and_layout_cached() {
    let ws = Workspace::with_spec("day");
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    ws.set("day", "buildings.gap", 4);
    let report = driver::build(&ws.spec("day"), &ws.options()).unwrap();
    use StageStatus::{Cached, Ran};
    assert_eq!(
        statuses(&report),
        [
            ("dataset", Ran),
            ("export", Ran),
            ("facades", Cached),
            ("frames", Ran),
            ("frames", Ran),
            ("frames-plan", Ran),
            ("frames-plan", Ran),
            ("lamps", Cached),
            ("mirror", Cached),
            ("overview", Ran),
            ("parse", Cached),
            ("place", Ran),
            ("plan", Ran),
            ("preview", Ran),
            ("scene", Ran)
        ]
    );
}

#[test]
fn damaged_cache_objects_are_detected_and_rebuilt() {
    let ws = Workspace::with_spec("day");
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let good = tree(&ws.out());
    // Flip one byte in every cached object, and drop the outputs.
    for (rel, mut bytes) in tree(&ws.cache().join("objects")) {
        match bytes.first_mut() {
            Some(first) => *first ^= 0xff,
            None => bytes.push(b'!'),
        }
        fs::write(ws.cache().join("objects").join(rel), bytes).unwrap();
    }
    fs::remove_dir_all(ws.out()).unwrap();
    let report = driver::build(&ws.spec("day"), &ws.options()).unwrap();
    assert_eq!(report.ran().count(), 16, "no damaged object may be used");
    // Every cached stage found its entry damaged (the scene is never cached).
    assert!(
        report
            .stages
            .iter()
            .filter(|s| s.stage != "scene")
            .all(|s| s.repaired.is_some())
    );
    assert_eq!(tree(&ws.out()), good);
    // The repaired cache now serves a no-op build.
    assert!(
        driver::build(&ws.spec("day"), &ws.options())
            .unwrap()
            .up_to_date()
    );
}

#[test]
fn tampered_artifact_is_restored_and_stale_temporaries_swept() {
    let ws = Workspace::with_spec("day");
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let good = tree(&ws.out());
    fs::write(ws.out().join("day/plan.json"), b"{}").unwrap();
    fs::write(
        ws.out().join("day/.plan.png.cityspec-tmp-999-0"),
        b"half a png",
    )
    .unwrap();
    let report = driver::build(&ws.spec("day"), &ws.options()).unwrap();
    assert_eq!(report.ran().count(), 0);
    assert_eq!(report.written, ["plan.json"]);
    assert_eq!(tree(&ws.out()), good);
}

#[test]
fn manifest_lists_every_artifact_with_its_hash() {
    let ws = Workspace::with_spec("day");
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let files = tree(&ws.out().join("day"));
    let manifest = driver::Manifest::from_bytes(&files["manifest.json"]).unwrap();
    assert_eq!(manifest.name, "day");
    assert_eq!(manifest.artifacts.len(), files.len() - 1);
    for artifact in &manifest.artifacts {
        let bytes = &files[&artifact.path];
        assert_eq!(
            artifact.sha256,
            cityspec::hash::sha256_hex(bytes),
            "{}",
            artifact.path
        );
        assert_eq!(artifact.bytes, bytes.len() as u64);
        assert_eq!(artifact.key.len(), 64);
    }
    let stages: Vec<_> = manifest
        .artifacts
        .iter()
        .filter(|a| !a.path.starts_with("textures/") && !a.path.starts_with("frames/"))
        .filter(|a| !dataset_frame_file(&a.path))
        .map(|a| (a.path.as_str(), a.stage.as_str()))
        .collect();
    assert_eq!(
        stages,
        [
            ("city.glb", "export"),
            ("city.mtl", "export"),
            ("city.obj", "export"),
            (
                "cityscapes/gtFine/cityscapes_panoptic_train.json",
                "dataset"
            ),
            ("cityscapes/gtFine/cityscapes_panoptic_val.json", "dataset"),
            ("cityscapes/labels.json", "dataset"),
            ("coco/train.json", "dataset"),
            ("coco/val.json", "dataset"),
            ("layout.png", "mirror"),
            ("overview.png", "overview"),
            ("plan.json", "plan"),
            ("plan.png", "preview"),
            ("yolo/data.yaml", "dataset"),
            ("yolo/dataset.yaml", "dataset")
        ]
    );
    assert!(
        manifest
            .artifacts
            .iter()
            .filter(|a| a.path.starts_with("textures/"))
            .all(|a| a.stage == "export")
    );
}

#[test]
fn drawn_layout_builds_and_moving_the_image_changes_nothing() {
    let ws = Workspace::with_spec("drawn");
    let report = driver::build(&ws.spec("drawn"), &ws.options()).unwrap();
    assert_eq!(report.ran().count(), 11);
    let plan: serde_json::Value =
        serde_json::from_slice(&fs::read(ws.out().join("drawn/plan.json")).unwrap()).unwrap();
    assert_eq!(
        plan["roads"].as_array().unwrap().len(),
        4,
        "{:#}",
        plan["roads"]
    );
    assert!(!plan["buildings"].as_array().unwrap().is_empty());
    // The key holds the image's hash, not its path: a moved image is still cached.
    fs::rename(
        ws.path().join("assets/layouts/drawn.png"),
        ws.path().join("specs/drawn.png"),
    )
    .unwrap();
    ws.set("drawn", "layout.image", "drawn.png");
    assert!(
        driver::build(&ws.spec("drawn"), &ws.options())
            .unwrap()
            .up_to_date()
    );
}

#[test]
fn cmp_facade_folder_builds_and_bad_facade_data_warns_or_fails_as_the_spec_says() {
    let ws = Workspace::with_spec("cmp");
    let report = driver::build(&ws.spec("cmp"), &ws.options()).unwrap();
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    let obj = String::from_utf8(fs::read(ws.out().join("cmp/city.obj")).unwrap()).unwrap();
    assert!(
        obj.contains("usemtl facade_street_04"),
        "the folder's facades clad the city"
    );

    // Break one facade's boxes: with on_error = "skip" it is left out with a warning…
    let xml = ws.path().join("assets/facades/sample/street_04.xml");
    fs::write(&xml, "<object><points><x>oops</x></points>").unwrap();
    let report = driver::build(&ws.spec("cmp"), &ws.options()).unwrap();
    assert_eq!(report.warnings.len(), 1, "{:?}", report.warnings);
    assert_eq!(report.warnings[0].code, "facade-skipped");
    assert!(
        report.warnings[0].message.contains("street_04.xml"),
        "{}",
        report.warnings[0]
    );
    let obj = String::from_utf8(fs::read(ws.out().join("cmp/city.obj")).unwrap()).unwrap();
    assert!(!obj.contains("facade_street_04"));

    // The warning is part of the stages' results: a warm build (the no-op fast path, then
    // a full build from the cache) says it again, and `--strict` fails on it whatever the
    // cache holds.
    let warm = driver::build(&ws.spec("cmp"), &ws.options()).unwrap();
    assert!(warm.up_to_date());
    assert_eq!(warm.warnings, report.warnings);
    fs::remove_dir_all(ws.out()).unwrap();
    let from_cache = driver::build(&ws.spec("cmp"), &ws.options()).unwrap();
    assert_eq!(
        from_cache.ran().count(),
        0,
        "every stage came from the cache"
    );
    assert_eq!(from_cache.warnings, report.warnings);
    let strict = driver::BuildOptions {
        strict: true,
        ..ws.options()
    };
    let err = driver::build(&ws.spec("cmp"), &strict).unwrap_err();
    assert!(matches!(err, driver::BuildError::Strict { .. }), "{err}");
    assert!(err.to_string().contains("street_04.xml"), "{err}");

    // …and with on_error = "error" the build stops, naming the file, as bad input.
    ws.set("cmp", "facades.on_error", "error");
    let err = driver::build(&ws.spec("cmp"), &ws.options()).unwrap_err();
    assert!(matches!(err, driver::BuildError::Facades { .. }), "{err}");
    assert!(err.to_string().contains("street_04.xml"), "{err}");
}

#[test]
fn noop_fast_path_reads_no_object_and_falls_back_when_a_file_changes() {
    let ws = Workspace::with_spec("day");
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let good = tree(&ws.out());
    let manifest = driver::Manifest::from_bytes(&good["day/manifest.json"]).unwrap();
    let plan = manifest
        .artifacts
        .iter()
        .find(|a| a.path == "plan.json")
        .unwrap();
    let object = ws
        .cache()
        .join("objects")
        .join(&plan.sha256[..2])
        .join(&plan.sha256);
    fs::write(&object, b"damaged").unwrap();
    // The output folder is as recorded: nothing is read, so the damage is not even seen.
    let report = driver::build(&ws.spec("day"), &ws.options()).unwrap();
    assert!(report.up_to_date());
    assert!(report.stages.iter().all(|s| s.repaired.is_none()));
    // A changed output file (same size, new bytes) takes the full path, which re-verifies
    // every object it reads, rebuilds the damaged one and restores the file.
    let png = ws.out().join("day/plan.png");
    let mut bytes = fs::read(&png).unwrap();
    let last = bytes.len() - 1;
    bytes[last] ^= 1;
    std::thread::sleep(std::time::Duration::from_millis(20));
    fs::write(&png, &bytes).unwrap();
    let report = driver::build(&ws.spec("day"), &ws.options()).unwrap();
    assert!(!report.up_to_date());
    assert_eq!(report.written, ["plan.png"]);
    let plan_run = report.stages.iter().find(|s| s.stage == "plan").unwrap();
    assert!(
        plan_run.repaired.is_some(),
        "the damaged plan object is rebuilt"
    );
    assert_eq!(tree(&ws.out()), good);
}

/// Every COCO annotation of `spec`'s street camera: (bbox, full_bbox, visible_fraction).
fn street_annotations(ws: &Workspace, spec: &str) -> Vec<([f64; 4], [f64; 4], f64)> {
    let path = ws.out().join(spec).join("frames/street/coco.json");
    let doc: serde_json::Value = serde_json::from_slice(&fs::read(path).unwrap()).unwrap();
    let four = |v: &serde_json::Value| -> [f64; 4] {
        std::array::from_fn(|i| v[i].as_f64().expect("a number"))
    };
    // Ignore regions (objects under the thresholds, iscrowd 1) are not annotations; words
    // (no full box: a plate's) are not objects.
    doc["annotations"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|a| a["iscrowd"] == 0 && a.get("full_bbox").is_some())
        .map(|a| {
            (
                four(&a["bbox"]),
                four(&a["full_bbox"]),
                a["visible_fraction"].as_f64().expect("a visible fraction"),
            )
        })
        .collect()
}

#[test]
fn coco_full_boxes_hold_the_visible_ones_and_min_fraction_filters() {
    let ws = Workspace::with_spec("text");
    // Plates keep off windows and hidden walls, so partly hidden ones are rarer: more frames.
    ws.set("text", "cameras[0].frames", 24);
    // Words on walls are seldom hidden (by a sign, a lamp, a corner): a high threshold.
    ws.set("text", "annotations.min_fraction", 0.95);
    driver::build(&ws.spec("text"), &ws.options()).unwrap();
    let kept = street_annotations(&ws, "text");
    assert!(kept.len() > 10, "{} annotations", kept.len());
    for (bbox, full, fraction) in &kept {
        assert!((0.95..=1.0).contains(fraction), "{fraction}");
        assert!(
            full[0] <= bbox[0]
                && full[1] <= bbox[1]
                && bbox[0] + bbox[2] <= full[0] + full[2]
                && bbox[1] + bbox[3] <= full[1] + full[3],
            "{bbox:?} outside {full:?}"
        );
    }
    // Without the fraction threshold, partly hidden words come back.
    ws.set("text", "annotations.min_fraction", 0.0);
    driver::build(&ws.spec("text"), &ws.options()).unwrap();
    let all = street_annotations(&ws, "text");
    let hidden = all.iter().filter(|(_, _, f)| *f < 0.95).count();
    assert!(hidden > 0, "no annotation below 0.95 of {}", all.len());
    assert_eq!(all.len(), kept.len() + hidden);
}

/// Issue 8, case 1: stale-file removal trusted the paths of the old `manifest.json`: an
/// absolute path got that file deleted, and so did a path through a directory symlink.
#[cfg(unix)]
#[test]
fn an_old_manifest_cannot_delete_files_outside_the_output_folder() {
    let ws = Workspace::with_spec("day");
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let day = ws.out().join("day");
    let far = ws.path().join("far");
    fs::create_dir_all(&far).unwrap();
    fs::write(far.join("victim.txt"), b"keep me").unwrap();
    let absolute = ws.path().join("absolute-victim.txt");
    fs::write(&absolute, b"keep me too").unwrap();
    std::os::unix::fs::symlink(&far, day.join("link")).unwrap();
    let manifest_file = day.join("manifest.json");
    let mut manifest = driver::Manifest::from_bytes(&fs::read(&manifest_file).unwrap()).unwrap();
    for path in [
        absolute.to_string_lossy().into_owned(),
        "link/victim.txt".into(),
    ] {
        let mut listed = manifest.artifacts[0].clone();
        listed.path = path;
        manifest.artifacts.push(listed);
    }
    fs::write(&manifest_file, manifest.to_bytes()).unwrap();

    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    assert_eq!(fs::read(&absolute).unwrap(), b"keep me too");
    assert_eq!(fs::read(far.join("victim.txt")).unwrap(), b"keep me");
    assert!(
        fs::symlink_metadata(day.join("link")).is_err(),
        "the link is gone"
    );
    common::assert_matches_manifest(&day);
}

/// Issue 8, case 1 (and 9): a build wrote through directory symlinks inside `out/`.
#[cfg(unix)]
#[test]
fn a_directory_symlink_in_the_output_folder_is_replaced_not_followed() {
    let ws = Workspace::with_spec("day");
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let day = ws.out().join("day");
    let good = tree(&day);
    let far = ws.path().join("far");
    fs::create_dir_all(&far).unwrap();
    fs::rename(day.join("frames"), ws.path().join("frames-moved")).unwrap();
    std::os::unix::fs::symlink(&far, day.join("frames")).unwrap();

    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    assert_eq!(
        fs::read_dir(&far).unwrap().count(),
        0,
        "nothing is written on the far side of the link"
    );
    assert!(fs::symlink_metadata(day.join("frames")).unwrap().is_dir());
    assert_eq!(tree(&day), good);
}

/// Issue 8, case 1: the output folder itself a link, or a folder that is not cityspec's.
#[cfg(unix)]
#[test]
fn a_linked_or_foreign_output_folder_is_refused_and_left_alone() {
    let ws = Workspace::with_spec("day");
    let mine = ws.path().join("mine");
    fs::create_dir_all(&mine).unwrap();
    fs::write(mine.join("notes.txt"), b"mine").unwrap();
    fs::create_dir_all(ws.out()).unwrap();
    std::os::unix::fs::symlink(&mine, ws.out().join("day")).unwrap();
    let err = driver::build(&ws.spec("day"), &ws.options()).unwrap_err();
    assert!(err.to_string().contains("is a symbolic link"), "{err}");
    fs::remove_file(ws.out().join("day")).unwrap();
    fs::rename(&mine, ws.out().join("day")).unwrap();
    let err = driver::build(&ws.spec("day"), &ws.options()).unwrap_err();
    assert!(
        err.to_string()
            .contains("not the output folder of spec \"day\""),
        "{err}"
    );
    assert_eq!(
        tree(&ws.out().join("day")).into_keys().collect::<Vec<_>>(),
        ["notes.txt"]
    );
}

/// Issue 8, case 2: a cache entry whose output name is an absolute path wrote that file.
#[test]
fn a_cache_entry_naming_a_path_outside_is_corrupt_and_rebuilt() {
    let ws = Workspace::with_spec("day");
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let good = tree(&ws.out());
    let files = tree(&ws.out().join("day"));
    let manifest = driver::Manifest::from_bytes(&files["manifest.json"]).unwrap();
    let plan = manifest
        .artifacts
        .iter()
        .find(|a| a.path == "plan.json")
        .unwrap();
    let entry_file = ws
        .cache()
        .join("entries")
        .join(format!("{}.json", plan.key));
    let mut entry: serde_json::Value =
        serde_json::from_slice(&fs::read(&entry_file).unwrap()).unwrap();
    let evil = ws.path().join("evil.json");
    let object = entry["outputs"]["plan.json"].clone();
    entry["outputs"] = serde_json::json!({ evil.to_string_lossy(): object });
    fs::write(&entry_file, serde_json::to_vec(&entry).unwrap()).unwrap();
    fs::remove_dir_all(ws.out()).unwrap();

    let report = driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let run = report.stages.iter().find(|s| s.stage == "plan").unwrap();
    assert_eq!(run.status, StageStatus::Ran);
    let why = run.repaired.as_deref().unwrap_or_default();
    assert!(
        why.contains("not a file this stage writes") && why.contains("evil.json"),
        "{why}"
    );
    assert!(
        !evil.exists(),
        "nothing is written outside the output folder"
    );
    assert_eq!(tree(&ws.out()), good);
    // The rebuilt entry is whole again.
    assert!(
        driver::build(&ws.spec("day"), &ws.options())
            .unwrap()
            .up_to_date()
    );
}

/// Issue 8, case 6: the no-op fast path returned before temporaries were swept, and
/// orphans of a killed build survived.
#[test]
fn no_temporary_or_orphan_survives_the_next_build_even_a_no_op() {
    let ws = Workspace::with_spec("day");
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let good = tree(&ws.out());
    let day = ws.out().join("day");
    fs::write(day.join(".plan.png.cityspec-tmp-999-0"), b"").unwrap();
    fs::write(day.join("frames/street/rgb/999999.png"), b"orphan").unwrap();
    let staged = ws.out().join(".day~cityspec-stage-999-0");
    fs::create_dir_all(staged.join("frames")).unwrap();
    fs::write(staged.join("plan.png"), b"half").unwrap();
    let report = driver::build(&ws.spec("day"), &ws.options()).unwrap();
    assert_eq!(report.ran().count(), 0);
    assert!(report.written.is_empty(), "{:?}", report.written);
    assert_eq!(
        report.removed,
        [
            ".plan.png.cityspec-tmp-999-0",
            "frames/street/rgb/999999.png"
        ]
    );
    assert_eq!(tree(&ws.out()), good);

    // A staging folder left beside an up-to-date folder: the fast path removes it too.
    fs::create_dir_all(&staged).unwrap();
    fs::write(staged.join("plan.png"), b"half").unwrap();
    let report = driver::build(&ws.spec("day"), &ws.options()).unwrap();
    assert!(report.up_to_date());
    assert_eq!(tree(&ws.out()), good);
}

/// The `poses.json` of camera `name` in the text city.
fn poses(ws: &Workspace, name: &str) -> serde_json::Value {
    let path = ws.out().join(format!("text/frames/{name}/poses.json"));
    serde_json::from_slice(&fs::read(path).unwrap()).unwrap()
}

#[test]
fn ranged_and_aimed_cameras_give_the_same_bytes_at_any_thread_count_and_per_camera() {
    let ws = Workspace::with_spec("text");
    ws.edit_spec("text", |spec| {
        // The street camera's ranges, narrowed and widened; one frame fewer of the words.
        spec.set("cameras[0].height", [1.4, 2.0])
            .set("cameras[0].heading", [-60, 60])
            .set("cameras[0].roll", [-5, 5])
            .set("cameras[1].frames", 3);
    });
    in_pool(1, || driver::build(&ws.spec("text"), &ws.options())).unwrap();
    let first = tree(&ws.out());
    let other = Workspace::with_spec("text");
    fs::copy(ws.spec("text"), other.spec("text")).unwrap();
    in_pool(8, || driver::build(&other.spec("text"), &other.options())).unwrap();
    assert_eq!(tree(&other.out()), first);

    let street = poses(&ws, "street");
    let frames = street["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 4);
    for f in frames {
        let heading = f["angles"]["heading"].as_f64().unwrap();
        let height = f["angles"]["height"].as_f64().unwrap();
        assert!((-60.0..=60.0).contains(&heading), "{f}");
        assert_eq!(f["eye"][1].as_f64().unwrap(), height);
    }
    // The aimed frames found viewpoints whose text shows: a frame whose 12 candidates all
    // hide their text is dropped (98 of `text.toml`'s 100 words frames find one), never
    // filled with a view of nothing.
    let words = poses(&ws, "words");
    let found = words["frames"].as_array().unwrap().len();
    assert!((2..=3).contains(&found), "{found} of 3 aimed frames");

    // A camera added in front of the others leaves their poses as they were.
    ws.edit_spec("text", |spec| {
        spec.expect("cameras[0].name", "street").insert_table(
            "cameras",
            0,
            "name = \"extra\"\nframes = 2\nheading = [-90, 90]",
        );
    });
    driver::build(&ws.spec("text"), &ws.options()).unwrap();
    assert_eq!(poses(&ws, "street"), street);
    assert_eq!(poses(&ws, "words"), words);
}

#[test]
fn path_render_input_renders_the_ids_and_depth_a_build_writes() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("small.toml");
    fs::write(&spec, include_str!("../fixtures/shards.toml")).unwrap();
    let cache = dir.path().join("cache");
    let options = common::quiet_options(dir.path().join("out"), cache.clone());
    let out = driver::build(&spec, &options).unwrap().out_dir;
    // From the cache the build filled: the same scene, poses and intrinsics.
    let input = driver::path_render_input(&spec, "street", &cache)
        .unwrap()
        .expect("the fixture has a street camera");
    assert_eq!(input.poses.len(), 43);
    for i in [0, 21, 42] {
        let frame = cityspec::render::render(
            &input.scene,
            &input.poses[i],
            &input.intrinsics,
            &input.lighting,
            input.supersample,
        );
        let pngs = frame.encode(&frame.rgb(), input.depth);
        let written = |kind: &str| fs::read(out.join(format!("frames/street/{kind}/{i:06}.png")));
        assert!(
            pngs.instance == written("ids").unwrap(),
            "frame {i}: ids differ"
        );
        assert!(
            pngs.depth == written("depth").unwrap(),
            "frame {i}: depth differs"
        );
    }
    assert!(
        driver::path_render_input(&spec, "nowhere", &cache)
            .unwrap()
            .is_none()
    );
}
