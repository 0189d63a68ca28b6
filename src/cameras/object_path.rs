//! Object views: labelled objects' positions + free space → candidate viewpoints per
//! frame, each aimed at one object from a seeded distance and bearing.
//!
//! The stage cannot see: whether a candidate's object is hidden behind a building, a lamp
//! or another object is the renderer's to say. So each frame gets [`ATTEMPTS`] candidates
//! in order, and the build's frames glue keeps the first whose object shows enough.

use rand::Rng;
use serde::{Deserialize, Serialize};

use super::CameraPose;
use super::aim::{Aim, aimed_pose, unit};
use crate::model::Streets;
use crate::model::geometry::cos_sin_deg;
use crate::rng;
use crate::spec::ValueRange;

/// Candidate viewpoints drawn per frame.
pub const ATTEMPTS: u32 = 12;

/// Metres an eye keeps from every block (the blocks hold the buildings): it stands on a
/// road or a sidewalk, never in a wall.
pub const CLEARANCE: f64 = 0.75;

/// Steepest line of sight from the eye up (or down) to the object, degrees. A person or a
/// car camera looks at a shop sign from across the street, not from under it: an eye that
/// would see its object steeper steps back along its bearing (within the path's distance
/// range) until the sight is this steep, or is dropped.
pub const MAX_ELEVATION: f64 = 20.0;

/// An object a camera may aim at.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ObjectTarget {
    /// Instance id (scene object index + 1).
    pub id: u32,
    /// The point to aim at, metres.
    pub centre: [f64; 3],
    /// Unit `[x, z]` direction its front looks to, if it has one (a text plate, a sign's
    /// face); bearings are measured from it.
    pub front: Option<[f64; 2]>,
}

/// How an objects path draws its viewpoints.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ObjectsPath {
    pub frames: u32,
    /// Heading and pitch turn the aim off the line of sight; roll and eye height as drawn.
    pub aim: Aim,
    /// Horizontal distance from the object to the eye, metres.
    pub distance: ValueRange,
    /// Bearing of the eye around the object from its front, degrees, positive clockwise
    /// seen from above; any bearing for an object without a front.
    pub angle: ValueRange,
}

/// One candidate: the object aimed at and the pose.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ObjectView {
    pub target: u32,
    pub pose: CameraPose,
}

/// Up to [`ATTEMPTS`] candidate views for each of `path.frames` frames. Attempt `a` of
/// frame `i` draws from `rng::stream(seed, "cameras/objects", i · ATTEMPTS + a)`, in order:
/// the object (uniformly among `targets`), the distance, the bearing, then the aim. A
/// candidate whose line of sight is steeper than `MAX_ELEVATION` steps back to that
/// elevation if the distance range allows, else it is dropped; a candidate whose eye is
/// outside the layout or within [`CLEARANCE`] of a block (on a map: outside its box or
/// within [`CLEARANCE`] of a building) is dropped, so a frame may get
/// fewer candidates, or none. The pose's recorded heading and
/// pitch are the aim's turn off the line of sight.
///
/// No candidates at all without targets or with a parameter out of range
/// (`metres_per_pixel` positive and finite, ranges finite, distances positive).
pub fn object_views(
    streets: Streets,
    metres_per_pixel: f64,
    targets: &[ObjectTarget],
    path: &ObjectsPath,
    seed: u64,
) -> Vec<Vec<ObjectView>> {
    let m = metres_per_pixel;
    let valid = m.is_finite()
        && m > 0.0
        && path.aim.is_valid()
        && path.distance.is_finite()
        && path.distance.ends()[0] > 0.0
        && path.angle.is_finite();
    if !valid || targets.is_empty() {
        return Vec::new();
    }
    let attempts = u64::from(ATTEMPTS);
    let tan_max_elevation = libm::tan(MAX_ELEVATION.to_radians());
    (0..u64::from(path.frames))
        .map(|frame| {
            (0..attempts)
                .filter_map(|a| {
                    let mut stream = rng::stream(seed, "cameras/objects", frame * attempts + a);
                    let pick = (unit(stream.next_u64()) * targets.len() as f64) as usize;
                    let target = &targets[pick.min(targets.len() - 1)];
                    let drawn = path.distance.at(unit(stream.next_u64()));
                    let turn = unit(stream.next_u64());
                    let (bearing, from) = match target.front {
                        Some(front) => (path.angle.at(turn), front),
                        None => (360.0 * turn - 180.0, [0.0, -1.0]),
                    };
                    let out = turned(from, bearing);
                    let angles = path.aim.draw(&mut stream);
                    let rise = (target.centre[1] - angles.height).abs();
                    let distance = drawn.max(rise / tan_max_elevation);
                    if distance > path.distance.ends()[1] * (1.0 + 1e-9) {
                        return None;
                    }
                    let ground = [
                        target.centre[0] + out[0] * distance,
                        target.centre[2] + out[1] * distance,
                    ];
                    if !free(streets, m, ground) {
                        return None;
                    }
                    let sight = [
                        target.centre[0] - ground[0],
                        target.centre[1] - angles.height,
                        target.centre[2] - ground[1],
                    ];
                    let flat = (sight[0] * sight[0] + sight[2] * sight[2]).sqrt();
                    let length = (flat * flat + sight[1] * sight[1]).sqrt();
                    if !(flat > 0.0 && length.is_finite()) {
                        return None;
                    }
                    let dir = [sight[0] / flat, sight[2] / flat];
                    let base = (flat / length, sight[1] / length);
                    Some(ObjectView {
                        target: target.id,
                        pose: aimed_pose(ground, dir, base, angles, length),
                    })
                })
                .collect()
        })
        .collect()
}

