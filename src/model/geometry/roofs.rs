//! A map building's footprint + `roof:shape` → its roof, where the shape is one built on
//! that footprint; for any other shape or footprint the city lays a flat roof. The scene
//! builds it (on each volume `massing` cuts a building into); wall text keeps below its
//! eaves.
//!
//! | `roof:shape` | footprint | roof |
//! |---|---|---|
//! | `gabled` | any, without a courtyard | a ridge along the longest side's direction (across it with `roof:orientation=across`), over the middle of the footprint's depth across it; the slopes fall to the two farthest lines (the eaves), and every wall rises to the roof above it (the gables) |
//! | `gambrel` | the same | the gabled roof's frame, each side in two slopes: steep from the eave to a quarter of the width in, rising three quarters of the rise there, then shallow to the ridge |
//! | `skillion` | the same | one slope across the width (a gabled roof's frame), down towards `roof:direction` where the map gives it (a compass bearing or point), else across the longest side; it rises as a gabled roof of that width would |
//! | `round` | the same | a half circle across the width (a barrel vault), in eight flat strips along the longest side; it rises half the width, at most [`MAX_DOME`] |
//! | `hipped` | convex, without a courtyard | every side slopes up at one pitch until the slopes meet (the footprint's straight skeleton: on a rectangle a ridge at mid-depth shortened by the half-depth at each end, on a square a pyramid); it rises [`PITCH`] times the run to the deepest point |
//! | `mansard` | the same | the hipped frame, each slope in two: steep over the outer half of the run to three quarters of the rise, then shallow |
//! | `half-hipped` | four corners, convex, without a courtyard | the gabled roof along the long sides, its gables' top half hipped back: the short sides' planes start half the rise up, over gable walls |
//! | `pyramidal` | convex, no courtyard | every side slopes up to a point over the footprint's centroid |
//! | `dome`, `onion` | the same | the footprint drawn in towards its centroid and up in four rings, as a quarter circle: a flat-shaded dome |
//!
//! Slopes rise [`PITCH`] per metre of run (about 31°), at most [`MAX_RISE`]; a dome rises
//! its footprint's mean radius, at most [`MAX_DOME`]. Where the map gives the building's
//! `height`, it is the roof's top (OSM's rule): the walls stop the rise below it (at most
//! half the height). A height from `building:levels`, or a seeded one, is the walls': the
//! roof rises above it. The map's `roof:height` replaces the rise (under a mapped
//! `height`, where it is lower: the walls stand the rest).
//!
//! A gabled, gambrel or round roof is the footprint triangulated (`earcut`), each
//! triangle cut by the lines its slopes break along (the ridge; a gambrel's knees; a round
//! roof's strips), each piece lifted by the roof's height over its side (so every face is
//! planar); its gables are each footprint side's wall from the eaves up to the roof, cut
//! at those lines where the side crosses them. Roof faces take the roof texture projected from above
//! (uv = metres / the tile), each triangle flat-shaded, facing up and out.

use crate::model::MapBuilding;
use crate::model::geometry::MeshBuilder;
use crate::model::geometry::polygon::{left_normal, longest_side, signed_area, triangles};
use crate::model::geometry::trig::cos_sin_deg;
use crate::model::geometry::{cross, dot, sub};

/// Rise per metre of run of a sloped roof.
pub const PITCH: f64 = 0.6;
/// The most a sloped roof rises, metres.
pub const MAX_RISE: f64 = 8.0;
/// The most a dome rises, metres.
pub const MAX_DOME: f64 = 20.0;
/// Rings of a dome between its foot and its top.
const DOME_RINGS: u32 = 4;
/// How far up a half-hipped roof's ends start to hip back (their gable walls below), as
/// a share of the hipped roof's run.
const HALF_HIP: f64 = 0.5;
/// Flat strips across a `round` roof's half circle.
const ROUND_STEPS: u32 = 8;

/// The walls' height and the roof of map building `b`, `height` tall (its cladding's), with
/// its `roof:shape` where [`Roof::of`] builds it on its footprint. The roof rises the map's
/// `roof:height` where it gives one (less than a mapped `height`), else by the shape's rule.
/// A mapped `height` is the roof's top, so the walls stop below it: `roof:height` below
/// it, or the shape's rise, at most half-way. Any other height is the walls': the roof
/// rises above it.
pub fn shaped_roof(b: &MapBuilding, height: f64) -> (f64, Option<Roof>) {
    shaped(&Mass::of(b), height)
}

/// What a roof is built from: a footprint and its roof tags.
#[derive(Clone, Copy)]
pub struct Mass<'a> {
    pub outer: &'a [[f64; 2]],
    pub holes: &'a [Vec<[f64; 2]>],
    pub roof_shape: Option<&'a str>,
    pub roof_height: Option<f64>,
    /// `roof:orientation=across`.
    pub across: bool,
    /// `roof:direction`, degrees clockwise from north.
    pub direction: Option<f64>,
    /// Its height is the map's `height`: the roof's top, not the walls'.
    pub top: bool,
}

