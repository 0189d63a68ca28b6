//! Tree specs + strip spots and open block paving → `tree_NNNN` objects: a hexagonal trunk
//! and a solid low-poly crown of one of four species, seeded in size, shape and shade.
//!
//! | species | crown | triangles |
//! |---|---|---|
//! | round | a ball and two smaller lobes | ~108 |
//! | columnar | two tall lobes stacked | ~76 |
//! | conifer | three stacked octagonal cones | ~60 |
//! | spreading | three wide, flat lobes | ~108 |
//!
//! Lobes are subdivided octahedra (32 faces) whose corners are pushed in or out at random,
//! so no two crowns are alike. A `plazas` share of the trees stands on the blocks' open
//! paving, clear of every building by its crown, taking a circle as wide as the crown
//! ([`super::ground_spots::Footprint::Circle`]). The rest line the streets:
//!
//! - a broadleaf tree whose crown can stay [`CLEAR_HEIGHT`] above the ground stands
//!   [`CURB_SETBACK`] from the curb, as street trees do, and its crown (up to
//!   [`MAX_STREET_CROWN`]) reaches over the parking lane, high above cars, vans and buses,
//!   never past the strip's far side; it takes a [`TRUNK_ROOM`] circle of ground, and its
//!   crown keeps clear of the lamps' arms and of other crowns;
//! - any other (conifers, small or young trees) stands mid-strip, its crown inside the
//!   strip, taking a circle as wide as the crown.
//!
//! So trees never overlap lamps, signs, cars, benches or each other.

use rand::RngExt;
use rand_pcg::Pcg64;

use super::footprint_grid::FootprintGrid;
use super::ground_spots::{Footprint, GRID_CELL, GroundSpots};
use super::vehicle_parts::{Solid, finish_all};
use super::{ATTEMPTS, GIVE_UP, Placing, trig};
use crate::model::Mesh;
use crate::model::geometry::KERB_Y;
use crate::spec::{ObjectSpec, TreeSpecies};

/// Largest crown radius on open paving, metres.
pub const MAX_PLAZA_CROWN: f64 = 3.5;
/// Room a plaza tree's crown keeps from a building, metres.
pub const BUILDING_CLEARANCE: f64 = 0.3;
/// Draws of a tree tried before one is left out.
pub const REDRAWS: u32 = 4;
/// Lowest a crown reaching over the road may hang, metres above the sidewalk: over a bus.
pub const CLEAR_HEIGHT: f64 = 4.5;
/// Distance of a curbside tree's trunk from the curb, metres.
pub const CURB_SETBACK: f64 = 1.0;
/// Largest crown radius of a curbside tree, metres.
pub const MAX_STREET_CROWN: f64 = 3.3;
/// Ground a curbside tree's trunk takes (its tree pit), radius in metres.
pub const TRUNK_ROOM: f64 = 0.6;
/// Room a curbside crown keeps from a lamp's pole (its arm runs over the road), metres.
pub const LAMP_ROOM: f64 = 0.6;

const BARK: [f32; 3] = [0.08, 0.055, 0.035];
/// Three leaf shades per species (linear RGB), in [`TreeSpecies::ALL`] order.
const LEAVES: [[[f32; 3]; 3]; 4] = [
    [[0.05, 0.12, 0.025], [0.07, 0.15, 0.03], [0.04, 0.09, 0.02]],
    [[0.08, 0.15, 0.03], [0.06, 0.13, 0.035], [0.1, 0.17, 0.04]],
    [
        [0.015, 0.05, 0.025],
        [0.02, 0.065, 0.03],
        [0.012, 0.04, 0.02],
    ],
    [[0.1, 0.14, 0.03], [0.13, 0.15, 0.035], [0.08, 0.12, 0.03]],
];

