//! Metres ↔ layout pixels, and the rounding of numbers written to JSON.
//!
//! The plan, the camera paths and the annotations write positions rounded to a fixed
//! number of decimals (the millimetre for lengths), so their files do not carry float
//! noise; all round the same way here.

/// `v` rounded to a multiple of `1 / scale` (`scale` a power of ten), with `-0` made `0`.
pub fn round_to(v: f64, scale: f64) -> f64 {
    let r = (v * scale).round() / scale;
    if r == 0.0 { 0.0 } else { r }
}

/// `v` rounded to 3 decimals (the millimetre), with `-0` made `0`.
pub fn mm(v: f64) -> f64 {
    round_to(v, 1000.0)
}

/// Building widths in layout pixels (at least one pixel each).
pub fn widths_px(widths_m: &[f64], metres_per_pixel: f64) -> Vec<u32> {
    widths_m
        .iter()
        .map(|w| (w / metres_per_pixel).round().max(1.0) as u32)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounds_to_the_millimetre() {
        let cases = [
            (1.23449, 1.234),
            (1.2345001, 1.235),
            (-0.0004, 0.0),
            (-2.5, -2.5),
            (0.1 + 0.2, 0.3),
        ];
        for (v, want) in cases {
            assert_eq!(mm(v), want, "{v}");
            assert!(mm(v).is_sign_positive() || want < 0.0, "{v}");
        }
        assert_eq!(round_to(0.123_456_7, 1e6), 0.123_457);
    }

    #[test]
    fn widths_are_at_least_a_pixel() {
        assert_eq!(widths_px(&[10.0, 0.1, 3.3], 0.6), [17, 1, 6]);
    }
}
