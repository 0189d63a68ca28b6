//! Helpers shared by the integration tests: temp workspaces with a copy of an example spec.

#![allow(dead_code)]

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

mod copy_tree;
mod spec_edit;
pub use copy_tree::copy_tree;
pub use spec_edit::{SpecEdit, SpecValue, set};

/// Frames the examples' cameras render in the tests (`spec`, key path, frames): far fewer
/// than the examples ask, so the suite stays quick in debug builds. Other specs build as
/// they are; dusk and night extend day and write no `frames`, so they take day's.
const QUICK_FRAMES: &[(&str, &str, i64)] = &[
    ("day", "cameras[0].frames", 4),   // street, 100
    ("day", "cameras[1].frames", 2),   // aerial, 12
    ("signs", "cameras[0].frames", 4), // street, 120
    ("signs", "cameras[1].frames", 3), // signs (aimed), 60
    ("text", "cameras[0].frames", 4),  // street, 100
    ("text", "cameras[1].frames", 4),  // words (aimed), 100
    ("text", "cameras[2].frames", 3),  // walk, 60
];

/// Runs the `cityspec` binary in `ws` with `args`, to the end.
pub fn cityspec(ws: &Workspace, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cityspec"))
        .current_dir(ws.path())
        .args(args)
        .output()
        .unwrap()
}

/// What a run printed on standard error.
pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Options for a quiet, non-strict, unlocked build of `out_root` with `cache_dir`.
pub fn quiet_options(out_root: PathBuf, cache_dir: PathBuf) -> cityspec::driver::BuildOptions {
    cityspec::driver::BuildOptions {
        out_root,
        cache_dir,
        progress: None,
        waiting: None,
        strict: false,
        locked: false,
        sets: Vec::new(),
    }
}

/// A temp folder holding `specs/<name>.toml` copied from the repo, plus `out/` and
/// `cache/` paths inside it.
pub struct Workspace {
    pub dir: tempfile::TempDir,
}

impl Workspace {
    pub fn with_spec(name: &str) -> Workspace {
        let dir = tempfile::tempdir().unwrap();
        fs::create_dir_all(dir.path().join("specs")).unwrap();
        let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
        for entry in fs::read_dir(repo.join("specs")).unwrap() {
            let entry = entry.unwrap();
            fs::copy(
                entry.path(),
                dir.path().join("specs").join(entry.file_name()),
            )
            .unwrap();
        }
        // Fewer frames than the examples render, so the suite stays quick in debug builds.
        for (name, path, frames) in QUICK_FRAMES {
            let spec = dir.path().join("specs").join(format!("{name}.toml"));
            let text =
                fs::read_to_string(&spec).unwrap_or_else(|e| panic!("{}: {e}", spec.display()));
            let mut edit = SpecEdit::parse(&format!("specs/{name}.toml"), &text);
            edit.set(path, *frames);
            fs::write(&spec, edit.text()).unwrap();
        }
        // Specs name layout images and facade folders under assets/, relative to their folder.
        copy_tree(&repo.join("assets"), &dir.path().join("assets"));
        assert!(
            dir.path()
                .join("specs")
                .join(format!("{name}.toml"))
                .exists()
        );
        Workspace { dir }
    }

    /// Shrinks `specs/day.toml` to a quarter of its ground (384 px, 2 + 2 roads), 2 + 1
    /// frames and about a tenth of most of its objects, keeping every kind of object, camera
    /// and output file: for tests that build it many times over.
    pub fn shrink_day(&self) {
        self.shrink("day");
    }

    /// [`Workspace::shrink_day`] for another spec of the day city (`night`, `dusk`, …).
    pub fn shrink(&self, name: &str) {
        self.edit_spec(name, |spec| {
            spec.set("layout.generate.width", 384)
                .set("layout.generate.height", 384)
                .set("layout.generate.horizontal_roads", 2)
                .set("layout.generate.vertical_roads", 2)
                .set("cameras[0].frames", 2)
                .set("cameras[1].frames", 1);
            // The street-name signs (16), traffic lights (14) and bicycles (120) keep their
            // counts.
            for (i, kind, count) in [
                (0, "text", 40),
                (3, "sign", 20),
                (4, "mesh", 6),
                (5, "tree", 40),
                (6, "car", 30),
                (7, "person", 50),
            ] {
                spec.expect(&format!("objects[{i}].kind"), kind)
                    .set(&format!("objects[{i}].count"), count);
            }
        });
    }

    pub fn path(&self) -> &Path {
        self.dir.path()
    }

    pub fn spec(&self, name: &str) -> PathBuf {
        self.path().join("specs").join(format!("{name}.toml"))
    }

