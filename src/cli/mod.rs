//! Command line: arguments → build driver calls → terminal output and exit codes.
//!
//! Exit codes: 0 ok, 1 the build failed, 2 an invalid spec, input or usage, 3 `--locked`
//! and the artifacts differ from the lock file (or there is none). This is the only
//! module that prints; the library returns typed errors and reports.

mod args;
mod exit_code;
mod print;
mod shared_args;

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Parser;

use crate::driver::{self, BuildError, BuildOptions};
use crate::model::FeatureKind;
use args::{Args, CacheCommand, Command, FacadesCommand};
use shared_args::{CacheArg, JobsArg, OutArg, SetArg};

/// Runs the command line and returns the process exit code.
// Long on purpose: the dispatch: one arm a command, each only turning its arguments into
// the options of the command's own function below.
pub fn run() -> ExitCode {
    let args = match Args::try_parse() {
        Ok(args) => args,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() {
                ExitCode::from(2)
            } else {
                ExitCode::SUCCESS
            };
        }
    };
    let terminal = std::io::stderr().is_terminal();
    let color = terminal && std::env::var_os("NO_COLOR").is_none();
    let verbose = match &args.command {
        Command::Build { verbosity, .. } | Command::Verify { verbosity, .. } => verbosity.verbose,
        _ => 0,
    };
    if args.quiet && verbose > 0 {
        use clap::CommandFactory;
        Args::command()
            .error(
                clap::error::ErrorKind::ArgumentConflict,
                "--quiet and --verbose cannot be used together",
            )
            .exit();
    }
    let out = print::Printer {
        quiet: args.quiet,
        verbose,
        color,
    };
    let cx = Context {
        out,
        quiet: args.quiet,
        terminal,
    };
    match args.command {
        Command::Build {
            verbosity: _,
            specs,
            out: OutArg { out: out_root },
            cache: CacheArg { cache },
            jobs: JobsArg { jobs },
            strict,
            set: SetArg { sets },
            shard,
            shard_count,
            stage,
            locked,
        } => {
            let options = BuildOptions {
                out_root,
                cache_dir: cache,
                progress: cx.progress(),
                waiting: Some(print::waiting_line()),
                strict,
                locked,
                sets,
            };
            let shards = (shard.is_some() || stage.is_some()).then_some((shard, shard_count));
            build_command(&cx, &specs, &options, jobs, shards)
        }
        Command::Lock {
            specs,
            out: OutArg { out: out_root },
            cache: CacheArg { cache },
            jobs: JobsArg { jobs },
        } => {
            let options = BuildOptions {
                out_root,
                cache_dir: cache,
                progress: cx.progress(),
                waiting: Some(print::waiting_line()),
                strict: false,
                locked: false,
                sets: Vec::new(),
            };
            lock_command(&cx, &specs, &options, jobs)
        }
        Command::Verify {
            verbosity: _,
            specs,
            cache: CacheArg { cache },
            all,
            sample,
            seed,
            jobs: JobsArg { jobs },
        } => {
            let options = driver::VerifyOptions {
                cache_dir: cache,
                all,
                sample,
                seed: seed.unwrap_or_else(clock_seed),
            };
            verify_command(&cx, &specs, &options, jobs)
        }
        Command::Validate {
            specs,
            set: SetArg { sets },
        } => validate_command(&cx, &specs, &sets),
        Command::Facades(FacadesCommand::Export { dir }) => facades_export(&cx, &dir),
        Command::Osm {
            file,
            bbox,
            json,
            picture,
            picture_size,
            overview,
        } => osm(
            &cx,
            &file,
            bbox,
            driver::OsmOutputs {
                json,
                picture: picture.map(|p| (p, picture_size)),
                overview,
            },
        ),
        Command::Cache(CacheCommand::Gc {
            specs,
            cache: CacheArg { cache },
            max_size,
            max_age,
            grace_minutes,
        }) => {
            let seconds = |s: f64| std::time::Duration::try_from_secs_f64(s.max(0.0));
            let (Ok(grace), Ok(max_age)) = (
                seconds(grace_minutes * 60.0),
                max_age.map(|d| seconds(d * 86_400.0)).transpose(),
            ) else {
                eprintln!("error: --max-age and --grace-minutes take a number");
                return ExitCode::from(2);
            };
            let options = driver::GcOptions {
                cache_dir: cache,
                max_size,
                max_age,
                grace,
            };
            cache_gc(&cx, &specs, &options)
        }
        Command::Explain {
            specs,
            cache: CacheArg { cache },
            json,
            set: SetArg { sets },
        } => explain_command(&cx, &specs, &sets, &cache, json),
        Command::Schema => print::stdout(&crate::spec::schema_json()),
        Command::Stats { dir, json } => stats_command(&dir, json),
        Command::Pack { spec, out } => pack_command(&cx, &spec, &out),
    }
}

