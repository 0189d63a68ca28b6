//! Wall surfaces and horizontal trim: brick or plaster, moldings, cornice, sky.

use rand::RngExt;
use rand_pcg::Pcg64;

use crate::model::PxRect;
use crate::model::geometry::rounding::round_i32;

use super::canvas::{Canvas, Colour, Grain, add, mix, rect, scale};
use super::design::Wall;

/// Brick course height and brick length, mortar joints included.
const COURSE: u32 = 8;
const BRICK: u32 = 22;
/// Spacing of the plaster's blotch grid.
const BLOTCH: u32 = 24;

/// Fills `r` with the wall material.
pub fn wall(c: &mut Canvas, r: PxRect, wall: Wall, rng: &mut Pcg64) {
    match wall {
        Wall::Brick { brick, mortar } => bricks(c, r, brick, mortar, rng),
        Wall::Plaster(colour) => plaster(c, r, colour, rng),
        Wall::Glass(tint) => glass(c, r, tint, rng),
        Wall::Stone(stone) => courses(c, r, stone, [48, 24, 2], 0.8, rng),
        Wall::Siding(paint) => siding(c, r, paint, rng),
        Wall::Tiles { tile, grout } => tiles(c, r, tile, grout, rng),
    }
}

/// A glass curtain wall: the sky reflected in bands, darker towards the street, with
/// slim mullions and transoms (the windows drawn over it are the vision panels).
fn glass(c: &mut Canvas, r: PxRect, tint: Colour, rng: &mut Pcg64) {
    let sky = mix(tint, [200, 214, 226], 0.45);
    c.gradient(r, sky, scale(tint, 0.7));
    let phase: u32 = rng.random_range(0..90);
    let mut noise = Grain::new(rng);
    c.each(r, |x, y, p| {
        let (lx, ly) = (x - r.x0, y - r.y0);
        if lx % 36 < 3 || ly % 26 < 3 {
            [96, 100, 106].map(|v| add(v, noise.next(4)))
        } else if (lx + ly / 2 + phase) % 140 < 30 {
            scale(p, 1.15)
        } else {
            p
        }
    });
}

/// Stone (or any block) courses: `[block length, course height, joint]` pixels, every
/// block a little lighter or darker, joints shaded by `joint_shade`.
pub fn courses(
    c: &mut Canvas,
    r: PxRect,
    stone: Colour,
    size: [u32; 3],
    joint_shade: f64,
    rng: &mut Pcg64,
) {
    let [block, course, joint] = size;
    let cols = r.width() / block + 2;
    let rows = r.height() / course + 1;
    let offsets: Vec<i32> = (0..cols * rows).map(|_| rng.random_range(-9..=9)).collect();
    let mut noise = Grain::new(rng);
    c.each(r, |x, y, _| {
        let (lx, ly) = (x - r.x0, y - r.y0);
        let row = ly / course;
        let shift = if row.is_multiple_of(2) { 0 } else { block / 2 };
        let col = (lx + shift) / block;
        let grain = noise.next(4);
        let base = stone.map(|v| add(v, offsets[(row * cols + col) as usize] + grain));
        if ly % course >= course - joint || (lx + shift) % block >= block - joint {
            scale(base, joint_shade)
        } else {
            base
        }
    });
}

/// Painted boards 12 px high, each with a shadow line under its lap.
fn siding(c: &mut Canvas, r: PxRect, paint: Colour, rng: &mut Pcg64) {
    let mut noise = Grain::new(rng);
    c.each(r, |_, y, _| {
        let k = (y - r.y0) % 12;
        let light = match k {
            0 => 0.7,
            1 => 0.86,
            _ => 1.04 - 0.012 * f64::from(k),
        };
        scale(paint.map(|v| add(v, noise.next(3))), light)
    });
}

