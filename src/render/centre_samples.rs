//! Rasterized tiles → the frame's centre samples: per output pixel, the screen triangle at
//! the sample nearest its centre and that sample's depth, row-major over the whole frame.
//!
//! Tiles own their pixels; the passes that read across tile borders (ambient occlusion,
//! edge antialiasing) read this instead: one flat array lookup per pixel, and 8 bytes a
//! pixel where a camera-space point and normal per pixel took 24.

use rayon::prelude::*;

use super::tile::{NOTHING, RasterContext, TILE, TileRaster};

/// Per output pixel, row-major: the centre sample's triangle and depth.
pub(crate) struct CentreSamples {
    pub width: usize,
    pub height: usize,
    /// Index into the frame's screen triangles, or [`NOTHING`] (the sky).
    pub tri: Vec<u32>,
    /// Depth along the view axis in metres (`1/q` as `f32`); 0 for the sky.
    pub z: Vec<f32>,
}

impl CentreSamples {
    pub(crate) fn new(ctx: &RasterContext, rasters: &[TileRaster]) -> CentreSamples {
        let (w, h) = (ctx.width as usize, ctx.height as usize);
        let s = ctx.samples as usize;
        let mut tri = super::filled(NOTHING, w * h);
        let mut z = super::filled(0f32, w * h);
        tri.par_chunks_mut(w)
            .zip(z.par_chunks_mut(w))
            .enumerate()
            .for_each(|(y, (trow, zrow))| {
                let row =
                    &rasters[y / TILE as usize * ctx.tiles_x as usize..][..ctx.tiles_x as usize];
                for raster in row {
                    let (x0, x1) = (raster.rect[0] as usize, raster.rect[2] as usize);
                    let oy = y - raster.rect[1] as usize;
                    for (ox, (t, z)) in trow[x0..x1].iter_mut().zip(&mut zrow[x0..x1]).enumerate() {
                        let i = raster.centre(ox, oy, s);
                        *t = raster.id[i];
                        if *t != NOTHING {
                            *z = (1.0 / raster.depth[i]) as f32;
                        }
                    }
                }
            });
        CentreSamples {
            width: w,
            height: h,
            tri,
            z,
        }
    }
}
