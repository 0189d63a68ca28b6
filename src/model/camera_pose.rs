//! A camera pose: eye and look-at target, shared by the cameras stage and the renderer.

use serde::{Deserialize, Serialize};

/// One frame's camera: eye and look-at target in metres (x east, y up, z south).
///
/// The camera's up direction is world +y; roll is always zero.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CameraPose {
    pub eye: [f64; 3],
    pub target: [f64; 3],
}
