//! The LiDAR stage: a rotating multi-beam scanner ray-cast against the prepared scene's
//! triangles through a [`bvh::Bvh`], with seeded range noise and dropout, intensities from
//! the materials' albedo and the incidence angle, and SemanticKITTI labels.
//!
//! Sensor frame (KITTI's velodyne): x forward (the camera's heading, levelled), y left,
//! z up, in metres, origin at the camera's eye. World: x east, y up, z south.

pub mod bvh;

use rand::{Rng, RngExt};
use rayon::prelude::*;

use crate::model::{CameraPose, ObjectKind};
use crate::render::PreparedScene;
use crate::spec::LidarSpec;
use bvh::{Bvh, Tri};

/// Bump when a scan's bytes change.
pub const VERSION: u32 = 2;

/// The weakest return a spec's scanner detects: albedo × cos(incidence) × the air's
/// attenuation below this is lost (dark, grazing or fogged-out surfaces).
pub const DETECTION_FLOOR: f64 = 0.005;

/// A scanner: beam elevations, azimuth steps per turn, range and its imperfections.
#[derive(Clone, Debug)]
pub struct Scanner {
    /// Beam elevations in degrees, top first.
    pub elevations: Vec<f64>,
    /// Azimuth steps per turn, starting straight ahead and turning left (counter-clockwise
    /// seen from above).
    pub azimuth_steps: u32,
    /// Returns beyond this many metres are lost.
    pub max_range: f64,
    /// Standard deviation of the Gaussian range noise, metres.
    pub noise: f64,
    /// Chance that a return is dropped.
    pub dropout: f64,
    /// Extinction coefficient of the air (fog, rain) per metre: the return's intensity is
    /// multiplied by `exp(-2·extinction·range)` (Beer–Lambert, there and back).
    pub extinction: f64,
    /// Returns whose intensity falls below this are lost.
    pub min_intensity: f64,
}

impl Scanner {
    /// The scanner a camera's `lidar` table describes, in air of `extinction` per metre
    /// (see [`Scanner::extinction`]); returns under [`DETECTION_FLOOR`] are lost.
    pub fn of(spec: &LidarSpec, extinction: f64) -> Scanner {
        Scanner {
            elevations: uniform_elevations(spec.beams, spec.top, spec.bottom),
            azimuth_steps: spec.columns,
            max_range: spec.range,
            noise: spec.noise,
            dropout: spec.dropout,
            extinction,
            min_intensity: DETECTION_FLOOR,
        }
    }

    /// The default pattern: 64 beams evenly from +2° down to −24.8° (an HDL-64E's span),
    /// 2048 azimuth steps, 120 m, 2 cm noise, 1 % dropout, clear air.
    pub fn default_64() -> Scanner {
        Scanner {
            elevations: uniform_elevations(64, 2.0, -24.8),
            azimuth_steps: 2048,
            max_range: 120.0,
            noise: 0.02,
            dropout: 0.01,
            extinction: 0.0,
            min_intensity: 0.0,
        }
    }
}

/// `beams` elevations evenly from `top` down to `bottom` degrees.
pub fn uniform_elevations(beams: u32, top: f64, bottom: f64) -> Vec<f64> {
    let step = if beams > 1 {
        (top - bottom) / f64::from(beams - 1)
    } else {
        0.0
    };
    (0..beams).map(|i| top - step * f64::from(i)).collect()
}

/// One return, in the sensor frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    pub xyz: [f32; 3],
    /// Albedo × cos(incidence) × the air's attenuation, in 0..=1.
    pub intensity: f32,
    /// SemanticKITTI label: semantic id | instance << 16.
    pub label: u32,
}

/// What a scan hits: triangles, their BVH, and per triangle its unit normal, albedo and
/// label.
pub struct Target {
    normals: Vec<[f32; 3]>,
    albedo: Vec<f32>,
    labels: Vec<u32>,
    bvh: Bvh,
}

impl Target {
    /// The target of `scene`'s triangles; `kinds` are its objects' kinds, by instance id − 1.
    pub fn of(scene: &PreparedScene, kinds: &[ObjectKind]) -> Target {
        Target::of_objects(scene, kinds, |_| true)
    }

