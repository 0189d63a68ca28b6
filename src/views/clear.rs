//! Moving cameras' poses: scene + each frame's draws of its aim → one pose per frame whose
//! view is not filled by something right in front of the eye.
//!
//! The cameras stage draws aims from the layout alone; here they meet the scene. Each frame keeps its first clear draw of [`DRAWS`]; when none is clear, the least
//! filled (the first of equals). Frames whose first draw is clear keep the pose they had
//! before. Two paths are checked, each by the rule that catches what it meets:
//!
//! - **Roads** ([`unblocked`], with [`cameras::road_path_draws`](crate::cameras)): the
//!   camera drives the outer lane, close to the parked cars (`specs/day.toml` keeps 0.65 m
//!   from a parked bus's side), so a heading drawn towards the curb could stare into a bus
//!   from under a metre, or fill most of the picture with one from a few metres: a frame
//!   of one blank flank, which no dashcam takes. A draw is blocked when one vehicle within
//!   [`NEAR`] metres of the eye covers more than [`MAX_SHARE`] of the view: [`COLUMNS`] × [`ROWS`] rays through the picture are cast
//!   against the vehicles' boxes (cars, vans, buses and trucks are axis-aligned boxes on
//!   the ground), and each ray counts for the nearest box it meets within `NEAR`.
//! - **Sidewalks** ([`unfilled`], with [`cameras::sidewalk_path_draws`](crate::cameras)):
//!   the walker is 1.3 m from the shop fronts on a 4.4 m sidewalk and passes trees, lamps
//!   and parked cars, so a drawn heading can face a wall, a trunk or a car door from a
//!   metre or two. A draw is filled when the renderer, at a quarter of the camera's
//!   resolution, shows more than [`WALK_MAX_SHARE`] of its pixels nearer than
//!   [`WALK_NEAR`] metres (depth along the view): anything counts, as the renderer sees it.
//!
//! Everything here is deterministic (`f64` rays in a fixed order; renders that are the
//! same on every machine, one per draw, frames in parallel but collected in order). Bump
//! [`VERSION`](super::VERSION) with any change here.

use rayon::prelude::*;

use crate::cameras::CameraPose;
use crate::model::geometry::normalize;
use crate::model::{CameraBasis, ObjectKind, Scene};
use crate::render::{self, Intrinsics, PreparedScene};

/// Draws tried per frame.
pub const DRAWS: usize = 8;

/// Reach of a blocking vehicle, metres from the eye: a vehicle 3–8 m away can still fill
/// more than half of a 60° view (with 3 m, `specs/day.toml`'s street kept such a frame).
pub const NEAR: f64 = 8.0;

/// Largest share of the view one vehicle within [`NEAR`] may cover.
pub const MAX_SHARE: f64 = 0.5;

/// Depth in metres within which a walker's view may not be filled.
pub const WALK_NEAR: f32 = 2.0;

/// Largest share of a walker's view that may be nearer than [`WALK_NEAR`] (everything
/// together, not one object): a third of the picture of bricks a metre away already
/// shows nothing a detector learns from.
pub const WALK_MAX_SHARE: f64 = 0.3;

/// Rays across the picture.
pub const COLUMNS: usize = 16;
/// Rays down the picture.
pub const ROWS: usize = 12;

/// An axis-aligned box, world metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Box3 {
    pub min: [f64; 3],
    pub max: [f64; 3],
}

/// The boxes of the scene's vehicles (objects of kind `car`), in scene order.
pub fn vehicle_boxes(scene: &Scene) -> Vec<Box3> {
    scene
        .objects
        .iter()
        .filter(|o| o.kind == ObjectKind::Car)
        .filter_map(|o| o.bounds())
        .map(|(min, max)| Box3 { min, max })
        .collect()
}

/// One pose per frame: its first draw that [`share`] finds at most [`MAX_SHARE`] blocked,
/// or its least blocked. `tan_half` is the tangent of half the field of view across and
/// down the picture. A frame without draws is left out.
pub fn unblocked(
    draws: Vec<Vec<CameraPose>>,
    boxes: &[Box3],
    tan_half: [f64; 2],
) -> Vec<CameraPose> {
    draws
        .into_iter()
        .filter_map(|frame| first_clear(frame, MAX_SHARE, |pose| share(pose, boxes, tan_half)))
        .collect()
}

/// One pose per frame: its first draw that [`near_share`] finds at most
/// [`WALK_MAX_SHARE`] filled when rendered with `check` (a quarter of the camera's
/// resolution), or its least filled. A frame without draws is left out.
pub fn unfilled(
    prepared: &PreparedScene,
    draws: Vec<Vec<CameraPose>>,
    check: &Intrinsics,
) -> Vec<CameraPose> {
    let chosen: Vec<Option<CameraPose>> = draws
        .into_par_iter()
        .map(|frame| {
            first_clear(frame, WALK_MAX_SHARE, |pose| {
                near_share(prepared, pose, check)
            })
        })
        .collect();
    chosen.into_iter().flatten().collect()
}

