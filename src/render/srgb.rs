//! Fixed sRGB ↔ linear tables: 8-bit sRGB → linear f32, linear f32 → 8-bit sRGB.
//!
//! Both tables are built once from the sRGB transfer function with nothing but + − × ÷ and
//! comparisons (the powers 2.4 and 1/2.4 are found by bisection), so every machine builds
//! the same bits. The encoding table has 4096 entries indexed by `sqrt(linear)`: the square
//! root spreads the entries evenly over the perceptual range, so dark values keep their
//! precision and every 8-bit value survives a decode → encode round trip.

use std::sync::OnceLock;

/// Entries of the encoding table.
const ENCODE_ENTRIES: usize = 4096;

/// The two conversion tables.
pub(crate) struct Srgb {
    decode: [f32; 256],
    encode: Vec<u8>,
}

/// The process-wide tables (built on first use; identical in every process).
pub(crate) fn srgb() -> &'static Srgb {
    static TABLES: OnceLock<Srgb> = OnceLock::new();
    TABLES.get_or_init(Srgb::build)
}

impl Srgb {
    fn build() -> Srgb {
        let mut decode = [0f32; 256];
        for (i, d) in decode.iter_mut().enumerate() {
            let s = i as f64 / 255.0;
            let linear = if s <= 0.04045 {
                s / 12.92
            } else {
                // ((s + 0.055) / 1.055)^(12/5)
                pow_ratio((s + 0.055) / 1.055, 12, 5)
            };
            *d = linear as f32;
        }
        let encode = (0..ENCODE_ENTRIES)
            .map(|i| {
                let root = i as f64 / (ENCODE_ENTRIES - 1) as f64;
                let linear = root * root;
                let s = if linear <= 0.003_130_8 {
                    12.92 * linear
                } else {
                    // 1.055 · linear^(5/12) − 0.055
                    1.055 * pow_ratio(linear, 5, 12) - 0.055
                };
                (s * 255.0 + 0.5).floor().clamp(0.0, 255.0) as u8
            })
            .collect();
        Srgb { decode, encode }
    }

    /// Linear value (0–1) of an 8-bit sRGB value.
    #[inline]
    pub(crate) fn to_linear(&self, s: u8) -> f32 {
        self.decode[usize::from(s)]
    }

    /// 8-bit sRGB of a linear value; values outside 0–1 are clamped, NaN is black.
    #[inline]
    pub(crate) fn to_srgb8(&self, linear: f32) -> u8 {
        // NaN stays NaN here and becomes index 0 in the saturating cast below.
        let l = linear.clamp(0.0, 1.0);
        let index = (l.sqrt() * (ENCODE_ENTRIES - 1) as f32 + 0.5) as usize;
        self.encode[index.min(ENCODE_ENTRIES - 1)]
    }
}

/// `x^(p/q)` for `x` in 0–1: the `y` in 0–1 with `y^q = x^p`, by 64 bisection steps.
fn pow_ratio(x: f64, p: u32, q: u32) -> f64 {
    let target = powi(x, p);
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for _ in 0..64 {
        let mid = 0.5 * (lo + hi);
        if powi(mid, q) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

fn powi(x: f64, n: u32) -> f64 {
    (0..n).fold(1.0, |acc, _| acc * x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_byte_round_trips() {
        let t = srgb();
        for s in 0..=255u8 {
            assert_eq!(t.to_srgb8(t.to_linear(s)), s, "sRGB {s}");
        }
    }

    #[test]
    fn known_values() {
        let t = srgb();
        let cases: &[(u8, f32)] = &[
            (0, 0.0),
            (255, 1.0),
            (188, 0.5029),
            (128, 0.2158),
            (10, 0.003035),
        ];
        for &(s, linear) in cases {
            assert!(
                (t.to_linear(s) - linear).abs() < 2e-4,
                "sRGB {s}: {}",
                t.to_linear(s)
            );
        }
        assert_eq!(t.to_srgb8(0.5), 188);
        assert_eq!(t.to_srgb8(-1.0), 0);
        assert_eq!(t.to_srgb8(7.0), 255);
        assert_eq!(t.to_srgb8(f32::NAN), 0);
    }

    #[test]
    fn decoding_is_monotonic() {
        let t = srgb();
        for s in 1..=255u8 {
            assert!(t.to_linear(s) > t.to_linear(s - 1));
        }
    }
}
