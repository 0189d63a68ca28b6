//! Prepared scene + direction to the sun → [`ShadowMap`]: an orthographic depth map of
//! the whole scene seen from the sun, and the soft shadow test against it.
//!
//! - **Extent and resolution** come from the scene's bounds only: the map covers the box
//!   of the objects that cast shadows (all but the ground, fields and hills: see
//!   `ObjectBounds::casts_shadow`) as seen from the sun, with square texels of `max extent / side` (at
//!   least [`MIN_TEXEL`]). Every frame under the same sun reads the same map, so shadows
//!   cannot crawl as the camera moves.
//! - **Content**: per texel, the largest `p · sun` (the surface nearest the sun) over every
//!   triangle covering the texel centre, both faces, except flat ground at the scene's
//!   lowest level (it can shade nothing). A max does not depend on the order
//!   of the triangles, and bands of rows are rasterized in parallel, each owning its rows.
//! - **Test** at a surface point `p` with normal `n`: `p` is moved one texel along `n`
//!   (normal offset), then compared with a bias of `texel · (0.5 + 2 · tan θ)` (slope
//!   scaled; θ is the angle between `n` and the sun), over a 4 × 4 texel grid weighted as
//!   a 3-texel box filter (percentage-closer filtering with a fixed kernel): soft edges
//!   about three texels wide.

use rayon::prelude::*;

use super::prepared_scene::PreparedScene;
use crate::model::geometry::rounding::floor;
use crate::model::geometry::{cross, dot};

/// Largest side of the map in texels, unless the lighting asks for less
/// ([`super::Lighting::shadow_map_side`]).
pub const MAX_SIDE: u32 = 4096;
/// Smallest texel, metres.
pub(crate) const MIN_TEXEL: f64 = 0.005;
/// Rows per parallel band.
const BAND: usize = 32;
/// Side of an overlay tile, texels ([`ShadowMap::add`]).
const TILE: usize = 16;

/// The scene's depth as seen from the sun.
#[derive(Clone)]
pub(crate) struct ShadowMap {
    /// Towards the sun.
    pub(crate) dir: [f64; 3],
    right: [f64; 3],
    up: [f64; 3],
    origin: [f64; 2],
    pub(crate) texel: f64,
    /// `1 / texel`.
    per_texel: f64,
    width: usize,
    height: usize,
    /// Per texel, row-major; shared by the posed frames' maps built on it.
    depth: std::sync::Arc<Vec<f32>>,
    /// With moving objects added ([`ShadowMap::add`]): the tiles they touch, which
    /// replace `depth`'s there.
    overlay: Option<Overlay>,
}

/// The tiles of a map that moving objects touch: each a copy of the map's texels there
/// with the objects added, made the first time a lookup reads it (a frame reads the few
/// tiles its view shows; the objects touch tiles all over the city). A tile's texels do
/// not depend on when or by which thread it is made.
#[derive(Clone)]
struct Overlay {
    /// Per tile (row-major, [`TILE`] texels a side), its slot, or `u32::MAX`.
    slot: Vec<u32>,
    tiles_x: usize,
    /// Per slot, the objects' triangles (indices into `tris`) whose boxes reach it.
    bins: Vec<Vec<u32>>,
    /// The objects' triangles in texel coordinates and depth towards the sun.
    tris: std::sync::Arc<Vec<[[f64; 3]; 3]>>,
    /// Per slot, its `TILE × TILE` texels, row-major, once made.
    tiles: Vec<std::sync::OnceLock<Box<[f32]>>>,
}

impl Overlay {
    /// The texel at `(x, y)` of `map` (whose overlay this is) when its tile is in the
    /// overlay.
    fn texel(&self, map: &ShadowMap, x: usize, y: usize) -> Option<f32> {
        let (tx, ty) = (x / TILE, y / TILE);
        let slot = self.slot[ty * self.tiles_x + tx];
        (slot != u32::MAX).then(|| self.tile(map, slot, tx, ty)[(y % TILE) * TILE + x % TILE])
    }