// Long on purpose: one placement loop, whose random draws must stay in this order (each
// changes every later object's); split, the order would be spread over functions.
pub fn place(spec: &ObjectSpec, rng: &mut Pcg64, spots: &mut GroundSpots, placing: &mut Placing) {
    let species: &[TreeSpecies] = if spec.species.is_empty() {
        &TreeSpecies::ALL
    } else {
        &spec.species
    };
    let strip_crown = spots.strip_half() - 0.15;
    // The far side of the strip bounds a curbside crown as well.
    let street_crown = MAX_STREET_CROWN.min(2.0 * spots.strip_half() - CURB_SETBACK - 0.15);
    let mpp = placing.input.metres_per_pixel;
    // Lamps (with the room a crown keeps from them as their radius), and the crowns of this
    // entry's curbside trees.
    let mut lamps = FootprintGrid::new(GRID_CELL);
    for l in placing.input.lamps {
        lamps.push(Footprint::Circle(
            [l.position[0] * mpp, l.position[1] * mpp],
            LAMP_ROOM,
        ));
    }
    let mut canopies = FootprintGrid::new(GRID_CELL);
    // The buildings, for trees on the blocks' paving: made for the first plaza tree.
    let mut buildings = None;
    let mut misses = 0;
    for _ in 0..spec.count {
        if misses >= GIVE_UP {
            break;
        }
        // A tree that finds no room is drawn again (species, height, strip or plaza) up to
        // REDRAWS times: the strips' room bounds `count`, not the first draw's luck.
        misses += 1;
        for _ in 0..REDRAWS {
            let kind = species[rng.random_range(0..species.len())];
            let t: f64 = rng.random();
            let [low, high] = spec.height_range();
            let height = low + t * (high - low);
            let shade = rng.random_range(0..3usize);
            let in_plaza = rng.random::<f64>() < spec.plazas;
            let kerbside = crown_radius(kind, height)
                .min(street_crown)
                .min(clear_crown(kind, height));
            let curbside = !in_plaza && kerbside > strip_crown;
            let max_crown = if in_plaza {
                MAX_PLAZA_CROWN
            } else if curbside {
                kerbside
            } else {
                strip_crown
            };
            if max_crown.is_nan() || max_crown <= 0.5 {
                continue;
            }
            let crown = crown_radius(kind, height).min(max_crown);
            let foot = if in_plaza {
                let buildings = buildings.get_or_insert_with(|| building_grid(placing));
                plaza_spot(rng, crown, spots, buildings, placing)
            } else if curbside {
                (0..ATTEMPTS).find_map(|_| {
                    let spot = spots.strip_at(rng, TRUNK_ROOM, CURB_SETBACK, 1)?;
                    let p = spot.position;
                    // Far enough: at least the two radii together apart.
                    let far = |f: &Footprint| {
                        let &Footprint::Circle(q, r) = f else {
                            return true;
                        };
                        let (dx, dz) = (p[0] - q[0], p[1] - q[1]);
                        let room = crown + r;
                        dx * dx + dz * dz >= room * room
                    };
                    let probe = Footprint::Circle(p, crown);
                    let free = lamps.all_near(&probe, far) && canopies.all_near(&probe, far);
                    if free {
                        canopies.push(probe);
                        Some(p)
                    } else {
                        spots.release(spot);
                        None
                    }
                })
            } else {
                spots.strip(rng, crown + 0.1, ATTEMPTS).map(|s| s.position)
            };
            let Some(foot) = foot else {
                continue;
            };
            let k = TreeSpecies::ALL
                .iter()
                .position(|&s| s == kind)
                .unwrap_or(0);
            let leaves = placing.material(&format!("tree_leaves_{k}_{shade}"), || {
                (LEAVES[k][shade], None)
            });
            let bark = placing.material("tree_bark", || (BARK, None));
            let meshes = tree_meshes(kind, height, crown, [foot[0], foot[1]], rng, [bark, leaves]);
            let name = placing.name("tree");
            let species = Some(("species", kind.name().to_owned()));
            let tree = crate::model::ObjectKind::Tree;
            placing.push_variant(tree, name, &spec.label, meshes, species);
            misses = 0;
            break;
        }
    }
}

