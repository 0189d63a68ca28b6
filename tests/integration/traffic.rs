//! Moving traffic (`[traffic]`) through whole builds: one process on one thread and three
//! shards on two threads give the same bytes, and the traffic really moves: frame 0 is
//! the city as built, later frames are not; motion blur over the shutter changes the RGB
//! images only.

use std::fs;
use std::path::Path;
use std::process::Command;

use crate::common::tree;

/// A small city driven through at 10 fps, with flow, KITTI boxes and a small LiDAR.
const SPEC: &str = r#"version = 1
name = "moving"
seed = 5

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

[[objects]]
kind = "car"
count = 40
parked = 0.3

[[objects]]
kind = "bicycle"
count = 10
parked = 0.0

[[objects]]
kind = "traffic_light"
count = 6

[[cameras]]
name = "street"
path = "roads"
frames = 24
fps = 10
speed_kmh = 40
heading = [-10, 10]
resolution = [96, 72]
flow = true
kitti = true

[cameras.lidar]
beams = 8
columns = 128

[annotations]
classes = ["car", "bicycle", "traffic_light"]
min_pixels = 4
"#;

/// `cityspec build` of `spec` in `dir` with `threads` threads and `extra` arguments.
fn build(dir: &Path, spec: &str, threads: &str, extra: &[&str]) {
    let out = Command::new(env!("CARGO_BIN_EXE_cityspec"))
        .current_dir(dir)
        .env("RAYON_NUM_THREADS", threads)
        .args(["build", "-q", "-j", threads])
        .args(extra)
        .arg(spec)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn traffic_is_the_same_bytes_on_one_thread_and_on_shards_and_it_moves() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let still = SPEC.replace("name = \"moving\"", "name = \"still\"");
    fs::write(dir.join("still.toml"), still).unwrap();
    fs::write(dir.join("moving.toml"), format!("{SPEC}\n[traffic]\n")).unwrap();
    build(dir, "moving.toml", "1", &["--cache", "c1", "--out", "one"]);
    for i in 0..3 {
        let shard = format!("{i}/3");
        build(
            dir,
            "moving.toml",
            "2",
            &["--cache", "c2", "--shard", &shard],
        );
    }
    build(
        dir,
        "moving.toml",
        "2",
        &["--cache", "c2", "--out", "merged"],
    );
    let one = tree(&dir.join("one/moving"));
    let merged = tree(&dir.join("merged/moving"));
    assert_eq!(
        one.keys().collect::<Vec<_>>(),
        merged.keys().collect::<Vec<_>>()
    );
    for (path, bytes) in &one {
        assert!(
            merged[path] == *bytes,
            "{path} differs between one thread and shards"
        );
    }
    for file in [
        "flow/000000.png",
        "velodyne/000023.bin",
        "label_2/000023.txt",
    ] {
        assert!(one.contains_key(&format!("frames/street/{file}")), "{file}");
    }

    // The traffic moves: poses.json has every mover at zero at frame 0, some far by the
    // last; frame 0's ids and depth are the still city's, a later frame's are not.
    let poses: serde_json::Value =
        serde_json::from_slice(&one["frames/street/poses.json"]).unwrap();
    let frames = poses["frames"].as_array().unwrap();
    let offsets = |k: usize| -> Vec<f64> {
        let objects = frames[k]["traffic"]["objects"].as_object().unwrap();
        objects
            .values()
            .map(|o| o[0].as_f64().unwrap().abs() + o[2].as_f64().unwrap().abs())
            .collect()
    };
    assert!(offsets(0).iter().all(|o| *o == 0.0));
    let last = offsets(23);
    assert!(last.iter().filter(|o| **o > 5.0).count() >= 5, "{last:?}");
    assert!(frames[0]["traffic"]["signals"].as_object().unwrap().len() >= 6);
    build(dir, "still.toml", "2", &["--cache", "c3", "--out", "still"]);
    let still = tree(&dir.join("still/still"));
    for file in ["ids/000000.png", "depth/000000.png"] {
        let file = format!("frames/street/{file}");
        assert!(
            one[&file] == still[&file],
            "{file}: frame 0 is not the city as built"
        );
    }
    let moved = (1..24)
        .filter(|k| {
            let file = format!("frames/street/ids/{k:06}.png");
            one[&file] != still[&file]
        })
        .count();
    assert!(moved >= 12, "only {moved} frames show the traffic moved");

    // Motion blur over the drive's shutter (0.5 m at 40 km/h: 45 ms): only the RGB
    // images change, nearly every frame's.
    let blurred = format!("{SPEC}\n[traffic]\n").replace(
        "\n[cameras.lidar]",
        "\n[cameras.sensor]\nmotion_blur = 0.5\n\n[cameras.lidar]",
    );
    fs::write(dir.join("moving.toml"), blurred).unwrap();
    build(
        dir,
        "moving.toml",
        "2",
        &["--cache", "c4", "--out", "blurred"],
    );
    let blurred = tree(&dir.join("blurred/moving"));
    let differs = |kind: &str| {
        (0..24)
            .filter(|k| {
                let file = format!("frames/street/{kind}/{k:06}.png");
                one[&file] != blurred[&file]
            })
            .count()
    };
    assert_eq!((differs("ids"), differs("depth")), (0, 0));
    assert!(differs("rgb") >= 20, "{} blurred frames", differs("rgb"));
}
