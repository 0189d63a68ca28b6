//! Opening a path as a regular file, or not at all: `path` → an open [`File`] whose type was
//! checked, never a FIFO that blocks forever, a device or a folder.
//!
//! Every file cityspec reads from a user's tree (spec, layout image, facades, OBJ models,
//! word lists) or from the cache goes through here. The file is opened with `O_NONBLOCK`,
//! so opening a FIFO returns at once instead of waiting for a writer, and its type is then
//! checked on the open descriptor (`fstat`), so nothing can swap the path between the check
//! and the read. Cache files are also opened with `O_NOFOLLOW` ([`Follow::No`]): the cache
//! writes no symlinks, so one found there is damage or a plant, never data.

use std::fs::File;
use std::io::{self, Read};
use std::path::Path;

/// Whether a symlink at the path itself is followed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Follow {
    /// Follow it (a user's inputs: a symlinked asset folder is ordinary).
    Yes,
    /// Refuse it (the cache and the output folder hold no symlinks of their own).
    No,
}

/// A path that exists but is not a regular file: what it is instead (`"a FIFO"`,
/// `"a folder"`, …). Carried inside the [`io::Error`]s of this module (kind
/// `InvalidInput`), so callers tell it apart by type, not by message.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("is {0}, not a regular file")]
pub struct NotRegular(pub &'static str);

/// The error for a path that exists but is `what` instead of a regular file.
pub fn not_regular(what: &'static str) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, NotRegular(what))
}

/// What the path is instead, when `error` is [`not_regular`]'s.
pub fn not_regular_kind(error: &io::Error) -> Option<&'static str> {
    error
        .get_ref()
        .and_then(|inner| inner.downcast_ref::<NotRegular>())
        .map(|not| not.0)
}

/// Whether `error` is [`not_regular`]'s (the path exists but is a FIFO, folder, …).
pub fn is_not_regular(error: &io::Error) -> bool {
    not_regular_kind(error).is_some()
}

/// Opens `path` for reading when it is a regular file; a FIFO, socket, device or folder is
/// [`not_regular`] without blocking, and with [`Follow::No`] so is a symlink.
pub fn open(path: &Path, follow: Follow) -> io::Result<File> {
    let file = open_nonblocking(path, follow)?;
    let meta = file.metadata()?;
    let kind = meta.file_type();
    if kind.is_file() {
        return Ok(file);
    }
    Err(not_regular(describe(&kind)))
}

/// The whole of a regular file (see [`open`]).
pub fn read(path: &Path, follow: Follow) -> io::Result<Vec<u8>> {
    let mut file = open(path, follow)?;
    let mut bytes = Vec::new();
    file.read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// The whole of a regular file as UTF-8 text (see [`open`]).
pub fn read_to_string(path: &Path, follow: Follow) -> io::Result<String> {
    let bytes = read(path, follow)?;
    String::from_utf8(bytes).map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e))
}

/// Opens `path` for writing, creating it when missing, for a lock file: never through a
/// symlink planted at the path, never blocking on a FIFO, and only when it is (or becomes)
/// a regular file. Its bytes are left as they are.
pub fn open_lock_file(path: &Path) -> io::Result<File> {
    let file = create_nonblocking(path)?;
    let kind = file.metadata()?.file_type();
    if kind.is_file() {
        Ok(file)
    } else {
        Err(not_regular(describe(&kind)))
    }
}

fn describe(kind: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return "a FIFO";
        }
        if kind.is_socket() {
            return "a socket";
        }
        if kind.is_block_device() || kind.is_char_device() {
            return "a device";
        }
    }
    if kind.is_dir() {
        "a folder"
    } else if kind.is_symlink() {
        "a symlink"
    } else {
        "something else"
    }
}

#[cfg(any(target_os = "linux", target_os = "android", target_vendor = "apple"))]
fn open_nonblocking(path: &Path, follow: Follow) -> io::Result<File> {
    use rustix::fs::{Mode, OFlags};
    let mut flags = OFlags::RDONLY | OFlags::NONBLOCK | OFlags::CLOEXEC;
    if follow == Follow::No {
        flags |= OFlags::NOFOLLOW;
    }
    match rustix::fs::open(path, flags, Mode::empty()) {
        Ok(fd) => Ok(File::from(fd)),
        // ELOOP: the last component is a symlink and NOFOLLOW is set.
        Err(rustix::io::Errno::LOOP) if follow == Follow::No => Err(not_regular("a symlink")),
        Err(e) => Err(e.into()),
    }
}

