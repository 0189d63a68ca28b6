//! Shared types the stages hand on to each other: blocks, roads, lamps, buildings, the
//! assembled city plan, facade sets and the 3D scene.
//!
//! Pixel geometry uses continuous image coordinates: pixel `(i, j)` covers
//! `[i, i + 1) × [j, j + 1)`, x to the right, y down. [`CityPlan`] is the same geometry in
//! metres, with x east (= image x) and z south (= image y).

pub mod geometry;
pub mod image_file;
pub(crate) mod srgb;

mod block;
mod building;
mod camera_basis;
mod camera_pose;
mod city_plan;
mod facade_set;
mod generated_layout;
mod instance_ids;
mod instances;
mod lamp;
mod map_cladding;
mod movement;
mod object_kind;
mod osm_map;
mod parsed_layout;
mod pixel_box;
mod pixel_class;
mod road;
mod scene;
mod streets;
mod texture;
mod traffic_role;

pub use block::{Band, Block, PxRect};
pub use building::Building;
pub use camera_basis::CameraBasis;
pub use camera_pose::{CameraPose, PoseAngles};
pub use city_plan::{CityPlan, PlanBlock, PlanBuilding, PlanLamp, PlanRoad};
pub use facade_set::{Facade, FacadeSet, Roof};
pub use generated_layout::GeneratedLayout;
pub use instance_ids::{pack_ids, unpack_ids};
pub use instances::{Instance, Instances};
pub use lamp::{LAMP_POLE_RADIUS, Lamp};
pub use map_cladding::{MapCladding, map_cladding};
pub use movement::{Movement, Recolour};
pub use object_kind::ObjectKind;
pub use osm_map::CAMERA_LANE as MAP_CAMERA_LANE;
pub use osm_map::{
    FeatureKind, GeoBox, LeftOut, MapArea, MapBuilding, MapFeature, MapPolygon, MapRoad,
    OsmElement, OsmMap, PavedSegment, SIGNAL_DIRECTION, paved_runs,
};
pub use osm_map::{LANE as MAP_LANE, camera_lane as map_camera_lane, lanes as map_lanes};
pub use osm_map::{NARROWEST_VEHICLE, driven_back};
pub use parsed_layout::ParsedLayout;
pub use pixel_box::PixelBox;
pub use pixel_class::PixelClass;
pub use road::{Axis, Road};
pub use scene::{LAMP_LIT_SUFFIX, Material, Mesh, Scene, SceneObject};
pub use streets::Streets;
pub use texture::{Texture, encode_png};
pub use traffic_role::{Crossing, LaneVehicle, TrafficRole, Walk};
