//! The `[output]` table: how a build lays out its frames.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// How the frames of every camera path are written.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// `"files"`: one file per image (`frames/<camera>/rgb/000000.png`, …). `"webdataset"`:
    /// tar shards of `samples_per_shard` frames each (`frames/<camera>/wds/000000.tar`),
    /// each frame a sample keyed `<camera>_000000`: `.png` (RGB), `.ids.png`, `.depth.npy`
    /// (float32 metres), `.json` (its COCO image and annotations, pose, sun and
    /// conditions), `.icdar.txt` and, with YOLO, `.yolo.txt`; with `[splits]` also each
    /// split's shards `wds/<split>/`. `coco.json`, `poses.json` and `preview.png` stay files.
    #[serde(default)]
    pub layout: OutputLayout,
    /// Frames per tar shard with `layout = "webdataset"`.
    #[serde(default = "default_samples_per_shard")]
    #[schemars(range(min = 1, max = 1000000))]
    pub samples_per_shard: u32,
}

/// See [`OutputSpec::layout`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum OutputLayout {
    // Plain comments: the schema stays a simple enum.
    #[default]
    Files,
    Webdataset,
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            layout: OutputLayout::Files,
            samples_per_shard: default_samples_per_shard(),
        }
    }
}

fn default_samples_per_shard() -> u32 {
    1000
}
