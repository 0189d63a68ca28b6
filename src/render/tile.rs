//! One tile of the frame: binned screen triangles → depth and triangle ids per sample →
//! shaded linear colour → resolved pixels (RGB, instance id, depth in metres).
//!
//! A tile owns its pixels, reads shared data only, and visits its triangles in scene
//! order, so its output does not depend on which thread runs it or when.

use super::Lighting;
use super::lit_windows::WindowLookup;
use super::prepared_scene::PreparedScene;
use super::screen_triangle::{ScreenTri, at};
use super::srgb::srgb;
use super::view::View;

/// Tile side in output pixels.
pub(crate) const TILE: u32 = 32;

/// A point light of this frame, with its conservative footprint in internal pixels.
pub(crate) struct FrameLight {
    pub position: [f64; 3],
    pub colour: [f32; 3],
    pub range2: f64,
    /// `[x0, y0, x1, y1)` internal pixels the light may reach.
    pub rect: [u32; 4],
}

/// What every tile of a frame shares.
pub(crate) struct FrameContext<'a> {
    pub scene: &'a PreparedScene,
    pub view: &'a View,
    pub lighting: &'a Lighting,
    pub tris: &'a [ScreenTri],
    pub bins: &'a [Vec<u32>],
    pub lights: &'a [FrameLight],
    pub windows: Option<&'a WindowLookup>,
    /// Samples per pixel side.
    pub samples: u32,
    /// Output size.
    pub width: u32,
    pub height: u32,
    pub tiles_x: u32,
    /// Accepted 1/w: above 1/far, at most 1.0001/near (nothing is nearer than the near
    /// plane; a larger 1/w is a rounding artefact).
    pub q_range: (f64, f64),
}

/// A finished tile: its rectangle in output pixels and its pixels, row-major.
pub(crate) struct TileOut {
    pub rect: [u32; 4],
    pub rgb: Vec<u8>,
    pub instance: Vec<u32>,
    pub depth: Vec<f32>,
}

const NOTHING: u32 = u32::MAX;

/// Renders tile number `tile` (row-major over the tile grid).
pub(crate) fn render_tile(ctx: &FrameContext, tile: usize) -> TileOut {
    let s = ctx.samples;
    let (tx, ty) = (tile as u32 % ctx.tiles_x, tile as u32 / ctx.tiles_x);
    let rect = [
        tx * TILE,
        ty * TILE,
        ((tx + 1) * TILE).min(ctx.width),
        ((ty + 1) * TILE).min(ctx.height),
    ];
    let inner = rect.map(|v| v * s);
    let (iw, ih) = (
        (inner[2] - inner[0]) as usize,
        (inner[3] - inner[1]) as usize,
    );

    // Visibility: nearest 1/w wins; ties go to the earlier triangle.
    let (q_min, q_max) = ctx.q_range;
    let mut depth = vec![q_min; iw * ih];
    let mut id = vec![NOTHING; iw * ih];
    for &t in &ctx.bins[tile] {
        ctx.tris[t as usize].rasterize(inner, |x, y, q| {
            let i = (y - inner[1]) as usize * iw + (x - inner[0]) as usize;
            if q > depth[i] && q <= q_max {
                depth[i] = q;
                id[i] = t;
            }
        });
    }

    let lights: Vec<&FrameLight> = ctx
        .lights
        .iter()
        .filter(|l| {
            l.rect[0] < inner[2]
                && inner[0] < l.rect[2]
                && l.rect[1] < inner[3]
                && inner[1] < l.rect[3]
        })
        .collect();
    let sky = ctx.lighting.sky;
    let colour: Vec<[f32; 3]> = (0..iw * ih)
        .map(|i| match id[i] {
            NOTHING => sky,
            t => {
                let x = inner[0] + (i % iw) as u32;
                let y = inner[1] + (i / iw) as u32;
                shade(ctx, &ctx.tris[t as usize], x, y, depth[i], &lights)
            }
        })
        .collect();

    // Resolve: colour averaged over the s × s samples; instance and depth from the sample
    // nearest the pixel centre (the upper-left of the central ones when s is even).
    let table = srgb();
    let (ow, oh) = ((rect[2] - rect[0]) as usize, (rect[3] - rect[1]) as usize);
    let s = s as usize;
    let mid = (s - 1) / 2;
    let norm = 1.0 / (s * s) as f32;
    let mut out = TileOut {
        rect,
        rgb: Vec::with_capacity(ow * oh * 3),
        instance: Vec::with_capacity(ow * oh),
        depth: Vec::with_capacity(ow * oh),
    };
    for oy in 0..oh {
        for ox in 0..ow {
            let mut sum = [0f32; 3];
            for sy in 0..s {
                for sx in 0..s {
                    let c = colour[(oy * s + sy) * iw + ox * s + sx];
                    sum = [sum[0] + c[0], sum[1] + c[1], sum[2] + c[2]];
                }
            }
            for c in sum {
                out.rgb.push(table.to_srgb8(c * norm));
            }
            let centre = (oy * s + mid) * iw + ox * s + mid;
            match id[centre] {
                NOTHING => {
                    out.instance.push(0);
                    out.depth.push(0.0);
                }
                t => {
                    let tri = &ctx.tris[t as usize];
                    out.instance
                        .push(ctx.scene.triangles[tri.source as usize].instance);
                    out.depth.push(depth_metres(depth[centre]));
                }
            }
        }
    }
    out
}

