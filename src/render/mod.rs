//! Render stage: prepared scene + camera pose + intrinsics + lighting → [`Frame`] (RGB,
//! instance ids, depth, optionally surface normals), on the CPU, deterministically.
//!
//! # Conventions
//!
//! - **World → camera**: right-handed look-at. `forward = normalize(target − eye)`,
//!   `right = normalize(forward × up)` with the pose's `up` (+y when level, turned about
//!   the view direction by a roll; a camera looking along it takes north, −z, as its up),
//!   `true up = right × forward`. For `d = p − eye`:
//!   `x_pixel = cx + fx · (right·d)/(forward·d)`, `y_pixel = cy − fy · (up·d)/(forward·d)`
//!   (y down in the image). Pixel `(i, j)` covers `[i, i+1) × [j, j+1)`; it is sampled at
//!   its centre `(i + 0.5, j + 0.5)`.
//! - **Depth** is `forward·d` in metres (not the distance to the eye), kept as `f32`; 0
//!   means sky. [`DepthFormat`] says how it is written (millimetres or centimetres in a
//!   16-bit PNG, or 32-bit float metres in a `.npy`).
//! - **Normals** (only when asked, [`render_with`]): per pixel, the unit face normal of the
//!   triangle whose sample gives the pixel its id and depth, in OpenCV camera axes
//!   (`x = right·n`, `y = −up·n`, `z = forward·n`: x right, y down, z forward), turned
//!   to face the camera (its dot product with the ray through that sample is ≤ 0); `[0, 0,
//!   0]` for the sky. [`Frame::encode`] writes them as a 16-bit RGB PNG,
//!   `value = round((n + 1) / 2 · 65535)`, the sky `(0, 0, 0)`.
//! - **Instance ids**: object index in [`crate::model::Scene::objects`] + 1, up to 24 bits
//!   ([`MAX_OBJECTS`]); 0 = sky. The ids PNG packs them into RGB as COCO panoptic does:
//!   `id = R + 256·G + 256²·B`.
//! - **Colour**: `albedo · (ambient · ao + sun_colour · max(0, n·sun) · lit + Σ lights
//!   colour · (1 − (d/r)²)² · near² / (near² + d²) · beam · max(0, n·l)) + emissive ·
//!   emission` (the emissive colour times the texture for a material whose emission
//!   follows it: a backlit sign), plus a glow on lit windows, in linear light; `ao` is the ambient
//!   occlusion, `lit = 1 − shadow_strength · (1 − the shadow map's share of the sun)`;
//!   `albedo = base colour · texture`; the lights (lamps, car lights, the light lit
//!   windows spill) and their `beam` are `point_lights`'; each tile shades with at most
//!   `MAX_TILE_LIGHTS` of them. Written as 8-bit sRGB through a fixed table. (The lamp
//!   term is multiplied by the albedo like the sun: a red wall under a white lamp looks
//!   red.)
//!
//! # Pipeline of one frame
//!
//! 1. Objects whose bounding box is outside the view frustum are skipped, and so are
//!    objects the big ones (buildings, roads) wholly hide: those are rasterized first, and
//!    bound what each block of pixels can still show (`occlusion`; no byte changes).
//! 2. Triangles facing away are culled (counter-clockwise is the front; where vertex
//!    normals contradict the winding, [`prepare`] turns the triangle to follow them).
//! 3. Triangles are clipped against the near plane (Sutherland–Hodgman; and, rarely,
//!    against a guard band 4096 px beyond the image edges), projected, and snapped to
//!    1/256 px for exact integer edge functions with a top-left fill rule.
//! 4. They are binned into 32 × 32-pixel tiles in scene order. Tiles render in parallel
//!    (rayon), each owning its pixels: depth test on interpolated 1/w, then each visible
//!    sample is shaded once, with perspective-correct uv and trilinear mipmapped texture
//!    sampling whose level comes from the per-pixel screen-space derivatives of u/w, v/w and
//!    1/w. Textures repeat. Visibility (step 4's depth test) runs for every tile first,
//!    then the ambient occlusion `ao` of each pixel is measured on the whole frame's
//!    depth buffer (`ambient_occlusion`: screen space, why in its docs), then tiles shade.
//! 5. At one sample per pixel (the default), edges are antialiased from coverage: where a
//!    real edge (two objects, an object and the sky, a fold) crosses a pixel, its colour
//!    mixes with the neighbour's across the edge by the share of the pixel beyond it
//!    (`edge_aa`). With supersampling `s`, each pixel holds `s × s` samples instead:
//!    colour is their mean. Either way, instance id and depth come from the sample
//!    nearest the centre, so ids stay exact.
//!
//! Floating-point work uses only + − × ÷, sqrt, floor/ceil/round, min/max: the bytes are
//! the same on every machine and for any number of threads.

