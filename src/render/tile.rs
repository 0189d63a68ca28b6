//! One tile of the frame: binned screen triangles → depth and triangle ids per sample →
//! shaded linear colour → resolved pixels (linear colour, instance id, depth in metres,
//! and where the pixel's triangle ends).
//!
//! A tile owns its pixels, reads shared data only, and visits its triangles in scene
//! order, so its output does not depend on which thread runs it or when.

use std::cell::Cell;

use super::Lighting;
use super::lit_windows::WindowLookup;
use super::mip_texture::{Footprint, MAX_ANISOTROPY};
use super::point_lights::{self, FrameLight};
use super::prepared_scene::{PreparedScene, ShadeMaterial, Triangle};
use super::screen_triangle::{ScreenTri, at};
use super::shadow_map::{Receiver, ShadowMap};
use super::view::View;
use crate::model::geometry::dot;

/// Most anisotropic texture taps on level surfaces (roads, sidewalks, plazas, roofs),
/// against [`MAX_ANISOTROPY`] on walls, signs and plates, where text is: one, plain
/// trilinear. Level surfaces are seen at the steepest slants, so they would need the most
/// taps, but their textures are fine noise (asphalt, paving, grass, tiles): slightly
/// softer in the distance, they look the same. Four taps cost 15 % more instructions per
/// frame than two, two about 4 % more than one.
const LEVEL_SURFACE_TAPS: f64 = 1.0;

/// Tile side in output pixels.
pub(crate) const TILE: u32 = 32;

/// What rasterizing every tile of a frame shares: the screen triangles. All that ids,
/// depth and visibility need.
pub(crate) struct RasterContext<'a> {
    pub scene: &'a PreparedScene,
    pub view: &'a View,
    pub tris: &'a [ScreenTri],
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

impl<'a> RasterContext<'a> {
    /// The context of `tris`, seen from `view` at `samples` per pixel side, for a frame
    /// `width` × `height` output pixels.
    pub(crate) fn new(
        scene: &'a PreparedScene,
        view: &'a View,
        tris: &'a [ScreenTri],
        samples: u32,
        (width, height): (u32, u32),
    ) -> RasterContext<'a> {
        RasterContext {
            scene,
            view,
            tris,
            samples,
            width,
            height,
            tiles_x: width.div_ceil(TILE),
            q_range: super::q_range(view),
        }
    }
}

/// What shading every tile of a frame shares: its raster, and its light.
pub(crate) struct FrameContext<'a> {
    pub raster: RasterContext<'a>,
    pub lighting: &'a Lighting,
    pub lights: &'a [FrameLight],
    pub windows: Option<&'a WindowLookup>,
    pub shadows: Option<&'a ShadowMap>,
    /// Whether edges are antialiased from coverage (at one sample per pixel).
    pub antialias_edges: bool,
}

/// Where a tile's pixels go: its rows' stretches of the frame's buffers, top to bottom
/// ([`TileTarget::all`]). Shading writes them in place; no tile is copied afterwards.
pub(crate) struct TileTarget<'f> {
    pub linear: Vec<&'f mut [[f32; 3]]>,
    pub instance: Vec<&'f mut [u32]>,
    pub depth: Vec<&'f mut [f32]>,
    /// Camera-space surface normals, when the frame writes them.
    pub normal: Option<Vec<&'f mut [[f32; 3]]>>,
}

impl<'f> TileTarget<'f> {
    /// The targets of every tile of a frame `width` pixels wide, in tile order (row-major
    /// over the grid of [`TILE`]-pixel tiles), cut from its row-major buffers.
    pub(crate) fn all(
        width: usize,
        linear: &'f mut [[f32; 3]],
        instance: &'f mut [u32],
        depth: &'f mut [f32],
        normal: Option<&'f mut [[f32; 3]]>,
    ) -> Vec<TileTarget<'f>> {
        if width == 0 {
            return Vec::new();
        }
        let tile = TILE as usize;
        let (tiles_x, tiles_y) = (width.div_ceil(tile), (linear.len() / width).div_ceil(tile));
        let mut targets: Vec<TileTarget> = (0..tiles_x * tiles_y)
            .map(|_| TileTarget {
                linear: Vec::with_capacity(tile),
                instance: Vec::with_capacity(tile),
                depth: Vec::with_capacity(tile),
                normal: normal.is_some().then(|| Vec::with_capacity(tile)),
            })
            .collect();
        if let Some(normal) = normal {
            for (y, row) in normal.chunks_mut(width).enumerate() {
                let band = &mut targets[y / tile * tiles_x..][..tiles_x];
                for (target, piece) in band.iter_mut().zip(row.chunks_mut(tile)) {
                    target.normal.as_mut().expect("made above").push(piece);
                }
            }
        }
        let rows = linear
            .chunks_mut(width)
            .zip(instance.chunks_mut(width))
            .zip(depth.chunks_mut(width));
        for (y, ((linear, instance), depth)) in rows.enumerate() {
            let band = &mut targets[y / tile * tiles_x..][..tiles_x];
            let pieces = linear
                .chunks_mut(tile)
                .zip(instance.chunks_mut(tile))
                .zip(depth.chunks_mut(tile));
            for (target, ((linear, instance), depth)) in band.iter_mut().zip(pieces) {
                target.linear.push(linear);
                target.instance.push(instance);
                target.depth.push(depth);
            }
        }
        targets
    }
}

