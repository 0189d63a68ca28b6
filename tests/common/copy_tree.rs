//! Copying a folder tree, for the integration tests and the benchmarks (which include this
//! file by path: they cannot share a module otherwise).

use std::fs;
use std::path::Path;

/// Copies every file below `from` into `to`, creating folders.
pub fn copy_tree(from: &Path, to: &Path) {
    fs::create_dir_all(to).unwrap();
    for entry in fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.path().is_dir() {
            copy_tree(&entry.path(), &target);
        } else {
            fs::copy(entry.path(), target).unwrap();
        }
    }
}
