//! Issue 12: a build split into shards sharing one cache, then merged by a plain build,
//! gives the bytes of a one-machine build; the merge renders nothing.

mod common;

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

use cityspec::build::{self, BuildOptions, Shard, StageStatus};
use common::tree;

/// A small city with two camera paths: 43 road frames (5 chunks, the last one short) and
/// a 12-frame orbit (2 chunks) with float depth; text, signs and cars so COCO, ICDAR and
/// YOLO files all have something in them.
const SPEC: &str = r#"
version = 1
name = "small"
seed = 11

[layout.generate]
width = 256
height = 256
road_width = 24
strip_width = 6
horizontal_roads = 2
vertical_roads = 2
min_block = 48

[buildings]
widths = [12, 16, 20]
gap = 2

[[objects]]
kind = "text"
label = "text"
count = 40

[[objects]]
kind = "sign"
label = "traffic_sign"
count = 20

[[objects]]
kind = "car"
count = 30

[[cameras]]
name = "street"
path = "roads"
frames = 43
height = [1.4, 2.2]
heading = [-60, 60]
resolution = [64, 48]

[[cameras]]
name = "aerial"
path = "orbit"
frames = 12
height = 200
resolution = [48, 36]
depth = "f32"

[lighting]                # a sun drawn per frame: poses.json's suns come from the records
sun_elevation = [30, 60]
sun_azimuth = [90, 270]
vary = "frame"
shadows = false

[annotations]
classes = ["text", "traffic_sign", "car"]
min_pixels = 4
yolo = true
"#;

fn options(dir: &Path, out: &str, cache: &str) -> BuildOptions {
    BuildOptions {
        out_root: dir.join(out),
        cache_dir: dir.join(cache),
        progress: None,
        waiting: None,
        strict: false,
        locked: false,
    }
}

fn spec(dir: &Path) -> PathBuf {
    let path = dir.join("small.toml");
    fs::write(&path, SPEC).unwrap();
    path
}

/// Builds `shards` shards (in this process, one after another) into `cache`, then
/// merges into `out`; checks the shards wrote no output folder and the merge rendered
/// nothing; returns the merged folder's files.
fn sharded(dir: &Path, spec: &Path, shards: u32, city_first: bool) -> Vec<(String, Vec<u8>)> {
    let (out, cache) = (format!("out{shards}"), format!("cache{shards}"));
    let options = options(dir, &out, &cache);
    let specs = [spec.to_path_buf()];
    if city_first {
        build::build_shards(&specs, &options, None).unwrap();
    }
    let mut rendered = 0;
    for index in 0..shards {
        let shard = Shard::new(index, shards).unwrap();
        let reports = build::build_shards(&specs, &options, Some(shard)).unwrap();
        rendered += reports[0].stats.rendered_chunks;
        assert!(!dir.join(&out).exists(), "shard {index} wrote the output");
    }
    assert_eq!(rendered, 5 + 2, "every chunk rendered exactly once");
    merge(dir, &options, spec)
}

/// The merge: a plain build that must find every chunk and plan in the cache.
fn merge(dir: &Path, options: &BuildOptions, spec: &Path) -> Vec<(String, Vec<u8>)> {
    let report = build::build(spec, options).unwrap();
    let ran: Vec<&str> = report
        .stages
        .iter()
        .filter(|s| s.status == StageStatus::Ran)
        .map(|s| s.stage)
        .collect();
    assert_eq!(ran, ["frames", "frames"], "the merge only assembles");
    let _ = dir;
    tree(&report.out_dir).into_iter().collect()
}

#[test]
fn one_machine_and_2_4_7_shards_give_the_same_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let spec = spec(dir);
    let one = build::build(&spec, &options(dir, "one", "cache1")).unwrap();
    let one = tree(&one.out_dir).into_iter().collect::<Vec<_>>();
    assert!(one.iter().any(|(p, _)| p == "frames/street/coco.json"));
    assert!(one.iter().any(|(p, _)| p == "frames/street/rgb/000042.png"));
    assert!(
        one.iter()
            .any(|(p, _)| p == "frames/aerial/depth/000011.npy")
    );
    for (shards, city_first) in [(2, true), (4, false), (7, false)] {
        let merged = sharded(dir, &spec, shards, city_first);
        let names = |files: &[(String, Vec<u8>)]| files.iter().map(|f| f.0.clone()).collect();
        let (a, b): (Vec<String>, Vec<String>) = (names(&one), names(&merged));
        assert_eq!(a, b, "{shards} shards: other files");
        for ((path, x), (_, y)) in one.iter().zip(&merged) {
            assert!(x == y, "{shards} shards: {path} differs");
        }
    }
}

#[test]
fn shards_as_concurrent_processes_share_one_cache_and_a_merge_finds_everything() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let spec = spec(dir);
    // Four processes at once, no `--stage city` first: they race for the city stages.
    let children: Vec<_> = (0..4)
        .map(|i| {
            Command::new(env!("CARGO_BIN_EXE_cityspec"))
                .current_dir(dir)
                .args(["build", "-q", "-j1", "--cache", "cache", "--out", "out"])
                .args(["--shard", &format!("{i}/4"), "small.toml"])
                .spawn()
                .unwrap()
        })
        .collect();
    for mut child in children {
        assert!(child.wait().unwrap().success());
    }
    assert!(!dir.join("out").exists());
    // `--shard auto` from a Kubernetes index finds its chunks done.
    let auto = Command::new(env!("CARGO_BIN_EXE_cityspec"))
        .current_dir(dir)
        .env("JOB_COMPLETION_INDEX", "2")
        .args(["build", "--cache", "cache", "--out", "out"])
        .args(["--shard", "auto", "--shard-count", "4", "small.toml"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&auto.stderr);
    assert!(auto.status.success(), "{text}");
    assert!(text.contains("shard 2/4: rendered 0 chunks"), "{text}");
    let merged = merge(dir, &options(dir, "out", "cache"), &spec);
    let one = build::build(&spec, &options(dir, "one", "cache1")).unwrap();
    let one: Vec<_> = tree(&one.out_dir).into_iter().collect();
    assert!(
        one == merged,
        "the merged folder differs from one machine's"
    );
    // Bad shard arguments are usage errors.
    for args in [&["--shard", "4/4"][..], &["--shard", "auto"]] {
        let out = Command::new(env!("CARGO_BIN_EXE_cityspec"))
            .current_dir(dir)
            .env_remove("SLURM_ARRAY_TASK_ID")
            .env_remove("JOB_COMPLETION_INDEX")
            .args(["build", "--cache", "cache"])
            .args(args)
            .arg("small.toml")
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
    }
}
