//! The dataset-level files of `[splits]`: the ultralytics folder `yolo/` and one COCO
//! document per split, over every camera path.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::Path;

use crate::common::{self, Workspace};
use cityspec::driver;
use serde_json::Value;

/// `specs/day.toml` shrunk, with `frames` street frames and `[splits]` as given.
fn day(frames: i64, splits: &[(&str, f64)]) -> Workspace {
    let ws = Workspace::with_spec("day");
    ws.shrink_day();
    ws.edit_spec("day", |spec| {
        spec.set("cameras[0].frames", frames);
        for (key, share) in splits {
            let key = format!("splits.{key}");
            match spec.get(&key).and_then(|item| item.as_float()) {
                Some(now) if now == *share => {}
                Some(_) => {
                    spec.set(&key, *share);
                }
                None => {
                    spec.insert(&key, *share);
                }
            }
        }
    });
    ws
}

fn json(path: &Path) -> Value {
    serde_json::from_slice(&fs::read(path).unwrap()).unwrap()
}

/// Every file of `dir/<split>/`, by split.
fn by_split(dir: &Path) -> BTreeMap<String, Vec<String>> {
    let mut all = BTreeMap::new();
    for split in fs::read_dir(dir).unwrap() {
        let split = split.unwrap();
        let mut names: Vec<String> = fs::read_dir(split.path())
            .unwrap()
            .map(|f| f.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        all.insert(split.file_name().to_string_lossy().into_owned(), names);
    }
    all
}

#[test]
fn the_ultralytics_folder_names_every_frame_of_every_camera_once_with_its_labels() {
    let ws = day(10, &[("train", 0.8), ("val", 0.2)]);
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let out = ws.out().join("day");
    let yolo = out.join("yolo");
    let images = by_split(&yolo.join("images"));
    let labels = by_split(&yolo.join("labels"));
    assert_eq!(images.keys().collect::<Vec<_>>(), ["train", "val"]);
    // 10 street frames (8 + 2) and 1 aerial frame (train: 1 frame cannot be split).
    let count = |split: &str, camera: &str| {
        images[split]
            .iter()
            .filter(|n| n.starts_with(&format!("{camera}_")))
            .count()
    };
    assert_eq!([count("train", "street"), count("val", "street")], [8, 2]);
    assert_eq!([count("train", "aerial"), count("val", "aerial")], [1, 0]);
    let mut seen = BTreeSet::new();
    for (split, names) in &images {
        for name in names {
            assert!(seen.insert(name.clone()), "{name} in two splits");
            let (camera, frame) = name.strip_suffix(".png").unwrap().rsplit_once('_').unwrap();
            let frames = out.join("frames").join(camera);
            // The image is the camera's frame (one file, hard-linked), the label its YOLO
            // lines.
            let image = yolo.join("images").join(split).join(name);
            let rgb = frames.join("rgb").join(format!("{frame}.png"));
            assert_eq!(fs::read(&image).unwrap(), fs::read(&rgb).unwrap(), "{name}");
            #[cfg(unix)]
            {
                use std::os::unix::fs::MetadataExt;
                let ino = |p: &Path| fs::metadata(p).unwrap().ino();
                assert_eq!(ino(&image), ino(&rgb), "{name} is a copy");
            }
            let label = format!("{camera}_{frame}.txt");
            assert!(labels[split].contains(&label), "{split}/{label} missing");
            assert_eq!(
                fs::read(yolo.join("labels").join(split).join(&label)).unwrap(),
                fs::read(frames.join("yolo").join(format!("{frame}.txt"))).unwrap(),
                "{label}"
            );
        }
    }
    assert_eq!(seen.len(), 11);
    assert_eq!(labels.values().map(Vec::len).sum::<usize>(), 11);
    let lines: usize = labels["train"]
        .iter()
        .map(|l| {
            fs::read_to_string(yolo.join("labels/train").join(l))
                .unwrap()
                .lines()
                .count()
        })
        .sum();
    assert!(lines > 0, "no labelled box in the train split");

    // data.yaml: the split folders, and the names of yolo/classes.txt by class id.
    let yaml = fs::read_to_string(yolo.join("data.yaml")).unwrap();
    assert!(
        yaml.contains("\ntrain: images/train\nval: images/val\n"),
        "{yaml}"
    );
    assert!(!yaml.contains("path:"), "{yaml}");
    let classes = fs::read_to_string(out.join("frames/street/yolo/classes.txt")).unwrap();
    let names: Vec<String> = yaml
        .split_once("names:\n")
        .unwrap()
        .1
        .lines()
        .enumerate()
        .map(|(k, line)| {
            let (id, name) = line.trim().split_once(": ").unwrap();
            assert_eq!(id, k.to_string());
            serde_json::from_str(name).unwrap()
        })
        .collect();
    assert_eq!(names, classes.lines().collect::<Vec<_>>());
    // dataset.yaml, the name FiftyOne's YOLOv5Dataset reads: the same file.
    assert_eq!(fs::read_to_string(yolo.join("dataset.yaml")).unwrap(), yaml);
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        let ino = |name: &str| fs::metadata(yolo.join(name)).unwrap().ino();
        assert_eq!(
            ino("dataset.yaml"),
            ino("data.yaml"),
            "dataset.yaml is a copy"
        );
    }
    common::assert_matches_manifest(&out);
}

