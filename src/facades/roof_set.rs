//! Roof set: fixed seeds → cityspec's roof textures, and molding colour → matching roof.
//!
//! Paper 3.2: a building's roof is the provided roof texture whose colour best matches the
//! molding of its facade. Here "best" is the smallest Euclidean distance in sRGB between the
//! molding's mean colour and the roof texture's mean colour; ties go to the lower index.

use image::{Rgb, RgbImage};
use rand::RngExt;
use rand_pcg::Pcg64;

use crate::model::{Roof, Texture};

/// Roof textures are square, this many pixels a side.
const SIZE: u32 = 256;

/// The kinds of roof cityspec draws, in index order.
const KINDS: [RoofKind; 7] = [
    RoofKind {
        name: "gravel_grey",
        base: [128, 127, 122],
        tile: 4.0,
        pattern: Pattern::Gravel,
    },
    RoofKind {
        name: "dark_tar",
        base: [50, 50, 54],
        tile: 8.0,
        pattern: Pattern::Seams(64),
    },
    RoofKind {
        name: "terracotta_tiles",
        base: [168, 82, 56],
        tile: 4.0,
        pattern: Pattern::Tiles,
    },
    RoofKind {
        name: "green_copper",
        base: [92, 150, 124],
        tile: 6.0,
        pattern: Pattern::Standing,
    },
    RoofKind {
        name: "light_concrete",
        base: [192, 189, 182],
        tile: 8.0,
        pattern: Pattern::Slabs,
    },
    RoofKind {
        name: "sand",
        base: [201, 180, 140],
        tile: 4.0,
        pattern: Pattern::Gravel,
    },
    RoofKind {
        name: "slate",
        base: [72, 78, 90],
        tile: 4.0,
        pattern: Pattern::Tiles,
    },
];

struct RoofKind {
    name: &'static str,
    base: [u8; 3],
    /// Metres one texture repeat covers.
    tile: f64,
    pattern: Pattern,
}

#[derive(Clone, Copy)]
enum Pattern {
    /// Coarse speckle of pebbles.
    Gravel,
    /// A membrane with welded seams every n pixels.
    Seams(u32),
    /// Overlapping rows of tiles, staggered.
    Tiles,
    /// Sheet metal with standing seams.
    Standing,
    /// Concrete slabs with joints.
    Slabs,
}

/// cityspec's roof textures, each with its mean colour. Drawn from fixed streams
/// (`crate::rng::stream(0, "builtin-roofs", i)`), so they never depend on the spec's seed.
pub fn builtin_roofs() -> Vec<Roof> {
    KINDS
        .iter()
        .enumerate()
        .map(|(i, kind)| {
            let mut rng = crate::rng::stream(0, "builtin-roofs", i as u64);
            let image = draw(kind, &mut rng);
            Roof {
                name: kind.name.to_string(),
                colour: mean_colour(&image),
                tile: kind.tile,
                texture: Texture::from_rgb(format!("roof_{}", kind.name), image),
            }
        })
        .collect()
}

/// The index of the roof whose colour is nearest to `colour` (Euclidean sRGB; ties to the
/// lower index). `roofs` must not be empty.
pub fn nearest_roof(colour: [u8; 3], roofs: &[Roof]) -> u32 {
    let mut best = (0usize, u32::MAX);
    for (i, roof) in roofs.iter().enumerate() {
        let d: u32 = (0..3)
            .map(|c| {
                let diff = i32::from(colour[c]) - i32::from(roof.colour[c]);
                (diff * diff) as u32
            })
            .sum();
        if d < best.1 {
            best = (i, d);
        }
    }
    best.0 as u32
}

/// Mean colour of an image, rounded.
pub fn mean_colour(image: &RgbImage) -> [u8; 3] {
    let mut sum = [0u64; 3];
    for p in image.pixels() {
        for c in 0..3 {
            sum[c] += u64::from(p[c]);
        }
    }
    let n = (u64::from(image.width()) * u64::from(image.height())).max(1);
    sum.map(|s| ((s + n / 2) / n) as u8)
}

