//! Degrees → (cos, sin) and tan(θ/2), the same bits on every platform.
//!
//! [`cos_sin_deg`] is `libm`'s `sincos` (pure Rust, correctly rounded to within an ulp) of
//! the angle in radians: the one sine and cosine of the crate's geometry, cameras and
//! objects alike. [`tan_half_degrees`] (a camera's field of view → its focal length) sums
//! 14 Taylor terms instead, exact to the last bit's neighbourhood; it is kept apart on
//! purpose: the frames' bytes depend on the focal length's bits.

/// `(cos d, sin d)` of `d` degrees. Non-finite angles give `(1, 0)`.
pub fn cos_sin_deg(degrees: f64) -> (f64, f64) {
    if !degrees.is_finite() {
        return (1.0, 0.0);
    }
    let (sin, cos) = libm::sincos(degrees * (std::f64::consts::PI / 180.0));
    (cos, sin)
}

/// `(cos, sin)` of the sum of two angles given as `(cos, sin)`.
pub fn add(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    (a.0 * b.0 - a.1 * b.1, a.1 * b.0 + a.0 * b.1)
}

/// tan(θ/2) for θ in degrees, from Taylor series of sin and cos (θ ≤ 120° keeps
/// θ/2 ≤ 1.05 rad, where 14 terms are exact to the last bit's neighbourhood).
pub fn tan_half_degrees(degrees: f64) -> f64 {
    let x = degrees / 2.0 * (std::f64::consts::PI / 180.0);
    let (mut sin, mut cos) = (0.0, 0.0);
    let (mut term_s, mut term_c) = (x, 1.0);
    for n in 0..14 {
        sin += term_s;
        cos += term_c;
        let k = 2.0 * f64::from(n);
        term_s *= -x * x / ((k + 2.0) * (k + 3.0));
        term_c *= -x * x / ((k + 1.0) * (k + 2.0));
    }
    sin / cos
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[allow(clippy::disallowed_methods)] // compares with the platform's sin and cos
    fn matches_std_to_the_last_bits() {
        let mut d = -725.0;
        while d <= 725.0 {
            let (c, s) = cos_sin_deg(d);
            let r = d.to_radians();
            assert!((c - r.cos()).abs() < 1e-15, "cos {d}");
            assert!((s - r.sin()).abs() < 1e-15, "sin {d}");
            d += 0.75;
        }
    }

    #[test]
    fn quarter_turns_and_sums() {
        let cases = [
            (0.0, (1.0, 0.0)),
            (90.0, (0.0, 1.0)),
            (180.0, (-1.0, 0.0)),
            (270.0, (0.0, -1.0)),
            (-90.0, (0.0, -1.0)),
        ];
        for (d, want) in cases {
            let got = cos_sin_deg(d);
            assert!(
                (got.0 - want.0).abs() < 1e-15 && (got.1 - want.1).abs() < 1e-15,
                "{d}"
            );
        }
        assert_eq!(cos_sin_deg(0.0), (1.0, 0.0));
        assert_eq!(cos_sin_deg(f64::NAN), (1.0, 0.0));
        let (c, s) = add(cos_sin_deg(30.0), cos_sin_deg(60.0));
        assert!(c.abs() < 1e-15 && (s - 1.0).abs() < 1e-15);
    }

    #[test]
    fn tan_half_matches_known_values() {
        for (degrees, expected) in [
            (90.0, 1.0),
            (60.0, 0.577_350_269_189_625_8),
            (120.0, 1.732_050_807_568_877_2),
        ] {
            let got = tan_half_degrees(degrees);
            assert!((got - expected).abs() < 1e-12, "{degrees}: {got}");
        }
    }
}
