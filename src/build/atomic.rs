//! Atomic file writes: bytes → a whole file or no file.
//!
//! A write goes to a hidden temporary file in the destination's folder and is renamed over
//! the destination only once every byte is written, so a reader (or a build that was
//! killed halfway) sees the old file or the new one, never half of one. Temporary files a
//! killed build left behind are swept by [`sweep_temporaries`].

use std::fs::{self, File};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

pub(super) const TEMP_MARK: &str = ".cityspec-tmp-";

/// Writes `bytes` to `path` atomically, creating the parent folder if needed.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    write_atomic_with(path, |file| file.write_all(bytes))
}

/// Writes `path` atomically with `fill`; if `fill` fails, neither `path` nor a temporary
/// file is left behind (an older `path` stays as it was).
pub fn write_atomic_with(
    path: &Path,
    fill: impl FnOnce(&mut File) -> io::Result<()>,
) -> io::Result<()> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    fs::create_dir_all(dir)?;
    let temp = temp_path(dir, path);
    let result = (|| {
        // A new file, never one that is there already (nor through a symlink planted at
        // the name).
        let mut file = File::create_new(&temp)?;
        fill(&mut file)?;
        file.flush()?;
        drop(file);
        fs::rename(&temp, path)
    })();
    if result.is_err() {
        let _ = fs::remove_file(&temp);
    }
    result
}

/// Removes the temporary files an interrupted build left in `dir` (not recursive).
pub fn sweep_temporaries(dir: &Path) -> io::Result<usize> {
    let entries = match fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(0),
        Err(e) => return Err(e),
    };
    let mut removed = 0;
    for entry in entries {
        let entry = entry?;
        if entry.file_name().to_string_lossy().contains(TEMP_MARK) {
            fs::remove_file(entry.path())?;
            removed += 1;
        }
    }
    Ok(removed)
}

pub(super) fn temp_path(dir: &Path, path: &Path) -> PathBuf {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    dir.join(format!(".{name}{TEMP_MARK}{}-{n}", std::process::id()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_whole_file_and_replaces_old() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sub/a.txt");
        write_atomic(&path, b"first").unwrap();
        write_atomic(&path, b"second").unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"second");
        assert_eq!(fs::read_dir(path.parent().unwrap()).unwrap().count(), 1);
    }

    #[test]
    fn interrupted_write_leaves_nothing_behind() {
        let dir = tempfile::tempdir().unwrap();
        let fresh = dir.path().join("fresh.png");
        let old = dir.path().join("old.png");
        fs::write(&old, b"old bytes").unwrap();
        for path in [&fresh, &old] {
            let err = write_atomic_with(path, |file| {
                file.write_all(b"half of the")?;
                Err(io::Error::other("disk full"))
            })
            .unwrap_err();
            assert_eq!(err.to_string(), "disk full");
        }
        assert!(
            !fresh.exists(),
            "a failed write must not create the artifact"
        );
        assert_eq!(
            fs::read(&old).unwrap(),
            b"old bytes",
            "a failed write must keep the old file"
        );
        let names: Vec<_> = fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("old.png")]);
    }

    #[test]
    fn sweep_removes_only_temporaries() {
        let dir = tempfile::tempdir().unwrap();
        fs::write(dir.path().join(".plan.png.cityspec-tmp-12-0"), b"half").unwrap();
        fs::write(dir.path().join("plan.png"), b"whole").unwrap();
        assert_eq!(sweep_temporaries(dir.path()).unwrap(), 1);
        assert!(dir.path().join("plan.png").exists());
        assert_eq!(sweep_temporaries(&dir.path().join("missing")).unwrap(), 0);
    }
}
