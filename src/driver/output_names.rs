//! The names a stage may give its outputs: a stage name (and camera) → the known relative
//! file names, and the check that a cache entry uses only those.
//!
//! A cache entry is data from disk, possibly from another machine: its output names decide
//! where the driver writes. So an entry is trusted only when every name is one its stage
//! writes (fixed names like `plan.png`, or a pattern like `frames/<camera>/rgb/NNNNNN.png`),
//! always relative, never with `..`; anything else makes the entry corrupt, and the stage is
//! rebuilt. A new artifact file name must be added here, or every build rebuilds its stage.

use super::stages::{Produces, Stage};

/// What names a stage's outputs may have.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum OutputNames {
    /// Exactly these names.
    Fixed(&'static [&'static str]),
    /// `layout.png`, or `map.json` for a map layout.
    Layout,
    /// `facades.json` and `textures/<file>.png`.
    Facades,
    /// `city.obj`, `city.mtl`, `city.glb` and `textures/<file>.png`.
    Export,
    /// Everything under `frames/<camera>/` a camera path writes.
    Frames(String),
    /// A chunk of a camera path: its frames' files and `summary.jsonl`.
    Chunk(String),
    /// `coco/<split>.json`, `yolo/data.yaml`, `yolo/dataset.yaml`,
    /// `yolo/images/<split>/<file>.png` and `yolo/labels/<split>/<file>.txt`,
    /// `wds/<split>/NNNNNN.tar`, and the Cityscapes folder `cityscapes/`.
    Dataset,
}

impl OutputNames {
    /// The names stage `stage` writes, as its declaration says; `camera` is the camera
    /// path's name for `frames`.
    pub fn of(stage: Stage, camera: Option<&str>) -> OutputNames {
        match stage.declaration().produces {
            Produces::Fixed(names) => OutputNames::Fixed(names),
            Produces::Layout => OutputNames::Layout,
            Produces::Facades => OutputNames::Facades,
            Produces::Export => OutputNames::Export,
            Produces::Frames => OutputNames::Frames(camera.unwrap_or_default().to_owned()),
            Produces::Dataset => OutputNames::Dataset,
        }
    }

    /// The names a chunk of camera path `camera`'s frames writes.
    pub fn chunk(camera: &str) -> OutputNames {
        OutputNames::Chunk(camera.to_owned())
    }

    /// The names a camera path's plan writes.
    pub fn path_plan() -> OutputNames {
        OutputNames::Fixed(&["path.json"])
    }

    /// Whether `name` is one of these.
    pub fn allows(&self, name: &str) -> bool {
        if !is_safe_relative(name) {
            return false;
        }
        match self {
            OutputNames::Fixed(names) => names.contains(&name),
            OutputNames::Layout => matches!(name, "layout.png" | "map.json"),
            OutputNames::Facades => name == "facades.json" || is_texture(name),
            OutputNames::Export => {
                matches!(name, "city.obj" | "city.mtl" | "city.glb") || is_texture(name)
            }
            OutputNames::Frames(camera) => name
                .strip_prefix("frames/")
                .and_then(|rest| rest.strip_prefix(camera.as_str()))
                .and_then(|rest| rest.strip_prefix('/'))
                .is_some_and(is_frame_file),
            OutputNames::Chunk(camera) => {
                name == "summary.jsonl"
                    || name
                        .strip_prefix("frames/")
                        .and_then(|rest| rest.strip_prefix(camera.as_str()))
                        .and_then(|rest| rest.strip_prefix('/'))
                        .is_some_and(is_numbered_frame_file)
            }
            OutputNames::Dataset => is_dataset_file(name),
        }
    }

    /// Names every entry of the stage must have.
    fn required(&self) -> &'static [&'static str] {
        match self {
            OutputNames::Fixed(names) => names,
            // One of its two names: checked in `check`.
            OutputNames::Layout => &[],
            OutputNames::Facades => &["facades.json"],
            OutputNames::Export => &["city.glb", "city.mtl", "city.obj"],
            OutputNames::Frames(_) => &[],
            OutputNames::Chunk(_) => &["summary.jsonl"],
            OutputNames::Dataset => &[],
        }
    }

    /// Why a set of output names (a cache entry's) is not this stage's, if it is not.
    pub fn check<'n>(&self, names: impl IntoIterator<Item = &'n str>) -> Result<(), String> {
        let names: Vec<&str> = names.into_iter().collect();
        if let Some(bad) = names.iter().find(|n| !self.allows(n)) {
            return Err(format!(
                "names output {bad:?}, not a file this stage writes"
            ));
        }
        if let Some(missing) = self.required().iter().find(|r| !names.contains(r)) {
            return Err(format!("lacks output {missing:?}"));
        }
        if *self == OutputNames::Layout && names.len() != 1 {
            return Err("holds not one output, layout.png or map.json".to_owned());
        }
        if let OutputNames::Frames(camera) = self {
            let coco = format!("frames/{camera}/coco.json");
            if !names.contains(&coco.as_str()) {
                return Err(format!("lacks output {coco:?}"));
            }
        }
        Ok(())
    }
}