#[test]
fn each_split_s_coco_has_ids_unique_over_the_cameras_and_files_of_the_folder() {
    let ws = day(10, &[("train", 0.6), ("val", 0.2), ("test", 0.2)]);
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let out = ws.out().join("day");
    let mut image_ids = BTreeSet::new();
    let mut files = BTreeSet::new();
    let mut per_split = Vec::new();
    let mut annotations = 0;
    for split in ["train", "val", "test"] {
        let doc = json(&out.join(format!("coco/{split}.json")));
        let images = doc["images"].as_array().unwrap();
        per_split.push(images.len());
        let ids: BTreeSet<u64> = images.iter().map(|i| i["id"].as_u64().unwrap()).collect();
        for image in images {
            assert!(image_ids.insert(image["id"].as_u64().unwrap()));
            let file = image["file_name"].as_str().unwrap();
            assert!(out.join(file).is_file(), "{file}");
            assert!(files.insert(file.to_owned()));
            assert!(
                out.join(image["depth"]["file_name"].as_str().unwrap())
                    .is_file()
            );
        }
        let anns = doc["annotations"].as_array().unwrap();
        let ann_ids: BTreeSet<u64> = anns.iter().map(|a| a["id"].as_u64().unwrap()).collect();
        assert_eq!(ann_ids.len(), anns.len(), "{split}: annotation ids repeat");
        let categories: BTreeSet<u64> = doc["categories"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["id"].as_u64().unwrap())
            .collect();
        for a in anns {
            assert!(ids.contains(&a["image_id"].as_u64().unwrap()));
            assert!(categories.contains(&a["category_id"].as_u64().unwrap()));
            assert!(a.get("instance_id").is_none() && a.get("cityspec_instance").is_some());
        }
        annotations += anns.len();
    }
    // 10 street frames 6 + 2 + 2, the aerial frame in train; every frame once.
    assert_eq!(per_split, [7, 2, 2]);
    assert_eq!(files.len(), 11);
    // Every camera's annotations, each once.
    let per_camera: usize = ["street", "aerial"]
        .iter()
        .map(|c| {
            json(&out.join(format!("frames/{c}/coco.json")))["annotations"]
                .as_array()
                .unwrap()
                .len()
        })
        .sum();
    assert_eq!(annotations, per_camera);
}

#[test]
fn splits_are_drawn_from_the_seed_and_rebuild_to_the_same_bytes() {
    let splits = [("train", 0.5), ("val", 0.5)];
    let ws = day(10, &splits);
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let first = common::tree(&ws.out().join("day"));
    // A cold cache in another folder: the same bytes.
    let again = day(10, &splits);
    driver::build(&again.spec("day"), &again.options()).unwrap();
    assert_eq!(common::tree(&again.out().join("day")), first);
    let val = |ws: &Workspace| by_split(&ws.out().join("day/yolo/images"))["val"].clone();
    // Half the street's 10 frames, and the aerial camera's one frame (1.5 rounds to 1
    // in val: a camera of one frame cannot give each split one).
    assert_eq!(val(&ws).len(), 6);
    // Another seed draws other frames (the frames themselves change too).
    ws.set("day", "seed", 8);
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let numbers = |names: Vec<String>| {
        names
            .into_iter()
            .filter(|n| n.starts_with("street_"))
            .collect::<Vec<_>>()
    };
    assert_ne!(numbers(val(&ws)), numbers(val(&again)));
}

