//! Issue 12: killing a shard at any moment and running it again loses nothing and
//! duplicates nothing. A shard process is SIGKILLed at several moments of its run (during
//! the city's stages, between and inside chunks), run again, then merged: the rerun renders
//! exactly the chunks the killed run had not recorded, and the merge gives the bytes of a
//! one-machine build without rendering a frame.

mod common;

use std::fs;
use std::path::Path;
use std::process::{Command, Output};
use std::time::Instant;

use cityspec::build::{self, BuildOptions, StageStatus};
use common::tree;

const SPEC: &str = include_str!("fixtures/shards.toml");

fn shard(dir: &Path, cache: &str, shard: &str) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_cityspec"));
    command.current_dir(dir).args([
        "build",
        "-j1",
        "--cache",
        cache,
        "--shard",
        shard,
        "small.toml",
    ]);
    command
}

/// (rendered, already cached) chunks, from a shard's report line.
fn counts(output: &Output) -> (usize, usize) {
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let text = String::from_utf8_lossy(&output.stderr);
    let number_after = |word: &str| -> usize {
        let rest = &text[text.find(word).unwrap_or_else(|| panic!("{text}")) + word.len()..];
        rest.split_whitespace().next().unwrap().parse().unwrap()
    };
    let cached = text
        .split(", ")
        .find_map(|part| part.strip_suffix(" already cached"))
        .unwrap_or_else(|| panic!("{text}"))
        .parse()
        .unwrap();
    (number_after(": rendered "), cached)
}

/// The chunk entries in a local cache folder.
fn chunk_entries(cache: &Path) -> usize {
    let Ok(entries) = fs::read_dir(cache.join("entries")) else {
        return 0;
    };
    entries
        .filter_map(|e| fs::read(e.unwrap().path()).ok())
        .filter(|text| {
            serde_json::from_slice::<serde_json::Value>(text)
                .is_ok_and(|v| v["stage"] == "frames-chunk")
        })
        .count()
}

fn options(dir: &Path, out: &str, cache: &str) -> BuildOptions {
    common::quiet_options(dir.join(out), dir.join(cache))
}

#[test]
fn a_killed_shard_rerun_renders_only_what_was_lost_and_merges_to_the_same_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let spec = dir.join("small.toml");
    fs::write(&spec, SPEC).unwrap();
    let one = build::build(&spec, &options(dir, "one", "one-cache")).unwrap();
    let one = tree(&one.out_dir);

    // The shared stages first (`--stage city`), as an array would: the shard's run is then
    // mostly its chunks, and the kills land among them. One kill is before, in the city.
    let city = Command::new(env!("CARGO_BIN_EXE_cityspec"))
        .current_dir(dir)
        .args([
            "build",
            "-q",
            "--stage",
            "city",
            "--cache",
            "city",
            "small.toml",
        ])
        .status()
        .unwrap();
    assert!(city.success());
    // An undisturbed shard 0/2, timed: the kills land at fractions of its run.
    common::copy_tree(&dir.join("city"), &dir.join("whole"));
    let start = Instant::now();
    let whole = shard(dir, "whole", "0/2").output().unwrap();
    let run = start.elapsed();
    let (mine, none) = counts(&whole);
    assert_eq!(none, 0);
    assert!(mine >= 3, "shard 0/2 renders {mine} chunks");

    let mut mid_render = 0;
    for (n, fraction) in [0.05, 0.6, 0.8, 0.87, 0.93, 0.97].into_iter().enumerate() {
        let cache = format!("cache{n}");
        if n > 0 {
            common::copy_tree(&dir.join("city"), &dir.join(&cache));
        }
        let mut child = shard(dir, &cache, "0/2").spawn().unwrap();
        std::thread::sleep(run.mul_f64(fraction));
        child.kill().unwrap(); // SIGKILL
        child.wait().unwrap();
        let survived = chunk_entries(&dir.join(&cache));
        eprintln!("killed at {fraction}: {survived} of {mine} chunks recorded");
        if 0 < survived && survived < mine {
            mid_render += 1;
        }
        let rerun = shard(dir, &cache, "0/2").output().unwrap();
        let (rendered, cached) = counts(&rerun);
        assert_eq!(
            (rendered, cached),
            (mine - survived, survived),
            "killed at {fraction} of the run with {survived} chunks recorded"
        );
        let other = shard(dir, &cache, "1/2").output().unwrap();
        assert_eq!(counts(&other).0 + mine, 5 + 2, "shard 1/2 renders the rest");
        let merged = build::build(&spec, &options(dir, &format!("out{n}"), &cache)).unwrap();
        let ran: Vec<&str> = merged
            .stages
            .iter()
            .filter(|s| s.status == StageStatus::Ran)
            .map(|s| s.stage)
            .collect();
        assert_eq!(ran, ["frames", "frames"], "the merge only assembles");
        let merged = tree(&merged.out_dir);
        assert_eq!(
            one.keys().collect::<Vec<_>>(),
            merged.keys().collect::<Vec<_>>(),
            "killed at {fraction}: other files"
        );
        for (path, bytes) in &one {
            assert!(
                bytes == &merged[path],
                "killed at {fraction}: {path} differs"
            );
        }
        fs::remove_dir_all(dir.join(&cache)).unwrap();
    }
    // Timing on a loaded machine varies; at least one kill must have cut the chunks.
    assert!(
        mid_render > 0,
        "no kill landed between chunks (the run took {run:?})"
    );
}
