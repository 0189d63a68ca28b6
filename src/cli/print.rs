//! Terminal output: build summaries, per-stage lines and rendered errors, on stderr.

use crate::diagnostic::Diagnostic;
use crate::driver::{BuildError, BuildReport, StageStatus, VerifyReport};

use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Writes a command's result to stdout. A reader that stops early (`| head`) is not an
/// error: the rest is dropped and the command still succeeds; any other write error is
/// reported and exits 1.
pub fn stdout(text: &str) -> ExitCode {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: cannot write to stdout: {e}");
            ExitCode::from(1)
        }
    }
}

pub struct Printer {
    pub quiet: bool,
    /// 0: a summary line per spec; 1: also every stage and files per folder; 2: also
    /// every file.
    pub verbose: u8,
    pub color: bool,
}

impl Printer {
    pub fn info(&self, line: &str) {
        if !self.quiet {
            eprintln!("{line}");
        }
    }

    /// One line per spec a shard (or `--stage city`) worked on.
    pub fn shard_report(&self, report: &crate::driver::ShardReport) {
        let s = &report.stats;
        let line = match report.shard {
            Some(shard) => format!(
                "{}: shard {}/{}: rendered {} chunks ({} frames), {} already cached, {} left to other shards, in {:.2} s",
                report.name,
                shard.index,
                shard.count,
                s.rendered_chunks,
                s.frames,
                s.cached_chunks,
                s.other_chunks,
                report.elapsed.as_secs_f64()
            ),
            None => format!(
                "{}: shared stages in the cache, in {:.2} s",
                report.name,
                report.elapsed.as_secs_f64()
            ),
        };
        self.info(&line);
    }

    pub fn report(&self, report: &BuildReport) {
        for run in &report.stages {
            if let Some(why) = &run.repaired {
                eprintln!("warning: {}: damaged cache entry rebuilt: {why}", run.stage);
            }
        }
        for line in diagnostic_lines(&report.spec, &report.warnings) {
            eprintln!("{line}");
        }
        if self.quiet {
            return;
        }
        if self.verbose >= 1 {
            for run in &report.stages {
                let status = match run.status {
                    StageStatus::Ran => "ran",
                    StageStatus::Cached => "cached",
                };
                let key = match run.key.get(..12) {
                    Some(short) => format!("key {short}"),
                    None => "(not cached)".to_owned(),
                };
                let stage = match &run.camera {
                    Some(camera) => format!("{} {camera}", run.stage),
                    None => run.stage.to_owned(),
                };
                eprintln!(
                    "  {status:<6} {stage:<16} {:>9.2} ms  {key}",
                    run.time.as_secs_f64() * 1e3,
                );
            }
            if let Some(triangles) = report.triangles {
                eprintln!("  scene: {triangles} triangles");
            }
            self.files("wrote", &report.out_dir, &report.written);
            self.files("removed stale", &report.out_dir, &report.removed);
        }
        let ms = report.elapsed.as_secs_f64() * 1e3;
        let ran = report.ran().count();
        let cached = report.stages.len() - ran;
        if report.up_to_date() {
            eprintln!(
                "{}: up to date in {}, nothing to do ({cached} stages cached, nothing written) [{ms:.1} ms]",
                report.name,
                report.out_dir.display()
            );
        } else {
            eprintln!(
                "{}: built {} ({} ran, {cached} cached; {} written, {} unchanged) [{ms:.1} ms]",
                report.name,
                report.out_dir.display(),
                plural(ran, "stage"),
                plural(report.written.len(), "file"),
                report.unchanged.len()
            );
        }
    }

    /// Files a build wrote or removed: with `-v` a count per folder, with `-vv` each file.
    fn files(&self, what: &str, out_dir: &Path, paths: &[String]) {
        if self.verbose >= 2 {
            for path in paths {
                eprintln!("  {what} {}", out_dir.join(path).display());
            }
            return;
        }
        for (folder, count) in per_folder(paths) {
            eprintln!(
                "  {what} {} in {}",
                plural(count, "file"),
                out_dir.join(folder).display()
            );
        }
    }