#[test]
fn by_camera_puts_each_camera_whole_into_one_split() {
    let ws = day(4, &[("train", 0.5), ("val", 0.5)]);
    ws.edit_spec("day", |spec| {
        spec.insert("splits.by", "camera");
    });
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let images = by_split(&ws.out().join("day/yolo/images"));
    let cameras = |split: &str| {
        images[split]
            .iter()
            .map(|n| n.rsplit_once('_').unwrap().0.to_owned())
            .collect::<BTreeSet<_>>()
    };
    let (train, val) = (cameras("train"), cameras("val"));
    assert_eq!(train.len() + val.len(), 2, "{train:?} {val:?}");
    assert!(train.is_disjoint(&val));
}

#[test]
fn without_splits_no_dataset_files_are_written() {
    let ws = Workspace::with_spec("day");
    ws.shrink_day();
    ws.edit_spec("day", |spec| {
        spec.remove("splits");
    });
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let out = ws.out().join("day");
    assert!(!out.join("yolo").exists() && !out.join("coco").exists());
    let manifest = fs::read_to_string(out.join("manifest.json")).unwrap();
    assert!(!manifest.contains("\"dataset\""), "{manifest}");
}

#[test]
fn bad_splits_are_refused_with_their_key_and_line() {
    // (the table's keys, the key blamed, what the message says); no key: valid.
    type Case<'a> = (&'a [(&'a str, &'a str)], &'a str, &'a str);
    let cases: &[Case] = &[
        (
            &[("train", "0.8"), ("val", "0.3")],
            "splits",
            "expected splits.train + splits.val + splits.test to make 1, found 0.8 + 0.3 + 0 = 1.1",
        ),
        (
            &[("val", "1.0")],
            "splits.train",
            "expected a share above 0 (a dataset needs frames to train on), found the default 0",
        ),
        (&[("train", "1.2")], "splits.train", "1.2"),
        (
            &[("train", "1.0"), ("bogus", "1")],
            "splits.bogus",
            "unknown key `bogus`",
        ),
        (
            &[
                ("train", "0.5"),
                ("val", "0.5"),
                ("by", "\"camera\""),
                ("test", "0.0"),
            ],
            "",
            "",
        ),
    ];
    for (keys, key, expected) in cases {
        let ws = Workspace::with_spec("day");
        let path = ws.spec("day");
        let text = fs::read_to_string(&path).unwrap();
        let (head, _) = text.split_once("\n[splits]").unwrap();
        let table: String = keys.iter().map(|(k, v)| format!("{k} = {v}\n")).collect();
        let written = format!("{head}\n[splits]\n{table}");
        fs::write(&path, &written).unwrap();
        let out = common::cityspec(&ws, &["validate", "specs/day.toml"]);
        let err = common::stderr(&out);
        if key.is_empty() {
            assert!(out.status.success(), "{keys:?}: {err}");
            continue;
        }
        assert_eq!(out.status.code(), Some(2), "{keys:?}: {err}");
        assert!(err.contains(&format!("invalid `{key}`")), "{keys:?}: {err}");
        assert!(err.contains(expected), "{keys:?}: {err}");
        // The line of the key, or of the table when the key is not written.
        let at = |start: &str| written.lines().position(|l| l.starts_with(start));
        let line = key
            .strip_prefix("splits.")
            .and_then(|leaf| at(&format!("{leaf} =")))
            .or_else(|| at("[splits]"))
            .unwrap()
            + 1;
        assert!(
            err.contains(&format!("specs/day.toml:{line}:")),
            "{keys:?}: {err}"
        );
    }
}
