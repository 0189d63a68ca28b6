//! One rendered frame as the annotator needs it, and the visibility thresholds.

use std::collections::BTreeMap;

use image::{ImageBuffer, Luma};

use crate::model::CameraPose;

/// One frame: its instance-id image and what the renderer knows about it.
///
/// Maps are keyed by instance id (the value in the instance image: object index + 1).
#[derive(Clone, Debug)]
pub struct FrameInput<'a> {
    /// Name of the frame's RGB image, as the dataset stores it (`frames/000017.png`).
    pub file_name: String,
    /// Instance ids per pixel: 0 = background, k = object index + 1.
    pub instance: &'a ImageBuffer<Luma<u32>, Vec<u32>>,
    /// The frame's final RGB image (after the sensor), when known: a labelled object
    /// that does not stand out in it is an ignore region ([`super::MIN_CONTRAST`]).
    pub rgb: Option<&'a image::RgbImage>,
    /// Pinhole intrinsics in pixels: `[fx, fy, cx, cy]`.
    pub intrinsics: [f64; 4],
    pub pose: CameraPose,
    /// Per object: its full projected box `[x, y, w, h]` and its projected pixel count
    /// ignoring occlusion, when the renderer knows them. Without it an object's visible
    /// fraction is unknown and only `min_pixels` applies to it.
    pub full: BTreeMap<u32, ([f64; 4], u64)>,
    /// Per text object: per word of its text (split at spaces, in order), the four
    /// projected corners of the word's quad, clockwise from the top-left of the writing,
    /// when the renderer knows them (for ICDAR lines).
    pub quads: BTreeMap<u32, Vec<[[f64; 2]; 4]>>,
    /// The frame's depth, metres along the view axis (0 the sky), when the path writes
    /// keypoints: their visibility is read from it ([`super::project_keypoints`]).
    pub depth: Option<&'a ImageBuffer<Luma<f32>, Vec<f32>>>,
}

/// Which visible objects are annotated.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Thresholds {
    /// Fewest visible pixels an annotated object shows.
    pub min_pixels: u64,
    /// Smallest visible fraction (visible ÷ projected pixels) of an annotated object, where
    /// the fraction is known.
    pub min_fraction: f64,
}
