//! Optical flow benchmark: `cargo bench --bench flow`.
//!
//! The `specs/drive.toml` street camera (the day city, a timed drive at 10 frames/s and
//! 30 km/h, 640 × 480; the city built into a temporary cache first, or loaded from
//! `BENCH_CACHE` when set): for `BENCH_RUNS` (default 15) consecutive pairs of its poses,
//! each frame's depth rendered first (not timed), then the forward flow to the next pose
//! (`render::flow`: a depth-only render of the next pose, every pixel unprojected,
//! projected and tested against it) and its KITTI PNG encoding. Prints the median,
//! fastest and slowest times by the clock, the CPU time of all threads per frame, and the
//! share of valid pixels. Timings are printed, never asserted.

mod support;

use std::hint::black_box;
use std::time::Instant;

use cityspec::driver::path_render_input;
use cityspec::render;
use support::{bench_runs, cpu_ms, median, repo};

fn main() {
    let runs = bench_runs(15);
    let temporary = tempfile::tempdir().unwrap();
    let cache =
        std::env::var_os("BENCH_CACHE").map_or_else(|| temporary.path().to_path_buf(), Into::into);
    let spec = repo().join("specs/drive.toml");
    let input = path_render_input(&spec, "street", &cache)
        .unwrap_or_else(|e| panic!("{}: {e}", spec.display()))
        .expect("specs/drive.toml has a street camera");
    let k = &input.intrinsics;
    let pairs = runs.min(input.poses.len() - 1);
    println!(
        "cityspec flow benchmark: specs/drive.toml street, {} triangles, {}x{}, {pairs} pairs of consecutive poses, rayon threads: {}",
        input.scene.triangle_count(),
        k.width,
        k.height,
        rayon::current_num_threads()
    );
    let (mut flow_ms, mut png_ms, mut valid) = (Vec::new(), Vec::new(), Vec::new());
    let mut cpu = 0.0;
    for i in 0..pairs {
        let frame = render::render(&input.scene, &input.poses[i], k, &input.lighting, 1);
        let (cpu_start, start) = (cpu_ms(), Instant::now());
        let flow = black_box(render::flow(
            &input.scene,
            &frame.depth,
            None,
            &input.poses[i],
            &input.poses[i + 1],
            k,
        ));
        flow_ms.push(start.elapsed().as_secs_f64() * 1e3);
        let start = Instant::now();
        black_box(flow.kitti_png());
        png_ms.push(start.elapsed().as_secs_f64() * 1e3);
        cpu += cpu_ms() - cpu_start;
        valid.push(flow.valid.iter().filter(|v| **v).count() as f64 / flow.valid.len() as f64);
    }
    let spread = |v: &[f64]| {
        (
            v.iter().copied().fold(f64::INFINITY, f64::min),
            v.iter().copied().fold(0.0, f64::max),
        )
    };
    let (lo, hi) = spread(&flow_ms);
    println!(
        "flow: median {:.1} ms ({lo:.1}-{hi:.1}); KITTI PNG: median {:.1} ms; CPU {:.1} ms a frame (both); valid pixels median {:.1} %",
        median(flow_ms.clone()),
        median(png_ms),
        cpu / pairs as f64,
        100.0 * median(valid)
    );
}
