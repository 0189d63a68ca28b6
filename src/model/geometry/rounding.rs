//! `f64::round` and `f64::floor` without the library calls they compile to on baseline
//! x86-64 (no SSE4.1 `roundsd`): truncation to an integer is one instruction, and
//! `v − trunc(v)` is exact. For `|v| < 2^52`, the range of pixel and colour arithmetic,
//! the results equal the library's bit for bit (but −0 for 0); casting them to an
//! integer always agrees with casting the library's (NaN casts to 0 in both).
//! Stages painting millions of pixels call these per pixel.

/// `v.round()`: halves away from zero.
pub fn round(v: f64) -> f64 {
    let whole = (v as i64) as f64;
    let rest = v - whole;
    if rest >= 0.5 {
        whole + 1.0
    } else if rest <= -0.5 {
        whole - 1.0
    } else {
        whole
    }
}

/// `v.floor()`.
pub fn floor(v: f64) -> f64 {
    let whole = (v as i64) as f64;
    if whole > v { whole - 1.0 } else { whole }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn agree_with_the_library() {
        let mut v = -300.0;
        while v < 300.0 {
            for x in [v, v + 0.5, v - 1e-9, v + 0.5 - 1e-12, 0.49999999999999994] {
                assert_eq!(round(x), x.round(), "{x}");
                assert_eq!(floor(x), x.floor(), "{x}");
                assert_eq!(
                    round(x).clamp(0.0, 255.0) as u8,
                    x.round().clamp(0.0, 255.0) as u8
                );
                assert_eq!(floor(x) as i64, x.floor() as i64);
            }
            v += 0.125;
        }
        assert_eq!(round(f64::NAN) as u8, f64::NAN.round() as u8);
        assert_eq!(floor(f64::NAN) as i64, f64::NAN.floor() as i64);
    }
}
