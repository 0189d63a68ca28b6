//! Degrees → (cos, sin) and tan(θ/2) with only `+ − × ÷`, so angles give the same bits on
//! every platform.
//!
//! [`cos_sin_deg`] reduces the angle to one of four quadrants around 0, 90, 180, 270°
//! (|x| ≤ 45°) and evaluates Taylor polynomials to x¹⁰ there: the error is below 2e-9.
//! [`tan_half_degrees`] (a camera's field of view → its focal length) sums 14 terms
//! instead, exact to the last bit's neighbourhood. The two are kept apart on purpose: the
//! frames' bytes depend on the focal length's bits, and a shared series would change them.

const DEG_TO_RAD: f64 = std::f64::consts::PI / 180.0;

/// `(cos d, sin d)` of `d` degrees. Non-finite angles give `(1, 0)`.
pub fn cos_sin_deg(degrees: f64) -> (f64, f64) {
    if !degrees.is_finite() {
        return (1.0, 0.0);
    }
    let turn = degrees - 360.0 * (degrees / 360.0).floor();
    let quadrant = (turn / 90.0).round();
    let x = (turn - 90.0 * quadrant) * DEG_TO_RAD;
    let x2 = x * x;
    let sin = x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0))));
    let cos = 1.0
        - x2 / 2.0 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0 * (1.0 - x2 / 56.0 * (1.0 - x2 / 90.0))));
    match quadrant as i64 {
        1 => (-sin, cos),
        2 => (-cos, -sin),
        3 => (sin, -cos),
        _ => (cos, sin),
    }
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
    fn matches_std_to_nine_digits() {
        let mut d = -725.0;
        while d <= 725.0 {
            let (c, s) = cos_sin_deg(d);
            let r = d.to_radians();
            assert!((c - r.cos()).abs() < 2e-9, "cos {d}");
            assert!((s - r.sin()).abs() < 2e-9, "sin {d}");
            d += 0.75;
        }
    }

    #[test]
    fn exact_at_quarter_turns_and_sums() {
        let cases = [
            (0.0, (1.0, 0.0)),
            (90.0, (0.0, 1.0)),
            (180.0, (-1.0, 0.0)),
            (270.0, (0.0, -1.0)),
            (-90.0, (0.0, -1.0)),
            (f64::NAN, (1.0, 0.0)),
        ];
        for (d, want) in cases {
            assert_eq!(cos_sin_deg(d), want, "{d}");
        }
        let (c, s) = add(cos_sin_deg(30.0), cos_sin_deg(60.0));
        assert!(c.abs() < 1e-8 && (s - 1.0).abs() < 1e-8);
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
