//! The `cityspec` binary as a user meets it: exit codes, messages, help, killed builds.

use crate::common;

use std::fs;
use std::process::{Command, Stdio};
use std::time::Duration;

use common::{Workspace, cityspec, stderr, tree};

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
    // Issue 9: no rate measured over a single frame ("1000000000.0 frames/s").
    assert!(
        stderr(&out).contains("rendered day/street: 4 frames"),
        "{}",
        stderr(&out)
    );
    assert!(
        !stderr(&out).contains("00000000.0 frames/s"),
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
    // Issue 9: -v names each camera's stage and counts files per folder; -vv lists them.
    assert!(
        text.contains("cached frames street") && text.contains("cached frames aerial"),
        "{text}"
    );
    fs::remove_file(ws.path().join("out/day/plan.png")).unwrap();
    fs::remove_dir_all(ws.path().join("out/day/frames/street/rgb")).unwrap();
    let v = stderr(&cityspec(&ws, &["build", "-v", "specs/day.toml"]));
    assert!(
        v.contains("wrote 4 files in out/day/frames/street/rgb"),
        "{v}"
    );
    assert!(v.contains("wrote 1 file in out/day/\n"), "{v}");
    assert!(v.contains("; 5 files written"), "{v}");
    fs::remove_file(ws.path().join("out/day/plan.png")).unwrap();
    let vv = stderr(&cityspec(&ws, &["build", "-vv", "specs/day.toml"]));
    assert!(vv.contains("wrote out/day/plan.png"), "{vv}");
    assert!(vv.contains("; 1 file written"), "{vv}");
    // -v is not offered where it prints nothing more.
    for args in [&["validate", "-v", "specs/day.toml"][..], &["schema", "-v"]] {
        assert_eq!(cityspec(&ws, args).status.code(), Some(2), "{args:?}");
    }
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
    ws.set("day", "layout.generate.road_width", 3200);
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
fn validate_accepts_the_examples_and_schema_prints_the_committed_schema() {
    let ws = Workspace::with_spec("day");
    let out = cityspec(&ws, &["validate", "specs/day.toml", "specs/mirrored.toml"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    // The Table 3 benchmark's specs (benches/downstream/) stay valid as the spec grows.
    let downstream = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/downstream");
    for name in ["day", "night", "day_test", "night_test"] {
        let spec = format!("{downstream}/{name}.toml");
        let out = cityspec(&ws, &["validate", &spec]);
        assert_eq!(out.status.code(), Some(0), "{spec}: {}", stderr(&out));
    }
    let schema = cityspec(&ws, &["schema"]);
    assert!(schema.status.success());
    let committed = fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/schemas/cityspec.schema.json"
    ))
    .unwrap();
    assert_eq!(String::from_utf8(schema.stdout).unwrap(), committed);
}

/// A reader that has gone (`cityspec schema | head -1`) is not a crash: the command
/// exits 0 without a panic message, for every command that prints to stdout.
#[test]
fn a_closed_stdout_is_not_a_panic() {
    let ws = Workspace::with_spec("day");
    for args in [
        &["schema"][..],
        &["explain", "--json", "specs/day.toml"],
        &["explain", "specs/day.toml"],
    ] {
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let out = Command::new(env!("CARGO_BIN_EXE_cityspec"))
            .current_dir(ws.path())
            .args(args)
            .stdout(writer)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(out.status.success(), "{args:?}: {:?}: {err}", out.status);
    }
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
        // The first build's folder appears whole or not at all.
        let out = ws.path().join("out/mirrored");
        if out.exists() {
            assert!(
                tree(&out) == whole,
                "the folder is partial after a kill at {delay_ms} ms"
            );
        }
        // Cache entries only ever point at whole objects: whatever was recorded verifies.
        let cache = cityspec::driver::Cache::new(ws.path().join(".cityspec-cache"));
        if let Ok(entries) = fs::read_dir(ws.path().join(".cityspec-cache/entries")) {
            for entry in entries {
                let name = entry.unwrap().file_name().to_string_lossy().into_owned();
                if let Some(key) = name.strip_suffix(".json") {
                    assert!(
                        cache.get(key, cityspec::driver::Load::References).is_ok(),
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
    assert_eq!(leftovers(&ws.path().join("out")), Vec::<String>::new());
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

/// Hidden entries beside the output folders (staging or old folders) besides lock files.
fn leftovers(out_root: &std::path::Path) -> Vec<String> {
    fs::read_dir(out_root)
        .map(|d| {
            d.map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .filter(|n| n.starts_with('.') && !n.ends_with("~cityspec-lock"))
                .collect()
        })
        .unwrap_or_default()
}

/// Issue 8, case 6 (case 4 of the brief): a build killed over an earlier one left files
/// that disagree with `manifest.json`. Here the sync aborts the process right after its
/// N-th change to the file system, for every N, so each kill lands mid-write for sure.
#[test]
fn a_build_killed_after_any_write_leaves_the_old_folder_or_the_new() {
    let ws = Workspace::with_spec("day");
    // Each of the kills copies, rebuilds and compares whole output folders, and every file
    // is one more kill: day.toml with every kind of file, but fewer of each.
    ws.shrink_day();
    let text = fs::read_to_string(ws.spec("day")).unwrap();
    fs::write(
        ws.path().join("specs/day-b.toml"),
        common::set(&text, "seed", 8),
    )
    .unwrap();
    let build = |spec: &str, out: &str, abort_after: Option<u64>| {
        let mut command = Command::new(env!("CARGO_BIN_EXE_cityspec"));
        command
            .current_dir(ws.path())
            .args(["build", "-q", "--out", out, spec]);
        if let Some(n) = abort_after {
            command.env("CITYSPEC_TEST_ABORT_AFTER_WRITES", n.to_string());
        }
        command.output().unwrap()
    };
    assert!(build("specs/day.toml", "old", None).status.success());
    assert!(build("specs/day-b.toml", "new", None).status.success());
    let old = tree(&ws.path().join("old/day"));
    let new = tree(&ws.path().join("new/day"));
    assert_ne!(old, new);
    let out = ws.path().join("out");
    let mut kills = 0;
    for n in 1u64.. {
        // Over an earlier build (every n), and as the first build (the first few n).
        for first in [false, true] {
            if first && n > 3 {
                continue;
            }
            let _ = fs::remove_dir_all(&out);
            if !first {
                common::copy_tree(&ws.path().join("old/day"), &out.join("day"));
            }
            let run = build("specs/day-b.toml", "out", Some(n));
            if run.status.success() {
                assert!(n > 3, "the sync makes more than 3 changes");
                assert_eq!(tree(&out.join("day")), new);
                assert_eq!(leftovers(&out), Vec::<String>::new());
                eprintln!("{kills} kills survived, after 1..{n} writes");
                assert!(kills > 20, "the sync wrote only {n} times");
                return;
            }
            assert_eq!(run.status.code(), None, "{}", stderr(&run));
            kills += 1;
            let now = if out.join("day").exists() {
                tree(&out.join("day"))
            } else {
                Default::default()
            };
            let before = if first { &Default::default() } else { &old };
            assert!(
                &now == before || now == new,
                "after {n} writes the folder is a mix: {} files, {} of the old, {} of the new",
                now.len(),
                now.iter().filter(|(k, v)| old.get(*k) == Some(v)).count(),
                now.iter().filter(|(k, v)| new.get(*k) == Some(v)).count()
            );
            // The next build completes and leaves nothing behind.
            assert!(build("specs/day-b.toml", "out", None).status.success());
            assert_eq!(tree(&out.join("day")), new, "after a kill at write {n}");
            assert_eq!(leftovers(&out), Vec::<String>::new());
        }
    }
}

/// Issue 8, case 7: concurrent builds into one output folder with a cold cache failed
/// ("cannot write out/day20/city.glb") in 11 of 13 rounds. Now they take turns.
#[test]
fn concurrent_builds_of_one_output_folder_take_turns() {
    let ws = Workspace::with_spec("day");
    // Thirteen cold builds: a small city.
    ws.shrink_day();
    let reference = cityspec(
        &ws,
        &[
            "build",
            "-q",
            "--out",
            "ref",
            "--cache",
            "ref-cache",
            "specs/day.toml",
        ],
    );
    assert!(reference.status.success());
    let whole = tree(&ws.path().join("ref/day"));
    let mut waited = 0;
    const ROUNDS: usize = 4;
    for round in 0..ROUNDS {
        let _ = fs::remove_dir_all(ws.path().join("out"));
        let _ = fs::remove_dir_all(ws.path().join(".cityspec-cache"));
        let children: Vec<_> = (0..3)
            .map(|_| {
                Command::new(env!("CARGO_BIN_EXE_cityspec"))
                    .current_dir(ws.path())
                    .args(["build", "-q", "-j1", "specs/day.toml"])
                    .stderr(Stdio::piped())
                    .spawn()
                    .unwrap()
            })
            .collect();
        for child in children {
            let out = child.wait_with_output().unwrap();
            let text = stderr(&out);
            assert!(out.status.success(), "round {round}: {text}");
            if text.contains("waiting for another cityspec build of out/day") {
                waited += 1;
            }
        }
        assert_eq!(tree(&ws.path().join("out/day")), whole, "round {round}");
        assert_eq!(leftovers(&ws.path().join("out")), Vec::<String>::new());
    }
    eprintln!("{ROUNDS} concurrent rounds of 3 builds, {waited} builds waited");
    assert!(waited > 0, "some build must have waited for another");
}

/// Issue 8: a cache shared by concurrent builds (into separate folders) stays whole, and
/// `verify --all` finds every cached stage rebuilding to its cached bytes.
#[test]
fn a_shared_cache_stays_whole_under_concurrent_builds() {
    let ws = Workspace::with_spec("day");
    ws.shrink_day();
    let children: Vec<_> = ["a", "b", "c"]
        .iter()
        .map(|out| {
            Command::new(env!("CARGO_BIN_EXE_cityspec"))
                .current_dir(ws.path())
                .args(["build", "-q", "-j1", "--out", out, "specs/day.toml"])
                .stderr(Stdio::piped())
                .spawn()
                .unwrap()
        })
        .collect();
    for child in children {
        let out = child.wait_with_output().unwrap();
        assert!(out.status.success(), "{}", stderr(&out));
    }
    let a = tree(&ws.path().join("a/day"));
    assert_eq!(tree(&ws.path().join("b/day")), a);
    assert_eq!(tree(&ws.path().join("c/day")), a);
    let verify = cityspec(&ws, &["verify", "--all", "specs/day.toml"]);
    assert_eq!(verify.status.code(), Some(0), "{}", stderr(&verify));
    assert!(
        stderr(&verify).contains("rechecked 13 of 13 cached stages: all rebuild"),
        "{}",
        stderr(&verify)
    );
}

/// Issue 8, case 2: an entry naming another stage's valid object went unnoticed, and
/// later builds said "up to date". `cityspec verify` reruns the stage and names it.
#[test]
fn verify_names_a_poisoned_entry() {
    let ws = Workspace::with_spec("day");
    assert!(
        cityspec(&ws, &["build", "-q", "specs/day.toml"])
            .status
            .success()
    );
    let sample = cityspec(
        &ws,
        &["verify", "--sample", "2", "--seed", "7", "specs/day.toml"],
    );
    assert_eq!(sample.status.code(), Some(0), "{}", stderr(&sample));
    assert!(
        stderr(&sample).contains("rechecked 2 of 13 cached stages (a sample, --seed 7)"),
        "{}",
        stderr(&sample)
    );

    let manifest = cityspec::driver::Manifest::from_bytes(
        &fs::read(ws.path().join("out/day/manifest.json")).unwrap(),
    )
    .unwrap();
    let find = |path: &str| manifest.artifacts.iter().find(|a| a.path == path).unwrap();
    let (plan_png, layout_png) = (find("plan.png"), find("layout.png"));
    let entry_file = ws
        .path()
        .join(".cityspec-cache/entries")
        .join(format!("{}.json", plan_png.key));
    let mut entry: serde_json::Value =
        serde_json::from_slice(&fs::read(&entry_file).unwrap()).unwrap();
    entry["outputs"]["plan.png"] =
        serde_json::json!({ "sha256": layout_png.sha256, "bytes": layout_png.bytes });
    fs::write(&entry_file, serde_json::to_vec(&entry).unwrap()).unwrap();

    let check = cityspec(&ws, &["verify", "--all", "specs/day.toml"]);
    let text = stderr(&check);
    assert_eq!(check.status.code(), Some(1), "{text}");
    assert!(
        text.contains("error: day: stage preview (cache entry")
            && text.contains(&format!(
                "plan.png is cached as {}",
                &layout_png.sha256[..12]
            ))
            && text.contains("rechecked 13 of 13 cached stages: 1 differ"),
        "{text}"
    );
}

#[test]
fn word_files_feed_the_text_and_bad_ones_exit_2() {
    let ws = Workspace::with_spec("text");
    ws.edit_spec("text", |spec| {
        spec.set("objects[0].case", "upper")
            .insert("objects[0].words_file", "shops.txt");
    });
    let words = ws.path().join("specs/shops.txt");
    let bad: [(Option<&[u8]>, &str); 3] = [
        (None, "objects[0].words_file"),
        (Some(b"# only a comment\n"), "holds no words"),
        (Some(&[0xff, 0xfe, b'a']), "not UTF-8"),
    ];
    for (bytes, message) in bad {
        if let Some(bytes) = bytes {
            fs::write(&words, bytes).unwrap();
        }
        let out = cityspec(&ws, &["build", "specs/text.toml"]);
        assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
        assert!(stderr(&out).contains(message), "{}", stderr(&out));
    }
    fs::write(&words, "# shop names\nbakery café\n").unwrap();
    let out = cityspec(&ws, &["build", "specs/text.toml"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let coco: serde_json::Value = serde_json::from_slice(
        &fs::read(ws.path().join("out/text/frames/street/coco.json")).unwrap(),
    )
    .unwrap();
    // The wall text reads the file; the street-name entry keeps the built-in list.
    let texts: Vec<&str> = coco["annotations"]
        .as_array()
        .unwrap()
        .iter()
        // Plates (words carry `word_index`), but for the street names and number plates,
        // which keep their own words.
        .filter(|a| {
            let style = &a["attributes"]["text_style"];
            a.get("word_index").is_none() && style != "street" && style != "plate"
        })
        .map(|a| a["text"].as_str().unwrap())
        .collect();
    assert!(!texts.is_empty());
    for word in texts.iter().flat_map(|t| t.split(' ')) {
        assert!(["BAKERY", "CAFÉ"].contains(&word), "{word}");
    }
}

#[test]
fn objects_placed_short_of_count_warn_and_fail_under_strict() {
    let ws = Workspace::with_spec("day");
    // A small city holds about 3,900 plates of 5,000 asked for (a default-sized one about
    // 9,200, and placing 100,000 tries took 22 s in this test).
    let spec = "version = 1\nname = \"crowded\"\nseed = 3\n\n[layout.generate]\n\
                width = 384\nheight = 384\nhorizontal_roads = 2\nvertical_roads = 2\n\n\
                [[objects]]\nkind = \"text\"\nlabel = \"text\"\ncount = 5000\n";
    fs::write(ws.path().join("specs/crowded.toml"), spec).unwrap();
    let strict = cityspec(&ws, &["build", "--strict", "specs/crowded.toml"]);
    let text = stderr(&strict);
    assert_eq!(strict.status.code(), Some(2), "{text}");
    assert!(text.contains("--strict"), "{text}");
    assert!(
        text.contains("objects[0] (text, label \"text\"): placed "),
        "{text}"
    );
    assert!(text.contains(" of 5,000"), "{text}");
    assert!(!ws.path().join("out/crowded").exists(), "{text}");

    let plain = cityspec(&ws, &["build", "specs/crowded.toml"]);
    let text = stderr(&plain);
    assert_eq!(plain.status.code(), Some(0), "{text}");
    // At the entry's `count` in the spec, with the warning's code.
    assert!(
        text.contains("specs/crowded.toml:14:1: warning[objects-short]: objects[0]"),
        "{text}"
    );
    assert!(text.contains(" of 5,000"), "{text}");
    assert!(ws.path().join("out/crowded/manifest.json").is_file());

    // An entry that fits places all it asks for: no warning, and --strict builds.
    ws.edit_spec("crowded", |spec| {
        spec.set("objects[0].kind", "sign")
            .set("objects[0].label", "traffic_sign")
            .set("objects[0].count", 2);
    });
    let fits = cityspec(&ws, &["build", "--strict", "specs/crowded.toml"]);
    let text = stderr(&fits);
    assert_eq!(fits.status.code(), Some(0), "{text}");
    assert!(!text.contains("warning"), "{text}");
}

/// Issue 8 leftover: `validate` read a facade folder's photos only as far as `build` did
/// not, so a truncated photo passed `validate` and then failed (or was skipped by) `build`.
#[test]
fn validate_refuses_a_truncated_facade_photo_as_build_does() {
    let ws = Workspace::with_spec("cmp");
    let photo = ws.path().join("assets/facades/sample/street_04.jpg");
    let bytes = fs::read(&photo).unwrap();
    fs::write(&photo, &bytes[..bytes.len() / 2]).unwrap();
    // on_error = "skip": valid, with the warning the build would print.
    let out = cityspec(&ws, &["validate", "specs/cmp.toml"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("warning") && stderr(&out).contains("street_04.jpg"),
        "{}",
        stderr(&out)
    );
    // on_error = "error": refused, naming the photo, with exit code 2.
    ws.set("cmp", "facades.on_error", "error");
    let out = cityspec(&ws, &["validate", "specs/cmp.toml"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("street_04.jpg"), "{}", stderr(&out));
    let build = cityspec(&ws, &["build", "specs/cmp.toml"]);
    assert_eq!(build.status.code(), Some(2), "{}", stderr(&build));
}
