//! Exposed linear RGB + noise levels + seed → the same image with sensor noise: shot
//! (photon) noise whose variance grows with the signal, and Gaussian read noise.
//!
//! Each value's random number comes from a counter-based hash of (seed, pixel, channel),
//! so rows can be processed in parallel and any thread count gives the same bits. The
//! normal deviate is an Irwin–Hall sum of four uniforms scaled to unit variance (bounded at
//! ±3.5σ; no log or cosine needed).

use rayon::prelude::*;

/// Adds noise of standard deviation `sqrt(read² + shot · x)` to every channel value `x`.
pub fn add_noise(exposed: &mut [[f32; 3]], width: u32, read: f32, shot: f32, seed: u64) {
    if read <= 0.0 && shot <= 0.0 {
        return;
    }
    let w = width.max(1) as usize;
    let read2 = read * read;
    exposed.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, c) in row.iter_mut().enumerate() {
            let index = ((y * w + x) as u64) * 3;
            for (k, v) in c.iter_mut().enumerate() {
                let sigma = (read2 + shot * v.max(0.0)).sqrt();
                *v = (*v + sigma * normal(seed, index + k as u64)).max(0.0);
            }
        }
    });
}

/// A unit-variance, zero-mean deviate for `(seed, counter)`.
#[inline]
pub(crate) fn normal(seed: u64, counter: u64) -> f32 {
    let bits = splitmix(seed ^ counter.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    let sum: u32 = (0..4).map(|i| ((bits >> (16 * i)) & 0xFFFF) as u32).sum();
    // Four uniforms on 0–1: mean 2, variance 4/12; so (sum − 2)·√3 has variance 1.
    (sum as f32 / 65535.0 - 2.0) * 1.732_050_8
}

/// SplitMix64's finalizer: a well-mixed 64-bit hash of `x`.
#[inline]
pub(crate) fn splitmix(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deviates_have_unit_variance_and_zero_mean() {
        let n = 100_000;
        let (mut s, mut s2) = (0.0f64, 0.0f64);
        for i in 0..n {
            let v = f64::from(normal(3, i));
            s += v;
            s2 += v * v;
        }
        let mean = s / n as f64;
        let var = s2 / n as f64 - mean * mean;
        assert!(mean.abs() < 0.02, "{mean}");
        assert!((var - 1.0).abs() < 0.03, "{var}");
    }

    #[test]
    fn shot_noise_grows_with_the_signal_and_seeds_repeat() {
        let make = || {
            let mut img = vec![[0.1f32; 3]; 100 * 50];
            img.extend(vec![[1.0f32; 3]; 100 * 50]);
            add_noise(&mut img, 100, 0.0, 0.01, 7);
            img
        };
        let img = make();
        assert_eq!(img, make());
        let spread = |part: &[[f32; 3]], mean: f32| {
            part.iter().map(|c| (c[0] - mean).abs()).sum::<f32>() / part.len() as f32
        };
        let (dark, bright) = img.split_at(5000);
        assert!(spread(bright, 1.0) > 2.5 * spread(dark, 0.1));
    }
}
