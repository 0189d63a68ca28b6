//! The overview shot: parsed layout + metres per pixel → the one pose, image size and view
//! that `overview.png` is rendered with.
//!
//! The numbers are choices of how the picture looks; changing any changes `overview.png`,
//! so bump [`super::VERSION`] (it is in the overview's cache key).

use super::{CameraPose, orbit_path};
use crate::model::ParsedLayout;

/// Image size: 4:3, large enough to read streets in a city of a few hundred metres.
pub const OVERVIEW_SIZE: [u32; 2] = [1280, 960];
/// tan of half the vertical field of view: 0.5, about 53° from top to bottom edge, a
/// normal lens that does not bend the city's edges.
pub const OVERVIEW_TAN_HALF_FOV: f64 = 0.5;
/// Eye height as a share of the city's diagonal: high enough that the near blocks do not
/// hide the far ones, low enough that facades still show.
pub const OVERVIEW_HEIGHT: f64 = 0.6;
/// The orbit is split into this many poses and the shot takes pose 1: one eighth of the
/// way clockwise from due north, the north-east corner.
pub const OVERVIEW_ORBIT_POSES: u32 = 8;
/// Far plane as a multiple of the diagonal: beyond the farthest corner from any orbit eye.
pub const OVERVIEW_FAR: f64 = 4.0;
/// Samples per pixel side: one, edges antialiased from coverage as the frames' are. Beside
/// 2 × 2 samples the picture differs by 2 of 255 on average, along edges, and the overview
/// stage takes about 50 ms less (314 → 262 ms for `specs/day.toml` on the 2-core machine;
/// its cold build without cameras, alternated with 2 × 2: a median of 1.03 → 0.98 s).
pub const OVERVIEW_SUPERSAMPLE: u32 = 1;
/// Side of the shadow map the overview reads, texels. The overview and the map both span
/// the whole city, so at any city size a map texel stays finer than the ground under an
/// overview pixel (2048 texels against 1280 pixels across), and its three-texel soft edge
/// about two pixels. A quarter of the street frames' map (4096): a cold build spends 50 ms
/// less on it.
pub const OVERVIEW_SHADOW_MAP_SIDE: u32 = 2048;

/// How to render the overview.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Overview {
    /// The eye; `None` for an empty layout (the overview is then a black image).
    pub pose: Option<CameraPose>,
    pub width: u32,
    pub height: u32,
    pub tan_half_fov: f64,
    /// Far clipping distance, metres.
    pub far: f64,
    pub supersample: u32,
}

/// The whole city in one oblique view from its north-east corner.
pub fn overview(layout: &ParsedLayout, metres_per_pixel: f64) -> Overview {
    let (w, h) = (f64::from(layout.width), f64::from(layout.height));
    let diagonal = (w * w + h * h).sqrt() * metres_per_pixel;
    let poses = orbit_path(
        layout,
        metres_per_pixel,
        OVERVIEW_ORBIT_POSES,
        diagonal * OVERVIEW_HEIGHT,
    );
    Overview {
        pose: poses.get(1).copied(),
        width: OVERVIEW_SIZE[0],
        height: OVERVIEW_SIZE[1],
        tan_half_fov: OVERVIEW_TAN_HALF_FOV,
        far: diagonal * OVERVIEW_FAR,
        supersample: OVERVIEW_SUPERSAMPLE,
    }
}

/// The overview of a map's box `[min_x, min_z, max_x, max_z]` (metres, `OsmMap::extent`):
/// the same shot as [`overview`] of a layout that size, from the box's north-east corner,
/// half the diagonal out from its centre and [`OVERVIEW_HEIGHT`] of the diagonal up.
pub fn map_overview(extent: [f64; 4]) -> Overview {
    let [x0, z0, x1, z1] = extent;
    let (w, h) = (x1 - x0, z1 - z0);
    let diagonal = (w * w + h * h).sqrt();
    let centre = [(x0 + x1) / 2.0, (z0 + z1) / 2.0];
    // North-east: +x, −z; the radius along the diagonal's half.
    let out = diagonal / 2.0 * std::f64::consts::FRAC_1_SQRT_2;
    let pose = (diagonal > 0.0 && diagonal.is_finite()).then(|| {
        CameraPose::level(
            [centre[0] + out, diagonal * OVERVIEW_HEIGHT, centre[1] - out],
            [centre[0], 0.0, centre[1]],
        )
    });
    Overview {
        pose,
        width: OVERVIEW_SIZE[0],
        height: OVERVIEW_SIZE[1],
        tan_half_fov: OVERVIEW_TAN_HALF_FOV,
        far: diagonal * OVERVIEW_FAR,
        supersample: OVERVIEW_SUPERSAMPLE,
    }
}