/// Bump when this stage's output bytes change: it is part of the stage's cache key.
pub const VERSION: u32 = 18;

mod ambient_occlusion;
mod centre_samples;
pub mod develop;
mod edge_aa;
mod flow;
mod footprint;
mod frame;
mod intrinsics;
mod lighting;
mod lit_windows;
mod mip_texture;
mod occlusion;
mod point_lights;
mod prepared_scene;
mod render_error;
mod scene_lighting;
mod screen_triangle;
mod shadow_map;
mod sky;
mod sun;
mod tile;
mod view;

#[cfg(test)]
mod shadow_tests;
#[cfg(test)]
mod tests;

pub use crate::model::CameraPose;
pub use flow::{Flow, Motion, flow};
pub use footprint::{Footprint, PAD as FOOTPRINT_PAD};
pub use frame::{DepthFormat, Frame, FramePngs};
pub use intrinsics::{DEFAULT_FAR, DEFAULT_NEAR, Intrinsics};
pub use lighting::{
    AMBIENT_OCCLUSION, CUTOFF_BAND, LAMP_COLOUR, Light, Lighting, MAX_SHADOW_MAP_SIDE, NIGHT_SKY,
    WINDOW_COLOUR, sun_colour,
};
pub use lit_windows::LitWindows;
pub use prepared_scene::{MAX_OBJECTS, PreparedScene, TextureMips, prepare, prepare_with};
pub use render_error::RenderError;
pub use scene_lighting::{ego_headlights, lighting_for};
pub use sky::Sky;
pub use sun::{Sun, solar_position};

use std::ops::Range;

use image::{ImageBuffer, Luma};
use rayon::prelude::*;

use centre_samples::CentreSamples;
use edge_aa::EdgeHint;
use lit_windows::WindowLookup;
use occlusion::{OcclusionBlocks, TileBlocks};
use screen_triangle::{SUB, ScreenTri};
use tile::{FrameContext, RasterContext, TILE, TileRaster, TileTarget};
use view::View;

/// Largest supersampling factor; larger requests are clamped to it.
pub const MAX_SUPERSAMPLE: u32 = 4;

/// Renders one frame. `supersample` 1 = one sample per pixel with edges antialiased from
/// coverage, 2 = 2×2 per pixel (colour averaged; instance and depth from the sample
/// nearest the pixel centre, so ids stay exact either way); 0 = one sample per pixel
/// without antialiasing (hard, jagged edges: for comparison and measurement);
/// more than [`MAX_SUPERSAMPLE`] as that. Unusable intrinsics (non-positive focal length
/// or near distance, far ≤ near) or a pose whose eye is its target give a frame of sky;
/// an image 0 pixels wide or high, an empty frame.
pub fn render(
    scene: &PreparedScene,
    pose: &CameraPose,
    intrinsics: &Intrinsics,
    lighting: &Lighting,
    supersample: u32,
) -> Frame {
    render_measuring(scene, pose, intrinsics, lighting, supersample, &[]).0
}