impl<'a> Mass<'a> {
    /// Map building `b`'s footprint and roof tags.
    pub fn of(b: &'a MapBuilding) -> Mass<'a> {
        Mass {
            outer: &b.outer,
            holes: &b.holes,
            roof_shape: b.roof_shape.as_deref(),
            roof_height: b.roof_height,
            across: b.roof_across,
            direction: b.roof_direction,
            top: b.height_from == "height",
        }
    }
}

/// [`shaped_roof`] of a mass `height` tall from its foot: the walls' height above the
/// foot, and the roof.
pub fn shaped(m: &Mass, height: f64) -> (f64, Option<Roof>) {
    let roof = (m.roof_shape)
        .filter(|_| m.holes.is_empty())
        .and_then(|shape| Roof::oriented(shape, m.outer, m.across, m.direction));
    let Some(mut roof) = roof else {
        return (height, None);
    };
    let top = m.top;
    let mapped = m.roof_height.filter(|&h| !top || h < height);
    if let Some(h) = mapped {
        roof.rise = h;
    }
    if !top {
        return (height, Some(roof));
    }
    let eave = if mapped.is_some() {
        height - roof.rise
    } else {
        (height - roof.rise).max(height / 2.0)
    };
    roof.rise = height - eave;
    (eave, Some(roof))
}

/// A roof to build on a footprint.
#[derive(Clone, Debug, PartialEq)]
pub struct Roof {
    shape: Shape,
    /// The footprint, counter-clockwise in `[x, z]` (positive area), from the corner the
    /// shape starts at.
    outer: Vec<[f64; 2]>,
    /// How far the top rises above the eaves, metres.
    pub rise: f64,
}

#[derive(Clone, Debug, PartialEq)]
enum Shape {
    /// Slopes along unit `d` over the lines `v = mid ± half` (`v` the distance to the left
    /// of `d`: the eaves) and between them, their cross-section `profile`: `(s, h)`
    /// points, `s` from −1 (one eave) to 1 (the other) by `(v − mid) / half`, `h` the
    /// share of the rise there, linear between them.
    Gable {
        d: [f64; 2],
        mid: f64,
        half: f64,
        profile: Vec<[f64; 2]>,
    },
    /// Every side sloping up at one pitch until the slopes meet: over a convex footprint
    /// the lower envelope of the sides' planes (its straight skeleton). Side `i`'s plane
    /// starts `lifts[i]` metres of run up (0 where missing: at its eave; a half-hipped
    /// roof's ends start higher, over gable walls), so over a point `d` metres in from
    /// the side it stands at level `lifts[i] + d`; the roof is at `profile`'s share of
    /// the rise at `level / run`, `run` the envelope's highest level (`(s, h)` points from
    /// the eaves, 0, to the top, 1; only a roof without lifts breaks it).
    Envelope {
        profile: Vec<[f64; 2]>,
        run: f64,
        lifts: Vec<f64>,
    },
    /// A point over `apex`.
    Pyramid { apex: [f64; 2] },
    /// Rings drawn in towards `centre`.
    Dome { centre: [f64; 2] },
}

impl Roof {
    /// The roof `shape` (a `roof:shape` value) makes on footprint `outer` (without
    /// courtyards), or `None`: a flat roof.
    pub fn of(shape: &str, outer: &[[f64; 2]]) -> Option<Roof> {
        Roof::oriented(shape, outer, false, None)
    }

    /// [`Roof::of`], a ridged roof's ridge across the longest side when `across`
    /// (`roof:orientation=across`), a skillion sloping down towards the compass bearing
    /// `direction` (degrees clockwise from north) where it is given.
    pub fn oriented(
        shape: &str,
        outer: &[[f64; 2]],
        across: bool,
        direction: Option<f64>,
    ) -> Option<Roof> {
        if outer.len() < 3 || signed_area(outer) <= 0.0 {
            return None;
        }
        if let Some(profile) = profile(shape) {
            // x east, z south: a bearing's direction is (sin, −cos); the frame's `v`
            // grows towards (−d_z, d_x), so that is downhill for d = (−cos, −sin).
            let downhill = direction.filter(|_| shape == "skillion").map(|b| {
                let (cos, sin) = cos_sin_deg(b);
                [-cos + 0.0, -sin + 0.0]
            });
            return gable(outer, profile, shape == "round", across, downhill);
        }
        if !convex(outer) {
            return None;
        }
        match shape {
            "hipped" | "mansard" | "half-hipped" => {
                let mut outer = without_straight_corners(outer);
                if outer.len() < 3 {
                    return None;
                }
                let (profile, lifts) = match shape {
                    "hipped" => (vec![[0.0, 0.0], [1.0, 1.0]], Vec::new()),
                    // Steep over the outer half of the run to three quarters of the rise,
                    // then shallow.
                    "mansard" => (vec![[0.0, 0.0], [0.5, 0.75], [1.0, 1.0]], Vec::new()),
                    // The short sides of four: gables up to half the hipped run, hipped
                    // above.
                    _ if outer.len() == 4 => {
                        let side = |i: usize| distance(outer[i], outer[(i + 1) % 4]);
                        // Sides 0 and 2 the long ones.
                        if side(1) + side(3) > side(0) + side(2) {
                            outer.rotate_left(1);
                        }
                        let lift = HALF_HIP * envelope_top(&outer, &[]);
                        (vec![[0.0, 0.0], [1.0, 1.0]], vec![0.0, lift, 0.0, lift])
                    }
                    _ => return None,
                };
                let run = envelope_top(&outer, &lifts);
                (run > 0.0).then(|| Roof {
                    shape: Shape::Envelope {
                        profile,
                        run,
                        lifts,
                    },
                    outer,
                    rise: (PITCH * run).min(MAX_RISE),
                })
            }
            "pyramidal" => {
                let apex = centroid(outer)?;
                let run = (0..outer.len())
                    .map(|i| line_distance(apex, outer[i], outer[(i + 1) % outer.len()]))
                    .fold(f64::INFINITY, f64::min);
                Some(Roof {
                    shape: Shape::Pyramid { apex },
                    outer: outer.to_vec(),
                    rise: (PITCH * run).min(MAX_RISE),
                })
            }
            "dome" | "onion" => {
                let centre = centroid(outer)?;
                let radius =
                    outer.iter().map(|&p| distance(p, centre)).sum::<f64>() / outer.len() as f64;
                Some(Roof {
                    shape: Shape::Dome { centre },
                    outer: outer.to_vec(),
                    rise: radius.min(MAX_DOME),
                })
            }
            _ => None,
        }
    }

    /// Builds the roof on walls `eave` metres high (above the ground `base`): its slopes
    /// into `roof` (uv = metres / `tile`), its gables into `walls`.
    pub fn build(
        &self,
        base: f64,
        eave: f64,
        tile: f64,
        roof: &mut MeshBuilder,
        walls: &mut MeshBuilder,
    ) {
        let y = base + eave;
        let mut slopes = Slopes { mesh: roof, tile };
        let (o, top) = (&self.outer, y + self.rise);
        match &self.shape {
            Shape::Gable {
                d,
                mid,
                half,
                profile,
            } => {
                let (d, mid, half) = (*d, *mid, *half);
                let height = |p: [f64; 2]| {
                    let s = ((p[1] * d[0] - p[0] * d[1] - mid) / half).clamp(-1.0, 1.0);
                    y + self.rise * share(profile, s)
                };
                let lift = |p: [f64; 2]| at(p, height(p));
                // The profile's inner points are the lines the slopes break along.
                let lines: Vec<f64> = (profile[1..profile.len() - 1].iter())
                    .map(|&[s, _]| mid + s * half)
                    .collect();
                for [a, b, c] in triangles(o, &[]) {
                    for piece in cut_all(vec![vec![a, b, c]], d, &lines) {
                        for k in 1..piece.len() - 1 {
                            slopes.add(lift(piece[0]), lift(piece[k]), lift(piece[k + 1]));
                        }
                    }
                }
                for i in 0..o.len() {
                    let side = vec![o[i], o[(i + 1) % o.len()]];
                    for piece in cut_all(vec![side], d, &lines) {
                        gable_wall(walls, piece[0], piece[1], y, &height);
                    }
                }
            }
            Shape::Envelope {
                profile,
                run,
                lifts,
            } => self.envelope(y, (profile, *run, lifts), &mut slopes, walls),
            Shape::Pyramid { apex } => {
                let apex = *apex;
                for i in 0..o.len() {
                    slopes.add(at(o[i], y), at(o[(i + 1) % o.len()], y), at(apex, top));
                }
            }
            Shape::Dome { centre } => self.dome(y, *centre, &mut slopes),
        }
    }

