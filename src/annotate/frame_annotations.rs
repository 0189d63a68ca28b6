//! One frame's instance image + labels + renderer data → [`FrameAnnotations`]: the labelled
//! objects it shows, measured once and owned, so the frame's images can be dropped.
//!
//! A camera path streams: each frame is rendered, summarized here, written (COCO lines,
//! YOLO, ICDAR) and forgotten, so memory does not grow with the number of frames.

use std::collections::BTreeMap;

use super::frame_input::{FrameInput, Thresholds};
use super::keypoints::{Keypoint, project_keypoints};
use super::object_label::ObjectLabel;
use super::shown_object::{ShownObject, shown};
use super::word_quad::WordQuad;
use crate::model::CameraPose;

/// What every output format needs of one frame.
#[derive(Clone, Debug)]
pub struct FrameAnnotations<'a> {
    /// Name of the frame's RGB image, as the dataset stores it.
    pub file_name: String,
    pub width: u32,
    pub height: u32,
    /// Pinhole intrinsics in pixels: `[fx, fy, cx, cy]`.
    pub intrinsics: [f64; 4],
    pub pose: CameraPose,
    /// The labelled objects the frame shows, in instance-id order, each with whether it
    /// passes the thresholds.
    pub objects: Vec<ShownObject<'a>>,
    /// Per shown text object that has them, by instance id: its words' projected quads and
    /// how much of each the frame shows.
    pub quads: BTreeMap<u32, Vec<WordQuad>>,
    /// The frame's depth image, when the dataset has one (the caller sets it).
    pub depth: Option<DepthFile>,
    /// Per shown object whose label has keypoints, by instance id: them projected, when
    /// the frame came with its depth.
    pub keypoints: BTreeMap<u32, [Keypoint; 17]>,
}

/// Where a frame's depth image is and how to read it.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthFile {
    /// Relative to the camera path's folder, like `file_name` (`depth/000017.png`).
    pub file_name: String,
    /// `cm16`, `mm16` or `f32`.
    pub format: &'static str,
    /// Metres per stored unit.
    pub scale: f64,
}

/// Scans `frame`'s instance image once and keeps what the outputs need.
pub fn summarize<'a>(
    labels: &'a [ObjectLabel],
    frame: &FrameInput,
    thresholds: &Thresholds,
) -> FrameAnnotations<'a> {
    let objects = shown(labels, frame, thresholds);
    let (width, height) = frame.instance.dimensions();
    let quads = objects
        .iter()
        .filter_map(|o| {
            let id = o.visible.id;
            let words = frame.quads.get(&id)?.iter().map(|&quad| {
                WordQuad::measure(quad, width, height, |x, y| {
                    frame.instance.get_pixel(x, y).0[0] == id
                })
            });
            Some((id, words.collect()))
        })
        .collect();
    let keypoints = match frame.depth {
        Some(depth) => objects
            .iter()
            .filter_map(|o| {
                let world = o.label.keypoints.as_ref()?;
                let projected = project_keypoints(world, &frame.pose, frame.intrinsics, depth);
                Some((o.visible.id, projected))
            })
            .collect(),
        None => BTreeMap::new(),
    };
    FrameAnnotations {
        file_name: frame.file_name.clone(),
        width,
        height,
        intrinsics: frame.intrinsics,
        pose: frame.pose,
        objects,
        quads,
        depth: None,
        keypoints,
    }
}
