//! The scene's objects, with what the objects stage knows of them (words, text
//! attributes, sign faces) → the annotate stage's [`annotate::ClassedObject`]s; with the
//! camera's `kitti`, each annotated object's 3D box from its meshes ([`annotate::Box3d`]);
//! with its `keypoints`, each annotated person's and rider's keypoints (and their
//! categories marked as having them).
//!
//! Glue only: which classes a path annotates, and how, is the annotate stage's
//! ([`annotate::path_labels`]).

use std::collections::BTreeMap;

use super::stages::PathInputs;
use crate::annotate::{self, ClassedObject, ObjectLabel, PathLabels, SignLabel};
use crate::model::Scene;
use crate::objects::{ObjectInfo, SignFace};

/// What a camera path annotates, for every object of `scene`.
pub fn labels(
    path: &PathInputs,
    scene: &Scene,
    info: &[Option<ObjectInfo>],
    sign_faces: &BTreeMap<usize, SignFace>,
) -> PathLabels {
    let objects = scene
        .objects
        .iter()
        .enumerate()
        .map(|(i, object)| {
            let info = info.get(i).and_then(Option::as_ref);
            ClassedObject {
                class: object.class.clone(),
                label: ObjectLabel {
                    name: object.name.clone(),
                    box3d: None,
                    keypoints: None,
                    category: None,
                    text: info.and_then(|info| info.text.clone()),
                    attributes: info.map(|info| info.attributes.clone()).unwrap_or_default(),
                    sign: sign_faces.get(&i).map(|face| SignLabel {
                        kind: face.kind.name().to_owned(),
                        centre: face.centre,
                        normal: face.normal,
                        back_category: None,
                    }),
                },
            }
        })
        .collect();
    let mut labels = annotate::path_labels(
        &path.annotations,
        &path.export.objects,
        &path.camera,
        objects,
    );
    if path.camera.kitti {
        // Only the objects the path may annotate: the rest are never written.
        for (label, object) in labels.labels.iter_mut().zip(&scene.objects) {
            if label.category.is_some() {
                let points = object.meshes.iter().flat_map(|m| &m.positions);
                label.box3d = annotate::Box3d::around(points.map(|p| p.map(f64::from)));
            }
        }
    }
    if path.camera.keypoints {
        for (label, info) in labels.labels.iter_mut().zip(info) {
            let keypoints = info.as_ref().and_then(|info| info.keypoints);
            if let (Some(category), Some(_)) = (label.category, keypoints) {
                label.keypoints = keypoints;
                for c in labels.categories.iter_mut().filter(|c| c.id == category) {
                    c.keypoints = true;
                }
            }
        }
    }
    labels
}
