//! 3-vectors as arrays → their difference, dot and cross products, and unit length.
//!
//! One set for every stage (mesh building, cameras, rendering, the sensor), generic over
//! `f32` and `f64` so that each caller keeps its precision. The sums are written out in one
//! fixed order and never fused, so a result has the same bits everywhere.

use std::ops::{Add, Mul, Neg, Sub};

/// World up (+y).
pub const UP: [f64; 3] = [0.0, 1.0, 0.0];

/// `a − b`.
pub fn sub<T: Copy + Sub<Output = T>>(a: [T; 3], b: [T; 3]) -> [T; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `−a`.
pub fn neg<T: Copy + Neg<Output = T>>(a: [T; 3]) -> [T; 3] {
    [-a[0], -a[1], -a[2]]
}

/// `a · b`, summed x, y, z in that order.
pub fn dot<T: Copy + Add<Output = T> + Mul<Output = T>>(a: [T; 3], b: [T; 3]) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a × b` (right-handed).
pub fn cross<T: Copy + Sub<Output = T> + Mul<Output = T>>(a: [T; 3], b: [T; 3]) -> [T; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The unit vector along `a`, or `None` if it is (nearly) zero or not finite.
pub fn normalize(a: [f64; 3]) -> Option<[f64; 3]> {
    let len2 = dot(a, a);
    if !len2.is_finite() || len2 <= 1e-24 {
        return None;
    }
    let len = len2.sqrt();
    Some([a[0] / len, a[1] / len, a[2] / len])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn products_of_the_axes() {
        let x = [1.0, 0.0, 0.0];
        let z = [0.0, 0.0, 1.0];
        assert_eq!(cross(z, x), UP);
        assert_eq!(cross([1.0f32, 0.0, 0.0], [0.0, 1.0, 0.0]), [0.0, 0.0, 1.0]);
        assert_eq!(dot(sub([3.0, 4.0, 0.0], neg(x)), x), 4.0);
        assert_eq!(normalize([0.0, 3.0, 4.0]), Some([0.0, 0.6, 0.8]));
        assert_eq!(normalize([0.0; 3]), None);
        assert_eq!(normalize([f64::NAN, 0.0, 0.0]), None);
    }
}
