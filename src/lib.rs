//! cityspec: a versioned TOML spec in, a synthetic city dataset out.
//!
//! The crate is a compiler in stages (see `ARCHITECTURE.md`). Each stage is a pure function
//! from one named type to the next; only [`driver`] knows their order (its stage table,
//! `driver::Stage`), touches the file system and keeps the content-addressed [`cache`]
//! (which knows no stage) and the [`out_dir`] it writes (lock, manifest, the whole-folder
//! replace), both with [`atomic_file`]; only [`cli`] prints.
//!
//! | stage | module | consumes | produces |
//! |---|---|---|---|
//! | spec | [`spec`] | TOML text | validated [`spec::Spec`] |
//! | layout | [`layout`] | `spec.layout`, seed | layout image (generated or the user's) |
//! | mirror | [`mirror`] | layout image, `spec.layout.mirror` | mirrored layout image |
//! | parse | [`parse`] | layout image, palette | [`model::ParsedLayout`]: blocks and roads |
//! | facades | [`facades`] | CMP-layout files (a folder, or [`facades::builtin`]) | [`model::FacadeSet`] |
//! | lamps | [`lamps`] | layout image, roads, `spec.lamps` | [`model::Lamp`]s |
//! | place | [`place`] | blocks, `spec.buildings`, seed | [`model::Building`]s |
//! | plan | [`plan`] | blocks, roads, lamps, buildings | [`model::CityPlan`] in metres |
//! | preview | [`preview`] | layout image, plan | `plan.png` |
//! | scene | [`scene`] | blocks, roads, lamps, buildings, facades | [`model::Scene`]: the 3D city |
//! | objects | [`objects`] | `spec.objects`, plan, buildings, facades, mesh files | [`objects::Inserted`]: text, signs, user meshes |
//! | export | [`export`] | scene | `city.obj`, `city.mtl`, `textures/`, `city.glb` |
//! | cameras | [`cameras`] | parsed layout, path settings, seed | [`cameras::CameraPose`]s drawn from the layout alone |
//! | views | [`views`] | a camera path, the scene, the layout | one [`cameras::CameraPose`] per frame, each a view worth rendering |
//! | annotate | [`annotate`] | instance images, labels, poses | COCO JSON, YOLO, ICDAR, KITTI |
//! | render | [`render`] | scene, camera pose, intrinsics, lighting | [`render::Frame`]: RGB, ids, depth (normals); [`render::Flow`] to the next pose |
//! | sensor | [`sensor`] | a frame's radiance and depth, camera, drawn weather | the RGB image a camera saves |
//! | traffic | [`traffic`] | objects' lane vehicles, signal heads and walking people, roads, `spec.traffic`, seed, a timed drive's poses | [`traffic::Traffic`]; `at(t)`: the [`model::Movement`] a frame poses the scene with |
//! | lidar | [`lidar`] | prepared scene's triangles, object kinds, a camera pose, scanner | [`lidar::Point`]s with SemanticKITTI labels: a camera's `velodyne/`, `labels/` |
//! | dataset | [`dataset`] | every camera path's `coco.json` and YOLO files, `spec.splits` | `coco/<split>.json`, the ultralytics `yolo/` folder |
//! | (tool) | [`osm`] | an OpenStreetMap extract, a box | [`model::OsmMap`]: footprints, roads, furniture in metres; the layout stage of a `[layout.osm]` spec |
//! | (tool) | [`stats`] | a built output folder | pixel share per kind, labels per frame, box heights |
//!
//! Shared types live in [`model`], with shared geometry (mesh building, road rectangles,
//! facade heights, vector and trig helpers) in [`model::geometry`] and image-file checks and
//! encoding in [`model::image_file`]; stages depend on these, on [`spec`], [`rng`], [`hash`],
//! [`diagnostic`] (the warnings a stage reports, cached with its result) and
//! [`regular_file`] (opening inputs without following or blocking), and on another stage
//! only along a declared edge (`views` reads `cameras`, `render` and `scene`; `lidar` reads `render`;
//! `traffic` reads `objects`' signal lamps).
//! `tests/integration/stage_imports.rs` fails when a stage names another off those edges;
//! tests that need another stage's output get it through `test_support`.

pub mod annotate;
pub mod atomic_file;
pub mod cache;
pub mod cameras;
pub mod cli;
pub mod dataset;
pub mod diagnostic;
pub mod driver;
pub mod export;
pub mod facades;
pub mod hash;
pub mod lamps;
pub mod layout;
pub mod lidar;
pub mod mirror;
pub mod model;
pub mod objects;
pub mod osm;
pub mod out_dir;
pub mod parse;
pub mod place;
pub mod plan;
pub mod preview;
pub mod regular_file;
pub mod render;
pub mod rng;
pub mod scene;
pub mod sensor;
pub mod spec;
pub mod stats;
#[doc(hidden)]
pub mod test_seed;
#[cfg(test)]
mod test_support;
pub mod traffic;
pub mod views;
