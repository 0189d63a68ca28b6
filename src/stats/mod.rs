//! Stats: a built output folder (`out/<name>/`) → per camera path, the pixel share of each
//! object kind, labelled objects per frame by class, and box-height percentiles
//! ([`Stats`]), for `cityspec stats`.
//!
//! The kind of an instance id comes from the scene's object names: `city.obj` lists one
//! `o <name>` per object in scene order, so id `k` is the `k`-th name, and the kind is the
//! name without its `_NNNN` number (`building_0042` → `building`, `sign_0003` → `sign`,
//! `ground` → `ground`); id 0 is `sky`. Pixel shares are counted over every `ids/` image
//! of a path (RGB-packed, `id = R + 256·G + 256²·B`). Labelled objects and box heights
//! come from the path's `coco.json`: annotations with `iscrowd` 0, by category; ignore
//! regions are counted apart.

mod path_stats;
mod stats_error;
mod table;

pub use path_stats::{ClassStats, KindShare, PathStats, measure_path, percentile};
pub use stats_error::StatsError;
pub use table::table;

/// An object's kind (kept here too: `cityspec stats` counts pixels by it).
pub use crate::model::kind_of;

use std::io::BufRead;
use std::path::Path;

use serde::Serialize;

/// Stats of every camera path of an output folder, paths in name order.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Stats {
    pub paths: Vec<PathStats>,
}

/// Reads `dir/city.obj`'s object names and measures each `dir/frames/<path>/`.
pub fn measure(dir: &Path) -> Result<Stats, StatsError> {
    let names = object_names(&dir.join("city.obj"))?;
    let kinds: Vec<String> = names.iter().map(|n| kind_of(n).to_owned()).collect();
    let frames = dir.join("frames");
    let mut paths: Vec<_> = std::fs::read_dir(&frames)
        .map_err(|source| StatsError::Io {
            path: frames.clone(),
            source,
        })?
        .filter_map(Result::ok)
        .filter(|e| e.path().join("coco.json").is_file())
        .map(|e| e.path())
        .collect();
    paths.sort();
    if paths.is_empty() {
        return Err(StatsError::NoPaths { dir: frames });
    }
    let paths = paths
        .iter()
        .map(|p| measure_path(p, &kinds))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Stats { paths })
}

/// The `o` names of an OBJ file, in order.
pub fn object_names(path: &Path) -> Result<Vec<String>, StatsError> {
    let io = |source| StatsError::Io {
        path: path.to_path_buf(),
        source,
    };
    let file = crate::regular_file::open(path, crate::regular_file::Follow::Yes).map_err(io)?;
    let mut names = Vec::new();
    for line in std::io::BufReader::new(file).split(b'\n') {
        let line = line.map_err(io)?;
        if let Some(name) = line.strip_prefix(b"o ") {
            names.push(String::from_utf8_lossy(name).trim_end().to_owned());
        }
    }
    Ok(names)
}