fn draw(kind: &RoofKind, rng: &mut Pcg64) -> RgbImage {
    // Per-cell colour jitter for tiles and slabs, drawn up front so a cell is one colour.
    let cells: Vec<i32> = (0..64 * 64).map(|_| rng.random_range(-14..=14)).collect();
    let mut image = RgbImage::new(SIZE, SIZE);
    for y in 0..SIZE {
        for x in 0..SIZE {
            let grain = rng.random_range(-7..=7);
            let shade = match kind.pattern {
                Pattern::Gravel => {
                    let pebble: i32 = rng.random_range(0..10);
                    grain * 2
                        + if pebble == 0 {
                            -30
                        } else if pebble == 1 {
                            25
                        } else {
                            0
                        }
                }
                Pattern::Seams(n) => grain + if x % n < 2 || y % n == 0 { 18 } else { 0 },
                Pattern::Tiles => {
                    let row = y / 16;
                    let offset = if row % 2 == 0 { 0 } else { 12 };
                    let col = (x + offset) / 24;
                    let cell = cells[((row % 64) * 64 + col % 64) as usize];
                    // Each tile darkens towards its lower edge; the gap between tiles is dark.
                    let v = (y % 16) as i32;
                    let gap = if (x + offset) % 24 == 0 { -40 } else { 0 };
                    grain + cell - v * 2 + 12 + gap
                }
                Pattern::Standing => {
                    let seam = match x % 32 {
                        0 => 35,
                        1 => -30,
                        _ => 0,
                    };
                    grain + seam + ((y / 40 + x / 32) % 3) as i32 * 4
                }
                Pattern::Slabs => {
                    let cell = cells[(((y / 64) % 64) * 64 + (x / 64) % 64) as usize] / 2;
                    let joint = if x % 64 == 0 || y % 64 == 0 { -45 } else { 0 };
                    grain + cell + joint
                }
            };
            image.put_pixel(x, y, Rgb(kind.base.map(|c| clamp(i32::from(c) + shade))));
        }
    }
    image
}

fn clamp(v: i32) -> u8 {
    v.clamp(0, 255) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roofs_are_distinct_deterministic_and_near_their_base_colour() {
        let roofs = builtin_roofs();
        assert!(roofs.len() >= 5);
        assert_eq!(roofs, builtin_roofs());
        for (roof, kind) in roofs.iter().zip(KINDS.iter()) {
            assert_eq!((roof.texture.width, roof.texture.height), (SIZE, SIZE));
            assert_eq!(mean_colour(&roof.texture.decode().unwrap()), roof.colour);
            for c in 0..3 {
                let d = i32::from(roof.colour[c]) - i32::from(kind.base[c]);
                assert!(d.abs() <= 20, "{}: mean {:?}", roof.name, roof.colour);
            }
        }
        for (i, a) in roofs.iter().enumerate() {
            // Each roof is the nearest to its own colour: no two are confusable.
            assert_eq!(nearest_roof(a.colour, &roofs), i as u32, "{}", a.name);
        }
    }

    #[test]
    fn nearest_roof_table() {
        let roof = |colour: [u8; 3]| Roof {
            name: String::new(),
            colour,
            tile: 1.0,
            texture: Texture::from_rgb("t", RgbImage::new(1, 1)),
        };
        let roofs = [
            roof([0, 0, 0]),
            roof([200, 80, 50]),
            roof([100, 100, 100]),
            roof([0, 0, 20]),
        ];
        let cases: [([u8; 3], u32); 6] = [
            ([0, 0, 0], 0),
            ([190, 90, 60], 1),
            ([255, 255, 255], 2),
            ([90, 110, 100], 2),
            ([0, 0, 10], 0), // equally far from 0 and 3: the lower index wins
            ([0, 0, 11], 3),
        ];
        for (colour, expected) in cases {
            assert_eq!(nearest_roof(colour, &roofs), expected, "{colour:?}");
        }
    }
}
