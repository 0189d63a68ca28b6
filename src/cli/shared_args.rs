//! Options several subcommands share, written once and flattened into each.

use std::path::PathBuf;

/// `--cache`: build, lock, verify, cache gc.
#[derive(Debug, clap::Args)]
pub struct CacheArg {
    /// Stage cache: a folder, or s3://BUCKET/PREFIX, gs://… or az://CONTAINER/… shared
    /// by several machines (credentials and endpoint from the environment as the
    /// cloud's SDK reads them: AWS_ACCESS_KEY_ID, AWS_REGION, AWS_ENDPOINT_URL,
    /// AWS_ALLOW_HTTP=true for a plain-HTTP S3-compatible server, …).
    #[arg(long, value_name = "DIR|URL", default_value = ".cityspec-cache", value_parser = crate::driver::cache_location)]
    pub cache: PathBuf,
}

/// `--out`: build, lock.
#[derive(Debug, clap::Args)]
pub struct OutArg {
    /// Parent folder of the output folders: each spec writes OUT/<name>/.
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
}

/// `-j`: build, lock, verify.
#[derive(Debug, clap::Args)]
pub struct JobsArg {
    /// Worker threads (default: one per core). Output bytes never depend on it.
    #[arg(short = 'j', long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=512))]
    pub jobs: Option<u16>,
}

/// `--set`: build, validate, explain.
#[derive(Debug, clap::Args)]
pub struct SetArg {
    /// Override one spec value after `extends`, with the merge rules of `extends`:
    /// KEY.PATH=VALUE, VALUE read as TOML (`4`, `[1, 2]`, `"night"`; anything else is
    /// taken as a string). Bare dotted keys; an array of named tables is entered by an
    /// entry's name: `--set cameras.street.frames=4`. Repeatable; applied in order to
    /// every spec given.
    #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
    pub sets: Vec<String>,
}
