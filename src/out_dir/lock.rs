//! `spec.lock`: the artifacts a spec must build, for `cityspec build --locked` in CI.
//!
//! `cityspec lock day.toml` builds the spec and writes `day.lock` beside it: the cityspec
//! version, the spec's name, and every artifact's SHA-256, size and path, one per line,
//! sorted by path (a text file that diffs well and is the same bytes on every machine).
//! `cityspec build --locked` then builds as usual but, before it touches the output folder,
//! compares what it made with the lock, and fails with exit code 3 listing every
//! difference (changed, missing and new artifacts, another cityspec version), or when the
//! lock is missing or unreadable.
//!
//! ```text
//! # cityspec lock: `cityspec build --locked` makes exactly these artifacts or fails.
//! cityspec 0.1.0
//! name day
//! 3f2a…e1 402113 city.glb
//! ```

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use super::Manifest;
use crate::driver::BuildError;

const HEADER: &str =
    "# cityspec lock: `cityspec build --locked` makes exactly these artifacts or fails.\n";

/// The lock file of the spec at `spec`: the same name with the extension `.lock`.
pub fn lock_path(spec: &Path) -> PathBuf {
    spec.with_extension("lock")
}

/// The lock file's text for a build's manifest.
pub fn render(manifest: &Manifest) -> String {
    let mut text = format!(
        "{HEADER}cityspec {}\nname {}\n",
        env!("CARGO_PKG_VERSION"),
        manifest.name
    );
    let mut artifacts: Vec<_> = manifest.artifacts.iter().collect();
    artifacts.sort_by(|a, b| a.path.cmp(&b.path));
    for a in artifacts {
        text.push_str(&format!("{} {} {}\n", a.sha256, a.bytes, a.path));
    }
    text
}

/// `--locked`: the spec's lock file agrees with `manifest`, or every difference.
pub fn check(spec: &Path, manifest: &Manifest) -> Result<(), BuildError> {
    let lock = lock_path(spec);
    let read = crate::regular_file::read_to_string(&lock, crate::regular_file::Follow::Yes);
    let differences = match read {
        Ok(text) => differences(&text, manifest),
        Err(e) => vec![format!(
            "no lock file ({e}): run `cityspec lock {}` and commit it",
            spec.display()
        )],
    };
    if differences.is_empty() {
        Ok(())
    } else {
        Err(BuildError::Locked { lock, differences })
    }
}

/// The SHA-256 of every artifact a lock file lists (for `cache gc`).
pub fn hashes(text: &str) -> Result<Vec<String>, String> {
    Ok(parse(text)?
        .artifacts
        .into_values()
        .map(|(sha, _)| sha)
        .collect())
}

/// What a lock file records.
#[derive(Debug, PartialEq, Eq)]
struct Lock {
    version: String,
    name: String,
    /// path → (sha256, bytes).
    artifacts: BTreeMap<String, (String, u64)>,
}

fn parse(text: &str) -> Result<Lock, String> {
    let mut version = None;
    let mut name = None;
    let mut artifacts = BTreeMap::new();
    for (n, line) in text.lines().enumerate() {
        let bad = || {
            format!(
                "line {}: expected `SHA256 BYTES PATH`, found {line:?}",
                n + 1
            )
        };
        if line.starts_with('#') || line.trim().is_empty() {
            continue;
        }
        if let Some(v) = line.strip_prefix("cityspec ") {
            version = Some(v.to_owned());
        } else if let Some(v) = line.strip_prefix("name ") {
            name = Some(v.to_owned());
        } else {
            let mut parts = line.splitn(3, ' ');
            let (Some(sha), Some(bytes), Some(path)) = (parts.next(), parts.next(), parts.next())
            else {
                return Err(bad());
            };
            let valid = sha.len() == 64 && sha.bytes().all(|b| b.is_ascii_hexdigit());
            let bytes: u64 = bytes.parse().map_err(|_| bad())?;
            if !valid {
                return Err(bad());
            }
            artifacts.insert(path.to_owned(), (sha.to_owned(), bytes));
        }
    }
    Ok(Lock {
        version: version.ok_or("no `cityspec VERSION` line")?,
        name: name.ok_or("no `name NAME` line")?,
        artifacts,
    })
}

/// Every difference between the lock file's text and a build's manifest, one line each
/// (empty when they agree).
pub fn differences(lock_text: &str, manifest: &Manifest) -> Vec<String> {
    let lock = match parse(lock_text) {
        Ok(lock) => lock,
        Err(why) => return vec![format!("the lock file does not parse: {why}")],
    };
    let mut out = Vec::new();
    let ours = env!("CARGO_PKG_VERSION");
    if lock.version != ours {
        out.push(format!(
            "locked with cityspec {}, building with {ours}",
            lock.version
        ));
    }
    if lock.name != manifest.name {
        out.push(format!(
            "locked for spec {:?}, building {:?}",
            lock.name, manifest.name
        ));
    }
    let built: BTreeMap<&str, (&str, u64)> = manifest
        .artifacts
        .iter()
        .map(|a| (a.path.as_str(), (a.sha256.as_str(), a.bytes)))
        .collect();
    for (path, (sha, bytes)) in &lock.artifacts {
        match built.get(path.as_str()) {
            None => out.push(format!("{path}: locked, not built")),
            Some((s, b)) if *s != sha || *b != *bytes => out.push(format!(
                "{path}: changed: locked {} ({bytes} bytes), built {} ({b} bytes)",
                &sha[..12],
                &s[..s.len().min(12)]
            )),
            Some(_) => {}
        }
    }
    for path in built.keys() {
        if !lock.artifacts.contains_key(*path) {
            out.push(format!("{path}: built, not in the lock"));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::out_dir::Artifact;

    fn manifest(files: &[(&str, &str, u64)]) -> Manifest {
        Manifest {
            name: "day".into(),
            artifacts: files
                .iter()
                .map(|(path, sha, bytes)| Artifact {
                    path: path.to_string(),
                    sha256: sha.repeat(64 / sha.len()),
                    bytes: *bytes,
                    stage: "plan".into(),
                    key: "k".into(),
                })
                .collect(),
        }
    }

    #[test]
    fn a_lock_of_the_same_build_agrees_and_is_stable_text() {
        let m = manifest(&[("plan.json", "ab", 10), ("frames/a b/coco.json", "cd", 3)]);
        let text = render(&m);
        assert_eq!(text, render(&m));
        assert!(text.ends_with(&format!("{} 10 plan.json\n", "ab".repeat(32))));
        assert!(differences(&text, &m).is_empty());
        assert_eq!(
            lock_path(Path::new("specs/day.toml")),
            Path::new("specs/day.lock")
        );
    }

    #[test]
    fn every_difference_is_listed() {
        let locked = render(&manifest(&[
            ("a.png", "aa", 1),
            ("b.png", "bb", 2),
            ("c.png", "cc", 3),
        ]));
        let built = manifest(&[("a.png", "a0", 1), ("b.png", "bb", 3), ("d.png", "dd", 4)]);
        let found = differences(&locked, &built);
        assert_eq!(found.len(), 4, "{found:?}");
        assert!(found[0].starts_with("a.png: changed"));
        assert!(found[1].starts_with("b.png: changed"));
        assert_eq!(found[2], "c.png: locked, not built");
        assert_eq!(found[3], "d.png: built, not in the lock");
        let old = locked.replace(env!("CARGO_PKG_VERSION"), "0.0.1");
        assert!(differences(&old, &built)[0].contains("cityspec 0.0.1"));
        assert!(differences("garbage", &built)[0].contains("does not parse"));
    }
}
