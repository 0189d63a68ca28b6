//! A spec's camera path → what rendering it takes: the prepared scene, the poses, the
//! intrinsics and the lighting of its first frame. For benchmarks and tools that drive
//! the renderer themselves (`benches/render.rs` times each lighting feature on the
//! `specs/day.toml` street with it).
//!
//! The city stages run, or load from the cache, as in a build; nothing is rendered and
//! the output folder is not touched.

use std::path::Path;
use std::sync::Arc;

use super::frames::camera_intrinsics;
use super::inputs::SpecInputs;
use super::pipeline::Pipeline;
use super::{BuildError, load_spec};
use crate::cache::Cache;
use crate::model::CameraPose;
use crate::render::{DepthFormat, Intrinsics, Lighting, PreparedScene};

/// What rendering one camera path takes.
pub struct PathRenderInput {
    pub scene: Arc<PreparedScene>,
    /// Every frame's pose, in frame order.
    pub poses: Vec<CameraPose>,
    pub intrinsics: Intrinsics,
    /// The lighting of the path's first frame, before weather (`vary = "frame"` draws a
    /// sun per frame; this is frame 0's).
    pub lighting: Lighting,
    /// The camera's `supersample` (1: one sample per pixel with edge antialiasing).
    pub supersample: u32,
    /// How the camera's depth images are written.
    pub depth: DepthFormat,
}

/// The render input of the camera named `camera` in the spec at `path`, with the city
/// stages cached in `cache_dir`; `None` when the spec has no such camera.
pub fn path_render_input(
    path: &Path,
    camera: &str,
    cache_dir: &Path,
) -> Result<Option<PathRenderInput>, BuildError> {
    let spec = load_spec(path)?;
    let Some(index) = spec.cameras.iter().position(|c| c.name == camera) else {
        return Ok(None);
    };
    let inputs = SpecInputs::read(path, &spec)?;
    let cache = Cache::open(cache_dir)?;
    let quiet = |_: &str, _: usize, _: usize| {};
    let mut pipeline = Pipeline::new(&spec, path.to_path_buf(), inputs, &cache, &quiet);
    let (scene, poses, lighting) = pipeline.path_render_input(index)?;
    let c = &spec.cameras[index];
    Ok(Some(PathRenderInput {
        scene,
        poses,
        intrinsics: camera_intrinsics(c),
        lighting,
        supersample: c.supersample,
        depth: c.depth,
    }))
}
