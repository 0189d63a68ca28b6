//! LiDAR benchmark: `cargo bench --bench lidar`.
//!
//! The `specs/sensors.toml` street path (the day city, about 110k triangles, built into a
//! temporary cache first, or loaded from `BENCH_CACHE` when set): the BVH build over the
//! prepared scene (once per camera path in a build), then one turn of the spec's scanner
//! (64 beams × 2048 steps, 120 m, noise and dropout) from `BENCH_RUNS` (default 15) of the
//! path's poses spread evenly over the drive, in clear air and in fog (extinction 0.05 per
//! metre, most far returns lost). Prints the median, fastest and slowest times by the
//! clock, the CPU time of all threads per scan, and the points a scan keeps.
//!
//! Target on the 2-core machine (issue 42): a 64 × 2048 scan in at most 50 ms. Timings are
//! printed, never asserted.

mod support;

use std::hint::black_box;
use std::time::Instant;

use cityspec::driver::path_render_input;
use cityspec::lidar::{self, Scanner, Target};
use support::{bench_runs, cpu_ms, median, repo};

fn main() {
    let runs = bench_runs(15);
    let temporary = tempfile::tempdir().unwrap();
    let cache =
        std::env::var_os("BENCH_CACHE").map_or_else(|| temporary.path().to_path_buf(), Into::into);
    let spec = repo().join("specs/sensors.toml");
    let start = Instant::now();
    let input = path_render_input(&spec, "street", &cache)
        .unwrap_or_else(|e| panic!("{}: {e}", spec.display()))
        .expect("specs/sensors.toml has a street camera");
    println!(
        "cityspec LiDAR benchmark: specs/sensors.toml street, {} triangles, city built or loaded in {:.1} s, rayon threads: {}",
        input.scene.triangle_count(),
        start.elapsed().as_secs_f64(),
        rayon::current_num_threads()
    );
    // Kinds only label the points; every triangle is scanned alike without them.
    let mut builds = Vec::new();
    let mut target = None;
    for _ in 0..5 {
        let t = Instant::now();
        target = Some(black_box(Target::of(&input.scene, &[])));
        builds.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let target = target.expect("built five times");
    println!(
        "BVH build: median {:.1} ms of 5 ({} triangles in the hierarchy)",
        median(builds),
        target.triangles()
    );
    let poses: Vec<_> = (0..runs)
        .map(|i| input.poses[i * input.poses.len() / runs])
        .collect();
    println!(
        "{:<28} {:>10} {:>10} {:>10} {:>10} {:>12}",
        "case", "median ms", "min ms", "max ms", "cpu ms", "points/scan"
    );
    for (label, extinction) in [("64 x 2048, clear", 0.0), ("64 x 2048, fog 0.05/m", 0.05)] {
        let scanner = Scanner::of(&Default::default(), extinction);
        let mut ms = Vec::new();
        let mut points = Vec::new();
        let cpu_start = cpu_ms();
        for (i, pose) in poses.iter().enumerate() {
            let t = Instant::now();
            let scan = black_box(lidar::scan(
                &target, None, &scanner, pose, 7, "bench", i as u64,
            ));
            ms.push(t.elapsed().as_secs_f64() * 1e3);
            points.push(scan.len() as f64);
        }
        let cpu = (cpu_ms() - cpu_start) / poses.len() as f64;
        let (min, max) = (
            ms.iter().copied().fold(f64::INFINITY, f64::min),
            ms.iter().copied().fold(0.0, f64::max),
        );
        println!(
            "{label:<28} {:>10.1} {:>10.1} {:>10.1} {:>10.1} {:>12.0}",
            median(ms),
            min,
            max,
            cpu,
            median(points)
        );
    }
}
