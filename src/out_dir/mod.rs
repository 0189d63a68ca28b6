//! The output folder: a build's artifacts → `<out>/<name>/`, replaced whole or not at all.
//!
//! The folder is closed. Every path written is one of the stage's known relative names
//! (`driver::OutputNames`), checked again here; nothing is read from or trusted in the
//! old folder except the bytes of regular files found by walking it without following
//! symbolic links; the old `manifest.json` only tells a cityspec output folder from a
//! foreign one.
//!
//! A build that changes anything writes the new folder beside the old one, in a hidden
//! staging folder `<out>/.<name>~cityspec-stage-…`: unchanged files are hard links to the
//! old ones (no bytes copied), new ones are written, `manifest.json` last; artifacts with
//! the same bytes (a `yolo/images/` file and its camera's `rgb/` frame) are written once
//! and hard-linked, so they are one file under two names. Then one
//! `renameat2(RENAME_EXCHANGE)` (macOS: `RENAME_SWAP`) swaps the two folders, and the old
//! one is deleted. So after a kill at any moment `<out>/<name>/` holds the whole previous
//! build or the whole new one. Where the exchange is not available the swap is two renames
//! through `<out>/.<name>~cityspec-old-…`, and a kill between them is rolled back by the
//! next build. Leftover staging and old folders are removed by the next build, before its
//! no-op fast path.
//!
//! Builds of one output folder serialize on `<out>/.<name>~cityspec-lock` (an OS file
//! lock, released when the process ends however it ends). The lock file stays.
//!
//! Test hooks: `CITYSPEC_TEST_ABORT_AFTER_WRITES=N` aborts the process right after the
//! N-th change the sync makes to the file system, so a test can kill a build at every step;
//! `CITYSPEC_TEST_NO_EXCHANGE=1` skips the one-step exchange, so the two-rename fallback
//! runs on systems that have the exchange too.

use std::collections::{BTreeMap, BTreeSet};
use std::fs::{self, File, TryLockError};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::UNIX_EPOCH;

use rayon::prelude::*;

use crate::cache::{Blob, Cache};
use crate::driver::{ArtifactOut, BuildError, is_safe_relative};
use fresh::FreshRecord;

pub mod fresh;
pub mod lock;
mod manifest;

use crate::hash::sha256_hex;
pub use manifest::{Artifact, Manifest};

/// One spec's output folder, locked for this build.
pub struct OutDir {
    root: PathBuf,
    name: String,
    dir: PathBuf,
    /// Held until the build ends.
    _lock: File,
    faults: Faults,
}

/// What a sync did, by relative path.
#[derive(Debug, Default)]
pub struct Synced {
    pub written: Vec<String>,
    pub unchanged: Vec<String>,
    pub removed: Vec<String>,
}

/// The regular files, folders and anything else (symbolic links, sockets) of the old
/// folder, found without following links.
#[derive(Default)]
struct OldTree {
    files: BTreeMap<String, (u64, u128)>,
    dirs: BTreeSet<String>,
    others: Vec<String>,
}

