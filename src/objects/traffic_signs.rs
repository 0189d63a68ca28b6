//! Sign specs + strip spots + the crossings' mouths → `sign_NNNN` objects, each a plate shaped like the sign (face
//! and back), its face turned towards the traffic coming along the nearest lane, on a grey
//! `sign_pole_NNNN` of class `pole`: the public datasets (GTSDB, Mapillary, TT100K,
//! Cityscapes) box and mask a sign's plate, and call its pole a pole.

use rand::RngExt;
use rand_pcg::Pcg64;

use std::collections::BTreeMap;

use super::ground_spots::{GroundSpots, Spot};
use super::sign_rules::{self, Mouth, Rule};
use super::{ATTEMPTS, Placing, sign_face};
use crate::model::geometry::{KERB_Y, MeshBuilder, cross, dot, sub};
use crate::model::{Mesh, Texture};
use crate::spec::{ObjectSpec, SignKind};

/// Pole height above the sidewalk, and half its thickness, in metres.
pub const POLE_HEIGHT: f64 = 2.6;
pub const POLE_HALF: f64 = 0.04;
/// Side of the plate's square (the sign's width and height), in metres.
pub const PLATE: f64 = 0.75;
/// The gap between two plates one above the other on a post, metres.
pub const PLATE_GAP: f64 = 0.1;
/// The most plates one above the other on a map's post: more codes are left out.
pub const MAX_LEVELS: u32 = 3;
/// Distance of the face in front of the pole's axis; the back sits 5 mm behind the face.
pub const FACE_OFFSET: f64 = POLE_HALF + 0.015;
/// Room a sign keeps around itself, in metres (from lamps, on top of their clearance).
pub const RADIUS: f64 = 1.0;
/// Numbers a speed-limit sign shows.
pub const SPEEDS: [u32; 8] = [20, 30, 40, 50, 60, 70, 80, 100];

const POLE_GREY: [f32; 3] = [0.45, 0.46, 0.48];
const BACK_GREY: [f32; 3] = [0.6, 0.6, 0.62];

/// Places the entry's signs; returns how many (each is two objects, plate and pole).
///
/// Each sign draws its type from the entry's list and stands where the type's
/// [`Rule`] puts it (stop and yield at the mouths of the roads giving way, speed limits
/// past a crossing, warnings before a zebra crossing, …); a type whose rule finds no room
/// is drawn again, up to [`ATTEMPTS`] times. Signs of one type placed off the mouths keep
/// [`SPACING`] from each other along a road's side.
pub fn place(
    spec: &ObjectSpec,
    rng: &mut Pcg64,
    spots: &mut GroundSpots,
    placing: &mut Placing,
) -> u32 {
    let mut placed = 0;
    let kinds: &[SignKind] = if spec.signs.is_empty() {
        &SignKind::ALL
    } else {
        &spec.signs
    };
    let input = placing.input;
    let mouths = sign_rules::mouths(input.layout, input.metres_per_pixel, input.seed);
    for _ in 0..spec.count {
        let speed = SPEEDS[rng.random_range(0..SPEEDS.len())];
        let found = (0..ATTEMPTS).find_map(|_| {
            let kind = kinds[rng.random_range(0..kinds.len())];
            let spot = spot_for(kind, rng, spots, &mouths, &placing.out.sign_faces)?;
            Some((kind, spot))
        });
        let Some((kind, spot)) = found else {
            continue;
        };
        push_sign(placing, spec, (kind, speed, spot), Post::SINGLE, true);
        placed += 1;
    }
    placed
}

/// Where a plate sits on its post: at `level` (0 the top) of `levels` one above the
/// other. A post of several stands taller by their plates and gaps, so its lowest plate
/// is as high as a single plate on its post.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Post {
    pub level: u32,
    pub levels: u32,
}

impl Post {
    /// A post with one plate.
    pub const SINGLE: Post = Post {
        level: 0,
        levels: 1,
    };

    /// The post's height above the sidewalk, metres.
    pub fn height(self) -> f64 {
        POLE_HEIGHT + f64::from(self.levels.saturating_sub(1)) * (PLATE + PLATE_GAP)
    }

    /// The height of the plate's centre, metres (`y` up).
    pub fn plate_centre_y(self) -> f64 {
        KERB_Y + self.height() - PLATE / 2.0 - f64::from(self.level) * (PLATE + PLATE_GAP)
    }
}

