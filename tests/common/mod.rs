//! Helpers shared by the integration tests: temp workspaces with a copy of an example spec.

#![allow(dead_code)]

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

mod copy_tree;
pub use copy_tree::copy_tree;

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
pub fn quiet_options(out_root: PathBuf, cache_dir: PathBuf) -> cityspec::build::BuildOptions {
    cityspec::build::BuildOptions {
        out_root,
        cache_dir,
        progress: None,
        waiting: None,
        strict: false,
        locked: false,
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
        // Fewer frames than the examples render, so the suite stays quick in debug builds
        // (60: text.toml's walk and signs.toml's aimed camera).
        for entry in fs::read_dir(dir.path().join("specs")).unwrap() {
            let path = entry.unwrap().path();
            let text = fs::read_to_string(&path).unwrap();
            let text = text
                .replace("frames = 100", "frames = 4")
                .replace("frames = 60", "frames = 3")
                .replace("frames = 12", "frames = 2");
            fs::write(&path, text).unwrap();
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
    /// frames and about a tenth of its objects, keeping every kind of object, camera and
    /// output file: for tests that build it many times over.
    pub fn shrink_day(&self) {
        self.shrink("day");
    }

    /// [`Workspace::shrink_day`] for another spec of the day city (`night`, `dusk`, …).
    pub fn shrink(&self, name: &str) {
        for (from, to) in [
            ("width = 768", "width = 384"),
            ("height = 768", "height = 384"),
            ("horizontal_roads = 3", "horizontal_roads = 2"),
            ("vertical_roads = 3", "vertical_roads = 2"),
            // The aerial camera's 2 first, then the street's 4.
            ("frames = 2\n", "frames = 1\n"),
            ("frames = 4", "frames = 2"),
            ("count = 240", "count = 40"),
            ("count = 120", "count = 20"),
            ("count = 60\n", "count = 6\n"),
            ("count = 450", "count = 40"),
            ("count = 300", "count = 30"),
            ("count = 500", "count = 50"),
        ] {
            self.edit_spec(name, from, to);
        }
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

    pub fn options(&self) -> cityspec::build::BuildOptions {
        quiet_options(self.out(), self.cache())
    }

    /// Replaces `from` with `to` in a spec file (panics if `from` is absent).
    pub fn edit_spec(&self, name: &str, from: &str, to: &str) {
        let path = self.spec(name);
        let text = fs::read_to_string(&path).unwrap();
        assert!(text.contains(from), "{from:?} not in {}", path.display());
        fs::write(&path, text.replacen(from, to, 1)).unwrap();
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
    let manifest = cityspec::build::Manifest::from_bytes(&files["manifest.json"])
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