impl OutDir {
    /// Locks `<root>/<name>/` for this build (telling `waiting` when another build holds
    /// it), removes what a killed build left beside it, and checks that the folder, if
    /// present, is a cityspec output folder of this spec.
    pub fn open(root: &Path, name: &str, waiting: &dyn Fn(&Path)) -> Result<OutDir, BuildError> {
        let io_err = |path: &Path| {
            let path = path.to_path_buf();
            move |source| BuildError::Output { path, source }
        };
        if let Ok(meta) = fs::metadata(root)
            && !meta.is_dir()
        {
            return Err(BuildError::OutNotAFolder {
                path: root.to_path_buf(),
            });
        }
        fs::create_dir_all(root).map_err(io_err(root))?;
        // Created or opened like every other write here: never through a symlink planted
        // at its name (which would make every build create its target outside the folder).
        let lock_path = root.join(format!(".{name}~cityspec-lock"));
        let lock = crate::regular_file::open_lock_file(&lock_path).map_err(io_err(&lock_path))?;
        match lock.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                waiting(&root.join(name));
                lock.lock().map_err(io_err(&lock_path))?;
            }
            Err(TryLockError::Error(e)) => return Err(io_err(&lock_path)(e)),
        }
        let out = OutDir {
            root: root.to_path_buf(),
            name: name.to_owned(),
            dir: root.join(name),
            _lock: lock,
            faults: Faults::from_env(),
        };
        out.recover().map_err(io_err(root))?;
        out.check_is_ours()?;
        Ok(out)
    }

    pub fn path(&self) -> &Path {
        &self.dir
    }

    /// Makes the folder hold exactly `artifacts` and `manifest.json` (`manifest`), and
    /// nothing else; writes nothing when it already does.
    pub fn sync(
        &self,
        artifacts: &[ArtifactOut],
        manifest: &[u8],
        cache: &Cache,
        record: Option<&FreshRecord>,
    ) -> Result<Synced, BuildError> {
        let io_err = |path: &Path| {
            let path = path.to_path_buf();
            move |source| BuildError::Output { path, source }
        };
        for artifact in artifacts {
            if !is_safe_relative(&artifact.path) || artifact.path == "manifest.json" {
                return Err(self.refuse(format!(
                    "stage {} names output {:?}, which is not a path inside the folder",
                    artifact.stage, artifact.path
                )));
            }
        }
        let old = walk(&self.dir).map_err(io_err(&self.dir))?;
        // Old files are read and hashed on every core; the answers come back in artifact order.
        let shas: Vec<String> = artifacts.par_iter().map(|a| a.blob.sha256()).collect();
        let (synced, keep, manifest_same) = self.compare(&old, artifacts, &shas, manifest, record);
        let wanted: BTreeSet<&str> = artifacts
            .iter()
            .map(|a| a.path.as_str())
            .chain(["manifest.json"])
            .collect();
        let dirs_match = old.dirs == folders_of(wanted.iter().copied());
        if synced.written.is_empty() && synced.removed.is_empty() && dirs_match {
            return Ok(synced);
        }

        // Build the new folder beside the old one, then swap.
        let stage = self.reserved("stage");
        fs::create_dir(&stage).map_err(io_err(&stage))?;
        self.faults.step();
        self.write_staged(&stage, artifacts, &shas, &keep, cache)?;
        let target = stage.join("manifest.json");
        let linked =
            manifest_same && fs::hard_link(self.dir.join("manifest.json"), &target).is_ok();
        if !linked {
            write_new(&target, manifest).map_err(io_err(&self.dir.join("manifest.json")))?;
        }
        self.faults.step();
        self.swap(&stage, old.exists()).map_err(io_err(&self.dir))?;
        Ok(synced)
    }

    /// What syncing `artifacts` and `manifest` over the folder's `old` files does: which
    /// files are written, kept (their old file holds their bytes: `keep`, hard-linked when
    /// the folder is replaced) and removed, and whether the manifest is unchanged.
    fn compare<'a>(
        &self,
        old: &OldTree,
        artifacts: &'a [ArtifactOut],
        shas: &[String],
        manifest: &[u8],
        record: Option<&FreshRecord>,
    ) -> (Synced, BTreeSet<&'a str>, bool) {
        // An artifact whose old file holds its bytes is kept (hard-linked when the folder
        // is replaced); the recorded hash of a file whose size and mtime are unchanged is
        // trusted, as by the no-op fast path.
        let same = |path: &str, sha256: &str, size: u64| {
            let Some(&(bytes, mtime_ns)) = old.files.get(path) else {
                return false;
            };
            if bytes != size {
                return false;
            }
            let recorded = record.and_then(|r| r.files.get(path));
            if recorded.is_some_and(|s| s.bytes == bytes && s.mtime_ns == mtime_ns) {
                return recorded.is_some_and(|s| s.sha256 == sha256);
            }
            crate::regular_file::read(&self.dir.join(path), crate::regular_file::Follow::No)
                .is_ok_and(|b| sha256_hex(&b) == sha256)
        };
        let mut synced = Synced::default();
        let mut keep = BTreeSet::new();
        let unchanged: Vec<bool> = artifacts
            .par_iter()
            .zip(shas)
            .map(|(a, sha)| same(&a.path, sha, a.blob.size()))
            .collect();
        for (artifact, unchanged) in artifacts.iter().zip(unchanged) {
            if unchanged {
                keep.insert(artifact.path.as_str());
                synced.unchanged.push(artifact.path.clone());
            } else {
                synced.written.push(artifact.path.clone());
            }
        }
        let manifest_same = same(
            "manifest.json",
            &sha256_hex(manifest),
            manifest.len() as u64,
        );
        if manifest_same {
            keep.insert("manifest.json");
            synced.unchanged.push("manifest.json".to_owned());
        } else {
            synced.written.push("manifest.json".to_owned());
        }
        let wanted: BTreeSet<&str> = artifacts
            .iter()
            .map(|a| a.path.as_str())
            .chain(["manifest.json"])
            .collect();
        synced.removed = old
            .files
            .keys()
            .filter(|p| !wanted.contains(p.as_str()))
            .chain(&old.others)
            .cloned()
            .collect();
        (synced, keep, manifest_same)
    }

    /// Writes every artifact into the staged folder `stage`: kept files hard-linked from
    /// the old folder, the rest from their bytes or cache objects, artifacts with the same
    /// bytes written once and linked.
    fn write_staged(
        &self,
        stage: &Path,
        artifacts: &[ArtifactOut],
        shas: &[String],
        keep: &BTreeSet<&str>,
        cache: &Cache,
    ) -> Result<(), BuildError> {
        let io_err = |path: &Path| {
            let path = path.to_path_buf();
            move |source| BuildError::Output { path, source }
        };
        // The folders first, then the files on every core: a path's frames come back
        // from the cache (read and checked against their hash), which took one core
        // 0.3 s in a 100-frame build. Largest first, one file a task, so the export's
        // OBJ and GLB (30 MB each) go to two threads. With several failures, any one is
        // reported.
        for dir in folders_of(artifacts.iter().map(|a| a.path.as_str())) {
            let target = stage.join(&dir);
            fs::create_dir_all(&target).map_err(io_err(&target))?;
        }
        // Artifacts with the same bytes (a dataset's image and its camera's frame) are
        // written once: the first in name order, the others hard-linked to it below.
        let mut first_of: BTreeMap<&str, &str> = BTreeMap::new();
        let mut twins: Vec<(&str, &str)> = Vec::new();
        for (artifact, sha) in artifacts.iter().zip(shas) {
            match first_of.get(sha.as_str()) {
                Some(first) => twins.push((artifact.path.as_str(), first)),
                None => {
                    first_of.insert(sha, &artifact.path);
                }
            }
        }
        let twin_paths: BTreeSet<&str> = twins.iter().map(|(path, _)| *path).collect();
        let mut largest_first: Vec<&ArtifactOut> = artifacts
            .iter()
            .filter(|a| !twin_paths.contains(a.path.as_str()))
            .collect();
        largest_first.sort_by_key(|a| std::cmp::Reverse(a.blob.size()));
        largest_first
            .into_par_iter()
            .with_max_len(1)
            .try_for_each(|artifact| {
                let target = stage.join(&artifact.path);
                let linked = keep.contains(artifact.path.as_str())
                    && fs::hard_link(self.dir.join(&artifact.path), &target).is_ok();
                if !linked {
                    match &artifact.blob {
                        Blob::Bytes(bytes) | Blob::Stored(_, Some(bytes)) => {
                            write_new(&target, bytes)
                        }
                        Blob::Stored(object, None) => match cache.read_object(object) {
                            Ok(bytes) => write_new(&target, &bytes),
                            Err(why) => Err(io::Error::other(format!("cache object {why}"))),
                        },
                    }
                    .map_err(io_err(&self.dir.join(&artifact.path)))?;
                }
                self.faults.step();
                Ok::<(), BuildError>(())
            })?;
        twins.into_par_iter().try_for_each(|(path, first)| {
            let target = stage.join(path);
            if fs::hard_link(stage.join(first), &target).is_err() {
                // A file system without hard links: a copy.
                fs::copy(stage.join(first), &target).map_err(io_err(&self.dir.join(path)))?;
            }
            self.faults.step();
            Ok::<(), BuildError>(())
        })?;
        Ok(())
    }

    /// Puts the staged folder in place of the old one, atomically where the OS can.
    fn swap(&self, stage: &Path, old_exists: bool) -> io::Result<()> {
        if !old_exists {
            fs::rename(stage, &self.dir)?;
            self.faults.step();
            return Ok(());
        }
        if !self.faults.no_exchange && exchange(stage, &self.dir)? {
            self.faults.step();
            // `stage` now holds the old build.
            remove_entry(stage)?;
            self.faults.step();
            return Ok(());
        }
        let aside = self.reserved("old");
        fs::rename(&self.dir, &aside)?;
        self.faults.step();
        fs::rename(stage, &self.dir)?;
        self.faults.step();
        remove_entry(&aside)?;
        self.faults.step();
        Ok(())
    }

    /// Removes what a killed build left beside the folder: staging folders (whole or not,
    /// never swapped in), and an old folder moved aside (deleted when the new one is in
    /// place, moved back when the kill landed between the two renames).
    fn recover(&self) -> io::Result<()> {
        let stage = format!(".{}~cityspec-stage-", self.name);
        let aside = format!(".{}~cityspec-old-", self.name);
        let mut leftovers: Vec<(bool, PathBuf)> = Vec::new();
        for entry in fs::read_dir(&self.root)? {
            let entry = entry?;
            let name = entry.file_name().to_string_lossy().into_owned();
            if name.starts_with(&stage) {
                leftovers.push((false, entry.path()));
            } else if name.starts_with(&aside) {
                leftovers.push((true, entry.path()));
            }
        }
        leftovers.sort();
        for (is_aside, path) in leftovers {
            if is_aside && fs::symlink_metadata(&self.dir).is_err() {
                fs::rename(&path, &self.dir)?;
            } else {
                remove_entry(&path)?;
            }
        }
        Ok(())
    }

    /// Refuses to replace a folder that is not a cityspec output folder of this spec (a
    /// user who points `--out` at a folder of their own must not lose it), or that is a
    /// symbolic link (the build would land on its far side).
    fn check_is_ours(&self) -> Result<(), BuildError> {
        let meta = match fs::symlink_metadata(&self.dir) {
            Ok(meta) => meta,
            Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(()),
            Err(source) => {
                return Err(BuildError::Output {
                    path: self.dir.clone(),
                    source,
                });
            }
        };
        if meta.file_type().is_symlink() {
            return Err(self.refuse(
                "is a symbolic link; cityspec replaces its output folder whole and does not \
                 follow links: remove the link, or point --out at the real folder's parent"
                    .to_owned(),
            ));
        }
        if !meta.is_dir() {
            return Err(self.refuse("is not a folder".to_owned()));
        }
        let manifest = self.dir.join("manifest.json");
        let ours = crate::regular_file::read(&manifest, crate::regular_file::Follow::No)
            .ok()
            .and_then(|b| Manifest::from_bytes(&b))
            .is_some_and(|m| m.name == self.name);
        let empty = fs::read_dir(&self.dir).is_ok_and(|mut d| d.next().is_none());
        if ours || empty {
            Ok(())
        } else {
            Err(self.refuse(format!(
                "exists but is not the output folder of spec {:?} (no manifest.json of that \
                 name); cityspec replaces its output folder whole, so it will not touch this \
                 one: move it away or choose another --out",
                self.name
            )))
        }
    }

    fn refuse(&self, message: String) -> BuildError {
        BuildError::OutputFolder {
            path: self.dir.clone(),
            message,
        }
    }

    /// A fresh hidden name beside the folder: `.<name>~cityspec-<what>-<pid>-<n>`.
    ///
    /// Not a `tempfile::TempDir`: the staging folder is swapped in by name and its
    /// leftovers are found by name ([`OutDir::recover`]); the old folder set aside is no
    /// temporary at all (a kill between the two renames moves it back); and removing
    /// what a swap left is a step whose error must reach the build, where a `TempDir`'s
    /// drop would ignore it.
    fn reserved(&self, what: &str) -> PathBuf {
        static COUNTER: AtomicU64 = AtomicU64::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let pid = std::process::id();
        self.root
            .join(format!(".{}~cityspec-{what}-{pid}-{n}", self.name))
    }
}

