//! Whole-frame tests on small hand-built scenes: the scene-building helpers they share (also
//! used by `shadow_tests` and `occlusion`), one file per subject.

use image::{Rgb, RgbImage};

use super::*;
use crate::model::geometry::{cross, dot, sub};
use crate::model::{Material, Mesh, Scene, SceneObject, Texture};

mod coverage;
mod depth;
mod flow;
mod footprints;
mod night;
mod normals;
mod perspective;
mod posing;
mod preparing;
mod sampling;

pub(super) fn material(colour: [f32; 3], texture: Option<u32>, emissive: [f32; 3]) -> Material {
    Material {
        name: format!("m{}", texture.map_or(-1, i64::from)),
        colour,
        texture,
        emissive,
        emissive_textured: false,
    }
}

/// A quad through corners `c` (in order around it), wound counter-clockwise around
/// `normal`, with vertex normals `normal`.
pub(super) fn quad(material: u32, c: [[f32; 3]; 4], uv: [[f32; 2]; 4], normal: [f32; 3]) -> Mesh {
    let g = cross(sub(c[1], c[0]), sub(c[2], c[0]));
    let indices = if dot(g, normal) >= 0.0 {
        vec![0, 1, 2, 0, 2, 3]
    } else {
        vec![0, 2, 1, 0, 3, 2]
    };
    Mesh {
        material,
        positions: c.to_vec(),
        normals: vec![normal; 4],
        uvs: uv.to_vec(),
        indices,
    }
}

/// A flat ground quad (material 0) reaching `half` metres from the origin each way, up.
pub(super) fn ground_quad(half: f32) -> Mesh {
    let c = [
        [-half, 0.0, -half],
        [half, 0.0, -half],
        [half, 0.0, half],
        [-half, 0.0, half],
    ];
    quad(0, c, UNIT_UV, [0.0, 1.0, 0.0])
}

pub(super) const UNIT_UV: [[f32; 2]; 4] = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];

/// A closed box, every face wound counter-clockwise seen from outside.
pub(super) fn cuboid(material: u32, lo: [f32; 3], hi: [f32; 3]) -> Vec<Mesh> {
    let [x0, y0, z0] = lo;
    let [x1, y1, z1] = hi;
    let faces = [
        (
            [[x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [x1, y0, z1]],
            [1.0, 0.0, 0.0],
        ),
        (
            [[x0, y0, z0], [x0, y1, z0], [x0, y1, z1], [x0, y0, z1]],
            [-1.0, 0.0, 0.0],
        ),
        (
            [[x0, y1, z0], [x1, y1, z0], [x1, y1, z1], [x0, y1, z1]],
            [0.0, 1.0, 0.0],
        ),
        (
            [[x0, y0, z0], [x1, y0, z0], [x1, y0, z1], [x0, y0, z1]],
            [0.0, -1.0, 0.0],
        ),
        (
            [[x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]],
            [0.0, 0.0, 1.0],
        ),
        (
            [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0]],
            [0.0, 0.0, -1.0],
        ),
    ];
    faces
        .into_iter()
        .map(|(c, n)| quad(material, c, UNIT_UV, n))
        .collect()
}

pub(super) fn object(name: &str, meshes: Vec<Mesh>) -> SceneObject {
    SceneObject {
        name: name.into(),
        kind: crate::model::ObjectKind::Mesh,
        class: "test".into(),
        meshes,
    }
}

fn checker_texture(size: u32, cell: u32) -> Texture {
    let image = RgbImage::from_fn(size, size, |x, y| {
        if (x / cell + y / cell).is_multiple_of(2) {
            Rgb([255, 255, 255])
        } else {
            Rgb([0, 0, 0])
        }
    });
    Texture::from_rgb(format!("checker_{size}_{cell}"), image)
}

pub(super) fn pose(eye: [f64; 3], target: [f64; 3]) -> CameraPose {
    CameraPose::level(eye, target)
}

/// Colour = albedo: black sky, white ambient, no sun, no emission.
pub(super) fn flat() -> Lighting {
    Lighting {
        sky: Sky::flat([0.0; 3]),
        ambient: [1.0; 3],
        ground_ambient: [1.0; 3],
        sun_direction: [0.0, 1.0, 0.0],
        sun_colour: [0.0; 3],
        shadows: false,
        shadow_map_side: MAX_SHADOW_MAP_SIDE,
        shadow_strength: 1.0,
        ambient_occlusion: 0.0,
        lights: Vec::new(),
        carried: Vec::new(),
        emission: 0.0,
        windows: None,
        exposure: 1.0,
    }
}

/// Pixel `(x, y)` of the frame's linear colour written as sRGB with a plain clip (no tone
/// curve): the albedo, under [`flat`] lighting.
fn clipped(frame: &Frame, x: u32, y: u32) -> [u8; 3] {
    let table = crate::model::srgb::srgb();
    frame.linear[(y * frame.rgb().width() + x) as usize].map(|c| table.to_srgb8(c))
}

fn count(frame: &Frame, id: u32) -> usize {
    frame.instance.pixels().filter(|p| p.0[0] == id).count()
}

fn wall(z: f32, half: f32) -> Mesh {
    quad(
        0,
        [
            [-half, -half, z],
            [half, -half, z],
            [half, half, z],
            [-half, half, z],
        ],
        UNIT_UV,
        [0.0, 0.0, 1.0],
    )
}

fn street_scene() -> Scene {
    let ground = quad(
        0,
        [
            [-200.0, 0.0, -200.0],
            [200.0, 0.0, -200.0],
            [200.0, 0.0, 200.0],
            [-200.0, 0.0, 200.0],
        ],
        [[-50.0, -50.0], [50.0, -50.0], [50.0, 50.0], [-50.0, 50.0]],
        [0.0, 1.0, 0.0],
    );
    let mut objects = vec![object("ground", vec![ground])];
    for i in 0..10 {
        let x = -30.0 + 7.0 * i as f32;
        let z = -15.0 - 3.0 * (i % 3) as f32;
        objects.push(object(
            &format!("building_{i}"),
            cuboid(1 + (i % 2), [x, 0.0, z - 5.0], [x + 5.0, 6.0 + i as f32, z]),
        ));
    }
    objects.push(object(
        "lamp",
        cuboid(3, [2.0, 4.0, -8.0], [2.4, 4.3, -7.6]),
    ));
    Scene {
        textures: vec![checker_texture(16, 2), checker_texture(64, 8)],
        materials: vec![
            material([0.4, 0.4, 0.45], Some(0), [0.0; 3]),
            material([0.9, 0.8, 0.7], Some(1), [0.0; 3]),
            material([0.6, 0.7, 0.9], Some(0), [0.0; 3]),
            material([0.1; 3], None, [4.0, 3.5, 2.5]),
        ],
        objects,
    }
}
