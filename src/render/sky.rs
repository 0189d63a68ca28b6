//! Sun + turbidity → [`Sky`]: the radiance of the sky in every direction (Preetham, Shirley
//! and Smits 1999: the Perez luminance and chromaticity distributions with their
//! turbidity fits), a sun disk, a tint of dusk and dawn near the horizon, and the sky's
//! irradiance on an upward surface (the scene's ambient light).
//!
//! The sky is tabulated once per lighting on a 64 × 64 octahedral map of the upper
//! hemisphere and read bilinearly, so a sky pixel costs a few multiplications and no
//! transcendental function. Table values come from the pure-Rust `libm` (`exp`, `tan`,
//! `acos`): the same bits on every machine. Units: 1.0 is the radiance of a white
//! surface lit by a unit light (see [`super::Lighting`]).

use serde::{Deserialize, Serialize};

use super::Sun;

/// Table side of the octahedral map.
const N: usize = 64;
/// Angular radius of the drawn sun disk, degrees (the real one is 0.27°; a little larger
/// so it shows at street-camera resolutions).
const DISK_DEGREES: f64 = 0.4;
/// Radiance of the sun disk per unit of sun colour: far above white, so it saturates.
const DISK_GAIN: f32 = 60.0;
/// Kilocandela per m² → this renderer's units (and a photographic gain: frames are exposed
/// for the ground, the sky shows bright).
const SCALE: f64 = 1.8 / 31.8;

/// A tabulated sky. `Flat` skies (night) have one colour everywhere.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Sky {
    /// N × N radiances over the octahedral square, or one colour.
    table: Vec<[f32; 3]>,
    sun: [f64; 3],
    cos_disk: f64,
    disk: [f32; 3],
    /// Irradiance on an upward surface from the sky ÷ π: the ambient light from above.
    pub ambient_up: [f32; 3],
}

impl Sky {
    /// The same colour in every direction, no sun disk.
    pub fn flat(colour: [f32; 3]) -> Sky {
        Sky {
            table: vec![colour],
            sun: [0.0, 1.0, 0.0],
            cos_disk: 2.0,
            disk: [0.0; 3],
            ambient_up: colour,
        }
    }

    /// The daylight sky for `sun` and `turbidity`, blended into `night` as the sun sinks
    /// below the horizon; `sun_colour` is the direct sun (for the disk and the dusk tint).
    pub fn daylight(sun: &Sun, turbidity: f64, sun_colour: [f32; 3], night: [f32; 3]) -> Sky {
        let s = sun.direction();
        let t = turbidity.clamp(1.7, 10.0);
        // Preetham is fitted for a sun above the horizon: below it the shape of the last
        // light is kept and faded out towards the night sky.
        let theta_s = (90.0 - sun.elevation.max(0.5)).to_radians();
        let perez = Perez::new(t, theta_s);
        let day = smoothstep(-7.0, 1.0, sun.elevation) as f32;
        // Dusk tint: the colour of the low sun, normalised to luminance 1.
        let low = 1.0 - smoothstep(4.0, 20.0, sun.elevation);
        let tint = {
            let c = [
                f64::from(sun_colour[0]) + 0.02,
                f64::from(sun_colour[1]) + 0.01,
                f64::from(sun_colour[2]) + 0.004,
            ];
            let l = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
            c.map(|v| v / l)
        };
        let radiance = |d: [f64; 3]| -> [f32; 3] {
            let up = d[1].max(0.0);
            let cos_gamma = (d[0] * s[0] + d[1] * s[1] + d[2] * s[2]).clamp(-1.0, 1.0);
            let mut c = perez.colour(up, cos_gamma);
            let w = low * powi(1.0 - up, 6) * (0.25 + 0.75 * 0.5 * (1.0 + cos_gamma));
            let l = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
            for k in 0..3 {
                c[k] = c[k] * (1.0 - w) + l * tint[k] * w;
            }
            std::array::from_fn(|k| c[k] as f32 * day + night[k] * (1.0 - day))
        };
        let table: Vec<[f32; 3]> = (0..N * N)
            .map(|i| radiance(octahedral_direction(i % N, i / N)))
            .collect();
        // Cosine-weighted integral over the hemisphere, in a fixed order.
        let (rings, segments) = (16, 32);
        let mut sum = [0f64; 3];
        for i in 0..rings {
            let theta = (i as f64 + 0.5) / rings as f64 * std::f64::consts::FRAC_PI_2;
            let (st, ct) = (libm::sin(theta), libm::cos(theta));
            for j in 0..segments {
                let phi = (j as f64 + 0.5) / segments as f64 * std::f64::consts::TAU;
                let d = [st * libm::cos(phi), ct, st * libm::sin(phi)];
                let c = radiance(d);
                for k in 0..3 {
                    sum[k] += f64::from(c[k]) * ct * st;
                }
            }
        }
        // ∫ L cosθ dω / π with dω = sinθ dθ dφ.
        let cell = (std::f64::consts::FRAC_PI_2 / rings as f64)
            * (std::f64::consts::TAU / segments as f64)
            / std::f64::consts::PI;
        Sky {
            table,
            sun: s,
            cos_disk: libm::cos(DISK_DEGREES.to_radians()),
            disk: sun_colour.map(|c| c * DISK_GAIN),
            ambient_up: sum.map(|v| (v * cell) as f32),
        }
    }

