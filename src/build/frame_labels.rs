//! Spec + one camera + scene + object data → that camera path's COCO categories, a label
//! per scene object, and the YOLO classes.

use std::collections::BTreeMap;

use crate::annotate::{self, Category, ObjectLabel, SignLabel, YoloClasses};
use crate::model::Scene;
use crate::objects::{ObjectInfo, SignFace};
use crate::spec::{CameraSpec, ObjectKind, SignKind, Spec};

/// What a camera path annotates.
pub struct PathLabels {
    pub categories: Vec<Category>,
    /// One per scene object, at index `instance id − 1`.
    pub labels: Vec<ObjectLabel>,
    /// YOLO's classes, when `[annotations] yolo` asks for YOLO files.
    pub yolo: Option<YoloClasses>,
}

/// The classes a path annotates: the camera's own `classes`, else `[annotations]
/// classes`, else every `[[objects]]` label and `lamp`; COCO ids from 1 in that order.
///
/// A traffic sign is its label's category only seen from the front; seen from behind it
/// is `<label>_back` when that class is listed, else nothing.
pub fn labels(
    spec: &Spec,
    camera: &CameraSpec,
    scene: &Scene,
    info: &[Option<ObjectInfo>],
    sign_faces: &BTreeMap<usize, SignFace>,
) -> PathLabels {
    let classes: Vec<String> = match (&camera.label_classes, spec.annotations.classes.is_empty()) {
        (Some(classes), _) => classes.clone(),
        (None, false) => spec.annotations.classes.clone(),
        (None, true) => {
            let mut classes: Vec<String> = Vec::new();
            for object in &spec.objects {
                if !classes.contains(&object.label) {
                    classes.push(object.label.clone());
                }
            }
            classes.push("lamp".to_owned());
            classes
        }
    };
    let categories: Vec<Category> = classes
        .iter()
        .enumerate()
        .map(|(i, name)| Category {
            id: i as u32 + 1,
            name: name.clone(),
        })
        .collect();
    let id_of = |name: &str| categories.iter().find(|c| c.name == name).map(|c| c.id);
    let labels = scene
        .objects
        .iter()
        .enumerate()
        .map(|(i, object)| ObjectLabel {
            name: object.name.clone(),
            category: id_of(&object.class),
            text: info.get(i).and_then(|info| info.as_ref()?.text.clone()),
            attributes: info
                .get(i)
                .and_then(|info| Some(info.as_ref()?.attributes.clone()))
                .unwrap_or_default(),
            sign: sign_faces.get(&i).map(|face| SignLabel {
                kind: face.kind.name().to_owned(),
                centre: face.centre,
                normal: face.normal,
                back_category: id_of(&format!("{}_back", object.class)),
            }),
        })
        .collect();
    let yolo = spec.annotations.yolo.then(|| {
        let mut split: BTreeMap<u32, Vec<String>> = BTreeMap::new();
        if spec.annotations.yolo_sign_types {
            for entry in spec.objects.iter().filter(|o| o.kind == ObjectKind::Sign) {
                let Some(id) = id_of(&entry.label) else {
                    continue;
                };
                let kinds = split.entry(id).or_default();
                for kind in SignKind::ALL {
                    let name = kind.name().to_owned();
                    let drawn = entry.signs.is_empty() || entry.signs.contains(&kind);
                    if drawn && !kinds.contains(&name) {
                        kinds.push(name);
                    }
                }
            }
            // Every entry's types in SignKind order, whatever the entries' order.
            for kinds in split.values_mut() {
                kinds.sort_by_key(|k| SignKind::ALL.iter().position(|s| s.name() == k));
            }
        }
        annotate::YoloClasses::new(&categories, &split)
    });
    PathLabels {
        categories,
        labels,
        yolo,
    }
}
