//! What the benchmarks share: the repository root, copying trees, the day spec without its
//! cameras, medians, and the CPU time and peak memory of this process.

#![allow(dead_code)] // each bench uses a part

use std::fs;
use std::path::{Path, PathBuf};

pub fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

#[path = "../../tests/common/copy_tree.rs"]
mod copy_tree;
#[allow(unused_imports)] // each bench uses a part
pub use copy_tree::copy_tree;

/// `specs/day.toml` with its `[[cameras]]` entries cut: the city alone.
pub fn day_without_cameras() -> String {
    let day = fs::read_to_string(repo().join("specs/day.toml")).unwrap();
    match (day.find("[[cameras]]"), day.find("[lighting]")) {
        (Some(a), Some(b)) if a < b => format!("{}{}", &day[..a], &day[b..]),
        _ => day,
    }
}

/// The `[[cameras]]` table of `specs/day.toml` named `name`, as written there (up to the
/// next table header).
pub fn day_camera(name: &str) -> String {
    let day = fs::read_to_string(repo().join("specs/day.toml")).unwrap();
    let tables: Vec<&str> = day.split("\n[").collect();
    tables
        .iter()
        .find(|t| {
            t.starts_with("[cameras]]")
                && t.lines()
                    .any(|l| l.split('#').next().unwrap().trim() == format!("name = \"{name}\""))
        })
        .map(|t| format!("[{t}"))
        .unwrap_or_else(|| panic!("specs/day.toml has no camera named {name:?}"))
}

/// `spec` with `key = value` added to its `[layout]` table. The day spec already opens
/// `[layout]` (for `metres_per_pixel`), so a second `[layout]` header would be a TOML
/// "duplicate key" error; a spec without the table gets one before `[layout.generate]`.
pub fn with_layout_key(spec: &str, key: &str, value: &str) -> String {
    let line = format!("{key} = {value}\n");
    match spec.find("\n[layout]") {
        Some(at) => {
            let after_header = at
                + 1
                + spec[at + 1..]
                    .find('\n')
                    .map_or(spec.len() - at - 1, |n| n + 1);
            format!("{}{line}{}", &spec[..after_header], &spec[after_header..])
        }
        None => spec.replacen(
            "[layout.generate]",
            &format!("[layout]\n{line}\n[layout.generate]"),
            1,
        ),
    }
}

/// `--child SPEC CACHE OUT`: the arguments of a bench's child build process, if it is one.
pub fn child_args() -> Option<[PathBuf; 3]> {
    let args: Vec<String> = std::env::args().collect();
    let i = args.iter().position(|a| a == "--child")?;
    Some(std::array::from_fn(|k| PathBuf::from(&args[i + 1 + k])))
}

/// Builds `spec` with this cache and output folder, without progress output.
pub fn build_into(spec: &Path, cache: &Path, out: &Path) -> cityspec::driver::BuildReport {
    cityspec::driver::build(
        spec,
        &cityspec::driver::BuildOptions {
            progress: None,
            out_root: out.to_path_buf(),
            cache_dir: cache.to_path_buf(),
            waiting: None,
            strict: false,
            locked: false,
            sets: Vec::new(),
        },
    )
    .unwrap()
}

/// Runs this bench again as a child build process (see [`child_args`]) and returns what
/// it printed: a fresh process, so its peak memory is the build's own.
pub fn run_child(spec: &Path, cache: &Path, out: &Path) -> String {
    let output = std::process::Command::new(std::env::current_exe().unwrap())
        .arg("--child")
        .arg(spec)
        .arg(cache)
        .arg(out)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).unwrap()
}

/// Runs per case: `BENCH_RUNS`, else `default`.
pub fn bench_runs(default: usize) -> usize {
    std::env::var("BENCH_RUNS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(default)
}

pub fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// Peak resident memory of this process so far, KiB (Linux `VmHWM`; 0 elsewhere).
pub fn peak_kib() -> u64 {
    let status = fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .unwrap_or(0)
}

/// CPU time of this process so far (user + system, all threads), ms; Linux only (0
/// elsewhere). `/proc/self/stat` counts in ticks of 10 ms (`CLK_TCK` = 100).
pub fn cpu_ms() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // Fields after the parenthesised command name: utime and stime are the 12th and 13th.
    let rest = stat.rsplit_once(')').map_or("", |(_, r)| r);
    let f: Vec<f64> = rest
        .split_whitespace()
        .skip(11)
        .take(2)
        .filter_map(|v| v.parse().ok())
        .collect();
    f.iter().sum::<f64>() * 10.0
}
