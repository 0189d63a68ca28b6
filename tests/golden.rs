//! Golden digests: builds one small city and pins the SHA-256 of every stage's output next
//! to the `VERSION` constants in that stage's key (`tests/golden/digests.toml`).
//!
//! The cache trusts a stage's key to name its output: a change of output bytes without a
//! `VERSION` bump would hand every user stale cache entries. This test fails when a
//! stage's bytes change while its versions stay, and names the constant to bump; it also
//! fails when a version moved but the pins were not renewed. `CITYSPEC_BLESS=1 cargo test
//! --test golden` rewrites the pins (after the bump).
//!
//! A digest says only "different": the golden city's `plan.json` and its street camera's
//! `coco.json` are also kept whole as `insta` snapshots (`tests/snapshots/golden__*.snap`),
//! so a change shows as a diff. Plain `cargo test` checks them against the committed files
//! and fails on any difference, with the diff; no `cargo-insta` is needed. After a wanted
//! change, rewrite them with `INSTA_UPDATE=always cargo test --test golden` (or review each
//! with `cargo insta review`), beside the `CITYSPEC_BLESS=1` above, and commit both.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;
use std::sync::LazyLock;

use cityspec::driver::{self, BuildOptions, Cache, Stage, StageStatus};

const PINS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/golden/digests.toml");
const SPEC: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/golden/city.toml");
const BLESS: &str = "CITYSPEC_BLESS=1 cargo test --test golden";

/// The one pinned frame: small, in the sun, shadowed.
const FRAME: &str = "frames/street/rgb/000000.png";