    /// The sky's mean colour just above the horizon, over eight compass directions: the
    /// colour fog and grey skies fade to.
    pub fn horizon(&self) -> [f32; 3] {
        let r = std::f64::consts::FRAC_1_SQRT_2;
        let mut sum = [0f32; 3];
        for [x, z] in [
            [1.0, 0.0],
            [r, r],
            [0.0, 1.0],
            [-r, r],
            [-1.0, 0.0],
            [-r, -r],
            [0.0, -1.0],
            [r, -r],
        ] {
            // 2° above the horizon (sin 2° ≈ 0.0349), normalised.
            let (y, n) = (0.0349, (1.0f64 + 0.0349 * 0.0349).sqrt());
            let c = self.radiance([x / n, y / n, z / n]);
            sum = [sum[0] + c[0], sum[1] + c[1], sum[2] + c[2]];
        }
        sum.map(|c| c / 8.0)
    }

    /// Radiance seen in direction `d` (unit length).
    #[inline]
    pub(crate) fn radiance(&self, d: [f64; 3]) -> [f32; 3] {
        if self.table.len() == 1 {
            return self.table[0];
        }
        let y = d[1].max(0.0);
        let s = d[0].abs() + y + d[2].abs();
        let (u, v) = if s > 0.0 {
            (d[0] / s, d[2] / s)
        } else {
            (0.0, 0.0)
        };
        // The diamond |u| + |v| ≤ 1 turned into the square [−1, 1]².
        let (a, b) = (u + v, u - v);
        let fx = ((a + 1.0) * 0.5 * (N - 1) as f64).clamp(0.0, (N - 1) as f64);
        let fy = ((b + 1.0) * 0.5 * (N - 1) as f64).clamp(0.0, (N - 1) as f64);
        let (x0, y0) = ((fx as usize).min(N - 2), (fy as usize).min(N - 2));
        let (tx, ty) = ((fx - x0 as f64) as f32, (fy - y0 as f64) as f32);
        let at = |x: usize, y: usize| self.table[y * N + x];
        let (c00, c10, c01, c11) = (
            at(x0, y0),
            at(x0 + 1, y0),
            at(x0, y0 + 1),
            at(x0 + 1, y0 + 1),
        );
        let mut c: [f32; 3] = std::array::from_fn(|k| {
            let top = c00[k] + (c10[k] - c00[k]) * tx;
            let bottom = c01[k] + (c11[k] - c01[k]) * tx;
            top + (bottom - top) * ty
        });
        let cos_sun = d[0] * self.sun[0] + d[1] * self.sun[1] + d[2] * self.sun[2];
        if cos_sun > self.cos_disk {
            for (c, d) in c.iter_mut().zip(self.disk) {
                *c += d;
            }
        }
        c
    }
}

/// The direction at the centre of table cell `(x, y)`.
fn octahedral_direction(x: usize, y: usize) -> [f64; 3] {
    let a = x as f64 / (N - 1) as f64 * 2.0 - 1.0;
    let b = y as f64 / (N - 1) as f64 * 2.0 - 1.0;
    let (u, v) = ((a + b) * 0.5, (a - b) * 0.5);
    let y = (1.0 - u.abs() - v.abs()).max(0.0);
    let len = (u * u + y * y + v * v).sqrt();
    [u / len, y / len, v / len]
}

/// Preetham's model for one sun: the Perez coefficients of Y, x and y, and the zenith
/// values.
struct Perez {
    coef: [[f64; 5]; 3],
    zenith: [f64; 3],
    /// F(0, θs) per channel: the distribution at the zenith.
    at_zenith: [f64; 3],
}