/// [`render`], and the [`Footprint`] of each object of `measure` (instance ids, ascending)
/// that shows in the frame, in id order: where it would show with nothing in front and no
/// image edge (the annotator's full projected box and the denominator of the visible
/// fraction). Objects wholly hidden are left out: nothing reads their footprint.
pub fn render_measuring(
    scene: &PreparedScene,
    pose: &CameraPose,
    intrinsics: &Intrinsics,
    lighting: &Lighting,
    supersample: u32,
    measure: &[u32],
) -> (Frame, Vec<Footprint>) {
    render_with(
        scene,
        pose,
        intrinsics,
        lighting,
        supersample,
        measure,
        false,
    )
}

/// [`render_measuring`], and with `normals` the frame's surface normals
/// ([`Frame::normals`]); without, none are worked out.
pub fn render_with(
    scene: &PreparedScene,
    pose: &CameraPose,
    intrinsics: &Intrinsics,
    lighting: &Lighting,
    supersample: u32,
    measure: &[u32],
    normals: bool,
) -> (Frame, Vec<Footprint>) {
    let samples = supersample.clamp(1, MAX_SUPERSAMPLE);
    let antialias_edges = supersample == 1;
    let (width, height) = (intrinsics.width, intrinsics.height);
    let Some(view) = View::new(pose, intrinsics, samples).filter(|_| width > 0 && height > 0)
    else {
        return (sky_frame(width, height, lighting, normals), Vec::new());
    };
    let tiles_x = width.div_ceil(TILE);
    let tiles_y = height.div_ceil(TILE);
    // Nothing reads across tiles without ambient occlusion or edge antialiasing: each tile
    // then shades as soon as it is rasterized, and its samples are dropped (a supersampled
    // frame's would be tens of megabytes).
    let keep = lighting.ambient_occlusion > 0.0 || antialias_edges;
    let Rasterized {
        tris,
        ranges,
        rasters,
    } = rasterize(scene, &view, (width, height), samples, keep);
    let lights = point_lights::frame_lights(&lighting.lights, &view);
    let windows = lighting
        .windows
        .as_ref()
        .map(|w| WindowLookup::new(w, scene.textures.len()));
    let shadows = if lighting.shadows {
        scene.shadow_map(lighting.sun_direction, lighting.shadow_map_side)
    } else {
        None
    };
    let ctx = FrameContext {
        raster: RasterContext::new(scene, &view, &tris, samples, (width, height)),
        lighting,
        lights: &lights,
        windows: windows.as_ref(),
        shadows: shadows.as_deref(),
        antialias_edges,
    };
    let n = width as usize * height as usize;
    let mut linear = filled([0f32; 3], n);
    let mut instance = filled(0u32, n);
    let mut depth = filled(0f32, n);
    let mut normal = normals.then(|| filled([0f32; 3], n));
    let targets = TileTarget::all(
        width as usize,
        &mut linear,
        &mut instance,
        &mut depth,
        normal.as_deref_mut(),
    );
    let centres = match rasters {
        None => {
            let bins = bin(&tris, 0, tiles_x, tiles_y, TILE * samples);
            targets.into_par_iter().enumerate().for_each(|(t, out)| {
                let raster = tile::raster_tile(&ctx.raster, t, &bins[t]);
                tile::finish_tile(&ctx, &raster, None, out);
            });
            None
        }
        Some(rasters) => {
            let centres = CentreSamples::new(&ctx.raster, &rasters);
            let ao = (lighting.ambient_occlusion > 0.0).then(|| {
                ambient_occlusion::visibility(&ctx.raster, &centres, lighting.ambient_occlusion)
            });
            targets
                .into_par_iter()
                .zip(&rasters)
                .for_each(|(out, r)| tile::finish_tile(&ctx, r, ao.as_deref(), out));
            Some(centres)
        }
    };
    let footprints = shown_footprints(
        scene,
        pose,
        intrinsics,
        &view,
        samples,
        (&tris, &ranges),
        measure,
        &instance,
    );
    let mut frame = finish(&ctx, centres.as_ref(), linear, instance, depth);
    frame.normals = normal;
    (frame, footprints)
}

/// What a view shows before shading: its screen triangles, each object's range of them
/// (by object index), and every tile's depth test over them when asked to keep them.
struct Rasterized {
    tris: Vec<ScreenTri>,
    ranges: Vec<Range<usize>>,
    rasters: Option<Vec<TileRaster>>,
}

