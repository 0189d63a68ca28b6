//! Issue 12: a build split into shards sharing one cache, then merged by a plain build,
//! gives the bytes of a one-machine build; the merge renders nothing.

use crate::common;

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

use cityspec::driver::{self, BuildOptions, Shard};
use common::{SpecEdit, tree};

/// A small city with two camera paths: 43 road frames (5 chunks, the last one short) and
/// a 12-frame orbit (2 chunks) with float depth; text, signs and cars so COCO, ICDAR and
/// YOLO files all have something in them. (.ci/run builds it on Slurm too.)
const SPEC: &str = include_str!("../fixtures/shards.toml");

fn options(dir: &Path, out: &str, cache: &str) -> BuildOptions {
    common::quiet_options(dir.join(out), dir.join(cache))
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
        driver::build_shards(&specs, &options, None).unwrap();
    }
    let mut rendered = 0;
    for index in 0..shards {
        let shard = Shard::new(index, shards).unwrap();
        let reports = driver::build_shards(&specs, &options, Some(shard)).unwrap();
        rendered += reports[0].stats.rendered_chunks;
        assert!(!dir.join(&out).exists(), "shard {index} wrote the output");
    }
    assert_eq!(rendered, 5 + 2, "every chunk rendered exactly once");
    merge(dir, &options, spec)
}

/// The merge: a plain build that must find every chunk and plan in the cache.
fn merge(dir: &Path, options: &BuildOptions, spec: &Path) -> Vec<(String, Vec<u8>)> {
    let report = driver::build(spec, options).unwrap();
    let ran: Vec<&str> = report.ran().map(|s| s.stage).collect();
    assert_eq!(ran, ["frames", "frames"], "the merge only assembles");
    let _ = dir;
    tree(&report.out_dir).into_iter().collect()
}

#[test]
fn one_machine_and_2_4_7_shards_give_the_same_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let spec = spec(dir);
    let one = driver::build(&spec, &options(dir, "one", "cache1")).unwrap();
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
    let one = driver::build(&spec, &options(dir, "one", "cache1")).unwrap();
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

/// The members of a tar: (name, mtime field, bytes), checking each header's fixed fields.
fn tar_members(tar: &[u8]) -> Vec<(String, Vec<u8>)> {
    let mut members = Vec::new();
    let mut at = 0;
    while at + 512 <= tar.len() && tar[at..at + 512].iter().any(|&b| b != 0) {
        let header = &tar[at..at + 512];
        let field = |from: usize, to: usize| {
            String::from_utf8(header[from..to].to_vec())
                .unwrap()
                .trim_end_matches('\0')
                .to_owned()
        };
        let name = field(0, 100);
        assert_eq!(field(100, 108), "0000644", "{name}: mode");
        assert_eq!(field(108, 124), "0000000\u{0}0000000", "{name}: uid, gid");
        assert_eq!(field(136, 148), "00000000000", "{name}: mtime");
        assert_eq!(field(257, 263), "ustar", "{name}: magic");
        let size = usize::from_str_radix(&field(124, 136), 8).unwrap();
        members.push((name, tar[at + 512..at + 512 + size].to_vec()));
        at += 512 + size.div_ceil(512) * 512;
    }
    assert_eq!(tar.len(), at + 1024, "two zero blocks end the tar");
    members
}

/// A `.npy` of float32 as (shape, values), checking its header.
fn npy_f32(npy: &[u8]) -> ((usize, usize), Vec<f32>) {
    assert_eq!(&npy[..8], b"\x93NUMPY\x01\x00", "npy magic, version 1.0");
    let len = usize::from(u16::from_le_bytes([npy[8], npy[9]]));
    let header = std::str::from_utf8(&npy[10..10 + len]).unwrap();
    assert!(header.contains("'descr': '<f4'"), "{header}");
    let shape = header.split_once("'shape': (").unwrap().1;
    let (h, w) = shape.split_once(')').unwrap().0.split_once(", ").unwrap();
    let values: Vec<f32> = npy[10 + len..]
        .chunks(4)
        .map(|b| f32::from_le_bytes(b.try_into().unwrap()))
        .collect();
    ((h.parse().unwrap(), w.parse().unwrap()), values)
}

