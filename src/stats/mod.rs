//! Stats: a built output folder (`out/<name>/`) → per camera path, the pixel share of each
//! object kind, labelled objects per frame by class, and box-height percentiles
//! ([`Stats`]), for `cityspec stats`.
//!
//! The kind of an instance id comes from the path's `instances.json` (written by every
//! build: id → kind, set by the stage that made the object); id 0 is `sky`. Pixel shares
//! are counted over every `ids/` image of a path (RGB-packed, `id = R + 256·G + 256²·B`).
//! Labelled objects and box heights
//! come from the path's `coco.json`: annotations with `iscrowd` 0, by category; ignore
//! regions are counted apart, and of them the faint ones (`cityspec_ignored: contrast`).
//!
//! Diversity: per variant attribute of `instances.json` (`facade` of buildings, `species`
//! of trees, `body` of cars, `appearance` and `pose` of people), over the instances the path's `ids/`
//! images show at all: how many distinct variants, and the most used one with its share.
//! Visibility: the path's positives (`iscrowd` 0) and its ignore regions by
//! `cityspec_ignored` reason (`pixels`, `fraction`, `contrast`).

mod path_stats;
mod stats_error;
mod table;

pub use path_stats::{
    ClassStats, Diversity, KindShare, PathStats, VARIANT_ATTRIBUTES, Visibility, measure_path,
    percentile,
};
pub use stats_error::StatsError;
pub use table::table;

use std::path::Path;

use serde::Serialize;

use crate::model::Instances;

/// Stats of every camera path of an output folder, paths in name order.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Stats {
    pub paths: Vec<PathStats>,
}

/// Measures each camera path `dir/frames/<path>/`, the kinds of its instance ids read
/// from its `instances.json`.
pub fn measure(dir: &Path) -> Result<Stats, StatsError> {
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
        .map(|p| {
            let listed = read_instances(&p.join("instances.json"))?;
            let kinds: Vec<String> = listed.iter().map(|i| i.kind.name().to_owned()).collect();
            let attributes: Vec<_> = listed.into_iter().map(|i| i.attributes).collect();
            measure_path(p, &kinds, &attributes)
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Stats { paths })
}

/// The kind of every instance id of a path's `instances.json`, by id − 1.
pub fn instance_kinds(path: &Path) -> Result<Vec<String>, StatsError> {
    Ok(read_instances(path)?
        .iter()
        .map(|i| i.kind.name().to_owned())
        .collect())
}

/// Every instance of a path's `instances.json`, by id − 1 (ids checked to run 1, 2, 3, …).
fn read_instances(path: &Path) -> Result<Vec<crate::model::Instance>, StatsError> {
    let bytes =
        crate::regular_file::read(path, crate::regular_file::Follow::Yes).map_err(|source| {
            StatsError::Io {
                path: path.to_path_buf(),
                source,
            }
        })?;
    let bad = |message: String| StatsError::Bad {
        path: path.to_path_buf(),
        message,
    };
    let listed: Instances = serde_json::from_slice(&bytes)
        .map_err(|e| bad(format!("not an instances.json ({e}): rebuild the folder")))?;
    for (instance, want) in listed.instances.iter().zip(1u32..) {
        if instance.id != want {
            return Err(bad(format!(
                "instance {} listed where id {want} belongs: ids must run 1, 2, 3, …",
                instance.id
            )));
        }
    }
    Ok(listed.instances)
}
