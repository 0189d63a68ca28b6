//! Shared geometry: what more than one stage builds with, so that no stage imports another.
//!
//! World coordinates are metres: x east (= layout x), y up, z south (= layout y). Every
//! item here is a pure function of its arguments; stages depend on this module and on
//! [`crate::model`], never on each other (`tests/integration/stage_imports.rs` checks it).
//!
//! | item | used by |
//! |---|---|
//! | [`ROAD_Y`], [`MARKING_Y`], [`KERB_Y`]: surface heights | scene, objects |
//! | [`MeshBuilder`], [`MaterialBook`]: triangles and materials | scene, objects |
//! | [`RoadRect`], [`StreetProfile`], [`strip_width_px`], [`WALK_SHARE`]: roads in plan | scene, objects, cameras, build |
//! | [`FacadeChoice`]: each building's facade and height | scene, objects |
//! | [`vector`] helpers: `sub`, `dot`, `cross`, `normalize` | scene, objects, render, export, sensor |
//! | [`trig`]: bit-exact cos/sin and tan(θ/2) | objects, build |
//! | [`units`]: metres ↔ pixels, millimetre rounding | plan, cameras, annotate, build |
//! | [`rounding`]: `floor`/`ceil`/`round` without a library call, bit-identical | render, facades, objects |
//! | [`zebras`]: where each road's zebra crossings lie | scene, objects |
//! | [`polygon_set`]: a map's polygons cut by polygons (`i_overlay`) | osm, scene |
//! | [`roofs`]: a map building's `roof:shape` on its footprint, and its walls' height | scene, objects |
//! | [`massing`]: a map building's volumes (its parts, `min_height`) and the eaves along a wall | scene, objects |

mod facade_choice;
pub mod map_lines;
pub mod massing;
mod material_book;
mod mesh_builder;
pub mod polygon;
pub mod polygon_set;
mod road_rect;
pub mod roofs;
pub mod rounding;
mod street_profile;
mod strip_width;
pub mod trig;
pub mod units;
pub mod vector;
pub mod zebras;

pub use facade_choice::{FacadeChoice, PLAIN_HEIGHT, facade_height, usable};
pub use material_book::MaterialBook;
pub use mesh_builder::MeshBuilder;
pub use road_rect::RoadRect;
pub use street_profile::StreetProfile;
pub use strip_width::{DEFAULT_STRIP_PX, WALK_SHARE, strip_width_px};
pub use trig::{cos_sin_deg, tan_half_degrees};
pub use units::{mm, round_to, widths_px};
pub use vector::{UP, cross, dot, neg, normalize, sub};

/// Height of the road surface above the ground.
pub const ROAD_Y: f64 = 0.02;
/// Height of the lane markings: a few millimetres above the road.
pub const MARKING_Y: f64 = 0.025;
/// How far from a crossing's edge the zebra crossing on each approach ends, in metres (the
/// scene paints it; its stop line lies just beyond, [`STOP_LINE_END`]).
pub const ZEBRA_END: f64 = 4.0;
/// How far from a crossing's edge the stop line before each zebra crossing ends, in
/// metres: cars standing in a lane wait behind it.
pub const STOP_LINE_END: f64 = ZEBRA_END + 0.5;
/// Top of the sidewalk slabs and of the block surfaces (a curb's height).
pub const KERB_Y: f64 = 0.15;