/// The screen triangles of the objects `view` may see, with the objects the occluders
/// wholly hide left out ([`occlusion`]): they would show in no pixel. The occluders' come
/// first, then the others', each group in scene order; the depth test breaks ties by
/// scene order, so the order changes no pixel.
///
/// The occluders are rasterized first, tile by tile; their depths bound what each block
/// of pixels can show, and every other object is tested against that before it is set
/// up. With `keep`, the tiles then go on with the other objects' triangles and are
/// returned; without, each tile's samples are dropped once its blocks are known (the
/// caller rasterizes every triangle again, tile by tile, as it shades).
fn rasterize(
    scene: &PreparedScene,
    view: &View,
    (width, height): (u32, u32),
    samples: u32,
    keep: bool,
) -> Rasterized {
    let (tiles_x, tiles_y) = (width.div_ceil(TILE), height.div_ceil(TILE));
    let tile_px = TILE * samples;
    let setup = |object: &prepared_scene::ObjectBounds| {
        let mut out = Vec::new();
        if view.may_see_box(object.min, object.max) {
            for i in object.first..object.end {
                screen_triangle::setup(&scene.triangles[i], i as u32, view, &mut out);
            }
        }
        out
    };
    let occluders: Vec<Vec<ScreenTri>> = scene
        .objects
        .par_iter()
        .map(|object| {
            if object.occluder {
                setup(object)
            } else {
                Vec::new()
            }
        })
        .collect();
    let mut ranges = vec![0..0; scene.objects.len()];
    let mut tris = Vec::new();
    for (range, object_tris) in ranges.iter_mut().zip(occluders) {
        *range = tris.len()..tris.len() + object_tris.len();
        tris.extend(object_tris);
    }
    let first_others = tris.len();
    let (mut rasters, blocks) = {
        let ctx = RasterContext::new(scene, view, &tris, samples, (width, height));
        let bins = bin(&tris, 0, tiles_x, tiles_y, tile_px);
        let tiles = (0..bins.len())
            .into_par_iter()
            .map(|t| tile::raster_tile(&ctx, t, &bins[t]));
        if keep {
            let rasters: Vec<TileRaster> = tiles.collect();
            let blocks: Vec<TileBlocks> = rasters.par_iter().map(TileBlocks::of).collect();
            let blocks = OcclusionBlocks::of_tiles(view.width, view.height, &blocks);
            (Some(rasters), blocks)
        } else {
            let blocks: Vec<TileBlocks> = tiles.map(|r| TileBlocks::of(&r)).collect();
            (
                None,
                OcclusionBlocks::of_tiles(view.width, view.height, &blocks),
            )
        }
    };
    let others: Vec<Vec<ScreenTri>> = scene
        .objects
        .par_iter()
        .map(|object| {
            let triangles = &scene.triangles[object.first..object.end];
            if object.occluder || blocks.hides_object(view, (object.min, object.max), triangles) {
                return Vec::new();
            }
            let tris = setup(object);
            if tris.iter().all(|t| blocks.hides(t)) {
                return Vec::new();
            }
            tris
        })
        .collect();
    for (range, object_tris) in ranges.iter_mut().zip(others) {
        if !object_tris.is_empty() {
            *range = tris.len()..tris.len() + object_tris.len();
            tris.extend(object_tris);
        }
    }
    if let Some(rasters) = &mut rasters {
        let ctx = RasterContext::new(scene, view, &tris, samples, (width, height));
        let bins = bin(
            &tris[first_others..],
            first_others,
            tiles_x,
            tiles_y,
            tile_px,
        );
        rasters
            .par_iter_mut()
            .zip(&bins)
            .for_each(|(raster, bin)| tile::raster_more(&ctx, raster, bin));
    }
    Rasterized {
        tris,
        ranges,
        rasters,
    }
}

/// Accepted 1/w: above 1/far, at most 1.0001/near. Nothing is nearer than the near plane;
/// a larger 1/w is a rounding artefact.
fn q_range(view: &View) -> (f64, f64) {
    (1.0 / view.far, 1.0001 / view.near)
}