/// The largest crown radius a tree of `kind` and `height` may have with its crown's lowest
/// point at least [`CLEAR_HEIGHT`] up (from the lobe layout in [`tree_meshes`]); 0 when
/// none does (conifers reach down to a fifth of their height, columnar crowns to 0.28).
fn clear_crown(kind: TreeSpecies, height: f64) -> f64 {
    let h = height;
    let room = h - CLEAR_HEIGHT;
    match kind {
        // Lowest point h − 1.85·ry with ry = min(0.95 r, 0.45 h).
        TreeSpecies::Round if h - 1.85 * 0.45 * h < CLEAR_HEIGHT => (room / (1.85 * 0.95)).max(0.0),
        TreeSpecies::Round => f64::INFINITY,
        // Lowest point h − 2·ry with ry = min(0.45 r, 0.3 h).
        TreeSpecies::Spreading if h - 2.0 * 0.3 * h < CLEAR_HEIGHT => (room / 0.9).max(0.0),
        TreeSpecies::Spreading => f64::INFINITY,
        TreeSpecies::Columnar | TreeSpecies::Conifer => 0.0,
    }
}

/// The crown radius a tree of `height` metres has, before any limit.
fn crown_radius(kind: TreeSpecies, height: f64) -> f64 {
    height
        * match kind {
            TreeSpecies::Round => 0.3,
            TreeSpecies::Columnar => 0.15,
            TreeSpecies::Conifer => 0.22,
            TreeSpecies::Spreading => 0.42,
        }
}

/// A random point on a block's paving, `crown + BUILDING_CLEARANCE` clear of every
/// building, whose circle of `crown` is free; it is taken.
fn plaza_spot(
    rng: &mut Pcg64,
    crown: f64,
    spots: &mut GroundSpots,
    buildings: &FootprintGrid,
    placing: &Placing,
) -> Option<[f64; 2]> {
    let input = placing.input;
    let blocks = &input.layout.blocks;
    let mpp = input.metres_per_pixel;
    if blocks.is_empty() {
        return None;
    }
    (0..ATTEMPTS).find_map(|_| {
        let block = &blocks[rng.random_range(0..blocks.len())];
        let (tx, ty): (f64, f64) = (rng.random(), rng.random());
        let b = block.bbox;
        let px = [
            f64::from(b.x0) + tx * f64::from(b.x1 - b.x0),
            f64::from(b.y0) + ty * f64::from(b.y1 - b.y0),
        ];
        // `as` saturates; the pixel test bounds it.
        if !block.contains_pixel(px[0] as u32, px[1] as u32) {
            return None;
        }
        let p = [px[0] * mpp, px[1] * mpp];
        let room = crown + BUILDING_CLEARANCE;
        // Far enough: `room` from the building.
        let far = |f: &Footprint| {
            let &Footprint::Rect(x, z) = f else {
                return true;
            };
            let dx = p[0] - p[0].clamp(x[0], x[1]);
            let dz = p[1] - p[1].clamp(z[0], z[1]);
            dx * dx + dz * dz >= room * room
        };
        let clear = buildings.all_near(&Footprint::Circle(p, room), far);
        (clear && spots.claim(Footprint::Circle(p, crown + 0.1))).then_some(p)
    })
}

/// The buildings' footprints, metres.
fn building_grid(placing: &Placing) -> FootprintGrid {
    let mpp = placing.input.metres_per_pixel;
    let mut grid = FootprintGrid::new(GRID_CELL);
    for building in placing.input.buildings {
        let f = building.footprint;
        grid.push(Footprint::Rect(
            [f64::from(f.x0) * mpp, f64::from(f.x1) * mpp],
            [f64::from(f.y0) * mpp, f64::from(f.y1) * mpp],
        ));
    }
    grid
}

