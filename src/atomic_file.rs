//! Atomic file writes: bytes → a whole file or no file.
//!
//! A write goes to a hidden temporary file in the destination's folder and is renamed over
//! the destination only once every byte is written, so a reader (or a build that was
//! killed halfway) sees the old file or the new one, never half of one. Temporary files a
//! killed build left behind are swept by [`sweep_temporaries`].

use std::fs::{self, File};
use std::io::{self, Write};
use std::path::Path;

use tempfile::NamedTempFile;

/// What every temporary's name holds: `.<name>.cityspec-tmp-<random>` (older cityspec
/// versions wrote `<pid>-<n>` after it).
pub(super) const TEMP_MARK: &str = ".cityspec-tmp-";
/// How many random letters and digits `tempfile` puts after [`TEMP_MARK`].
pub(super) const TEMP_RANDOM: usize = 6;

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
    // Dropped on every early return, which removes the temporary.
    let mut temp = temp_file(dir, path)?;
    fill(temp.as_file_mut())?;
    temp.as_file_mut().flush()?;
    temp.persist(path).map_err(|e| e.error)?;
    Ok(())
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

/// A new hidden temporary file in `dir` for `path`, `.<name>.cityspec-tmp-<random>`:
/// created new (never one that is there already, nor through a symlink planted at the
/// name) and removed when dropped unless persisted. Its mode is what `File::create` gives
/// (0666 less the umask), not tempfile's private 0600: it becomes an output file.
pub(super) fn temp_file(dir: &Path, path: &Path) -> io::Result<NamedTempFile> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let prefix = format!(".{name}{TEMP_MARK}");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).rand_bytes(TEMP_RANDOM);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(fs::Permissions::from_mode(0o666));
    }
    builder.tempfile_in(dir)
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

    #[cfg(unix)]
    #[test]
    fn written_files_get_the_usual_mode_not_a_private_one() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let (atomic, plain) = (dir.path().join("a.txt"), dir.path().join("b.txt"));
        write_atomic(&atomic, b"a").unwrap();
        fs::write(&plain, b"b").unwrap();
        let mode = |p: &Path| fs::metadata(p).unwrap().permissions().mode();
        assert_eq!(mode(&atomic), mode(&plain));
    }

    #[test]
    fn temporaries_are_hidden_and_marked() {
        let dir = tempfile::tempdir().unwrap();
        let temp = temp_file(dir.path(), Path::new("plan.png")).unwrap();
        let name = temp
            .path()
            .file_name()
            .unwrap()
            .to_str()
            .unwrap()
            .to_owned();
        let random = name.strip_prefix(".plan.png.cityspec-tmp-").unwrap();
        assert_eq!(random.len(), TEMP_RANDOM, "{name}");
        assert!(random.bytes().all(|b| b.is_ascii_alphanumeric()), "{name}");
        assert_eq!(sweep_temporaries(dir.path()).unwrap(), 1);
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
