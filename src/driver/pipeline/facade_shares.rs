//! Every example spec's buildings, by the cheap stages only (layout, place, facades), clad
//! by the balanced facade choice: no facade on more than 8 % of them (issue 41).

use std::path::{Path, PathBuf};

use super::Pipeline;
use crate::cache::Cache;
use crate::driver::inputs::SpecInputs;
use crate::driver::load_spec;
use crate::model::geometry::FacadeChoice;

/// The most buildings one facade may clad, as a share of all.
const MAX_SHARE: f64 = 0.08;

/// Per example spec: (file name, buildings, facades in the set, the most used facade's
/// share under the balanced choice, and under the paper's rule `kind % n`).
fn shares() -> Vec<(String, usize, usize, f64, f64)> {
    let mut specs: Vec<PathBuf> =
        std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("specs"))
            .expect("specs/ is readable")
            .map(|e| e.expect("a specs/ entry").path())
            .filter(|p| p.extension().is_some_and(|e| e == "toml"))
            .collect();
    specs.sort();
    let cache_dir = tempfile::tempdir().expect("a temporary cache");
    let cache = Cache::new(cache_dir.path());
    let quiet = |_: &str, _: usize, _: usize| {};
    specs
        .iter()
        .filter_map(|path| {
            let spec = load_spec(path).expect("an example spec loads");
            // A map's buildings are its own; each draws its facade uniformly
            // (`scene::map_city`), with no placement to skew the shares.
            if spec.layout.osm.is_some() {
                return None;
            }
            let files = SpecInputs::read(path, &spec).expect("its inputs read");
            let mut p = Pipeline::new(&spec, path.clone(), files, &cache, &quiet);
            let buildings = p.buildings().expect("place runs");
            let facades = p.facade_set().expect("facades run");
            let export = &p.inputs.export;
            let choice = FacadeChoice {
                facades: &facades,
                widths: export.widths.as_deref(),
                metres_per_pixel: export.metres_per_pixel,
                seed: export.seed,
            }
            .all(&buildings);
            let n = facades.facades.len();
            let most = |of: &mut dyn Iterator<Item = usize>| {
                let mut used = vec![0usize; n.max(1)];
                for f in of {
                    used[f] += 1;
                }
                used.into_iter().max().unwrap_or(0) as f64 / buildings.len().max(1) as f64
            };
            let balanced = most(&mut choice.iter().flatten().copied());
            let paper = most(&mut buildings.iter().map(|b| b.kind as usize % n.max(1)));
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            Some((name, buildings.len(), n, balanced, paper))
        })
        .collect()
}

#[test]
fn no_facade_clads_more_than_8_percent_of_any_example_spec() {
    let shares = shares();
    assert!(shares.len() >= 10, "{shares:?}");
    for (name, buildings, n, balanced, paper) in &shares {
        println!(
            "{name}: {buildings} buildings, {n} facades, most used {:.1} % (paper's rule {:.1} %)",
            balanced * 100.0,
            paper * 100.0
        );
    }
    for (name, buildings, n, balanced, _) in shares {
        assert!(buildings > 50, "{name}: {buildings} buildings");
        // A set of n facades cannot go under 1/n: every example spec's set is big enough.
        assert!(n as f64 * MAX_SHARE >= 1.0, "{name}: only {n} facades");
        assert!(
            balanced <= MAX_SHARE,
            "{name}: the most used of {n} facades clads {:.1} %",
            balanced * 100.0
        );
    }
}