/// The first of `frame`'s draws whose `share` is at most `most`, or the one with the
/// least (the first of equals); `None` for no draws.
fn first_clear(
    frame: Vec<CameraPose>,
    most: f64,
    share: impl Fn(&CameraPose) -> f64,
) -> Option<CameraPose> {
    let mut best: Option<(f64, CameraPose)> = None;
    for pose in frame {
        let s = share(&pose);
        if s <= most {
            return Some(pose);
        }
        if best.as_ref().is_none_or(|(b, _)| s < *b) {
            best = Some((s, pose));
        }
    }
    best.map(|(_, pose)| pose)
}

/// The share of `pose`'s view (0–1) that the renderer, at `check`'s size, shows nearer
/// than [`WALK_NEAR`] metres of depth.
pub fn near_share(prepared: &PreparedScene, pose: &CameraPose, check: &Intrinsics) -> f64 {
    // Only depth is read: the depth test alone, no shading.
    let (shown, _) = render::visibility(prepared, pose, check, &[]);
    let pixels = shown.depth.as_raw();
    // The sky has depth 0.
    let near = pixels.iter().filter(|&&d| d > 0.0 && d < WALK_NEAR).count();
    near as f64 / pixels.len().max(1) as f64
}

/// The largest share of `pose`'s view (0–1) that one box of `boxes` covers within [`NEAR`]
/// metres of the eye, by [`COLUMNS`] × [`ROWS`] rays through the picture.
pub fn share(pose: &CameraPose, boxes: &[Box3], tan_half: [f64; 2]) -> f64 {
    let eye = pose.eye;
    let near: Vec<&Box3> = boxes
        .iter()
        .filter(|b| {
            let d2: f64 = (0..3)
                .map(|k| (b.min[k] - eye[k]).max(eye[k] - b.max[k]).max(0.0).powi(2))
                .sum();
            d2 <= NEAR * NEAR
        })
        .collect();
    if near.is_empty() {
        return 0.0;
    }
    let Some(CameraBasis { right, up, forward }) = pose.basis() else {
        return 0.0;
    };
    let mut counts = vec![0usize; near.len()];
    for row in 0..ROWS {
        let b = (1.0 - 2.0 * (row as f64 + 0.5) / ROWS as f64) * tan_half[1];
        for column in 0..COLUMNS {
            let a = (2.0 * (column as f64 + 0.5) / COLUMNS as f64 - 1.0) * tan_half[0];
            let Some(d) = normalize(std::array::from_fn(|k| {
                forward[k] + a * right[k] + b * up[k]
            })) else {
                continue;
            };
            let mut nearest: Option<(f64, usize)> = None;
            for (i, b) in near.iter().enumerate() {
                if let Some(t) = entry(eye, d, b)
                    && t <= NEAR
                    && nearest.is_none_or(|(n, _)| t < n)
                {
                    nearest = Some((t, i));
                }
            }
            if let Some((_, i)) = nearest {
                counts[i] += 1;
            }
        }
    }
    let most = counts.into_iter().max().unwrap_or(0);
    most as f64 / (COLUMNS * ROWS) as f64
}

