//! Issue 12: killing a shard at any moment and running it again loses nothing and
//! duplicates nothing. A shard process is SIGKILLed at several moments of its run (while it
//! loads the city, and as soon as its first and second chunks are recorded, inside the
//! next chunk), run again, then merged: the rerun renders exactly the chunks the killed run
//! had not recorded, and the merge gives the bytes of a one-machine build without rendering
//! a frame.
//!
//! The kills inside the run wait for chunk entries to appear in the cache, not for a
//! fraction of a timed run: on a busy 2-core CI machine the chunks of a small spec all land
//! within a few milliseconds of each other, and a timed kill missed them (CI, stop 15).

use crate::common;

use std::fs;
use std::path::Path;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use cityspec::driver::{self, BuildOptions};
use common::tree;

const SPEC: &str = include_str!("../fixtures/shards.toml");

/// The street frames of the shared fixture are 64 × 48, rendered in a few milliseconds a
/// chunk. At 256 × 192 a chunk takes about 170 ms in a debug build: a wide window for a
/// kill that polls every millisecond to land inside the next chunk.
fn spec_text() -> String {
    common::set(SPEC, "cameras[0].resolution", [256, 192])
}

/// When a shard is killed.
#[derive(Clone, Copy, Debug)]
enum Kill {
    /// This long after it starts: while it loads the city, before any chunk.
    After(Duration),
    /// As soon as this many chunk entries are in its cache: inside the next chunk.
    OnChunk(usize),
}

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

/// The chunk entries in a local cache folder. An entry is written whole to a hidden
/// temporary (`.<name>.cityspec-tmp-…`) and renamed into place; a kill between the two
/// leaves no entry, so the temporaries are not counted (counting one made a kill that
/// landed there look like a recorded chunk the rerun then rendered again, once in a
/// clean-clone run of `.ci/run`).
fn chunk_entries(cache: &Path) -> usize {
    let Ok(entries) = fs::read_dir(cache.join("entries")) else {
        return 0;
    };
    entries
        .map(|e| e.unwrap())
        .filter(|e| !e.file_name().to_string_lossy().starts_with('.'))
        .filter_map(|e| fs::read(e.path()).ok())
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
    fs::write(&spec, spec_text()).unwrap();
    let one = driver::build(&spec, &options(dir, "one", "one-cache")).unwrap();
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
    // An undisturbed shard 0/2: how many chunks it renders.
    common::copy_tree(&dir.join("city"), &dir.join("whole"));
    let whole = shard(dir, "whole", "0/2").output().unwrap();
    let (mine, none) = counts(&whole);
    assert_eq!(none, 0);
    assert!(mine >= 3, "shard 0/2 renders {mine} chunks");

    let mut mid_render = 0;
    let kills = [
        Kill::After(Duration::from_millis(20)),
        Kill::OnChunk(1),
        Kill::OnChunk(2),
    ];
    for (n, kill) in kills.into_iter().enumerate() {
        let cache = format!("cache{n}");
        common::copy_tree(&dir.join("city"), &dir.join(&cache));
        let mut child = shard(dir, &cache, "0/2").spawn().unwrap();
        match kill {
            Kill::After(delay) => std::thread::sleep(delay),
            Kill::OnChunk(chunks) => {
                let start = Instant::now();
                while chunk_entries(&dir.join(&cache)) < chunks
                    && child.try_wait().unwrap().is_none()
                {
                    assert!(start.elapsed() < Duration::from_secs(120), "shard hung");
                    std::thread::sleep(Duration::from_millis(1));
                }
            }
        }
        child.kill().unwrap(); // SIGKILL; a no-op when the shard has already finished
        child.wait().unwrap();
        let survived = chunk_entries(&dir.join(&cache));
        eprintln!("killed {kill:?}: {survived} of {mine} chunks recorded");
        if let Kill::OnChunk(chunks) = kill {
            assert!(
                survived >= chunks,
                "killed {kill:?} with {survived} recorded"
            );
        }
        if 0 < survived && survived < mine {
            mid_render += 1;
        }
        let rerun = shard(dir, &cache, "0/2").output().unwrap();
        let (rendered, cached) = counts(&rerun);
        assert_eq!(
            (rendered, cached),
            (mine - survived, survived),
            "killed {kill:?} with {survived} chunks recorded"
        );
        let other = shard(dir, &cache, "1/2").output().unwrap();
        assert_eq!(counts(&other).0 + mine, 5 + 2, "shard 1/2 renders the rest");
        let merged = driver::build(&spec, &options(dir, &format!("out{n}"), &cache)).unwrap();
        let ran: Vec<&str> = merged.ran().map(|s| s.stage).collect();
        assert_eq!(ran, ["frames", "frames"], "the merge only assembles");
        let merged = tree(&merged.out_dir);
        assert_eq!(
            one.keys().collect::<Vec<_>>(),
            merged.keys().collect::<Vec<_>>(),
            "killed {kill:?}: other files"
        );
        for (path, bytes) in &one {
            assert!(bytes == &merged[path], "killed {kill:?}: {path} differs");
        }
        fs::remove_dir_all(dir.join(&cache)).unwrap();
    }
    // A kill polls every millisecond and a chunk takes about 170 ms: only a test thread
    // stalled for a whole chunk on both kills misses.
    assert!(mid_render > 0, "no kill landed between chunks");
}
