//! The big objects' depths (buildings, roads, sidewalks) → which other objects they hide
//! wholly: object-level occlusion culling, exact.
//!
//! A street frame's frustum reaches across many blocks, but the first row of buildings
//! hides most of what lies behind: of the twelve thousand triangles a `specs/day.toml`
//! street frame set up, the objects it showed owned about a fifth. Every hidden triangle
//! was set up, binned and rasterized, only to lose each depth test.
//!
//! So the occluders (objects whose triangles are large, [`is_occluder`]) are set up and
//! rasterized first, tile by tile. Over a grid of [`BLOCK`]-pixel blocks, each block
//! keeps the least 1/w they leave at its pixels (1/far where a pixel shows none of them):
//! whatever the frame shows there ends at least that near. Then each other object is
//! judged before its triangles are set up ([`OcclusionBlocks::hides_object`]): when its
//! box lies wholly in front of the near plane and behind the bound of every block its
//! projection touches, by more than the most vertex snapping can move a pixel's 1/w, none
//! of its triangles can win a depth test, and it is dropped. An object that passes is set
//! up, and dropped still if each of its screen triangles lies behind the blocks of its
//! pixel bounds, from its own 1/w plane with the rasterizer's arithmetic
//! ([`OcclusionBlocks::hides`]). The rest are rasterized over the occluders.
//!
//! Ids, depth, colours and footprints are the same bytes as without culling (a test
//! renders both): a dropped object shows in no pixel, and footprints are measured only for
//! objects that show. Objects are dropped whole, never single triangles, so every object
//! that shows keeps its full run of screen triangles for its footprint. Which objects
//! occlude changes only the speed.

use super::prepared_scene::Triangle;
use super::screen_triangle::{SUB, ScreenTri};
use super::tile::TileRaster;
use super::view::View;
use crate::model::geometry::{cross, dot, sub};

/// Side of the occlusion blocks, internal pixels.
pub(crate) const BLOCK: u32 = 8;

/// An object occludes when its triangles average at least this many square metres: walls,
/// roofs, roads and sidewalks, not people, cars, lamps or signs, whose many small
/// triangles rarely cover a whole block. Only the speed depends on it.
const OCCLUDER_AREA: f64 = 2.0;

/// Relative margin between a triangle's 1/w and the block's bound before it counts as
/// hidden: far above the rounding of an affine plane evaluated at pixels.
const MARGIN: f64 = 1e-6;

/// Twice the most 1/w can exceed its vertices' at a covered pixel, times the focal
/// length and the distance from the eye to the triangle's plane: 1/w is affine on the
/// screen with a slope of at most `1 / (focal · distance)` per pixel, and a covered pixel
/// centre lies within `√2/512` px (vertex snapping) of the unsnapped triangle.
const SNAP_SLOPE: f64 = 2.0 * std::f64::consts::SQRT_2 / (2 * SUB) as f64;

/// Relative margin of [`OcclusionBlocks::hides_object`]'s bound, for the rounding of
/// triangle setup it reasons about without running it.
const BOX_MARGIN: f64 = 1e-4;

/// Whether an object of `triangles` is set up first, as an occluder.
pub(crate) fn is_occluder(triangles: &[Triangle]) -> bool {
    if triangles.is_empty() {
        return false;
    }
    let area: f64 = triangles
        .iter()
        .map(|t| {
            let p = t.p.map(|v| v.map(f64::from));
            let c = cross(sub(p[1], p[0]), sub(p[2], p[0]));
            0.5 * dot(c, c).sqrt()
        })
        .sum();
    area >= OCCLUDER_AREA * triangles.len() as f64
}

/// The occluders' bound per block of a frame.
pub(crate) struct OcclusionBlocks {
    cols: usize,
    /// Per block, row-major: the least 1/w the occluders leave at its pixels (1/far where
    /// a pixel shows none of them). Whatever the frame shows there is at least this near.
    near: Vec<f64>,
}

impl OcclusionBlocks {
    /// The bounds of a `width` × `height` internal image from its tiles' blocks.
    pub(crate) fn of_tiles(width: u32, height: u32, tiles: &[TileBlocks]) -> OcclusionBlocks {
        let cols = width.div_ceil(BLOCK) as usize;
        let rows = height.div_ceil(BLOCK) as usize;
        let mut near = vec![0f64; cols * rows];
        for tile in tiles {
            let (bx0, by0) = (
                (tile.inner[0] / BLOCK) as usize,
                (tile.inner[1] / BLOCK) as usize,
            );
            for (k, row) in tile.near.chunks(tile.cols.max(1)).enumerate() {
                near[(by0 + k) * cols + bx0..][..row.len()].copy_from_slice(row);
            }
        }
        OcclusionBlocks { cols, near }
    }