/// Trunk and crown of a tree standing at `foot` (x, z) on the kerb-high paving.
fn tree_meshes(
    kind: TreeSpecies,
    height: f64,
    crown: f64,
    foot: [f64; 2],
    rng: &mut Pcg64,
    [bark, leaves]: [u32; 2],
) -> Vec<Mesh> {
    let mut trunk = Solid::new(bark);
    let mut crowns = Solid::new(leaves);
    let base = [foot[0], KERB_Y, foot[1]];
    let h = height;
    let r = crown;
    // Lobes: (centre offset (x, y, z) from the foot, radii (across, up)).
    let mut lobes: Vec<([f64; 3], [f64; 2])> = Vec::new();
    let turn: f64 = rng.random::<f64>() * 360.0;
    let (c, s) = trig::cos_sin_deg(turn);
    let trunk_top = match kind {
        TreeSpecies::Round => {
            let ry = (0.95 * r).min(0.45 * h);
            lobes.push(([0.0, h - ry, 0.0], [r * 0.85, ry * 0.85]));
            lobes.push((
                [0.35 * r * c, h - 1.2 * ry, 0.35 * r * s],
                [r * 0.62, ry * 0.6],
            ));
            lobes.push((
                [-0.35 * r * c, h - 1.1 * ry, -0.35 * r * s],
                [r * 0.62, ry * 0.6],
            ));
            h - ry
        }
        TreeSpecies::Columnar => {
            let ry = 0.24 * h;
            lobes.push(([0.0, h - ry, 0.0], [r * 0.9, ry]));
            lobes.push(([0.0, h - 2.1 * ry, 0.0], [r, ry * 0.9]));
            h - ry
        }
        TreeSpecies::Conifer => {
            for (k, (b, a, w)) in [(0.18, 0.6, 1.0), (0.4, 0.82, 0.75), (0.62, 1.0, 0.5)]
                .into_iter()
                .enumerate()
            {
                cone(
                    &mut crowns,
                    [base[0], base[1] + b * h, base[2]],
                    a * h - b * h,
                    w * r,
                    turn + 15.0 * k as f64,
                );
            }
            0.5 * h
        }
        TreeSpecies::Spreading => {
            let ry = (0.45 * r).min(0.3 * h);
            lobes.push(([0.0, h - ry, 0.0], [r * 0.7, ry]));
            lobes.push((
                [0.4 * r * c, h - 1.2 * ry, 0.4 * r * s],
                [r * 0.6, ry * 0.8],
            ));
            lobes.push((
                [-0.4 * r * c, h - 1.2 * ry, -0.4 * r * s],
                [r * 0.6, ry * 0.8],
            ));
            h - ry
        }
    };
    for (offset, radii) in lobes {
        let centre = [
            base[0] + offset[0],
            base[1] + offset[1],
            base[2] + offset[2],
        ];
        blob(&mut crowns, centre, radii, rng);
    }
    let trunk_radius = 0.08 + 0.012 * h;
    hexagonal_trunk(&mut trunk, base, trunk_radius, trunk_top, turn);
    finish_all(vec![trunk, crowns])
}

/// A subdivided octahedron (32 faces) of radii `[across, up]` around `centre`, each corner
/// pushed out or in by up to 15 %; every face looks away from the centre. Lobe radii are
/// chosen so the jittered crown stays within the tree's crown radius.
fn blob(solid: &mut Solid, centre: [f64; 3], radii: [f64; 2], rng: &mut Pcg64) {
    let (points, faces) = geosphere();
    let scale: Vec<f64> = points
        .iter()
        .map(|_| 0.85 + 0.15 * rng.random::<f64>())
        .collect();
    let at = |i: usize| {
        let p = points[i];
        let k = scale[i];
        [
            centre[0] + p[0] * radii[0] * k,
            centre[1] + p[1] * radii[1] * k,
            centre[2] + p[2] * radii[0] * k,
        ]
    };
    for [a, b, c] in faces {
        solid.triangle_out([at(a), at(b), at(c)], centre);
    }
}

