//! Numbers as text for OBJ/MTL: `f32` → fixed-point decimal, `u64` → decimal, appended to a
//! byte buffer without allocating.
//!
//! Not `format!("{:.4}")`: that prints `-0.0000` for tiny negatives and is several times
//! slower. Here the value is scaled in `f64` (exact for an `f32` times a power of ten up to
//! 10⁶ up to one rounding, which IEEE 754 fixes on every platform), rounded half away from
//! zero, and printed as an integer with the point put back: the same bytes everywhere, and
//! a value that rounds to zero is printed without a sign.

/// Powers of ten for the supported numbers of decimals (0–6).
const SCALE: [u64; 7] = [1, 10, 100, 1_000, 10_000, 100_000, 1_000_000];

/// Appends `x` with exactly `decimals` (capped at 6) digits after the point. Non-finite
/// values, which a scene should never hold, are written as zero so the file stays readable.
#[inline]
pub fn push_fixed(out: &mut Vec<u8>, x: f32, decimals: usize) {
    let decimals = decimals.min(SCALE.len() - 1);
    let scale = SCALE[decimals];
    let x = if x.is_finite() { f64::from(x) } else { 0.0 };
    // `as` saturates: a coordinate beyond ±9·10¹² m prints as the clamped value.
    let scaled = (x * scale as f64).round() as i64;
    if scaled < 0 {
        out.push(b'-');
    }
    let magnitude = scaled.unsigned_abs();
    let mut digits = itoa::Buffer::new();
    out.extend_from_slice(digits.format(magnitude / scale).as_bytes());
    if decimals > 0 {
        out.push(b'.');
        // The fraction's digits with their leading zeros: those of `scale + frac`, the
        // leading 1 dropped.
        let padded = digits.format(scale + magnitude % scale).as_bytes();
        out.extend_from_slice(&padded[1..]);
    }
}

/// Appends `n` in decimal.
#[inline]
pub fn push_u64(out: &mut Vec<u8>, n: u64) {
    out.extend_from_slice(itoa::Buffer::new().format(n).as_bytes());
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fixed(x: f32, decimals: usize) -> String {
        let mut s = Vec::new();
        push_fixed(&mut s, x, decimals);
        String::from_utf8(s).unwrap()
    }

    #[test]
    fn fixed_point_table() {
        let cases: &[(f32, usize, &str)] = &[
            (0.0, 4, "0.0000"),
            (-0.0, 4, "0.0000"),
            (-0.00004, 4, "0.0000"),
            (-0.000_001, 5, "0.00000"),
            (-0.00016, 4, "-0.0002"),
            (1.5, 4, "1.5000"),
            (-2.25, 5, "-2.25000"),
            (123.456_78, 4, "123.4568"),
            (0.999_99, 4, "1.0000"),
            (0.5, 0, "1"),
            (-768.0, 4, "-768.0000"),
            (0.1, 5, "0.10000"),
            (1.0e-7, 5, "0.00000"),
            (f32::NAN, 4, "0.0000"),
            (f32::INFINITY, 4, "0.0000"),
            (42.0, 9, "42.000000"),
        ];
        for &(x, decimals, want) in cases {
            assert_eq!(fixed(x, decimals), want, "{x} with {decimals} decimals");
        }
    }

    #[test]
    fn agrees_with_std_formatting_away_from_ties() {
        // Values whose decimal expansion is not near a rounding tie print as `{:.4}` does.
        for i in -2000..2000 {
            let x = i as f32 * 0.37 + 0.011;
            assert_eq!(fixed(x, 4), format!("{x:.4}"), "{x}");
        }
    }

    #[test]
    fn integers_table() {
        for (n, want) in [(0u64, "0"), (7, "7"), (10, "10"), (1_234_567, "1234567")] {
            let mut s = Vec::new();
            push_u64(&mut s, n);
            assert_eq!(s, want.as_bytes());
        }
        let mut s = Vec::new();
        push_u64(&mut s, u64::MAX);
        assert_eq!(s, u64::MAX.to_string().as_bytes());
    }
}
