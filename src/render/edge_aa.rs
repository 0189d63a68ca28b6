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

use super::tile::NOTHING;

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

/// Marks in `out` the pixels of row `y` with a 4-neighbour that shows another triangle
/// than they do (`tri` the triangle at each pixel's centre, row-major, `width` ×
/// `height`): the only pixels a real edge can pass beside. Whole rows at a time, which
/// the compiler turns into vector compares.
fn boundary_row(tri: &[u32], width: usize, height: usize, y: usize, out: &mut [bool]) {
    let row = &tri[y * width..][..width];
    out.fill(false);
    for x in 1..width {
        let differs = row[x] != row[x - 1];
        out[x] |= differs;
        out[x - 1] |= differs;
    }
    let mut beside = |other: &[u32]| {
        for ((o, a), b) in out.iter_mut().zip(row).zip(other) {
            *o |= a != b;
        }
    };
    if y > 0 {
        beside(&tri[(y - 1) * width..][..width]);
    }
    if y + 1 < height {
        beside(&tri[(y + 1) * width..][..width]);
    }
}

/// Mixes `linear` (row-major, `width` wide) across the real edges, in place. `tri` is the
/// triangle at each pixel's centre ([`NOTHING`] for the sky), `hint(p)` pixel `p`'s hint,
/// and `real(p, q)` whether the boundary between pixels `p` and `q` (indices) is a real
/// edge.
///
/// A mix acts only across a real edge, between two pixels of different triangles, so only
/// pixels with a 4-neighbour of another triangle change, and only their hints are read:
/// both are worked out at those pixels alone (a tenth to a fifth of a street frame).
pub(crate) fn antialias(
    linear: &mut [[f32; 3]],
    tri: &[u32],
    width: usize,
    hint: impl Fn(usize) -> EdgeHint + Sync,
    real: impl Fn(usize, usize) -> bool + Sync,
) {
    let height = linear.len() / width.max(1);
    let mut boundary = super::filled(false, linear.len());
    let mut hints = super::filled(EdgeHint::NONE, linear.len());
    hints
        .par_chunks_mut(width)
        .zip(boundary.par_chunks_mut(width))
        .enumerate()
        .for_each(|(y, (row, marks))| {
            boundary_row(tri, width, height, y, marks);
            for (x, (slot, _)) in row
                .iter_mut()
                .zip(&*marks)
                .enumerate()
                .filter(|(_, (_, m))| **m)
            {
                if tri[y * width + x] != NOTHING {
                    *slot = hint(y * width + x);
                }
            }
        });
    let neighbour = |x: usize, y: usize, dx: i8, dy: i8| -> Option<usize> {
        let nx = x.checked_add_signed(isize::from(dx))?;
        let ny = y.checked_add_signed(isize::from(dy))?;
        (nx < width && ny < height).then_some(ny * width + nx)
    };
    let source: &[[f32; 3]] = linear;
    // Each row's changed pixels, from the unmixed colours; written once all are known.
    let changes: Vec<Vec<(usize, [f32; 3])>> = (0..height)
        .into_par_iter()
        .map(|y| {
            let mut changed = Vec::new();
            let marks = &boundary[y * width..][..width];
            for x in (0..width).filter(|&x| marks[x]) {
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
                    let (a, b) = (source[p], source[mix.1]);
                    changed.push((x, [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * mix.0)));
                }
            }
            changed
        })
        .collect();
    linear
        .par_chunks_mut(width)
        .zip(changes)
        .for_each(|(row, changed)| {
            for (x, c) in changed {
                row[x] = c;
            }
        });
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
        let tri = [0, 0, NOTHING];
        let hint = |p: usize| EdgeHint::of(&edges, 128 + 256 * p as i64, 128, 256);
        let mut out = linear.clone();
        antialias(&mut out, &tri, 3, hint, |_, _| true);
        // Pixel 1 keeps its colour (the edge is in pixel 2); pixel 2 takes 0.3 of white.
        assert_eq!(out[0], [1.0; 3]);
        assert_eq!(out[1], [1.0; 3]);
        assert!((out[2][0] - 0.3008).abs() < 1e-3, "{:?}", out[2]);
        // Not a real edge: nothing moves.
        let mut out = linear.clone();
        antialias(&mut out, &tri, 3, hint, |_, _| false);
        assert_eq!(out, linear);
    }

    #[test]
    fn only_pixels_beside_another_triangle_ask_for_their_hint_or_change() {
        // 4 × 3: triangle 7 but in the last column (triangle 9). Hints are worked out in
        // columns 2 and 3 only; every hint says "an edge 0.2 px to the right", so column 2
        // takes 0.3 of column 3's colour and every other pixel keeps its own.
        let tri: Vec<u32> = (0..12).map(|p| if p % 4 == 3 { 9 } else { 7 }).collect();
        let linear: Vec<[f32; 3]> = (0..12).map(|p| [p as f32; 3]).collect();
        let asked = std::sync::Mutex::new(Vec::new());
        let mut out = linear.clone();
        let hint = |p: usize| {
            asked.lock().unwrap().push(p);
            EdgeHint {
                dx: 1,
                dy: 0,
                d: 0.2,
            }
        };
        antialias(&mut out, &tri, 4, hint, |_, _| true);
        let mut asked = asked.into_inner().unwrap();
        asked.sort();
        assert_eq!(asked, [2, 3, 6, 7, 10, 11]);
        for p in 0..12 {
            if p % 4 == 2 {
                assert!(
                    (out[p][0] - (p as f32 + 0.3)).abs() < 1e-5,
                    "{p}: {:?}",
                    out[p]
                );
            } else {
                assert_eq!(out[p], linear[p], "{p}");
            }
        }
    }
}
