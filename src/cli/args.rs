//! The command line's shape (clap derive): subcommands, flags and their help.

use std::path::PathBuf;

use clap::{Parser, Subcommand};

use super::shared_args::{CacheArg, JobsArg, OutArg, SetArg};
use crate::model::GeoBox;

/// Turn a versioned TOML spec into a synthetic city dataset: a road layout, the city plan,
/// a textured 3D city, and rendered, labelled frames. The same spec gives the same bytes
/// on every machine.
///
/// Stages: layout (generated or your image) → mirror → parse (blocks, roads) → lamps and
/// place (buildings, paper Algorithm 1) → plan → facades (built-in set or a CMP folder) →
/// scene and objects (text, signs, meshes, trees, cars) → export (city.obj, city.glb) →
/// overview.png → per camera: render, sensor (weather, exposure) and annotate (COCO, YOLO,
/// ICDAR). Every stage's result is cached by the hash of what it reads, so a rebuild runs
/// only the stages whose inputs changed.
#[derive(Debug, Parser)]
#[command(name = "cityspec", version, propagate_version = true)]
#[command(
    after_help = "Examples:\n  cityspec build specs/day.toml\n  cityspec validate specs/*.toml\n  cityspec verify --all specs/day.toml\n  cityspec stats out/day\n  cityspec schema > schemas/cityspec.schema.json\n\nExit codes: 0 ok, 1 build failed, 2 invalid spec, input or usage, 3 --locked and an artifact differs from the lock file."
)]
pub struct Args {
    #[command(subcommand)]
    pub command: Command,
    /// Print only errors (and warnings).
    #[arg(short, long, global = true)]
    pub quiet: bool,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Build specs into output folders: layout.png, plan.json, plan.png, city.obj,
    /// city.mtl, textures/, city.glb, overview.png, frames/<camera>/ (rgb/, ids/, depth/,
    /// coco.json, poses.json, preview.png, and yolo/, icdar/ where asked), manifest.json.
    ///
    /// Each spec writes to OUT/<name>/. Stage results are cached by content hash in the
    /// cache folder, so a rebuild runs only the stages whose inputs changed, and a rebuild
    /// with nothing changed writes nothing. All specs are validated before any is built.
    #[command(
        after_help = "Examples:\n  cityspec build specs/day.toml\n  cityspec build -j1 --out build --cache /tmp/cs-cache specs/day.toml specs/drawn.toml\n  cityspec build -v specs/day.toml     # which stages ran or came from the cache, files per folder\n  cityspec build -vv specs/day.toml    # … and every file written or removed\n  AWS_REGION=eu-west-1 cityspec build --shard auto --cache s3://my-bucket/cityspec specs/day.toml"
    )]
    Build {
        #[command(flatten)]
        verbosity: Verbosity,
        /// Spec files (TOML).
        #[arg(required = true, value_name = "SPEC")]
        specs: Vec<PathBuf>,
        #[command(flatten)]
        out: OutArg,
        #[command(flatten)]
        cache: CacheArg,
        #[command(flatten)]
        jobs: JobsArg,
        /// Treat warnings (objects placed fewer times than `count` asks, facade problems, a
        /// camera path with no frames) as errors: exit code 2, and the output folder is left
        /// as it was. Warnings are kept with the cache, so a warm build fails as a cold one.
        #[arg(long)]
        strict: bool,
        #[command(flatten)]
        set: SetArg,
        /// Build only shard I of N (0-based) into the cache, no output folder: the city's
        /// stages and every I-th chunk of each camera path. `auto` reads
        /// SLURM_ARRAY_TASK_ID/_COUNT or JOB_COMPLETION_INDEX. A plain build afterwards
        /// (the merge) writes the output folder from the cache.
        #[arg(long, value_name = "I/N|auto", value_parser = crate::driver::ShardArg::parse)]
        shard: Option<crate::driver::ShardArg>,
        /// The number of shards, for `--shard auto` under Kubernetes (or
        /// CITYSPEC_SHARD_COUNT).
        #[arg(long, value_name = "N", requires = "shard")]
        shard_count: Option<u32>,
        /// Build only the stages every shard shares (the city, the camera paths' poses)
        /// into the cache, before an array of shards starts.
        #[arg(long, value_name = "STAGE", value_parser = ["city"], conflicts_with = "shard")]
        stage: Option<String>,
        /// Fail with exit code 3, before the output folder is touched, when any artifact
        /// differs from the spec's lock file (`cityspec lock`), or there is none.
        #[arg(long, conflicts_with_all = ["shard", "stage"])]
        locked: bool,
    },
    /// Build specs and write each one's lock file beside it (`day.toml` → `day.lock`):
    /// the cityspec version and every artifact's SHA-256, size and path. Commit it, and
    /// build with `--locked` in CI.
    #[command(
        after_help = "Example:\n  cityspec lock specs/day.toml && git add specs/day.lock\n  cityspec build --locked specs/day.toml   # exit 3 when an artifact changed"
    )]
    Lock {
        /// Spec files (TOML).
        #[arg(required = true, value_name = "SPEC")]
        specs: Vec<PathBuf>,
        #[command(flatten)]
        out: OutArg,
        #[command(flatten)]
        cache: CacheArg,
        #[command(flatten)]
        jobs: JobsArg,
    },
    /// Check the cache: rerun a seeded sample of a spec's cached stages (or all of them)
    /// and compare their bytes with the cached ones, like Nix's `--check`.
    ///
    /// Finds entries that name whole, valid objects which are not what their stage makes
    /// (a poisoned shared cache, or a stage whose code changed without a `VERSION` bump).
    /// Each rechecked stage takes its inputs from the cache, so a bad entry is named by its
    /// own stage. Exit code 1 when any entry differs or is damaged.
    #[command(
        after_help = "Examples:\n  cityspec verify specs/day.toml                 # 3 stages, a fresh seed (printed)\n  cityspec verify --all specs/day.toml           # every cached stage\n  cityspec verify --sample 5 --seed 42 specs/*.toml"
    )]
    Verify {
        #[command(flatten)]
        verbosity: Verbosity,
        /// Spec files (TOML).
        #[arg(required = true, value_name = "SPEC")]
        specs: Vec<PathBuf>,
        #[command(flatten)]
        cache: CacheArg,
        /// Recheck every cached stage.
        #[arg(long, conflicts_with = "sample")]
        all: bool,
        /// How many cached stages of each spec to recheck.
        #[arg(long, value_name = "N", default_value_t = 3)]
        sample: usize,
        /// Seed of the sample (default: from the clock, printed so a run can be repeated).
        #[arg(long, value_name = "N")]
        seed: Option<u64>,
        #[command(flatten)]
        jobs: JobsArg,
    },
    /// Check specs (syntax, schema, meaning, input files) without building; report every
    /// error with file:line:col and key path.
    ///
    /// Input files are read and checked as `build` reads them: the layout image decoded,
    /// mesh models and word files parsed, a facade folder's photos, boxes and floors
    /// processed (a truncated photo is refused, or skipped with a warning under
    /// `on_error = "skip"`).
    #[command(after_help = "Example:\n  cityspec validate specs/*.toml")]
    Validate {
        /// Spec files (TOML).
        #[arg(required = true, value_name = "SPEC")]
        specs: Vec<PathBuf>,
        #[command(flatten)]
        set: SetArg,
    },
    /// Work with facade sets (paper 3.2).
    #[command(subcommand)]
    Facades(FacadesCommand),
    /// Work with the stage cache.
    #[command(subcommand)]
    Cache(CacheCommand),
    /// Read an OpenStreetMap extract into the map a city is built from: building footprints
    /// (with courtyards and parts) and heights, road centrelines with their widths and
    /// sidewalks, and the map's traffic signals, lamps, trees, benches, signs and
    /// crossings, in metres around the box's centre. Prints what it read; writes it as
    /// JSON and as a picture when asked.
    ///
    /// Buildings with a node outside the box are left out; roads are cut at its edges. The
    /// rules (which tags, which defaults, the projection) are in docs/osm.md. To build a
    /// city with frames and labels from a map, name it in a spec's `[layout.osm]` (see
    /// specs/osm.toml) and run `cityspec build`.
    #[command(
        after_help = "Examples:\n  cityspec osm assets/osm/helsinki.osm.pbf --picture map.png --overview city.png\n  cityspec osm city.osm --bbox 60.165,24.936,60.172,24.950 --json map.json"
    )]
    Osm {
        /// The extract: an .osm.pbf file or OSM XML.
        #[arg(value_name = "EXTRACT")]
        file: PathBuf,
        /// Only what lies in this box: south,west,north,east in degrees (default: the
        /// file's own bounds, else the extent of its nodes).
        #[arg(long, value_name = "S,W,N,E", value_parser = parse_box, allow_hyphen_values = true)]
        bbox: Option<GeoBox>,
        /// Write the map as JSON to this file.
        #[arg(long, value_name = "FILE")]
        json: Option<PathBuf>,
        /// Write a picture of the map (PNG, north up) to this file.
        #[arg(long, value_name = "FILE")]
        picture: Option<PathBuf>,
        /// Render the map's 3D city from the air to this file (PNG): its street surface and
        /// its buildings on their footprints, at their mapped heights, clad in the
        /// built-in facades, under a day sun at the map's latitude.
        #[arg(long, value_name = "FILE")]
        overview: Option<PathBuf>,
        /// The picture's longer side in pixels.
        #[arg(long, value_name = "PIXELS", default_value_t = 2048, value_parser = clap::value_parser!(u32).range(64..=16384))]
        picture_size: u32,
    },
    /// Show each cached stage of a spec: what its key is the hash of (its version, the
    /// spec parts it reads, the stages and input files it consumes) and what the cache
    /// holds under it. Runs nothing and writes nothing.
    ///
    /// A stage whose key changed after an edit is `missing` and runs at the next build;
    /// the stages it consumes show which of them changed too.
    #[command(
        after_help = "Examples:\n  cityspec explain specs/day.toml\n  cityspec explain --json --cache /shared/cache specs/day.toml"
    )]
    Explain {
        /// Spec files (TOML).
        #[arg(required = true, value_name = "SPEC")]
        specs: Vec<PathBuf>,
        #[command(flatten)]
        cache: CacheArg,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        set: SetArg,
    },
    /// Pack a spec and every file it reads (layout image, facade folder, models, word
    /// files) into one tar, for a build on another machine.
    ///
    /// Entries keep their paths relative to the folder all the files share, so the spec's
    /// relative paths resolve the same once unpacked; the command prints where the spec
    /// is inside. The tar is the same bytes every time. `deploy/k8s/run.sh` ships a spec
    /// to its jobs this way.
    #[command(
        after_help = "Examples:\n  cityspec pack specs/day.toml -o day.tar\n  tar xf day.tar -C /work && cityspec build /work/specs/day.toml"
    )]
    Pack {
        /// The spec file (TOML).
        #[arg(value_name = "SPEC")]
        spec: PathBuf,
        /// The tar to write.
        #[arg(short, long, value_name = "FILE")]
        out: PathBuf,
    },
    /// Print the spec's JSON schema (Draft 2020-12), as committed in schemas/.
    ///
    /// Editors that read `#:schema` comments (Taplo, Even Better TOML) complete and check
    /// specs with it.
    #[command(after_help = "Example:\n  cityspec schema > schemas/cityspec.schema.json")]
    Schema,
    /// Measure a built output folder: per camera path, the pixel share of each object
    /// kind (from the ids images and the object names in city.obj), labelled objects per
    /// frame by class (median), and box-height percentiles (from coco.json).
    #[command(after_help = "Example:\n  cityspec stats out/day\n  cityspec stats --json out/day")]
    Stats {
        /// An output folder (OUT/<name>/) holding city.obj and frames/.
        #[arg(value_name = "OUT_DIR")]
        dir: PathBuf,
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
}