    /// Whether every triangle of an object (world box `min`–`max`, `triangles`) loses the
    /// depth test at every pixel it could cover, judged before setting any of them up:
    /// false when unsure. See the module's docs for the bound.
    pub(crate) fn hides_object(
        &self,
        view: &View,
        (min, max): ([f64; 3], [f64; 3]),
        triangles: &[Triangle],
    ) -> bool {
        let corners = view.box_corners(min, max);
        let nearest = corners.iter().map(|c| c[2]).fold(f64::INFINITY, f64::min);
        // Wholly in front of the near plane: nothing is clipped there, and every point
        // of the box, so every vertex, has 1/w at most the box's.
        if !(nearest > view.near && nearest.is_finite()) {
            return false;
        }
        let q_box = 1.0 / nearest;
        let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
        for c in &corners {
            let [x, y] = view.project(*c);
            (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
        }
        if !(x0.is_finite() && y0.is_finite() && x1.is_finite() && y1.is_finite()) {
            return false;
        }
        // Pixels whose centre lies within a pixel of the projected box (snapping moves a
        // vertex by 1/512 px at most), inside the image.
        let pixels = |lo: f64, hi: f64, size: u32| {
            let first = (lo - 1.0).floor().max(0.0);
            let last = (hi + 1.0).ceil().min(f64::from(size));
            (first as u32, last as u32)
        };
        let (px0, px1) = pixels(x0, x1, view.width);
        let (py0, py1) = pixels(y0, y1, view.height);
        if px0 >= px1 || py0 >= py1 {
            return true;
        }
        let mut bound = f64::INFINITY;
        for by in py0 / BLOCK..=(py1 - 1) / BLOCK {
            let row = &self.near[by as usize * self.cols..][..self.cols];
            for &b in &row[(px0 / BLOCK) as usize..=((px1 - 1) / BLOCK) as usize] {
                bound = bound.min(b);
            }
            if bound <= q_box {
                return false;
            }
        }
        let focal = view.fx.min(view.fy);
        triangles.iter().all(|t| {
            // As `screen_triangle::setup` measures it.
            let facing = dot(
                t.normal.map(f64::from),
                sub(view.eye, t.p[0].map(f64::from)),
            );
            if facing.is_nan() {
                return false;
            }
            // A back face is culled at setup.
            facing <= 0.0 || (q_box + SNAP_SLOPE / (focal * facing)) * (1.0 + BOX_MARGIN) < bound
        })
    }

    /// Whether `tri` loses the depth test at every pixel it could cover: its greatest 1/w
    /// over its pixel bounds lies behind every touched block's bound.
    pub(crate) fn hides(&self, tri: &ScreenTri) -> bool {
        let [x0, y0, x1, y1] = tri.bounds;
        let most = [(x0, y0), (x1 - 1, y0), (x0, y1 - 1), (x1 - 1, y1 - 1)]
            .map(|(x, y)| tri.pixel_q(x, y))
            .into_iter()
            .fold(f64::NEG_INFINITY, f64::max);
        if !most.is_finite() {
            return false;
        }
        let bound = most * (1.0 + MARGIN);
        (y0 / BLOCK..=(y1 - 1) / BLOCK).all(|by| {
            let row = &self.near[by as usize * self.cols..][..self.cols];
            (x0 / BLOCK..=(x1 - 1) / BLOCK).all(|bx| row[bx as usize] > bound)
        })
    }
}

/// One tile's share of [`OcclusionBlocks`]: the least 1/w of each of its blocks.
pub(crate) struct TileBlocks {
    /// The tile's internal pixels `[x0, y0, x1, y1)`; `x0` and `y0` are multiples of
    /// [`BLOCK`].
    inner: [u32; 4],
    /// Blocks per row.
    cols: usize,
    /// Row-major.
    near: Vec<f64>,
}

impl TileBlocks {
    /// The blocks of a tile rasterized with the occluders alone: each block's least 1/w,
    /// the far bound 1/far where a pixel shows none of them.
    pub(crate) fn of(raster: &TileRaster) -> TileBlocks {
        let inner = raster.inner;
        debug_assert!(inner[0].is_multiple_of(BLOCK) && inner[1].is_multiple_of(BLOCK));
        let iw = raster.inner_width();
        let cols = iw.div_ceil(BLOCK as usize);
        let rows = ((inner[3] - inner[1]) as usize).div_ceil(BLOCK as usize);
        let mut near = vec![f64::INFINITY; cols * rows];
        if iw > 0 {
            for (y, row) in raster.depth.chunks(iw).enumerate() {
                let blocks = &mut near[y / BLOCK as usize * cols..][..cols];
                for (b, run) in blocks.iter_mut().zip(row.chunks(BLOCK as usize)) {
                    *b = run.iter().copied().fold(*b, f64::min);
                }
            }
        }
        TileBlocks { inner, cols, near }
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{cuboid, material, object, pose};
    use super::super::*;
    use super::{BLOCK, OcclusionBlocks};
    use crate::model::Scene;

    /// Ground, a row of houses across the view, and 0.5 × 1.7 m "people" in front of
    /// them, behind them (hidden), peeking past their corners, just behind a wall, and far
    /// off through the gaps.
    fn town() -> Scene {
        let mut objects = vec![object(
            "ground",
            cuboid(0, [-300.0, -1.0, -300.0], [300.0, 0.0, 300.0]),
        )];
        for i in 0..6 {
            let x = -33.0 + 12.0 * i as f32;
            objects.push(object(
                &format!("house_{i}"),
                cuboid(1, [x, 0.0, -30.0], [x + 10.0, 8.0 + i as f32, -20.0]),
            ));
        }
        let mut k = 0;
        for z in [-5.0f32, -19.9, -20.0 - 1e-3, -31.0, -45.0, -120.0] {
            for x in (-40..40).step_by(3) {
                let x = x as f32 + 0.37 * (k % 5) as f32;
                objects.push(object(
                    &format!("person_{k}"),
                    cuboid(2, [x, 0.0, z], [x + 0.5, 1.7, z + 0.5]),
                ));
                k += 1;
            }
        }
        Scene {
            textures: Vec::new(),
            materials: vec![
                material([0.4; 3], None, [0.0; 3]),
                material([0.8, 0.7, 0.6], None, [0.0; 3]),
                material([0.2, 0.3, 0.9], None, [0.0; 3]),
            ],
            objects,
        }
    }

    #[test]
    fn houses_and_ground_occlude_and_people_do_not() {
        let scene = prepare(&town()).unwrap();
        let occluders: Vec<bool> = scene.objects.iter().map(|o| o.occluder).collect();
        assert!(occluders[..7].iter().all(|&o| o), "{occluders:?}");
        assert!(occluders[7..].iter().all(|&o| !o));
    }

    #[test]
    fn culling_hidden_objects_changes_no_byte_of_frames_or_footprints() {
        let culled = prepare(&town()).unwrap();
        let mut uncut = prepare(&town()).unwrap();
        for object in &mut uncut.objects {
            object.occluder = false;
        }
        let measure: Vec<u32> = (1..=culled.object_count() as u32).collect();
        let k = Intrinsics::from_fov(160, 96, 1.0);
        let mut ao = Lighting::day();
        ao.ambient_occlusion = 0.8;
        let mut plain = Lighting::day();
        plain.ambient_occlusion = 0.0;
        let poses = [
            pose([0.0, 1.6, 10.0], [0.0, 1.5, -40.0]),
            pose([5.0, 2.0, 2.0], [-20.0, 3.0, -60.0]),
            pose([-2.0, 12.0, 15.0], [0.0, 0.0, -40.0]),
            // Past a house's corner, down the gap between two of them.
            pose([-22.5, 1.7, -10.0], [-22.6, 1.6, -100.0]),
        ];
        let mut dropped = 0;
        for eye in &poses {
            // Kept tiles (ambient occlusion, edge antialiasing) and dropped ones
            // (supersampled, no ambient occlusion).
            for (lighting, samples) in [(&ao, 1), (&plain, 2)] {
                let a = render_measuring(&culled, eye, &k, lighting, samples, &measure);
                let b = render_measuring(&uncut, eye, &k, lighting, samples, &measure);
                assert_eq!(a.0, b.0);
                assert_eq!(a.1, b.1);
            }
            let (a, b) = (
                visibility(&culled, eye, &k, &measure),
                visibility(&uncut, eye, &k, &measure),
            );
            assert!(a.0.instance == b.0.instance && a.0.depth == b.0.depth && a.1 == b.1);
            let view = View::new(eye, &k, 1).unwrap();
            let count = |s: &PreparedScene| {
                let r = rasterize(s, &view, (k.width, k.height), 1, true);
                r.ranges.iter().filter(|r| !r.is_empty()).count()
            };
            dropped += count(&uncut) - count(&culled);
        }
        // The test means something: the houses hid whole rows of people.
        assert!(dropped > 40, "{dropped} objects culled");
    }

    #[test]
    fn an_object_reaching_the_near_plane_or_off_the_image_is_judged_safely() {
        let scene = prepare(&town()).unwrap();
        let k = Intrinsics::from_fov(160, 96, 1.0);
        let view = View::new(&pose([0.0, 1.6, 10.0], [0.0, 1.5, -40.0]), &k, 1).unwrap();
        let full = OcclusionBlocks {
            cols: view.width.div_ceil(BLOCK) as usize,
            near: vec![10.0; (view.width.div_ceil(BLOCK) * view.height.div_ceil(BLOCK)) as usize],
        };
        // person_13, 15 m ahead, in the middle of the image.
        let person = &scene.objects[7 + 13];
        let tris = &scene.triangles[person.first..person.end];
        // Everything is hidden behind a wall 0.1 m away ...
        assert!(full.hides_object(&view, (person.min, person.max), tris));
        // ... but not a box around the eye, which crosses the near plane.
        assert!(!full.hides_object(&view, ([-1.0, 0.0, 9.0], [1.0, 2.0, 11.0]), tris));
        // Nothing is hidden where no occluder bounds the blocks (1/w 0).
        let open = OcclusionBlocks {
            near: vec![0.0; full.near.len()],
            ..full
        };
        assert!(!open.hides_object(&view, (person.min, person.max), tris));
        // Except what projects beside the image: person_0, 40 m to the left.
        let aside = &scene.objects[7];
        assert!(open.hides_object(&view, (aside.min, aside.max), tris));
    }
}