// Long on purpose: one build of each layout, then every member of every sample of both
// cameras checked against the files layout's file it comes from.
#[test]
fn webdataset_layout_packs_the_same_frames_into_reproducible_tars() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    // The orbit labels cars only: no ICDAR files, and its samples still get the member.
    let base = SpecEdit::parse("shards.toml", SPEC)
        .insert("cameras[1].label_classes", ["car"])
        .text();
    let files_spec = dir.join("small.toml");
    fs::write(&files_spec, &base).unwrap();
    let files = driver::build(&files_spec, &options(dir, "files", "cache")).unwrap();
    let files = tree(&files.out_dir);
    assert!(!files.keys().any(|p| p.starts_with("frames/aerial/icdar/")));
    assert!(files.contains_key("frames/street/icdar/gt_000000.txt"));
    let wds_spec = dir.join("wds.toml");
    fs::write(
        &wds_spec,
        format!("{base}\n[output]\nlayout = \"webdataset\"\nsamples_per_shard = 20\n"),
    )
    .unwrap();
    // The frames' content keys ignore the layout: only the paths are assembled again.
    let wds = driver::build(&wds_spec, &options(dir, "wds", "cache")).unwrap();
    let ran: Vec<&str> = wds.ran().map(|s| s.stage).collect();
    assert_eq!(ran, ["frames", "frames"]);
    let out = tree(&wds.out_dir);
    let tars: Vec<&String> = out.keys().filter(|p| p.ends_with(".tar")).collect();
    assert_eq!(
        tars,
        [
            "frames/aerial/wds/000000.tar",
            "frames/street/wds/000000.tar",
            "frames/street/wds/000001.tar",
            "frames/street/wds/000002.tar"
        ]
    );
    assert!(
        !out.keys().any(|p| p.contains("/rgb/")),
        "frames are in the tars"
    );
    // Every sample's key over both cameras, and every sample's members.
    let mut keys = BTreeSet::new();
    let mut columns = BTreeSet::new();
    for tar in tars {
        let (camera, n) = tar["frames/".len()..].split_once("/wds/").unwrap();
        let n: usize = n.trim_end_matches(".tar").parse().unwrap();
        let coco: serde_json::Value =
            serde_json::from_slice(&out[&format!("frames/{camera}/coco.json")]).unwrap();
        let file = |name: String| files.get(&format!("frames/{camera}/{name}"));
        let members = tar_members(&out[tar]);
        let names: Vec<&str> = members.iter().map(|m| m.0.as_str()).collect();
        let mut sorted = names.clone();
        sorted.sort();
        assert_eq!(names, sorted, "members in name order");
        let mut samples: BTreeMap<String, Vec<String>> = BTreeMap::new();
        for (name, bytes) in &members {
            let (key, kind) = name.split_once('.').unwrap();
            samples
                .entry(key.to_owned())
                .or_default()
                .push(kind.to_owned());
            let stem = key
                .strip_prefix(&format!("{camera}_"))
                .unwrap_or_else(|| panic!("{name}: not keyed by its camera {camera}"));
            let i: usize = stem.parse().unwrap();
            assert!(i / 20 == n, "{name} in tar {n}");
            let image = &coco["images"][i];
            let same = |source: Option<&Vec<u8>>| assert!(source == Some(bytes), "{tar}: {name}");
            match kind {
                "png" => same(file(format!("rgb/{stem}.png"))),
                "ids.png" => same(file(format!("ids/{stem}.png"))),
                "yolo.txt" => same(file(format!("yolo/{stem}.txt"))),
                "icdar.txt" => match file(format!("icdar/gt_{stem}.txt")) {
                    Some(source) => assert!(source == bytes, "{name}"),
                    None => assert!(bytes.is_empty(), "{name}: a path without text"),
                },
                "depth.npy" => {
                    let depth = &image["depth"];
                    let source = file(depth["file_name"].as_str().unwrap().to_owned()).unwrap();
                    let scale = depth["scale"].as_f64().unwrap();
                    let expected = if depth["format"] == "f32" {
                        assert!(source == bytes, "{name}: the f32 file itself");
                        npy_f32(source).1
                    } else {
                        let units = image::load_from_memory(source).unwrap().into_luma16();
                        let units = units.into_raw();
                        assert!(units.contains(&0) && units.iter().any(|&u| u > 100));
                        units
                            .iter()
                            .map(|&u| (f64::from(u) * scale) as f32)
                            .collect()
                    };
                    let shape = (
                        image["height"].as_u64().unwrap() as usize,
                        image["width"].as_u64().unwrap() as usize,
                    );
                    assert_eq!(npy_f32(bytes), (shape, expected), "{name}: metres");
                }
                "json" => {
                    let sample: serde_json::Value = serde_json::from_slice(bytes).unwrap();
                    assert_eq!(sample["image"], *image);
                    let expected: Vec<&serde_json::Value> = coco["annotations"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .filter(|a| a["image_id"] == i as u64 + 1)
                        .collect();
                    let got: Vec<&serde_json::Value> =
                        sample["annotations"].as_array().unwrap().iter().collect();
                    assert_eq!(got, expected, "{name}");
                    assert!(sample["conditions"]["sun"].is_object());
                }
                other => panic!("unexpected member {other}"),
            }
        }
        for (key, kinds) in samples {
            assert!(keys.insert(key.clone()), "{key} twice");
            columns.insert(kinds);
        }
    }
    assert_eq!(
        keys.len(),
        43 + 12,
        "every frame of both cameras, keys distinct"
    );
    assert_eq!(
        columns.into_iter().collect::<Vec<_>>(),
        [[
            "depth.npy",
            "icdar.txt",
            "ids.png",
            "json",
            "png",
            "yolo.txt"
        ]],
        "every sample of every camera has the same members"
    );
    // Rendered from scratch into another cache: the same tar bytes.
    let fresh = driver::build(&wds_spec, &options(dir, "wds2", "cache2")).unwrap();
    assert!(tree(&fresh.out_dir) == out, "the tars are not reproducible");
}