/// Unit `v` turned `degrees` clockwise seen from above (x east, z south).
fn turned(v: [f64; 2], degrees: f64) -> [f64; 2] {
    let (c, s) = cos_sin_deg(degrees);
    [c * v[0] - s * v[1], c * v[1] + s * v[0]]
}

/// Whether ground point `p` (metres) is free to stand on: on a layout, inside it and at
/// least [`CLEARANCE`] from every block, checked at `p` and at the four points that far
/// from it along the axes (blocks are unions of pixel rectangles, at least a few metres
/// wide); on a map, inside its box and out of every building by at least [`CLEARANCE`].
fn free(streets: Streets, m: f64, p: [f64; 2]) -> bool {
    let layout = match streets {
        Streets::Layout(layout) => layout,
        Streets::Map(map) => {
            let [x0, z0, x1, z1] = map.extent;
            let inside = (x0..=x1).contains(&p[0]) && (z0..=z1).contains(&p[1]);
            return inside && !map.in_building(p) && map.building_distance(p) >= CLEARANCE;
        }
    };
    let (w, h) = (f64::from(layout.width) * m, f64::from(layout.height) * m);
    let c = CLEARANCE;
    let probes = [
        p,
        [p[0] - c, p[1]],
        [p[0] + c, p[1]],
        [p[0], p[1] - c],
        [p[0], p[1] + c],
    ];
    probes.iter().all(|q| {
        let inside = q[0] >= 0.0 && q[1] >= 0.0 && q[0] < w && q[1] < h;
        inside && {
            let (x, y) = ((q[0] / m) as u32, (q[1] / m) as u32);
            !layout.blocks.iter().any(|b| b.contains_pixel(x, y))
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ParsedLayout;
    use crate::model::{Band, Block, PxRect};

    /// A 100 × 100 m layout at 1 m per pixel with one block x 40–60, z 40–60.
    fn layout() -> ParsedLayout {
        ParsedLayout {
            width: 100,
            height: 100,
            blocks: vec![Block {
                id: 0,
                bbox: PxRect {
                    x0: 40,
                    y0: 40,
                    x1: 60,
                    y1: 60,
                },
                area: 400,
                outline: Vec::new(),
                bands: vec![Band {
                    y0: 40,
                    y1: 60,
                    spans: vec![[40, 60]],
                }],
            }],
            roads: Vec::new(),
        }
    }

    fn path(heading: ValueRange) -> ObjectsPath {
        ObjectsPath {
            frames: 20,
            aim: Aim {
                heading,
                pitch: ValueRange::Fixed(0.0),
                roll: ValueRange::Fixed(0.0),
                height: ValueRange::Fixed(1.6),
            },
            distance: ValueRange::Between([4.0, 8.0]),
            angle: ValueRange::Between([-45.0, 45.0]),
        }
    }

    /// Text on the block's north wall, facing north, 3 m up.
    const TEXT: ObjectTarget = ObjectTarget {
        id: 7,
        centre: [50.0, 3.0, 40.0],
        front: Some([0.0, -1.0]),
    };

    #[test]
    fn on_a_map_views_stand_in_its_box_clear_of_its_buildings() {
        let map = crate::test_support::street_map();
        // A plate on the building's north wall (z 19, x −120…−100), and its middle: with
        // bearings all round, eyes fall on the street, in the building and out of the box.
        let wall = ObjectTarget {
            id: 1,
            centre: [-110.0, 3.0, 19.0],
            front: Some([0.0, -1.0]),
        };
        let mut around = path(ValueRange::Fixed(0.0));
        around.angle = ValueRange::Between([-180.0, 180.0]);
        around.distance = ValueRange::Between([2.0, 60.0]);
        let views = object_views(Streets::Map(&map), 1.0, &[wall], &around, 4);
        let eyes: Vec<[f64; 2]> = views
            .iter()
            .flatten()
            .map(|v| [v.pose.eye[0], v.pose.eye[2]])
            .collect();
        assert!(eyes.len() > 20, "{} eyes", eyes.len());
        assert!(
            eyes.len() < views.len() * ATTEMPTS as usize,
            "some are dropped"
        );
        for eye in eyes {
            let [x0, z0, x1, z1] = map.extent;
            assert!(
                (x0..=x1).contains(&eye[0]) && (z0..=z1).contains(&eye[1]),
                "{eye:?}"
            );
            assert!(!map.in_building(eye), "{eye:?}");
            assert!(map.building_distance(eye) >= CLEARANCE - 1e-3, "{eye:?}");
        }
    }

    #[test]
    fn views_stand_in_front_of_the_object_outside_the_block_and_look_at_it() {
        let views = object_views(
            Streets::Layout(&layout()),
            1.0,
            &[TEXT],
            &path(ValueRange::Fixed(0.0)),
            4,
        );
        assert_eq!(views.len(), 20);
        for frame in &views {
            // Every eye in front of the wall is free: all attempts survive.
            assert_eq!(frame.len(), ATTEMPTS as usize);
            for v in frame {
                let p = v.pose;
                assert_eq!(v.target, 7);
                let (dx, dz) = (p.eye[0] - 50.0, p.eye[2] - 40.0);
                let d = (dx * dx + dz * dz).sqrt();
                assert!((4.0 - 2e-3..=8.0 + 2e-3).contains(&d), "{p:?}");
                // Within 45° of the front (north, −z).
                assert!(-dz >= d * std::f64::consts::FRAC_1_SQRT_2 - 2e-3, "{p:?}");
                // Aimed straight at the centre: the target is the object's centre.
                let t = p.target;
                assert!(
                    (t[0] - 50.0).abs() < 3e-3 && (t[1] - 3.0).abs() < 3e-3,
                    "{p:?}"
                );
                assert!((t[2] - 40.0).abs() < 3e-3, "{p:?}");
            }
        }
    }

    #[test]
    fn eyes_never_stand_in_a_block_and_aims_turn_off_the_centre() {
        // The same text seen from behind: every bearing puts the eye inside the block.
        let behind = ObjectTarget {
            front: Some([0.0, 1.0]),
            ..TEXT
        };
        let views = object_views(
            Streets::Layout(&layout()),
            1.0,
            &[behind],
            &path(ValueRange::Fixed(0.0)),
            4,
        );
        assert!(views.iter().all(|f| f.is_empty()));
        // A lamp without a front, beside the block: any bearing, never into the block.
        let lamp = ObjectTarget {
            id: 3,
            centre: [50.0, 2.0, 37.0],
            front: None,
        };
        let turned = path(ValueRange::Between([-20.0, 20.0]));
        let views = object_views(Streets::Layout(&layout()), 1.0, &[lamp, TEXT], &turned, 9);
        let mut off_centre = 0;
        for v in views.iter().flatten() {
            let [x, _, z] = v.pose.eye;
            assert!(
                !((39.25..=60.75).contains(&x) && (39.25..=60.75).contains(&z)),
                "{v:?}"
            );
            let heading = v.pose.angles.unwrap().heading;
            assert!((-20.0..=20.0).contains(&heading));
            off_centre += usize::from(heading.abs() > 5.0);
        }
        assert!(off_centre > 20, "{off_centre}");
        assert_eq!(
            views,
            object_views(Streets::Layout(&layout()), 1.0, &[lamp, TEXT], &turned, 9)
        );
        assert!(object_views(Streets::Layout(&layout()), 1.0, &[], &turned, 9).is_empty());
    }

    #[test]
    fn high_objects_are_seen_from_far_enough_back_or_not_at_all() {
        // A plate 12 m up: from 4–8 m away the sight would be 52–69° steep; stepping back
        // to 20° needs 28.6 m, beyond the range, so none of these views exist…
        let high = ObjectTarget {
            centre: [50.0, 12.0, 40.0],
            ..TEXT
        };
        let near = path(ValueRange::Fixed(0.0));
        let views = object_views(Streets::Layout(&layout()), 1.0, &[high], &near, 4);
        assert!(views.iter().all(|f| f.is_empty()));
        // …while a range reaching 35 m gives views, none steeper than 20°.
        let far = ObjectsPath {
            distance: ValueRange::Between([4.0, 35.0]),
            ..near
        };
        let views = object_views(Streets::Layout(&layout()), 1.0, &[high], &far, 4);
        let mut n = 0;
        for v in views.iter().flatten() {
            let p = v.pose;
            let flat = ((p.eye[0] - 50.0).powi(2) + (p.eye[2] - 40.0).powi(2)).sqrt();
            let rise = 12.0 - p.eye[1];
            // Poses are written to the millimetre.
            assert!(
                rise <= flat * libm::tan(MAX_ELEVATION.to_radians()) + 5e-3,
                "{p:?}"
            );
            assert!(flat <= 35.0 + 5e-3);
            n += 1;
        }
        assert!(n > 20, "{n}");
    }
}