/// A plate the map has: its design, the number on it (a speed limit's) and where it
/// stands, facing the traffic of [`Spot::travel`] (`map_objects::sign_sites`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MappedSign {
    pub kind: SignKind,
    pub speed: u32,
    pub spot: Spot,
    /// Hung on a street lamp's pole (the map's node is both): no pole of its own, and the
    /// lamp holds the ground.
    pub on_lamp: bool,
    /// Its place on the post.
    pub post: Post,
    /// On the post of the plate before it in the list (the same node's next code).
    pub stacked: bool,
}

/// The ground a mapped sign holds, radius in metres: half its plate. Mapped posts stand
/// where the map has them, closer together than [`RADIUS`] keeps a layout's.
pub const MAPPED_RADIUS: f64 = PLATE / 2.0;

/// Places the map's plates, in node order, up to the entry's `count`: each of a type the
/// entry's `signs` lists (any when empty) on a post whose ground `claim` grants (asked
/// once a post, at its first plate of such a type; a post on a lamp claims none).
/// Returns how many plates.
pub fn place_mapped(
    spec: &ObjectSpec,
    signs: &[MappedSign],
    claim: &mut dyn FnMut(super::ground_spots::Footprint) -> bool,
    placing: &mut Placing,
) -> u32 {
    let mut placed = 0;
    // Whether the current post stands: None before its first plate of a listed type.
    let mut stands: Option<bool> = None;
    for sign in signs {
        if placed >= spec.count {
            break;
        }
        if !sign.stacked {
            stands = None;
        }
        if !(spec.signs.is_empty() || spec.signs.contains(&sign.kind)) {
            continue;
        }
        let own_pole = match stands {
            Some(false) => continue,
            Some(true) => false,
            None => {
                let ground =
                    super::ground_spots::Footprint::Circle(sign.spot.position, MAPPED_RADIUS);
                let granted = sign.on_lamp || claim(ground);
                stands = Some(granted);
                if !granted {
                    continue;
                }
                !sign.on_lamp
            }
        };
        push_sign(
            placing,
            spec,
            (sign.kind, sign.speed, sign.spot),
            sign.post,
            own_pole,
        );
        placed += 1;
    }
    placed
}

/// Metres a sign placed off the mouths keeps from one of its type on the same side of
/// the same road.
pub const SPACING: f64 = 40.0;

/// A spot for a sign of `kind` by its rule, taken from `spots`; None when its rule finds
/// no room (every mouth of its kind signed, the strip taken, another of its type within
/// [`SPACING`]).
fn spot_for(
    kind: SignKind,
    rng: &mut Pcg64,
    spots: &mut GroundSpots,
    mouths: &[Mouth],
    faces: &BTreeMap<usize, SignFace>,
) -> Option<Spot> {
    let spot = match sign_rules::rule(kind) {
        Rule::Mouth(priority) => {
            let fits = |m: &Mouth| m.priority == priority && !signed(faces, m, MOUTH_KINDS);
            return mouth_spots(rng, mouths, fits, spots, |m| {
                [0.5, 1.5, 2.5, 3.5, 4.5, 5.5].map(|back| m.before(back))
            });
        }
        Rule::Zebra => {
            let fits = |m: &Mouth| !signed(faces, m, &[kind]);
            return mouth_spots(rng, mouths, fits, spots, |m| {
                [0.5, 0.3, 0.7, 0.1].map(|t| m.zebra[0] + t * (m.zebra[1] - m.zebra[0]))
            });
        }
        Rule::Before([lo, hi], priority) => {
            let candidates: Vec<&Mouth> = mouths
                .iter()
                .filter(|m| priority.is_none_or(|p| m.priority == p))
                .collect();
            let m = candidates.get(rng.random_range(0..candidates.len().max(1)))?;
            let along = m.before(lo + rng.random::<f64>() * (hi - lo));
            spots.strip_beside(m.road, m.in_high(), along, RADIUS)?
        }
        Rule::After([lo, hi]) => {
            let m = mouths.get(rng.random_range(0..mouths.len().max(1)))?;
            // Past the zebra, on the side of the traffic leaving the crossing.
            let along = m.before(lo + rng.random::<f64>() * (hi - lo));
            spots.strip_beside(m.road, !m.in_high(), along, RADIUS)?
        }
        Rule::Free => spots.strip(rng, RADIUS, ATTEMPTS)?,
    };
    let close = faces.values().any(|f| {
        let (dx, dz) = (
            f.centre[0] - spot.position[0],
            f.centre[2] - spot.position[1],
        );
        let d = (dx * dx + dz * dz).sqrt();
        f.kind == kind && f.road == spot.road && faces_travel(f, spot.travel) && d < SPACING
    });
    if close {
        spots.release(spot);
        return None;
    }
    Some(spot)
}