/// Where the ray `eye + t·d` (`t ≥ 0`) enters box `b` (0 when the eye is inside), if it
/// meets it: the slab test.
fn entry(eye: [f64; 3], d: [f64; 3], b: &Box3) -> Option<f64> {
    let (mut enter, mut leave) = (0.0f64, f64::INFINITY);
    for k in 0..3 {
        if d[k] == 0.0 {
            if eye[k] < b.min[k] || eye[k] > b.max[k] {
                return None;
            }
            continue;
        }
        let (t0, t1) = ((b.min[k] - eye[k]) / d[k], (b.max[k] - eye[k]) / d[k]);
        enter = enter.max(t0.min(t1));
        leave = leave.min(t0.max(t1));
    }
    (enter <= leave).then_some(enter)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bus 2.5 m wide, 3 m tall, 12 m long beside the lane: its near side 0.65 m east of
    /// an eye at the origin, 1.5 m up, from 1 m behind to 11 m ahead (north is −z).
    fn bus() -> Box3 {
        Box3 {
            min: [0.65, 0.0, -11.0],
            max: [3.15, 3.0, 1.0],
        }
    }

    /// A pose at 1.5 m looking `heading` degrees east of north, level.
    fn looking(heading: f64) -> CameraPose {
        let (cos, sin) = crate::model::geometry::trig::cos_sin_deg(heading);
        CameraPose {
            eye: [0.0, 1.5, 0.0],
            target: [10.0 * sin, 1.5, -10.0 * cos],
            up: [0.0, 1.0, 0.0],
            angles: None,
            time: None,
        }
    }

    /// 60° down the picture, 4:3.
    const TAN_HALF: [f64; 2] = [0.577_350_269 * 4.0 / 3.0, 0.577_350_269];

    #[test]
    fn a_bus_beside_the_eye_blocks_the_view_towards_it_only() {
        let boxes = [bus()];
        // Straight down the lane the bus fills the right-hand side, under half the view.
        let ahead = share(&looking(0.0), &boxes, TAN_HALF);
        assert!(ahead > 0.1 && ahead <= MAX_SHARE, "{ahead}");
        // Turned 60° towards it: its flank fills the picture.
        let towards = share(&looking(60.0), &boxes, TAN_HALF);
        assert!(towards > 0.9, "{towards}");
        // Turned away: nothing.
        assert_eq!(share(&looking(-60.0), &boxes, TAN_HALF), 0.0);
        // The same bus 4 m further east is within NEAR (3 m until 26 Nov): the two fifths
        // of that view it fills count, though they stay under the limit.
        let beyond = Box3 {
            min: [4.65, 0.0, -11.0],
            max: [7.15, 3.0, 1.0],
        };
        let four = share(&looking(60.0), &[beyond], TAN_HALF);
        assert!(four > 0.35 && four <= MAX_SHARE, "{four}");
        // 8 m further east it is beyond NEAR: it does not count.
        let far = Box3 {
            min: [8.65, 0.0, -11.0],
            max: [11.15, 3.0, 1.0],
        };
        assert_eq!(share(&looking(60.0), &[far], TAN_HALF), 0.0);
    }

    #[test]
    fn each_frame_keeps_its_first_clear_draw_or_its_least_blocked() {
        let boxes = [bus()];
        let frames = vec![
            // Clear at once: kept as drawn.
            vec![looking(-30.0), looking(0.0)],
            // Blocked, then clear: the second draw.
            vec![looking(60.0), looking(70.0), looking(-10.0), looking(-20.0)],
            // All blocked: the least blocked, the first of equals.
            vec![looking(80.0), looking(50.0), looking(50.0)],
            // No draws: no frame.
            vec![],
        ];
        let kept = unblocked(frames, &boxes, TAN_HALF);
        assert_eq!(kept.len(), 3);
        assert_eq!(kept[0], looking(-30.0));
        assert_eq!(kept[1], looking(-10.0));
        let s = |h| share(&looking(h), &boxes, TAN_HALF);
        let least = if s(50.0) < s(80.0) { 50.0 } else { 80.0 };
        assert_eq!(kept[2], looking(least));
    }

    #[test]
    fn the_slab_test_enters_boxes_ahead_and_reports_zero_from_inside() {
        let b = Box3 {
            min: [1.0, -1.0, -1.0],
            max: [2.0, 1.0, 1.0],
        };
        assert_eq!(entry([0.0; 3], [1.0, 0.0, 0.0], &b), Some(1.0));
        assert_eq!(entry([0.0; 3], [-1.0, 0.0, 0.0], &b), None);
        assert_eq!(entry([0.0, 2.0, 0.0], [1.0, 0.0, 0.0], &b), None);
        assert_eq!(entry([1.5, 0.0, 0.0], [0.0, 1.0, 0.0], &b), Some(0.0));
    }

    /// A wall 20 m long, 4 m tall and 0.2 m thick, its face 1 m east of the eye of
    /// [`looking`], prepared for rendering.
    fn wall_east() -> PreparedScene {
        use crate::model::geometry::MeshBuilder;
        use crate::model::{Material, SceneObject};
        let mut mesh = MeshBuilder::new(0);
        mesh.oriented_box([1.1, 0.0, 0.0], [0.0, 1.0], [10.0, 0.1], 4.0);
        let scene = Scene {
            textures: Vec::new(),
            materials: vec![Material {
                name: "brick".into(),
                colour: [0.5; 3],
                texture: None,
                emissive: [0.0; 3],
                emissive_textured: false,
            }],
            objects: vec![SceneObject {
                name: "building_0000".into(),
                kind: crate::model::ObjectKind::Building,
                class: "building".into(),
                meshes: vec![mesh.finish()],
            }],
        };
        render::prepare(&scene).expect("a one-box scene prepares")
    }

    #[test]
    fn a_wall_a_metre_away_fills_a_walkers_view_turned_to_it_only() {
        let prepared = wall_east();
        let check = Intrinsics::from_fov(64, 48, TAN_HALF[1]);
        // Facing it: all wall, 1 m away.
        assert!(near_share(&prepared, &looking(90.0), &check) > 0.95);
        // Turned away: nothing near (and no sky counts).
        assert_eq!(near_share(&prepared, &looking(-90.0), &check), 0.0);
        // Along it: the wall's first 2 m of depth on the right edge, under the limit.
        let along = near_share(&prepared, &looking(0.0), &check);
        assert!(along > 0.05 && along <= WALK_MAX_SHARE, "{along}");
        // Each frame keeps its first draw not filled, else the least filled.
        let kept = unfilled(
            &prepared,
            vec![
                vec![looking(90.0), looking(0.0), looking(-90.0)],
                vec![looking(90.0), looking(60.0)],
                vec![],
            ],
            &check,
        );
        assert_eq!(kept, vec![looking(0.0), looking(60.0)]);
    }
}