/// What every command prints with.
struct Context {
    out: print::Printer,
    quiet: bool,
    /// Standard error is a terminal (the progress line is drawn in place).
    terminal: bool,
}

impl Context {
    /// The progress line of frames rendered, unless `--quiet`.
    fn progress(&self) -> Option<driver::Progress> {
        (!self.quiet).then(|| print::progress_line(self.terminal))
    }
}

/// `cityspec build`: every spec into its output folder, or with `shards` (`--shard`,
/// `--shard-count`; `--stage city` when the shard is `None`) a shard's share into the
/// cache.
fn build_command(
    cx: &Context,
    specs: &[PathBuf],
    options: &BuildOptions,
    jobs: Option<u16>,
    shards: Option<(Option<driver::ShardArg>, Option<u32>)>,
) -> ExitCode {
    let pool = match pool(jobs) {
        Ok(pool) => pool,
        Err(code) => return code,
    };
    if let Some((shard, shard_count)) = shards {
        let shard = match shard.map(|s| s.resolve(shard_count, |k| std::env::var(k).ok())) {
            Some(Err(e)) => {
                eprintln!("error: --shard: {e}");
                return ExitCode::from(2);
            }
            Some(Ok(shard)) => Some(shard),
            None => None,
        };
        return match pool.install(|| driver::build_shards(specs, options, shard)) {
            Ok(reports) => {
                reports.iter().for_each(|r| cx.out.shard_report(r));
                ExitCode::SUCCESS
            }
            Err(errors) => exit_for(&errors, &cx.out),
        };
    }
    match pool.install(|| driver::build_all(specs, options)) {
        Ok(reports) => {
            for report in &reports {
                cx.out.report(report);
            }
            ExitCode::SUCCESS
        }
        Err(errors) => exit_for(&errors, &cx.out),
    }
}

/// `cityspec lock`: build, then write each spec's lock file.
fn lock_command(
    cx: &Context,
    specs: &[PathBuf],
    options: &BuildOptions,
    jobs: Option<u16>,
) -> ExitCode {
    let pool = match pool(jobs) {
        Ok(pool) => pool,
        Err(code) => return code,
    };
    match pool.install(|| driver::lock_all(specs, options)) {
        Ok(locks) => {
            for lock in &locks {
                cx.out.info(&format!("wrote {}", lock.display()));
            }
            ExitCode::SUCCESS
        }
        Err(errors) => exit_for(&errors, &cx.out),
    }
}

/// `cityspec verify`: rerun cached stages and compare; exit 1 when any differs.
fn verify_command(
    cx: &Context,
    specs: &[PathBuf],
    options: &driver::VerifyOptions,
    jobs: Option<u16>,
) -> ExitCode {
    let pool = match pool(jobs) {
        Ok(pool) => pool,
        Err(code) => return code,
    };
    match pool.install(|| driver::verify_all(specs, options)) {
        Ok(reports) => {
            let failed = reports.iter().any(|r| r.failed().next().is_some());
            for report in &reports {
                cx.out
                    .verify_report(report, (!options.all).then_some(options.seed));
            }
            if failed {
                ExitCode::from(1)
            } else {
                ExitCode::SUCCESS
            }
        }
        Err(errors) => exit_for(&errors, &cx.out),
    }
}

/// `cityspec validate`: every spec checked as a build would, every error reported.
fn validate_command(cx: &Context, specs: &[PathBuf], sets: &[String]) -> ExitCode {
    let mut errors = Vec::new();
    for path in specs {
        match driver::validate(path, sets) {
            Ok((spec, warnings)) => {
                for line in print::diagnostic_lines(path, &warnings) {
                    eprintln!("{line}");
                }
                cx.out
                    .info(&format!("{}: ok ({})", path.display(), spec.name));
            }
            Err(e) => errors.push(e),
        }
    }
    if errors.is_empty() {
        ExitCode::SUCCESS
    } else {
        exit_for(&errors, &cx.out)
    }
}