    pub fn out(&self) -> PathBuf {
        self.path().join("out")
    }

    pub fn cache(&self) -> PathBuf {
        self.path().join("cache")
    }

    pub fn options(&self) -> cityspec::driver::BuildOptions {
        quiet_options(self.out(), self.cache())
    }

    /// Changes `specs/<name>.toml` through its parsed value: each change `change` makes
    /// panics unless it takes effect (see [`SpecEdit`]).
    pub fn edit_spec(&self, name: &str, change: impl FnOnce(&mut SpecEdit)) {
        let path = self.spec(name);
        let text = fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mut spec = SpecEdit::parse(&format!("specs/{name}.toml"), &text);
        change(&mut spec);
        fs::write(&path, spec.text()).unwrap();
    }

    /// Sets the value at key path `key` of `specs/<name>.toml` (see [`SpecEdit::set`]).
    pub fn set(&self, name: &str, key: &str, value: impl SpecValue) {
        self.edit_spec(name, |spec| {
            spec.set(key, value);
        });
    }
}

/// Every file below `dir` (relative path → bytes), sorted; symbolic links as
/// `-> target`. Builds' lock files (`.<name>~cityspec-lock`, empty, kept on purpose
/// beside each output folder) are left out.
pub fn tree(dir: &Path) -> std::collections::BTreeMap<String, Vec<u8>> {
    let mut files = std::collections::BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            let kind = fs::symlink_metadata(&path).unwrap().file_type();
            if path.to_string_lossy().ends_with("~cityspec-lock") {
                continue;
            }
            if kind.is_symlink() {
                let rel = path
                    .strip_prefix(dir)
                    .unwrap()
                    .to_string_lossy()
                    .into_owned();
                let target = fs::read_link(&path).unwrap();
                files.insert(rel, format!("-> {}", target.display()).into_bytes());
            } else if kind.is_dir() {
                stack.push(path);
            } else {
                let rel = path
                    .strip_prefix(dir)
                    .unwrap()
                    .to_string_lossy()
                    .replace('\\', "/");
                files.insert(rel, fs::read(&path).unwrap());
            }
        }
    }
    files
}

/// The artifacts of a manifest's output folder: its `manifest.json` lists exactly the
/// other files, each with its bytes' hash.
pub fn assert_matches_manifest(out: &Path) {
    let files = tree(out);
    let manifest = cityspec::driver::Manifest::from_bytes(&files["manifest.json"])
        .unwrap_or_else(|| panic!("{}: manifest.json does not parse", out.display()));
    let listed: std::collections::BTreeMap<&str, &str> = manifest
        .artifacts
        .iter()
        .map(|a| (a.path.as_str(), a.sha256.as_str()))
        .collect();
    let found: Vec<&str> = files
        .keys()
        .map(String::as_str)
        .filter(|p| *p != "manifest.json")
        .collect();
    assert_eq!(
        found,
        listed.keys().copied().collect::<Vec<_>>(),
        "{}: files besides the manifest's",
        out.display()
    );
    for (path, bytes) in &files {
        if let Some(sha) = listed.get(path.as_str()) {
            assert_eq!(&cityspec::hash::sha256_hex(bytes), sha, "{path}");
        }
    }
}

/// Asserts that two `coco.json` of the same frames under other weather or sensor settings
/// label the same objects with the same boxes and masks, and differ at most in which are
/// positives, an object being an ignore region in one only for its contrast (the final
/// image decides what shows: fog hides a dark car, or brings out a dark tree).
pub fn same_objects_but_for_contrast(a: &[u8], b: &[u8]) {
    let parse = |bytes: &[u8]| -> serde_json::Value { serde_json::from_slice(bytes).unwrap() };
    let (a, b) = (parse(a), parse(b));
    let by_object = |coco: &serde_json::Value| -> BTreeMap<(u64, u64), serde_json::Value> {
        coco["annotations"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| {
                let key = (
                    x["image_id"].as_u64().unwrap(),
                    x["cityspec_instance"].as_u64().unwrap(),
                );
                (key, x.clone())
            })
            .collect()
    };
    let (a, b) = (by_object(&a), by_object(&b));
    assert_eq!(a.keys().collect::<Vec<_>>(), b.keys().collect::<Vec<_>>());
    for (key, x) in &a {
        let y = &b[key];
        for field in ["bbox", "segmentation", "category_id", "area"] {
            assert_eq!(x[field], y[field], "{key:?} {field}");
        }
        if x["iscrowd"] != y["iscrowd"] {
            let ignored = if x["iscrowd"] == 1 { x } else { y };
            assert_eq!(ignored["cityspec_ignored"], "contrast", "{key:?}");
        }
    }
}
