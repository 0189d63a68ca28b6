//! Issue 8: mutated inputs (byte flips, line deletions and swaps, value swaps of the
//! example specs; damaged layout PNGs, OBJ files and OpenStreetMap extracts) never panic,
//! finish in bounded time, and end in a clean error or Ok, in process and through
//! `cityspec validate` (exit 0 or 2).
//!
//! Cases come from `cityspec::test_seed` (a fixed seed by default;
//! `CITYSPEC_PROPTEST_CASES=N CITYSPEC_PROPTEST_SEED=random` for a longer random run).

use crate::common;

use std::fs;
use std::io::Cursor;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

use cityspec::spec::{self, FsWorld, SpecSource};

/// SplitMix64: a tiny seeded stream, enough to pick mutations.
struct Draw(u64);

impl Draw {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Values a mutation may drop in place of another: edge cases of every type the spec has.
const VALUES: &[&str] = &[
    "0",
    "-1",
    "1",
    "65536",
    "4294967296",
    "1e308",
    "-0.0",
    "nan",
    "inf",
    "\"\"",
    "\"x\"",
    "[]",
    "[0, 0]",
    "[1]",
    "true",
    "{}",
    "2048",
    "\"../../etc/passwd\"",
    "\"/dev/zero\"",
];

/// One mutation of `bytes`: flip a byte, delete/duplicate/swap lines, or swap a value.
fn mutate(bytes: &[u8], draw: &mut Draw) -> Vec<u8> {
    let mut out = bytes.to_vec();
    let rounds = 1 + draw.below(3);
    for _ in 0..rounds {
        let text = String::from_utf8_lossy(&out).into_owned();
        let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
        match draw.below(6) {
            0 if !out.is_empty() => {
                let i = draw.below(out.len());
                out[i] ^= 1 << draw.below(8);
                continue;
            }
            1 if !lines.is_empty() => {
                lines.remove(draw.below(lines.len()));
            }
            2 if !lines.is_empty() => {
                let i = draw.below(lines.len());
                lines.insert(draw.below(lines.len()), lines[i].clone());
            }
            3 if lines.len() > 1 => {
                let (a, b) = (draw.below(lines.len()), draw.below(lines.len()));
                lines.swap(a, b);
            }
            4 => {
                out.truncate(draw.below(out.len() + 1));
                continue;
            }
            _ => {
                let candidates: Vec<usize> = (0..lines.len())
                    .filter(|&i| lines[i].contains(" = "))
                    .collect();
                if candidates.is_empty() {
                    continue;
                }
                let i = candidates[draw.below(candidates.len())];
                let key = lines[i].split(" = ").next().unwrap_or("").to_owned();
                lines[i] = format!("{key} = {}", VALUES[draw.below(VALUES.len())]);
            }
        }
        out = lines.join("\n").into_bytes();
    }
    out
}

/// A binary file's mutation: one to three bytes flipped or cuts short.
fn flip_or_cut(bytes: &[u8], draw: &mut Draw) -> Vec<u8> {
    let mut bytes = bytes.to_vec();
    for _ in 0..1 + draw.below(3) {
        if draw.below(4) == 0 {
            bytes.truncate(draw.below(bytes.len() + 1));
        } else if !bytes.is_empty() {
            let i = draw.below(bytes.len());
            bytes[i] ^= 1 << draw.below(8);
        }
    }
    bytes
}

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Runs `f` and asserts it neither panicked nor took longer than `limit`.
fn bounded<T>(what: &str, limit: Duration, f: impl FnOnce() -> T) -> T {
    let start = Instant::now();
    let result = catch_unwind(AssertUnwindSafe(f));
    let took = start.elapsed();
    let value = result.unwrap_or_else(|_| panic!("{what}: panicked"));
    assert!(took < limit, "{what}: took {took:?}");
    value
}

fn example_specs() -> Vec<(std::path::PathBuf, Vec<u8>)> {
    let mut specs: Vec<_> = fs::read_dir(repo().join("specs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .map(|p| {
            let bytes = fs::read(&p).unwrap();
            (p, bytes)
        })
        .collect();
    specs.sort();
    specs
}

#[test]
fn mutated_specs_load_cleanly() {
    let (cases, seed) = cityspec::test_seed::cases_and_seed(3000);
    let mut draw = Draw(seed ^ 0x5bec);
    let specs = example_specs();
    let (mut ok, mut refused) = (0, 0);
    for case in 0..cases {
        let (path, bytes) = &specs[draw.below(specs.len())];
        let mutated = mutate(bytes, &mut draw);
        let what = format!("case {case} (seed {seed}) of {}", path.display());
        // Specs are UTF-8 text; the CLI refuses other bytes before `spec::load`.
        let Ok(text) = String::from_utf8(mutated) else {
            refused += 1;
            continue;
        };
        let source = SpecSource {
            path: path.clone(),
            text,
        };
        match bounded(&what, Duration::from_secs(2), || {
            spec::load(&source, &FsWorld)
        }) {
            Ok(_) => ok += 1,
            Err(errors) => {
                assert!(!errors.to_string().trim().is_empty(), "{what}: empty error");
                refused += 1;
            }
        }
    }
    // The mutations must reach both outcomes, or they test nothing.
    assert!(ok > 0 && refused > 0, "{ok} loaded, {refused} refused");
}

#[test]
fn mutated_layout_pngs_decode_or_fail_cleanly() {
    let (cases, seed) = cityspec::test_seed::cases_and_seed(300);
    let mut draw = Draw(seed ^ 0x9a6e);
    let mut small = Vec::new();
    let image = image::RgbImage::from_fn(24, 16, |x, y| {
        if x % 8 < 2 || y % 8 < 2 {
            image::Rgb([0, 0, 0])
        } else {
            image::Rgb([255, 255, 255])
        }
    });
    image
        .write_to(&mut Cursor::new(&mut small), image::ImageFormat::Png)
        .unwrap();
    let (mut ok, mut refused) = (0, 0);
    for case in 0..cases {
        // Byte flips and truncations only: PNGs are binary, line edits mean little.
        let bytes = flip_or_cut(&small, &mut draw);
        let what = format!("PNG case {case} (seed {seed})");
        let result = bounded(&what, Duration::from_secs(2), || {
            cityspec::model::image_file::check_complete(&bytes)
                .map_err(|e| e.to_string())
                .and_then(|()| cityspec::layout::decode(&bytes).map_err(|e| e.to_string()))
        });
        match result {
            Ok(_) => ok += 1,
            Err(message) => {
                assert!(!message.trim().is_empty(), "{what}");
                refused += 1;
            }
        }
    }
    assert!(refused > 0, "{ok} decoded, {refused} refused");
}

#[test]
fn mutated_obj_files_load_or_fail_at_a_line() {
    let (cases, seed) = cityspec::test_seed::cases_and_seed(300);
    let mut draw = Draw(seed ^ 0x0b1);
    let obj = fs::read(repo().join("assets/models/bench.obj")).unwrap();
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    let (mut ok, mut refused) = (0, 0);
    for case in 0..cases {
        let bytes = mutate(&obj, &mut draw);
        let what = format!("OBJ case {case} (seed {seed})");
        let text = String::from_utf8_lossy(&bytes).into_owned();
        bounded(&what, Duration::from_secs(2), || {
            match tobj::load_obj_buf(&mut Cursor::new(&bytes[..]), &options, |_| {
                Ok((Vec::new(), Default::default()))
            }) {
                Ok(_) => ok += 1,
                Err(e) => {
                    // The line finder the build uses to point at the bad line.
                    if let Some(line) = cityspec::objects::obj_lines::obj_error_line(&text, &e) {
                        assert!(line >= 1 && line <= text.lines().count().max(1), "{what}");
                    }
                    refused += 1;
                }
            }
        });
    }
    assert!(ok > 0, "{ok} loaded, {refused} refused");
}

#[test]
fn mutated_specs_through_validate_exit_0_or_2() {
    let (cases, seed) = cityspec::test_seed::cases_and_seed(20);
    let cases = cases.min(200);
    let mut draw = Draw(seed ^ 0xc11);
    let ws = common::Workspace::with_spec("day");
    let specs = example_specs();
    let obj = fs::read(repo().join("assets/models/bench.obj")).unwrap();
    for case in 0..cases {
        let (path, bytes) = &specs[draw.below(specs.len())];
        let name = path.file_name().unwrap();
        let target = ws.path().join("specs").join(name);
        fs::write(&target, mutate(bytes, &mut draw)).unwrap();
        // Every fourth case damages the model the specs name instead.
        if case % 4 == 3 {
            fs::write(&target, bytes).unwrap();
            fs::write(
                ws.path().join("assets/models/bench.obj"),
                mutate(&obj, &mut draw),
            )
            .unwrap();
        }
        let start = Instant::now();
        let out = Command::new(env!("CARGO_BIN_EXE_cityspec"))
            .current_dir(ws.path())
            .arg("validate")
            .arg(Path::new("specs").join(name))
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            matches!(out.status.code(), Some(0 | 2)),
            "case {case} (seed {seed}): {:?}\n{stderr}",
            out.status
        );
        assert!(!stderr.contains("panicked"), "case {case}: {stderr}");
        assert!(start.elapsed() < Duration::from_secs(20), "case {case}");
        fs::write(&target, bytes).unwrap();
        fs::write(ws.path().join("assets/models/bench.obj"), &obj).unwrap();
    }
}