    /// One spec's cache check: every entry that differs, then a summary line.
    pub fn verify_report(&self, report: &VerifyReport, seed: Option<u64>) {
        for verdict in &report.verdicts {
            match &verdict.problem {
                Some(problem) => eprintln!(
                    "error: {}: stage {} (cache entry {}) does not rebuild to its cached \
                     bytes: {problem}; remove the entry and build again",
                    report.name,
                    verdict.stage,
                    verdict.entry.display()
                ),
                None if self.verbose >= 1 => eprintln!(
                    "  ok     {:<8} key {}",
                    verdict.stage,
                    verdict.key.get(..12).unwrap_or(&verdict.key)
                ),
                None => {}
            }
        }
        let failed = report.failed().count();
        let sample = match seed {
            Some(seed) => format!(" (a sample, --seed {seed})"),
            None => String::new(),
        };
        if failed > 0 || !self.quiet {
            eprintln!(
                "{}: rechecked {} of {} cached stages{sample}: {}",
                report.name,
                report.verdicts.len(),
                report.cached,
                if failed == 0 {
                    "all rebuild to their cached bytes".to_owned()
                } else {
                    format!("{failed} differ")
                }
            );
        }
    }

    pub fn error(&self, error: &BuildError) {
        match error {
            BuildError::Spec(errors) => eprint!("{}", crate::spec::report(errors, self.color)),
            other => eprintln!("error: {other}"),
        }
    }
}

/// A one-line progress report of rendered frames: on a terminal an `indicatif` bar per
/// camera path, redrawn in place (at most ten times a second); otherwise one line per path
/// when it is done, and no bar at all. The rate is shown once it means something: measured
/// from the first frame over at least half a second.
pub fn progress_line(terminal: bool) -> crate::driver::Progress {
    use std::sync::Mutex;
    use std::time::Instant;
    /// The path being rendered, when its first frame was reported (and how many were done
    /// then), and its bar on a terminal.
    struct PathProgress {
        path: String,
        first: (Instant, usize),
        bar: Option<indicatif::ProgressBar>,
    }
    let state: Mutex<Option<PathProgress>> = Mutex::new(None);
    std::sync::Arc::new(move |spec: &str, camera: &str, done: usize, total: usize| {
        let mut state = state.lock().unwrap_or_else(|e| e.into_inner());
        let path = format!("{spec}/{camera}");
        let now = Instant::now();
        let current = match state.take() {
            Some(p) if p.path == path => p,
            previous => {
                if let Some(bar) = previous.and_then(|p| p.bar) {
                    bar.abandon();
                }
                PathProgress {
                    bar: terminal.then(|| path_bar(&path, total)),
                    path,
                    first: (now, done),
                }
            }
        };
        let rate = frame_rate(current.first, (now, done));
        let finished = done == total;
        match &current.bar {
            // The finished line is printed by us, with its newline: the bar's own last
            // draw pads to the terminal's width and leaves the next line to its wrapping.
            Some(bar) if finished => {
                bar.finish_and_clear();
                eprintln!("  rendering {}: {done}/{total} frames{rate}", current.path);
            }
            Some(bar) => {
                bar.set_message(rate);
                bar.set_position(done as u64);
            }
            None if finished => {
                eprintln!(
                    "  rendered {}: {}{rate}",
                    current.path,
                    plural(total, "frame")
                );
            }
            None => {}
        }
        *state = Some(current);
    })
}

/// `  rendering <spec>/<camera>: 12/40 frames, 3.1 frames/s` on stderr, the rate its
/// message.
fn path_bar(path: &str, total: usize) -> indicatif::ProgressBar {
    let target = indicatif::ProgressDrawTarget::stderr_with_hz(10);
    let bar = indicatif::ProgressBar::with_draw_target(Some(total as u64), target);
    let style =
        indicatif::ProgressStyle::with_template("  rendering {prefix}: {pos}/{len} frames{msg}")
            .expect("the template is valid");
    bar.set_style(style);
    bar.set_prefix(path.to_owned());
    bar
}

/// ", 12.3 frames/s" from the first report to now, or nothing while too little has been
/// seen to say (one frame, or under half a second).
fn frame_rate(
    (start, start_done): (std::time::Instant, usize),
    (now, done): (std::time::Instant, usize),
) -> String {
    let seconds = now.duration_since(start).as_secs_f64();
    let frames = done.saturating_sub(start_done);
    if frames == 0 || seconds < 0.5 {
        return String::new();
    }
    format!(", {:.1} frames/s", frames as f64 / seconds)
}

/// "1 file", "2 files".
fn plural(count: usize, noun: &str) -> String {
    match count {
        1 => format!("1 {noun}"),
        n => format!("{n} {noun}s"),
    }
}

/// How many of `paths` lie directly in each folder ("" for the top), by folder.
fn per_folder(paths: &[String]) -> BTreeMap<&str, usize> {
    let mut counts = BTreeMap::new();
    for path in paths {
        let folder = path.rsplit_once('/').map_or("", |(folder, _)| folder);
        *counts.entry(folder).or_insert(0) += 1;
    }
    counts
}