/// Depth `1/q` in metres as `f32`, at least 1e-6 (0 is kept for the sky).
fn depth_metres(q: f64) -> f32 {
    ((1.0 / q) as f32).max(1e-6)
}

/// Linear colour of the surface of `tri` at internal pixel `(x, y)`, where 1/w = `q`.
fn shade(
    ctx: &FrameContext,
    tri: &ScreenTri,
    x: u32,
    y: u32,
    q: f64,
    lights: &[&FrameLight],
) -> [f32; 3] {
    let scene = ctx.scene;
    let source = &scene.triangles[tri.source as usize];
    let material = &scene.materials[source.material as usize];
    let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
    let mut albedo = material.colour;
    let mut window = None;
    if let Some(texture) = material.texture {
        let u = at(&tri.uq, tri.origin, px, py) / q;
        let v = at(&tri.vq, tri.origin, px, py) / q;
        let (u, v) = if u.is_finite() && v.is_finite() {
            (u, v)
        } else {
            (0.0, 0.0)
        };
        // d(u/w · w)/dx = (d(u/w)/dx − u · d(1/w)/dx) · w, and likewise for v and y.
        let d = [
            (tri.uq[0] - u * tri.q[0]) / q,
            (tri.vq[0] - v * tri.q[0]) / q,
            (tri.uq[1] - u * tri.q[1]) / q,
            (tri.vq[1] - v * tri.q[1]) / q,
        ];
        let t = scene.textures[texture as usize].sample(u, v, d);
        albedo = [albedo[0] * t[0], albedo[1] * t[1], albedo[2] * t[2]];
        if let Some(w) = ctx.windows
            && w.is_lit(texture, source.instance, u, v)
        {
            window = Some((w.colour, t));
        }
    }
    let l = ctx.lighting;
    let n = source.normal;
    let sun = (n[0] * l.sun_direction[0] + n[1] * l.sun_direction[1] + n[2] * l.sun_direction[2])
        .max(0.0);
    let mut light = [
        l.ambient[0] + l.sun_colour[0] * sun,
        l.ambient[1] + l.sun_colour[1] * sun,
        l.ambient[2] + l.sun_colour[2] * sun,
    ];
    if !lights.is_empty() {
        let p = ctx.view.unproject(px, py, 1.0 / q);
        for lamp in lights {
            let d = [
                lamp.position[0] - p[0],
                lamp.position[1] - p[1],
                lamp.position[2] - p[2],
            ];
            let d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if d2.is_nan() || d2 >= lamp.range2 || d2 <= 0.0 {
                continue;
            }
            let n_dot = (f64::from(n[0]) * d[0] + f64::from(n[1]) * d[1] + f64::from(n[2]) * d[2])
                / d2.sqrt();
            if n_dot <= 0.0 {
                continue;
            }
            let t = 1.0 - d2 / lamp.range2;
            let k = (t * t * n_dot) as f32;
            for (l, c) in light.iter_mut().zip(lamp.colour) {
                *l += c * k;
            }
        }
    }
    let e = l.emission;
    let mut out = [
        albedo[0] * light[0] + material.emissive[0] * e,
        albedo[1] * light[1] + material.emissive[1] * e,
        albedo[2] * light[2] + material.emissive[2] * e,
    ];
    if let Some((glow, t)) = window {
        for c in 0..3 {
            out[c] += glow[c] * (0.5 + 0.5 * t[c]);
        }
    }
    out
}