/// The footprints (see [`render_measuring`]) of the objects of `measure` that show in
/// `instance`, the frame's instance ids: an object no pixel shows is not measured, for
/// nobody asks how much of it is hidden.
#[allow(clippy::too_many_arguments)] // the frame's context, passed as the renderer holds it
fn shown_footprints(
    scene: &PreparedScene,
    pose: &CameraPose,
    intrinsics: &Intrinsics,
    view: &View,
    samples: u32,
    (tris, ranges): (&[ScreenTri], &[Range<usize>]),
    measure: &[u32],
    instance: &[u32],
) -> Vec<Footprint> {
    let Some(&top) = measure.iter().max() else {
        return Vec::new();
    };
    let mut shows = vec![false; top as usize + 1];
    for &id in instance {
        if id <= top {
            shows[id as usize] = true;
        }
    }
    let shown: Vec<u32> = measure
        .iter()
        .copied()
        .filter(|&id| shows[id as usize])
        .collect();
    let per_object: Vec<&[ScreenTri]> = ranges.iter().map(|r| &tris[r.clone()]).collect();
    footprint::measure(
        scene,
        pose,
        intrinsics,
        view,
        samples,
        &per_object,
        &shown,
        q_range(view),
    )
}

/// `n` copies of `value`, written on every core: a frame-sized buffer (the overview's are
/// 5 to 15 MB) would otherwise be cleared, its pages first touched, on one core while the
/// others wait.
pub(crate) fn filled<T: Copy + Send + Sync>(value: T, n: usize) -> Vec<T> {
    rayon::iter::repeat_n(value, n).collect()
}

/// What a frame shows, without its colours: the instance id and depth of each pixel, as
/// [`render_measuring`] gives them at one sample per pixel, and the footprints of
/// `measure`. Only the depth test runs: no shading, sky, shadows, ambient occlusion or
/// antialiasing (none of which changes ids or depth), so it costs a fraction of a frame.
/// For the build's checks of what a camera would see.
pub fn visibility(
    scene: &PreparedScene,
    pose: &CameraPose,
    intrinsics: &Intrinsics,
    measure: &[u32],
) -> (Visibility, Vec<Footprint>) {
    let (width, height) = (intrinsics.width, intrinsics.height);
    let Some(view) = View::new(pose, intrinsics, 1).filter(|_| width > 0 && height > 0) else {
        return (
            Visibility {
                instance: ImageBuffer::new(width, height),
                depth: ImageBuffer::new(width, height),
            },
            Vec::new(),
        );
    };
    let Rasterized {
        tris,
        ranges,
        rasters,
    } = rasterize(scene, &view, (width, height), 1, true);
    let rasters = rasters.expect("kept");
    let ctx = RasterContext::new(scene, &view, &tris, 1, (width, height));
    let w = width as usize;
    let mut instance = vec![0u32; w * height as usize];
    let mut depth = vec![0f32; w * height as usize];
    for r in &rasters {
        let rw = r.inner_width();
        for (row, (ids, qs)) in r.id.chunks(rw).zip(r.depth.chunks(rw)).enumerate() {
            let start = (r.rect[1] as usize + row) * w + r.rect[0] as usize;
            for (k, (&t, &q)) in ids.iter().zip(qs).enumerate() {
                (instance[start + k], depth[start + k]) = tile::instance_and_depth(&ctx, t, q);
            }
        }
    }
    let footprints = shown_footprints(
        scene,
        pose,
        intrinsics,
        &view,
        1,
        (&tris, &ranges),
        measure,
        &instance,
    );
    let visibility = Visibility {
        instance: ImageBuffer::from_raw(width, height, instance).expect("one id a pixel"),
        depth: ImageBuffer::from_raw(width, height, depth).expect("one depth a pixel"),
    };
    (visibility, footprints)
}

