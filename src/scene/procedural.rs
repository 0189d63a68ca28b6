//! Seeded texture recipes → the small repeating surface images: grass, asphalt, paving,
//! concrete, and the distant woods on the hills around the city.
//!
//! Each image draws from `crate::rng::stream(0, "textures", i)` with integer arithmetic only,
//! so it is the same on every platform and independent of the spec's seed. Every recipe
//! tiles seamlessly: the noise is a lattice sampled with wrap-around.

use image::{Rgb, RgbImage};
use rand::RngExt;

use crate::rng::stream;

/// Side of every procedural texture, in pixels.
pub const SIZE: u32 = 128;

/// Metres one repeat of each texture covers.
pub const GRASS_TILE: f64 = 4.0;
pub const ASPHALT_TILE: f64 = 4.0;
pub const PAVING_TILE: f64 = 2.0;
pub const CONCRETE_TILE: f64 = 2.0;
pub const WOODS_TILE: f64 = 40.0;

/// Muted grass and earth: a coarse green/brown mottle with fine speckle.
pub fn grass() -> RgbImage {
    let coarse = lattice(0, 16);
    let fine = lattice(1, SIZE);
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let c = smooth(&coarse, 16, x, y);
        let f = fine[idx(x, y, SIZE)];
        // c in 0..=255 blends grass (86, 110, 58) towards earth (112, 98, 70).
        let mix = |g: i32, e: i32| (g * (255 - c) + e * c) / 255 + (f - 128) / 10;
        rgb([mix(86, 112), mix(110, 98), mix(58, 70)])
    })
}

/// Woods seen from afar: clumps of tree crowns, lit tops and dark gaps, muted towards the
/// blue-grey of distance (the hills stand hundreds of metres out).
pub fn woods() -> RgbImage {
    let clumps = lattice(8, 16);
    let crowns = lattice(10, 32);
    let fine = lattice(11, SIZE);
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let c = smooth(&clumps, 16, x, y);
        let k = smooth(&crowns, 32, x, y);
        // Crowns where the finer noise peaks; gaps between them darker.
        let lit = ((k - 96) * 2).clamp(0, 255) * (128 + c / 2) / 255;
        let f = (fine[idx(x, y, SIZE)] - 128) / 14;
        let mix = |gap: i32, top: i32| (gap * (255 - lit) + top * lit) / 255 + f;
        rgb([mix(58, 104), mix(72, 122), mix(72, 108)])
    })
}

/// Asphalt: dark grey with aggregate speckle.
pub fn asphalt() -> RgbImage {
    let coarse = lattice(2, 8);
    let fine = lattice(3, SIZE);
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let base = 62 + (smooth(&coarse, 8, x, y) - 128) / 16;
        let f = fine[idx(x, y, SIZE)];
        // One pixel in ~16 is a light stone.
        let v = if f > 240 {
            base + 28
        } else {
            base + (f - 128) / 12
        };
        rgb([v, v, v + 2])
    })
}

/// Plaza paving: a running bond of 0.5 m × 0.25 m stones with dark joints.
pub fn paving() -> RgbImage {
    let stone = lattice(4, 8);
    let fine = lattice(5, SIZE);
    let (w, h) = (SIZE / 4, SIZE / 8);
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let row = y / h;
        let xs = (x + if row % 2 == 1 { w / 2 } else { 0 }) % SIZE;
        let joint = y % h == 0 || xs.is_multiple_of(w);
        let tone = (stone[idx(xs / w + 4 * (row % 2), row, 8)] - 128) / 8;
        let f = (fine[idx(x, y, SIZE)] - 128) / 16;
        let v = if joint { 92 } else { 150 + tone + f };
        rgb([v + 6, v, v - 8])
    })
}

/// Sidewalk concrete: 1 m slabs with thin joints.
pub fn concrete() -> RgbImage {
    let fine = lattice(6, SIZE);
    let coarse = lattice(7, 8);
    let slab = SIZE / 2;
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let joint = x % slab == 0 || y % slab == 0;
        let v = 170 + (smooth(&coarse, 8, x, y) - 128) / 12 + (fine[idx(x, y, SIZE)] - 128) / 14;
        let v = if joint { v - 45 } else { v };
        rgb([v, v, v - 3])
    })
}

/// `n × n` uniform values in 0..=255 from the texture stream `item`.
fn lattice(item: u64, n: u32) -> Vec<i32> {
    let mut rng = stream(0, "textures", item);
    (0..n * n).map(|_| rng.random_range(0..=255)).collect()
}

fn idx(x: u32, y: u32, n: u32) -> usize {
    ((y % n) * n + (x % n)) as usize
}

/// Bilinear interpolation of an `n × n` lattice stretched over the texture, wrapping.
fn smooth(lattice: &[i32], n: u32, x: u32, y: u32) -> i32 {
    let cell = (SIZE / n) as i32;
    let (gx, gy) = (x / cell as u32, y / cell as u32);
    let (fx, fy) = ((x as i32) % cell, (y as i32) % cell);
    let at = |i: u32, j: u32| lattice[idx(i, j, n)];
    let top = at(gx, gy) * (cell - fx) + at(gx + 1, gy) * fx;
    let bottom = at(gx, gy + 1) * (cell - fx) + at(gx + 1, gy + 1) * fx;
    (top * (cell - fy) + bottom * fy) / (cell * cell)
}

fn rgb(c: [i32; 3]) -> Rgb<u8> {
    Rgb(c.map(|v| v.clamp(0, 255) as u8))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn textures_are_reproducible_distinct_and_not_flat() {
        let all = [grass(), asphalt(), paving(), concrete(), woods()];
        for (i, image) in all.iter().enumerate() {
            assert_eq!(image.dimensions(), (SIZE, SIZE));
            let first = image.get_pixel(0, 0);
            assert!(image.pixels().any(|p| p != first), "texture {i} is flat");
            for (j, other) in all.iter().enumerate().skip(i + 1) {
                assert_ne!(image, other, "textures {i} and {j}");
            }
        }
        assert_eq!(grass(), all[0]);
        assert_eq!(concrete(), all[3]);
    }

    #[test]
    fn smooth_noise_wraps_around_the_edges() {
        let lattice = lattice(9, 8);
        // Past the last cell the interpolation heads back to the first lattice value.
        let last = smooth(&lattice, 8, SIZE - 1, 0);
        let towards = (lattice[7] + lattice[0] * 15) / 16;
        assert!((last - towards).abs() <= 1, "{last} vs {towards}");
    }
}
