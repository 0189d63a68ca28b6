//! Shaded pixels + the distance from each pixel's centre to the nearest edge of its
//! triangle → antialiased colours: coverage at edges from the geometry itself, at one
//! shaded sample per pixel (geometry-buffer antialiasing, as in Persson's GBAA).
//!
//! Rasterizing sees one sample per pixel, so a roof line or a pole is a staircase. But
//! the triangle that owns a pixel's centre knows exactly where its edges run: at a pixel
//! whose centre lies `d < ½` pixel from an edge (measured along the x or y axis, whichever
//! the edge crosses more steeply), the share `½ − d` of the pixel beyond the edge belongs
//! to the neighbour on the other side, and the two colours mix in that proportion. When
//! the edge lies in the neighbour's pixel instead (`½ ≤ d < 1`), the neighbour takes `d −
//! ½` of this pixel's colour. A pixel takes the larger of the mixes it is offered.
//!
//! Only real edges count: between different objects, between an object and the sky, or
//! where the surface folds (normals differ). The diagonal inside a wall quad, where both
//! triangles continue one surface, is left alone, so textures are not blurred.
//!
//! Only the RGB image changes: instance ids and depth still come from the pixel centre,
//! exact. Each output pixel reads the unmixed colours and writes only itself: the bytes
//! do not depend on threads.

use rayon::prelude::*;

/// Where a pixel's triangle ends nearest its centre: the neighbour across that edge is
/// `(x + dx, y + dy)`, at `d` pixels along that axis. `d ≥ 1` (or the sky): no edge near.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct EdgeHint {
    pub dx: i8,
    pub dy: i8,
    pub d: f32,
}

impl EdgeHint {
    pub(crate) const NONE: EdgeHint = EdgeHint {
        dx: 0,
        dy: 0,
        d: f32::INFINITY,
    };

    /// The hint of a pixel centre at fixed-point position `(px, py)` inside a triangle of
    /// edge functions `edges` (`a·X + b·Y + c ≥ 0` inside, `sub` steps per pixel).
    pub(crate) fn of(edges: &[[i64; 3]; 3], px: i64, py: i64, sub: i64) -> EdgeHint {
        let mut best = EdgeHint::NONE;
        for e in edges {
            let value = e[0] * px + e[1] * py + e[2];
            let (ax, ay) = (e[0].abs(), e[1].abs());
            // Moving one pixel along the steeper axis changes the value by |a| · sub.
            let (step, dx, dy) = if ax >= ay {
                (ax, -e[0].signum(), 0)
            } else {
                (ay, 0, -e[1].signum())
            };
            if step == 0 {
                continue;
            }
            let d = (value.max(0) as f64 / (step * sub) as f64) as f32;
            if d < best.d {
                best = EdgeHint {
                    dx: dx as i8,
                    dy: dy as i8,
                    d,
                };
            }
        }
        if best.d < 1.0 { best } else { EdgeHint::NONE }
    }
}

/// Every pixel's hint, row-major, `width` wide, from the triangle at each pixel's centre
/// (`tri`, [`super::tile::NOTHING`] for the sky): `hint(p)` where a 4-neighbour of pixel `p`
/// shows another triangle, [`EdgeHint::NONE`] elsewhere. A hint acts only across a real
/// edge, between two pixels of different triangles; a pixel whose four neighbours show its
/// own triangle has none beside it, so its hint is never read, and is not worked out.
pub(crate) fn hints(
    tri: &[u32],
    width: usize,
    hint: impl Fn(usize) -> EdgeHint + Sync,
) -> Vec<EdgeHint> {
    let height = tri.len() / width.max(1);
    let mut out = vec![EdgeHint::NONE; tri.len()];
    out.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
        for (x, slot) in row.iter_mut().enumerate() {
            let p = y * width + x;
            let t = tri[p];
            if t == super::tile::NOTHING {
                continue;
            }
            let differs = (x > 0 && tri[p - 1] != t)
                || (x + 1 < width && tri[p + 1] != t)
                || (y > 0 && tri[p - width] != t)
                || (y + 1 < height && tri[p + width] != t);
            if differs {
                *slot = hint(p);
            }
        }
    });
    out
}

/// Mixes `linear` (row-major, `width` wide) across the real edges that `hints` mark;
/// `real(p, q)` says whether the boundary between pixels `p` and `q` (indices) is one.
pub(crate) fn resolve(
    linear: &[[f32; 3]],
    hints: &[EdgeHint],
    width: usize,
    real: impl Fn(usize, usize) -> bool + Sync,
) -> Vec<[f32; 3]> {
    let height = linear.len() / width.max(1);
    let neighbour = |x: usize, y: usize, dx: i8, dy: i8| -> Option<usize> {
        let nx = x.checked_add_signed(isize::from(dx))?;
        let ny = y.checked_add_signed(isize::from(dy))?;
        (nx < width && ny < height).then_some(ny * width + nx)
    };
    let mut out = linear.to_vec();
    out.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
        for (x, slot) in row.iter_mut().enumerate() {
            let p = y * width + x;
            // (weight, neighbour) of the strongest mix offered.
            let mut mix = (0f32, p);
            let h = hints[p];
            if h.d < 0.5
                && let Some(q) = neighbour(x, y, h.dx, h.dy)
                && real(p, q)
            {
                mix = (0.5 - h.d, q);
            }
            for (dx, dy) in [(-1i8, 0i8), (1, 0), (0, -1), (0, 1)] {
                let Some(q) = neighbour(x, y, dx, dy) else {
                    continue;
                };
                let g = hints[q];
                // q's edge points back at p and lies inside p's pixel.
                if g.dx == -dx && g.dy == -dy && g.d >= 0.5 && g.d - 0.5 > mix.0 && real(q, p) {
                    mix = (g.d - 0.5, q);
                }
            }
            if mix.0 > 0.0 {
                let (a, b) = (linear[p], linear[mix.1]);
                *slot = [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * mix.0);
            }
        }
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_vertical_edge_mixes_by_the_distance_to_it() {
        // Left half-plane x ≤ 2.3 px (fixed point, 256 per pixel): −X + 2.3·256 ≥ 0.
        let edges = [[-1, 0, 589], [0, 0, 1 << 40], [0, 0, 1 << 40]];
        // Pixel 1's centre (1.5) is 0.8 px from the edge; pixel 2's (2.5) is outside.
        let h = EdgeHint::of(&edges, 384, 128, 256);
        assert_eq!((h.dx, h.dy), (1, 0));
        assert!((h.d - 0.8008).abs() < 1e-3, "{h:?}");
        // A row: two pixels of the triangle (white), then the sky (black).
        let linear = vec![[1.0; 3], [1.0; 3], [0.0; 3]];
        let hints = vec![EdgeHint::of(&edges, 128, 128, 256), h, EdgeHint::NONE];
        let out = resolve(&linear, &hints, 3, |_, _| true);
        // Pixel 1 keeps its colour (the edge is in pixel 2); pixel 2 takes 0.3 of white.
        assert_eq!(out[0], [1.0; 3]);
        assert_eq!(out[1], [1.0; 3]);
        assert!((out[2][0] - 0.3008).abs() < 1e-3, "{:?}", out[2]);
        // Not a real edge: nothing moves.
        assert_eq!(resolve(&linear, &hints, 3, |_, _| false), linear);
    }
}