    /// The target of the triangles of `scene`'s objects that `take` takes (by instance
    /// id): with moving traffic, what stands still once per path, and the moving objects
    /// as each frame has them.
    pub fn of_objects(
        scene: &PreparedScene,
        kinds: &[ObjectKind],
        take: impl Fn(u32) -> bool,
    ) -> Target {
        let t: Vec<_> = scene
            .triangles
            .iter()
            .filter(|t| take(t.instance))
            .collect();
        // A material's colour, times its texture's mean where it has one.
        let albedo = |m: u32| {
            let material = &scene.materials[m as usize];
            let mean = material
                .texture
                .map_or([1.0; 3], |t| scene.textures[t as usize].mean());
            let c: [f32; 3] = std::array::from_fn(|k| material.colour[k] * mean[k]);
            0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
        };
        Target::new(
            t.iter().map(|t| t.p).collect(),
            t.iter().map(|t| t.normal).collect(),
            t.iter().map(|t| albedo(t.material)).collect(),
            t.iter()
                .map(|t| label(kinds.get(t.instance as usize - 1).copied(), t.instance))
                .collect(),
        )
    }

    /// Triangles its hierarchy holds (long ones split into pieces).
    pub fn triangles(&self) -> usize {
        self.bvh.triangles()
    }

    /// A target of these triangles (and their normals, albedos and labels).
    pub fn new(
        tris: Vec<Tri>,
        normals: Vec<[f32; 3]>,
        albedo: Vec<f32>,
        labels: Vec<u32>,
    ) -> Target {
        let bvh = Bvh::build(&tris);
        Target {
            normals,
            albedo,
            labels,
            bvh,
        }
    }
}

/// SemanticKITTI's semantic id of a kind (0: unlabelled).
pub fn semantic_id(kind: ObjectKind) -> u32 {
    use ObjectKind::*;
    match kind {
        Car => 10,
        Bicycle => 11,
        Person => 30,
        Rider => 31,
        Road => 40,
        Marking => 60,
        // A block is paved ground between the streets (a map's squares too), as
        // Cityscapes' sidewalk 8 takes it; grass is ground.
        Sidewalk | Block => 48,
        Building | Text => 50,
        Tree => 70,
        Ground | Hills => 72,
        Lamp | SignPole | SignalPole | StreetPole => 80,
        Sign | TrafficLight => 81,
        Mesh => 99,
    }
}

/// SemanticKITTI's names of the semantic ids [`semantic_id`] gives (its
/// `semantic-kitti.yaml` `labels`).
pub const SEMANTIC_NAMES: [(u32, &str); 14] = [
    (0, "unlabeled"),
    (10, "car"),
    (11, "bicycle"),
    (30, "person"),
    (31, "bicyclist"),
    (40, "road"),
    (48, "sidewalk"),
    (50, "building"),
    (60, "lane-marking"),
    (70, "vegetation"),
    (72, "terrain"),
    (80, "pole"),
    (81, "traffic-sign"),
    (99, "other-object"),
];

/// The label of a point on instance `instance` of `kind`: the semantic id, with the
/// instance id (low 16 bits) above it for things (cars, bicycles, people, signs).
pub fn label(kind: Option<ObjectKind>, instance: u32) -> u32 {
    let Some(kind) = kind else { return 0 };
    let id = semantic_id(kind);
    let thing = matches!(
        kind,
        ObjectKind::Car
            | ObjectKind::Bicycle
            | ObjectKind::Person
            | ObjectKind::Rider
            | ObjectKind::Sign
            | ObjectKind::TrafficLight
    );
    if thing {
        id | (instance & 0xFFFF) << 16
    } else {
        id
    }
}

/// The sensor's axes in the world: forward (levelled heading), left, up.
pub fn sensor_axes(pose: &CameraPose) -> [[f64; 3]; 3] {
    let (fx, fz) = (pose.target[0] - pose.eye[0], pose.target[2] - pose.eye[2]);
    let n = libm::hypot(fx, fz).max(1e-12);
    let f = [fx / n, 0.0, fz / n];
    [f, [f[2], 0.0, -f[0]], [0.0, 1.0, 0.0]]
}

/// The sensor frame → the world at `pose`: a row-major 3 × 4 matrix `[R | t]`, R's
/// columns the sensor's axes ([`sensor_axes`]) and t the eye, so a point `p` of a scan is
/// at `R · p + t` in the world.
pub fn to_world(pose: &CameraPose) -> [[f64; 4]; 3] {
    let axes = sensor_axes(pose);
    std::array::from_fn(|row| [axes[0][row], axes[1][row], axes[2][row], pose.eye[row]])
}

