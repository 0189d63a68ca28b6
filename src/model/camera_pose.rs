//! A camera pose: eye, look-at target and up direction (with the angles drawn for it),
//! shared by the cameras stage, the renderer and the annotators.

use serde::{Deserialize, Serialize};

/// One frame's camera: eye and look-at target in metres (x east, y up, z south), and the
/// direction the top of the image points to.
///
/// `up` need not be perpendicular to the view direction: the renderer takes the part of it
/// that is. A level camera has `up = [0, 1, 0]` (world +y); a rolled camera's `up` is
/// turned about the view direction.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CameraPose {
    pub eye: [f64; 3],
    pub target: [f64; 3],
    #[serde(default = "world_up")]
    pub up: [f64; 3],
    /// The seeded angles and height this pose was made from, when its path draws them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angles: Option<PoseAngles>,
    /// Seconds since the path's first frame, on a timed drive (a roads camera with `fps`);
    /// `None` elsewhere.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time: Option<f64>,
}

/// The drawn aim of one frame, written beside the pose so a user can filter or stratify
/// frames by it.
///
/// Degrees: `heading` is the yaw relative to the direction of travel (roads, sidewalks;
/// positive turns right, clockwise seen from above) or relative to the target's front
/// (objects); `pitch` is positive up; `roll` positive turns the camera clockwise about its
/// view direction (the horizon tilts anticlockwise in the image). `height` is the eye
/// height above the ground in metres.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PoseAngles {
    pub heading: f64,
    pub pitch: f64,
    pub roll: f64,
    pub height: f64,
}

fn world_up() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}

impl CameraPose {
    /// A level camera (up = world +y) at `eye` looking at `target`, with no drawn angles.
    pub const fn level(eye: [f64; 3], target: [f64; 3]) -> CameraPose {
        CameraPose {
            eye,
            target,
            up: [0.0, 1.0, 0.0],
            angles: None,
            time: None,
        }
    }
}