/// A pinned output: its name, the outputs it is made from, its key's `VERSION`s.
type Pinned = (String, Vec<String>, Vec<(&'static str, u32)>);

/// Each pinned output, the stages it reads (its digest may change because of theirs), and
/// the `VERSION` constants in its key besides the driver's `codec::VERSION`: the stage
/// table's declarations, and the one pinned frame.
fn table() -> Vec<Pinned> {
    let mut table: Vec<Pinned> = Stage::ALL
        .into_iter()
        .map(|stage| {
            let declared = stage.declaration();
            let name = match stage {
                Stage::Frames => "frames street".to_owned(),
                _ => declared.name.to_owned(),
            };
            let reads = declared.reads.iter().map(|s| s.name().to_owned()).collect();
            (name, reads, declared.versions.to_vec())
        })
        .collect();
    // The frame's pixels: the frames' versions but annotate's, which draws none.
    let frames = Stage::Frames.declaration();
    table.push((
        "frame".to_owned(),
        frames.reads.iter().map(|s| s.name().to_owned()).collect(),
        frames
            .versions
            .iter()
            .copied()
            .filter(|(name, _)| *name != "annotate::VERSION")
            .collect(),
    ));
    table
}

/// "render::VERSION 3, cameras::VERSION 3, codec::VERSION 2".
fn versions_text(versions: &[(&str, u32)]) -> String {
    let mut all: Vec<String> = versions.iter().map(|(n, v)| format!("{n} {v}")).collect();
    all.push(format!("codec::VERSION {}", driver::CODEC_VERSION));
    all.join(", ")
}

/// SHA-256 over a stage's outputs: each name and its object's SHA-256, in name order.
fn digest(outputs: &BTreeMap<String, String>) -> String {
    let mut text = String::new();
    for (name, sha) in outputs {
        writeln!(text, "{name} {sha}").unwrap();
    }
    cityspec::hash::sha256_hex(text.as_bytes())
}

/// What the tests read of one build of the golden city.
struct Golden {
    /// Each pinned output's digest.
    digests: BTreeMap<String, String>,
    /// `plan.json`, as written.
    plan: String,
    /// The street camera's `coco.json`.
    coco: String,
}

/// The golden city, built once for all the tests here.
static GOLDEN: LazyLock<Golden> = LazyLock::new(build_golden);

/// Builds the golden city and reads each pinned output's digest and the snapshotted files.
fn build_golden() -> Golden {
    let dir = tempfile::tempdir().unwrap();
    let options = BuildOptions {
        out_root: dir.path().join("out"),
        cache_dir: dir.path().join("cache"),
        ..BuildOptions::default()
    };
    let report = driver::build(Path::new(SPEC), &options).unwrap();
    let cache = Cache::new(&options.cache_dir);
    let mut digests = BTreeMap::new();
    for run in report.stages.iter().filter(|r| !r.key.is_empty()) {
        assert_eq!(
            run.status,
            StageStatus::Ran,
            "a cold cache runs every stage"
        );
        let entry = cache
            .entry(&run.key)
            .expect("every stage that ran has an entry");
        let outputs: BTreeMap<String, String> = entry
            .outputs
            .iter()
            .map(|(name, object)| (name.clone(), object.sha256.clone()))
            .collect();
        let name = match &run.camera {
            Some(camera) => format!("{} {camera}", run.stage),
            None => run.stage.to_owned(),
        };
        if let Some(frame) = outputs.get(FRAME) {
            digests.insert("frame".to_owned(), frame.clone());
        }
        digests.insert(name, digest(&outputs));
    }
    let read = |name: &str| std::fs::read_to_string(report.out_dir.join(name)).unwrap();
    Golden {
        digests,
        plan: read("plan.json"),
        coco: read("frames/street/coco.json"),
    }
}

#[test]
fn the_plan_is_as_snapshotted() {
    insta::assert_snapshot!("plan.json", GOLDEN.plan);
}

#[test]
fn the_street_cameras_coco_is_as_snapshotted() {
    // Written one record a line; pretty-printed here, so a diff names the field that
    // changed. Every byte is pinned by the digests anyway.
    let coco: serde_json::Value = serde_json::from_str(&GOLDEN.coco).unwrap();
    insta::assert_snapshot!("coco.json", serde_json::to_string_pretty(&coco).unwrap());
}

#[test]
fn every_stage_output_is_pinned_to_its_versions() {
    let digests = &GOLDEN.digests;
    let table = table();
    for (stage, _, _) in &table {
        assert!(
            digests.contains_key(stage),
            "the golden city has no {stage} output"
        );
    }
    if std::env::var_os("CITYSPEC_BLESS").is_some() {
        let mut text = String::from(
            "# Pinned by tests/golden.rs: each stage's output digest for tests/golden/city.toml\n\
             # and the VERSION constants in its key. Rewrite with CITYSPEC_BLESS=1 cargo test\n\
             # --test golden, only after bumping the VERSION of the stage whose bytes changed.\n",
        );
        for (stage, _, versions) in &table {
            write!(
                text,
                "\n[{stage:?}]\nversions = {:?}\ndigest = {:?}\n",
                versions_text(versions),
                digests[stage]
            )
            .unwrap();
        }
        std::fs::write(PINS, text).unwrap();
        return;
    }
    let pins: toml::Table = std::fs::read_to_string(PINS)
        .unwrap_or_else(|e| panic!("cannot read {PINS} ({e}): create it with {BLESS}"))
        .parse()
        .unwrap();
    let pinned = |stage: &str, field: &str| -> Option<String> {
        Some(pins.get(stage)?.get(field)?.as_str()?.to_owned())
    };
    let changed = |stage: &str| pinned(stage, "digest").as_deref() != Some(&digests[stage]);
    let mut problems = Vec::new();
    // Per stage changed by its own code: the constants that could cover it.
    let mut culprits: Vec<Vec<&str>> = Vec::new();
    for (stage, inputs, versions) in &table {
        let now = versions_text(versions);
        let Some(was) = pinned(stage, "versions") else {
            problems.push(format!("stage `{stage}` has no pin: run {BLESS}"));
            continue;
        };
        if was != now {
            problems.push(format!(
                "stage `{stage}`: its versions are now [{now}] but the pins hold [{was}]: \
                 run {BLESS} to pin its new output"
            ));
        } else if changed(stage) && !inputs.iter().any(|input| changed(input)) {
            // Its inputs are as pinned, so the stage's own code changed its bytes.
            culprits.push(versions.iter().map(|(name, _)| *name).collect::<Vec<_>>());
            let advice = match &versions[..] {
                [(name, value)] => format!("{name} is still {value}: bump it"),
                several => format!(
                    "none of {} moved: bump the one whose code changed",
                    several
                        .iter()
                        .map(|(name, value)| format!("{name} ({value})"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            };
            problems.push(format!(
                "stage `{stage}` output changed but {advice} (codec::VERSION for an \
                 encoding), then {BLESS}"
            ));
        } else if changed(stage) {
            problems.push(format!(
                "stage `{stage}` output changed with its inputs (the upstream stage named \
                 above needs the bump): after that, {BLESS}"
            ));
        }
    }
    // A constant in every such stage's key is the likely one (render for a renderer change
    // seen by the overview and the frames alike).
    if let Some((first, rest)) = culprits.split_first() {
        let shared: Vec<&&str> = first
            .iter()
            .filter(|c| rest.iter().all(|r| r.contains(c)))
            .collect();
        match &shared[..] {
            [] => {}
            [only] => problems.push(format!(
                "likely {only}: every stage that changed has it in its key"
            )),
            several => problems.push(format!(
                "likely one of {}: every stage that changed has them in its key",
                several
                    .iter()
                    .map(|c| c.to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
        }
    }
    assert!(problems.is_empty(), "\n{}\n", problems.join("\n"));
}