    /// Slot `slot`'s texels (tile `(tx, ty)`): the map's there, with its triangles.
    fn tile(&self, map: &ShadowMap, slot: u32, tx: usize, ty: usize) -> &[f32] {
        self.tiles[slot as usize].get_or_init(|| {
            // Texels beyond the map's edge are left empty.
            let mut tile = vec![f32::NEG_INFINITY; TILE * TILE].into_boxed_slice();
            let rows = [ty * TILE, ((ty + 1) * TILE).min(map.height)];
            let cols = [tx * TILE, ((tx + 1) * TILE).min(map.width)];
            for y in rows[0]..rows[1] {
                let to = (y - rows[0]) * TILE;
                tile[to..to + cols[1] - cols[0]]
                    .copy_from_slice(&map.depth[y * map.width + cols[0]..y * map.width + cols[1]]);
            }
            for &i in &self.bins[slot as usize] {
                raster(&self.tris[i as usize], rows, cols, TILE, &mut tile);
            }
            tile
        })
    }

    /// Whether any texel of the 4 × 4 window from `(x0, y0)` lies in the overlay.
    fn touches(&self, x0: usize, y0: usize) -> bool {
        (y0 / TILE..=(y0 + 3) / TILE).any(|ty| {
            (x0 / TILE..=(x0 + 3) / TILE).any(|tx| self.slot[ty * self.tiles_x + tx] != u32::MAX)
        })
    }
}

impl ShadowMap {
    /// The map of `scene` for the sun in direction `dir` (unit, towards the sun), at most
    /// `side` texels a side (1 to [`MAX_SIDE`]), leaving out the objects `without`
    /// (instance ids, ascending; their bounds still count towards the extent). `None` for
    /// an empty scene or a sun at or below the horizon.
    pub(crate) fn build(
        scene: &PreparedScene,
        dir: [f64; 3],
        side: u32,
        without: &[u32],
    ) -> Option<ShadowMap> {
        if dir[1].is_nan() || dir[1] <= 1e-3 || scene.triangles.is_empty() {
            return None;
        }
        // Light space: `right` horizontal, `up` = right × (−dir) … any fixed basis works.
        let r = [dir[2], 0.0, -dir[0]];
        let rl = (r[0] * r[0] + r[2] * r[2]).sqrt();
        let right = if rl > 1e-9 {
            [r[0] / rl, 0.0, r[2] / rl]
        } else {
            [1.0, 0.0, 0.0]
        };
        let up = cross(dir, right);
        let (lo, hi) = light_space_bounds(scene, right, up)?;
        let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let texel = (extent / f64::from(side.clamp(1, MAX_SIDE))).max(MIN_TEXEL);
        // One texel of margin on every side, for the filter.
        let origin = [lo[0] - texel, lo[1] - texel];
        let width = ((hi[0] - lo[0]) / texel).ceil() as usize + 2;
        let height = ((hi[1] - lo[1]) / texel).ceil() as usize + 2;

        let mut map = ShadowMap {
            dir,
            right,
            up,
            origin,
            texel,
            per_texel: 1.0 / texel,
            width,
            height,
            depth: std::sync::Arc::new(Vec::new()),
            overlay: None,
        };
        let all: Vec<usize> = (0..scene.triangles.len()).collect();
        let tris = map.texel_triangles(scene, &all);
        let take = |i: u32| without.binary_search(&i).is_err();
        let bins = band_bins(scene, &tris, &all, height.div_ceil(BAND), take);
        // Zeroed memory comes from the system untouched; each band fills its own rows, in
        // parallel, straight into the map (no per-band buffers to copy).
        let mut depth = vec![0.0f32; width * height];
        depth
            .par_chunks_mut(BAND * width)
            .zip(&bins)
            .enumerate()
            .for_each(|(b, (band, bin))| {
                band.fill(f32::NEG_INFINITY);
                let rows = [b * BAND, ((b + 1) * BAND).min(height)];
                for &i in bin {
                    raster(&tris[i as usize], rows, [0, width], width, band);
                }
            });
        map.depth = std::sync::Arc::new(depth);
        Some(map)
    }

