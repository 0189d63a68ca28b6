//! Layout size + seed → the land beyond the city: `fields` (flat grass reaching out to
//! [`FIELDS_REACH`]) and `hills` (a ring of wooded hills standing in them), so a street
//! running to the city's edge ends in a line of hills, not in a flat plain under an empty
//! sky, and the overview shows countryside round the city.
//!
//! The ring is drawn without trigonometry, as the overview orbit is: the edge of the
//! `ground` quad (the layout grown by [`GROUND_MARGIN`]) is sampled every [`STEP`] metres
//! or less along each side, corners included, and each sample `q` gives the ray `u` from
//! the layout's centre `c` through it. Along that ray, at distances from `c`:
//!
//! | from | to | what |
//! |---|---|---|
//! | `q` | `r0` | fields (flat, y = 0), meeting the ground quad's edge exactly |
//! | `r0` | `r0 + depth` | the hills' front slope, up to `height` at the crest |
//! | `r0 + depth` | `r0 + 2 depth` | the back slope, down to y = 0 |
//! | `r0 + 2 depth` | `+` [`FIELDS_REACH`] | fields again |
//!
//! `r0` is the distance from `c` to the ground's corners plus [`FOOT_CLEARANCE`]: the hills
//! stand clear of the ground quad and of the overview orbit (the circle through the
//! layout's corners) all round. `height` ([`HEIGHTS`]) and `depth` ([`DEPTHS`]) vary
//! smoothly round the ring: seeded values at [`KNOTS`] points spaced evenly along the
//! samples, eased between with a smoothstep (polynomials only, so the same bits on every
//! platform), from `crate::rng::stream(seed, "hills", 0)`.
//!
//! Both objects are flat-shaded triangles whose fronts face up. The renderer casts no
//! shadows from them ([`crate::render`] leaves the ground and the hills out of its shadow
//! map: they stand beyond everything they could shade).

use rand::RngExt;

use super::GROUND_MARGIN;
use super::procedural::{GRASS_TILE, WOODS_TILE};
use crate::model::geometry::{cross, dot, sub};
use crate::model::{Mesh, ObjectKind, ParsedLayout, SceneObject};

/// Longest step between two ring samples along the ground's edge, metres.
pub const STEP: f64 = 16.0;
/// Gap between the ground quad's corners and the hills' foot, metres.
pub const FOOT_CLEARANCE: f64 = 20.0;
/// Crest heights above the fields, metres.
pub const HEIGHTS: [f64; 2] = [20.0, 70.0];
/// Foot-to-crest distance across the ring, metres.
pub const DEPTHS: [f64; 2] = [70.0, 160.0];
/// Seeded control points round the ring.
pub const KNOTS: usize = 24;
/// How far the fields reach behind the hills, metres.
pub const FIELDS_REACH: f64 = 1200.0;

/// The `fields` (class ground, material `grass`) and `hills` (class hills, material
/// `woods`) around `layout`; none for an empty layout or a bad metres-per-pixel.
pub fn horizon_objects(
    layout: &ParsedLayout,
    mpp: f64,
    seed: u64,
    grass: u32,
    woods: u32,
) -> Vec<SceneObject> {
    let (w, h) = (
        f64::from(layout.width) * mpp,
        f64::from(layout.height) * mpp,
    );
    if !(w > 0.0 && h > 0.0 && w.is_finite() && h.is_finite()) {
        return Vec::new();
    }
    let centre = [w / 2.0, h / 2.0];
    let half = [w / 2.0 + GROUND_MARGIN, h / 2.0 + GROUND_MARGIN];
    let r0 = (half[0] * half[0] + half[1] * half[1]).sqrt() + FOOT_CLEARANCE;
    let edge = ground_edge(half);
    let shape = ring_shape(edge.len(), seed);
    let mut fields = Triangles::new(grass, GRASS_TILE);
    let mut hills = Triangles::new(woods, WOODS_TILE);
    for i in 0..edge.len() {
        let j = (i + 1) % edge.len();
        // Per sample: the rings of points across it, inner to outer.
        let across = |k: usize| -> [[f64; 3]; 5] {
            let q = edge[k];
            let len = (q[0] * q[0] + q[1] * q[1]).sqrt();
            let u = [q[0] / len, q[1] / len];
            let (height, depth) = shape[k];
            let at = |r: f64, y: f64| [centre[0] + u[0] * r, y, centre[1] + u[1] * r];
            [
                [centre[0] + q[0], 0.0, centre[1] + q[1]],
                at(r0, 0.0),
                at(r0 + depth, height),
                at(r0 + 2.0 * depth, 0.0),
                at(r0 + 2.0 * depth + FIELDS_REACH, 0.0),
            ]
        };
        let (a, b) = (across(i), across(j));
        for band in 0..4 {
            let target = if band == 0 || band == 3 {
                &mut fields
            } else {
                &mut hills
            };
            target.quad([a[band], b[band], b[band + 1], a[band + 1]]);
        }
    }
    vec![
        fields.object(ObjectKind::Ground, "fields"),
        hills.object(ObjectKind::Hills, "hills"),
    ]
}