/// No triangle at a sample: the sky.
pub(crate) const NOTHING: u32 = u32::MAX;

/// A tile's visibility: 1/w and triangle (index into the frame's screen triangles, or
/// [`NOTHING`]) per internal sample, row-major over `inner`.
pub(crate) struct TileRaster {
    /// Output pixels `[x0, y0, x1, y1)`.
    pub rect: [u32; 4],
    /// Internal pixels `[x0, y0, x1, y1)`.
    pub inner: [u32; 4],
    pub depth: Vec<f64>,
    pub id: Vec<u32>,
}

impl TileRaster {
    /// Width of `inner`.
    pub(crate) fn inner_width(&self) -> usize {
        (self.inner[2] - self.inner[0]) as usize
    }

    /// Index of the sample nearest the centre of output pixel `(ox, oy)` (tile-local),
    /// the upper-left of the central ones when `s` is even.
    pub(crate) fn centre(&self, ox: usize, oy: usize, s: usize) -> usize {
        let mid = (s - 1) / 2;
        (oy * s + mid) * self.inner_width() + ox * s + mid
    }
}

/// Rasterizes the triangles of `bin` (indices into the frame's screen triangles) into
/// tile number `tile` (row-major over the tile grid): depth test only.
pub(crate) fn raster_tile(ctx: &RasterContext, tile: usize, bin: &[u32]) -> TileRaster {
    let s = ctx.samples;
    let (tx, ty) = (tile as u32 % ctx.tiles_x, tile as u32 / ctx.tiles_x);
    let rect = [
        tx * TILE,
        ty * TILE,
        ((tx + 1) * TILE).min(ctx.width),
        ((ty + 1) * TILE).min(ctx.height),
    ];
    let inner = rect.map(|v| v * s);
    let n = ((inner[2] - inner[0]) * (inner[3] - inner[1])) as usize;
    let mut raster = TileRaster {
        rect,
        inner,
        depth: vec![ctx.q_range.0; n],
        id: vec![NOTHING; n],
    };
    raster_more(ctx, &mut raster, bin);
    raster
}

/// Rasterizes the triangles of `bin` into `raster`, over what it holds: the nearest 1/w
/// wins, and of equal ones the earlier triangle in the scene (so the bytes do not depend
/// on the order triangles come in).
pub(crate) fn raster_more(ctx: &RasterContext, raster: &mut TileRaster, bin: &[u32]) {
    let inner = raster.inner;
    let iw = raster.inner_width();
    let (q_max, tris) = (ctx.q_range.1, ctx.tris);
    let TileRaster { depth, id, .. } = raster;
    for &t in bin {
        let tri = &tris[t as usize];
        tri.rasterize(inner, |x, y, q| {
            let i = (y - inner[1]) as usize * iw + (x - inner[0]) as usize;
            let d = depth[i];
            if (q > d || (q == d && id[i] != NOTHING && tris[id[i] as usize].source > tri.source))
                && q <= q_max
            {
                depth[i] = q;
                id[i] = t;
            }
        });
    }
}

/// Writes a rasterized tile's normals into `out` when the frame has them
/// ([`write_normals`]), then shades it ([`shade_tile`]).
pub(crate) fn finish_tile(
    ctx: &FrameContext,
    raster: &TileRaster,
    ao: Option<&[f32]>,
    mut out: TileTarget,
) {
    if let Some(normal) = out.normal.take() {
        write_normals(&ctx.raster, raster, normal);
    }
    shade_tile(ctx, raster, ao, out);
}

