//! Test seeds: the environment (`CITYSPEC_PROPTEST_CASES`, `CITYSPEC_PROPTEST_SEED`) → how
//! many cases a property test draws and from which seed.
//!
//! The default `cargo test` run draws every property test's cases from one fixed seed, so
//! CI and a user's first run on a fresh clone see the same cases and cannot fail by chance
//! (issue 8, case 8). Failures found by longer runs are committed under
//! `proptest-regressions/` and replayed first on every run. A longer random run is one
//! environment variable away:
//!
//! ```sh
//! CITYSPEC_PROPTEST_CASES=5000 CITYSPEC_PROPTEST_SEED=random cargo test
//! ```
//!
//! A random seed is printed (`CITYSPEC_PROPTEST_SEED=…`) so a failure can be replayed.

/// The seed of the default run.
pub const FIXED_SEED: u64 = 0x000c_17f5_bec5_eed8;

/// `(cases, seed)` for a property test whose default run draws `default_cases` cases.
///
/// `CITYSPEC_PROPTEST_CASES=N` draws N cases instead; `CITYSPEC_PROPTEST_SEED=N` uses seed
/// N, `=random` a fresh seed, printed on stderr. Values that do not parse are reported and
/// ignored.
pub fn cases_and_seed(default_cases: u32) -> (u32, u64) {
    let cases = match std::env::var("CITYSPEC_PROPTEST_CASES") {
        Ok(text) => text.trim().parse().unwrap_or_else(|_| {
            eprintln!("CITYSPEC_PROPTEST_CASES={text:?} is not a number; using {default_cases}");
            default_cases
        }),
        Err(_) => default_cases,
    };
    let seed = match std::env::var("CITYSPEC_PROPTEST_SEED") {
        Ok(text) if text.trim() == "random" => {
            let seed = fresh_seed();
            eprintln!("property tests draw from CITYSPEC_PROPTEST_SEED={seed}");
            seed
        }
        Ok(text) => text.trim().parse().unwrap_or_else(|_| {
            eprintln!(
                "CITYSPEC_PROPTEST_SEED={text:?} is neither a number nor \"random\"; \
                 using {FIXED_SEED}"
            );
            FIXED_SEED
        }),
        Err(_) => FIXED_SEED,
    };
    (cases, seed)
}

/// A seed nobody chose: the clock's nanoseconds mixed with the process id.
fn fresh_seed() -> u64 {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos() as u64);
    // SplitMix64's finaliser spreads nearby clock readings over the whole range.
    let mut z = nanos ^ (u64::from(std::process::id()) << 32);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A proptest config: [`cases_and_seed`], with failures persisted beside the sources in
/// `proptest-regressions/` (committed, replayed first).
#[cfg(test)]
pub(crate) fn proptest_config(default_cases: u32) -> proptest::test_runner::Config {
    let (cases, seed) = cases_and_seed(default_cases);
    proptest::test_runner::Config {
        cases,
        rng_seed: proptest::test_runner::RngSeed::Fixed(seed),
        failure_persistence: Some(Box::new(
            proptest::test_runner::FileFailurePersistence::SourceParallel("proptest-regressions"),
        )),
        ..proptest::test_runner::Config::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_run_is_fixed() {
        // Only meaningful when the variables are unset, as in the README's test command.
        if std::env::var_os("CITYSPEC_PROPTEST_SEED").is_none()
            && std::env::var_os("CITYSPEC_PROPTEST_CASES").is_none()
        {
            assert_eq!(cases_and_seed(48), (48, FIXED_SEED));
            assert_eq!(
                proptest_config(7).rng_seed,
                proptest::test_runner::RngSeed::Fixed(FIXED_SEED)
            );
        }
        assert_ne!(fresh_seed(), fresh_seed());
    }
}
