//! Benchmarks of the compiler core, printing medians: `cargo bench --bench pipeline`.
//!
//! - layout generation, parsing, lamp siting and building placement, for the default
//!   768 × 768 layout and for a 4 × 4 mirrored one (3072 × 3072);
//! - a cold build (empty cache, no output folder; up to 5 runs) with every stage's median,
//!   then a no-op rebuild (everything cached), through the library and as a whole process;
//! - reading an OpenStreetMap extract into its map (`osm::read`): the committed
//!   `assets/osm/helsinki.osm.pbf` (1.0 × 1.7 km of central Helsinki) and its PNG picture.
//!
//! Targets on the 2-core machine (issue 2): layout + parse + place for 768 × 768 under
//! 50 ms; a no-op rebuild under 30 ms; (issue 11) the cold build of the day spec without
//! cameras under 0.5 s. Timings are printed, never asserted: a busy machine
//! must not fail a build.

mod support;

use std::collections::BTreeMap;
use std::hint::black_box;
use std::process::Command;
use std::time::{Duration, Instant};

use cityspec::driver::{self, BuildOptions, widths_px};
use cityspec::spec::{GenerateSpec, Palette, Spec};
use cityspec::{lamps, layout, mirror, parse, place, rng};
use support::{bench_runs, copy_tree, day_without_cameras, repo};

fn main() {
    let runs = bench_runs(21);
    println!(
        "cityspec pipeline benchmarks, {runs} runs each, rayon threads: {}",
        rayon::current_num_threads()
    );
    println!(
        "{:<44} {:>10} {:>10} {:>10}",
        "case", "median", "min", "max"
    );
    stages("768x768", &[], runs);
    stages("4x4 mirrored (3072x3072)", &[2, 1, 2, 1], runs);
    noop_rebuild(runs);
    osm_read(runs);
}

/// `osm::read` of the Helsinki extract from its bytes (the file read once, outside the
/// timing), then its picture.
fn osm_read(runs: usize) {
    let bytes = std::fs::read(repo().join("assets/osm/helsinki.osm.pbf")).unwrap();
    let mut reads = Vec::new();
    let mut draws = Vec::new();
    let mut counts = (0, 0, 0);
    for _ in 0..runs {
        let start = Instant::now();
        let map = cityspec::osm::read(&bytes, None).unwrap();
        let read = Instant::now();
        black_box(cityspec::osm::draw(&map, 2048));
        draws.push(read.elapsed());
        reads.push(read - start);
        counts = (map.buildings.len(), map.roads.len(), map.features.len());
    }
    println!(
        "OSM helsinki.osm.pbf ({} KiB): {} buildings, {} road and path pieces, {} features",
        bytes.len() / 1024,
        counts.0,
        counts.1,
        counts.2
    );
    row("  osm::read (PBF → map in metres)", &mut reads);
    row("  osm::draw (2048-pixel picture)", &mut draws);
}

fn stages(label: &str, ops: &[u8], runs: usize) {
    let spec: Spec = driver::load_spec(&repo().join("specs/day.toml")).unwrap();
    let generate: GenerateSpec = spec.layout.generate.clone().unwrap();
    let palette = Palette::default();
    // Fixed widths, so the figure measures placement, not the facade set's choice of sizes.
    let widths = widths_px(&[12.0, 16.0, 20.0, 24.0, 30.0], 1.0);
    let gap = spec.buildings.gap.round() as u32;

    let mut t_layout = Vec::new();
    let mut t_parse = Vec::new();
    let mut t_lamps = Vec::new();
    let mut t_place = Vec::new();
    let mut t_total = Vec::new();
    let mut counts = (0, 0, 0, 0);
    for _ in 0..runs {
        let start = Instant::now();
        let mut stream = rng::stream(spec.seed, "layout", 0);
        let image = mirror::mirror(
            &layout::generate(&generate, &palette, &mut stream).image,
            ops,
        );
        let a = Instant::now();
        let parsed = parse::parse(&image, &palette);
        let b = Instant::now();
        let sites = lamps::site_lamps(
            &image,
            &parsed,
            &palette,
            spec.lamps.spacing,
            spec.lamps.min_distance,
        );
        let c = Instant::now();
        let buildings = place::place(&parsed.blocks, &widths, gap, spec.seed);
        let d = Instant::now();
        t_layout.push(a - start);
        t_parse.push(b - a);
        t_lamps.push(c - b);
        t_place.push(d - c);
        t_total.push(d - start);
        counts = (
            parsed.blocks.len(),
            parsed.roads.len(),
            sites.len(),
            buildings.len(),
        );
        black_box((parsed, sites, buildings));
    }
    println!(
        "{label}: {} blocks, {} roads, {} lamps, {} buildings",
        counts.0, counts.1, counts.2, counts.3
    );
    row(&format!("  {label}: layout (+mirror)"), &mut t_layout);
    row(&format!("  {label}: parse"), &mut t_parse);
    row(&format!("  {label}: lamps"), &mut t_lamps);
    row(&format!("  {label}: place"), &mut t_place);
    row(
        &format!("  {label}: layout + parse + lamps + place"),
        &mut t_total,
    );
}

