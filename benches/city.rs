//! City-scale benchmark: `cargo bench --bench city`.
//!
//! For the default 768 × 768 city, 2 × 2 and 4 × 4 mirrored ones and 1 km² of central
//! Helsinki from OpenStreetMap (`specs/osm.toml` without cameras: PBF to a textured city,
//! issue 43), each cold build
//! (spec to OBJ + MTL + textures + GLB, with the built-in facades already cached, as the
//! issue asks) runs in its own process so its peak memory can be read. Prints, per case,
//! triangles, the median time of every stage, the median total and the peak resident
//! memory (Linux `VmHWM`), and draws build time against triangles into
//! `target/bench/city_scaling.png` (the paper's Fig. 10, left).
//!
//! Targets on the 2-core machine (issue 3): default city under 0.5 s, 4 × 4 under 10 s and
//! 2 GiB, cost close to linear in polygons. Figures are printed, never asserted.

mod support;

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::time::Instant;

use ab_glyph::FontRef;
use image::{Rgb, RgbImage};
use imageproc::drawing::{draw_filled_circle_mut, draw_line_segment_mut, draw_text_mut};
use support::{
    bench_runs, build_into, child_args, day_without_cameras, median, peak_kib, repo, run_child,
    with_layout_key,
};

const CASES: [(&str, &str); 3] = [
    ("768x768", "[]"),
    ("2x2 mirrored", "[2, 1]"),
    ("4x4 mirrored", "[2, 1, 2, 1]"),
];

fn main() {
    if let Some([spec, cache, out]) = child_args() {
        child(&spec, &cache, &out);
        return;
    }
    let runs = bench_runs(5);
    let dir = tempfile::tempdir().unwrap();
    // The city only: the day spec's cameras (frames are benchmarked by `frames`) are cut.
    let day = day_without_cameras();

    // The built-in facades, cached once, seed every cold build's cache.
    let seed_cache = dir.path().join("seed-cache");
    let warm_spec = write_spec(dir.path(), "warm", &day, "[]");
    build_into(&warm_spec, &seed_cache, &dir.path().join("warm-out"));

    println!("cityspec city benchmark: {runs} cold builds per case, built-in facades cached");
    let mut points = Vec::new();
    let mut cases: Vec<(&str, PathBuf)> = CASES
        .iter()
        .map(|(label, mirror)| {
            let spec = write_spec(dir.path(), &label.replace(' ', "_"), &day, mirror);
            (*label, spec)
        })
        .collect();
    cases.push(("OpenStreetMap 1 km2", write_osm_spec(dir.path())));
    for (label, spec) in cases {
        let mut results = Vec::new();
        for run in 0..runs {
            let cache = dir
                .path()
                .join(format!("cache-{}-{run}", label.replace(' ', "_")));
            copy_facade_entries(&seed_cache, &cache);
            let out = dir.path().join(format!("out-{run}"));
            results.push(Sample::parse(&run_child(&spec, &cache, &out)));
            let _ = fs::remove_dir_all(&cache);
            let _ = fs::remove_dir_all(&out);
        }
        let triangles = results[0].triangles;
        let total = median(results.iter().map(|r| r.total_ms).collect());
        // The figure: spec to OBJ + MTL + textures + GLB, without the overview render.
        let to_glb = median(
            results
                .iter()
                .map(|r| r.total_ms - r.stages.get("overview").copied().unwrap_or(0.0))
                .collect(),
        );
        let peak = results.iter().map(|r| r.peak_kib).max().unwrap();
        println!(
            "\n{label}: {triangles} triangles; cold build median {total:.1} ms ({to_glb:.1} ms to OBJ+MTL+textures+GLB, without overview.png); peak memory {:.1} MiB",
            peak as f64 / 1024.0
        );
        let stages: Vec<String> = results[0].stages.keys().cloned().collect();
        for stage in stages {
            let times: Vec<f64> = results
                .iter()
                .filter_map(|r| r.stages.get(&stage).copied())
                .collect();
            println!("  {stage:<8} {:>9.2} ms", median(times));
        }
        points.push((label, triangles as f64, total));
    }
    let plot = repo().join("target/bench/city_scaling.png");
    draw_plot(&points, &plot);
    println!("\nplot: {}", plot.display());
}

/// One cold build in this process; prints `triangles`, stage times, total and peak memory.
fn child(spec: &Path, cache: &Path, out: &Path) {
    let start = Instant::now();
    let report = build_into(spec, cache, out);
    let total = start.elapsed().as_secs_f64() * 1e3;
    println!("triangles {}", report.triangles.unwrap_or(0));
    for run in &report.stages {
        println!("stage {} {:.3}", run.stage, run.time.as_secs_f64() * 1e3);
    }
    println!("total {total:.3}");
    println!("peak_kib {}", peak_kib());
}

struct Sample {
    triangles: usize,
    stages: BTreeMap<String, f64>,
    total_ms: f64,
    peak_kib: u64,
}

impl Sample {
    fn parse(text: &str) -> Sample {
        let mut sample = Sample {
            triangles: 0,
            stages: BTreeMap::new(),
            total_ms: 0.0,
            peak_kib: 0,
        };
        for line in text.lines() {
            let parts: Vec<&str> = line.split_whitespace().collect();
            match parts.as_slice() {
                ["triangles", n] => sample.triangles = n.parse().unwrap(),
                ["stage", name, ms] => {
                    *sample.stages.entry((*name).to_owned()).or_default() +=
                        ms.parse::<f64>().unwrap()
                }
                ["total", ms] => sample.total_ms = ms.parse().unwrap(),
                ["peak_kib", kib] => sample.peak_kib = kib.parse().unwrap(),
                _ => {}
            }
        }
        sample
    }
}