    /// Adds the triangles of objects `ids` (instance ids, ascending) of `scene` to the
    /// map, as [`ShadowMap::build`] would have (a texel keeps the nearest surface to the
    /// sun whatever the order): `scene` is the one the map was built from, posed.
    ///
    /// The map's own texels are shared, not copied: the objects go into an overlay of the
    /// tiles they touch, each tile a copy of the map's texels there.
    pub(crate) fn add(&mut self, scene: &PreparedScene, ids: &[u32]) {
        let chosen: Vec<usize> = ids
            .iter()
            .filter_map(|&id| scene.objects.get((id as usize).wrapping_sub(1)))
            .flat_map(|o| o.first..o.end)
            .collect();
        let tris = self.texel_triangles(scene, &chosen);
        let bins = band_bins(scene, &tris, &chosen, 1, |_| true);
        let tris: Vec<&[[f64; 3]; 3]> = bins[0].iter().map(|&i| &tris[i as usize]).collect();
        let (tiles_x, tiles_y) = (self.width.div_ceil(TILE), self.height.div_ceil(TILE));
        // The tiles each triangle's box reaches, in texels.
        let reach = |t: &[[f64; 3]; 3], k: usize, end: usize| {
            let lo = t.iter().map(|v| v[k]).fold(f64::INFINITY, f64::min);
            let hi = t.iter().map(|v| v[k]).fold(f64::NEG_INFINITY, f64::max);
            let a = (lo.floor().max(0.0) as usize).min(end);
            let b = (hi.ceil().max(0.0) as usize).min(end);
            (a / TILE, b.saturating_sub(1).max(a) / TILE)
        };
        let mut slot = vec![u32::MAX; tiles_x * tiles_y];
        let mut bins: Vec<Vec<u32>> = Vec::new();
        for (k, t) in tris.iter().enumerate() {
            let ((x0, x1), (y0, y1)) = (reach(t, 0, self.width), reach(t, 1, self.height));
            for ty in y0..=y1.min(tiles_y - 1) {
                for tx in x0..=x1.min(tiles_x - 1) {
                    let s = &mut slot[ty * tiles_x + tx];
                    if *s == u32::MAX {
                        *s = bins.len() as u32;
                        bins.push(Vec::new());
                    }
                    bins[*s as usize].push(k as u32);
                }
            }
        }
        let tris: Vec<[[f64; 3]; 3]> = tris.into_iter().copied().collect();
        self.overlay = Some(Overlay {
            slot,
            tiles_x,
            tiles: (0..bins.len())
                .map(|_| std::sync::OnceLock::new())
                .collect(),
            bins,
            tris: std::sync::Arc::new(tris),
        });
    }

    /// The triangles `chosen` (indices into the scene's) in texel coordinates and depth
    /// towards the sun.
    fn texel_triangles(&self, scene: &PreparedScene, chosen: &[usize]) -> Vec<[[f64; 3]; 3]> {
        let (right, up, dir, origin, texel) =
            (self.right, self.up, self.dir, self.origin, self.texel);
        chosen
            .par_iter()
            .map(|&i| {
                scene.triangles[i].p.map(|p| {
                    let p = p.map(f64::from);
                    [
                        (dot(p, right) - origin[0]) / texel,
                        (dot(p, up) - origin[1]) / texel,
                        dot(p, dir),
                    ]
                })
            })
            .collect()
    }

    /// What the test needs of a surface with unit normal `n`, the same at each of its
    /// points: `None` when it faces away from the sun (no light reaches it).
    pub(crate) fn receiver(&self, n: [f64; 3]) -> Option<Receiver> {
        let cos = dot(n, self.dir);
        if cos <= 0.0 {
            return None;
        }
        let tan = ((1.0 - cos * cos).max(0.0).sqrt() / cos).min(5.0);
        Some(Receiver {
            n,
            bias: self.texel * (0.5 + 2.0 * tan),
        })
    }

