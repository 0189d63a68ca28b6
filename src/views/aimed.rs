//! An objects camera's poses: scene + parsed layout + camera spec → one pose per frame,
//! aimed at an object of the camera's classes that the renderer shows.
//!
//! The cameras stage proposes candidates
//! ([`cameras::object_views`]) from geometry alone; here each candidate is rendered at a
//! quarter of the camera's resolution and kept only if its object shows, so a target
//! behind a building, a lamp or another object is never aimed at.

use rayon::prelude::*;

use crate::cameras::{self, ObjectTarget, ObjectView, ObjectsPath};
use crate::model::{CameraPose, Scene, Streets};
use crate::render::{self, Intrinsics, PreparedScene};
use crate::spec::{CameraSpec, DEFAULT_FRAMES};

/// Share of its footprint (the pixels it would cover with nothing in front and no image
/// edge) a target must show: at least half of it unhidden and in the picture.
pub const MIN_SHOWN: f64 = 0.5;

/// Pixels a target must show in the quarter-resolution check (≈ 16 × that at full size).
pub const MIN_CHECK_PIXELS: u64 = 4;

/// Each frame's first candidate whose object shows (at least [`MIN_SHOWN`] of its
/// footprint and [`MIN_CHECK_PIXELS`] pixels at a quarter of the resolution). A frame none
/// of whose candidates shows its object is left out, so the path may have fewer frames
/// than asked for (none, when no object of the classes can be seen from free space).
pub fn aimed_poses(
    prepared: &PreparedScene,
    scene: &Scene,
    streets: Streets,
    metres_per_pixel: f64,
    camera: &CameraSpec,
    seed: u64,
) -> Vec<CameraPose> {
    let targets = object_targets(scene, &camera.classes);
    let path = ObjectsPath {
        frames: camera.frames.unwrap_or(DEFAULT_FRAMES),
        aim: cameras::Aim::of(camera),
        distance: camera.distance,
        angle: camera.angle,
    };
    let candidates = cameras::object_views(streets, metres_per_pixel, &targets, &path, seed);
    let check = check_intrinsics(camera);
    let chosen: Vec<Option<CameraPose>> = candidates
        .par_iter()
        .map(|frame| {
            frame
                .iter()
                .find(|view| shows(prepared, view, &check))
                .map(|view| view.pose)
        })
        .collect();
    chosen.into_iter().flatten().collect()
}

/// The camera at a quarter of its resolution (at least 16 × 16), for renders that only
/// check what a view shows.
pub fn check_intrinsics(camera: &CameraSpec) -> Intrinsics {
    let (w, h) = (camera.resolution[0], camera.resolution[1]);
    Intrinsics::from_fov(
        (w / 4).max(16),
        (h / 4).max(16),
        cameras::tan_half_degrees(camera.fov),
    )
}

/// Whether `view`'s object shows enough in a render with `intrinsics`.
fn shows(prepared: &PreparedScene, view: &ObjectView, intrinsics: &Intrinsics) -> bool {
    let id = view.target;
    let (frame, footprints) = render::visibility(prepared, &view.pose, intrinsics, &[id]);
    let Some(footprint) = footprints.first() else {
        return false;
    };
    let visible = frame.instance.pixels().filter(|p| p.0[0] == id).count() as u64;
    visible >= MIN_CHECK_PIXELS && visible as f64 >= MIN_SHOWN * footprint.pixels as f64
}

/// The objects of `classes` as targets, in scene order: each aimed at the centre of its
/// bounding box, its front the area-weighted mean normal of its textured triangles (a text
/// plate's words, a sign's face) when that leans clearly one way in plan; none otherwise
/// (a lamp, or a building textured on every side).
pub fn object_targets(scene: &Scene, classes: &[String]) -> Vec<ObjectTarget> {
    scene
        .objects
        .iter()
        .zip(1u32..)
        .filter(|(object, _)| classes.contains(&object.class))
        .filter_map(|(object, id)| {
            let (min, max) = object.bounds()?;
            let mut normal = [0.0f64; 3];
            for mesh in &object.meshes {
                let textured = scene
                    .materials
                    .get(mesh.material as usize)
                    .is_some_and(|m| m.texture.is_some());
                if !textured {
                    continue;
                }
                for tri in mesh.indices.chunks_exact(3) {
                    let [a, b, c] = [0, 1, 2].map(|k| {
                        mesh.positions
                            .get(tri[k] as usize)
                            .map_or([0.0; 3], |p| p.map(f64::from))
                    });
                    let (u, v) = (sub(b, a), sub(c, a));
                    // Twice the area times the unit normal: counter-clockwise is the front.
                    let n = [
                        u[1] * v[2] - u[2] * v[1],
                        u[2] * v[0] - u[0] * v[2],
                        u[0] * v[1] - u[1] * v[0],
                    ];
                    normal = [normal[0] + n[0], normal[1] + n[1], normal[2] + n[2]];
                }
            }
            let flat = (normal[0] * normal[0] + normal[2] * normal[2]).sqrt();
            let length = (flat * flat + normal[1] * normal[1]).sqrt();
            let front =
                (flat > 0.0 && flat >= 0.5 * length).then(|| [normal[0] / flat, normal[2] / flat]);
            Some(ObjectTarget {
                id,
                centre: std::array::from_fn(|k| (min[k] + max[k]) / 2.0),
                front,
            })
        })
        .collect()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Material, Mesh, SceneObject};

    fn quad(material: u32, facing_south: bool) -> Mesh {
        // A 2 × 1 m quad in the plane z = 5, x 0–2, y 1–2.
        let positions = vec![
            [0.0, 1.0, 5.0],
            [2.0, 1.0, 5.0],
            [2.0, 2.0, 5.0],
            [0.0, 2.0, 5.0],
        ];
        let indices = if facing_south {
            vec![0, 1, 2, 0, 2, 3]
        } else {
            vec![0, 2, 1, 0, 3, 2]
        };
        Mesh {
            material,
            positions,
            normals: Vec::new(),
            uvs: Vec::new(),
            indices,
        }
    }

    #[test]
    fn targets_face_the_way_their_textured_side_looks() {
        let material = |name: &str, texture| Material {
            name: name.to_owned(),
            colour: [1.0; 3],
            texture,
            emissive: [0.0; 3],
            emissive_textured: false,
        };
        let object = |name: &str, class: &str, meshes| SceneObject {
            name: name.to_owned(),
            kind: crate::model::ObjectKind::ALL
                .into_iter()
                .find(|k| k.name() == class)
                .unwrap_or(crate::model::ObjectKind::Mesh),
            class: class.to_owned(),
            meshes,
        };
        let scene = Scene {
            textures: Vec::new(),
            materials: vec![material("plain", None), material("words", Some(0))],
            objects: vec![
                object("road_0000", "road", vec![quad(0, true)]),
                // Words facing south, an untextured back facing north.
                object("text_0000", "text", vec![quad(1, true), quad(0, false)]),
                object("text_0001", "text", vec![quad(1, false)]),
                // Textured on both sides: no front.
                object("sign_0000", "sign", vec![quad(1, true), quad(1, false)]),
            ],
        };
        let classes = ["text".to_owned(), "sign".to_owned()];
        let targets = object_targets(&scene, &classes);
        let summary: Vec<(u32, Option<[f64; 2]>)> =
            targets.iter().map(|t| (t.id, t.front)).collect();
        assert_eq!(
            summary,
            [(2, Some([0.0, 1.0])), (3, Some([0.0, -1.0])), (4, None)]
        );
        assert_eq!(targets[0].centre, [1.0, 1.5, 5.0]);
    }
}