impl Perez {
    fn new(t: f64, theta_s: f64) -> Perez {
        let coef = [
            [
                0.1787 * t - 1.4630,
                -0.3554 * t + 0.4275,
                -0.0227 * t + 5.3251,
                0.1206 * t - 2.5771,
                -0.0670 * t + 0.3703,
            ],
            [
                -0.0193 * t - 0.2592,
                -0.0665 * t + 0.0008,
                -0.0004 * t + 0.2125,
                -0.0641 * t - 0.8989,
                -0.0033 * t + 0.0452,
            ],
            [
                -0.0167 * t - 0.2608,
                -0.0950 * t + 0.0092,
                -0.0079 * t + 0.2102,
                -0.0441 * t - 1.6537,
                -0.0109 * t + 0.0529,
            ],
        ];
        let chi = (4.0 / 9.0 - t / 120.0) * (std::f64::consts::PI - 2.0 * theta_s);
        let big_y = (4.0453 * t - 4.9710) * libm::tan(chi) - 0.2155 * t + 2.4192;
        let (t1, t2, t3) = (theta_s, theta_s * theta_s, theta_s * theta_s * theta_s);
        let poly = |m: [[f64; 4]; 3]| {
            let row = |r: [f64; 4]| r[0] * t3 + r[1] * t2 + r[2] * t1 + r[3];
            t * t * row(m[0]) + t * row(m[1]) + row(m[2])
        };
        let x = poly([
            [0.00166, -0.00375, 0.00209, 0.0],
            [-0.02903, 0.06377, -0.03202, 0.00394],
            [0.11693, -0.21196, 0.06052, 0.25886],
        ]);
        let y = poly([
            [0.00275, -0.00610, 0.00317, 0.0],
            [-0.04214, 0.08970, -0.04153, 0.00516],
            [0.15346, -0.26756, 0.06670, 0.26688],
        ]);
        let cos_s = libm::cos(theta_s);
        let at_zenith = coef.map(|c| f(c, 1.0, cos_s));
        Perez {
            coef,
            zenith: [big_y.max(0.0), x, y],
            at_zenith,
        }
    }

    /// Linear RGB (this renderer's units) of the sky at `cos θ = up`, `cos γ = cos_gamma`.
    fn colour(&self, up: f64, cos_gamma: f64) -> [f64; 3] {
        let v: [f64; 3] = std::array::from_fn(|k| {
            self.zenith[k] * f(self.coef[k], up, cos_gamma) / self.at_zenith[k]
        });
        let (big_y, x, y) = (v[0].max(0.0) * SCALE, v[1], v[2].max(1e-4));
        let big_x = x / y * big_y;
        let big_z = (1.0 - x - y) / y * big_y;
        [
            (3.2406 * big_x - 1.5372 * big_y - 0.4986 * big_z).max(0.0),
            (-0.9689 * big_x + 1.8758 * big_y + 0.0415 * big_z).max(0.0),
            (0.0557 * big_x - 0.2040 * big_y + 1.0570 * big_z).max(0.0),
        ]
    }
}

/// Perez: `(1 + A e^(B / cos θ)) (1 + C e^(D γ) + E cos² γ)`.
fn f(c: [f64; 5], cos_theta: f64, cos_gamma: f64) -> f64 {
    let gamma = libm::acos(cos_gamma.clamp(-1.0, 1.0));
    (1.0 + c[0] * libm::exp(c[1] / cos_theta.max(0.01)))
        * (1.0 + c[2] * libm::exp(c[3] * gamma) + c[4] * cos_gamma * cos_gamma)
}

fn powi(x: f64, n: u32) -> f64 {
    (0..n).fold(1.0, |p, _| p * x)
}

/// 0 below `a`, 1 above `b`, smooth between.
pub(crate) fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sun(elevation: f64, azimuth: f64) -> Sun {
        Sun {
            elevation,
            azimuth,
            hour: None,
        }
    }

    #[test]
    fn noon_sky_is_blue_above_and_bright_at_the_horizon() {
        let sky = Sky::daylight(&sun(60.0, 180.0), 3.0, [1.0; 3], [0.0; 3]);
        let zenith = sky.radiance([0.0, 1.0, 0.0]);
        assert!(zenith[2] > zenith[0] * 1.3, "blue zenith {zenith:?}");
        // Haze: the horizon is whiter than the zenith; towards the sun it is brighter.
        let north = sky.radiance([0.0, 0.02, -1.0]);
        assert!(
            north[2] / north[0] < zenith[2] / zenith[0],
            "{north:?} vs {zenith:?}"
        );
        let south = sky.radiance([0.0, 0.02, 1.0]);
        assert!(south[1] > zenith[1], "{south:?} vs {zenith:?}");
        let disk = sky.radiance(sun(60.0, 180.0).direction());
        assert!(disk[0] > 10.0, "sun disk {disk:?}");
        assert!(
            sky.ambient_up.iter().all(|&a| a > 0.05 && a < 1.0),
            "{:?}",
            sky.ambient_up
        );
    }

    #[test]
    fn dusk_is_warm_towards_the_sun_and_night_is_the_night_colour() {
        let low = [1.0, 0.35, 0.05];
        let sky = Sky::daylight(&sun(2.0, 270.0), 3.0, low, [0.0; 3]);
        let west = sky.radiance([-0.999, 0.04, 0.0]);
        assert!(west[0] > west[2], "warm dusk horizon {west:?}");
        let night = [0.005, 0.007, 0.02];
        let dark = Sky::daylight(&sun(-20.0, 0.0), 3.0, [0.0; 3], night);
        assert_eq!(dark.radiance([0.3, 0.5, 0.1]), night);
    }
}
