//! Tree specs + strip spots and open block paving → `tree_NNNN` objects: a hexagonal trunk
//! and a solid low-poly crown of one of seven species, seeded in size, shape and shades.
//!
//! | species | crown | triangles |
//! |---|---|---|
//! | round (lime) | a ball and two to four smaller lobes round it | 108–172 |
//! | columnar (poplar) | three tall lobes stacked, a little off the trunk | 108 |
//! | conifer (spruce) | four or five ragged tiers with drooping rims, narrowing up, and a tip | 172–204 |
//! | spreading (plane) | a flat middle lobe and four or five wide ones round it | 172–204 |
//! | birch | a thin white trunk under a loose top lobe and four or five small ones | 172–204 |
//! | weeping (willow) | a dome and four or five tall lobes hanging round it (to 0.27 h when wide) | 172–204 |
//! | pine | a tall bare rust trunk under a flat tip and three or four flat clumps | 140–172 |
//!
//! Lobes are subdivided octahedra (32 faces) whose corners are pulled in at random, so no
//! two crowns are alike; each tree takes two of its species' four leaf shades, one for its
//! main lobes and one for some of the others. A `plazas` share of the trees stands on the blocks' open
//! paving, clear of every building by its crown, taking a circle as wide as the crown
//! ([`super::ground_spots::Footprint::Circle`]). The rest line the streets:
//!
//! - a broadleaf tree whose crown can stay [`CLEAR_HEIGHT`] above the ground stands
//!   [`CURB_SETBACK`] from the curb, as street trees do, and its crown (up to
//!   [`MAX_STREET_CROWN`]) reaches over the parking lane, high above cars, vans and buses,
//!   never past the strip's far side; it takes a [`TRUNK_ROOM`] circle of ground, and its
//!   crown keeps clear of the lamps' arms and of other crowns;
//! - any other (conifers, columnar crowns, small or young trees) stands mid-strip, its crown inside the
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

/// Bark per species (linear RGB), in [`TreeSpecies::ALL`] order: brown, a plane's grey,
/// a birch's white, a pine's rust.
const BARK: [[f32; 3]; 7] = [
    [0.08, 0.055, 0.035],
    [0.07, 0.05, 0.035],
    [0.06, 0.045, 0.03],
    [0.16, 0.14, 0.1],
    [0.55, 0.55, 0.5],
    [0.07, 0.055, 0.04],
    [0.22, 0.09, 0.04],
];
/// Four leaf shades per species (linear RGB), in [`TreeSpecies::ALL`] order; a tree takes
/// two of its species' shades, one for its main lobes and one for the others.
const LEAVES: [[[f32; 3]; 4]; 7] = [
    // Round (lime): mid greens, one yellowish.
    [
        [0.05, 0.12, 0.025],
        [0.07, 0.15, 0.03],
        [0.04, 0.09, 0.02],
        [0.1, 0.15, 0.03],
    ],
    // Columnar (poplar).
    [
        [0.08, 0.15, 0.03],
        [0.06, 0.13, 0.035],
        [0.1, 0.17, 0.04],
        [0.07, 0.11, 0.03],
    ],
    // Conifer (spruce): dark, one bluish.
    [
        [0.015, 0.05, 0.025],
        [0.02, 0.065, 0.03],
        [0.012, 0.04, 0.02],
        [0.02, 0.055, 0.045],
    ],
    // Spreading (plane).
    [
        [0.1, 0.14, 0.03],
        [0.13, 0.15, 0.035],
        [0.08, 0.12, 0.03],
        [0.11, 0.16, 0.05],
    ],
    // Birch: light yellow-green.
    [
        [0.14, 0.2, 0.04],
        [0.11, 0.18, 0.035],
        [0.17, 0.21, 0.05],
        [0.12, 0.16, 0.03],
    ],
    // Weeping (willow): silvery yellow-green.
    [
        [0.12, 0.17, 0.06],
        [0.1, 0.15, 0.05],
        [0.14, 0.18, 0.07],
        [0.09, 0.13, 0.04],
    ],
    // Pine: dark, greyish.
    [
        [0.03, 0.06, 0.025],
        [0.04, 0.075, 0.03],
        [0.025, 0.05, 0.02],
        [0.035, 0.065, 0.035],
    ],
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
        // A tree that finds no room is drawn again (height, strip or plaza) up to REDRAWS
        // times: the strips' room bounds `count`, not the first draw's luck. Its species
        // stays: redrawn, the species that fit more easily (mid-strip conifers) would
        // crowd out the rest.
        misses += 1;
        let kind = species[rng.random_range(0..species.len())];
        for _ in 0..REDRAWS {
            let (height, shades) = draw_size(spec, rng);
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
            let tree = Tree {
                kind,
                height,
                crown,
                shades,
            };
            push_tree(placing, &spec.label, &tree, foot, rng);
            misses = 0;
            break;
        }
    }
}

