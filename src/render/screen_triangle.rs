//! World triangle + view → [`ScreenTri`]s: back-face cull, near-plane (and guard-band)
//! clipping, projection, fixed-point edge functions and perspective-correct attribute
//! planes.
//!
//! Vertices snap to 1/256 pixel. Edge functions are exact 64-bit integers evaluated at
//! pixel centres, and a pixel centre exactly on an edge belongs to the triangle only when
//! that edge is a top or left edge: two triangles sharing an edge never both cover a pixel,
//! and leave no gap between them.

use super::prepared_scene::Triangle;
use super::view::{View, plane};
use crate::model::geometry::dot;
use crate::model::geometry::rounding::round;

/// Fixed-point subpixel steps per pixel.
pub(crate) const SUB: i64 = 256;

/// A triangle ready to rasterize at the internal resolution.
pub(crate) struct ScreenTri {
    /// Edge functions `a·X + b·Y + c` on fixed-point pixel positions, biased by the fill
    /// rule: the pixel is covered when all three are ≥ 0.
    pub edges: [[i64; 3]; 3],
    /// Pixel bounds `[x0, y0, x1, y1)`, inside the image.
    pub bounds: [u32; 4],
    /// Reference point (vertex 0, pixels) of the attribute planes.
    pub origin: [f64; 2],
    /// Planes `[d/dx, d/dy, value at origin]` of 1/w, u/w and v/w.
    pub q: [f64; 3],
    pub uq: [f64; 3],
    pub vq: [f64; 3],
    /// Index into the prepared scene's triangles.
    pub source: u32,
}

impl ScreenTri {
    /// 1/w at the centre of pixel `(x, y)`, with the arithmetic of [`ScreenTri::rasterize`].
    #[inline]
    pub(crate) fn pixel_q(&self, x: u32, y: u32) -> f64 {
        let row = self.q[2] + self.q[1] * (f64::from(y) + 0.5 - self.origin[1]);
        row + self.q[0] * (f64::from(x) + 0.5 - self.origin[0])
    }

    /// Calls `cover(x, y, q)` for every covered pixel inside `[x0, x1) × [y0, y1)`, block
    /// by block of [`BLOCK`] × [`BLOCK`] pixels: a block wholly inside the triangle
    /// (every edge function non-negative at its four corner pixels, so at all its pixels:
    /// they are linear) is covered without testing its pixels, one wholly outside an edge
    /// is skipped, and only the blocks an edge crosses test each pixel. The pixels covered
    /// and their `q` are those of a test of every pixel; they come block by block, so a
    /// caller must not depend on their order (depth tests and coverage masks do not).
    #[inline]
    pub(crate) fn rasterize(&self, clip: [u32; 4], mut cover: impl FnMut(u32, u32, f64)) {
        let x0 = self.bounds[0].max(clip[0]);
        let y0 = self.bounds[1].max(clip[1]);
        let x1 = self.bounds[2].min(clip[2]);
        let y1 = self.bounds[3].min(clip[3]);
        if x0 >= x1 || y0 >= y1 {
            return;
        }
        let edges = self.edges;
        let centre = |v: u32| i64::from(v) * SUB + SUB / 2;
        let (qx, qy) = (self.q[0], self.q[1]);
        let row_q = |y: u32| self.q[2] + qy * (f64::from(y) + 0.5 - self.origin[1]);
        let pixel_q = |row_q: f64, x: u32| row_q + qx * (f64::from(x) + 0.5 - self.origin[0]);
        for by in (y0..y1).step_by(BLOCK as usize) {
            let by1 = (by + BLOCK).min(y1);
            for bx in (x0..x1).step_by(BLOCK as usize) {
                let bx1 = (bx + BLOCK).min(x1);
                // Each edge's least and greatest value over the block's corner pixels.
                let (cx0, cx1, cy0, cy1) =
                    (centre(bx), centre(bx1 - 1), centre(by), centre(by1 - 1));
                let mut inside = true;
                let mut outside = false;
                for e in &edges {
                    let (ex0, ex1) = (e[0] * cx0, e[0] * cx1);
                    let (ey0, ey1) = (e[1] * cy0, e[1] * cy1);
                    let least = ex0.min(ex1) + ey0.min(ey1) + e[2];
                    let most = ex0.max(ex1) + ey0.max(ey1) + e[2];
                    inside &= least >= 0;
                    outside |= most < 0;
                }
                if outside {
                    continue;
                }
                if inside {
                    for y in by..by1 {
                        let rq = row_q(y);
                        for x in bx..bx1 {
                            cover(x, y, pixel_q(rq, x));
                        }
                    }
                    continue;
                }
                let [e0, e1, e2] = edges;
                for y in by..by1 {
                    let py = centre(y);
                    let mut w0 = e0[0] * cx0 + e0[1] * py + e0[2];
                    let mut w1 = e1[0] * cx0 + e1[1] * py + e1[2];
                    let mut w2 = e2[0] * cx0 + e2[1] * py + e2[2];
                    let rq = row_q(y);
                    for x in bx..bx1 {
                        if (w0 | w1 | w2) >= 0 {
                            cover(x, y, pixel_q(rq, x));
                        }
                        w0 += e0[0] * SUB;
                        w1 += e1[0] * SUB;
                        w2 += e2[0] * SUB;
                    }
                }
            }
        }
    }
}