    /// A hipped, mansard or half-hipped roof (see `Shape::Envelope`): its faces into
    /// `slopes`, eaves at `y`; the gable walls of lifted sides into `walls`.
    fn envelope(
        &self,
        y: f64,
        (profile, run, lifts): (&[[f64; 2]], f64, &[f64]),
        slopes: &mut Slopes,
        walls: &mut MeshBuilder,
    ) {
        let o = &self.outer;
        let faces = envelope_faces(o, lifts);
        let level = |i: usize, side: &Side, p: [f64; 2]| {
            lifts.get(i).copied().unwrap_or(0.0) + side.depth(p)
        };
        let plane = |i: usize, side: &Side, p: [f64; 2]| {
            y + self.rise * share(profile, level(i, side, p) / run)
        };
        for (i, (side, face)) in faces.iter().enumerate() {
            // The bands between the profile's breaks, each planar.
            for w in profile.windows(2) {
                let (from, to) = (w[0][0] * run, w[1][0] * run);
                let band = clip(&clip(face, |p| from - level(i, side, p)), |p| {
                    level(i, side, p) - to
                });
                let lifted = |p| at(p, plane(i, side, p));
                for k in 1..band.len().saturating_sub(1) {
                    slopes.add(lifted(band[0]), lifted(band[k]), lifted(band[k + 1]));
                }
            }
        }
        if lifts.iter().any(|&l| l > 0.0) {
            let height = |p: [f64; 2]| {
                (faces.iter().enumerate())
                    .map(|(i, (side, _))| plane(i, side, p))
                    .fold(f64::INFINITY, f64::min)
            };
            for i in 0..o.len() {
                for w in side_pieces(o[i], o[(i + 1) % o.len()], &faces).windows(2) {
                    gable_wall(walls, w[0], w[1], y, &height);
                }
            }
        }
    }

    /// A dome's rings, its foot at `y`, drawn in towards `centre`.
    fn dome(&self, y: f64, centre: [f64; 2], slopes: &mut Slopes) {
        let o = &self.outer;
        let ring = |k: u32| -> Vec<[f64; 3]> {
            let (cos, sin) = cos_sin_deg(90.0 * f64::from(k) / f64::from(DOME_RINGS));
            let h = y + self.rise * sin;
            o.iter()
                .map(|&p| at([0, 1].map(|j| centre[j] + (p[j] - centre[j]) * cos), h))
                .collect()
        };
        for k in 0..DOME_RINGS {
            let (low, high) = (ring(k), ring(k + 1));
            for i in 0..o.len() {
                let j = (i + 1) % o.len();
                slopes.add(low[i], low[j], high[j]);
                slopes.add(low[i], high[j], high[i]);
            }
        }
    }
}

/// Roof faces going into one mesh: flat-shaded triangles facing up, the roof texture
/// projected from above.
struct Slopes<'a> {
    mesh: &'a mut MeshBuilder,
    tile: f64,
}

impl Slopes<'_> {
    fn add(&mut self, a: [f64; 3], b: [f64; 3], c: [f64; 3]) {
        let n = cross(sub(b, a), sub(c, a));
        let len = dot(n, n).sqrt();
        if len.is_nan() || len <= 1e-9 {
            return;
        }
        let sign = if n[1] < 0.0 { -1.0 } else { 1.0 };
        let normal = n.map(|v| sign * v / len + 0.0);
        let tile = self.tile;
        let uvs = [a, b, c].map(|p| [p[0] / tile, p[2] / tile]);
        self.mesh.triangle([a, b, c], normal, uvs);
    }
}

/// A side of a convex footprint as a roof slope rises from it.
#[derive(Clone, Copy)]
struct Side {
    a: [f64; 2],
    /// Unit normal into the footprint.
    inward: [f64; 2],
}

impl Side {
    /// How far `p` lies inside the side's line, metres.
    fn depth(&self, p: [f64; 2]) -> f64 {
        (p[0] - self.a[0]) * self.inward[0] + (p[1] - self.a[1]) * self.inward[1]
    }
}

/// The convex ring `ring` without repeated points and the corners where it goes straight
/// on.
fn without_straight_corners(ring: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut ring = ring.to_vec();
    ring.dedup();
    if ring.len() > 1 && ring.first() == ring.last() {
        ring.pop();
    }
    let n = ring.len();
    (0..n)
        .filter(|&i| {
            let (a, p, b) = (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
            let turn = (p[0] - a[0]) * (b[1] - p[1]) - (p[1] - a[1]) * (b[0] - p[0]);
            turn.abs() > 1e-9 * distance(a, p) * distance(p, b)
        })
        .map(|i| ring[i])
        .collect()
}

/// Each side of convex ring `ring` with the part of the footprint where its plane is the
/// lowest (the straight skeleton's face when no side is lifted): side `i`'s plane stands
/// `lifts[i]` metres of run (0 where missing) above its eave and rises one per metre in.
fn envelope_faces(ring: &[[f64; 2]], lifts: &[f64]) -> Vec<(Side, Vec<[f64; 2]>)> {
    let Some(c) = centroid(ring) else {
        return Vec::new();
    };
    let n = ring.len();
    let sides: Vec<Side> = (0..n)
        .filter_map(|i| {
            let (a, b) = (ring[i], ring[(i + 1) % n]);
            let l = left_normal(a, b)?;
            let inward = if (c[0] - a[0]) * l[0] + (c[1] - a[1]) * l[1] >= 0.0 {
                l
            } else {
                [-l[0], -l[1]]
            };
            Some(Side { a, inward })
        })
        .collect();
    let level = |i: usize, p: [f64; 2]| lifts.get(i).copied().unwrap_or(0.0) + sides[i].depth(p);
    (0..sides.len())
        .map(|i| {
            let face = ((0..sides.len()).filter(|&j| j != i)).fold(ring.to_vec(), |face, j| {
                clip(&face, |p| level(i, p) - level(j, p))
            });
            (sides[i], face)
        })
        .collect()
}

/// The highest level of the envelope of convex `ring`'s sides' planes, lifted as
/// [`envelope_faces`] lifts them: at a corner of a face.
fn envelope_top(ring: &[[f64; 2]], lifts: &[f64]) -> f64 {
    (envelope_faces(ring, lifts).iter().enumerate())
        .flat_map(|(i, (side, face))| {
            let lift = lifts.get(i).copied().unwrap_or(0.0);
            face.iter().map(move |&p| lift + side.depth(p))
        })
        .fold(0.0, f64::max)
}

/// Side `a`–`b` cut where the faces' corners lie on it, in order from `a`.
fn side_pieces(a: [f64; 2], b: [f64; 2], faces: &[(Side, Vec<[f64; 2]>)]) -> Vec<[f64; 2]> {
    let len = distance(a, b);
    let mut along: Vec<f64> = (faces.iter().flat_map(|(_, f)| f.iter()))
        .filter(|&&p| line_distance(p, a, b) < 1e-6)
        .map(|&p| ((p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1])) / len)
        .filter(|&t| t > 1e-6 && t < len - 1e-6)
        .collect();
    along.sort_by(f64::total_cmp);
    along.dedup_by(|x, y| (*x - *y).abs() < 1e-6);
    let point = |t: f64| {
        [
            a[0] + (b[0] - a[0]) * t / len,
            a[1] + (b[1] - a[1]) * t / len,
        ]
    };
    std::iter::once(a)
        .chain(along.into_iter().map(point))
        .chain(std::iter::once(b))
        .collect()
}

