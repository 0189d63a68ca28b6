//! What the scene knows of each object, and the categories annotations use.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::box3d::Box3d;

/// A COCO category.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Category {
    /// COCO category id (use 1 and up: some tools treat 0 as "none").
    pub id: u32,
    pub name: String,
    /// Whether its annotations carry keypoints: then COCO lists its `keypoints` names
    /// and `skeleton`.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub keypoints: bool,
}

/// One object of the scene, at index `instance id − 1`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ObjectLabel {
    /// Stable object name (`building_0042`), written into each annotation.
    pub name: String,
    /// Its [`Category::id`]; objects without one (ground, sky) are never annotated.
    pub category: Option<u32>,
    /// The words on a text object; text objects also go into the ICDAR lines.
    pub text: Option<String>,
    /// Extra attributes written into the object's COCO annotation as `attributes` (text:
    /// `text_style`, `text_font`); none written when empty.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub attributes: BTreeMap<String, String>,
    /// Its upright oriented 3D box, when the path writes 3D boxes (KITTI files and COCO
    /// `attributes.box3d`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub box3d: Option<Box3d>,
    /// A person's or rider's 17 COCO keypoints in world metres, when the path writes
    /// keypoints.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub keypoints: Option<[[f64; 3]; 17]>,
    /// A sign: which way its face looks, so it is labelled by the side a frame shows.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sign: Option<SignLabel>,
}

/// A sign's face: it counts as its category only where the camera sees the front.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SignLabel {
    /// The sign's type (`stop`, `yield`, `speed_limit`, …): the annotation's
    /// `attributes.sign_type`, and the YOLO subclass.
    pub kind: String,
    /// Centre of the face, world metres.
    pub centre: [f64; 3],
    /// Unit normal of the face, pointing out of its front.
    pub normal: [f64; 3],
    /// Category of the sign seen from behind (a blank back), when one is annotated.
    pub back_category: Option<u32>,
}

impl SignLabel {
    /// Whether a camera at `eye` sees the front: the eye lies on the face's side of its
    /// plane. (The face is flat, so this holds for every pixel of it at once.)
    pub fn front_seen_from(&self, eye: [f64; 3]) -> bool {
        let d = [
            eye[0] - self.centre[0],
            eye[1] - self.centre[1],
            eye[2] - self.centre[2],
        ];
        d[0] * self.normal[0] + d[1] * self.normal[1] + d[2] * self.normal[2] > 0.0
    }
}

/// A frame's labels with the traffic where the frame has it: each moving object's 3D box
/// and keypoints moved by its offset, each signal head's attribute `state` the lamp it
/// shows.
pub fn moved_labels(labels: &[ObjectLabel], movement: &crate::model::Movement) -> Vec<ObjectLabel> {
    let mut out = labels.to_vec();
    let shift = |p: &mut [f64; 3], o: [f64; 3]| {
        for k in 0..3 {
            p[k] += o[k];
        }
    };
    for &(id, offset) in &movement.moves {
        let Some(label) = out.get_mut((id as usize).wrapping_sub(1)) else {
            continue;
        };
        if offset == [0.0; 3] {
            continue;
        }
        if let Some(b) = &mut label.box3d {
            shift(&mut b.centre, offset);
        }
        if let Some(points) = &mut label.keypoints {
            points.iter_mut().for_each(|p| shift(p, offset));
        }
    }
    for &(id, state) in &movement.signals {
        if let Some(label) = out.get_mut((id as usize).wrapping_sub(1)) {
            label
                .attributes
                .insert("state".to_owned(), state.to_owned());
        }
    }
    out
}
