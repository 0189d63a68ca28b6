//! `cityspec pack`: a spec and every file it reads in one tar, which builds the same
//! stages once unpacked anywhere (the Kubernetes jobs of `deploy/k8s/` rely on it).

use std::fs;
use std::path::Path;
use std::process::Command;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

fn cityspec(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_cityspec"))
        .current_dir(ROOT)
        .args(args)
        .output()
        .unwrap()
}

/// Every stage's key of `spec`, as `cityspec explain --json` gives them: the keys hash
/// every input file's bytes, so equal keys mean every file arrived whole.
fn keys(spec: &Path, cache: &Path) -> Vec<String> {
    let run = cityspec(&[
        "explain",
        "--json",
        "--cache",
        cache.to_str().unwrap(),
        spec.to_str().unwrap(),
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let explained: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    explained[0]["stages"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["key"].as_str().unwrap().to_owned())
        .collect()
}

#[test]
fn a_packed_spec_unpacked_elsewhere_reads_the_same_files() {
    let dir = tempfile::tempdir().unwrap();
    // A drawn layout, a facade folder with a floors file, a model with MTL and texture,
    // and a variant that extends another spec.
    for name in ["drawn", "cmp", "day", "night"] {
        let spec = Path::new(ROOT).join(format!("specs/{name}.toml"));
        let tar = dir.path().join(format!("{name}.tar"));
        let run = cityspec(&["pack", spec.to_str().unwrap(), "-o", tar.to_str().unwrap()]);
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let bytes = fs::read(&tar).unwrap();
        // The same bytes every time.
        let again = dir.path().join(format!("{name}-again.tar"));
        cityspec(&[
            "pack",
            spec.to_str().unwrap(),
            "-o",
            again.to_str().unwrap(),
        ]);
        assert_eq!(bytes, fs::read(&again).unwrap(), "{name}");

        let unpacked = dir.path().join(name);
        tar::Archive::new(&bytes[..]).unpack(&unpacked).unwrap();
        let inside = fs::read_to_string(unpacked.join("CITYSPEC_SPEC")).unwrap();
        let moved = unpacked.join(inside.trim_end());
        assert!(moved.ends_with(format!("specs/{name}.toml")), "{moved:?}");
        let cache = dir.path().join("no-cache");
        assert_eq!(keys(&spec, &cache), keys(&moved, &cache), "{name}");
    }
}

#[test]
fn packing_a_spec_whose_file_is_missing_names_the_file_and_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("spec.toml");
    fs::write(
        &spec,
        "version = 1\nname = 'x'\n[layout]\nimage = 'missing.png'\n",
    )
    .unwrap();
    let run = cityspec(&[
        "pack",
        spec.to_str().unwrap(),
        "-o",
        dir.path().join("x.tar").to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("missing.png"), "{stderr}");
    assert!(!dir.path().join("x.tar").exists());
}