#[test]
fn webdataset_splits_hold_the_cameras_samples_in_coco_order() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let spec = dir.join("splits.toml");
    // Both tables are new (the fixture has neither): the coco/ and wds/ files below show
    // they took effect.
    fs::write(
        &spec,
        format!(
            "{SPEC}\n[splits]\ntrain = 0.75\nval = 0.25\n\n[output]\nlayout = \"webdataset\"\n\
             samples_per_shard = 20\n"
        ),
    )
    .unwrap();
    let report = driver::build(&spec, &options(dir, "out", "cache")).unwrap();
    let out = tree(&report.out_dir);
    assert!(
        !out.keys().any(|p| p.starts_with("yolo/")),
        "no ultralytics folder: its images would be files the tars hold"
    );
    // Every camera's samples by key, as their members' (name, bytes).
    let mut samples: BTreeMap<String, Vec<(String, Vec<u8>)>> = BTreeMap::new();
    for (name, bytes) in out.iter().filter(|(p, _)| p.starts_with("frames/")) {
        if name.ends_with(".tar") {
            for member in tar_members(bytes) {
                let key = member.0.split_once('.').unwrap().0.to_owned();
                samples.entry(key).or_default().push(member);
            }
        }
    }
    assert_eq!(samples.len(), 43 + 12);
    let mut seen = BTreeSet::new();
    for split in ["train", "val"] {
        let coco: serde_json::Value =
            serde_json::from_slice(&out[&format!("coco/{split}.json")]).unwrap();
        let images = coco["images"].as_array().unwrap();
        let tars: Vec<&String> = out
            .keys()
            .filter(|p| p.starts_with(&format!("wds/{split}/")))
            .collect();
        assert_eq!(
            tars.len(),
            images.len().div_ceil(20),
            "{split}: 20 samples a shard"
        );
        let mut members = Vec::new();
        for (n, tar) in tars.iter().enumerate() {
            assert_eq!(**tar, format!("wds/{split}/{n:06}.tar"));
            members.extend(tar_members(&out[*tar]));
        }
        let mut keys: Vec<String> = Vec::new();
        for member in &members {
            let key = member.0.split_once('.').unwrap().0;
            if keys.last().map(String::as_str) != Some(key) {
                keys.push(key.to_owned());
            }
        }
        let names: Vec<&str> = images
            .iter()
            .map(|i| i["file_name"].as_str().unwrap())
            .collect();
        let expected: Vec<String> = names.iter().map(|n| n.replace(".png", "")).collect();
        assert_eq!(
            keys, expected,
            "{split}: samples in coco/{split}.json's order"
        );
        for image in images {
            let key = image["file_name"].as_str().unwrap().replace(".png", "");
            assert_eq!(image["depth"]["file_name"], format!("{key}.depth.npy"));
            assert_eq!(image["depth"]["scale"], 1.0);
            let copied: Vec<&(String, Vec<u8>)> = members
                .iter()
                .filter(|m| m.0.starts_with(&format!("{key}.")))
                .collect();
            let own: Vec<&(String, Vec<u8>)> = samples[&key].iter().collect();
            assert!(copied == own, "{split}: {key} is its camera's sample");
            assert!(seen.insert(key), "a frame in two splits");
        }
    }
    assert_eq!(seen.len(), samples.len(), "every frame in a split");
}