    /// Share of the sun reaching point `p` of the surface `r` describes, 0–1.
    pub(crate) fn light_at(&self, p: [f64; 3], r: &Receiver) -> f32 {
        let n = r.n;
        let q = [
            p[0] + n[0] * self.texel,
            p[1] + n[1] * self.texel,
            p[2] + n[2] * self.texel,
        ];
        let z = dot(q, self.dir) + r.bias;
        let fx = (dot(q, self.right) - self.origin[0]) * self.per_texel - 0.5;
        let fy = (dot(q, self.up) - self.origin[1]) * self.per_texel - 0.5;
        if !(fx.is_finite() && fy.is_finite()) {
            return 1.0;
        }
        let (ix, iy) = (floor(fx), floor(fy));
        let (tx, ty) = (fx - ix, fy - iy);
        // A 3-texel box centred on the point: texels ix−1 … ix+2, the outer two partly.
        let wx = [(1.0 - tx) / 3.0, 1.0 / 3.0, 1.0 / 3.0, tx / 3.0];
        let wy = [(1.0 - ty) / 3.0, 1.0 / 3.0, 1.0 / 3.0, ty / 3.0];
        // `f64::from(depth) <= z` for an f32 depth is `depth <= zf`, zf the largest f32 not
        // above z: the same test without widening 16 texels.
        let zf = at_most(z);
        let (x0, y0) = (ix as i64 - 1, iy as i64 - 1);
        let mut lit = 0.0;
        let inside =
            x0 >= 0 && y0 >= 0 && x0 + 4 <= self.width as i64 && y0 + 4 <= self.height as i64;
        let overlaid = |o: &Overlay| o.touches(x0 as usize, y0 as usize);
        if inside && !self.overlay.as_ref().is_some_and(overlaid) {
            // Inside the map, as nearly every lookup is: four rows of four texels.
            let (x0, y0) = (x0 as usize, y0 as usize);
            for (j, wy) in wy.iter().enumerate() {
                let row = &self.depth[(y0 + j) * self.width + x0..][..4];
                for (depth, wx) in row.iter().zip(&wx) {
                    if *depth <= zf {
                        lit += wy * wx;
                    }
                }
            }
            return lit as f32;
        }
        for (j, wy) in wy.iter().enumerate() {
            let y = y0 + j as i64;
            if y < 0 || y >= self.height as i64 {
                lit += wy;
                continue;
            }
            for (i, wx) in wx.iter().enumerate() {
                let x = x0 + i as i64;
                if x < 0 || x >= self.width as i64 || self.texel(x as usize, y as usize) <= zf {
                    lit += wy * wx;
                }
            }
        }
        lit as f32
    }
}

impl ShadowMap {
    /// The depth at texel `(x, y)` (inside the map): the overlay's where it has the tile.
    fn texel(&self, x: usize, y: usize) -> f32 {
        self.overlay
            .as_ref()
            .and_then(|o| o.texel(self, x, y))
            .unwrap_or_else(|| self.depth[y * self.width + x])
    }
}

/// A surface facing the sun, as the shadow test sees it ([`ShadowMap::receiver`]).
#[derive(Clone, Copy)]
pub(crate) struct Receiver {
    /// Unit normal.
    n: [f64; 3],
    /// Depth bias: `texel · (0.5 + 2 · tan θ)`.
    bias: f64,
}

/// The largest `f32` not above `z` (NaN stays NaN, so every test against it fails, as
/// against `z`).
fn at_most(z: f64) -> f32 {
    let f = z as f32;
    if f64::from(f) > z { f.next_down() } else { f }
}