/// Convex polygon `poly` where `f` (linear) is at most 0 (Sutherland–Hodgman).
fn clip(poly: &[[f64; 2]], f: impl Fn([f64; 2]) -> f64) -> Vec<[f64; 2]> {
    const ON: f64 = 1e-9;
    let mut out = Vec::new();
    for i in 0..poly.len() {
        let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
        let (fp, fq) = (f(p), f(q));
        if fp <= ON {
            out.push(p);
        }
        if (fp < -ON && fq > ON) || (fp > ON && fq < -ON) {
            let t = fp / (fp - fq);
            out.push([p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t]);
        }
    }
    out
}

/// `p` at height `h`.
fn at(p: [f64; 2], h: f64) -> [f64; 3] {
    [p[0], h, p[1]]
}

/// The cross-section of a roof along its longest side, by `roof:shape` (see
/// `Shape::Gable`), or `None` for a shape of another kind.
fn profile(shape: &str) -> Option<Vec<[f64; 2]>> {
    Some(match shape {
        "gabled" => vec![[-1.0, 0.0], [0.0, 1.0], [1.0, 0.0]],
        // One slope from the high eave down to the low one.
        "skillion" => vec![[-1.0, 1.0], [1.0, 0.0]],
        // Steep below, shallow above: the lower slopes rise three quarters of the way
        // over the outer quarter of the width.
        "gambrel" => vec![
            [-1.0, 0.0],
            [-0.5, 0.75],
            [0.0, 1.0],
            [0.5, 0.75],
            [1.0, 0.0],
        ],
        // A half circle (the rise scales it): ROUND_STEPS flat strips.
        "round" => (0..=ROUND_STEPS)
            .map(|k| {
                let (cos, sin) = cos_sin_deg(180.0 * f64::from(k) / f64::from(ROUND_STEPS));
                // + 0.0: the top's s is 0, not -0.
                [-cos + 0.0, sin]
            })
            .collect(),
        _ => return None,
    })
}

/// A roof of cross-section `profile` on `outer`, along its longest side (`across`: at
/// right angles to it), or along unit `frame` where given: it rises [`PITCH`] per metre
/// of its half-width (at most [`MAX_RISE`]), or, `round`, its half-width (at most
/// [`MAX_DOME`]).
fn gable(
    outer: &[[f64; 2]],
    profile: Vec<[f64; 2]>,
    round: bool,
    across: bool,
    frame: Option<[f64; 2]>,
) -> Option<Roof> {
    let d = longest_side(outer)?;
    // + 0.0: no negative zero in the direction.
    let d = if across { [-d[1] + 0.0, d[0]] } else { d };
    let d = frame.unwrap_or(d);
    let across = outer.iter().map(|p| p[1] * d[0] - p[0] * d[1]);
    let (lo, hi) = across.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    let half = (hi - lo) / 2.0;
    let rise = if round {
        half.min(MAX_DOME)
    } else {
        (PITCH * half).min(MAX_RISE)
    };
    (half > 0.0).then(|| Roof {
        shape: Shape::Gable {
            d,
            mid: (lo + hi) / 2.0,
            half,
            profile,
        },
        outer: outer.to_vec(),
        rise,
    })
}

/// The share of the rise `profile` gives at `s` (in −1…1), linear between its points.
fn share(profile: &[[f64; 2]], s: f64) -> f64 {
    for w in profile.windows(2) {
        let ([s0, h0], [s1, h1]) = (w[0], w[1]);
        if s <= s1 {
            return h0 + (h1 - h0) * (s - s0) / (s1 - s0);
        }
    }
    profile.last().map_or(0.0, |p| p[1])
}

/// `pieces` (convex polygons or segments) cut by each line `v = line` in turn (see
/// [`cut`]); a segment on a line is one piece, not two.
fn cut_all(pieces: Vec<Vec<[f64; 2]>>, d: [f64; 2], lines: &[f64]) -> Vec<Vec<[f64; 2]>> {
    lines.iter().fold(pieces, |pieces, &line| {
        pieces
            .iter()
            .flat_map(|p| {
                let mut cut = cut(p, d, line);
                cut.dedup();
                cut
            })
            .collect()
    })
}

/// A convex polygon or a segment (`points` in order) cut by the line `v = mid` (`v` the
/// distance to the left of unit `d`): its pieces on either side, each in order.
fn cut(points: &[[f64; 2]], d: [f64; 2], mid: f64) -> Vec<Vec<[f64; 2]>> {
    let v = |p: [f64; 2]| p[1] * d[0] - p[0] * d[1] - mid;
    let closed = points.len() > 2;
    let mut sides: [Vec<[f64; 2]>; 2] = [Vec::new(), Vec::new()];
    let n = points.len();
    for i in 0..n {
        let p = points[i];
        let side = usize::from(v(p) > 0.0);
        sides[side].push(p);
        if v(p) == 0.0 {
            sides[1].push(p);
        }
        if i + 1 == n && !closed {
            break;
        }
        let q = points[(i + 1) % n];
        let (vp, vq) = (v(p), v(q));
        if (vp < 0.0 && vq > 0.0) || (vp > 0.0 && vq < 0.0) {
            let t = vp / (vp - vq);
            let x = [p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t];
            sides[0].push(x);
            sides[1].push(x);
        }
    }
    let least = if closed { 3 } else { 2 };
    sides.into_iter().filter(|s| s.len() >= least).collect()
}

