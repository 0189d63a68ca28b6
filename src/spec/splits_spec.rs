//! The `[splits]` table: which frames are train, val and test, for the dataset-level
//! files (`coco/<split>.json`, the ultralytics `yolo/` folder).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::findings::Findings;

/// The share of the dataset in each split, and what is split: frames (seeded from the
/// spec's `seed`) or whole cameras. Without `[splits]` a build writes no dataset-level
/// files at all, as before they existed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SplitsSpec {
    /// Share of the frames (or cameras) in `train`; the three shares make 1.
    #[serde(default)]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub train: f64,
    /// Share in `val`.
    #[serde(default)]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub val: f64,
    /// Share in `test`.
    #[serde(default)]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub test: f64,
    /// `"frame"`: each camera's frames are split by the shares, drawn from the seed.
    /// `"camera"`: whole cameras go to one split each (no street seen in two splits).
    #[serde(default)]
    pub by: SplitBy,
}

/// See [`SplitsSpec::by`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SplitBy {
    // Plain comments: the schema stays a simple enum.
    #[default]
    Frame,
    Camera,
}

/// The splits' names, in the order of [`SplitsSpec::shares`].
pub const SPLIT_NAMES: [&str; 3] = ["train", "val", "test"];

impl SplitsSpec {
    /// `[train, val, test]`.
    pub fn shares(&self) -> [f64; 3] {
        [self.train, self.val, self.test]
    }
}

/// The shares make 1, `train` is not empty, and splitting by camera has a camera for each
/// split that has a share.
pub(crate) fn check_splits(
    splits: Option<&SplitsSpec>,
    cameras: usize,
    findings: &mut Findings<'_, '_>,
) {
    let Some(splits) = splits else {
        return;
    };
    let sum: f64 = splits.shares().iter().sum();
    if (sum - 1.0).abs() > 1e-6 {
        findings.error(
            "splits",
            format!(
                "expected splits.train + splits.val + splits.test to make 1, found {} + {} + {} \
                 = {}",
                splits.train,
                splits.val,
                splits.test,
                (sum * 1e6).round() / 1e6
            ),
        );
    }
    if splits.train <= 0.0 {
        findings.error(
            "splits.train",
            format!(
                "expected a share above 0 (a dataset needs frames to train on), found {}",
                findings.shown("splits.train", splits.train)
            ),
        );
    }
    let used = splits.shares().iter().filter(|s| **s > 0.0).count();
    if splits.by == SplitBy::Camera && cameras < used {
        findings.error(
            "splits.by",
            format!(
                "expected at least {used} [[cameras]] to split by camera ({} of the splits have \
                 a share), found {cameras}: split by \"frame\", or add cameras",
                used
            ),
        );
    }
}