/// Shades and resolves a rasterized tile into `out`, its stretch of the frame. `ao` is the
/// frame's ambient visibility per output pixel (row-major, 1 = open sky), when ambient
/// occlusion is on.
fn shade_tile(ctx: &FrameContext, raster: &TileRaster, ao: Option<&[f32]>, out: TileTarget) {
    let s = ctx.raster.samples;
    let (rect, inner) = (raster.rect, raster.inner);
    let iw = raster.inner_width();
    let (q, id) = (&raster.depth, &raster.id);
    let lights = point_lights::tile_lights(ctx.lights, ctx.raster.view, raster);

    // Resolve, shading once per pixel and triangle: each distinct triangle (or the sky)
    // among a pixel's s × s samples is shaded once, at the sample nearest the centre for
    // the centre's triangle and at its first sample otherwise, and weighted by its share
    // of the samples. Instance and depth come from the sample nearest the pixel centre
    // (the upper-left of the central ones when s is even).
    let (ow, oh) = ((rect[2] - rect[0]) as usize, (rect[3] - rect[1]) as usize);
    let su = s as usize;
    let mid = (su - 1) / 2;
    let norm = 1.0 / (su * su) as f32;
    let TileTarget {
        mut linear,
        mut instance,
        mut depth,
        ..
    } = out;
    debug_assert!(linear.len() == oh && linear.iter().all(|row| row.len() == ow));
    let scale = f64::from(s);
    // The surface of the last triangle shaded: runs of pixels share one.
    let mut last: Option<(u32, Surface)> = None;
    let mut shade_sample = |i: usize, open: f32| -> [f32; 3] {
        let x = inner[0] + (i % iw) as u32;
        let y = inner[1] + (i / iw) as u32;
        match id[i] {
            NOTHING => sky(ctx, x, y),
            t => {
                let surface = match &last {
                    Some((u, surface)) if *u == t => surface,
                    _ => &last.insert((t, Surface::of(ctx, t))).1,
                };
                shade(ctx, surface, x, y, q[i], &lights, scale, open)
            }
        }
    };
    // (triangle, samples, sample to shade) per distinct triangle of a pixel.
    let mut seen: Vec<(u32, u32, usize)> = Vec::with_capacity(su * su);
    for oy in 0..oh {
        for ox in 0..ow {
            let centre = (oy * su + mid) * iw + ox * su + mid;
            let open = ao.map_or(1.0, |ao| {
                ao[(rect[1] as usize + oy) * ctx.raster.width as usize + rect[0] as usize + ox]
            });
            let c = if su == 1 {
                shade_sample(centre, open)
            } else {
                seen.clear();
                seen.push((id[centre], 0, centre));
                for sy in 0..su {
                    for sx in 0..su {
                        let i = (oy * su + sy) * iw + ox * su + sx;
                        match seen.iter_mut().find(|e| e.0 == id[i]) {
                            Some(e) => e.1 += 1,
                            None => seen.push((id[i], 1, i)),
                        }
                    }
                }
                let mut sum = [0f32; 3];
                for &(_, count, i) in &seen {
                    let c = shade_sample(i, open);
                    let w = count as f32 * norm;
                    sum = [sum[0] + c[0] * w, sum[1] + c[1] * w, sum[2] + c[2] * w];
                }
                sum
            };
            linear[oy][ox] = c;
            (instance[oy][ox], depth[oy][ox]) =
                instance_and_depth(&ctx.raster, id[centre], q[centre]);
        }
    }
}

/// A pixel's instance id and depth in metres from its centre sample's triangle `t` and
/// 1/w `q`: (0, 0) for the sky. Frames and [`super::visibility`] both write these.
pub(crate) fn instance_and_depth(ctx: &RasterContext, t: u32, q: f64) -> (u32, f32) {
    match t {
        NOTHING => (0, 0.0),
        t => {
            let tri = &ctx.tris[t as usize];
            (
                ctx.scene.triangles[tri.source as usize].instance,
                depth_metres(q),
            )
        }
    }
}