/// The gable part of the wall along footprint side `a → b` (on one side of the ridge):
/// from the eaves at `y` up to the roof's `height` above each end, facing out, in the
/// walls' material: the walls' texture's top strip across it.
fn gable_wall(
    walls: &mut MeshBuilder,
    a: [f64; 2],
    b: [f64; 2],
    y: f64,
    height: &dyn Fn([f64; 2]) -> f64,
) {
    let Some(n) = left_normal(a, b) else {
        return;
    };
    let u = distance(a, b) / 3.0;
    let normal = [n[0] + 0.0, 0.0, n[1] + 0.0];
    let (low_a, low_b) = ([a[0], y, a[1]], [b[0], y, b[1]]);
    let (top_a, top_b) = ([a[0], height(a), a[1]], [b[0], height(b), b[1]]);
    // An end at the eaves is a corner, not an edge: a triangle, never a quad with two
    // corners in one place.
    const LOW: f64 = 1e-6;
    match (top_a[1] - y > LOW, top_b[1] - y > LOW) {
        (true, true) => walls.quad(
            [low_a, low_b, top_b, top_a],
            normal,
            [[0.0, 0.02], [u, 0.02], [u, 0.0], [0.0, 0.0]],
        ),
        (false, true) => walls.triangle(
            [low_a, low_b, top_b],
            normal,
            [[0.0, 0.02], [u, 0.02], [u, 0.0]],
        ),
        (true, false) => walls.triangle(
            [low_a, low_b, top_a],
            normal,
            [[0.0, 0.02], [u, 0.02], [0.0, 0.0]],
        ),
        (false, false) => {}
    }
}

/// Whether every corner of the counter-clockwise ring turns left (collinear ones pass).
fn convex(ring: &[[f64; 2]]) -> bool {
    let n = ring.len();
    signed_area(ring) > 0.0
        && (0..n).all(|i| {
            let (a, b, c) = (ring[i], ring[(i + 1) % n], ring[(i + 2) % n]);
            (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]) >= 0.0
        })
}

/// The area centroid of a ring.
fn centroid(ring: &[[f64; 2]]) -> Option<[f64; 2]> {
    let (mut a, mut cx, mut cz) = (0.0, 0.0, 0.0);
    let o = ring[0];
    for i in 1..ring.len() - 1 {
        let (p, q) = (ring[i], ring[i + 1]);
        let w = ((p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0])) / 2.0;
        a += w;
        cx += w * (o[0] + p[0] + q[0]) / 3.0;
        cz += w * (o[1] + p[1] + q[1]) / 3.0;
    }
    (a > 0.0).then(|| [cx / a, cz / a])
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    crate::model::geometry::polygon::distance(a, b)
}