/// Writes the max depth of triangle `t` (texel coordinates and depth) at the texel centres
/// it covers within `rows` and `cols` into `band`, whose rows (from `rows[0]`) are
/// `stride` texels apart and start at column `cols[0]`.
fn raster(t: &[[f64; 3]; 3], rows: [usize; 2], cols: [usize; 2], stride: usize, band: &mut [f32]) {
    let [a, b, c] = *t;
    let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if area.is_nan() || area.abs() <= 1e-12 {
        return;
    }
    let x0 = (a[0].min(b[0]).min(c[0]).floor().max(0.0) as usize).max(cols[0]);
    let x1 = (a[0].max(b[0]).max(c[0]).ceil().max(0.0) as usize).min(cols[1]);
    let y0 = (a[1].min(b[1]).min(c[1]).floor().max(0.0) as usize).max(rows[0]);
    let y1 = (a[1].max(b[1]).max(c[1]).ceil().max(0.0) as usize).min(rows[1]);
    let inv = 1.0 / area;
    for y in y0..y1 {
        let py = y as f64 + 0.5;
        // Only the texels near the triangle's span on this row are tested (a slanted or
        // thin triangle covers a small part of its box); the test itself is unchanged,
        // and the span is padded far beyond its rounding (see `row_span`).
        let Some((xa, xb)) = row_span(t, py) else {
            continue;
        };
        let (xa, xb) = (xa.max(x0), xb.min(x1));
        if xa >= xb {
            continue;
        }
        let row = &mut band[(y - rows[0]) * stride..][..cols[1] - cols[0]];
        // The row's terms once; every texel then runs the same arithmetic, its depth kept
        // or not by a select instead of a branch (mispredicted at every span's ends).
        let (ay, by, cy) = (a[1] - py, b[1] - py, c[1] - py);
        for (slot, x) in row[xa - cols[0]..xb - cols[0]].iter_mut().zip(xa..) {
            let px = x as f64 + 0.5;
            // Barycentric weights; a texel centre on an edge counts for both sides.
            let w0 = ((b[0] - px) * cy - by * (c[0] - px)) * inv;
            let w1 = ((c[0] - px) * ay - cy * (a[0] - px)) * inv;
            let w2 = 1.0 - w0 - w1;
            let z = (w0 * a[2] + w1 * b[2] + w2 * c[2]) as f32;
            let nearer = (w0 >= 0.0) & (w1 >= 0.0) & (w2 >= 0.0) & (z > *slot);
            *slot = if nearer { z } else { *slot };
        }
    }
}

/// Texels `[xa, xb)` of the row whose centres lie at `py` that can pass [`raster`]'s
/// inside test: the x extent of the triangle within one texel of the row (clipped to the
/// slab `py ± 1`), padded by a texel. The test's rounding errs by far less than a
/// texel, so a centre it accepts always lies in the slab and inside the padding.
fn row_span(t: &[[f64; 3]; 3], py: f64) -> Option<(usize, usize)> {
    let (lo, hi) = (py - 1.0, py + 1.0);
    let (mut x_min, mut x_max) = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..3 {
        let (p, q) = (t[k], t[(k + 1) % 3]);
        let (y_min, y_max) = (p[1].min(q[1]), p[1].max(q[1]));
        if y_max < lo || y_min > hi {
            continue;
        }
        // The part of edge p→q inside the slab: its ends' x.
        let dy = q[1] - p[1];
        let (t0, t1) = if dy == 0.0 {
            (0.0, 1.0)
        } else {
            let (a, b) = ((lo - p[1]) / dy, (hi - p[1]) / dy);
            (a.min(b).max(0.0), a.max(b).min(1.0))
        };
        for s in [t0, t1] {
            let x = p[0] + (q[0] - p[0]) * s;
            x_min = x_min.min(x);
            x_max = x_max.max(x);
        }
    }
    if x_min > x_max {
        return None;
    }
    let xa = (x_min - 1.0).floor().max(0.0) as usize;
    let xb = (x_max + 1.0).ceil().max(0.0) as usize;
    Some((xa, xb))
}