/// `cityspec facades export DIR`.
fn facades_export(cx: &Context, dir: &Path) -> ExitCode {
    match driver::export_builtin_facades(dir) {
        Ok(count) => {
            cx.out.info(&format!(
                "wrote {count} built-in facades to {}",
                dir.display()
            ));
            ExitCode::SUCCESS
        }
        Err(e) => exit_for(&[e], &cx.out),
    }
}

/// `cityspec osm EXTRACT`: what the map holds.
fn osm(
    cx: &Context,
    file: &Path,
    bbox: Option<crate::model::GeoBox>,
    outputs: driver::OsmOutputs,
) -> ExitCode {
    let map = match driver::read_osm(file, bbox, &outputs) {
        Ok(map) => map,
        Err(e) => return exit_for(&[e], &cx.out),
    };
    let b = &map.bounds;
    let [x0, z0, x1, z1] = map.extent;
    // + 0.0: an empty sum is -0.0.
    let area: f64 = map.buildings.iter().map(|b| b.area).sum::<f64>() + 0.0;
    let with_height = map.buildings.iter().filter(|b| b.height.is_some()).count();
    let with_parts: Vec<_> = map
        .buildings
        .iter()
        .filter(|b| !b.parts.is_empty())
        .collect();
    let drivable: Vec<_> = map.roads.iter().filter(|r| r.drivable).collect();
    let km = |roads: &[&crate::model::MapRoad]| {
        roads.iter().map(|r| r.length).sum::<f64>() / 1000.0 + 0.0
    };
    let paths: Vec<_> = map.roads.iter().filter(|r| !r.drivable).collect();
    let l = &map.left_out;
    cx.out.info(&format!(
        "{}: box {:.6},{:.6},{:.6},{:.6} ({:.0} × {:.0} m)\n  {} buildings ({} with a height from the map, {} with {} parts), {:.0} m² of footprint\n  {} road pieces ({:.2} km), {} paths ({:.2} km)\n  {} traffic signals, {} street lamps, {} trees, {} benches, {} traffic signs, {} crossings\n  street: carriageway {:.0} m², sidewalks {:.0} m², {} blocks ({:.0} m², {:.0} m² of it green with {:.0} m² of paths across it, {:.0} m² squares); {} road segments narrowed between buildings, {} unpaved under them\n  left out: {} buildings crossing the box, {} unclosed, {} incomplete multipolygons, {} ways missing nodes, {} roads outside the box, {} incomplete green areas or squares, {} parts in no building",
        file.display(),
        b.south, b.west, b.north, b.east, x1 - x0, z1 - z0,
        map.buildings.len(), with_height, with_parts.len(), with_parts.iter().map(|b| b.parts.len()).sum::<usize>(), area,
        drivable.len(), km(&drivable), paths.len(), km(&paths),
        count(&map, FeatureKind::TrafficSignals), count(&map, FeatureKind::StreetLamp),
        count(&map, FeatureKind::Tree), count(&map, FeatureKind::Bench),
        count(&map, FeatureKind::TrafficSign), count(&map, FeatureKind::Crossing),
        surface(&map.carriageway), surface(&map.sidewalks), map.blocks.len(), surface(&map.blocks),
        map.green.iter().map(|g| g.shape.area).sum::<f64>() + 0.0,
        map.paths.iter().map(|g| g.shape.area).sum::<f64>() + 0.0,
        map.squares.iter().map(|g| g.shape.area).sum::<f64>() + 0.0,
        l.segments_narrowed, l.segments_blocked,
        l.buildings_outside, l.buildings_open, l.buildings_incomplete, l.ways_missing_nodes, l.roads_outside,
        l.areas_incomplete, l.parts_alone,
    ));
    for (what, path) in [
        ("map", outputs.json.as_deref()),
        ("picture", outputs.picture.as_ref().map(|p| p.0.as_path())),
    ] {
        if let Some(path) = path {
            cx.out
                .info(&format!("wrote the {what} to {}", path.display()));
        }
    }
    ExitCode::SUCCESS
}

fn surface(polygons: &[crate::model::MapPolygon]) -> f64 {
    polygons.iter().map(|p| p.area).sum::<f64>() + 0.0
}

fn count(map: &crate::model::OsmMap, kind: FeatureKind) -> usize {
    map.features.iter().filter(|f| f.kind == kind).count()
}