/// Square 12 px tiles in 2 px of grout, each tile a little different.
fn tiles(c: &mut Canvas, r: PxRect, tile: Colour, grout: Colour, rng: &mut Pcg64) {
    let cols = r.width() / 12 + 1;
    let rows = r.height() / 12 + 1;
    let offsets: Vec<i32> = (0..cols * rows)
        .map(|_| rng.random_range(-10..=10))
        .collect();
    c.each(r, |x, y, _| {
        let (lx, ly) = (x - r.x0, y - r.y0);
        if lx % 12 >= 10 || ly % 12 >= 10 {
            grout
        } else {
            tile.map(|v| add(v, offsets[((ly / 12) * cols + lx / 12) as usize]))
        }
    });
}

/// Half-timbering over `r`: dark posts at `posts` (x), rails at `rails` (y) and a brace
/// across each panel between two posts below a rail.
pub fn timber(c: &mut Canvas, r: PxRect, posts: &[u32], rails: &[u32], wood: Colour) {
    const BEAM: u32 = 7;
    for &y in rails {
        c.fill(rect(r.x0, y, r.x1, y + BEAM), wood);
    }
    for &x in posts {
        c.fill(rect(x, r.y0, x + BEAM, r.y1), wood);
    }
    for pair in rails.windows(2) {
        let (y0, y1) = (pair[0] + BEAM, pair[1]);
        for (i, post) in posts.windows(2).enumerate() {
            let (x0, x1) = (post[0] + BEAM, post[1]);
            if x1 <= x0 + 2 * BEAM || y1 <= y0 {
                continue;
            }
            let (w, h) = (f64::from(x1 - x0), f64::from(y1 - y0));
            c.each(rect(x0, y0, x1, y1), |x, y, p| {
                let t = f64::from(x - x0) / w;
                let t = if i % 2 == 0 { t } else { 1.0 - t };
                let on = (f64::from(y - y0) - t * h).abs() < f64::from(BEAM) * 0.7;
                if on { wood } else { p }
            });
        }
    }
}

fn bricks(c: &mut Canvas, r: PxRect, brick: Colour, mortar: Colour, rng: &mut Pcg64) {
    let cols = r.width() / BRICK + 2;
    let rows = r.height() / COURSE + 1;
    // One colour offset per brick, some bricks darker or lighter than the rest.
    let offsets: Vec<i32> = (0..cols * rows)
        .map(|_| {
            let roll: u32 = rng.random_range(0..12);
            rng.random_range(-12..=12)
                + if roll == 0 {
                    -28
                } else if roll == 1 {
                    18
                } else {
                    0
                }
        })
        .collect();
    let mut noise = Grain::new(rng);
    c.each(r, |x, y, _| {
        let (lx, ly) = (x - r.x0, y - r.y0);
        let row = ly / COURSE;
        let shift = if row.is_multiple_of(2) { 0 } else { BRICK / 2 };
        let col = (lx + shift) / BRICK;
        let in_joint = ly % COURSE >= COURSE - 2 || (lx + shift) % BRICK >= BRICK - 2;
        let grain = noise.next(6);
        if in_joint {
            mortar.map(|v| add(v, grain))
        } else {
            let o = offsets[(row * cols + col) as usize];
            // The brick's top edge catches a little light.
            let lit = if ly % COURSE == 0 { 8 } else { 0 };
            brick.map(|v| add(v, o + grain + lit))
        }
    });
}