/// One turn of `scanner` from `pose`'s eye against `target` and, with moving traffic,
/// the `moving` objects where the frame has them, column by column (azimuth step, then
/// beam top first); lost returns are left out. Noise and dropout draw from the stream
/// (`seed`, "lidar " + `name`, frame · 2²⁰ + column), so the bytes do not depend on the
/// thread count.
pub fn scan(
    target: &Target,
    moving: Option<&Target>,
    scanner: &Scanner,
    pose: &CameraPose,
    seed: u64,
    name: &str,
    frame: u64,
) -> Vec<Point> {
    let axes = sensor_axes(pose);
    let origin = pose.eye.map(|v| v as f32);
    let stream = format!("lidar {name}");
    let elev: Vec<(f64, f64)> = scanner
        .elevations
        .iter()
        .map(|e| (libm::cos(e.to_radians()), libm::sin(e.to_radians())))
        .collect();
    let columns: Vec<Vec<Point>> = (0..scanner.azimuth_steps)
        .into_par_iter()
        .map(|col| {
            let mut rng = crate::rng::stream(seed, &stream, (frame << 20) + u64::from(col));
            let a = std::f64::consts::TAU * f64::from(col) / f64::from(scanner.azimuth_steps);
            let (sa, ca) = libm::sincos(a);
            // The slot the beam above hit: the next beam often hits it (or its
            // neighbour) too, and then searches only nearer than it.
            let mut hint = None;
            elev.iter()
                .filter_map(|&(ce, se)| {
                    let local = [ce * ca, ce * sa, se];
                    let world: [f64; 3] =
                        std::array::from_fn(|k| (0..3).map(|j| axes[j][k] * local[j]).sum());
                    let noise = gaussian(&mut rng) * scanner.noise;
                    let drop = rng.random::<f64>() < scanner.dropout;
                    let dir = world.map(|v| v as f32);
                    let still = target
                        .bvh
                        .closest(origin, dir, scanner.max_range as f32, hint);
                    if let Some(hit) = &still {
                        hint = Some(hit.slot);
                    }
                    // What moves, nearer than what stands still.
                    let reach = still.as_ref().map_or(scanner.max_range as f32, |h| h.t);
                    let moved =
                        moving.and_then(|m| Some((m, m.bvh.closest(origin, dir, reach, None)?)));
                    let (target, hit) = moved.or(still.map(|h| (target, h)))?;
                    let n = target.normals[hit.triangle as usize];
                    let cos = (n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2]).abs() as f64;
                    let range = f64::from(hit.t);
                    let air = libm::exp(-2.0 * scanner.extinction * range);
                    let intensity = f64::from(target.albedo[hit.triangle as usize]) * cos * air;
                    if drop || intensity < scanner.min_intensity {
                        return None;
                    }
                    let r = (range + noise).max(0.0);
                    Some(Point {
                        xyz: local.map(|v| (v * r) as f32),
                        intensity: intensity.clamp(0.0, 1.0) as f32,
                        label: target.labels[hit.triangle as usize],
                    })
                })
                .collect()
        })
        .collect();
    columns.concat()
}

/// A standard normal draw (Box–Muller).
fn gaussian(rng: &mut impl Rng) -> f64 {
    let u1: f64 = rng.random::<f64>().max(1e-300);
    let u2 = rng.random::<f64>();
    (-2.0 * libm::log(u1)).sqrt() * libm::cos(std::f64::consts::TAU * u2)
}

/// The KITTI `.bin` bytes: x, y, z, intensity as little-endian float32 per point.
pub fn velodyne_bytes(points: &[Point]) -> Vec<u8> {
    points
        .iter()
        .flat_map(|p| [p.xyz[0], p.xyz[1], p.xyz[2], p.intensity])
        .flat_map(f32::to_le_bytes)
        .collect()
}

/// The SemanticKITTI `.label` bytes: one little-endian uint32 per point.
pub fn label_bytes(points: &[Point]) -> Vec<u8> {
    points.iter().flat_map(|p| p.label.to_le_bytes()).collect()
}

/// A binary little-endian PLY of the points: float x, y, z, intensity and uint label per
/// vertex, in the sensor frame.
pub fn ply_bytes(points: &[Point]) -> Vec<u8> {
    let header = format!(
        "ply\nformat binary_little_endian 1.0\ncomment cityspec LiDAR scan, KITTI velodyne \
         frame (x forward, y left, z up, metres)\nelement vertex {}\nproperty float x\n\
         property float y\nproperty float z\nproperty float intensity\n\
         property uint label\nend_header\n",
        points.len()
    );
    let mut out = Vec::with_capacity(header.len() + points.len() * 20);
    out.extend_from_slice(header.as_bytes());
    for p in points {
        for v in [p.xyz[0], p.xyz[1], p.xyz[2], p.intensity] {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out.extend_from_slice(&p.label.to_le_bytes());
    }
    out
}

#[cfg(test)]
mod tests;