/// `-v`, where it prints more.
#[derive(Debug, clap::Args)]
pub struct Verbosity {
    /// More detail: -v every stage (ran or cached, time, cache key) and files per folder;
    /// -vv also every file.
    #[arg(short, long, action = clap::ArgAction::Count)]
    pub verbose: u8,
}

#[derive(Debug, Subcommand)]
pub enum CacheCommand {
    /// Remove what the given specs (and lock files) do not need: every other entry and
    /// object, or with --max-age only those older, with --max-size only the oldest until
    /// the cache fits. Safe while builds run: nothing younger than --grace-minutes goes.
    ///
    /// Only the cache's own files ever go: a folder (or prefix) without the CACHEDIR.TAG
    /// a cache's first write leaves is refused, names the cache does not write are left
    /// and listed, and no symlink is followed.
    #[command(
        after_help = "Examples:\n  cityspec cache gc specs/*.toml\n  cityspec cache gc --max-size 20G --cache /shared/cache specs/day.toml specs/night.lock\n  cityspec cache gc --max-age 30 --cache s3://my-bucket/cityspec specs/*.toml"
    )]
    Gc {
        /// Spec files (TOML) or lock files (`.lock`) whose artifacts to keep.
        #[arg(required = true, value_name = "SPEC")]
        specs: Vec<PathBuf>,
        #[command(flatten)]
        cache: CacheArg,
        /// Remove unneeded files, oldest first, only until the cache holds at most SIZE
        /// (bytes, or 500M, 20G, …).
        #[arg(long, value_name = "SIZE", value_parser = crate::driver::parse_size)]
        max_size: Option<u64>,
        /// Remove only unneeded files older than DAYS.
        #[arg(long, value_name = "DAYS")]
        max_age: Option<f64>,
        /// Never remove a file modified within this many minutes (a running build's).
        #[arg(long, value_name = "MINUTES", default_value_t = 60.0)]
        grace_minutes: f64,
    },
}

