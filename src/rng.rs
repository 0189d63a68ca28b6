//! Seeded random streams: (spec seed, stage name, item index) → an independent PCG stream.
//!
//! Every stage and every item within it draws from its own stream, so changing one part of a
//! spec never reshuffles another (a new lamp spacing must not move a building). The stream
//! seed is the SHA-256 of the three inputs, so streams are the same on every platform.

use rand_pcg::Pcg64;
use sha2::{Digest, Sha256};

/// The random stream for `item` of `stage`, under the spec's `seed`.
pub fn stream(seed: u64, stage: &str, item: u64) -> Pcg64 {
    use rand::SeedableRng;
    let mut hasher = Sha256::new();
    hasher.update(seed.to_le_bytes());
    hasher.update((stage.len() as u64).to_le_bytes());
    hasher.update(stage.as_bytes());
    hasher.update(item.to_le_bytes());
    let digest = hasher.finalize();
    let mut bytes = [0u8; 32];
    bytes.copy_from_slice(&digest);
    Pcg64::from_seed(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::Rng;

    #[test]
    fn streams_are_reproducible_and_independent() {
        let a: Vec<u64> = (0..4)
            .map(|_| 0)
            .scan(stream(7, "place", 3), |r, _| Some(r.next_u64()))
            .collect();
        let b: Vec<u64> = (0..4)
            .map(|_| 0)
            .scan(stream(7, "place", 3), |r, _| Some(r.next_u64()))
            .collect();
        let c: Vec<u64> = (0..4)
            .map(|_| 0)
            .scan(stream(7, "place", 4), |r, _| Some(r.next_u64()))
            .collect();
        let d: Vec<u64> = (0..4)
            .map(|_| 0)
            .scan(stream(7, "layout", 3), |r, _| Some(r.next_u64()))
            .collect();
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert_ne!(a, d);
    }

    #[test]
    fn stream_is_pinned_across_platforms() {
        const PINNED: u64 = 11036501420278810913;
        // Pinned so that a change of hashing or of rand_pcg shows up as a test failure
        // rather than as silently different cities.
        let first = stream(42, "layout", 0).next_u64();
        assert_eq!(first, PINNED, "got {first}");
    }
}
