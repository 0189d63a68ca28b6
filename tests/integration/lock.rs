//! Issue 12: `cityspec lock` and `cityspec build --locked` (exit code 3).

use crate::common;

use std::fs;
use std::path::Path;

use common::{Workspace, cityspec, stderr, tree};

fn flip_one_byte(path: &Path) -> Vec<u8> {
    let mut bytes = fs::read(path).unwrap();
    let middle = bytes.len() / 2;
    bytes[middle] ^= 0x01;
    fs::write(path, &bytes).unwrap();
    bytes
}

/// The object file of `sha256` in the workspace's default cache.
fn object(ws: &Workspace, sha256: &str) -> std::path::PathBuf {
    ws.path()
        .join(".cityspec-cache/objects")
        .join(&sha256[..2])
        .join(sha256)
}

#[test]
fn locked_builds_fail_with_3_on_a_missing_lock_and_on_every_changed_artifact() {
    let ws = Workspace::with_spec("mirrored");
    let spec = "specs/mirrored.toml";

    let no_lock = cityspec(&ws, &["build", "--locked", spec]);
    assert_eq!(no_lock.status.code(), Some(3), "{}", stderr(&no_lock));
    assert!(
        stderr(&no_lock).contains("no lock file"),
        "{}",
        stderr(&no_lock)
    );
    assert!(
        !ws.path().join("out/mirrored").exists(),
        "a failed --locked wrote"
    );

    let lock = cityspec(&ws, &["lock", spec]);
    assert!(lock.status.success(), "{}", stderr(&lock));
    let lock_file = ws.path().join("specs/mirrored.lock");
    let text = fs::read_to_string(&lock_file).unwrap();
    assert!(text.contains(&format!("cityspec {}\n", env!("CARGO_PKG_VERSION"))));
    assert!(text.contains(" plan.json\n"), "{text}");
    // The same build locks to the same bytes.
    assert!(cityspec(&ws, &["lock", spec]).status.success());
    assert_eq!(fs::read_to_string(&lock_file).unwrap(), text);
    let ok = cityspec(&ws, &["build", "--locked", spec]);
    assert_eq!(ok.status.code(), Some(0), "{}", stderr(&ok));

    let manifest_file = ws.path().join("out/mirrored/manifest.json");
    let manifest =
        cityspec::driver::Manifest::from_bytes(&fs::read(&manifest_file).unwrap()).unwrap();
    let find = |path: &str| manifest.artifacts.iter().find(|a| a.path == path).unwrap();

    // One byte flipped in a cached object, the output folder gone: the cache sees the
    // damage, the stage reruns, and the artifact is again what the lock says.
    flip_one_byte(&object(&ws, &find("plan.png").sha256));
    fs::remove_dir_all(ws.path().join("out/mirrored")).unwrap();
    let repaired = cityspec(&ws, &["build", "--locked", spec]);
    assert_eq!(repaired.status.code(), Some(0), "{}", stderr(&repaired));
    assert!(stderr(&repaired).contains("damaged cache entry rebuilt"));

    // One byte flipped in an output file: the build does not trust the folder and
    // writes the locked bytes back.
    let plan_json = ws.path().join("out/mirrored/plan.json");
    let good = fs::read(&plan_json).unwrap();
    flip_one_byte(&plan_json);
    let rewritten = cityspec(&ws, &["build", "--locked", spec]);
    assert_eq!(rewritten.status.code(), Some(0), "{}", stderr(&rewritten));
    assert_eq!(fs::read(&plan_json).unwrap(), good);

    // A cache that holds other bytes for two artifacts, consistently (each flipped object
    // stored under its own new hash and its entry pointed at it, as a poisoned shared
    // cache or a stage changed without a VERSION bump would): only the lock can tell.
    let before = tree(&ws.path().join("out/mirrored"));
    for name in ["plan.json", "layout.png"] {
        let artifact = find(name);
        let mut bytes = fs::read(object(&ws, &artifact.sha256)).unwrap();
        let middle = bytes.len() / 2;
        bytes[middle] ^= 0x01;
        let sha = cityspec::hash::sha256_hex(&bytes);
        let path = object(&ws, &sha);
        fs::create_dir_all(path.parent().unwrap()).unwrap();
        fs::write(&path, &bytes).unwrap();
        let entry_file = ws
            .path()
            .join(".cityspec-cache/entries")
            .join(format!("{}.json", artifact.key));
        let mut entry: serde_json::Value =
            serde_json::from_slice(&fs::read(&entry_file).unwrap()).unwrap();
        entry["outputs"][name] = serde_json::json!({ "sha256": sha, "bytes": bytes.len() });
        fs::write(&entry_file, serde_json::to_vec(&entry).unwrap()).unwrap();
    }
    let caught = cityspec(&ws, &["build", "--locked", spec]);
    let text = stderr(&caught);
    assert_eq!(caught.status.code(), Some(3), "{text}");
    assert!(text.contains("plan.json: changed"), "{text}");
    assert!(text.contains("layout.png: changed"), "{text}");
    assert_eq!(
        tree(&ws.path().join("out/mirrored")),
        before,
        "a failed --locked build touched the output folder"
    );
}
