//! Renderer benchmark, printing median frames per second: `cargo bench --bench render`.
//!
//! The `specs/day.toml` street path, as the target names it: its city (about 110k
//! triangles, built into a temporary cache first, or loaded from `BENCH_CACHE` when set),
//! its camera at 640 × 480, `BENCH_RUNS` (default 15) of its poses spread evenly over the
//! drive. Each lighting feature alone (the analytic sky, shadows, ambient occlusion), then
//! all together, without antialiasing and 2 × 2 supersampled, and the `specs/dusk.toml`
//! and `specs/night.toml` streets (the same city and poses under their lighting). Every
//! case has the default edge antialiasing and the tone curve (its cost alone is the last
//! line). This times the renderer and the development only: `cargo bench --bench frames`
//! times the whole frame path (PNG encoding, annotation, the cache).
//!
//! Target on the 2-core machine (issue 11): at least 30 frames/s by day with sky, shadows,
//! ambient occlusion and the tone curve. Besides the clock (median frames/s, fastest and
//! slowest frame), each case prints the CPU time per frame of all threads, which a busy
//! machine inflates far less than the clock (with `RAYON_NUM_THREADS=1` it is also free of
//! the pool's idle spinning). Timings are printed, never asserted. `BENCH_CASES` picks
//! cases by parts of their labels (`BENCH_CASES="+ AO,night"`).

mod support;

use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

use cityspec::driver::{PathRenderInput, path_render_input};
use cityspec::render::{self, CameraPose, Lighting, Sky, develop};
use support::{bench_runs, cpu_ms, repo};

fn main() {
    let runs = bench_runs(15);
    let temporary = tempfile::tempdir().unwrap();
    let cache =
        std::env::var_os("BENCH_CACHE").map_or_else(|| temporary.path().to_path_buf(), Into::into);
    let start = Instant::now();
    let day = street("day", &cache);
    println!(
        "cityspec render benchmark: specs/day.toml street, {} triangles, {}x{}, city built or loaded in {:.1} s, rayon threads: {}",
        day.scene.triangle_count(),
        day.intrinsics.width,
        day.intrinsics.height,
        start.elapsed().as_secs_f64(),
        rayon::current_num_threads()
    );
    let (dusk, night) = (street("dusk", &cache), street("night", &cache));
    let poses = spread(&day, runs);
    let k = &day.intrinsics;
    if let Ok(dir) = std::env::var("RENDER_BENCH_DUMP") {
        // For a look at what is being timed: the first pose, by day, at dusk and by night.
        for (name, input) in [("day", &day), ("dusk", &dusk), ("night", &night)] {
            let pose = &spread(input, runs)[0];
            let frame = render::render(&input.scene, pose, k, &input.lighting, 1);
            let png = frame.encode(&frame.rgb(), input.depth);
            let dir = Path::new(&dir);
            std::fs::write(dir.join(format!("{name}_rgb.png")), &png.rgb).unwrap();
            std::fs::write(dir.join(format!("{name}_instance.png")), &png.instance).unwrap();
            std::fs::write(dir.join(format!("{name}_depth.png")), &png.depth).unwrap();
        }
    }
    println!(
        "{:<36} {:>10} {:>10} {:>10} {:>10}",
        "case", "median fps", "min ms", "max ms", "cpu ms"
    );
    // Each lighting feature on its own, then all together. The sky is the analytic
    // Preetham sky (a flat colour without it); shadows the shadow map with PCF (built once
    // per sun, outside the timed frames: its cost is printed above); ambient occlusion the
    // screen-space pass; every case develops with the tone curve.
    let all = day.lighting.clone();
    let plain = Lighting {
        sky: Sky::flat([0.45, 0.62, 0.9]),
        shadows: false,
        ambient_occlusion: 0.0,
        ..all.clone()
    };
    let sky_only = Lighting {
        sky: all.sky.clone(),
        ..plain.clone()
    };
    let shadows_only = Lighting {
        shadows: true,
        ..plain.clone()
    };
    let ao_only = Lighting {
        ambient_occlusion: all.ambient_occlusion,
        ..plain.clone()
    };
    let start = Instant::now();
    black_box(render::render(&day.scene, &poses[0], k, &all, 1));
    println!(
        "first day frame, building the shadow map: {:.1} ms",
        start.elapsed().as_secs_f64() * 1000.0
    );
    let ss = day.supersample;
    for (label, input, lighting, ss) in [
        ("640x480 day, no sky, no shadows", &day, plain, ss),
        ("640x480 day, sky", &day, sky_only, ss),
        ("640x480 day, shadows", &day, shadows_only, ss),
        ("640x480 day, ambient occlusion", &day, ao_only, ss),
        ("640x480 day, sky + shadows + AO", &day, all.clone(), ss),
        ("640x480 day, all, no antialiasing", &day, all.clone(), 0),
        ("640x480 day, all, 2x2 supersampled", &day, all.clone(), 2),
        (
            "640x480 dusk, all",
            &dusk,
            dusk.lighting.clone(),
            dusk.supersample,
        ),
        (
            "640x480 night",
            &night,
            night.lighting.clone(),
            night.supersample,
        ),
    ] {
        if !selected(label) {
            continue;
        }
        let poses = spread(input, runs);
        let k = &input.intrinsics;
        let cpu = cpu_ms();
        let ms: Vec<f64> = poses
            .iter()
            .map(|pose| {
                let t = Instant::now();
                // Developed as `Frame::rgb` does: exposure, tone curve, sRGB.
                black_box(render::render(&input.scene, pose, k, &lighting, ss).rgb());
                t.elapsed().as_secs_f64() * 1000.0
            })
            .collect();
        let cpu = (cpu_ms() - cpu) / poses.len() as f64;
        report(label, ms, cpu);
    }
    if !selected("640x480 tone curve + sRGB alone") {
        return;
    }
    let (w, h) = (k.width, k.height);
    let frame = render::render(&day.scene, &poses[0], k, &all, 1);
    let cpu = cpu_ms();
    let ms = (0..runs)
        .map(|_| {
            let t = Instant::now();
            black_box(develop::develop(&frame.linear, w, h, all.exposure));
            t.elapsed().as_secs_f64() * 1000.0
        })
        .collect();
    let cpu = (cpu_ms() - cpu) / runs as f64;
    report("640x480 tone curve + sRGB alone", ms, cpu);
}