/// Values a mutated OpenStreetMap tag or coordinate takes: numbers past every range,
/// non-numbers, and the words the reader looks for.
const OSM_VALUES: &[&str] = &[
    "0",
    "-1",
    "-0",
    "1e30",
    "1e308",
    "-1e308",
    "nan",
    "inf",
    "-inf",
    "",
    "yes",
    "no",
    "-1;2",
    "999999999",
    "4294967296",
    "N",
    "#fff",
    "1,5",
    "91",
    "-181",
    "3 m",
    "12'",
    "gabled",
    "hipped",
    "skillion",
    "round",
    "dome",
    "both",
    "separate",
    "roundabout",
];

/// Keys the map reader reads off buildings, parts and roads.
const OSM_KEYS: &[&str] = &[
    "building",
    "building:part",
    "height",
    "min_height",
    "building:levels",
    "building:min_level",
    "roof:shape",
    "roof:height",
    "roof:levels",
    "roof:direction",
    "roof:orientation",
    "building:colour",
    "roof:colour",
    "highway",
    "width",
    "lanes",
    "oneway",
    "junction",
    "sidewalk",
    "sidewalk:width",
    "layer",
    "tunnel",
    "covered",
    "parking:lane:both",
    "area",
    "natural",
    "crossing",
    "traffic_sign",
    "name",
];