#[derive(Debug, Subcommand)]
pub enum FacadesCommand {
    /// Write cityspec's built-in facade set to DIR in the CMP Facade Database layout
    /// (`<name>.jpg` photo, `<name>.xml` boxes, `<name>.png` label mask), to look at or to
    /// start a set of your own from.
    #[command(
        after_help = "Example:\n  cityspec facades export builtin-facades/\n  # then in a spec: [facades] source = \"builtin-facades\""
    )]
    Export {
        /// Folder to write (created if missing).
        #[arg(value_name = "DIR")]
        dir: PathBuf,
    },
}

/// `--bbox S,W,N,E`: four numbers in degrees, south below north and west left of east.
fn parse_box(text: &str) -> Result<GeoBox, String> {
    let numbers: Vec<f64> = text
        .split(',')
        .map(|n| {
            n.trim()
                .parse::<f64>()
                .map_err(|_| format!("{n:?} is not a number"))
        })
        .collect::<Result<_, _>>()?;
    let [south, west, north, east] = numbers[..] else {
        return Err(format!(
            "expected four numbers south,west,north,east; got {}",
            numbers.len()
        ));
    };
    let b = GeoBox {
        south,
        west,
        north,
        east,
    };
    crate::osm::check_box(&b).map_err(|e| e.to_string())?;
    Ok(b)
}
