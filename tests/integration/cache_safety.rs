//! Nothing lost, nothing hidden: `cache gc` removes only the cache's own files, damage in
//! the cache is a miss (never a panic or a hang), the output folder's lock cannot be
//! planted, and warnings survive the cache.

use crate::common;

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::mpsc;
use std::time::Duration;

use cityspec::driver::{self, BuildError, GcOptions};
use common::{Workspace, cityspec, stderr};

/// A workspace with `specs/small.toml`: the shards fixture, edited through its parsed
/// value by `edit` (so an edit that names a missing key fails here, not silently).
fn small(edit: impl FnOnce(&mut toml::Table)) -> (Workspace, PathBuf) {
    let ws = Workspace::with_spec("day");
    let mut spec: toml::Table = include_str!("../fixtures/shards.toml").parse().unwrap();
    // Fewer frames: these tests are about files, not pictures.
    for camera in spec["cameras"].as_array_mut().unwrap() {
        camera.as_table_mut().unwrap()["frames"] = toml::Value::Integer(3);
    }
    edit(&mut spec);
    let path = ws.path().join("specs/small.toml");
    fs::write(&path, toml::to_string(&spec).unwrap()).unwrap();
    (ws, path)
}

fn gc_all(cache: &Path) -> Result<driver::GcReport, Vec<BuildError>> {
    driver::gc(
        &[],
        &GcOptions {
            cache_dir: cache.to_path_buf(),
            max_size: None,
            max_age: None,
            grace: Duration::ZERO,
        },
    )
}

/// Every file below `dir` with its bytes (symlinks as their target), for before/after.
fn snapshot(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(folder) = stack.pop() {
        for entry in fs::read_dir(&folder).unwrap() {
            let path = entry.unwrap().path();
            let meta = fs::symlink_metadata(&path).unwrap();
            if meta.is_dir() {
                stack.push(path);
            } else if meta.is_symlink() {
                let target = fs::read_link(&path).unwrap();
                out.push((path, target.to_string_lossy().as_bytes().to_vec()));
            } else {
                out.push((path.clone(), fs::read(&path).unwrap()));
            }
        }
    }
    out.sort();
    out
}

#[test]
fn gc_refuses_a_git_repository_and_deletes_nothing() {
    let ws = Workspace::with_spec("day");
    let repo = ws.path().join("repo");
    fs::create_dir_all(&repo).unwrap();
    let git = |args: &[&str]| {
        let out = Command::new("git")
            .current_dir(&repo)
            .args(["-c", "user.name=t", "-c", "user.email=t@example.com"])
            .args(args)
            .output()
            .expect("git runs");
        assert!(out.status.success(), "git {args:?}: {}", stderr(&out));
    };
    git(&["init", "-q"]);
    fs::write(repo.join("a.txt"), "a").unwrap();
    git(&["add", "a.txt"]);
    git(&["commit", "-q", "-m", "one"]);
    let before = snapshot(&repo.join(".git"));
    let out = cityspec(
        &ws,
        &["cache", "gc", "--cache", "repo/.git", "specs/day.toml"],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let message = stderr(&out);
    assert!(message.contains("not a cityspec cache"), "{message}");
    assert!(message.contains("CACHEDIR.TAG"), "{message}");
    assert_eq!(snapshot(&repo.join(".git")), before, "gc touched .git");
    git(&["cat-file", "-t", "HEAD"]);
}

#[test]
fn gc_removes_only_names_the_cache_writes_and_follows_no_symlink() {
    let (ws, spec) = small(|_| {});
    driver::build(&spec, &ws.options()).unwrap();
    let cache = ws.cache();
    assert!(
        cache.join("CACHEDIR.TAG").is_file(),
        "the first write marks it"
    );
    // A cache an older cityspec made has no marker: gc refuses it until a build, even
    // one with nothing to do, marks it.
    fs::remove_file(cache.join("CACHEDIR.TAG")).unwrap();
    assert!(matches!(
        gc_all(&cache).unwrap_err()[..],
        [BuildError::NotACache { .. }]
    ));
    assert!(driver::build(&spec, &ws.options()).unwrap().up_to_date());
    assert!(
        cache.join("CACHEDIR.TAG").is_file(),
        "a no-op build marks it"
    );
    // Foreign files inside a real cache: a note, git-like objects, odd entries.
    let sha = "3f".repeat(32);
    let foreign = [
        "objects/README-keep.txt".to_owned(),
        format!("objects/3f/{}", &sha[..40]),
        format!("objects/ab/{sha}"),
        "entries/HEAD".to_owned(),
        format!("entries/{sha}.json.bak"),
    ];
    for name in &foreign {
        let path = cache.join(name);
        fs::create_dir_all(path.parent().unwrap()).unwrap();
        fs::write(&path, "not cityspec's").unwrap();
    }
    // A folder elsewhere, holding files with the cache's own names, reached through a
    // symlinked shard: not followed.
    let elsewhere = ws.path().join("elsewhere");
    fs::create_dir_all(&elsewhere).unwrap();
    fs::write(elsewhere.join(format!("ee{}", "e".repeat(62))), "keep").unwrap();
    std::os::unix::fs::symlink(&elsewhere, cache.join("objects/ee")).unwrap();

    let report = gc_all(&cache).unwrap();
    assert!(report.removed_entries > 0 && report.removed_objects > 0);
    for name in &foreign {
        assert!(cache.join(name).exists(), "{name} was removed");
        assert!(
            report.skipped.iter().any(|s| s.starts_with(name.as_str())),
            "{name} not reported: {:?}",
            report.skipped
        );
    }
    assert!(
        report
            .skipped
            .contains(&"objects/ee (a symlink)".to_owned()),
        "{:?}",
        report.skipped
    );
    assert_eq!(fs::read_dir(&elsewhere).unwrap().count(), 1);
    // Nothing of the cache's own is left (every spec was unneeded).
    assert_eq!(fs::read_dir(cache.join("entries")).unwrap().count(), 2);

    // A symlinked `entries/` is reported and not entered.
    let outside = ws.path().join("outside-entries");
    fs::create_dir_all(&outside).unwrap();
    let old_entry = outside.join(format!("{sha}.json"));
    fs::write(&old_entry, "{}").unwrap();
    fs::remove_dir_all(cache.join("entries")).unwrap();
    std::os::unix::fs::symlink(&outside, cache.join("entries")).unwrap();
    let report = gc_all(&cache).unwrap();
    assert!(old_entry.exists(), "gc followed a symlinked entries/");
    assert!(
        report
            .skipped
            .contains(&"entries (a symlink: not followed)".to_owned()),
        "{:?}",
        report.skipped
    );

    // The CLI says what it skipped.
    let out = cityspec(
        &ws,
        &[
            "cache",
            "gc",
            "--cache",
            "cache",
            "--grace-minutes",
            "0",
            "specs/small.toml",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(stderr(&out).contains("skipped"), "{}", stderr(&out));
}

/// Runs `f` on another thread and fails the test when it takes longer than a minute (a
/// FIFO opened for reading would block forever).
fn within_a_minute<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = send.send(f());
    });
    receive
        .recv_timeout(Duration::from_secs(60))
        .expect("hung on a FIFO in the cache")
}