fn plaster(c: &mut Canvas, r: PxRect, colour: Colour, rng: &mut Pcg64) {
    let gw = r.width() / BLOTCH + 2;
    let gh = r.height() / BLOTCH + 2;
    let grid: Vec<f64> = (0..gw * gh).map(|_| rng.random_range(-7.0..7.0)).collect();
    let mut noise = Grain::new(rng);
    let at = |gx: u32, gy: u32| grid[(gy * gw + gx) as usize];
    // The blotch is bilinear in the grid: each column's mix along x of the grid rows above
    // and below is the same for every pixel row of a grid band, so it is worked out once
    // a band (the same sums as per pixel, so the same values).
    let columns: Vec<(u32, f64)> = (0..r.width())
        .map(|dx| {
            let fx = f64::from(dx) / f64::from(BLOTCH);
            let ix = fx as u32;
            (ix, fx - f64::from(ix))
        })
        .collect();
    let mut band = (u32::MAX, Vec::new(), Vec::new());
    let mut row = (u32::MAX, 0.0);
    c.each(r, |x, y, _| {
        if row.0 != y {
            let fy = f64::from(y - r.y0) / f64::from(BLOTCH);
            let iy = fy as u32;
            if band.0 != iy {
                let along = |gy: u32| -> Vec<f64> {
                    columns
                        .iter()
                        .map(|&(ix, tx)| at(ix, gy) * (1.0 - tx) + at(ix + 1, gy) * tx)
                        .collect()
                };
                band = (iy, along(iy), along(iy + 1));
            }
            row = (y, fy - f64::from(iy));
        }
        let (i, ty) = ((x - r.x0) as usize, row.1);
        let blotch = round_i32(band.1[i] * (1.0 - ty) + band.2[i] * ty);
        let grain = noise.next(3);
        colour.map(|v| add(v, blotch + grain))
    });
}

/// Sky above the parapet.
pub fn sky(c: &mut Canvas, r: PxRect) {
    c.gradient(r, [150, 182, 214], [200, 216, 230]);
}

/// A molding band: lit top edge, body, shadowed underside and a shadow on the wall below.
pub fn molding(c: &mut Canvas, r: PxRect, trim: Colour, rng: &mut Pcg64) {
    c.fill_grain(r, trim, 3, rng);
    c.shade(rect(r.x0, r.y0, r.x1, r.y0 + 2), 1.12);
    c.shade(rect(r.x0, r.y1 - 2, r.x1, r.y1), 0.75);
    shadow_below(c, r, 4);
}

/// A cornice: cap, dentil course, underside, and a deeper shadow on the wall below.
pub fn cornice(c: &mut Canvas, r: PxRect, trim: Colour, rng: &mut Pcg64) {
    let h = r.height();
    c.fill_grain(r, trim, 3, rng);
    c.shade(rect(r.x0, r.y0, r.x1, r.y0 + h / 5), 1.12);
    let (d0, d1) = (r.y0 + h * 2 / 5, r.y0 + h * 7 / 10);
    c.each(rect(r.x0, d0, r.x1, d1), |x, _, p| {
        if (x - r.x0) % 10 >= 6 {
            scale(p, 0.62)
        } else {
            p
        }
    });
    c.shade(rect(r.x0, d1 - 1, r.x1, d1), 0.8);
    c.shade(rect(r.x0, r.y1 - h / 5, r.x1, r.y1), 0.78);
    shadow_below(c, r, 7);
}

/// Darkens `depth` rows of wall under `r`, most at the top.
pub fn shadow_below(c: &mut Canvas, r: PxRect, depth: u32) {
    for i in 0..depth {
        let factor = 0.62 + 0.38 * f64::from(i) / f64::from(depth);
        c.shade(rect(r.x0, r.y1 + i, r.x1, r.y1 + i + 1), factor);
    }
}

/// A stone plinth along the bottom.
pub fn plinth(c: &mut Canvas, r: PxRect, trim: Colour, rng: &mut Pcg64) {
    let stone = mix(scale(trim, 0.78), [120, 118, 112], 0.5);
    c.fill_grain(r, stone, 5, rng);
    c.shade(rect(r.x0, r.y0, r.x1, r.y0 + 2), 1.15);
}

/// A pilaster: a vertical stone strip with block joints.
pub fn pilaster(c: &mut Canvas, r: PxRect, trim: Colour, rng: &mut Pcg64) {
    c.fill_grain(r, trim, 3, rng);
    c.each(r, |x, y, p| {
        if (y - r.y0) % 26 == 25 {
            scale(p, 0.8)
        } else if x == r.x0 {
            scale(p, 1.1)
        } else if x + 3 >= r.x1 {
            scale(p, 0.8)
        } else {
            p
        }
    });
}