#[cfg(any(target_os = "linux", target_os = "android", target_vendor = "apple"))]
fn create_nonblocking(path: &Path) -> io::Result<File> {
    use rustix::fs::{Mode, OFlags};
    let flags =
        OFlags::WRONLY | OFlags::CREATE | OFlags::NOFOLLOW | OFlags::NONBLOCK | OFlags::CLOEXEC;
    let mode = Mode::RUSR | Mode::WUSR | Mode::RGRP | Mode::ROTH;
    match rustix::fs::open(path, flags, mode) {
        Ok(fd) => Ok(File::from(fd)),
        Err(rustix::io::Errno::LOOP) => Err(not_regular("a symlink")),
        // ENXIO: a FIFO with no reader, opened for writing without blocking.
        Err(rustix::io::Errno::NXIO) => Err(not_regular("a FIFO")),
        Err(e) => Err(e.into()),
    }
}

#[cfg(not(any(target_os = "linux", target_os = "android", target_vendor = "apple")))]
fn create_nonblocking(path: &Path) -> io::Result<File> {
    match std::fs::symlink_metadata(path) {
        Ok(meta) if !meta.is_file() => return Err(not_regular(describe(&meta.file_type()))),
        _ => {}
    }
    File::options()
        .create(true)
        .truncate(false)
        .write(true)
        .open(path)
}

/// Elsewhere: the type is checked before opening (a race a local user would have to win,
/// on platforms cityspec is not tested on).
#[cfg(not(any(target_os = "linux", target_os = "android", target_vendor = "apple")))]
fn open_nonblocking(path: &Path, follow: Follow) -> io::Result<File> {
    let meta = match follow {
        Follow::Yes => std::fs::metadata(path)?,
        Follow::No => std::fs::symlink_metadata(path)?,
    };
    if !meta.is_file() {
        return Err(not_regular(describe(&meta.file_type())));
    }
    File::open(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regular_files_open_and_others_are_refused_at_once() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("a.txt");
        std::fs::write(&file, b"text").unwrap();
        assert_eq!(read(&file, Follow::No).unwrap(), b"text");
        let folder = read(dir.path(), Follow::Yes).unwrap_err();
        assert!(is_not_regular(&folder), "{folder}");
        assert!(folder.to_string().contains("a folder"));
        let missing = read(&dir.path().join("none"), Follow::Yes).unwrap_err();
        assert_eq!(missing.kind(), io::ErrorKind::NotFound);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn a_fifo_is_refused_without_blocking_and_a_symlink_only_when_asked() {
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("fifo");
        rustix::fs::mkfifoat(rustix::fs::CWD, &fifo, rustix::fs::Mode::RUSR).unwrap();
        // Opened blocking, this would wait forever for a writer.
        let error = read(&fifo, Follow::Yes).unwrap_err();
        assert!(error.to_string().contains("a FIFO"), "{error}");
        let target = dir.path().join("target.txt");
        std::fs::write(&target, b"real").unwrap();
        let link = dir.path().join("link.txt");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        assert_eq!(read(&link, Follow::Yes).unwrap(), b"real");
        let refused = read(&link, Follow::No).unwrap_err();
        assert!(is_not_regular(&refused), "{refused}");
        assert!(refused.to_string().contains("a symlink"));
        // A lock file is opened through neither, and its target is never created.
        let planted = dir.path().join("planted.lock");
        std::os::unix::fs::symlink(dir.path().join("outside"), &planted).unwrap();
        let refused = open_lock_file(&planted).unwrap_err();
        assert!(refused.to_string().contains("a symlink"), "{refused}");
        assert!(!dir.path().join("outside").exists());
        let refused = open_lock_file(&fifo).unwrap_err();
        assert!(refused.to_string().contains("a FIFO"), "{refused}");
        let lock = dir.path().join("real.lock");
        open_lock_file(&lock).unwrap();
        open_lock_file(&lock).unwrap();
        assert!(lock.is_file());
    }
}