impl crate::cache::NameCheck for OutputNames {
    fn check_names(&self, names: &[&str]) -> Result<(), String> {
        self.check(names.iter().copied())
    }
}

/// A relative, `/`-separated path that stays inside the folder it is joined to: no root,
/// drive or `\`, no empty, `.` or `..` component, no NUL.
pub fn is_safe_relative(path: &str) -> bool {
    !path.is_empty()
        && !path.contains(['\\', '\0', ':'])
        && path
            .split('/')
            .all(|part| !part.is_empty() && part != "." && part != "..")
}

/// One plain file name: not hidden (no temporary or reserved name), not a path.
fn is_file_name(name: &str) -> bool {
    is_safe_relative(name) && !name.contains('/') && !name.starts_with('.')
}

fn is_texture(name: &str) -> bool {
    name.strip_prefix("textures/")
        .and_then(|rest| rest.strip_suffix(".png"))
        .is_some_and(|stem| !stem.is_empty() && is_file_name(stem))
}

/// A file of the dataset stage: `coco/<split>.json`, `yolo/data.yaml` (and its twin
/// `yolo/dataset.yaml`), a frame's image or label file of a split, a split's WebDataset
/// shard, or a file of the Cityscapes folder.
fn is_dataset_file(name: &str) -> bool {
    let in_split = |folder: &str, extension: &str| {
        name.strip_prefix(folder)
            .and_then(in_split_folder)
            .and_then(|file| file.strip_suffix(extension))
            .is_some_and(|stem| !stem.is_empty() && is_file_name(stem))
    };
    let tar = name
        .strip_prefix("wds/")
        .and_then(in_split_folder)
        .and_then(|file| file.strip_suffix(".tar"));
    matches!(name, "yolo/data.yaml" | "yolo/dataset.yaml")
        || is_cityscapes_file(name)
        || tar.is_some_and(|n| n.len() >= 6 && n.bytes().all(|b| b.is_ascii_digit()))
        || name
            .strip_prefix("coco/")
            .and_then(|file| file.strip_suffix(".json"))
            .is_some_and(|s| crate::spec::SPLIT_NAMES.contains(&s))
        || in_split("yolo/images/", ".png")
        || in_split("yolo/labels/", ".txt")
}

/// `rest` after a split's folder (`train/`, `val/`, `test/`).
fn in_split_folder(rest: &str) -> Option<&str> {
    crate::spec::SPLIT_NAMES
        .iter()
        .find_map(|s| rest.strip_prefix(s)?.strip_prefix('/'))
}

/// A file of the dataset's Cityscapes folder: `cityscapes/labels.json`,
/// `cityscapes/leftImg8bit/<split>/<city>/<name>_leftImg8bit.png`,
/// `cityscapes/gtFine/<split>/<city>/<name>_gtFine_<labelIds|instanceIds|color>.png`,
/// `cityscapes/gtFine/cityscapes_panoptic_<split>.json` and its folder's
/// `<name>_gtFine_panoptic.png`.
fn is_cityscapes_file(name: &str) -> bool {
    let Some(rest) = name.strip_prefix("cityscapes/") else {
        return false;
    };
    // `<city>/<file>` with `file` ending in `suffix`.
    let in_city = |rest: &str, suffixes: &[&str]| {
        rest.split_once('/').is_some_and(|(city, file)| {
            is_file_name(city)
                && is_file_name(file)
                && suffixes
                    .iter()
                    .any(|s| file.strip_suffix(s).is_some_and(|stem| !stem.is_empty()))
        })
    };
    let panoptic = |rest: &str| {
        crate::spec::SPLIT_NAMES.iter().any(|split| {
            let folder = format!("cityscapes_panoptic_{split}");
            rest == format!("{folder}.json")
                || rest
                    .strip_prefix(folder.as_str())
                    .and_then(|r| r.strip_prefix('/'))
                    .and_then(|file| file.strip_suffix("_gtFine_panoptic.png"))
                    .is_some_and(|stem| !stem.is_empty() && is_file_name(stem))
        })
    };
    rest == "labels.json"
        || rest
            .strip_prefix("leftImg8bit/")
            .and_then(in_split_folder)
            .is_some_and(|r| in_city(r, &["_leftImg8bit.png"]))
        || rest.strip_prefix("gtFine/").is_some_and(|r| {
            panoptic(r)
                || in_split_folder(r).is_some_and(|r| {
                    in_city(
                        r,
                        &[
                            "_gtFine_labelIds.png",
                            "_gtFine_instanceIds.png",
                            "_gtFine_color.png",
                        ],
                    )
                })
        })
}

