//! The `cityspec` binary: parses the command line and maps the outcome to an exit code.

/// mimalloc instead of the system's allocator: a frame allocates and frees tens of
/// megabytes in many buffers (tiles, images, PNGs) from two threads at once, and glibc's
/// malloc spent about 4 % of a frame's CPU time in its free lists. Measured with `cargo
/// bench --bench frames`: 26.9 → 29.4 frames/s (100 frames), 29.5 → 32.5 (1,000). Outputs
/// do not depend on the allocator.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> std::process::ExitCode {
    cityspec::cli::run()
}
