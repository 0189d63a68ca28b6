//! Input files: a path a spec names + a size cap → its bytes, or why not.
//!
//! Every file cityspec reads goes through [`read_capped`]: it must be a regular file (a
//! device such as `/dev/zero`, a pipe or a socket is refused before a byte is read) and no
//! larger than the cap for its kind, so no input can make a build read until memory runs
//! out. Symlinks to regular files are followed: a user may link a model in.

use std::fs::{self, File};
use std::io::{ErrorKind, Read};
use std::path::Path;

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

/// Why `path` cannot be read as a regular file of at most `cap` bytes, completing
/// "expected …, found {why}"; Ok with its size otherwise.
pub fn check_file(path: &Path, cap: u64) -> Result<u64, String> {
    let meta = fs::metadata(path).map_err(|e| unreadable(&e))?;
    if meta.is_dir() {
        return Err("a folder, not a file".to_owned());
    }
    if !meta.is_file() {
        return Err("not a regular file (a device, pipe or socket)".to_owned());
    }
    if meta.len() > cap {
        return Err(too_large(meta.len(), cap));
    }
    Ok(meta.len())
}

/// The bytes of the regular file `path`, refused (see [`check_file`]) when it is not a
/// regular file or holds more than `cap` bytes.
pub fn read_capped(path: &Path, cap: u64) -> Result<Vec<u8>, String> {
    let size = check_file(path, cap)?;
    let mut bytes = Vec::with_capacity(usize::try_from(size).unwrap_or(0));
    File::open(path)
        .and_then(|f| f.take(cap + 1).read_to_end(&mut bytes))
        .map_err(|e| unreadable(&e))?;
    // It may have grown since it was measured.
    if bytes.len() as u64 > cap {
        return Err(too_large(bytes.len() as u64, cap));
    }
    Ok(bytes)
}

/// [`read_capped`] as UTF-8 text.
pub fn read_text_capped(path: &Path, cap: u64) -> Result<String, String> {
    String::from_utf8(read_capped(path, cap)?).map_err(|e| {
        format!(
            "a file that is not UTF-8 text (byte {})",
            e.utf8_error().valid_up_to()
        )
    })
}

fn unreadable(e: &std::io::Error) -> String {
    match e.kind() {
        ErrorKind::NotFound => "no such file".to_owned(),
        ErrorKind::PermissionDenied => "a file it may not read".to_owned(),
        _ => format!("an unreadable file ({e})"),
    }
}

fn too_large(size: u64, cap: u64) -> String {
    format!("a file of {size} bytes, over the limit of {cap} bytes for this kind of input")
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
            read_capped(&small, 4).unwrap_err(),
            "a file of 5 bytes, over the limit of 4 bytes for this kind of input"
        );
        assert_eq!(
            read_capped(dir.path(), 9).unwrap_err(),
            "a folder, not a file"
        );
        assert_eq!(
            read_capped(&dir.path().join("b"), 9).unwrap_err(),
            "no such file"
        );
        let started = std::time::Instant::now();
        assert_eq!(
            read_capped(Path::new("/dev/zero"), MAX_MODEL_BYTES).unwrap_err(),
            "not a regular file (a device, pipe or socket)"
        );
        assert!(started.elapsed().as_secs() < 1);
        std::fs::write(&small, [0xff, 0xfe]).unwrap();
        assert!(
            read_text_capped(&small, 9)
                .unwrap_err()
                .contains("not UTF-8")
        );
    }
}