/// Writes the camera-space normal of each output pixel of `raster` into `out` (its rows):
/// the face normal of the triangle at the pixel's centre sample (the one its id and depth
/// come from) in OpenCV camera axes (x right, y down, z forward), turned to face the
/// camera along the ray through that sample; `[0, 0, 0]` for the sky.
fn write_normals(ctx: &RasterContext, raster: &TileRaster, mut out: Vec<&mut [[f32; 3]]>) {
    let su = ctx.samples as usize;
    let view = ctx.view;
    let (right, up, forward) = (view.basis.right, view.basis.up, view.basis.forward);
    for (oy, row) in out.iter_mut().enumerate() {
        for (ox, n) in row.iter_mut().enumerate() {
            let centre = raster.centre(ox, oy, su);
            let t = raster.id[centre];
            if t == NOTHING {
                *n = [0.0; 3];
                continue;
            }
            let world = ctx.scene.triangles[ctx.tris[t as usize].source as usize]
                .normal
                .map(f64::from);
            let c = [dot(right, world), -dot(up, world), dot(forward, world)];
            // The ray through the centre sample, in the same axes.
            let x = f64::from(raster.inner[0]) + (centre % raster.inner_width()) as f64 + 0.5;
            let y = f64::from(raster.inner[1]) + (centre / raster.inner_width()) as f64 + 0.5;
            let ray = [(x - view.cx) / view.fx, (y - view.cy) / view.fy, 1.0];
            let sign = if dot(c, ray) > 0.0 { -1.0 } else { 1.0 };
            let len = dot(c, c).sqrt();
            *n = c.map(|v| (sign * v / len) as f32);
        }
    }
}

/// Depth `1/q` in metres as `f32`, at least 1e-6 (0 is kept for the sky).
fn depth_metres(q: f64) -> f32 {
    ((1.0 / q) as f32).max(1e-6)
}

/// Sky radiance through internal pixel `(x, y)`.
fn sky(ctx: &FrameContext, x: u32, y: u32) -> [f32; 3] {
    let v = ctx.raster.view;
    let a = (f64::from(x) + 0.5 - v.cx) / v.fx;
    let b = (f64::from(y) + 0.5 - v.cy) / v.fy;
    let (r, u, f) = (v.basis.right, v.basis.up, v.basis.forward);
    let d = [
        f[0] + a * r[0] - b * u[0],
        f[1] + a * r[1] - b * u[1],
        f[2] + a * r[2] - b * u[2],
    ];
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    ctx.lighting.sky.radiance(d.map(|c| c / len))
}

/// What shading needs of a screen triangle's surface that is the same at each of its
/// pixels, worked out once for a run of pixels on it ([`shade_tile`] keeps the last one).
struct Surface<'a> {
    tri: &'a ScreenTri,
    source: &'a Triangle,
    material: &'a ShadeMaterial,
    /// Most anisotropic texture taps.
    taps: f64,
    /// `n · sun` (the sun lights the surface where it is positive), before shadowing.
    sun: f32,
    /// The shadow test's view of the surface, when it faces the sun and shadows are on.
    receiver: Option<Receiver>,
    /// Whether the surface faces the sun while shadows are on: its pixels take the shadow
    /// test, at their point.
    tests_shadow: bool,
    /// Ambient light before occlusion: the sky's from above, the ground's bounce from
    /// below, blended by the normal.
    ambient: [f32; 3],
    /// The texture footprint of the last pixel shaded on the surface (internal `x`, `y`)
    /// when its right neighbour may take it: the first of a pair.
    footprint: Cell<Option<(u32, u32, Footprint)>>,
}