/// The light-space box (`right`, `up`) of every object's bounds' corners; `None` when no
/// object has bounds.
fn light_space_bounds(
    scene: &PreparedScene,
    right: [f64; 3],
    up: [f64; 3],
) -> Option<([f64; 2], [f64; 2])> {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for o in scene.objects.iter().filter(|o| o.casts_shadow) {
        if o.min[0].is_nan() || o.min[0] > o.max[0] {
            continue;
        }
        for i in 0..8 {
            let p = [
                if i & 1 == 0 { o.min[0] } else { o.max[0] },
                if i & 2 == 0 { o.min[1] } else { o.max[1] },
                if i & 4 == 0 { o.min[2] } else { o.max[2] },
            ];
            let q = [dot(p, right), dot(p, up)];
            for k in 0..2 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
    }
    (lo[0] <= hi[0] && lo[1] <= hi[1]).then_some((lo, hi))
}

/// Per band of [`BAND`] rows, the triangles (`tris`, in texel coordinates, of the scene's
/// triangles `chosen`) of the objects `take` takes (by instance id) that reach it.
///
/// Flat ground at the scene's lowest level shades nothing (nothing lies below it to
/// receive its shadow) and is the largest area to fill: left out, its texels read as lit,
/// as anything at or above it found them anyway.
fn band_bins(
    scene: &PreparedScene,
    tris: &[[[f64; 3]; 3]],
    chosen: &[usize],
    bands: usize,
    take: impl Fn(u32) -> bool,
) -> Vec<Vec<u32>> {
    let floor = scene
        .objects
        .iter()
        .map(|o| o.min[1])
        .fold(f64::INFINITY, f64::min);
    let is_floor = |t: &super::prepared_scene::Triangle| {
        t.normal[1] > 0.999 && t.p.iter().all(|p| f64::from(p[1]) <= floor + 1e-4)
    };
    let mut bins = vec![Vec::new(); bands];
    for (i, t) in tris.iter().enumerate() {
        let triangle = &scene.triangles[chosen[i]];
        let object = &scene.objects[triangle.instance as usize - 1];
        if !object.casts_shadow || !take(triangle.instance) || is_floor(triangle) {
            continue;
        }
        let y0 = t.iter().map(|v| v[1]).fold(f64::INFINITY, f64::min);
        let y1 = t.iter().map(|v| v[1]).fold(f64::NEG_INFINITY, f64::max);
        let (b0, b1) = (
            (y0.max(0.0) as usize / BAND).min(bands - 1),
            (y1.max(0.0) as usize / BAND).min(bands - 1),
        );
        for bin in &mut bins[b0..=b1] {
            bin.push(i as u32);
        }
    }
    bins
}

#[cfg(test)]
mod tests {
    use rand::RngExt;

    use super::*;

    /// The shadow test on f32 depths against [`at_most`] decides as the widened test
    /// against the f64 depth did, for depths near, at and far from f32 values.
    #[test]
    fn f32_test_against_at_most_is_the_f64_test() {
        let mut rng = crate::rng::stream(3, "at-most", 0);
        let mut depths: Vec<f32> = vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            f32::MAX,
            f32::MIN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::MIN_POSITIVE,
        ];
        depths.extend((0..2000).map(|_| (rng.random::<f64>() * 400.0 - 200.0) as f32));
        for &d in &depths.clone() {
            depths.push(d.next_up());
            depths.push(d.next_down());
        }
        let mut zs: Vec<f64> = depths.iter().map(|&d| f64::from(d)).collect();
        for &d in &depths {
            let d = f64::from(d);
            zs.extend([
                d + 1e-12,
                d - 1e-12,
                d * (1.0 + 1e-9),
                f64::MAX,
                -f64::MAX,
                f64::NAN,
            ]);
        }
        zs.extend([f64::INFINITY, f64::NEG_INFINITY, 1e300, -1e300]);
        for &z in &zs {
            let zf = at_most(z);
            for &d in depths.iter().step_by(7) {
                assert_eq!(d <= zf, f64::from(d) <= z, "depth {d:e}, z {z:e}");
            }
        }
    }

    /// [`raster`] as it was before rows were cut to their spans: every texel of the box.
    fn raster_whole_box(t: &[[f64; 3]; 3], rows: [usize; 2], width: usize, band: &mut [f32]) {
        let [a, b, c] = *t;
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if area.is_nan() || area.abs() <= 1e-12 {
            return;
        }
        let x0 = a[0].min(b[0]).min(c[0]).floor().max(0.0) as usize;
        let x1 = (a[0].max(b[0]).max(c[0]).ceil().max(0.0) as usize).min(width);
        let y0 = (a[1].min(b[1]).min(c[1]).floor().max(0.0) as usize).max(rows[0]);
        let y1 = (a[1].max(b[1]).max(c[1]).ceil().max(0.0) as usize).min(rows[1]);
        let inv = 1.0 / area;
        for y in y0..y1 {
            let py = y as f64 + 0.5;
            let row = &mut band[(y - rows[0]) * width..][..width];
            for (x, slot) in row.iter_mut().enumerate().take(x1).skip(x0) {
                let px = x as f64 + 0.5;
                let w0 = ((b[0] - px) * (c[1] - py) - (b[1] - py) * (c[0] - px)) * inv;
                let w1 = ((c[0] - px) * (a[1] - py) - (c[1] - py) * (a[0] - px)) * inv;
                let w2 = 1.0 - w0 - w1;
                if w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0 {
                    let z = (w0 * a[2] + w1 * b[2] + w2 * c[2]) as f32;
                    if z > *slot {
                        *slot = z;
                    }
                }
            }
        }
    }

    #[test]
    fn row_spans_fill_exactly_the_texels_the_whole_box_test_fills() {
        let mut rng = crate::rng::stream(5, "shadow-map-spans", 0);
        let (width, rows) = (64usize, [8usize, 56usize]);
        for case in 0..4000 {
            let mut v = || -> [f64; 3] {
                [
                    rng.random::<f64>() * 80.0 - 8.0,
                    rng.random::<f64>() * 80.0 - 8.0,
                    rng.random::<f64>(),
                ]
            };
            let mut t = [v(), v(), v()];
            match case % 5 {
                // Slivers: a vertex nearly on the opposite edge.
                1 => {
                    let (a, b) = (t[0], t[1]);
                    t[2] = std::array::from_fn(|k| a[k] + (b[k] - a[k]) * 0.3);
                    t[2][1] += 1e-7;
                }
                // Nearly horizontal and vertical edges, vertices on texel centres.
                2 => t[1][1] = t[0][1] + 1e-9,
                3 => t[1][0] = t[0][0] - 1e-9,
                4 => t = t.map(|p| [p[0].floor() + 0.5, p[1].floor() + 0.5, p[2]]),
                _ => {}
            }
            let mut spans = vec![f32::NEG_INFINITY; (rows[1] - rows[0]) * width];
            let mut whole = spans.clone();
            raster(&t, rows, [0, width], width, &mut spans);
            raster_whole_box(&t, rows, width, &mut whole);
            assert!(
                spans
                    .iter()
                    .zip(&whole)
                    .all(|(a, b)| a.to_bits() == b.to_bits()),
                "triangle {t:?}"
            );
        }
    }

    #[test]
    fn moving_objects_added_over_the_still_map_give_the_whole_map_texel_for_texel() {
        use crate::render::tests::{cuboid, ground_quad, material, object};
        let plane = ground_quad(30.0);
        let mut objects = vec![
            object("plane", vec![plane]),
            object("tower", cuboid(0, [-6.0, 0.0, -6.0], [-3.0, 12.0, -3.0])),
        ];
        // Cars (3 to 12) side by side, some close enough to share tiles.
        for k in 0..10 {
            let x = -20.0 + 4.3 * k as f32;
            let z = if k % 2 == 0 { 2.0 } else { 9.5 };
            objects.push(object(
                "car",
                cuboid(0, [x, 0.0, z], [x + 3.9, 1.6, z + 1.8]),
            ));
        }
        let scene = crate::model::Scene {
            textures: Vec::new(),
            materials: vec![material([0.5; 3], None, [0.0; 3])],
            objects,
        };
        let prepared = crate::render::prepare(&scene).unwrap();
        let cars: Vec<u32> = (3..=12).collect();
        let dir = crate::model::geometry::normalize([0.4, 0.7, 0.3]).unwrap();
        let whole = ShadowMap::build(&prepared, dir, 700, &[]).unwrap();
        let mut parts = ShadowMap::build(&prepared, dir, 700, &cars).unwrap();
        assert!(parts.overlay.is_none());
        parts.add(&prepared, &cars);
        let overlay = parts.overlay.as_ref().unwrap();
        let tiles = overlay.slot.iter().filter(|s| **s != u32::MAX).count();
        assert!(tiles > 10 && tiles * 10 < overlay.slot.len(), "{tiles}");
        let mut differ = 0;
        for y in 0..whole.height {
            for x in 0..whole.width {
                assert_eq!(whole.texel(x, y), parts.texel(x, y), "({x}, {y})");
                differ += usize::from(
                    whole.depth[y * whole.width + x] != parts.depth[y * parts.width + x],
                );
            }
        }
        // The still map lacks the cars; the overlay puts them back.
        assert!(differ > 100, "{differ}");
        // And the soft test reads the same everywhere on the ground.
        let up = whole.receiver([0.0, 1.0, 0.0]).unwrap();
        for i in 0..60 {
            for j in 0..60 {
                let p = [-30.0 + f64::from(i), 0.0, -30.0 + f64::from(j)];
                assert_eq!(whole.light_at(p, &up), parts.light_at(p, &up), "{p:?}");
            }
        }
    }
}
