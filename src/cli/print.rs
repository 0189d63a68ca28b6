//! Terminal output: build summaries, per-stage lines and rendered errors, on stderr.

use crate::build::{BuildError, BuildReport, StageStatus, VerifyReport};

pub struct Printer {
    pub quiet: bool,
    pub verbose: bool,
    pub color: bool,
}

impl Printer {
    pub fn info(&self, line: &str) {
        if !self.quiet {
            eprintln!("{line}");
        }
    }

    /// One line per spec a shard (or `--stage city`) worked on.
    pub fn shard_report(&self, report: &crate::build::ShardReport) {
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
        for warning in &report.warnings {
            eprintln!("warning: {}: {warning}", report.name);
        }
        if self.quiet {
            return;
        }
        if self.verbose {
            for run in &report.stages {
                let status = match run.status {
                    StageStatus::Ran => "ran",
                    StageStatus::Cached => "cached",
                };
                let key = match run.key.get(..12) {
                    Some(short) => format!("key {short}"),
                    None => "(not cached)".to_owned(),
                };
                eprintln!(
                    "  {status:<6} {:<8} {:>9.2} ms  {key}",
                    run.stage,
                    run.time.as_secs_f64() * 1e3,
                );
            }
            for path in &report.written {
                eprintln!("  wrote  {}", report.out_dir.join(path).display());
            }
            for path in &report.removed {
                eprintln!("  removed stale {}", report.out_dir.join(path).display());
            }
        }
        if let Some(triangles) = report.triangles
            && self.verbose
        {
            eprintln!("  scene: {triangles} triangles");
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
                "{}: built {} ({ran} stages ran, {cached} cached; {} files written, {} unchanged) [{ms:.1} ms]",
                report.name,
                report.out_dir.display(),
                report.written.len(),
                report.unchanged.len()
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
                None if self.verbose => eprintln!(
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
            BuildError::Spec(errors) => eprint!("{}", crate::spec::render(errors, self.color)),
            other => eprintln!("error: {other}"),
        }
    }
}

/// A one-line progress report of rendered frames, with frames per second, redrawn in place
/// on a terminal (at most ten times a second) and printed once per path otherwise.
pub fn progress_line(terminal: bool) -> crate::build::Progress {
    use std::sync::Mutex;
    use std::time::{Duration, Instant};
    let state: Mutex<Option<(String, Instant, Instant)>> = Mutex::new(None);
    std::sync::Arc::new(move |spec: &str, camera: &str, done: usize, total: usize| {
        let mut state = state.lock().unwrap_or_else(|e| e.into_inner());
        let path = format!("{spec}/{camera}");
        let now = Instant::now();
        let (started, last) = match &*state {
            Some((p, started, last)) if *p == path => (*started, *last),
            _ => (now, now - Duration::from_secs(1)),
        };
        let finished = done == total;
        let rate = done as f64 / now.duration_since(started).as_secs_f64().max(1e-9);
        if terminal && (finished || now.duration_since(last) >= Duration::from_millis(100)) {
            eprint!("\r  rendering {path}: {done}/{total} frames, {rate:.1} frames/s   ");
            if finished {
                eprintln!();
            }
            *state = Some((path, started, now));
        } else {
            if !terminal && finished {
                eprintln!("  rendered {path}: {total} frames, {rate:.1} frames/s");
            }
            *state = Some((path, started, last));
        }
    })
}

/// Says that this build waits for another build of the same output folder (even with
/// `--quiet`: a build that seems to hang should say why).
pub fn waiting_line() -> crate::build::Waiting {
    std::sync::Arc::new(|dir: &std::path::Path| {
        eprintln!(
            "waiting for another cityspec build of {} to finish…",
            dir.display()
        );
    })
}