impl OldTree {
    fn exists(&self) -> bool {
        self.dirs.contains("")
    }
}

/// Every folder the paths need, `""` (the output folder itself) included.
pub fn folders_of<'p>(paths: impl IntoIterator<Item = &'p str>) -> BTreeSet<String> {
    let mut dirs = BTreeSet::from([String::new()]);
    for path in paths {
        let mut at = 0;
        while let Some(slash) = path[at..].find('/') {
            dirs.insert(path[..at + slash].to_owned());
            at += slash + 1;
        }
    }
    dirs
}

/// The old folder's contents, without following symbolic links.
fn walk(dir: &Path) -> io::Result<OldTree> {
    let mut tree = OldTree::default();
    match fs::symlink_metadata(dir) {
        Ok(meta) if meta.is_dir() => {}
        Ok(_) => return Ok(tree),
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(tree),
        Err(e) => return Err(e),
    }
    tree.dirs.insert(String::new());
    let mut stack = vec![String::new()];
    while let Some(rel) = stack.pop() {
        for entry in fs::read_dir(dir.join(&rel))? {
            let entry = entry?;
            let name = entry.file_name().to_string_lossy().into_owned();
            let path = if rel.is_empty() {
                name
            } else {
                format!("{rel}/{name}")
            };
            let kind = entry.file_type()?;
            if kind.is_dir() {
                tree.dirs.insert(path.clone());
                stack.push(path);
            } else if kind.is_file() {
                let meta = entry.metadata()?;
                tree.files.insert(path, (meta.len(), mtime_ns(&meta)));
            } else {
                tree.others.push(path);
            }
        }
    }
    Ok(tree)
}

