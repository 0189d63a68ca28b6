//! Cameras stage: parsed layout + metres per pixel + path settings → [`CameraPose`]s per frame.
//!
//! Four paths, all computed the same bit for bit on every platform (only `+ − × ÷`,
//! `sqrt`, which IEEE 754 rounds exactly, and `libm`'s pure-Rust sine and cosine):
//!
//! - [`road_path`] drives along the roads on the right-hand lane, through crossings, each
//!   road until the look-at point reaches its end (never out of town), with frames evenly
//!   spaced by arc length over the whole tour and a seeded target jitter;
//! - [`sidewalk_path`] walks clockwise around each block on its sidewalk, shop fronts on
//!   the right, the street on the left; on a map, [`map_sidewalk_path`] walks each
//!   road's sidewalks along its polyline, the block on the right;
//! - [`object_views`] stands in free space around objects of chosen classes and aims at
//!   them: candidates per frame, of which the build keeps the first whose object the
//!   renderer shows;
//! - [`orbit_path`] circles the city for overviews, looking at its centre ([`orbit_path_around`]
//!   a map's box).
//!
//! The moving paths draw each frame's heading, pitch, roll and eye height from the
//! camera's [`Aim`] ranges, from a stream per camera seed and frame, so one camera's poses
//! never depend on another camera. The drawn values ride along in the pose
//! ([`crate::model::PoseAngles`]) and are written beside it.
//!
//! A path takes a frame count or a spacing ([`FrameRule`]): a spacing divides the path's
//! length, [`tour_length`], [`walk_length`] or [`orbit_length`], into frames.
//!
//! Poses are in world metres (x east = layout x, y up, z south = layout y), rounded to the
//! millimetre so that written poses print short, stable numbers; `-0` becomes `0`.
//! [`CameraPose`] lives in [`crate::model`]; the renderer consumes it.

/// Bump when this stage's output changes: it is part of the stage's cache key.
pub const VERSION: u32 = 12;

mod aim;
mod leg;
mod map_walk;
mod object_path;
mod orbit_path;
mod overview;
mod road_path;
mod sidewalk_path;

pub use crate::model::CameraPose;
use crate::model::geometry::mm;
/// A camera's field of view → the tangent of its half angle (shared with the renderer's
/// intrinsics).
pub use crate::model::geometry::tan_half_degrees;
pub use crate::spec::FrameRule;
pub use aim::Aim;
pub use map_walk::{
    CARRIAGEWAY_CLEARANCE, MIN_SIDEWALK, MIN_STRETCH, map_sidewalk_path, map_sidewalk_path_draws,
};
pub use object_path::{ATTEMPTS, CLEARANCE, ObjectTarget, ObjectView, ObjectsPath, object_views};
pub use orbit_path::{orbit_length, orbit_length_around, orbit_path, orbit_path_around};
pub use overview::{
    OVERVIEW_FAR, OVERVIEW_HEIGHT, OVERVIEW_ORBIT_POSES, OVERVIEW_SHADOW_MAP_SIDE, OVERVIEW_SIZE,
    OVERVIEW_SUPERSAMPLE, OVERVIEW_TAN_HALF_FOV, Overview, map_overview, overview,
};
pub use road_path::{
    Drive, ROAD_PITCH, RoadPath, map_road_path, map_road_path_draws, road_path, road_path_draws,
    tour_length,
};
pub use sidewalk_path::{
    SidewalkPath, WALK_SHARE, sidewalk_path, sidewalk_path_draws, walk_length,
};
