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