/// A file's modification time in nanoseconds since the epoch (0 when unknown).
pub fn mtime_ns(meta: &fs::Metadata) -> u128 {
    meta.modified()
        .ok()
        .and_then(|t| t.duration_since(UNIX_EPOCH).ok())
        .map_or(0, |d| d.as_nanos())
}

/// Writes a file that must not exist yet (the staging folder is this build's own).
fn write_new(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let mut file = File::create_new(path)?;
    file.write_all(bytes)?;
    file.flush()
}

/// Removes a file, a symbolic link (not what it points at) or a whole folder.
fn remove_entry(path: &Path) -> io::Result<()> {
    match fs::symlink_metadata(path) {
        Ok(meta) if meta.is_dir() => fs::remove_dir_all(path),
        Ok(_) => fs::remove_file(path),
        Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(e),
    }
}

/// Swaps two folders in one step; `Ok(false)` when this OS or file system cannot.
#[cfg(any(target_os = "linux", target_os = "android", target_vendor = "apple"))]
fn exchange(a: &Path, b: &Path) -> io::Result<bool> {
    use rustix::fs::{CWD, RenameFlags, renameat_with};
    use rustix::io::Errno;
    match renameat_with(CWD, a, CWD, b, RenameFlags::EXCHANGE) {
        Ok(()) => Ok(true),
        Err(Errno::INVAL | Errno::NOSYS | Errno::OPNOTSUPP) => Ok(false),
        Err(e) => Err(e.into()),
    }
}