/// Side of the blocks [`ScreenTri::rasterize`] tests whole, pixels.
const BLOCK: u32 = 8;

#[inline]
pub(crate) fn at(p: &[f64; 3], origin: [f64; 2], x: f64, y: f64) -> f64 {
    p[2] + p[0] * (x - origin[0]) + p[1] * (y - origin[1])
}

/// A vertex during clipping: camera coordinates and uv.
#[derive(Clone, Copy)]
struct ClipVert {
    c: [f64; 3],
    uv: [f64; 2],
}

/// Appends the screen triangles of `tri` (none, one, or a fan after clipping).
pub(crate) fn setup(tri: &Triangle, source: u32, view: &View, out: &mut Vec<ScreenTri>) {
    let p = tri.p.map(|v| v.map(f64::from));
    // Back faces: the eye is not on the front side of the triangle's plane.
    let n = tri.normal.map(f64::from);
    let to_eye = [
        view.eye[0] - p[0][0],
        view.eye[1] - p[0][1],
        view.eye[2] - p[0][2],
    ];
    let facing = dot(n, to_eye);
    if facing.is_nan() || facing <= 0.0 {
        return;
    }
    let c = p.map(|v| view.to_camera(v));
    if c.iter().all(|v| v[2] < view.near) || c.iter().all(|v| v[2] > view.far) {
        return;
    }
    if view
        .viewport_planes
        .iter()
        .any(|pl| c.iter().all(|v| plane(pl, v) < 0.0))
    {
        return;
    }
    let verts: [ClipVert; 3] = std::array::from_fn(|i| ClipVert {
        c: c[i],
        uv: tri.uv[i].map(f64::from),
    });
    let needs_clip = c
        .iter()
        .any(|v| v[2] < view.near || view.guard_planes.iter().any(|pl| plane(pl, v) < 0.0));
    if !needs_clip {
        emit(&verts, source, view, out);
        return;
    }
    let mut poly = clip(&verts, |v| v.c[2] - view.near);
    for pl in &view.guard_planes {
        if poly.len() < 3 {
            return;
        }
        if poly.iter().any(|v| plane(pl, &v.c) < 0.0) {
            poly = clip(&poly, |v| plane(pl, &v.c));
        }
    }
    for i in 1..poly.len().saturating_sub(1) {
        emit(&[poly[0], poly[i], poly[i + 1]], source, view, out);
    }
}