/// Points round the edge of the rectangle `[-half, half]` (x, z), anticlockwise seen from
/// above starting at the north-west corner, every corner included, at most [`STEP`] apart.
fn ground_edge(half: [f64; 2]) -> Vec<[f64; 2]> {
    let corners = [
        [-half[0], -half[1]],
        [-half[0], half[1]],
        [half[0], half[1]],
        [half[0], -half[1]],
    ];
    let mut points = Vec::new();
    for (k, from) in corners.iter().enumerate() {
        let to = corners[(k + 1) % 4];
        let d = sub2(to, *from);
        let steps = ((d[0].abs() + d[1].abs()) / STEP).ceil().max(1.0) as usize;
        for s in 0..steps {
            let t = s as f64 / steps as f64;
            points.push([from[0] + d[0] * t, from[1] + d[1] * t]);
        }
    }
    points
}

/// `(height, depth)` at each of `samples` points round the ring: seeded knots eased
/// between with a smoothstep, wrapping round.
fn ring_shape(samples: usize, seed: u64) -> Vec<(f64, f64)> {
    let mut rng = crate::rng::stream(seed, "hills", 0);
    let mut draw = |range: [f64; 2]| rng.random_range(range[0]..range[1]);
    let knots: Vec<(f64, f64)> = (0..KNOTS).map(|_| (draw(HEIGHTS), draw(DEPTHS))).collect();
    (0..samples)
        .map(|i| {
            let x = i as f64 * KNOTS as f64 / samples as f64;
            let k = x as usize % KNOTS;
            let t = x - x.floor();
            let s = t * t * (3.0 - 2.0 * t);
            let (a, b) = (knots[k], knots[(k + 1) % KNOTS]);
            (a.0 + (b.0 - a.0) * s, a.1 + (b.1 - a.1) * s)
        })
        .collect()
}