#[cfg(not(any(target_os = "linux", target_os = "android", target_vendor = "apple")))]
fn exchange(_: &Path, _: &Path) -> io::Result<bool> {
    Ok(false)
}

/// The test hooks: abort after the N-th file-system change; do without the exchange.
struct Faults {
    abort_after: Option<u64>,
    done: AtomicU64,
    no_exchange: bool,
}

impl Faults {
    fn from_env() -> Faults {
        Faults {
            abort_after: std::env::var("CITYSPEC_TEST_ABORT_AFTER_WRITES")
                .ok()
                .and_then(|v| v.parse().ok()),
            done: AtomicU64::new(0),
            no_exchange: std::env::var_os("CITYSPEC_TEST_NO_EXCHANGE").is_some(),
        }
    }

    fn step(&self) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        if self.abort_after == Some(done) {
            std::process::abort();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folders_of_lists_every_ancestor() {
        let dirs = folders_of(["a.png", "frames/s/rgb/000000.png", "textures/t.png"]);
        let want = ["", "frames", "frames/s", "frames/s/rgb", "textures"];
        assert_eq!(dirs, want.iter().map(|s| s.to_string()).collect());
    }

    #[test]
    fn walk_does_not_follow_links() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let far = dir.path().join("far");
        fs::create_dir_all(out.join("sub")).unwrap();
        fs::create_dir_all(&far).unwrap();
        fs::write(far.join("secret.txt"), b"x").unwrap();
        fs::write(out.join("sub/a.txt"), b"a").unwrap();
        #[cfg(unix)]
        std::os::unix::fs::symlink(&far, out.join("link")).unwrap();
        let tree = walk(&out).unwrap();
        assert_eq!(tree.files.keys().collect::<Vec<_>>(), ["sub/a.txt"]);
        #[cfg(unix)]
        assert_eq!(tree.others, ["link"]);
        remove_entry(&out).unwrap();
        assert!(far.join("secret.txt").exists());
    }