#[test]
fn damaged_entries_are_misses_never_panics_or_hangs() {
    let (ws, spec) = small(|_| {});
    let first = driver::build(&spec, &ws.options()).unwrap();
    let entries = ws.cache().join("entries");
    let mirror = first.stages.iter().find(|s| s.stage == "mirror").unwrap();
    let entry = entries.join(format!("{}.json", mirror.key));
    let text = fs::read_to_string(&entry).unwrap();
    let sha = serde_json::from_str::<serde_json::Value>(&text).unwrap()["outputs"]["layout.png"]
        ["sha256"]
        .as_str()
        .unwrap()
        .to_owned();
    for damaged in ["", "a"] {
        fs::write(&entry, text.replace(&sha, damaged)).unwrap();
        fs::remove_dir_all(ws.out()).unwrap();
        let report = driver::build(&spec, &ws.options()).unwrap();
        let rebuilt = report.stages.iter().find(|s| s.stage == "mirror").unwrap();
        let why = rebuilt.repaired.as_deref().unwrap_or_default();
        assert!(why.contains("not a cache entry"), "{damaged:?}: {why}");
        assert_eq!(fs::read_to_string(&entry).unwrap(), text, "rebuilt whole");
    }
    fs::write(&entry, text.replace(&sha, "a")).unwrap();
    let out = cityspec(
        &ws,
        &["verify", "--all", "--cache", "cache", "specs/small.toml"],
    );
    assert_ne!(out.status.code(), Some(101), "{}", stderr(&out));
    assert!(!stderr(&out).contains("panicked"), "{}", stderr(&out));

    // An entry replaced by a FIFO: reported, rebuilt, and gc removes one found later.
    fs::remove_file(&entry).unwrap();
    rustix::fs::mkfifoat(rustix::fs::CWD, &entry, rustix::fs::Mode::RUSR).unwrap();
    fs::remove_dir_all(ws.out()).unwrap();
    let options = ws.options();
    let spec_path = spec.clone();
    let report = within_a_minute(move || driver::build(&spec_path, &options).unwrap());
    let rebuilt = report.stages.iter().find(|s| s.stage == "mirror").unwrap();
    let why = rebuilt.repaired.as_deref().unwrap_or_default();
    assert!(why.contains("a FIFO"), "{why}");
    assert!(fs::symlink_metadata(&entry).unwrap().is_file());
    let stray = entries.join(format!("{}.json", "0".repeat(64)));
    rustix::fs::mkfifoat(rustix::fs::CWD, &stray, rustix::fs::Mode::RUSR).unwrap();
    let cache = ws.cache();
    let report = within_a_minute(move || gc_all(&cache).unwrap());
    assert_eq!(report.removed_damaged, 1);
    assert!(fs::symlink_metadata(&stray).is_err());
}