fn noop_rebuild(runs: usize) {
    let day = std::fs::read_to_string(repo().join("specs/day.toml")).unwrap();
    // The city alone (what issue 2 measured), then the full dataset with its 112 frames.
    let city = day_without_cameras();
    // Several cold builds of the city (issue 11's target); one of the dataset (seconds).
    noop_case("day.toml without cameras", &city, runs, runs.min(COLD_RUNS));
    noop_case("day.toml with 112 frames", &day, runs, 1);
}

fn noop_case(label: &str, text: &str, runs: usize, cold_runs: usize) {
    let dir = tempfile::tempdir().unwrap();
    // specs/day.toml names ../assets/…: copy both, side by side as in the repo.
    std::fs::create_dir_all(dir.path().join("specs")).unwrap();
    let spec = dir.path().join("specs/day.toml");
    std::fs::write(&spec, text).unwrap();
    copy_tree(&repo().join("assets"), &dir.path().join("assets"));
    let options = BuildOptions {
        progress: None,
        out_root: dir.path().join("out"),
        cache_dir: dir.path().join("cache"),
        waiting: None,
        strict: false,
        locked: false,
        sets: Vec::new(),
    };
    // Cold builds: an empty cache and no output folder each time, every stage's time kept.
    let mut cold_times = Vec::new();
    let mut stage_times: BTreeMap<&'static str, Vec<Duration>> = BTreeMap::new();
    let mut others = Vec::new();
    for _ in 0..cold_runs {
        let _ = std::fs::remove_dir_all(&options.cache_dir);
        let _ = std::fs::remove_dir_all(&options.out_root);
        let cold = Instant::now();
        let report = driver::build(&spec, &options).unwrap();
        let total = cold.elapsed();
        cold_times.push(total);
        // A stage's runs summed (one `frames` per camera); the rest of the time is the
        // driver's own: spec and input reads, keys, the renderer's `prepare` (decoded
        // textures' mips, flat triangles), the output folder and its freshness record.
        let mut this_run: BTreeMap<&'static str, Duration> = BTreeMap::new();
        for run in &report.stages {
            *this_run.entry(run.stage).or_default() += run.time;
        }
        let in_stages: Duration = this_run.values().sum();
        for (stage, time) in this_run {
            stage_times.entry(stage).or_default().push(time);
        }
        others.push(total.saturating_sub(in_stages));
    }
    let mut lib = Vec::new();
    for _ in 0..runs {
        let start = Instant::now();
        let report = driver::build(&spec, &options).unwrap();
        lib.push(start.elapsed());
        assert!(report.up_to_date());
    }
    let mut process = Vec::new();
    for _ in 0..runs {
        let start = Instant::now();
        let status = Command::new(env!("CARGO_BIN_EXE_cityspec"))
            .args(["build", "-q", "--out"])
            .arg(&options.out_root)
            .arg("--cache")
            .arg(&options.cache_dir)
            .arg(&spec)
            .status()
            .unwrap();
        process.push(start.elapsed());
        assert!(status.success());
    }
    row(&format!("{label}: cold build"), &mut cold_times);
    // Stages in the order a cold build runs them (sequentially; each may use every core).
    let mut stages: Vec<(&str, Vec<Duration>)> = stage_times.into_iter().collect();
    stages.sort_by_key(|(stage, _)| STAGE_ORDER.iter().position(|s| s == stage));
    for (stage, mut times) in stages {
        row(&format!("  cold: {stage}"), &mut times);
    }
    row("  cold: outside stages (driver, prepare)", &mut others);
    row(&format!("{label}: no-op rebuild (library)"), &mut lib);
    row(&format!("{label}: no-op rebuild (process)"), &mut process);
}

/// Cold builds of the city, at most (each takes up to a second or more).
const COLD_RUNS: usize = 5;

/// The order a build evaluates its stages, for the cold build's breakdown.
const STAGE_ORDER: [&str; 13] = [
    "layout",
    "mirror",
    "parse",
    "lamps",
    "facades",
    "place",
    "plan",
    "preview",
    "scene",
    "export",
    "overview",
    "frames-plan",
    "frames",
];

fn row(label: &str, times: &mut [Duration]) {
    times.sort();
    let ms = |d: Duration| format!("{:.2} ms", d.as_secs_f64() * 1e3);
    println!(
        "{label:<44} {:>10} {:>10} {:>10}",
        ms(times[times.len() / 2]),
        ms(times[0]),
        ms(times[times.len() - 1])
    );
}
