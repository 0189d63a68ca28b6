//! Annotate stage: instance-id images + scene labels + camera data → COCO JSON, YOLO txt
//! and ICDAR 2015 text lines.
//!
//! Every label comes from the instance image, which already resolved occlusion: a pixel
//! shows the one object the renderer drew there. One column-major pass per frame gives each
//! id's visible box, pixel count and COCO RLE ([`VisibleObject`]); the renderer's projected
//! box and pixel count (ignoring occlusion) give the visible fraction. An object is
//! annotated when it has a category, shows at least `min_pixels` pixels and, where its
//! fraction is known, at least `min_fraction` of itself; a listed object that shows less
//! becomes a COCO ignore region (`iscrowd` 1) rather than vanishing. A sign counts as its
//! category only where the frame sees its face ([`SignLabel`]).
//!
//! A frame is first [`summarize`]d (one scan of its instance image) into
//! [`FrameAnnotations`]; every format is written from that summary, so a camera path
//! streams: frame after frame is summarized, written and dropped.
//!
//! | output | function | per |
//! |---|---|---|
//! | COCO JSON (pycocotools loads it) | [`CocoWriter`] (or [`coco`] for frames in memory) | camera path |
//! | YOLO `class cx cy w h` | [`yolo`] | frame |
//! | ICDAR 2015 `x1,y1,…,x4,y4,text` | [`icdar`] | frame |
//! | `instances.json`: instance id → kind, class, category, words, attributes | [`instances`] | camera path |
//! | KITTI object `label_2` lines and `calib` (3D boxes: [`Box3d`]) | [`kitti`] | frame |
//! | MOT Challenge `gt/gt.txt` and `seqinfo.ini` of a timed drive | [`mot_lines`], [`mot_seqinfo`] | frame, camera path |
//! | COCO `keypoints` of people and riders, visibility from the depth image | [`project_keypoints`] (in [`summarize`], written by [`CocoWriter`]) | frame |
//! | Cityscapes `labelIds`, `instanceIds`, `color` and COCO panoptic images and segments | [`semantic`] (labels: [`SemanticClasses`]) | frame |
//!
//! Output is deterministic: objects in instance-id order, JSON keys in a fixed order, and
//! floats rounded to fixed decimals before printing.

/// Bump when this stage's output bytes change: it is part of the stage's cache key.
pub const VERSION: u32 = 10;

mod box3d;
mod cityscapes;
mod coco;
mod coco_words;
mod contact_sheet;
mod contrast;
#[cfg(test)]
mod fixture_tests;
mod frame_annotations;
mod frame_input;
mod icdar;
mod instances;
mod keypoints;
mod kitti;
mod mot;
mod object_label;
mod path_labels;
mod project_quad;
mod rle;
mod semantic;
mod shown_object;
mod visible_object;
mod word_quad;
mod yolo;

pub use box3d::{Box3d, LevelCamera};
pub use cityscapes::{CityscapesLabel, SemanticClasses, TooManyClasses};
pub use coco::{CocoLines, CocoWriter, coco, write_coco};
pub use coco_words::WORD_CATEGORY;
pub use contact_sheet::{ContactSheet, picks as contact_sheet_picks};
pub use contrast::{MIN_CONTRAST, contrast};
pub use frame_annotations::{DepthFile, FrameAnnotations, summarize};
pub use frame_input::{FrameInput, Thresholds};
pub use icdar::icdar;
pub use instances::instances;
pub use keypoints::{KEYPOINT_NAMES, Keypoint, SKELETON, SURFACE_DEPTH, project_keypoints};
pub use kitti::{KittiFiles, kitti};
pub use mot::{mot_lines, mot_seqinfo};
pub use object_label::{Category, ObjectLabel, SignLabel, moved_labels};
pub use path_labels::{ClassedObject, PathLabels, path_labels};
pub use project_quad::project_quad;
pub use rle::{Rle, RleError};
pub use semantic::{PanopticImage, Segment, SemanticFrame, panoptic_json, semantic};
pub use shown_object::{Ignored, ShownObject, shown};
pub use visible_object::{VisibleObject, scan};
pub use word_quad::WordQuad;
pub use yolo::{YoloClasses, yolo};

/// `v` rounded to a multiple of `1 / scale` (`scale` a power of ten; `-0` made `0`), or
/// `None` when it is not finite.
fn round(v: f64, scale: f64) -> Option<f64> {
    let r = crate::model::geometry::round_to(v, scale);
    r.is_finite().then_some(r)
}

/// The word-quad fixture of the ICDAR and COCO word tests, 20 × 6: 1 "Write Group" (x 0..12,
/// rows 0..3), 2 "Edge" running past the right edge, 3 "Hidden" mostly behind 5, 4 "Gone
/// word" whose second word is off the image, 5 "Ok" with no quads, 6 a building (no
/// category); texts are category 1. Its instance image, labels, and word quads by id.
#[cfg(test)]
#[allow(clippy::type_complexity)]
pub(crate) fn word_fixture() -> (
    image::ImageBuffer<image::Luma<u32>, Vec<u32>>,
    Vec<ObjectLabel>,
    std::collections::BTreeMap<u32, Vec<[[f64; 2]; 4]>>,
) {
    let img = test_image(&[
        &[1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0, 2, 2, 2, 2, 2, 2],
        &[1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0, 2, 2, 2, 2, 2, 2],
        &[1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0, 2, 2, 2, 2, 2, 2],
        &[0; 20],
        &[3, 3, 3, 5, 5, 5, 5, 5, 5, 5, 5, 5, 6, 6, 4, 4, 4, 4, 4, 4],
        &[3, 3, 3, 5, 5, 5, 5, 5, 5, 5, 5, 5, 6, 6, 4, 4, 4, 4, 4, 4],
    ]);
    let label = |text: Option<&str>| ObjectLabel {
        name: text.unwrap_or("building").into(),
        box3d: None,
        keypoints: None,
        category: text.map(|_| 1),
        text: text.map(String::from),
        attributes: Default::default(),
        sign: None,
    };
    let labels = [
        Some("Write Group"),
        Some("Edge"),
        Some("Hidden"),
        Some("Gone word"),
        Some("Ok"),
        None,
    ]
    .map(label)
    .to_vec();
    let rect = |x0: f64, y0: f64, x1: f64, y1: f64| [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
    let quads = std::collections::BTreeMap::from([
        (
            1,
            vec![rect(0.0, 0.0, 10.0, 3.0), rect(10.0, 0.0, 12.0, 3.0)],
        ),
        (2, vec![rect(14.0, 0.0, 24.0, 3.0)]),
        (3, vec![rect(0.0, 4.0, 12.0, 6.0)]),
        (
            4,
            vec![rect(14.0, 4.0, 20.0, 6.0), rect(30.0, 4.0, 40.0, 6.0)],
        ),
    ]);
    (img, labels, quads)
}

/// An instance image from rows of ids.
#[cfg(test)]
pub(crate) fn test_image(rows: &[&[u32]]) -> image::ImageBuffer<image::Luma<u32>, Vec<u32>> {
    image::ImageBuffer::from_fn(rows[0].len() as u32, rows.len() as u32, |x, y| {
        image::Luma([rows[y as usize][x as usize]])
    })
}