/// A frame's instance ids and depths, without its colours ([`visibility`]).
pub struct Visibility {
    /// As [`Frame::instance`]: 0 where nothing is.
    pub instance: ImageBuffer<Luma<u32>, Vec<u32>>,
    /// As [`Frame::depth`]: metres along the view axis, 0 for the sky.
    pub depth: ImageBuffer<Luma<f32>, Vec<f32>>,
}

/// Builds the shadow map `lighting` needs, if any, and keeps it in `scene`: frames under
/// that sun rendered side by side afterwards find it there instead of each building it.
pub fn warm_shadow_map(scene: &PreparedScene, lighting: &Lighting) {
    if lighting.shadows {
        scene.shadow_map(lighting.sun_direction, lighting.shadow_map_side);
    }
}

/// Indices of `tris` per tile, in order, numbered from `first`.
fn bin(
    tris: &[ScreenTri],
    first: usize,
    tiles_x: u32,
    tiles_y: u32,
    tile_px: u32,
) -> Vec<Vec<u32>> {
    let mut bins = vec![Vec::new(); (tiles_x * tiles_y) as usize];
    for (i, t) in (first..).zip(tris) {
        let [x0, y0, x1, y1] = t.bounds;
        for ty in y0 / tile_px..=(y1 - 1) / tile_px {
            for tx in x0 / tile_px..=(x1 - 1) / tile_px {
                bins[(ty * tiles_x + tx) as usize].push(i as u32);
            }
        }
    }
    bins
}

/// The frame from its shaded pixels: colours mixed across edges (at one sample per pixel,
/// which reads the frame's `centres`); ids and depth as the tiles resolved them.
/// [`Frame::rgb`] develops it.
fn finish(
    ctx: &FrameContext,
    centres: Option<&CentreSamples>,
    mut linear: Vec<[f32; 3]>,
    instance: Vec<u32>,
    depth: Vec<f32>,
) -> Frame {
    let (width, height) = (ctx.raster.width, ctx.raster.height);
    let w = width as usize;
    let instance: ImageBuffer<Luma<u32>, Vec<u32>> =
        ImageBuffer::from_raw(width, height, instance).expect("one id a pixel");
    let depth: ImageBuffer<Luma<f32>, Vec<f32>> =
        ImageBuffer::from_raw(width, height, depth).expect("one depth a pixel");
    if let Some(centres) = centres.filter(|_| ctx.antialias_edges) {
        // The triangle at each output pixel's centre (one sample per pixel).
        let tri = &centres.tri;
        let hint = |p: usize| {
            let fixed = |v: usize| v as i64 * SUB + SUB / 2;
            EdgeHint::of(
                &ctx.raster.tris[tri[p] as usize].edges,
                fixed(p % w),
                fixed(p / w),
                SUB,
            )
        };
        let ids = instance.as_raw();
        // A real edge: two objects, an object and the sky, or a fold of one surface.
        let real = |p: usize, q: usize| {
            if ids[p] != ids[q] {
                return true;
            }
            let (a, b) = (tri[p], tri[q]);
            if a == b || a == tile::NOTHING || b == tile::NOTHING {
                return a != b;
            }
            let normal = |t: u32| {
                ctx.raster.scene.triangles[ctx.raster.tris[t as usize].source as usize].normal
            };
            let (m, n) = (normal(a), normal(b));
            m[0] * n[0] + m[1] * n[1] + m[2] * n[2] < 0.999
        };
        edge_aa::antialias(&mut linear, tri, w, hint, real);
    }
    Frame {
        linear,
        instance,
        depth,
        normals: None,
        exposure: ctx.lighting.exposure,
    }
}

/// A frame of sky: `normals` asks for its (all-sky) normals too.
fn sky_frame(width: u32, height: u32, lighting: &Lighting, normals: bool) -> Frame {
    // No usable view: the sky at the horizon, everywhere.
    let sky = lighting.sky.radiance([0.0, 0.0, -1.0]);
    let n = width as usize * height as usize;
    let linear = vec![sky; n];
    Frame {
        linear,
        instance: ImageBuffer::new(width, height),
        depth: ImageBuffer::new(width, height),
        normals: normals.then(|| vec![[0.0; 3]; n]),
        exposure: lighting.exposure,
    }
}
