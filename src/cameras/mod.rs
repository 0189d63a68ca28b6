//! Cameras stage: parsed layout + metres per pixel + path settings → [`CameraPose`]s per frame.
//!
//! Two paths, both without trigonometry, so every platform computes the same poses bit for
//! bit (only `+ − × ÷` and `sqrt`, which IEEE 754 rounds exactly):
//!
//! - [`road_path`] drives along the roads on the right-hand lane, through crossings, each
//!   road until the look-at point reaches its end (never out of town), with frames evenly
//!   spaced by arc length over the whole tour and a seeded target jitter;
//! - [`orbit_path`] circles the city for overviews, looking at its centre.
//!
//! A path takes a frame count or a spacing ([`FrameRule`]): a spacing divides the path's
//! length, [`tour_length`] or [`orbit_length`], into frames.
//!
//! Poses are in world metres (x east = layout x, y up, z south = layout y), rounded to the
//! millimetre so that written poses print short, stable numbers; `-0` becomes `0`.
//! [`CameraPose`] lives in [`crate::model`]; the renderer consumes it.

/// Bump when this stage's output changes: it is part of the stage's cache key.
pub const VERSION: u32 = 2;

mod leg;
mod orbit_path;
mod road_path;

pub use crate::model::CameraPose;
pub use crate::spec::FrameRule;
pub use orbit_path::{orbit_length, orbit_path};
pub use road_path::{RoadPath, road_path, tour_length};

/// `v` rounded to the millimetre, with `-0` made `0`.
fn mm(v: f64) -> f64 {
    let r = (v * 1000.0).round() / 1000.0;
    if r == 0.0 { 0.0 } else { r }
}