impl<'a> Surface<'a> {
    fn of(ctx: &FrameContext<'a>, t: u32) -> Surface<'a> {
        let scene = ctx.raster.scene;
        let tri = &ctx.raster.tris[t as usize];
        let source = &scene.triangles[tri.source as usize];
        let material = &scene.materials[source.material as usize];
        let taps = if source.normal[1].abs() > 0.9 {
            LEVEL_SURFACE_TAPS
        } else {
            MAX_ANISOTROPY
        };
        let l = ctx.lighting;
        let n = source.normal;
        let sun = n[0] * l.sun_direction[0] + n[1] * l.sun_direction[1] + n[2] * l.sun_direction[2];
        let tests_shadow = sun > 0.0 && ctx.shadows.is_some();
        let receiver = ctx
            .shadows
            .filter(|_| sun > 0.0)
            .and_then(|map| map.receiver(n.map(f64::from)));
        let up = 0.5 + 0.5 * n[1];
        let ambient = std::array::from_fn(|k| {
            l.ground_ambient[k] + (l.ambient[k] - l.ground_ambient[k]) * up
        });
        Surface {
            tri,
            source,
            material,
            taps,
            sun,
            receiver,
            tests_shadow,
            ambient,
            footprint: Cell::new(None),
        }
    }
}

/// Linear colour of `surface` at internal pixel `(x, y)`, where 1/w = `q`; `open` scales
/// its ambient light (ambient occlusion).
// Long on purpose: the per-pixel shader, texture to light in one pass over shared locals.
#[allow(clippy::too_many_arguments)]
fn shade(
    ctx: &FrameContext,
    surface: &Surface,
    x: u32,
    y: u32,
    q: f64,
    lights: &[&FrameLight],
    scale: f64,
    open: f32,
) -> [f32; 3] {
    let scene = ctx.raster.scene;
    let (tri, source, material) = (surface.tri, surface.source, surface.material);
    let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
    // w, the camera-space depth: one division for the texture coordinates, their
    // derivatives and the point.
    let w = 1.0 / q;
    let mut albedo = material.colour;
    let mut emitted = material.emissive;
    let mut window = None;
    if let Some(texture) = material.texture {
        let u = at(&tri.uq, tri.origin, px, py) * w;
        let v = at(&tri.vq, tri.origin, px, py) * w;
        let (u, v) = if u.is_finite() && v.is_finite() {
            (u, v)
        } else {
            (0.0, 0.0)
        };
        let mips = &scene.textures[texture as usize];
        // Pixels are shaded in pairs along a row: the second of two neighbours on one
        // surface takes the first's footprint (the derivatives change by a fraction of a
        // percent from one pixel to the next): every other pixel skips working out the
        // footprint (derivatives, tap count, level).
        let footprint = match surface.footprint.take() {
            Some((fx, fy, footprint)) if fx + 1 == x && fy == y => footprint,
            _ => {
                // d(u/w · w)/dx = (d(u/w)/dx − u · d(1/w)/dx) · w, and likewise for v
                // and y. Scaled to output pixels: a pixel is shaded once, whatever its
                // samples.
                let ws = w * scale;
                let d = [
                    (tri.uq[0] - u * tri.q[0]) * ws,
                    (tri.vq[0] - v * tri.q[0]) * ws,
                    (tri.uq[1] - u * tri.q[1]) * ws,
                    (tri.vq[1] - v * tri.q[1]) * ws,
                ];
                let footprint = mips.footprint(d, surface.taps);
                surface.footprint.set(Some((x, y, footprint)));
                footprint
            }
        };
        let t = mips.sample_at(u, v, &footprint);
        albedo = [albedo[0] * t[0], albedo[1] * t[1], albedo[2] * t[2]];
        if material.emissive_textured {
            emitted = [emitted[0] * t[0], emitted[1] * t[1], emitted[2] * t[2]];
        }
        if let Some(glow) = ctx
            .windows
            .and_then(|w| w.glow(texture, source.instance, u, v))
        {
            window = Some((glow, t));
        }
    }
    let l = ctx.lighting;
    let n = source.normal;
    let needs_point = !lights.is_empty() || surface.tests_shadow;
    let p = if needs_point {
        ctx.raster.view.unproject(px, py, w)
    } else {
        [0.0; 3]
    };
    let sun = if surface.sun <= 0.0 {
        0.0
    } else if ctx.shadows.is_some() {
        let lit = surface
            .receiver
            .as_ref()
            .zip(ctx.shadows)
            .map_or(0.0, |(r, map)| map.light_at(p, r));
        surface.sun * (1.0 - l.shadow_strength.clamp(0.0, 1.0) * (1.0 - lit))
    } else {
        surface.sun
    };
    let a = surface.ambient;
    let mut light = [
        a[0] * open + l.sun_colour[0] * sun,
        a[1] * open + l.sun_colour[1] * sun,
        a[2] * open + l.sun_colour[2] * sun,
    ];
    point_lights::add_lights(&mut light, lights, p, n);
    let e = l.emission;
    let mut out = [
        albedo[0] * light[0] + emitted[0] * e,
        albedo[1] * light[1] + emitted[1] * e,
        albedo[2] * light[2] + emitted[2] * e,
    ];
    if let Some((glow, t)) = window {
        for c in 0..3 {
            out[c] += glow[c] * (0.5 + 0.5 * t[c]);
        }
    }
    out
}