/// `cityspec cache gc`: what it kept and removed, and (even with `--quiet`) what it left
/// because the cache does not write it.
fn cache_gc(cx: &Context, specs: &[PathBuf], options: &driver::GcOptions) -> ExitCode {
    let r = match driver::gc(specs, options) {
        Ok(report) => report,
        Err(errors) => return exit_for(&errors, &cx.out),
    };
    cx.out.info(&format!(
        "kept {} entries and {} objects; removed {} entries, {} objects, {} temporaries ({:.1} MiB); the cache holds {:.1} MiB",
        r.kept_entries,
        r.kept_objects,
        r.removed_entries,
        r.removed_objects,
        r.removed_temporaries,
        r.removed_bytes as f64 / 1048576.0,
        r.bytes as f64 / 1048576.0
    ));
    if r.removed_damaged > 0 {
        cx.out.info(&format!(
            "removed {} damaged files (FIFOs, symlinks or other non-regular files where the \
             cache keeps its files)",
            r.removed_damaged
        ));
    }
    if !r.skipped.is_empty() {
        const SHOWN: usize = 10;
        let mut names: Vec<&str> = r.skipped.iter().take(SHOWN).map(String::as_str).collect();
        if r.skipped.len() > SHOWN {
            names.push("…");
        }
        eprintln!(
            "skipped {} files and folders that cityspec does not write (left as they are): {}",
            r.skipped.len(),
            names.join(", ")
        );
    }
    ExitCode::SUCCESS
}

/// `cityspec explain`: each spec's stages, on standard output.
fn explain_command(
    cx: &Context,
    specs: &[PathBuf],
    sets: &[String],
    cache: &Path,
    json: bool,
) -> ExitCode {
    let mut explained = Vec::new();
    let mut errors = Vec::new();
    for path in specs {
        match driver::explain(path, sets, cache) {
            Ok(one) => explained.push(one),
            Err(e) => errors.push(e),
        }
    }
    if !errors.is_empty() {
        return exit_for(&errors, &cx.out);
    }
    if json {
        let text = serde_json::to_string_pretty(&explained).expect("explanations serialize");
        print::stdout(&format!("{text}\n"))
    } else {
        print::stdout(&explained.iter().map(print::explained).collect::<String>())
    }
}

/// `cityspec pack SPEC -o FILE`: the spec and its files in one tar.
fn pack_command(cx: &Context, spec: &Path, out: &Path) -> ExitCode {
    let packed = match driver::pack(spec) {
        Ok(packed) => packed,
        Err(e) => return exit_for(&[e], &cx.out),
    };
    if let Err(e) = driver::write_atomic(out, &packed.bytes) {
        eprintln!("error: cannot write {}: {e}", out.display());
        return ExitCode::from(1);
    }
    if !cx.quiet {
        println!(
            "packed {} files ({} bytes) into {}; the spec is {} inside it",
            packed.entries.len(),
            packed.bytes.len(),
            out.display(),
            packed.spec
        );
    }
    ExitCode::SUCCESS
}

/// `cityspec stats DIR`: a table, or JSON.
fn stats_command(dir: &Path, json: bool) -> ExitCode {
    match crate::stats::measure(dir) {
        Ok(stats) if json => print::stdout(&format!(
            "{}\n",
            serde_json::to_string_pretty(&stats).expect("stats serialize")
        )),
        Ok(stats) => print::stdout(&crate::stats::table(&stats)),
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// A worker pool of `jobs` threads (default: one per core).
fn pool(jobs: Option<u16>) -> Result<rayon::ThreadPool, ExitCode> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.map_or(0, usize::from))
        .build()
        .map_err(|e| {
            eprintln!(
                "error: cannot start {} worker threads: {e}",
                jobs.map_or(0, usize::from)
            );
            ExitCode::from(1)
        })
}

/// A sample seed for `verify` when none is given: a different sample on every run.
fn clock_seed() -> u64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos() as u64 % 1_000_000)
}

fn exit_for(errors: &[BuildError], out: &print::Printer) -> ExitCode {
    for error in errors {
        // An error about a line of a model's OBJ or MTL shows that line, as spec errors do.
        match driver::framed_report(error, out.color) {
            Some(report) => eprint!("{report}"),
            None => out.error(error),
        }
    }
    ExitCode::from(exit_code::exit_code_of(errors))
}
