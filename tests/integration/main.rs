//! The integration tests, one module per subject, in one test binary.
//!
//! One binary instead of one per file: each links the whole library and its dependencies
//! (about 100 MB each), and on a 2-core CI machine ten such links cost more than the tests
//! they hold; in one binary the harness also runs every file's tests side by side. Two
//! suites stay binaries of their own because CI runs them apart: `tests/golden.rs` (again
//! in a release build) and `tests/s3_cache.rs` (with the `remote-cache` feature and a
//! local S3 server). Run one subject with `cargo test --test integration cli::`.

#[path = "../common/mod.rs"]
mod common;

mod build;
mod cache_gc;
mod cache_safety;
mod cli;
mod dataset;
mod explain;
mod extends;
mod function_length;
mod input_files;
mod instances;
mod lock;
mod mutations;
mod osm;
mod pack;
mod sensor;
mod shard_kill;
mod shards;
mod spec_edit;
mod spec_errors;
mod stage_imports;
mod traffic;
mod visibility;