/// Says that this build waits for another build of the same output folder (even with
/// `--quiet`: a build that seems to hang should say why).
pub fn waiting_line() -> crate::driver::Waiting {
    std::sync::Arc::new(|dir: &std::path::Path| {
        eprintln!(
            "waiting for another cityspec build of {} to finish…",
            dir.display()
        );
    })
}

/// `cityspec explain`'s text for one spec: a line per stage (name, camera, short key,
/// cache state), then what its key reads.
pub fn explained(explained: &crate::driver::Explained) -> String {
    use crate::driver::EntryState;
    let mut text = format!(
        "{} ({}), cache {}\n",
        explained.name,
        explained.spec.display(),
        explained.cache.display()
    );
    for line in &explained.stages {
        let stage = match &line.camera {
            Some(camera) => format!("{} {camera}", line.stage),
            None => line.stage.to_string(),
        };
        let state = match &line.state {
            EntryState::Missing => "missing: runs at the next build".to_owned(),
            EntryState::Cached {
                outputs,
                bytes,
                diagnostics,
            } => {
                let warned = match diagnostics {
                    0 => String::new(),
                    n => format!(", {n} warnings"),
                };
                let plural = if *outputs == 1 { "" } else { "s" };
                let size = if *bytes < 1 << 20 {
                    format!("{:.1} KiB", *bytes as f64 / 1024.0)
                } else {
                    format!("{:.1} MiB", *bytes as f64 / 1_048_576.0)
                };
                format!("cached: {outputs} output{plural}, {size}{warned}")
            }
            EntryState::Older => "older: an earlier cityspec's entry, runs again".to_owned(),
            EntryState::Damaged(why) => format!("damaged: rebuilt at the next build ({why})"),
        };
        let key = line.key.get(..12).unwrap_or(&line.key);
        text.push_str(&format!("  {stage:<22} {key}  {state}\n"));
        let mut reads = vec![format!("version {}", line.version)];
        if !line.spec.is_empty() {
            reads.push(format!("spec {}", line.spec.join(", ")));
        }
        for (name, value) in &line.inputs {
            reads.push(format!("{name} {}", value.get(..12).unwrap_or(value)));
        }
        text.push_str(&format!("  {:<22} reads {}\n", "", reads.join("; ")));
    }
    text
}

/// Each diagnostic as `spec.toml:LINE:COL: warning[code]: message (file)`, placed at its
/// key where the spec (or a base it extends) still writes it; the spec is read once for
/// all of them.
pub fn diagnostic_lines(spec: &Path, diagnostics: &[Diagnostic]) -> Vec<String> {
    if diagnostics.is_empty() {
        return Vec::new();
    }
    let keys: Vec<&str> = diagnostics
        .iter()
        .filter_map(|d| d.key.as_deref())
        .collect();
    let mut places = crate::spec::key_places(spec, &keys, &crate::spec::FsWorld)
        .unwrap_or_default()
        .into_iter();
    diagnostics
        .iter()
        .map(|d| {
            let place = d.key.as_ref().and_then(|_| places.next());
            diagnostic_line(spec, place, d)
        })
        .collect()
}

fn diagnostic_line(
    spec: &Path,
    place: Option<(PathBuf, usize, usize)>,
    diagnostic: &Diagnostic,
) -> String {
    let place = match place {
        Some((file, line, column)) => format!("{}:{line}:{column}", file.display()),
        None => spec.display().to_string(),
    };
    let file = match &diagnostic.file {
        Some(file) => format!(" ({file})"),
        None => String::new(),
    };
    format!("{place}: {diagnostic}{file}")
}

#[cfg(test)]
mod tests {
    use std::time::{Duration, Instant};

    use super::*;

    #[test]
    fn plural_and_folders() {
        assert_eq!(plural(1, "file"), "1 file");
        assert_eq!(plural(0, "file"), "0 files");
        assert_eq!(plural(500, "file"), "500 files");
        let paths = [
            "plan.png",
            "frames/a/rgb/000000.png",
            "frames/a/rgb/000001.png",
            "frames/a/coco.json",
        ]
        .map(String::from);
        let counts: Vec<(&str, usize)> = per_folder(&paths).into_iter().collect();
        assert_eq!(counts, [("", 1), ("frames/a", 1), ("frames/a/rgb", 2)]);
    }

    #[test]
    fn no_rate_until_it_means_something() {
        let start = Instant::now();
        // The first report: one frame done a moment ago, no time to measure.
        assert_eq!(frame_rate((start, 1), (start, 1)), "");
        assert_eq!(
            frame_rate((start, 1), (start + Duration::from_millis(100), 2)),
            ""
        );
        assert_eq!(
            frame_rate((start, 1), (start + Duration::from_secs(2), 5)),
            ", 2.0 frames/s"
        );
    }
}
