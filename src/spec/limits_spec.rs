//! The `[limits]` table: what a build may cost before validation refuses the spec.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// What a build may cost. Validation estimates the build from the spec alone (the layout's
/// pixels after mirroring, buildings from the block area and the smallest width, lamps from
/// the road length and spacing, inserted objects, frames × resolution) and refuses a spec
/// whose estimate is over a limit, before any of it is spent. Raise a limit here when the
/// machine has room.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LimitsSpec {
    /// Peak memory a build may need, in MiB.
    #[serde(default = "default_memory_mib")]
    #[schemars(range(min = 64, max = 16777216))]
    pub memory_mib: u64,
    /// Bytes the frames of all cameras may write, in MiB.
    #[serde(default = "default_output_mib")]
    #[schemars(range(min = 1, max = 1073741824))]
    pub output_mib: u64,
}

impl Default for LimitsSpec {
    fn default() -> Self {
        LimitsSpec {
            memory_mib: default_memory_mib(),
            output_mib: default_output_mib(),
        }
    }
}

fn default_memory_mib() -> u64 {
    8192
}
fn default_output_mib() -> u64 {
    64 * 1024
}
