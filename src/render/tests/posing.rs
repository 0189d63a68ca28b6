//! A posed scene ([`PreparedScene::posed`]): moved objects and swapped lamps render as a
//! scene built with them there, shadows included.

use super::{cuboid, ground_quad, material, object, pose};
use crate::model::{Movement, Recolour, Scene};
use crate::render::*;

/// A 40 m plane, a tall box and a small "car" box (object 3) that moves, and a "lamp"
/// (object 4) of material 1 that can be switched to material 2.
fn street(car_at: f32) -> Scene {
    let plane = ground_quad(20.0);
    Scene {
        textures: Vec::new(),
        materials: vec![
            material([0.8; 3], None, [0.0; 3]),
            material([0.1, 0.0, 0.0], None, [0.0; 3]),
            material([1.0, 0.1, 0.0], None, [1.0, 0.1, 0.0]),
        ],
        objects: vec![
            object("plane", vec![plane]),
            object("tower", cuboid(0, [-6.0, 0.0, -6.0], [-4.0, 8.0, -4.0])),
            object(
                "car",
                cuboid(0, [car_at, 0.0, 1.0], [car_at + 4.0, 1.5, 3.0]),
            ),
            object("lamp", cuboid(1, [5.0, 2.0, -3.0], [5.5, 2.5, -2.5])),
        ],
    }
}

fn sunny() -> Lighting {
    let mut lighting = Lighting::day();
    lighting.shadows = true;
    lighting.shadow_map_side = 1024;
    lighting
}

fn shot(scene: &PreparedScene, lighting: &Lighting) -> Frame {
    let intrinsics = Intrinsics::from_fov(160, 120, 0.8);
    let eye = pose([0.0, 6.0, 22.0], [0.0, 0.0, 0.0]);
    render(scene, &eye, &intrinsics, lighting, 1)
}

fn sun(lighting: &Lighting) -> Option<([f32; 3], u32)> {
    Some((lighting.sun_direction, lighting.shadow_map_side))
}

#[test]
fn a_posed_scene_renders_as_one_built_with_the_objects_moved() {
    let lighting = sunny();
    let base = prepare(&street(-2.0)).unwrap();
    let moved = prepare(&street(3.0)).unwrap();
    let movement = Movement {
        moves: vec![(3, [5.0, 0.0, 0.0])],
        ..Movement::default()
    };
    let posed = base.posed(&movement, sun(&lighting));
    let (a, b) = (shot(&posed, &lighting), shot(&moved, &lighting));
    assert!(a.rgb() == b.rgb() && a.instance == b.instance && a.depth == b.depth);
    // And it differs from the scene as built (the car and its shadow moved).
    assert!(shot(&base, &lighting).rgb() != a.rgb());
}

#[test]
fn nothing_moved_is_the_scene_as_built_to_the_byte() {
    let lighting = sunny();
    let base = prepare(&street(-2.0)).unwrap();
    let movement = Movement {
        moves: vec![(3, [0.0; 3])],
        ..Movement::default()
    };
    let posed = base.posed(&movement, sun(&lighting));
    let (a, b) = (shot(&posed, &lighting), shot(&base, &lighting));
    assert!(a.rgb() == b.rgb() && a.instance == b.instance && a.depth == b.depth);
}

#[test]
fn a_recoloured_lamp_takes_its_new_material_only_in_its_object() {
    let lighting = sunny();
    let mut lit = street(-2.0);
    lit.objects[3]
        .meshes
        .iter_mut()
        .for_each(|m| m.material = 2);
    let movement = Movement {
        recolour: vec![Recolour {
            instance: 4,
            from: 1,
            to: 2,
        }],
        ..Movement::default()
    };
    let posed = prepare(&street(-2.0)).unwrap().posed(&movement, None);
    let (a, b) = (
        shot(&posed, &lighting),
        shot(&prepare(&lit).unwrap(), &lighting),
    );
    assert!(a.rgb() == b.rgb());
}

#[test]
fn carried_lights_move_with_their_object_and_the_others_stay() {
    let mut lighting = Lighting::night(
        vec![
            Light::point([0.0, 1.0, 0.0], [1.0; 3], 5.0),
            Light::point([3.0, 1.0, 0.0], [1.0; 3], 5.0),
        ],
        None,
    );
    lighting.carried = vec![(1, 7)];
    let driving = Movement {
        moves: vec![(7, [2.0, 0.0, -1.0])],
        ..Movement::default()
    };
    let moved = lighting.moved(&driving).unwrap();
    assert_eq!(moved.lights[0].position, [0.0, 1.0, 0.0]);
    assert_eq!(moved.lights[1].position, [5.0, 1.0, -1.0]);
    let standing = Movement {
        moves: vec![(7, [0.0; 3])],
        ..Movement::default()
    };
    assert!(lighting.moved(&standing).is_none());
}