/// Distance from `p` to the line through `a` and `b`.
fn line_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let len = distance(a, b);
    if len == 0.0 {
        return distance(p, a);
    }
    ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])).abs() / len
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Mesh;

    /// A `w × d` rectangle at `c`, its long side turned `deg` from x, counter-clockwise.
    fn rectangle(c: [f64; 2], (w, d): (f64, f64), deg: f64) -> Vec<[f64; 2]> {
        let (k, s) = cos_sin_deg(deg);
        [[-w, -d], [w, -d], [w, d], [-w, d]]
            .map(|[x, z]| [c[0] + (x * k - z * s) / 2.0, c[1] + (x * s + z * k) / 2.0])
            .to_vec()
    }

    /// A regular `n`-gon of radius `r` round `c`, counter-clockwise.
    fn regular(c: [f64; 2], r: f64, n: u32) -> Vec<[f64; 2]> {
        (0..n)
            .map(|i| {
                let (k, s) = cos_sin_deg(360.0 * f64::from(i) / f64::from(n));
                [c[0] + r * k, c[1] + r * s]
            })
            .collect()
    }

    /// A concave footprint: an L of two 8 m wide arms, 20 m long.
    const L_SHAPE: [[f64; 2]; 6] = [
        [0.0, 0.0],
        [20.0, 0.0],
        [20.0, 8.0],
        [8.0, 8.0],
        [8.0, 20.0],
        [0.0, 20.0],
    ];

    /// The roof built on walls 10 m high: (roof mesh, walls mesh).
    #[test]
    fn a_mapped_roof_height_sets_the_rise_and_the_walls_stand_the_rest() {
        // A 20 × 20 m footprint, 12 m to the top of its roof (`height`).
        let mut b = crate::test_support::street_map().buildings.remove(0);
        let walls = |b: &MapBuilding| {
            let (eave, roof) = shaped_roof(b, 12.0);
            (eave, roof.map(|r| r.rise))
        };
        assert_eq!(walls(&b), (12.0, None), "flat");
        b.roof_height = Some(3.0);
        assert_eq!(walls(&b), (12.0, None), "flat, whatever its roof:height");
        b.roof_shape = Some("gabled".to_owned());
        b.roof_height = None;
        // The shape's rise, 0.6 × 10 m, stops at half the height.
        assert_eq!(walls(&b), (6.0, Some(6.0)));
        b.roof_height = Some(3.0);
        assert_eq!(walls(&b), (9.0, Some(3.0)));
        // A roof:height of the whole height or more leaves no walls: the shape's rule.
        b.roof_height = Some(12.0);
        assert_eq!(walls(&b), (6.0, Some(6.0)));
        // A height from levels is the walls': the roof rises its roof:height above.
        b.height_from = "levels".to_owned();
        b.roof_height = Some(4.0);
        assert_eq!(walls(&b), (12.0, Some(4.0)));
        b.roof_height = None;
        assert_eq!(walls(&b), (12.0, Some(6.0)));
        // A dome rises its roof:height too.
        b.height_from = "height".to_owned();
        b.roof_shape = Some("dome".to_owned());
        b.roof_height = Some(5.0);
        assert_eq!(walls(&b), (7.0, Some(5.0)));
    }

    fn built(shape: &str, outer: &[[f64; 2]]) -> (Roof, Mesh, Mesh) {
        let roof = Roof::of(shape, outer).expect("a roof of that shape");
        let (mut top, mut walls) = (MeshBuilder::new(0), MeshBuilder::new(1));
        roof.build(0.0, 10.0, 4.0, &mut top, &mut walls);
        (roof, top.finish(), walls.finish())
    }

    fn triangles(mesh: &Mesh) -> Vec<[[f64; 3]; 3]> {
        mesh.indices
            .chunks_exact(3)
            .map(|t| [0, 1, 2].map(|k| mesh.positions[t[k] as usize].map(f64::from)))
            .collect()
    }

    /// Each triangle's area seen from above, and its normal's rise (the winding's).
    fn from_above(t: [[f64; 3]; 3]) -> (f64, f64) {
        let [a, b, c] = t;
        let n = cross(sub(b, a), sub(c, a));
        (n[1].abs() / 2.0, n[1] / dot(n, n).sqrt())
    }

    /// The slopes cover the footprint once, all facing up; the top is `rise` above the
    /// eaves, nothing below them.
    fn covers(outer: &[[f64; 2]], roof: &Roof, top: &Mesh) {
        let mut area = 0.0;
        for t in triangles(top) {
            let (a, up) = from_above(t);
            assert!(up > 0.0, "{t:?} faces down");
            area += a;
            for p in t {
                assert!(
                    p[1] >= 10.0 - 1e-4 && p[1] <= 10.0 + roof.rise + 1e-4,
                    "{p:?}"
                );
            }
        }
        assert!(
            (area - signed_area(outer)).abs() < 1e-3,
            "{area} {}",
            signed_area(outer)
        );
        let highest = top
            .positions
            .iter()
            .map(|p| f64::from(p[1]))
            .fold(0.0, f64::max);
        assert!((highest - 10.0 - roof.rise).abs() < 1e-4);
    }

    /// The points of `mesh` at the top, `rise` above the eaves.
    fn ridge(mesh: &Mesh, rise: f64) -> Vec<[f64; 2]> {
        let mut top: Vec<[f64; 2]> = (mesh.positions.iter())
            .filter(|p| (f64::from(p[1]) - 10.0 - rise).abs() < 1e-4)
            .map(|p| [f64::from(p[0]), f64::from(p[2])])
            .collect();
        top.sort_by(|a, b| a.partial_cmp(b).unwrap());
        top.dedup_by(|a, b| distance(*a, *b) < 1e-3);
        top
    }

    #[test]
    fn a_gabled_roof_runs_its_ridge_along_the_long_sides_with_a_gable_at_each_end() {
        // Given from a short side, so the ridge must turn.
        let mut outer = rectangle([5.0, 7.0], (20.0, 10.0), 30.0);
        outer.rotate_left(1);
        let (roof, top, walls) = built("gabled", &outer);
        assert_eq!(roof.rise, PITCH * 5.0);
        covers(&outer, &roof, &top);
        // The ridge: 20 m along the long sides' direction, over the middle.
        let line = ridge(&top, roof.rise);
        let (ends, long) = ((line[0], line[line.len() - 1]), cos_sin_deg(30.0));
        assert!((distance(ends.0, ends.1) - 20.0).abs() < 1e-3, "{line:?}");
        for p in &line {
            let across = (p[1] - 7.0) * long.0 - (p[0] - 5.0) * long.1;
            assert!(across.abs() < 1e-4, "{p:?} off the middle");
        }
        // Gables: upright, outwards, 10 m × the rise / 2 at each end.
        let mut area = 0.0;
        for (g, n) in triangles(&walls).iter().zip(walls.indices.chunks_exact(3)) {
            let n = walls.normals[n[0] as usize].map(f64::from);
            assert_eq!(n[1], 0.0);
            assert!(
                g.iter()
                    .all(|p| p[1] >= 10.0 - 1e-4 && p[1] <= 10.0 + roof.rise + 1e-4)
            );
            let out = [g[0][0] - 5.0, 0.0, g[0][2] - 7.0];
            assert!(dot(out, n) > 0.0, "faces in");
            let [a, b, c] = *g;
            let m = cross(sub(b, a), sub(c, a));
            area += dot(m, m).sqrt() / 2.0;
        }
        assert!((area - 2.0 * 10.0 * roof.rise / 2.0).abs() < 1e-3, "{area}");
        // A concave footprint takes a gabled roof too, covered once.
        let l_shape = L_SHAPE;
        let (roof, top, _) = built("gabled", &l_shape);
        covers(&l_shape, &roof, &top);
        // A notch whose inner side lies on the ridge line (z = 10): its wall once.
        let notched = [
            [0.0, 0.0],
            [20.0, 0.0],
            [20.0, 20.0],
            [12.0, 20.0],
            [12.0, 10.0],
            [8.0, 10.0],
            [8.0, 20.0],
            [0.0, 20.0],
        ];
        let (roof, top, walls) = built("gabled", &notched);
        covers(&notched, &roof, &top);
        let mut faces: Vec<String> = triangles(&walls)
            .iter()
            .map(|t| {
                let mut t = *t;
                t.sort_by(|a, b| a.partial_cmp(b).unwrap());
                format!("{t:?}")
            })
            .collect();
        let all = faces.len();
        faces.sort();
        faces.dedup();
        assert_eq!(faces.len(), all, "a gable wall twice");
    }

    #[test]
    fn a_skillion_slopes_down_across_the_long_sides_or_towards_its_direction() {
        // 20 m east–west, 10 m north–south.
        let outer = rectangle([0.0, 0.0], (20.0, 10.0), 0.0);
        let heights = |roof: &Roof| {
            let (mut top, mut walls) = (MeshBuilder::new(0), MeshBuilder::new(1));
            roof.build(0.0, 10.0, 4.0, &mut top, &mut walls);
            let top = top.finish();
            covers(&outer, roof, &top);
            let walls = walls.finish();
            assert!(!walls.indices.is_empty(), "no walls up to the roof");
            (top.positions.iter())
                .map(|p| [f64::from(p[0]), f64::from(p[1]) - 10.0, f64::from(p[2])])
                .collect::<Vec<_>>()
        };
        // No direction: one slope across the long sides, a gabled roof's rise.
        let roof = Roof::of("skillion", &outer).unwrap();
        assert!((roof.rise - PITCH * 5.0).abs() < 1e-9);
        let all = heights(&roof);
        let high_north = all.iter().any(|p| p[2] < -4.9 && p[1] > roof.rise - 1e-4);
        for [_, y, z] in all {
            let share = if high_north {
                (5.0 - z) / 10.0
            } else {
                (z + 5.0) / 10.0
            };
            assert!((y - roof.rise * share).abs() < 1e-4, "{y} at z {z}");
        }
        // Down towards the north (0°): the south eave high.
        let roof = Roof::oriented("skillion", &outer, false, Some(0.0)).unwrap();
        for [_, y, z] in heights(&roof) {
            assert!(
                (y - roof.rise * (z + 5.0) / 10.0).abs() < 1e-4,
                "{y} at z {z}"
            );
        }
        // Down towards the east (90°): across the short sides, high in the west.
        let roof = Roof::oriented("skillion", &outer, false, Some(90.0)).unwrap();
        assert!((roof.rise - PITCH * 10.0).abs() < 1e-9);
        for [x, y, _] in heights(&roof) {
            assert!(
                (y - roof.rise * (10.0 - x) / 20.0).abs() < 1e-4,
                "{y} at x {x}"
            );
        }
        // The direction turns a skillion only.
        assert_eq!(
            Roof::oriented("gabled", &outer, false, Some(90.0)),
            Roof::of("gabled", &outer)
        );
    }

    #[test]
    fn roof_orientation_across_turns_the_ridge_across_the_long_sides() {
        let outer = rectangle([5.0, 7.0], (20.0, 10.0), 30.0);
        let roof = Roof::oriented("gabled", &outer, true, None).unwrap();
        // The half-width is now half the long side: 10 m, rising 6 m.
        assert!((roof.rise - PITCH * 10.0).abs() < 1e-9, "{}", roof.rise);
        let (mut top, mut walls) = (MeshBuilder::new(0), MeshBuilder::new(1));
        roof.build(0.0, 10.0, 4.0, &mut top, &mut walls);
        let top = top.finish();
        covers(&outer, &roof, &top);
        // The ridge: 10 m, along the short sides' direction (120°), over the middle.
        let line = ridge(&top, roof.rise);
        assert!(
            (distance(line[0], line[line.len() - 1]) - 10.0).abs() < 1e-3,
            "{line:?}"
        );
        let short = cos_sin_deg(120.0);
        for p in &line {
            let off = (p[1] - 7.0) * short.0 - (p[0] - 5.0) * short.1;
            assert!(off.abs() < 1e-4, "{p:?} off the middle");
        }
    }

    #[test]
    fn round_and_gambrel_roofs_follow_their_cross_section_with_gables_to_match() {
        // 20 m along x, 10 m across z, round (0, 0).
        let outer = rectangle([0.0, 0.0], (20.0, 10.0), 0.0);
        // A half circle of radius 5 over the eaves at 10 m: every corner of the roof on
        // it; the gables the half circle's eight strips, twice.
        let (roof, top, walls) = built("round", &outer);
        assert_eq!(roof.rise, 5.0);
        covers(&outer, &roof, &top);
        for p in &top.positions {
            let (y, z) = (f64::from(p[1]) - 10.0, f64::from(p[2]));
            assert!((y * y + z * z - 25.0).abs() < 1e-3, "{p:?} off the circle");
        }
        let strips = 8.0 * 0.5 * 25.0 * cos_sin_deg(180.0 / 8.0).1;
        assert!(
            (wall_area(&walls) - 2.0 * strips).abs() < 1e-3,
            "{}",
            wall_area(&walls)
        );
        // A gambrel: 3 m high, its knees 2.5 m in from the eaves at three quarters of that.
        let (roof, top, walls) = built("gambrel", &outer);
        assert_eq!(roof.rise, PITCH * 5.0);
        covers(&outer, &roof, &top);
        let knee = 10.0 + 0.75 * roof.rise;
        for p in &top.positions {
            let (y, z) = (f64::from(p[1]), f64::from(p[2]).abs());
            let want = match z {
                z if (z - 5.0).abs() < 1e-4 => 10.0,
                z if (z - 2.5).abs() < 1e-4 => knee,
                z if z < 1e-4 => 10.0 + roof.rise,
                _ => panic!("a corner off the profile's lines at z {z}"),
            };
            assert!((y - want).abs() < 1e-4, "{p:?}: {want}");
        }
        let end = 2.5 * (0.75 / 2.0 + 1.75 / 2.0) * roof.rise * 2.0;
        assert!(
            (wall_area(&walls) - 2.0 * end).abs() < 1e-3,
            "{}",
            wall_area(&walls)
        );
    }

    #[test]
    fn a_hipped_roof_shortens_the_ridge_by_the_half_depth_and_has_no_gables() {
        let outer = rectangle([0.0, 0.0], (20.0, 10.0), -15.0);
        let (roof, top, walls) = built("hipped", &outer);
        covers(&outer, &roof, &top);
        let line = ridge(&top, roof.rise);
        assert!((distance(line[0], line[1]) - 10.0).abs() < 1e-3, "{line:?}");
        assert!(walls.indices.is_empty());
        // A square leaves no ridge: a pyramid.
        let square = rectangle([0.0, 0.0], (10.0, 10.0), 0.0);
        let (roof, top, _) = built("hipped", &square);
        covers(&square, &roof, &top);
        assert_eq!(ridge(&top, roof.rise).len(), 1);
    }

    /// The area of `walls`' triangles.
    fn wall_area(walls: &Mesh) -> f64 {
        (triangles(walls).iter())
            .map(|&[a, b, c]| {
                let m = cross(sub(b, a), sub(c, a));
                dot(m, m).sqrt() / 2.0
            })
            .sum()
    }

    /// `shape` on a regular hexagon of radius 6 round (3, −4): one apex over the centre,
    /// rising the hexagon's inradius' worth.
    fn a_pyramid_over_the_hexagon(shape: &str) {
        let hexagon = regular([3.0, -4.0], 6.0, 6);
        let (roof, top, _) = built(shape, &hexagon);
        covers(&hexagon, &roof, &top);
        let apex = ridge(&top, roof.rise);
        assert_eq!(apex.len(), 1, "{shape}");
        assert!(distance(apex[0], [3.0, -4.0]) < 1e-4, "{shape}");
        assert!(
            (roof.rise - PITCH * 6.0 * cos_sin_deg(30.0).0).abs() < 1e-9,
            "{shape}"
        );
    }

    /// The least depth of `p` inside convex `ring`'s sides.
    fn least_depth(ring: &[[f64; 2]], p: [f64; 2]) -> f64 {
        (0..ring.len())
            .map(|i| line_distance(p, ring[i], ring[(i + 1) % ring.len()]))
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn hipped_and_mansard_roofs_slope_up_from_every_side_of_a_convex_footprint() {
        // A pentagon with a corner cut off a rectangle, and one straight corner.
        let house = [
            [0.0, 0.0],
            [16.0, 0.0],
            [16.0, 7.0],
            [12.0, 10.0],
            [6.0, 10.0],
            [0.0, 10.0],
        ];
        // The same with a corner given twice: the same roof.
        let mut twice = house.to_vec();
        twice.insert(3, house[3]);
        assert_eq!(Roof::of("hipped", &twice), Roof::of("hipped", &house));
        for shape in ["hipped", "mansard"] {
            let (roof, top, walls) = built(shape, &house);
            covers(&house, &roof, &top);
            assert!(walls.indices.is_empty(), "{shape}: no gables");
            // The deepest point is 5 m in (half the depth): the run.
            assert!(
                (roof.rise - PITCH * 5.0).abs() < 1e-9,
                "{shape} {}",
                roof.rise
            );
            let share = |s: f64| match shape {
                "hipped" => s,
                _ if s <= 0.5 => 1.5 * s,
                _ => 0.75 + 0.5 * (s - 0.5),
            };
            for p in &top.positions {
                let [x, y, z] = p.map(f64::from);
                let expected = 10.0 + roof.rise * share(least_depth(&house, [x, z]) / 5.0);
                assert!((y - expected).abs() < 1e-4, "{shape}: {p:?} not {expected}");
            }
        }
        // A regular hexagon: a pyramid over its centre.
        a_pyramid_over_the_hexagon("hipped");
    }

    #[test]
    fn a_half_hipped_roof_hips_the_top_half_of_its_gables() {
        // 20 m along the 30° direction, 10 m deep, given from a short side.
        let mut outer = rectangle([5.0, 7.0], (20.0, 10.0), 30.0);
        outer.rotate_left(1);
        let (roof, top, walls) = built("half-hipped", &outer);
        covers(&outer, &roof, &top);
        // The gabled roof's rise over the half-depth; the ends hip back from half of it.
        assert!((roof.rise - PITCH * 5.0).abs() < 1e-9);
        let (long, short) = (cos_sin_deg(30.0), cos_sin_deg(120.0));
        for p in &top.positions {
            let [x, y, z] = p.map(f64::from);
            let (u, v) = (
                (x - 5.0) * long.0 + (z - 7.0) * long.1,
                (x - 5.0) * short.0 + (z - 7.0) * short.1,
            );
            let eaves = (5.0 - v.abs()) / 5.0;
            let ends = 0.5 + (10.0 - u.abs()) / 5.0;
            let expected = 10.0 + roof.rise * eaves.min(ends);
            assert!((y - expected).abs() < 1e-4, "{p:?} not {expected}");
        }
        // The ridge: 20 m less the two hips' 2.5 m run.
        let line = ridge(&top, roof.rise);
        assert!(
            (distance(line[0], line[line.len() - 1]) - 15.0).abs() < 1e-3,
            "{line:?}"
        );
        // Each gable wall: the gabled triangle (10 m × the rise) less its hipped top half
        // (5 m × half the rise), up to half the rise; none along the eaves.
        let area = wall_area(&walls);
        let end = 10.0 * roof.rise / 2.0 - 5.0 * (roof.rise / 2.0) / 2.0;
        assert!((area - 2.0 * end).abs() < 1e-3, "{area} not {}", 2.0 * end);
        for p in &walls.positions {
            assert!(f64::from(p[1]) <= 10.0 + roof.rise / 2.0 + 1e-4, "{p:?}");
        }
    }

    #[test]
    fn pyramids_and_domes_rise_over_the_centroid() {
        a_pyramid_over_the_hexagon("pyramidal");
        let octagon = regular([0.0, 0.0], 9.0, 8);
        let (roof, top, _) = built("dome", &octagon);
        assert!((roof.rise - 9.0).abs() < 1e-9);
        covers(&octagon, &roof, &top);
        assert_eq!(
            top.indices.len() / 3,
            8 * 4 * 2 - 8,
            "the top ring is a point"
        );
    }

    #[test]
    fn other_shapes_and_footprints_get_a_flat_roof() {
        let l_shape = L_SHAPE;
        let pentagon = regular([0.0, 0.0], 6.0, 5);
        let clockwise: Vec<[f64; 2]> = rectangle([0.0, 0.0], (8.0, 6.0), 0.0)
            .into_iter()
            .rev()
            .collect();
        assert_eq!(Roof::of("pyramidal", &l_shape), None);
        assert_eq!(Roof::of("hipped", &l_shape), None);
        assert_eq!(Roof::of("mansard", &l_shape), None);
        assert_eq!(Roof::of("half-hipped", &pentagon), None);
        assert_eq!(Roof::of("half-hipped", &l_shape), None);
        assert_eq!(Roof::of("saltbox", &pentagon), None);
        assert_eq!(Roof::of("gabled", &clockwise), None);
        assert!(Roof::of("pyramidal", &pentagon).is_some());
    }

    proptest::proptest! {
        #![proptest_config(crate::test_seed::proptest_config(64))]

        /// Hipped and mansard roofs on any convex footprint (points of an ellipse), and
        /// half-hipped ones on any four of them, cover it once, face up and stay between
        /// the eaves and the rise; only the half-hipped has walls, below half its rise.
        #[test]
        fn envelope_roofs_cover_any_convex_footprint_once(
            angles in proptest::collection::vec(0.0f64..360.0, 3..12),
            axes in (3.0f64..30.0, 3.0f64..30.0),
            turn in 0.0f64..180.0,
            centre in (-20.0f64..20.0, -20.0f64..20.0),
        ) {
            let mut angles = angles;
            angles.sort_by(f64::total_cmp);
            angles.dedup_by(|a, b| (*a - *b).abs() < 2.0);
            if angles.len() > 1 && angles[0] + 360.0 - angles[angles.len() - 1] < 2.0 {
                angles.pop();
            }
            proptest::prop_assume!(angles.len() >= 3);
            let (k, s) = cos_sin_deg(turn);
            let ring: Vec<[f64; 2]> = (angles.iter())
                .map(|&a| {
                    let (x, z) = cos_sin_deg(a);
                    let (x, z) = (axes.0 * x, axes.1 * z);
                    [centre.0 + x * k - z * s, centre.1 + x * s + z * k]
                })
                .collect();
            proptest::prop_assume!(signed_area(&ring) > 1.0);
            for shape in ["hipped", "mansard"] {
                let (roof, top, walls) = built(shape, &ring);
                covers(&ring, &roof, &top);
                proptest::prop_assert!(walls.indices.is_empty(), "{shape}");
            }
            if ring.len() == 4 {
                let (roof, top, walls) = built("half-hipped", &ring);
                covers(&ring, &roof, &top);
                for p in &walls.positions {
                    proptest::prop_assert!(f64::from(p[1]) <= 10.0 + roof.rise / 2.0 + 1e-3);
                }
            }
        }
    }
}
