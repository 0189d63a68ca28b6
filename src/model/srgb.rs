//! Fixed sRGB ↔ linear tables: 8-bit sRGB → linear f32, linear f32 → 8-bit sRGB. The
//! renderer decodes textures and develops through them, the sensor stage encodes its
//! tone-mapped frames with them.
//!
//! Both tables are built once from the sRGB transfer function with nothing but + − × ÷ and
//! comparisons (the powers 2.4 and 1/2.4 are found by bisection), so every machine builds
//! the same bits. The encoding table has 4096 entries indexed by `sqrt(linear)`: the square
//! root spreads the entries evenly over the perceptual range, so dark values keep their
//! precision and every 8-bit value survives a decode → encode round trip.

use std::sync::OnceLock;

/// Entries of the encoding table.
const ENCODE_ENTRIES: usize = 4096;
/// A linear value's bits shifted right by this give its bucket of [`Srgb::buckets`]: the
/// sign, the exponent and the mantissa's top 7 bits, so a bucket is at most 1/128 of its
/// values wide. The 8-bit output's steps are wider (the narrowest, near white, about 1/112
/// of the value), so no bucket holds two of them; building the table asserts it.
const BUCKET_SHIFT: u32 = 16;
/// Buckets up to the one holding 1.0 (values from 1 up encode as 255 before any lookup).
const BUCKETS: usize = (1.0f32.to_bits() >> BUCKET_SHIFT) as usize;

/// The two conversion tables.
pub(crate) struct Srgb {
    decode: [f32; 256],
    encode: Vec<u8>,
    /// Per bucket of positive linear values below 1: the 8-bit value at its lowest value
    /// and the value from which it is one more (above the bucket when it never is).
    /// [`Srgb::to_srgb8`] in two lookups, without the square root: the same bytes as
    /// [`Srgb::to_srgb8_by_root`].
    buckets: Vec<(u8, f32)>,
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
        let mut tables = Srgb {
            decode,
            encode,
            buckets: Vec::new(),
        };
        tables.buckets = tables.bucket_table();
        tables
    }

    /// [`Srgb::buckets`], from [`Srgb::to_srgb8_by_root`], which rises with its input (the
    /// square root, the scaling and the truncation all keep order, and `encode` rises):
    /// each bucket's value at its lowest input, and the first input where it steps, found
    /// by bisection over the bits (positive floats order as their bits).
    ///
    /// # Panics
    /// If a bucket holds two steps (it does not: see [`BUCKET_SHIFT`]).
    fn bucket_table(&self) -> Vec<(u8, f32)> {
        let f = |bits: u32| self.to_srgb8_by_root(f32::from_bits(bits));
        (0..BUCKETS as u32)
            .map(|b| {
                let (first, last) = (b << BUCKET_SHIFT, ((b + 1) << BUCKET_SHIFT) - 1);
                let base = f(first);
                let top = f(last);
                assert!(top - base <= 1, "bucket {b} holds two sRGB steps");
                if top == base {
                    return (base, f32::INFINITY);
                }
                // The first bits in (first, last] whose value is base + 1.
                let (mut lo, mut hi) = (first, last);
                while hi - lo > 1 {
                    let mid = lo + (hi - lo) / 2;
                    if f(mid) > base { hi = mid } else { lo = mid }
                }
                (base, f32::from_bits(hi))
            })
            .collect()
    }

    /// Linear value (0–1) of an 8-bit sRGB value.
    #[inline]
    pub(crate) fn to_linear(&self, s: u8) -> f32 {
        self.decode[usize::from(s)]
    }

    /// 8-bit sRGB of a linear value; values outside 0–1 are clamped, NaN is black.
    #[inline]
    pub(crate) fn to_srgb8(&self, linear: f32) -> u8 {
        // Zero, below it and NaN are black.
        if linear.is_nan() || linear <= 0.0 {
            return 0;
        }
        if linear >= 1.0 {
            return 255;
        }
        let (base, step) = self.buckets[(linear.to_bits() >> BUCKET_SHIFT) as usize];
        base + u8::from(linear >= step)
    }

    /// [`Srgb::to_srgb8`] by its definition: the encoding table's entry nearest the
    /// square root of the value.
    fn to_srgb8_by_root(&self, linear: f32) -> u8 {
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
    fn buckets_encode_as_the_square_root_table_does() {
        // Every value where the output steps and a float either side of it, a spread of
        // values between (every 251st bit pattern from 0 to 1), the edges and outside.
        let t = srgb();
        let spread = (0..=1.0f32.to_bits()).step_by(251).map(f32::from_bits);
        let steps = t
            .buckets
            .iter()
            .filter(|b| b.1.is_finite())
            .flat_map(|b| [b.1.next_down(), b.1, b.1.next_up()]);
        let edges = [
            f32::MIN_POSITIVE,
            1.0f32.next_down(),
            1.0,
            1.5,
            f32::INFINITY,
        ];
        let outside = [-0.0, -1e-30, f32::NEG_INFINITY, f32::NAN];
        for v in spread.chain(steps).chain(edges).chain(outside) {
            assert_eq!(t.to_srgb8(v), t.to_srgb8_by_root(v), "{v:e}");
        }
        // Every output value is some bucket's, at its start or past its step.
        let mut seen = [false; 256];
        for &(base, step) in &t.buckets {
            seen[usize::from(base)] = true;
            if step.is_finite() {
                seen[usize::from(base) + 1] = true;
            }
        }
        assert!(seen.iter().all(|&s| s));
    }

    #[test]
    fn encoding_table_rises() {
        let t = srgb();
        assert!(t.encode.windows(2).all(|w| w[0] <= w[1]));
    }

    #[test]
    fn decoding_is_monotonic() {
        let t = srgb();
        for s in 1..=255u8 {
            assert!(t.to_linear(s) > t.to_linear(s - 1));
        }
    }
}