    /// An output folder `<root>/city/` holding a cityspec build of `files`.
    fn write_build(dir: &Path, files: &[(&str, &str)]) {
        fs::create_dir_all(dir.join("sub")).unwrap();
        for (name, text) in files {
            fs::write(dir.join(name), text).unwrap();
        }
        let manifest = Manifest {
            name: "city".to_owned(),
            artifacts: Vec::new(),
        };
        fs::write(dir.join("manifest.json"), manifest.to_bytes()).unwrap();
    }

    fn read_tree(dir: &Path) -> BTreeMap<String, Vec<u8>> {
        walk(dir)
            .unwrap()
            .files
            .keys()
            .map(|name| (name.clone(), fs::read(dir.join(name)).unwrap()))
            .collect()
    }

    /// What lies beside the output folder besides it and its lock.
    fn beside(root: &Path) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(root)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n != "city" && !n.ends_with("~cityspec-lock"))
            .collect();
        names.sort();
        names
    }

    const OLD: [(&str, &str); 2] = [("a.txt", "old a"), ("sub/b.txt", "old b")];
    const NEW: [(&str, &str); 2] = [("a.txt", "new a"), ("sub/c.txt", "new c")];

    #[test]
    fn the_two_rename_fallback_puts_the_new_folder_in_whole() {
        let root = tempfile::tempdir().unwrap();
        write_build(&root.path().join("city"), &OLD);
        let mut out = OutDir::open(root.path(), "city", &|_| {}).unwrap();
        out.faults.no_exchange = true;
        let stage = out.reserved("stage");
        write_build(&stage, &NEW);
        let want = read_tree(&stage);
        out.swap(&stage, true).unwrap();
        // The fallback's three changes (old aside, new in, old removed), not the exchange's two.
        assert_eq!(out.faults.done.load(Ordering::Relaxed), 3);
        assert_eq!(read_tree(&root.path().join("city")), want);
        assert_eq!(beside(root.path()), Vec::<String>::new());
    }

    #[test]
    fn a_kill_between_the_two_renames_is_rolled_back_by_the_next_build() {
        let root = tempfile::tempdir().unwrap();
        let city = root.path().join("city");
        write_build(&city, &OLD);
        let old = read_tree(&city);
        let out = OutDir::open(root.path(), "city", &|_| {}).unwrap();
        let stage = out.reserved("stage");
        write_build(&stage, &NEW);
        // The fallback's first rename, then the kill: no folder in place, the old one
        // aside and the new one staged.
        fs::rename(&city, out.reserved("old")).unwrap();
        drop(out);
        assert!(!city.exists());
        assert_eq!(beside(root.path()).len(), 2);
        // The next build's open puts the old folder back whole and drops the staging.
        let _next = OutDir::open(root.path(), "city", &|_| {}).unwrap();
        assert_eq!(read_tree(&city), old);
        assert_eq!(beside(root.path()), Vec::<String>::new());
    }
}
