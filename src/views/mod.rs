//! Stage `views`: a camera path's spec + the city → one pose per frame, each a view worth
//! rendering.
//!
//! The cameras stage draws poses from the layout alone (roads to drive, sidewalks to walk,
//! candidates around an object, an orbit); this stage chooses among them with the scene in
//! hand: a driver's view not filled by a parked bus ([`clear::unblocked`]), a walker's
//! not filled by a wall a metre away ([`clear::unfilled`]), an object camera's target
//! shown, not hidden ([`aimed::aimed_poses`]). It reads the cameras, render and scene
//! stages along the graph's declared edges (`tests/integration/stage_imports.rs`), and
//! every choice of which pose a frame gets is here, under [`VERSION`].
//!
//! | file | holds |
//! |---|---|
//! | [`clear`] | roads' and sidewalks' clear-view checks |
//! | [`aimed`] | an objects camera's candidates, kept when their object shows |

pub mod aimed;
pub mod clear;

use rand::Rng;

use crate::cameras::{self, CameraPose};
use crate::model::{Scene, Streets};
use crate::render::PreparedScene;
use crate::rng;
use crate::scene;
use crate::spec::{CameraPath, CameraSpec};

/// Bump when the poses a camera path gets change.
pub const VERSION: u32 = 1;

/// A timed drive's speed when the camera gives none, km/h.
pub const DRIVE_KMH: f64 = 30.0;

/// What choosing a path's views reads.
pub struct ViewsInput<'a> {
    pub camera: &'a CameraSpec,
    pub streets: Streets<'a>,
    pub scene: &'a Scene,
    pub prepared: &'a PreparedScene,
    pub metres_per_pixel: f64,
    /// The spec's seed.
    pub seed: u64,
}

/// One pose per frame of `input.camera`'s path (fewer when a frame has no view to keep).
pub fn poses(input: &ViewsInput) -> Vec<CameraPose> {
    let ViewsInput {
        camera,
        streets,
        scene,
        prepared,
        metres_per_pixel: mpp,
        seed,
    } = *input;
    // Seeded by the camera's name, not its place in the list: adding or reordering
    // cameras leaves every other camera's poses as they were.
    let camera_seed = rng::stream(seed, &format!("camera/{}", camera.name), 0).next_u64();
    match (camera.path, streets) {
        (CameraPath::Roads, streets) => {
            let path = road_path(camera);
            let (seed, n) = (camera_seed, clear::DRAWS);
            if path.drive.is_some() {
                // A timed drive keeps every frame: one time step apart, none skipped.
                return match streets {
                    Streets::Layout(layout) => cameras::road_path(layout, mpp, &path, seed),
                    Streets::Map(map) => cameras::map_road_path(map, &path, seed),
                };
            }
            let draws = match streets {
                Streets::Layout(layout) => cameras::road_path_draws(layout, mpp, &path, seed, n),
                Streets::Map(map) => cameras::map_road_path_draws(map, &path, seed, n),
            };
            unblocked(camera, scene, draws)
        }
        (CameraPath::Sidewalks, streets) => {
            let (frames, aim) = (camera.frame_rule(), cameras::Aim::of(camera));
            let draws = match streets {
                Streets::Layout(layout) => {
                    let path = cameras::SidewalkPath {
                        frames,
                        aim,
                        sidewalk: f64::from(scene::strip_width_px(layout)) * mpp,
                    };
                    cameras::sidewalk_path_draws(layout, mpp, &path, camera_seed, clear::DRAWS)
                }
                Streets::Map(map) => {
                    cameras::map_sidewalk_path_draws(map, frames, aim, camera_seed, clear::DRAWS)
                }
            };
            let check = aimed::check_intrinsics(camera);
            clear::unfilled(prepared, draws, &check)
        }
        (CameraPath::Objects, streets) => {
            aimed::aimed_poses(prepared, scene, streets, mpp, camera, camera_seed)
        }
        (CameraPath::Orbit, Streets::Layout(layout)) => {
            let length = cameras::orbit_length(layout, mpp);
            let frames = camera.frame_rule().frames(length);
            // A range of heights: the orbit flies at its middle.
            cameras::orbit_path(layout, mpp, frames, camera.height.at(0.5))
        }
        (CameraPath::Orbit, Streets::Map(map)) => {
            let length = cameras::orbit_length_around(map.extent);
            let frames = camera.frame_rule().frames(length);
            cameras::orbit_path_around(map.extent, frames, camera.height.at(0.5))
        }
    }
}

/// Each frame's first draw whose view no vehicle fills.
fn unblocked(camera: &CameraSpec, scene: &Scene, draws: Vec<Vec<CameraPose>>) -> Vec<CameraPose> {
    // Fields of view down and across the picture.
    let down = cameras::tan_half_degrees(camera.fov);
    let aspect = f64::from(camera.resolution[0]) / f64::from(camera.resolution[1].max(1));
    let boxes = clear::vehicle_boxes(scene);
    clear::unblocked(draws, &boxes, [down * aspect, down])
}

/// How `camera` drives a road tour.
fn road_path(camera: &CameraSpec) -> cameras::RoadPath {
    cameras::RoadPath {
        frames: camera.frame_rule(),
        aim: cameras::Aim::of(camera),
        look_ahead: camera.look_ahead,
        jitter: camera.jitter,
        lane_offset: camera.lane_offset,
        drive: camera.fps.map(|fps| cameras::Drive {
            fps,
            speed: camera.speed_kmh.unwrap_or(DRIVE_KMH) / 3.6,
        }),
    }
}
