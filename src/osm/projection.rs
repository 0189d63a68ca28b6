//! Degrees → metres: a local equirectangular projection on the WGS 84 ellipsoid.
//!
//! Around the origin `(lat₀, lon₀)` (the box's centre), `x = N·cos lat₀ · Δlon` and
//! `z = −M · Δlat` (radians), where `N` and `M` are the ellipsoid's radii of curvature at
//! lat₀ (prime vertical and meridian). Lengths along both axes are exact at the origin; a
//! point `d` metres north or south of it has east–west lengths off by about
//! `tan lat₀ · d / 6,370 km` (0.03 % at 1 km from the centre of a city at 60° N), so a box
//! of a few kilometres keeps lengths and areas well within the 2 % the map is checked to.
//! Straight lines in degrees stay straight, so the box is a rectangle in metres.

use crate::model::geometry::trig::cos_sin_deg;

/// WGS 84 semi-major axis, metres.
const A: f64 = 6_378_137.0;
/// WGS 84 flattening.
const F: f64 = 1.0 / 298.257_223_563;

/// The projection around one origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection {
    /// `(lat, lon)` of the origin, degrees.
    pub origin: [f64; 2],
    /// Metres per degree of longitude and of latitude at the origin.
    pub metres_per_degree: [f64; 2],
}

impl Projection {
    /// The projection around `(lat, lon)` in degrees.
    pub fn new(lat: f64, lon: f64) -> Projection {
        let e2 = F * (2.0 - F);
        let (cos, sin) = cos_sin_deg(lat);
        let w = (1.0 - e2 * sin * sin).sqrt();
        let n = A / w;
        let m = A * (1.0 - e2) / (w * w * w);
        let per_radian = std::f64::consts::PI / 180.0;
        Projection {
            origin: [lat, lon],
            metres_per_degree: [n * cos * per_radian, m * per_radian],
        }
    }

    /// `[x, z]` in metres (x east, z south) of `(lat, lon)` in degrees.
    pub fn project(&self, lat: f64, lon: f64) -> [f64; 2] {
        [
            (lon - self.origin[1]) * self.metres_per_degree[0],
            -(lat - self.origin[0]) * self.metres_per_degree[1],
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_degree_is_the_ellipsoids_arc() {
        // At the equator a degree of longitude is a · π / 180 = 111,319.49 m and a degree
        // of latitude M(0) · π / 180 = 110,574.28 m; at 60° N, 55,800.00 m and 111,412.29 m
        // (the tables of WGS 84's arc lengths give 111.320 / 110.574 and 55.800 / 111.412 km).
        let eq = Projection::new(0.0, 0.0).metres_per_degree;
        assert!((eq[0] - 111_319.49).abs() < 0.01, "{eq:?}");
        assert!((eq[1] - 110_574.28).abs() < 0.01, "{eq:?}");
        let north = Projection::new(60.0, 25.0).metres_per_degree;
        assert!((north[0] - 55_800.00).abs() < 0.01, "{north:?}");
        assert!((north[1] - 111_412.29).abs() < 0.01, "{north:?}");
    }

    #[test]
    fn east_is_x_and_north_is_minus_z() {
        let p = Projection::new(60.17, 24.94);
        assert_eq!(p.project(60.17, 24.94), [0.0, 0.0]);
        let [x, z] = p.project(60.171, 24.941);
        assert!(x > 55.0 && x < 56.0 && z < -111.0 && z > -112.0, "{x} {z}");
    }
}
