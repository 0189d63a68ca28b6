//! `floor`, `ceil` and `round` for the per-pixel loops, bit-identical to `f64::floor`/
//! `f64::ceil`/`f64::round`.
//!
//! On the x86-64 baseline (no SSE4.1 `roundsd`) the standard ones are calls into the
//! soft-float routine of `compiler_builtins`; in texture sampling, shadow lookups and
//! sRGB encoding they cost about 5 % of a frame. These convert through `i64` instead,
//! which is exact wherever `|x| < 2^52` (every value there is either an integer or has a
//! fraction), and fall back to the standard functions elsewhere (huge values, which are
//! already integers, infinities and NaN).

/// Bit-identical to `x.floor()`.
#[inline]
pub fn floor(x: f64) -> f64 {
    if x.abs() < 4_503_599_627_370_496.0 {
        let t = x as i64 as f64;
        // Truncation rounds toward zero: one below for negative fractions. `t - 1.0` is
        // exact, and -0.0 stays -0.0 (t = 0.0 > -0.0 is false).
        if t > x { t - 1.0 } else { t.copysign(x) }
    } else {
        x.floor()
    }
}

/// Bit-identical to `x.ceil()`.
#[inline]
pub fn ceil(x: f64) -> f64 {
    -floor(-x)
}

/// Bit-identical to `x.round()` (halves away from zero). The facade painter and the wall
/// patch behind painted text round every channel of every pixel.
#[inline]
pub fn round(x: f64) -> f64 {
    if x.abs() < 4_503_599_627_370_496.0 {
        let t = x as i64 as f64;
        // `x - t` is exact: the fraction, with x's sign.
        let rest = x - t;
        let r = if rest >= 0.5 {
            t + 1.0
        } else if rest <= -0.5 {
            t - 1.0
        } else {
            t
        };
        r.copysign(x)
    } else {
        x.round()
    }
}

/// `x.round() as i32` (halves away from zero) for `|x| < 2^31`: the facade painter's
/// per-pixel blotches, without [`round`]'s range check and sign copy. Outside that range
/// the result saturates like `as i32` but may be one off.
#[inline]
pub fn round_i32(x: f64) -> i32 {
    let t = x as i32;
    // Exact: x and its truncation differ by less than 1 (and NaN truncates to 0, rest NaN).
    let rest = x - f64::from(t);
    // Two compares added in, not branched on: `rest` is as good as random from one pixel
    // to the next, so a branch would be mispredicted half the time. (NaN: both false.)
    t + i32::from(rest >= 0.5) - i32::from(rest <= -0.5)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_standard_functions_bit_for_bit() {
        let mut values = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            0.49999999999999994,
            -0.49999999999999994,
            0.5000000000000001,
            1.5,
            -1.5,
            2.4999999999999996,
            1.0e-300,
            -1.0e-300,
            2.5,
            -2.5,
            4_503_599_627_370_495.5,
            -4_503_599_627_370_495.5,
            4_503_599_627_370_496.0,
            9.0e18,
            -9.3e18,
            1.0e300,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MAX,
            f64::MIN_POSITIVE,
        ];
        // A sweep of ordinary magnitudes, both signs.
        let mut x = 1.0e-6;
        while x < 1.0e17 {
            values.extend([x, -x, x + 0.5, -x - 0.5]);
            x *= 1.37;
        }
        for v in values {
            assert_eq!(floor(v).to_bits(), v.floor().to_bits(), "floor({v:e})");
            assert_eq!(ceil(v).to_bits(), v.ceil().to_bits(), "ceil({v:e})");
            assert_eq!(round(v).to_bits(), v.round().to_bits(), "round({v:e})");
        }
        // Every step of an eighth and just beside the halves, as colour arithmetic meets.
        for i in -2400..2400 {
            let v = f64::from(i) / 8.0;
            for x in [v, v - 1e-9, v + 1e-12] {
                assert_eq!(round(x).to_bits(), x.round().to_bits(), "round({x:e})");
            }
        }
        assert!(floor(f64::NAN).is_nan() && ceil(f64::NAN).is_nan() && round(f64::NAN).is_nan());
    }

    #[test]
    fn round_i32_is_round_as_i32_in_its_range() {
        let mut values = vec![
            0.0,
            -0.0,
            0.49999999999999994,
            -0.49999999999999994,
            f64::NAN,
        ];
        for i in -4000..4000 {
            let v = f64::from(i) / 8.0;
            values.extend([v, v - 1e-9, v + 1e-12, v * 1e5 + 0.5, v * 5e5 - 0.5]);
        }
        values.extend([
            2_147_483_646.5,
            -2_147_483_647.5,
            2_147_483_646.4,
            -2_147_483_648.0,
        ]);
        for v in values {
            assert_eq!(round_i32(v), v.round() as i32, "round_i32({v:e})");
        }
    }
}