/// Sutherland–Hodgman against one plane (`distance ≥ 0` is inside).
fn clip(poly: &[ClipVert], distance: impl Fn(&ClipVert) -> f64) -> Vec<ClipVert> {
    let mut out = Vec::with_capacity(poly.len() + 2);
    for (i, a) in poly.iter().enumerate() {
        let b = &poly[(i + 1) % poly.len()];
        let (da, db) = (distance(a), distance(b));
        if da >= 0.0 {
            out.push(*a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            let t = da / (da - db);
            let lerp = |x: f64, y: f64| x + (y - x) * t;
            out.push(ClipVert {
                c: [
                    lerp(a.c[0], b.c[0]),
                    lerp(a.c[1], b.c[1]),
                    lerp(a.c[2], b.c[2]),
                ],
                uv: [lerp(a.uv[0], b.uv[0]), lerp(a.uv[1], b.uv[1])],
            });
        }
    }
    out
}

/// Projects a triangle whose vertices are in front of the near plane and within the guard
/// band, and sets up its edges and planes.
fn emit(v: &[ClipVert; 3], source: u32, view: &View, out: &mut Vec<ScreenTri>) {
    let mut fixed = [[0i64; 2]; 3];
    let mut pix = [[0f64; 2]; 3];
    let mut attr = [[0f64; 3]; 3];
    for i in 0..3 {
        let [x, y] = view.project(v[i].c);
        if !(x.is_finite() && y.is_finite()) {
            return;
        }
        pix[i] = [x, y];
        fixed[i] = [round(x * SUB as f64) as i64, round(y * SUB as f64) as i64];
        let q = 1.0 / v[i].c[2];
        attr[i] = [q, v[i].uv[0] * q, v[i].uv[1] * q];
    }
    let area = cross(fixed[0], fixed[1], fixed[2]);
    if area == 0 {
        return;
    }
    if area < 0 {
        fixed.swap(1, 2);
        pix.swap(1, 2);
        attr.swap(1, 2);
    }
    let min_x = fixed.iter().map(|f| f[0]).min().expect("three vertices");
    let max_x = fixed.iter().map(|f| f[0]).max().expect("three vertices");
    let min_y = fixed.iter().map(|f| f[1]).min().expect("three vertices");
    let max_y = fixed.iter().map(|f| f[1]).max().expect("three vertices");
    // Pixels whose centre `i·SUB + SUB/2` lies within the vertices' range.
    let first = |m: i64| (m - SUB / 2 + SUB - 1).div_euclid(SUB);
    let last = |m: i64| (m - SUB / 2).div_euclid(SUB) + 1;
    let x0 = first(min_x).clamp(0, i64::from(view.width));
    let x1 = last(max_x).clamp(0, i64::from(view.width));
    let y0 = first(min_y).clamp(0, i64::from(view.height));
    let y1 = last(max_y).clamp(0, i64::from(view.height));
    if x0 >= x1 || y0 >= y1 {
        return;
    }
    let edges: [[i64; 3]; 3] = std::array::from_fn(|i| {
        let a = fixed[i];
        let b = fixed[(i + 1) % 3];
        let d = [b[0] - a[0], b[1] - a[1]];
        let top_left = (d[1] == 0 && d[0] > 0) || d[1] < 0;
        // E(p) = d × (p − a) = −d.y·p.x + d.x·p.y + (d.y·a.x − d.x·a.y).
        let c = d[1] * a[0] - d[0] * a[1] - if top_left { 0 } else { 1 };
        [-d[1], d[0], c]
    });
    // Attribute planes from the unsnapped positions: snapping moves vertices by up to
    // 1/512 px, which near the horizon would shift depths by centimetres.
    let (dx1, dy1) = (pix[1][0] - pix[0][0], pix[1][1] - pix[0][1]);
    let (dx2, dy2) = (pix[2][0] - pix[0][0], pix[2][1] - pix[0][1]);
    let det = dx1 * dy2 - dx2 * dy1;
    if !det.is_finite() || det.abs() <= 1e-9 {
        // A sliver: no stable planes; it covers next to nothing, so skip it.
        return;
    }
    let planes: [[f64; 3]; 3] = std::array::from_fn(|k| {
        let (a0, a1, a2) = (attr[0][k], attr[1][k], attr[2][k]);
        [
            ((a1 - a0) * dy2 - (a2 - a0) * dy1) / det,
            ((a2 - a0) * dx1 - (a1 - a0) * dx2) / det,
            a0,
        ]
    });
    out.push(ScreenTri {
        edges,
        bounds: [x0 as u32, y0 as u32, x1 as u32, y1 as u32],
        origin: pix[0],
        q: planes[0],
        uq: planes[1],
        vq: planes[2],
        source,
    });
}

fn cross(a: [i64; 2], b: [i64; 2], c: [i64; 2]) -> i64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
}