/// A file of one camera path, relative to `frames/<camera>/`.
fn is_frame_file(rest: &str) -> bool {
    let tar = rest
        .strip_prefix("wds/")
        .and_then(|s| s.strip_suffix(".tar"));
    matches!(
        rest,
        "coco.json"
            | "instances.json"
            | "poses.json"
            | "preview.png"
            | "yolo/classes.txt"
            | "panoptic.json"
            | "semantic/labels.json"
            | "gt/gt.txt"
            | "seqinfo.ini"
    ) || is_numbered_frame_file(rest)
        || tar.is_some_and(|n| n.len() >= 6 && n.bytes().all(|b| b.is_ascii_digit()))
}

/// A file of one frame, relative to `frames/<camera>/`.
fn is_numbered_frame_file(rest: &str) -> bool {
    let numbered =
        |s: Option<&str>| s.is_some_and(|n| n.len() >= 6 && n.bytes().all(|b| b.is_ascii_digit()));
    let png = rest.strip_suffix(".png");
    let txt = rest.strip_suffix(".txt");
    ["rgb/", "ids/", "depth/", "normals/", "flow/"]
        .iter()
        .any(|dir| numbered(png.and_then(|s| s.strip_prefix(dir))))
        || numbered(
            rest.strip_suffix(".npy")
                .and_then(|s| s.strip_prefix("depth/")),
        )
        || numbered(txt.and_then(|s| s.strip_prefix("yolo/")))
        || numbered(txt.and_then(|s| s.strip_prefix("label_2/")))
        || numbered(txt.and_then(|s| s.strip_prefix("calib/")))
        || numbered(txt.and_then(|s| s.strip_prefix("icdar/gt_")))
        || [
            ("velodyne/", ".bin"),
            ("labels/", ".label"),
            ("lidar/", ".ply"),
        ]
        .iter()
        .any(|(dir, ext)| numbered(rest.strip_suffix(ext).and_then(|s| s.strip_prefix(dir))))
        || png
            .and_then(|s| s.strip_prefix("semantic/"))
            .and_then(|s| s.split_once('_'))
            .is_some_and(|(n, suffix)| {
                numbered(Some(n)) && super::frames::SEMANTIC_SUFFIXES.contains(&suffix)
            })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_that_leave_the_folder_are_unsafe() {
        for bad in [
            "",
            "/etc/passwd",
            "../x",
            "a/../../x",
            "a//b",
            "./a",
            "a/.",
            "C:x",
            "a\\b",
            "a\0b",
        ] {
            assert!(!is_safe_relative(bad), "{bad:?}");
        }
        for good in ["plan.png", "frames/street/rgb/000001.png", "a/..b/c"] {
            assert!(is_safe_relative(good), "{good:?}");
        }
    }

    #[test]
    fn each_stage_allows_only_its_own_names() {
        use Stage::*;
        let cases: &[(Stage, Option<&str>, &str, bool)] = &[
            (Preview, None, "plan.png", true),
            (Preview, None, "plan.json", false),
            (Preview, None, "/tmp/plan.png", false),
            (Mirror, None, "layout.png", true),
            (Export, None, "textures/0123abcd.png", true),
            (Export, None, "textures/.hidden.png", false),
            (Export, None, "textures/a/b.png", false),
            (Export, None, "textures/../../x.png", false),
            (Facades, None, "textures/street_01.png", true),
            (Frames, Some("street"), "frames/street/rgb/000003.png", true),
            (
                Frames,
                Some("street"),
                "frames/street/icdar/gt_000003.txt",
                true,
            ),
            (
                Frames,
                Some("street"),
                "frames/street/yolo/000003.txt",
                true,
            ),
            (
                Frames,
                Some("street"),
                "frames/street/yolo/classes.txt",
                true,
            ),
            (
                Frames,
                Some("street"),
                "frames/street/depth/000003.npy",
                true,
            ),
            (
                Frames,
                Some("street"),
                "frames/street/normals/000003.png",
                true,
            ),
            (
                Frames,
                Some("street"),
                "frames/street/normals/000003.npy",
                false,
            ),
            (
                Frames,
                Some("street"),
                "frames/street/flow/000003.png",
                true,
            ),
            (
                Frames,
                Some("street"),
                "frames/street/velodyne/000003.bin",
                true,
            ),
            (
                Frames,
                Some("street"),
                "frames/street/labels/000003.label",
                true,
            ),
            (
                Frames,
                Some("street"),
                "frames/street/lidar/000003.ply",
                true,
            ),
            (
                Frames,
                Some("street"),
                "frames/street/velodyne/000003.label",
                false,
            ),
            (Frames, Some("street"), "frames/street/lidar/3.ply", false),
            (
                Frames,
                Some("street"),
                "frames/street/label_2/000003.txt",
                true,
            ),
            (
                Frames,
                Some("street"),
                "frames/street/calib/000003.txt",
                true,
            ),
            (Frames, Some("street"), "frames/street/calib/x.txt", false),
            (Frames, Some("street"), "frames/street/coco.json", true),
            (Frames, Some("street"), "frames/aerial/coco.json", false),
            (Frames, Some("street"), "frames/street/rgb/3.png", false),
            (
                Frames,
                Some("street"),
                "frames/street/../../x/000001.png",
                false,
            ),
            (Frames, Some("street"), "frames/streetx/coco.json", false),
            (Dataset, None, "coco/train.json", true),
            (Dataset, None, "coco/other.json", false),
            (Dataset, None, "yolo/data.yaml", true),
            (Dataset, None, "yolo/dataset.yaml", true),
            (Dataset, None, "yolo/other.yaml", false),
            (Dataset, None, "yolo/images/val/street_000001.png", true),
            (Dataset, None, "yolo/labels/test/street_000001.txt", true),
            (Dataset, None, "yolo/labels/test/street_000001.png", false),
            (Dataset, None, "yolo/images/dev/street_000001.png", false),
            (Dataset, None, "yolo/images/val/.png", false),
            (Dataset, None, "yolo/images/val/a/b.png", false),
            (Dataset, None, "wds/train/000000.tar", true),
            (Dataset, None, "wds/test/000012.tar", true),
            (Dataset, None, "wds/dev/000000.tar", false),
            (Dataset, None, "wds/train/00.tar", false),
            (Dataset, None, "wds/train/a.tar", false),
            (Dataset, None, "frames/street/coco.json", false),
            (Dataset, None, "cityscapes/labels.json", true),
            (
                Dataset,
                None,
                "cityscapes/leftImg8bit/train/street/street_000000_000001_leftImg8bit.png",
                true,
            ),
            (
                Dataset,
                None,
                "cityscapes/gtFine/val/street/street_000000_000001_gtFine_instanceIds.png",
                true,
            ),
            (
                Dataset,
                None,
                "cityscapes/gtFine/val/street/street_000000_000001_gtFine_depth.png",
                false,
            ),
            (
                Dataset,
                None,
                "cityscapes/gtFine/dev/street/street_000000_000001_gtFine_color.png",
                false,
            ),
            (
                Dataset,
                None,
                "cityscapes/gtFine/cityscapes_panoptic_val.json",
                true,
            ),
            (
                Dataset,
                None,
                "cityscapes/gtFine/cityscapes_panoptic_val/street_000000_000001_gtFine_panoptic.png",
                true,
            ),
            (
                Dataset,
                None,
                "cityscapes/gtFine/val/a/b/c_gtFine_color.png",
                false,
            ),
            (
                Frames,
                Some("street"),
                "frames/street/semantic/000003_labelIds.png",
                true,
            ),
            (
                Frames,
                Some("street"),
                "frames/street/semantic/000003_depth.png",
                false,
            ),
            (Frames, Some("street"), "frames/street/panoptic.json", true),
        ];
        for (stage, camera, name, allowed) in cases {
            assert_eq!(
                OutputNames::of(*stage, *camera).allows(name),
                *allowed,
                "{stage:?} {name}"
            );
        }
    }

    #[test]
    fn entries_need_their_stage_s_outputs() {
        use Stage::*;
        assert!(OutputNames::of(Plan, None).check(["plan.json"]).is_ok());
        assert!(
            OutputNames::of(Plan, None)
                .check([])
                .unwrap_err()
                .contains("lacks")
        );
        let export = OutputNames::of(Export, None);
        assert!(export.check(["city.obj", "city.mtl", "city.glb"]).is_ok());
        assert!(export.check(["city.obj", "city.glb"]).is_err());
        let frames = OutputNames::of(Frames, Some("a"));
        assert!(frames.check(["frames/a/coco.json"]).is_ok());
        assert!(frames.check(["frames/a/poses.json"]).is_err());
        assert!(
            OutputNames::of(Plan, None)
                .check(["plan.json", "/home/u/.bashrc"])
                .unwrap_err()
                .contains("/home/u/.bashrc")
        );
    }
}