fn write_spec(dir: &Path, name: &str, day: &str, mirror: &str) -> PathBuf {
    // Paths in the spec are relative to specs/; this copy lives elsewhere.
    let assets = format!("\"{}/assets/", repo().display());
    let text = with_layout_key(
        &day.replace("\"../assets/", &assets)
            .replace("name = \"day\"", &format!("name = \"{name}\"")),
        "mirror",
        mirror,
    );
    let path = dir.join(format!("{name}.toml"));
    fs::write(&path, text).unwrap();
    path
}

/// `specs/osm.toml` (1 km² of central Helsinki from the committed extract) without its
/// cameras and splits: the extract read, its city built, exported and seen from the air.
fn write_osm_spec(dir: &Path) -> PathBuf {
    let osm = fs::read_to_string(repo().join("specs/osm.toml")).unwrap();
    let cut = match (osm.find("[[cameras]]"), osm.find("[lighting]")) {
        (Some(a), Some(b)) if a < b => format!("{}{}", &osm[..a], &osm[b..]),
        _ => osm,
    };
    let cut = cut.split("[splits]").next().unwrap().to_owned();
    let assets = format!("\"{}/assets/", repo().display());
    let path = dir.join("osm.toml");
    fs::write(&path, cut.replace("\"../assets/", &assets)).unwrap();
    path
}

/// Copies the facades stage's cache entries and their objects into a fresh cache.
fn copy_facade_entries(from: &Path, to: &Path) {
    for entry in fs::read_dir(from.join("entries")).unwrap() {
        let path = entry.unwrap().path();
        let text = fs::read_to_string(&path).unwrap();
        let json: serde_json::Value = serde_json::from_str(&text).unwrap();
        if json["stage"] != "facades" {
            continue;
        }
        fs::create_dir_all(to.join("entries")).unwrap();
        fs::copy(&path, to.join("entries").join(path.file_name().unwrap())).unwrap();
        for object in json["outputs"].as_object().unwrap().values() {
            let sha = object["sha256"].as_str().unwrap();
            let rel = Path::new("objects").join(&sha[..2]).join(sha);
            fs::create_dir_all(to.join(rel.parent().unwrap())).unwrap();
            fs::copy(from.join(&rel), to.join(&rel)).unwrap();
        }
    }
}

/// Build time (ms) against triangles, with a least-squares line through the origin.
fn draw_plot(points: &[(&str, f64, f64)], path: &Path) {
    let (w, h) = (720u32, 480u32);
    let (left, right, top, bottom) = (90.0f32, 30.0f32, 40.0f32, 70.0f32);
    let mut img = RgbImage::from_pixel(w, h, Rgb([255, 255, 255]));
    let font = FontRef::try_from_slice(notosans::REGULAR_TTF).unwrap();
    let black = Rgb([30, 30, 30]);
    let max_x = points.iter().map(|p| p.1).fold(0.0, f64::max) * 1.1;
    let max_y = points.iter().map(|p| p.2).fold(0.0, f64::max) * 1.2;
    let px = |x: f64| left + (x / max_x) as f32 * (w as f32 - left - right);
    let py = |y: f64| h as f32 - bottom - (y / max_y) as f32 * (h as f32 - top - bottom);
    draw_line_segment_mut(
        &mut img,
        (left, py(0.0)),
        (w as f32 - right, py(0.0)),
        black,
    );
    draw_line_segment_mut(&mut img, (left, py(0.0)), (left, top), black);
    for i in 0..=4 {
        let (x, y) = (max_x * i as f64 / 4.0, max_y * i as f64 / 4.0);
        draw_line_segment_mut(&mut img, (px(x), py(0.0)), (px(x), py(0.0) + 6.0), black);
        draw_text_mut(
            &mut img,
            black,
            px(x) as i32 - 20,
            py(0.0) as i32 + 10,
            16.0,
            &font,
            &format!("{:.0}k", x / 1000.0),
        );
        draw_line_segment_mut(&mut img, (left - 6.0, py(y)), (left, py(y)), black);
        draw_text_mut(
            &mut img,
            black,
            8,
            py(y) as i32 - 9,
            16.0,
            &font,
            &format!("{y:.0} ms"),
        );
    }
    draw_text_mut(
        &mut img,
        black,
        (w / 2 - 60) as i32,
        (h - 30) as i32,
        18.0,
        &font,
        "triangles in the city",
    );
    draw_text_mut(
        &mut img,
        black,
        left as i32,
        10,
        18.0,
        &font,
        "cold build time (built-in facades cached), median",
    );
    // Least squares through the origin: time = k · triangles.
    let k = points.iter().map(|p| p.1 * p.2).sum::<f64>()
        / points.iter().map(|p| p.1 * p.1).sum::<f64>();
    draw_line_segment_mut(
        &mut img,
        (px(0.0), py(0.0)),
        (px(max_x), py(k * max_x)),
        Rgb([160, 160, 220]),
    );
    for (label, x, y) in points {
        draw_filled_circle_mut(
            &mut img,
            (px(*x) as i32, py(*y) as i32),
            5,
            Rgb([200, 40, 40]),
        );
        draw_text_mut(
            &mut img,
            black,
            px(*x) as i32 + 8,
            py(*y) as i32 - 22,
            15.0,
            &font,
            label,
        );
    }
    fs::create_dir_all(path.parent().unwrap()).unwrap();
    img.save(path).unwrap();
}