/// Whether a case runs: every case, or with `BENCH_CASES` set, those whose label contains
/// one of its comma-separated parts (`BENCH_CASES="AO,night"`).
fn selected(label: &str) -> bool {
    std::env::var("BENCH_CASES").map_or(true, |cases| {
        cases
            .split(',')
            .any(|c| !c.trim().is_empty() && label.contains(c.trim()))
    })
}

/// `runs` of the path's poses, spread evenly over the drive.
fn spread(input: &PathRenderInput, runs: usize) -> Vec<CameraPose> {
    (0..runs.max(1))
        .map(|i| input.poses[i * input.poses.len() / runs.max(1)])
        .collect()
}

/// The `street` camera of `specs/{name}.toml`, its city stages in `cache`.
fn street(name: &str, cache: &Path) -> PathRenderInput {
    let spec = repo().join(format!("specs/{name}.toml"));
    path_render_input(&spec, "street", cache)
        .unwrap_or_else(|e| panic!("{}: {e}", spec.display()))
        .unwrap_or_else(|| panic!("{} has no street camera", spec.display()))
}

/// Prints a case: median frames/s and the extremes by the clock, and the CPU time per
/// frame (all threads), which a busy machine inflates far less than the clock.
fn report(label: &str, mut ms: Vec<f64>, cpu: f64) {
    ms.sort_by(f64::total_cmp);
    println!(
        "{label:<36} {:>10.1} {:>10.2} {:>10.2} {:>10.1}",
        1000.0 / ms[ms.len() / 2],
        ms[0],
        ms[ms.len() - 1],
        cpu
    );
}
