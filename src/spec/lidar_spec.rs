//! A camera's LiDAR: the `lidar` table of a `[[cameras]]` entry.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A rotating multi-beam LiDAR riding with the camera: one turn per frame from the
/// camera's eye, its axes KITTI's velodyne frame (x forward along the camera's level
/// heading, y left, z up). Each frame writes `velodyne/NNNNNN.bin` (float32 x, y, z,
/// intensity), `labels/NNNNNN.label` (uint32 SemanticKITTI semantic id | instance id << 16)
/// and, with `ply`, `lidar/NNNNNN.ply`. Rain and fog attenuate the returns as they dim the
/// camera's image. The defaults are a 64-beam scanner of an HDL-64E's vertical span.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LidarSpec {
    /// Beams (lasers), their elevations evenly from `top` down to `bottom`.
    #[serde(default = "default_beams")]
    #[schemars(range(min = 1, max = 256))]
    pub beams: u32,
    /// Azimuth steps in one turn, starting straight ahead and turning left.
    #[serde(default = "default_columns")]
    #[schemars(range(min = 16, max = 16384))]
    pub columns: u32,
    /// Elevation of the top beam, degrees (above the horizon positive).
    #[serde(default = "default_top")]
    #[schemars(range(min = -89.0, max = 89.0))]
    pub top: f64,
    /// Elevation of the bottom beam, degrees; below `top`.
    #[serde(default = "default_bottom")]
    #[schemars(range(min = -89.0, max = 89.0))]
    pub bottom: f64,
    /// Returns beyond this many metres are lost.
    #[serde(default = "default_range")]
    #[schemars(range(min = 1.0, max = 1000.0))]
    pub range: f64,
    /// Standard deviation of the Gaussian range noise, metres (seeded per frame and beam).
    #[serde(default = "default_noise")]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub noise: f64,
    /// Chance that a return is dropped (seeded per frame and beam).
    #[serde(default = "default_dropout")]
    #[schemars(range(min = 0.0, max = 0.99))]
    pub dropout: f64,
    /// Also write each scan as a binary little-endian PLY (`lidar/NNNNNN.ply`: float x, y,
    /// z, intensity and uint label per vertex), for point-cloud viewers.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub ply: bool,
}

impl Default for LidarSpec {
    fn default() -> Self {
        LidarSpec {
            beams: default_beams(),
            columns: default_columns(),
            top: default_top(),
            bottom: default_bottom(),
            range: default_range(),
            noise: default_noise(),
            dropout: default_dropout(),
            ply: false,
        }
    }
}

fn default_beams() -> u32 {
    64
}
fn default_columns() -> u32 {
    2048
}
fn default_top() -> f64 {
    2.0
}
fn default_bottom() -> f64 {
    -24.8
}
fn default_range() -> f64 {
    120.0
}
fn default_noise() -> f64 {
    0.02
}
fn default_dropout() -> f64 {
    0.01
}