/// Unit directions and faces of an octahedron subdivided once: 18 corners, 32 faces.
fn geosphere() -> (Vec<[f64; 3]>, Vec<[usize; 3]>) {
    let mut points: Vec<[f64; 3]> = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let octa = [
        [0, 2, 4],
        [4, 2, 1],
        [1, 2, 5],
        [5, 2, 0],
        [0, 4, 3],
        [4, 1, 3],
        [1, 5, 3],
        [5, 0, 3],
    ];
    let mid = |a: usize, b: usize, points: &mut Vec<[f64; 3]>| {
        let (p, q) = (points[a], points[b]);
        let m = [
            (p[0] + q[0]) / 2.0,
            (p[1] + q[1]) / 2.0,
            (p[2] + q[2]) / 2.0,
        ];
        let len = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
        let m = m.map(|v| v / len);
        if let Some(i) = points.iter().position(|&x| x == m) {
            return i;
        }
        points.push(m);
        points.len() - 1
    };
    let mut faces = Vec::new();
    for [a, b, c] in octa {
        let ab = mid(a, b, &mut points);
        let bc = mid(b, c, &mut points);
        let ca = mid(c, a, &mut points);
        faces.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    (points, faces)
}

/// An octagonal cone: base circle of `radius` at `base`, apex `height` above, and its base.
fn cone(solid: &mut Solid, base: [f64; 3], height: f64, radius: f64, turn: f64) {
    let ring: Vec<[f64; 3]> = (0..8)
        .map(|k| {
            let (c, s) = trig::cos_sin_deg(turn + 45.0 * f64::from(k));
            [base[0] + radius * c, base[1], base[2] + radius * s]
        })
        .collect();
    let apex = [base[0], base[1] + height, base[2]];
    let inside = [base[0], base[1] + height / 3.0, base[2]];
    for k in 0..8 {
        solid.triangle_out([ring[k], ring[(k + 1) % 8], apex], inside);
    }
    solid.polygon(&ring, [0.0, -1.0, 0.0]);
}

/// A six-sided trunk from `base` up to `top` (absolute height above the paving), no caps.
fn hexagonal_trunk(solid: &mut Solid, base: [f64; 3], radius: f64, top: f64, turn: f64) {
    let ring: Vec<[f64; 2]> = (0..6)
        .map(|k| {
            let (c, s) = trig::cos_sin_deg(turn + 60.0 * f64::from(k));
            [base[0] + radius * c, base[2] + radius * s]
        })
        .collect();
    let y = [base[1], base[1] + top];
    for k in 0..6 {
        let (a, b) = (ring[k], ring[(k + 1) % 6]);
        let mid = [(a[0] + b[0]) / 2.0 - base[0], (a[1] + b[1]) / 2.0 - base[2]];
        let len = (mid[0] * mid[0] + mid[1] * mid[1]).sqrt();
        let normal = [mid[0] / len, 0.0, mid[1] / len];
        let corners = [
            [a[0], y[0], a[1]],
            [b[0], y[0], b[1]],
            [b[0], y[1], b[1]],
            [a[0], y[1], a[1]],
        ];
        solid.polygon(&corners, normal);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::stream;

    #[test]
    fn geosphere_is_closed() {
        let (points, faces) = geosphere();
        assert_eq!((points.len(), faces.len()), (18, 32));
        // Closed: every edge is shared by exactly two faces.
        let mut edges = std::collections::BTreeMap::new();
        for f in &faces {
            for k in 0..3 {
                let (a, b) = (f[k].min(f[(k + 1) % 3]), f[k].max(f[(k + 1) % 3]));
                *edges.entry((a, b)).or_insert(0) += 1;
            }
        }
        assert!(edges.values().all(|&n| n == 2));
    }

    #[test]
    fn trees_are_low_poly_and_stay_within_their_crown() {
        let mut rng = stream(3, "tree-test", 0);
        for kind in TreeSpecies::ALL {
            for height in [5.0, 10.0] {
                let crown = crown_radius(kind, height).min(2.25);
                let meshes = tree_meshes(kind, height, crown, [10.0, 20.0], &mut rng, [0, 1]);
                let triangles: usize = meshes.iter().map(|m| m.indices.len() / 3).sum();
                assert!((50..=150).contains(&triangles), "{kind:?}: {triangles}");
                for p in meshes.iter().flat_map(|m| &m.positions) {
                    let p = p.map(f64::from);
                    let (dx, dz) = (p[0] - 10.0, p[2] - 20.0);
                    assert!((dx * dx + dz * dz).sqrt() <= crown + 1e-6, "{kind:?} {p:?}");
                    assert!(
                        p[1] >= KERB_Y && p[1] <= KERB_Y + height + 1e-6,
                        "{kind:?} {p:?}"
                    );
                }
            }
        }
    }
}