/// The types that sign a mouth's priority: at most one of them a mouth.
const MOUTH_KINDS: &[SignKind] = &[SignKind::Stop, SignKind::Yield, SignKind::PriorityRoad];

/// Whether a sign of one of `kinds` already stands at mouth `m` (beside its zebra or stop
/// line, facing its traffic).
fn signed(faces: &BTreeMap<usize, SignFace>, m: &Mouth, kinds: &[SignKind]) -> bool {
    let travel = super::ground_spots::travel(m.axis, m.in_high());
    faces.values().any(|f| {
        let along = match m.axis {
            crate::model::Axis::Horizontal => f.centre[0],
            crate::model::Axis::Vertical => f.centre[2],
        };
        kinds.contains(&f.kind)
            && f.road == m.road
            && faces_travel(f, travel)
            && (along - m.stop).abs() < 8.0
    })
}

/// Whether face `f` looks at traffic running along `travel`.
fn faces_travel(f: &SignFace, travel: [f64; 2]) -> bool {
    f.normal[0] * -travel[0] + f.normal[2] * -travel[1] > 0.99
}

/// The first mouth (from a random one on, in order) for which `fits` holds and one of the
/// along-axis places `at` gives is a free strip spot on its traffic's side.
fn mouth_spots<const N: usize>(
    rng: &mut Pcg64,
    mouths: &[Mouth],
    fits: impl Fn(&Mouth) -> bool,
    spots: &mut GroundSpots,
    at: impl Fn(&Mouth) -> [f64; N],
) -> Option<Spot> {
    let start = rng.random_range(0..mouths.len().max(1));
    (0..mouths.len())
        .map(|k| &mouths[(start + k) % mouths.len()])
        .filter(|m| fits(m))
        .find_map(|m| {
            at(m)
                .into_iter()
                .find_map(|along| spots.strip_beside(m.road, m.in_high(), along, RADIUS))
        })
}

/// Pushes a sign of `kind` (showing `speed` where it is a limit) standing at `spot`, at
/// its place on the `post`: its pole where it brings one (`own_pole`; else it hangs on a
/// lamp's or its post's), then its plate, its face looking at the traffic coming
/// towards it; and records its face.
fn push_sign(
    placing: &mut Placing,
    spec: &ObjectSpec,
    (kind, speed, spot): (SignKind, u32, Spot),
    post: Post,
    own_pole: bool,
) {
    // The face looks against the traffic: at the drivers coming towards it.
    let facing = [-spot.travel[0], -spot.travel[1]];
    let face_name = match kind {
        SignKind::SpeedLimit => format!("sign_speed_limit_{speed}"),
        other => format!("sign_{}", other.name()),
    };
    let face = placing.material(&face_name, || {
        let image = sign_face::draw(kind, speed);
        ([1.0; 3], Some(Texture::from_rgb(face_name.clone(), image)))
    });
    let pole = placing.material("sign_pole", || (POLE_GREY, None));
    let back = placing.material("sign_back", || (BACK_GREY, None));
    let [pole_mesh, face, back] =
        sign_meshes(kind, (spot.position, post), facing, [pole, face, back]);
    if own_pole {
        let name = placing.name("sign_pole");
        placing.push_plain(
            crate::model::ObjectKind::SignPole,
            name,
            "pole",
            vec![pole_mesh],
        );
    }
    let name = placing.name("sign");
    placing.push_plain(
        crate::model::ObjectKind::Sign,
        name,
        &spec.label,
        vec![face, back],
    );
    let index = placing.out.objects.len() - 1;
    let centre = [
        spot.position[0] + facing[0] * FACE_OFFSET,
        post.plate_centre_y(),
        spot.position[1] + facing[1] * FACE_OFFSET,
    ];
    let normal = [facing[0], 0.0, facing[1]];
    placing.out.sign_faces.insert(
        index,
        SignFace {
            kind,
            centre,
            normal,
            road: spot.road,
        },
    );
}

/// Where a sign's face is and which way it looks, so annotations can tell its front from
/// its blank back.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SignFace {
    pub kind: SignKind,
    /// Centre of the face, world metres.
    pub centre: [f64; 3],
    /// Unit normal out of the face (horizontal).
    pub normal: [f64; 3],
    /// The road whose traffic it faces.
    pub road: u32,
}