#[test]
fn a_planted_lock_symlink_is_refused_and_its_target_never_made() {
    let (ws, spec) = small(|_| {});
    fs::create_dir_all(ws.out()).unwrap();
    let target = ws.path().join("planted-target");
    std::os::unix::fs::symlink(&target, ws.out().join(".small~cityspec-lock")).unwrap();
    let err = driver::build(&spec, &ws.options()).unwrap_err();
    assert!(err.to_string().contains("a symlink"), "{err}");
    assert!(!target.exists(), "the build created the symlink's target");
    assert!(!ws.out().join("small").exists());
}

#[test]
fn out_naming_a_file_is_a_usage_error_that_says_so() {
    let (ws, _) = small(|_| {});
    fs::write(ws.path().join("a-file"), "x").unwrap();
    let out = cityspec(
        &ws,
        &[
            "build",
            "-q",
            "--out",
            "a-file",
            "--cache",
            "cache",
            "specs/small.toml",
        ],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("--out names a file, not a folder"),
        "{}",
        stderr(&out)
    );
    assert!(!stderr(&out).contains("os error"), "{}", stderr(&out));
}

#[test]
fn strict_fails_on_a_warm_cache_exactly_when_on_a_cold_one() {
    // Far more signs than a 256 px city has curb for: placed short of their count.
    let (ws, _) = small(|spec| {
        let objects = spec["objects"].as_array_mut().unwrap();
        let sign = objects[1].as_table_mut().unwrap();
        assert_eq!(sign["kind"].as_str(), Some("sign"));
        sign["count"] = toml::Value::Integer(2000);
    });
    let strict = |ws: &Workspace| {
        cityspec(
            ws,
            &[
                "build",
                "-q",
                "--strict",
                "--out",
                "out",
                "--cache",
                "cache",
                "specs/small.toml",
            ],
        )
    };
    let plain = |ws: &Workspace| {
        cityspec(
            ws,
            &[
                "build",
                "-q",
                "--out",
                "out",
                "--cache",
                "cache",
                "specs/small.toml",
            ],
        )
    };
    let cold = strict(&ws);
    assert_eq!(cold.status.code(), Some(2), "{}", stderr(&cold));
    assert!(stderr(&cold).contains("objects-short"), "{}", stderr(&cold));
    // A plain build warns, at the key in the spec, and writes the folder.
    let built = plain(&ws);
    assert_eq!(built.status.code(), Some(0), "{}", stderr(&built));
    let warned = stderr(&built);
    assert!(
        warned.contains("specs/small.toml:") && warned.contains("warning[objects-short]"),
        "{warned}"
    );
    // Warm: the no-op fast path says the same, and --strict fails the same.
    let again = plain(&ws);
    assert_eq!(stderr(&again), warned);
    let warm = strict(&ws);
    assert_eq!(warm.status.code(), Some(2), "{}", stderr(&warm));
    assert!(stderr(&warm).contains("objects-short"), "{}", stderr(&warm));
}

#[test]
fn a_camera_path_with_no_frames_warns_on_every_build() {
    // Aimed at signs from 40–50 m up but at most 5 m away: no view is steep enough to
    // keep, so the path has no frame.
    let (ws, _) = small(|spec| {
        let cameras = spec["cameras"].as_array_mut().unwrap();
        let camera: toml::Table = toml::from_str(
            "name = \"signs\"\npath = \"objects\"\nclasses = [\"traffic_sign\"]\n\
             frames = 3\ndistance = [4, 5]\nheight = [40, 50]\nresolution = [64, 48]",
        )
        .unwrap();
        cameras.push(toml::Value::Table(camera));
    });
    let build = |strict: bool| {
        let mut args = vec!["build", "-q", "--out", "out", "--cache", "cache"];
        if strict {
            args.push("--strict");
        }
        args.push("specs/small.toml");
        cityspec(&ws, &args)
    };
    let cold = build(false);
    assert_eq!(cold.status.code(), Some(0), "{}", stderr(&cold));
    let warned = stderr(&cold);
    assert!(
        warned.contains("warning[camera-no-frames]: camera path \"signs\" yields 0 frames"),
        "{warned}"
    );
    // At the camera's table in the spec.
    assert!(warned.starts_with("specs/small.toml:"), "{warned}");
    let warm = build(false);
    assert_eq!(stderr(&warm), warned);
    let strict = build(true);
    assert_eq!(strict.status.code(), Some(2), "{}", stderr(&strict));
}