/// A tree as drawn: species, height and crown radius in metres, its two leaf shades.
struct Tree {
    kind: TreeSpecies,
    height: f64,
    crown: f64,
    shades: [usize; 2],
}

/// A tree's height (from `spec.height`) and its two leaf shades, drawn from `rng` in
/// that order.
fn draw_size(spec: &ObjectSpec, rng: &mut Pcg64) -> (f64, [usize; 2]) {
    let t: f64 = rng.random();
    let [low, high] = spec.height_range();
    let shade = rng.random_range(0..4usize);
    let other = (shade + rng.random_range(1..4usize)) % 4;
    (low + t * (high - low), [shade, other])
}

/// Pushes `tree` standing at `foot`, of class `label`; its crown's shape is drawn from
/// `rng`.
fn push_tree(placing: &mut Placing, label: &str, tree: &Tree, foot: [f64; 2], rng: &mut Pcg64) {
    let k = TreeSpecies::ALL
        .iter()
        .position(|&s| s == tree.kind)
        .unwrap_or(0);
    let mut leaves = |shade: usize| {
        placing.material(&format!("tree_leaves_{k}_{shade}"), || {
            (LEAVES[k][shade], None)
        })
    };
    let leaves = [leaves(tree.shades[0]), leaves(tree.shades[1])];
    let bark = placing.material(&format!("tree_bark_{k}"), || (BARK[k], None));
    let meshes = tree_meshes(tree.kind, tree.height, tree.crown, foot, rng, bark, leaves);
    let name = placing.name("tree");
    let species = Some(("species", tree.kind.name().to_owned()));
    let kind = crate::model::ObjectKind::Tree;
    placing.push_variant(kind, name, label, meshes, species);
}

/// Trees where a map has them: one per site of `sites` (its foot, and the largest crown
/// radius it has room for), in order, up to `spec.count`. Each draws its species (from
/// `spec.species`, else all), height (from `spec.height`) and shades from `rng`; its crown
/// is its species' for that height, cut to the room; a site with room for no crown of
/// half a metre gets no tree.
pub fn place_mapped(
    spec: &ObjectSpec,
    rng: &mut Pcg64,
    sites: &[([f64; 2], f64)],
    placing: &mut Placing,
) {
    let species: &[TreeSpecies] = if spec.species.is_empty() {
        &TreeSpecies::ALL
    } else {
        &spec.species
    };
    let mut placed = 0;
    for &(foot, room) in sites {
        if placed >= spec.count {
            break;
        }
        let kind = species[rng.random_range(0..species.len())];
        let (height, shades) = draw_size(spec, rng);
        let crown = crown_radius(kind, height).min(room);
        if crown.is_nan() || crown < 0.5 {
            continue;
        }
        let tree = Tree {
            kind,
            height,
            crown,
            shades,
        };
        push_tree(placing, &spec.label, &tree, foot, rng);
        placed += 1;
    }
}

