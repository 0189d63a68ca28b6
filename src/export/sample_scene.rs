//! Test scenes built by hand: textured boxes, a shared and an unused texture, an emissive
//! lamp. Only for the export's tests (the scene stage builds the real ones).

use image::RgbImage;

use crate::model::geometry::cross;
use crate::model::{Material, Mesh, ObjectKind, Scene, SceneObject, Texture};

fn texture(name: &str, size: u32, salt: u8) -> Texture {
    let image = RgbImage::from_fn(size, size, |x, y| {
        image::Rgb([x as u8 * 30 + salt, y as u8 * 30, 200 - salt])
    });
    Texture::from_rgb(name, image)
}

fn material(name: &str, colour: [f32; 3], texture: Option<u32>, emissive: [f32; 3]) -> Material {
    Material {
        name: name.to_owned(),
        colour,
        texture,
        emissive,
        emissive_textured: false,
    }
}

/// One quad from corner `p0` along edges `u` then `w`; `u × w` is the outward normal, so
/// the two triangles wind counter-clockwise seen from outside. `uv` spans `(0, 1)` at `p0`
/// to `(us, 0)` at `p0 + u + w` (v down from the top edge).
fn push_quad(mesh: &mut Mesh, p0: [f32; 3], u: [f32; 3], w: [f32; 3], us: f32) {
    let add = |a: [f32; 3], b: [f32; 3]| [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
    let n = cross(u, w);
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    let n = [n[0] / len, n[1] / len, n[2] / len];
    let base = mesh.positions.len() as u32;
    mesh.positions
        .extend([p0, add(p0, u), add(add(p0, u), w), add(p0, w)]);
    mesh.normals.extend([n; 4]);
    mesh.uvs
        .extend([[0.0, 1.0], [us, 1.0], [us, 0.0], [0.0, 0.0]]);
    mesh.indices
        .extend([base, base + 1, base + 2, base, base + 2, base + 3]);
}

/// A box on the ground from `min` to `max`: four walls of `wall` material, a roof of `roof`.
fn boxed(min: [f32; 3], max: [f32; 3], wall: u32, roof: u32) -> Vec<Mesh> {
    let [x0, y0, z0] = min;
    let [x1, y1, z1] = max;
    let (dx, dy, dz) = (x1 - x0, y1 - y0, z1 - z0);
    let mut walls = Mesh {
        material: wall,
        ..Mesh::default()
    };
    push_quad(
        &mut walls,
        [x0, y0, z1],
        [dx, 0.0, 0.0],
        [0.0, dy, 0.0],
        1.0,
    ); // south, +z
    push_quad(
        &mut walls,
        [x1, y0, z1],
        [0.0, 0.0, -dz],
        [0.0, dy, 0.0],
        1.0,
    ); // east, +x
    push_quad(
        &mut walls,
        [x1, y0, z0],
        [-dx, 0.0, 0.0],
        [0.0, dy, 0.0],
        2.5,
    ); // north, -z
    push_quad(
        &mut walls,
        [x0, y0, z0],
        [0.0, 0.0, dz],
        [0.0, dy, 0.0],
        1.0,
    ); // west, -x
    let mut top = Mesh {
        material: roof,
        ..Mesh::default()
    };
    push_quad(&mut top, [x0, y1, z1], [dx, 0.0, 0.0], [0.0, 0.0, -dz], 1.0); // roof, +y
    vec![walls, top]
}

fn object(name: &str, kind: ObjectKind, meshes: Vec<Mesh>) -> SceneObject {
    SceneObject {
        name: name.to_owned(),
        kind,
        class: kind.name().to_owned(),
        meshes,
    }
}

/// Five objects, five materials, four textures (two with identical bytes, one unused).
pub fn sample_scene() -> Scene {
    let mut ground = Mesh {
        material: 2,
        ..Mesh::default()
    };
    // Crosses the origin, so positions print as negative, zero and positive numbers.
    push_quad(
        &mut ground,
        [-50.0, 0.0, 50.0],
        [100.0, 0.0, 0.0],
        [0.0, 0.0, -100.0],
        10.0,
    );
    let mut sign = Mesh {
        material: 4,
        ..Mesh::default()
    };
    push_quad(
        &mut sign,
        [1.0, 2.0, 10.01],
        [2.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        1.0,
    );
    Scene {
        textures: vec![
            texture("brick", 8, 0),
            texture("brick_copy", 8, 0),
            texture("glass", 4, 40),
            texture("unused", 4, 80),
        ],
        materials: vec![
            material("facade_a", [1.0, 1.0, 1.0], Some(0), [0.0; 3]),
            material("facade_b", [0.9, 0.8, 0.7], Some(1), [0.0; 3]),
            material("roof", [0.3, 0.3, 0.35], None, [0.0; 3]),
            material("lamp_head", [1.0, 0.95, 0.8], None, [1.0, 0.9, 0.6]),
            material("sign", [1.0, 1.0, 1.0], Some(2), [0.0; 3]),
        ],
        objects: vec![
            object("ground", ObjectKind::Ground, vec![ground]),
            object(
                "building_0000",
                ObjectKind::Building,
                boxed([0.0; 3], [10.0, 12.0, 10.0], 0, 2),
            ),
            object(
                "building_0001",
                ObjectKind::Building,
                boxed([-20.5, 0.0, -8.0], [-8.25, 30.0, 4.0], 1, 2),
            ),
            object(
                "lamp_0000",
                ObjectKind::Lamp,
                boxed([12.0, 5.0, 12.0], [12.4, 5.4, 12.4], 3, 3),
            ),
            object("sign_0000", ObjectKind::Sign, vec![sign]),
        ],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quads_wind_counter_clockwise_towards_their_normals() {
        let scene = sample_scene();
        for mesh in scene.objects.iter().flat_map(|o| &o.meshes) {
            for tri in mesh.indices.chunks(3) {
                let [a, b, c] = [0, 1, 2].map(|k| mesh.positions[tri[k] as usize]);
                let sub = |p: [f32; 3], q: [f32; 3]| [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
                let n = cross(sub(b, a), sub(c, a));
                let stored = mesh.normals[tri[0] as usize];
                let dot = n[0] * stored[0] + n[1] * stored[1] + n[2] * stored[2];
                assert!(dot > 0.0, "triangle {tri:?} faces away from its normal");
            }
        }
    }
}
