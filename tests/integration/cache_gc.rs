//! Issue 12: `cityspec cache gc` keeps what the given specs (or lock files) need and removes
//! the rest, never anything a running build may have just written.

use crate::common;

use std::fs;
use std::time::{Duration, SystemTime};

use cityspec::driver::{self, GcOptions};
use common::{SpecEdit, Workspace};

fn ran(report: &driver::BuildReport) -> Vec<&'static str> {
    report.ran().map(|s| s.stage).collect()
}

#[test]
fn gc_keeps_the_given_specs_and_removes_the_rest() {
    let ws = Workspace::with_spec("mirrored");
    let small = ws.path().join("specs/small.toml");
    fs::write(&small, include_str!("../fixtures/shards.toml")).unwrap();
    // Another city (another seed and name): nothing in common with the first but facades.
    let other_spec = ws.path().join("specs/other.toml");
    let other_text = SpecEdit::parse("shards.toml", include_str!("../fixtures/shards.toml"))
        .set("name", "other")
        .set("seed", 12)
        .set("cameras[0].frames", 3)
        .text();
    fs::write(&other_spec, other_text).unwrap();
    let options = ws.options();
    driver::build(&small, &options).unwrap();
    let other = driver::build(&other_spec, &options).unwrap();
    let object = |sha: &str| ws.cache().join("objects").join(&sha[..2]).join(sha);
    let manifest = |dir: &std::path::Path| {
        driver::Manifest::from_bytes(&fs::read(dir.join("manifest.json")).unwrap()).unwrap()
    };
    let other_manifest = manifest(&other.out_dir);

    // Temporaries of killed builds: a stale one goes, a young one (a running build's) stays.
    let stale = ws.cache().join("objects/.stream.cityspec-tmp-1-1");
    let young = ws.cache().join("objects/.stream.cityspec-tmp-1-2");
    fs::write(&stale, b"half").unwrap();
    fs::write(&young, b"half").unwrap();
    let two_hours_ago = SystemTime::now() - Duration::from_secs(7200);
    fs::File::options()
        .append(true)
        .open(&stale)
        .unwrap()
        .set_modified(two_hours_ago)
        .unwrap();

    let gc = |specs: &[std::path::PathBuf], grace: u64, max_age: Option<u64>| {
        driver::gc(
            specs,
            &GcOptions {
                cache_dir: ws.cache(),
                max_size: None,
                max_age: max_age.map(Duration::from_secs),
                grace: Duration::from_secs(grace),
            },
        )
        .unwrap()
    };
    // Within the grace period nothing but the stale temporary goes.
    let safe = gc(std::slice::from_ref(&small), 3600, None);
    assert_eq!(
        (
            safe.removed_entries,
            safe.removed_objects,
            safe.removed_temporaries
        ),
        (0, 0, 1)
    );
    assert!(!stale.exists() && young.exists());
    // With --max-age, young unneeded files stay too.
    let aged = gc(std::slice::from_ref(&small), 0, Some(86_400));
    assert_eq!((aged.removed_entries, aged.removed_objects), (0, 0));

    // The other spec's lock file keeps its artifacts' objects, not its entries.
    fs::write(
        ws.path().join("specs/other.lock"),
        format!(
            "cityspec {}\nname other\n{} {} plan.json\n",
            env!("CARGO_PKG_VERSION"),
            other_manifest.artifacts[0].sha256,
            other_manifest.artifacts[0].bytes
        ),
    )
    .unwrap();
    let report = gc(
        &[small.clone(), ws.path().join("specs/other.lock")],
        0,
        None,
    );
    assert!(
        report.removed_entries > 0 && report.removed_objects > 0,
        "{report:?}"
    );
    assert!(object(&other_manifest.artifacts[0].sha256).exists());
    assert!(!object(&other_manifest.artifacts[1].sha256).exists());

    // The kept spec builds from the cache alone, into a new folder; the other builds again.
    let fresh = driver::BuildOptions {
        out_root: ws.path().join("out2"),
        ..options.clone()
    };
    assert!(ran(&driver::build(&small, &fresh).unwrap()).is_empty());
    assert!(!ran(&driver::build(&other_spec, &fresh).unwrap()).is_empty());
    // A shard's chunks are needed too: after a gc, a merge of a sharded build renders
    // nothing. (Every chunk and plan of `small` is in the cache from its build.)
    let chunk_keys = fs::read_dir(ws.cache().join("entries")).unwrap().count();
    let again = gc(&[small.clone(), other_spec.clone()], 0, None);
    assert_eq!(
        (again.removed_entries, again.removed_objects),
        (0, 0),
        "{again:?}"
    );
    assert_eq!(
        fs::read_dir(ws.cache().join("entries")).unwrap().count(),
        chunk_keys
    );
}