/// The largest crown radius a tree of `kind` and `height` may have with its crown's lowest
/// point at least [`CLEAR_HEIGHT`] up ([`crown_bottom`]); 0 when none does (conifers and
/// columnar crowns reach far down).
fn clear_crown(kind: TreeSpecies, height: f64) -> f64 {
    let clear = |r: f64| crown_bottom(kind, height, r) >= CLEAR_HEIGHT;
    let (mut low, mut high) = (0.0, crown_radius(kind, height));
    if clear(high) {
        return high;
    }
    if !clear(low) {
        return 0.0;
    }
    // The bottom only falls as the crown widens: halve the interval down to a millimetre.
    while high - low > 1e-3 {
        let mid = (low + high) / 2.0;
        if clear(mid) {
            low = mid;
        } else {
            high = mid;
        }
    }
    low
}

/// The lowest any leaf of a tree of `kind`, `height` and crown radius `r` can hang, metres
/// above its foot (the bound the lobe layouts in [`crown`] keep, whatever they draw).
fn crown_bottom(kind: TreeSpecies, height: f64, r: f64) -> f64 {
    let h = height;
    match kind {
        TreeSpecies::Round => h - 1.85 * (0.95 * r).min(0.45 * h),
        TreeSpecies::Spreading => h - 2.2 * (0.45 * r).min(0.3 * h),
        TreeSpecies::Columnar => 0.25 * h,
        // The lowest tier hangs a quarter of a tier below 0.12 h; tiers are 0.78 h / 4 at most.
        TreeSpecies::Conifer => 0.12 * h - 0.25 * 0.78 * h / 4.0,
        TreeSpecies::Birch => 0.35 * h,
        TreeSpecies::Weeping => {
            let (ry, curtain) = weeping_sizes(h, r);
            h - 0.6 * ry - 2.0 * curtain
        }
        TreeSpecies::Pine => 0.58 * h,
    }
}

/// A weeping crown's dome half-height and its hanging lobes' half-height, metres.
fn weeping_sizes(h: f64, r: f64) -> (f64, f64) {
    ((0.22 * h).min(0.6 * r), (0.3 * h).min(0.95 * r))
}

