//! Field of view in degrees → the tangent of its half angle, the same bits everywhere.

/// tan(θ/2) for θ in degrees, from Taylor series of sin and cos (only + − × ÷, so the
/// same bits on every platform; θ ≤ 120° keeps θ/2 ≤ 1.05 rad where 14 terms are exact to
/// the last bit's neighbourhood).
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