fn sub2(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// Flat-shaded triangles of one material, fronts up, uvs from the ground plan.
struct Triangles {
    mesh: Mesh,
    tile: f64,
}

impl Triangles {
    fn new(material: u32, tile: f64) -> Triangles {
        Triangles {
            mesh: Mesh {
                material,
                ..Mesh::default()
            },
            tile,
        }
    }

    /// The quad `p` as two triangles (`p[0] p[1] p[2]` and `p[0] p[2] p[3]`).
    fn quad(&mut self, p: [[f64; 3]; 4]) {
        self.triangle([p[0], p[1], p[2]]);
        self.triangle([p[0], p[2], p[3]]);
    }

    /// One triangle, wound so that its normal points up; skipped when degenerate.
    fn triangle(&mut self, mut p: [[f64; 3]; 3]) {
        let mut n = cross(sub(p[1], p[0]), sub(p[2], p[0]));
        let len = dot(n, n).sqrt();
        if len.is_nan() || len <= 1e-9 {
            return;
        }
        if n[1] < 0.0 {
            p.swap(1, 2);
            n = n.map(|v| -v);
        }
        let base = self.mesh.positions.len() as u32;
        for v in p {
            self.mesh.positions.push(v.map(|c| c as f32));
            self.mesh.normals.push(n.map(|c| (c / len) as f32));
            self.mesh
                .uvs
                .push([(v[0] / self.tile) as f32, (v[2] / self.tile) as f32]);
        }
        self.mesh
            .indices
            .extend_from_slice(&[base, base + 1, base + 2]);
    }

    fn object(self, kind: ObjectKind, name: &str) -> SceneObject {
        SceneObject {
            name: name.to_owned(),
            kind,
            class: kind.name().to_owned(),
            meshes: vec![self.mesh],
        }
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;

    use super::*;

    /// A layout of `width × height` pixels with nothing in it: the horizon only reads its size.
    fn generated(width: u32, height: u32) -> ParsedLayout {
        ParsedLayout {
            width,
            height,
            blocks: Vec::new(),
            roads: Vec::new(),
        }
    }

    fn hills_of(seed: u64) -> (ParsedLayout, Vec<SceneObject>) {
        let layout = generated(384, 256);
        let objects = horizon_objects(&layout, 0.5, seed, 0, 1);
        (layout, objects)
    }

    /// Every point of `object` as f64.
    fn points(object: &SceneObject) -> impl Iterator<Item = [f64; 3]> + '_ {
        object.meshes[0].positions.iter().map(|p| p.map(f64::from))
    }

    /// The hills ring the city clear of the ground quad and of the overview orbit, rise to
    /// their seeded heights, and the fields meet the ground's edge with no gap: every
    /// ground-edge sample is a fields vertex.
    #[test]
    fn hills_ring_the_city_clear_of_the_ground_and_the_orbit() {
        let (layout, objects) = hills_of(7);
        let [fields, hills] = &objects[..] else {
            panic!("{} objects", objects.len())
        };
        assert_eq!(
            (fields.name.as_str(), fields.kind),
            ("fields", ObjectKind::Ground)
        );
        assert_eq!(
            (hills.name.as_str(), hills.kind),
            ("hills", ObjectKind::Hills)
        );
        let (w, h) = (
            f64::from(layout.width) * 0.5,
            f64::from(layout.height) * 0.5,
        );
        let c = [w / 2.0, h / 2.0];
        let orbit = (w * w + h * h).sqrt() / 2.0;
        let ground = [w / 2.0 + GROUND_MARGIN, h / 2.0 + GROUND_MARGIN];
        let corner = (ground[0] * ground[0] + ground[1] * ground[1]).sqrt();
        let mut top: f64 = 0.0;
        for p in points(hills) {
            let r = ((p[0] - c[0]).powi(2) + (p[2] - c[1]).powi(2)).sqrt();
            assert!(r >= corner + FOOT_CLEARANCE - 1e-3, "{p:?} at {r} m");
            assert!(r > orbit + GROUND_MARGIN, "{p:?} at {r} m");
            assert!((0.0..=HEIGHTS[1]).contains(&p[1]), "{p:?}");
            top = top.max(p[1]);
        }
        assert!(top >= HEIGHTS[0], "highest crest {top} m");
        assert!(points(fields).all(|p| p[1] == 0.0));
        let fields: BTreeSet<[u64; 2]> = points(fields)
            .map(|p| [p[0].to_bits(), p[2].to_bits()])
            .collect();
        for q in ground_edge(ground) {
            let at = [(c[0] + q[0]) as f32, (c[1] + q[1]) as f32].map(|v| f64::from(v).to_bits());
            assert!(
                fields.contains(&at),
                "ground edge {q:?} not met by the fields"
            );
        }
    }

    /// Fronts face up; the seed changes the skyline; the same seed gives the same bytes.
    #[test]
    fn hills_face_up_and_follow_the_seed() {
        let (_, a) = hills_of(7);
        for object in &a {
            assert!(
                object.meshes[0].normals.iter().all(|n| n[1] > 0.0),
                "{}",
                object.name
            );
        }
        assert_eq!(a, hills_of(7).1);
        assert_ne!(a[1], hills_of(8).1[1]);
        let empty = generated(0, 0);
        assert!(horizon_objects(&empty, 0.5, 7, 0, 1).is_empty());
        assert!(horizon_objects(&generated(64, 64), f64::NAN, 7, 0, 1).is_empty());
    }

    /// The ring shape eases between its knots: heights and depths stay in range and change
    /// little between neighbouring samples.
    #[test]
    fn ring_shape_is_smooth_and_in_range() {
        let shape = ring_shape(400, 3);
        for (k, &(height, depth)) in shape.iter().enumerate() {
            assert!((HEIGHTS[0]..=HEIGHTS[1]).contains(&height), "{k}: {height}");
            assert!((DEPTHS[0]..=DEPTHS[1]).contains(&depth), "{k}: {depth}");
            let (h2, d2) = shape[(k + 1) % shape.len()];
            assert!(
                (h2 - height).abs() < 6.0 && (d2 - depth).abs() < 15.0,
                "{k}"
            );
        }
    }
}