/// The crown radius a tree of `height` metres has, before any limit.
fn crown_radius(kind: TreeSpecies, height: f64) -> f64 {
    height
        * match kind {
            TreeSpecies::Round => 0.3,
            TreeSpecies::Columnar => 0.15,
            TreeSpecies::Conifer => 0.22,
            TreeSpecies::Spreading => 0.42,
            TreeSpecies::Birch => 0.25,
            TreeSpecies::Weeping => 0.32,
            TreeSpecies::Pine => 0.26,
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

/// One lobe of a crown: a jittered [`blob`].
#[derive(Clone, Copy, Debug)]
struct Lobe {
    /// Centre (x, y, z) from the tree's foot, metres.
    offset: [f64; 3],
    /// Radii (across, up).
    radii: [f64; 2],
    /// Whether it takes the tree's second leaf shade.
    second: bool,
}

/// A crown's lobes, how ragged they are and where the trunk ends.
struct Crown {
    lobes: Vec<Lobe>,
    /// Each corner of a lobe is pulled in by up to this share of its radius.
    jitter: f64,
    /// A lobe's rim hangs this share of its height below its centre (spruce tiers).
    droop: f64,
    /// Trunk height above the foot, metres.
    trunk_top: f64,
    /// Trunk radius, metres.
    trunk_radius: f64,
}

/// Trunk and crown of a tree standing at `foot` (x, z) on the kerb-high paving: the
/// trunk in `bark`, the crown's lobes in the two `leaves` shades.
fn tree_meshes(
    kind: TreeSpecies,
    height: f64,
    crown_r: f64,
    foot: [f64; 2],
    rng: &mut Pcg64,
    bark: u32,
    leaves: [u32; 2],
) -> Vec<Mesh> {
    let mut trunk = Solid::new(bark);
    let mut first = Solid::new(leaves[0]);
    let mut second = Solid::new(leaves[1]);
    let base = [foot[0], KERB_Y, foot[1]];
    let turn: f64 = rng.random::<f64>() * 360.0;
    let layout = crown(kind, height, crown_r, turn, rng);
    for lobe in &layout.lobes {
        let centre = [
            base[0] + lobe.offset[0],
            base[1] + lobe.offset[1],
            base[2] + lobe.offset[2],
        ];
        let solid = if lobe.second { &mut second } else { &mut first };
        let shape = [layout.jitter, layout.droop];
        blob(solid, centre, lobe.radii, shape, rng);
    }
    hexagonal_trunk(
        &mut trunk,
        base,
        layout.trunk_radius,
        layout.trunk_top,
        turn,
    );
    finish_all(vec![trunk, first, second])
}

/// The crown of a tree of `kind`, `h` tall with crown radius `r`, turned by `turn`
/// degrees: every lobe inside the radius `r` about the trunk, under `h` and over
/// [`crown_bottom`].
fn crown(kind: TreeSpecies, h: f64, r: f64, turn: f64, rng: &mut Pcg64) -> Crown {
    let mut lobes = Vec::new();
    let main = |y: f64, radii: [f64; 2]| Lobe {
        offset: [0.0, y, 0.0],
        radii,
        second: false,
    };
    let at = [turn, r];
    let trunk = 0.08 + 0.012 * h;
    // Per species: how ragged and drooping its lobes are, trunk height and radius.
    let (jitter, droop, trunk_top, trunk_radius) = match kind {
        TreeSpecies::Round => {
            let ry = (0.95 * r).min(0.45 * h);
            lobes.push(main(h - ry, [0.85 * r, 0.85 * ry]));
            let n = rng.random_range(2..5usize);
            let y = [h - 1.25 * ry, h - 1.05 * ry];
            let ring = Ring::new([0.3, 0.38], y, [0.6 * r, 0.6 * ry]);
            ring_lobes(&mut lobes, n, ring, at, rng);
            (0.15, 0.0, h - ry, trunk)
        }
        TreeSpecies::Spreading => {
            let ry = (0.45 * r).min(0.3 * h);
            lobes.push(main(h - ry, [0.5 * r, ry]));
            let n = rng.random_range(4..6usize);
            let y = [h - 1.4 * ry, h - ry];
            let ring = Ring::new([0.45, 0.55], y, [0.45 * r, 0.8 * ry]);
            ring_lobes(&mut lobes, n, ring, at, rng);
            (0.2, 0.0, h - ry, trunk)
        }
        TreeSpecies::Columnar => {
            columnar_lobes(&mut lobes, h, r, rng);
            (0.15, 0.0, 0.6 * h, trunk)
        }
        TreeSpecies::Conifer => {
            conifer_tiers(&mut lobes, h, r, rng);
            (0.3, 0.3, 0.6 * h, trunk)
        }
        TreeSpecies::Birch => {
            lobes.push(main(0.85 * h, [0.35 * r, 0.15 * h]));
            let n = rng.random_range(4..6usize);
            let y = [0.5 * h, 0.8 * h];
            let ring = Ring::new([0.2, 0.6], y, [0.38 * r, 0.15 * h]);
            ring_lobes(&mut lobes, n, ring, at, rng);
            (0.2, 0.0, 0.8 * h, 0.04 + 0.006 * h)
        }
        TreeSpecies::Weeping => {
            // Dome and curtain sized by the crown as much as the height: a narrow willow
            // is a small weeping crown high on its trunk, not a column.
            let (ry, curtain) = weeping_sizes(h, r);
            lobes.push(main(h - ry, [0.62 * r, ry]));
            let n = rng.random_range(4..6usize);
            let y = h - 0.6 * ry - curtain;
            let ring = Ring::new([0.58, 0.62], [y, y], [0.38 * r, curtain]);
            ring_lobes(&mut lobes, n, ring, at, rng);
            (0.15, 0.0, h - ry, trunk)
        }
        TreeSpecies::Pine => {
            lobes.push(main(0.9 * h, [0.35 * r, 0.1 * h]));
            let n = rng.random_range(3..5usize);
            let y = [0.68 * h, 0.86 * h];
            let ring = Ring::new([0.15, 0.5], y, [0.5 * r, 0.1 * h]);
            ring_lobes(&mut lobes, n, ring, at, rng);
            (0.3, 0.0, 0.88 * h, trunk)
        }
    };
    Crown {
        lobes,
        jitter,
        droop,
        trunk_top,
        trunk_radius,
    }
}

/// Lobes in a ring about the trunk: `spread` (the least and most distance out, as shares
/// of the crown radius), centre heights between `y[0]` and `y[1]`, and `radii`
/// (across, up) before a seeded scale of 0.85–1.
#[derive(Clone, Copy, Debug)]
struct Ring {
    spread: [f64; 2],
    y: [f64; 2],
    radii: [f64; 2],
}

impl Ring {
    fn new(spread: [f64; 2], y: [f64; 2], radii: [f64; 2]) -> Ring {
        Ring { spread, y, radii }
    }
}

/// `n` lobes of `ring` at even angles from `turn` (give or take 20°), out by shares of the
/// crown radius `r`; each takes the second leaf shade one time in two.
fn ring_lobes(lobes: &mut Vec<Lobe>, n: usize, ring: Ring, [turn, r]: [f64; 2], rng: &mut Pcg64) {
    let Ring { spread, y, radii } = ring;
    for k in 0..n {
        let a = turn + 360.0 * k as f64 / n as f64 + 40.0 * (rng.random::<f64>() - 0.5);
        let (c, s) = trig::cos_sin_deg(a);
        let d = r * (spread[0] + (spread[1] - spread[0]) * rng.random::<f64>());
        let size = 0.85 + 0.15 * rng.random::<f64>();
        let up = y[0] + (y[1] - y[0]) * rng.random::<f64>();
        lobes.push(Lobe {
            offset: [d * c, up, d * s],
            radii: radii.map(|v| v * size),
            second: rng.random::<bool>(),
        });
    }
}

/// A poplar's crown: three tall lobes stacked from 0.25 h to the top, each a little off
/// the trunk, the lower two in either shade.
fn columnar_lobes(lobes: &mut Vec<Lobe>, h: f64, r: f64, rng: &mut Pcg64) {
    let ry = 0.2 * h;
    for (y, across, up) in [(1.0, 0.8, 1.0), (2.0, 0.95, 1.0), (2.9, 0.85, 0.85)] {
        let (c, s) = trig::cos_sin_deg(rng.random::<f64>() * 360.0);
        let d = 0.05 * r * rng.random::<f64>();
        lobes.push(Lobe {
            offset: [d * c, h - y * ry, d * s],
            radii: [across * r, up * ry],
            second: y > 1.5 && rng.random::<bool>(),
        });
    }
}

/// A spruce's crown: four or five ragged tiers from 0.12 h up, each narrower than the one
/// below and pushed a little off the trunk, and a narrow tip.
fn conifer_tiers(lobes: &mut Vec<Lobe>, h: f64, r: f64, rng: &mut Pcg64) {
    let tiers = rng.random_range(4..6usize);
    let band = 0.78 * h / tiers as f64;
    for k in 0..tiers {
        let share = 1.0 - 0.7 * k as f64 / tiers as f64;
        let across = 0.94 * r * share * (0.85 + 0.15 * rng.random::<f64>());
        let (c, s) = trig::cos_sin_deg(rng.random::<f64>() * 360.0);
        let d = 0.06 * r * rng.random::<f64>();
        lobes.push(Lobe {
            offset: [d * c, 0.12 * h + band * (k as f64 + 0.5), d * s],
            radii: [across, 0.75 * band],
            second: k % 2 == 1,
        });
    }
    lobes.push(Lobe {
        offset: [0.0, 0.9 * h, 0.0],
        radii: [0.15 * r, 0.1 * h],
        second: false,
    });
}

/// A subdivided octahedron (32 faces) of radii `[across, up]` around `centre`, each corner
/// pulled in by up to `jitter` of its radius, its rim lowered by `droop` of its height
/// (the poles stay: the lobe never reaches past its radii); every face looks away from
/// the centre.
fn blob(
    solid: &mut Solid,
    centre: [f64; 3],
    radii: [f64; 2],
    [jitter, droop]: [f64; 2],
    rng: &mut Pcg64,
) {
    let (points, faces) = geosphere();
    let scale: Vec<f64> = points
        .iter()
        .map(|_| 1.0 - jitter * rng.random::<f64>())
        .collect();
    let at = |i: usize| {
        let p = points[i];
        let k = scale[i];
        let sag = droop * (1.0 - p[1] * p[1]);
        [
            centre[0] + p[0] * radii[0] * k,
            centre[1] + (p[1] * k - sag) * radii[1],
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
            for height in [5.0, 10.0, 14.0] {
                let crown = crown_radius(kind, height).min(2.25);
                let bottom = crown_bottom(kind, height, crown);
                let meshes = tree_meshes(kind, height, crown, [10.0, 20.0], &mut rng, 0, [1, 2]);
                let triangles: usize = meshes.iter().map(|m| m.indices.len() / 3).sum();
                assert!((90..=204).contains(&triangles), "{kind:?}: {triangles}");
                // The trunk first, then one or two leaf shades.
                assert!(meshes.len() >= 2 && meshes[0].material == 0, "{kind:?}");
                for m in &meshes {
                    for p in &m.positions {
                        let p = p.map(f64::from);
                        let (dx, dz) = (p[0] - 10.0, p[2] - 20.0);
                        assert!((dx * dx + dz * dz).sqrt() <= crown + 1e-6, "{kind:?} {p:?}");
                        assert!(p[1] <= KERB_Y + height + 1e-6, "{kind:?} {p:?}");
                        let floor = if m.material == 0 { 0.0 } else { bottom };
                        assert!(p[1] >= KERB_Y + floor - 1e-6, "{kind:?} {p:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn a_crown_kept_clear_of_buses_hangs_high_enough() {
        let mut wide = 0;
        for kind in TreeSpecies::ALL {
            for height in [6.0, 8.0, 11.0, 14.0, 20.0] {
                let r = clear_crown(kind, height);
                assert!(r <= crown_radius(kind, height), "{kind:?} {height}");
                if r > 0.0 {
                    assert!(crown_bottom(kind, height, r) >= CLEAR_HEIGHT, "{kind:?}");
                    wide += 1;
                } else {
                    // None would: even a crown of no width hangs too low.
                    assert!(crown_bottom(kind, height, 1e-3) < CLEAR_HEIGHT, "{kind:?}");
                }
            }
        }
        // Most species can reach over the road when tall enough.
        assert!(wide >= 15, "{wide}");
    }

    #[test]
    fn crowns_of_one_species_differ_from_tree_to_tree() {
        let mut rng = stream(3, "tree-test", 1);
        for kind in TreeSpecies::ALL {
            let shapes: Vec<Vec<Mesh>> = (0..3)
                .map(|_| tree_meshes(kind, 10.0, 2.5, [0.0, 0.0], &mut rng, 0, [1, 2]))
                .collect();
            assert!(shapes[0] != shapes[1] && shapes[1] != shapes[2], "{kind:?}");
        }
    }
}