/// One mutation of an OSM XML extract: a tag the reader reads set to an edge value on a
/// way or node, a value or coordinate replaced, a line deleted, doubled or swapped, a
/// byte flipped, or the file cut short.
fn mutate_osm(text: &str, draw: &mut Draw) -> Vec<u8> {
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    for _ in 0..1 + draw.below(4) {
        let n = lines.len();
        match draw.below(7) {
            0 | 1 => {
                let element: Vec<usize> = (0..n)
                    .filter(|&i| lines[i].contains("<way ") || lines[i].contains("<relation "))
                    .filter(|&i| !lines[i].ends_with("/>"))
                    .collect();
                if let Some(&i) = element.get(draw.below(element.len())) {
                    let key = OSM_KEYS[draw.below(OSM_KEYS.len())];
                    let value = OSM_VALUES[draw.below(OSM_VALUES.len())];
                    lines.insert(i + 1, format!("    <tag k=\"{key}\" v=\"{value}\"/>"));
                }
            }
            2 => {
                let with: Vec<usize> = (0..n)
                    .filter(|&i| lines[i].contains(" v=\"") || lines[i].contains(" lat=\""))
                    .collect();
                if let Some(&i) = with.get(draw.below(with.len())) {
                    let attribute = [" v=\"", " lat=\"", " lon=\""][draw.below(3)];
                    if let Some(start) = lines[i].find(attribute) {
                        let from = start + attribute.len();
                        let end = lines[i][from..]
                            .find('"')
                            .map_or(lines[i].len(), |e| from + e);
                        let value = OSM_VALUES[draw.below(OSM_VALUES.len())];
                        lines[i].replace_range(from..end, value);
                    }
                }
            }
            3 if n > 0 => {
                lines.remove(draw.below(n));
            }
            4 if n > 1 => {
                let i = draw.below(n);
                lines.insert(draw.below(n), lines[i].clone());
            }
            5 if n > 1 => {
                let (a, b) = (draw.below(n), draw.below(n));
                lines.swap(a, b);
            }
            _ => {
                let mut bytes = lines.join("\n").into_bytes();
                if draw.below(2) == 0 {
                    bytes.truncate(draw.below(bytes.len() + 1));
                } else if !bytes.is_empty() {
                    let i = draw.below(bytes.len());
                    bytes[i] ^= 1 << draw.below(8);
                }
                lines = String::from_utf8_lossy(&bytes)
                    .lines()
                    .map(str::to_owned)
                    .collect();
            }
        }
    }
    lines.join("\n").into_bytes()
}