/// Pole, face and back of a sign standing at `foot` (x, z), its plate at its place on
/// `post`, its face towards `facing`.
pub fn sign_meshes(
    kind: SignKind,
    (foot, post): ([f64; 2], Post),
    facing: [f64; 2],
    materials: [u32; 3],
) -> [Mesh; 3] {
    let [pole_m, face_m, back_m] = materials;
    let mut pole = MeshBuilder::new(pole_m);
    pole.oriented_box(
        [foot[0], KERB_Y, foot[1]],
        facing,
        [POLE_HALF, POLE_HALF],
        post.height(),
    );
    let ring = sign_face::outline(kind);
    let centre_y = post.plate_centre_y();
    // Seen from the front, "right" is (-facing) × up.
    let right = [facing[1], -facing[0]];
    let at = |uv: [f64; 2], out: f64| {
        [
            foot[0] + right[0] * (uv[0] - 0.5) * PLATE + facing[0] * out,
            centre_y + (0.5 - uv[1]) * PLATE,
            foot[1] + right[1] * (uv[0] - 0.5) * PLATE + facing[1] * out,
        ]
    };
    let front_normal = [facing[0], 0.0, facing[1]];
    let face = fan(face_m, &ring, |uv| at(uv, FACE_OFFSET), front_normal, true);
    let back_normal = [-facing[0], 0.0, -facing[1]];
    let back = fan(
        back_m,
        &ring,
        |uv| at(uv, FACE_OFFSET - 0.005),
        back_normal,
        false,
    );
    [pole.finish(), face, back]
}

/// A convex polygon as a triangle fan around its centre, wound towards `normal`; uv from
/// the outline when `textured`, else zero.
fn fan(
    material: u32,
    ring: &[[f64; 2]],
    at: impl Fn([f64; 2]) -> [f64; 3],
    normal: [f64; 3],
    textured: bool,
) -> Mesh {
    let mut mesh = Mesh {
        material,
        ..Mesh::default()
    };
    let centre = [0.5, 0.5];
    // Placed before `push(centre)`: rustc 1.95 at opt-level 1 (our test profile) let the
    // pushes clobber `centre` when `at(centre)` was called after them, winding some
    // triangles the wrong way in test builds only (release was right).
    let middle = at(centre);
    let mut push = |uv: [f64; 2]| {
        let p = at(uv);
        mesh.positions.push(p.map(|v| v as f32));
        mesh.normals.push(normal.map(|v| v as f32));
        let uv = if textured { uv } else { [0.0, 0.0] };
        mesh.uvs.push([uv[0] as f32, uv[1] as f32]);
    };
    push(centre);
    for &uv in ring {
        push(uv);
    }
    let n = ring.len() as u32;
    for i in 0..n {
        let (a, b) = (1 + i, 1 + (i + 1) % n);
        let pa = at(ring[i as usize]);
        let pb = at(ring[((i + 1) % n) as usize]);
        let towards = dot(cross(sub(pa, middle), sub(pb, middle)), normal) >= 0.0;
        if towards {
            mesh.indices.extend_from_slice(&[0, a, b]);
        } else {
            mesh.indices.extend_from_slice(&[0, b, a]);
        }
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::geometry::normalize;

    /// Every triangle of a sign's face and back turns its front the way its vertex normals
    /// point (a wrong winding showed only in the exported OBJ and GLB: the renderer turns
    /// such triangles round).
    #[test]
    fn face_and_back_are_wound_towards_their_normals() {
        let inv = std::f64::consts::FRAC_1_SQRT_2;
        for kind in SignKind::ALL {
            for facing in [[0.0, 1.0], [-1.0, 0.0], [inv, -inv]] {
                let meshes = sign_meshes(kind, ([92.0, 114.7], Post::SINGLE), facing, [0, 1, 2]);
                for mesh in &meshes[1..] {
                    for t in mesh.indices.chunks_exact(3) {
                        let p = |i: u32| mesh.positions[i as usize].map(f64::from);
                        let n = normalize(cross(sub(p(t[1]), p(t[0])), sub(p(t[2]), p(t[0]))))
                            .expect("no degenerate triangle");
                        let stored = mesh.normals[t[0] as usize].map(f64::from);
                        assert!(
                            dot(n, stored) > 0.99,
                            "{kind:?} facing {facing:?}, material {}: {t:?}",
                            mesh.material
                        );
                    }
                }
            }
        }
    }
}
