//! Input files: a path a spec names + a size cap → its bytes, or why not.
//!
//! Every file cityspec reads from the user's tree goes through [`read_capped`] (or
//! [`open_capped`]), which opens it through [`crate::regular_file`]: without blocking, and
//! only when the open descriptor is a regular file (a FIFO, a device such as `/dev/zero`, a
//! socket or a folder is refused before a byte is read, and a FIFO never hangs the build
//! waiting for a writer). Its size is then checked against the cap for its kind, so no
//! input can make a build read until memory runs out. Symlinks to regular files are
//! followed: a user may link a model in.

use std::fs::File;
use std::io::{self, ErrorKind, Read};
use std::path::Path;

use crate::regular_file::{self, Follow};

/// Largest spec file.
pub const MAX_SPEC_BYTES: u64 = 1 << 20;
/// Largest layout image file (a 16384 × 4096 RGBA PNG stored without compression).
pub const MAX_IMAGE_BYTES: u64 = 256 << 20;
/// Largest OBJ model.
pub const MAX_MODEL_BYTES: u64 = 256 << 20;
/// Largest MTL file.
pub const MAX_MTL_BYTES: u64 = 16 << 20;
/// Largest texture of a model, and largest file of a facade folder (photo, XML, mask).
pub const MAX_TEXTURE_BYTES: u64 = 64 << 20;
/// Largest facade floors file.
pub const MAX_FLOORS_BYTES: u64 = 4 << 20;

/// Why a file a spec names cannot be read. Its text completes "expected …, found {it}".
#[derive(Debug, thiserror::Error)]
pub enum InputFileError {
    #[error("no such file")]
    NotFound,
    #[error("a file it may not read")]
    PermissionDenied,
    #[error("an unreadable file ({0})")]
    Unreadable(#[source] io::Error),
    /// A FIFO, device, socket or folder: which one ("a FIFO").
    #[error("{0}, not a regular file")]
    NotRegular(&'static str),
    #[error("a file of {size} bytes, over the limit of {cap} bytes for this kind of input")]
    TooLarge { size: u64, cap: u64 },
    #[error("a file that is not UTF-8 text (byte {valid_up_to})")]
    NotUtf8 { valid_up_to: usize },
}

impl InputFileError {
    /// The error of a failed open, read or metadata call.
    pub fn of_io(e: io::Error) -> InputFileError {
        if let Some(what) = regular_file::not_regular_kind(&e) {
            return InputFileError::NotRegular(what);
        }
        match e.kind() {
            ErrorKind::NotFound => InputFileError::NotFound,
            ErrorKind::PermissionDenied => InputFileError::PermissionDenied,
            _ => InputFileError::Unreadable(e),
        }
    }
}

/// `path` opened for reading (see [`crate::regular_file::open`]) with its size, refused when
/// it is not a regular file or holds more than `cap` bytes.
pub fn open_capped(path: &Path, cap: u64) -> Result<(File, u64), InputFileError> {
    let file = regular_file::open(path, Follow::Yes).map_err(InputFileError::of_io)?;
    let size = file.metadata().map_err(InputFileError::of_io)?.len();
    if size > cap {
        return Err(InputFileError::TooLarge { size, cap });
    }
    Ok((file, size))
}

/// Why `path` cannot be read as a regular file of at most `cap` bytes; Ok with its size
/// otherwise. It is opened (without blocking) to tell, so what passes here is what
/// [`read_capped`] would open.
pub fn check_file(path: &Path, cap: u64) -> Result<u64, InputFileError> {
    open_capped(path, cap).map(|(_, size)| size)
}

/// The bytes of the regular file `path`, refused (see [`open_capped`]) when it is not a
/// regular file or holds more than `cap` bytes.
pub fn read_capped(path: &Path, cap: u64) -> Result<Vec<u8>, InputFileError> {
    let (file, size) = open_capped(path, cap)?;
    let mut bytes = Vec::with_capacity(usize::try_from(size).unwrap_or(0));
    file.take(cap + 1)
        .read_to_end(&mut bytes)
        .map_err(InputFileError::of_io)?;
    // It may have grown since it was measured.
    if bytes.len() as u64 > cap {
        return Err(InputFileError::TooLarge {
            size: bytes.len() as u64,
            cap,
        });
    }
    Ok(bytes)
}

/// [`read_capped`] as UTF-8 text.
pub fn read_text_capped(path: &Path, cap: u64) -> Result<String, InputFileError> {
    String::from_utf8(read_capped(path, cap)?).map_err(|e| InputFileError::NotUtf8 {
        valid_up_to: e.utf8_error().valid_up_to(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn devices_folders_and_oversized_files_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let small = dir.path().join("a.txt");
        std::fs::write(&small, b"hello").unwrap();
        assert_eq!(read_capped(&small, 5).unwrap(), b"hello");
        assert_eq!(
            read_capped(&small, 4).unwrap_err().to_string(),
            "a file of 5 bytes, over the limit of 4 bytes for this kind of input"
        );
        assert_eq!(
            read_capped(dir.path(), 9).unwrap_err().to_string(),
            "a folder, not a regular file"
        );
        assert_eq!(
            read_capped(&dir.path().join("b"), 9)
                .unwrap_err()
                .to_string(),
            "no such file"
        );
        let started = std::time::Instant::now();
        assert_eq!(
            read_capped(Path::new("/dev/zero"), MAX_MODEL_BYTES)
                .unwrap_err()
                .to_string(),
            "a device, not a regular file"
        );
        assert!(started.elapsed().as_secs() < 1);
        #[cfg(target_os = "linux")]
        {
            // Opened blocking, a FIFO with no writer would hang the read forever.
            let fifo = dir.path().join("fifo");
            rustix::fs::mkfifoat(rustix::fs::CWD, &fifo, rustix::fs::Mode::RUSR).unwrap();
            let started = std::time::Instant::now();
            assert_eq!(
                read_capped(&fifo, 9).unwrap_err().to_string(),
                "a FIFO, not a regular file"
            );
            assert_eq!(
                check_file(&fifo, 9).unwrap_err().to_string(),
                "a FIFO, not a regular file"
            );
            assert!(started.elapsed().as_secs() < 1);
        }
        std::fs::write(&small, [0xff, 0xfe]).unwrap();
        assert!(
            read_text_capped(&small, 9)
                .unwrap_err()
                .to_string()
                .contains("not UTF-8")
        );
    }
}