/// Mutated OpenStreetMap extracts (the Kamppi XML with tags set to edge values,
/// coordinates replaced, lines moved; the PBF with bytes flipped and cut) read into a map
/// or fail with a message, in bounded time; a map that reads builds its lamps, its 3D
/// city and the Helsinki spec's objects without a panic, in bounded time too.
#[test]
fn mutated_osm_extracts_read_and_build_or_fail_cleanly() {
    let (cases, seed) = cityspec::test_seed::cases_and_seed(40);
    let mut draw = Draw(seed ^ 0x05a1);
    let fixtures = repo().join("tests/fixtures/osm");
    let xml = fs::read_to_string(fixtures.join("kamppi.osm")).unwrap();
    let pbf = fs::read(fixtures.join("kamppi.osm.pbf")).unwrap();
    let (facades, _) =
        cityspec::facades::process_builtin(3.0, cityspec::spec::OnError::Error).unwrap();
    let lamps = cityspec::spec::LampsSpec::default();
    // The Helsinki spec's objects (but its bench model), a tenth as many of each.
    let source = SpecSource {
        path: repo().join("specs/osm.toml"),
        text: fs::read_to_string(repo().join("specs/osm.toml")).unwrap(),
    };
    let objects: Vec<_> = (spec::load(&source, &FsWorld).unwrap().objects.into_iter())
        .filter(|o| o.kind != cityspec::spec::EntryKind::Mesh)
        .map(|mut o| {
            o.count = (o.count / 10).max(1);
            o
        })
        .collect();
    assert!(objects.len() >= 8, "{objects:?}");
    let (mut built, mut refused) = (0, 0);
    for case in 0..2 * cases {
        let bytes = if case % 2 == 0 {
            mutate_osm(&xml, &mut draw)
        } else {
            flip_or_cut(&pbf, &mut draw)
        };
        let what = format!("OSM case {case} (seed {seed})");
        let read = bounded(&what, Duration::from_secs(20), || {
            cityspec::osm::read(&bytes, None)
        });
        match read {
            Ok(map) => {
                bounded(&what, Duration::from_secs(20), || {
                    let lamps = cityspec::lamps::map_lamps(&map, Some(&lamps));
                    cityspec::scene::map_city(&cityspec::scene::MapSceneInput {
                        map: &map,
                        lamps: &lamps,
                        facades: &facades,
                        seed,
                    });
                    cityspec::objects::insert_map(&cityspec::objects::MapObjectsInput {
                        specs: &objects,
                        map: &map,
                        lamps: &lamps,
                        facades: &facades,
                        meshes: &Default::default(),
                        seed,
                    })
                    .map_err(|e| e.to_string())
                })
                .unwrap_or_else(|e| panic!("{what}: objects refused a map that read: {e}"));
                built += 1;
            }
            Err(error) => {
                assert!(!error.to_string().trim().is_empty(), "{what}");
                refused += 1;
            }
        }
    }
    eprintln!("{built} built, {refused} refused");
    // The mutations must reach both outcomes, or they test nothing.
    assert!(built > 0 && refused > 0, "{built} built, {refused} refused");
}
