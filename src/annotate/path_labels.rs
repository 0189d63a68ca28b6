//! Spec + one camera + the scene's objects → that camera path's COCO categories, a label
//! per scene object, and the YOLO classes.
//!
//! Part of the annotate stage's output (category ids and names in `coco.json`, YOLO
//! `classes.txt`): a change here calls for a bump of [`super::VERSION`].

use std::collections::BTreeMap;

use super::coco_words::WORD_CATEGORY;
use super::{Category, ObjectLabel, YoloClasses};
use crate::spec::{AnnotationsSpec, CameraSpec, EntryKind, ObjectSpec, SignKind};

/// The class every lamp head is labelled with.
const LAMP_CLASS: &str = "lamp";

/// One scene object as the annotations see it, before the path's categories are known:
/// its class and its label with `category` and `sign.back_category` left unset.
pub struct ClassedObject {
    pub class: String,
    pub label: ObjectLabel,
}

/// What a camera path annotates.
pub struct PathLabels {
    pub categories: Vec<Category>,
    /// One per scene object, at index `instance id − 1`.
    pub labels: Vec<ObjectLabel>,
    /// YOLO's classes, when `[annotations] yolo` asks for YOLO files.
    pub yolo: Option<YoloClasses>,
}

/// The classes a path annotates: the camera's own `classes`, else `[annotations]
/// classes`, else every `[[objects]]` label (and `rider` after a bicycle entry's) and
/// `lamp`; COCO ids from 1 in that order, then `word` when a listed class carries text
/// and `word` is not listed already (a class list may name it to choose its place). Words
/// are COCO annotations only: YOLO's classes leave `word` out.
///
/// A traffic sign is its label's category only seen from the front; seen from behind it
/// is `<label>_back` when that class is listed, else nothing.
pub fn path_labels(
    annotations: &AnnotationsSpec,
    specs: &[ObjectSpec],
    camera: &CameraSpec,
    objects: Vec<ClassedObject>,
) -> PathLabels {
    let classes: Vec<String> = match (&camera.label_classes, annotations.classes.is_empty()) {
        (Some(classes), _) => classes.clone(),
        (None, false) => annotations.classes.clone(),
        (None, true) => {
            let mut classes: Vec<String> = Vec::new();
            for object in specs {
                let companions = ObjectSpec::annotated_companions(object.kind);
                for class in
                    std::iter::once(object.label.as_str()).chain(companions.iter().copied())
                {
                    if !classes.iter().any(|c| c == class) {
                        classes.push(class.to_owned());
                    }
                }
            }
            classes.push(LAMP_CLASS.to_owned());
            classes
        }
    };
    let classes = with_words(classes, &objects);
    let split = split_labels(annotations, specs);
    let categories = categories(&classes, &split);
    let id_of = |name: &str| categories.iter().find(|c| c.name == name).map(|c| c.id);
    let labels = objects
        .into_iter()
        .map(|ClassedObject { class, mut label }| {
            label.category = match &label.sign {
                Some(sign) if split.contains(&class.as_str()) => {
                    id_of(&format!("{class}/{}", sign.kind))
                }
                _ => id_of(&class),
            };
            if let Some(sign) = &mut label.sign {
                sign.back_category = id_of(&format!("{class}_back"));
            }
            label
        })
        .collect();
    let yolo = annotations.yolo.then(|| {
        let mut split: BTreeMap<u32, Vec<String>> = BTreeMap::new();
        if annotations.yolo_sign_types {
            for entry in specs.iter().filter(|o| o.kind == EntryKind::Sign) {
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
        // Words are COCO's (and ICDAR's) alone: YOLO boxes the plates.
        let plates: Vec<Category> = categories
            .iter()
            .filter(|c| c.name != WORD_CATEGORY)
            .cloned()
            .collect();
        YoloClasses::new(&plates, &split)
    });
    PathLabels {
        categories,
        labels,
        yolo,
    }
}

/// `classes` and, when one of them carries text and `word` is not among them, `word`.
fn with_words(mut classes: Vec<String>, objects: &[ClassedObject]) -> Vec<String> {
    let texts = objects
        .iter()
        .any(|o| o.label.text.is_some() && classes.contains(&o.class));
    if texts && !classes.iter().any(|c| c == WORD_CATEGORY) {
        classes.push(WORD_CATEGORY.to_owned());
    }
    classes
}

/// The sign entries' labels that become one category per sign type: with
/// `sign_categories`, every sign entry's; else none.
fn split_labels<'a>(annotations: &AnnotationsSpec, specs: &'a [ObjectSpec]) -> Vec<&'a str> {
    if !annotations.sign_categories {
        return Vec::new();
    }
    specs
        .iter()
        .filter(|o| o.kind == EntryKind::Sign)
        .map(|o| o.label.as_str())
        .collect()
}

/// COCO categories from 1 in `classes` order, a class in `split` replaced by
/// `<class>/<type>` for every sign type in catalogue order.
fn categories(classes: &[String], split: &[&str]) -> Vec<Category> {
    classes
        .iter()
        .flat_map(|name| {
            if split.contains(&name.as_str()) {
                SignKind::ALL
                    .iter()
                    .map(|k| format!("{name}/{}", k.name()))
                    .collect()
            } else {
                vec![name.clone()]
            }
        })
        .enumerate()
        .map(|(i, name)| Category {
            id: i as u32 + 1,
            name,
            keypoints: false,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::Spec;

    #[test]
    fn by_default_every_label_then_riders_after_bicycles_then_lamps() {
        let text = "version = 1\nname = 'a'\n[layout.generate]\n[buildings]\nwidths = [5, 5]\n\
                    [[objects]]\nkind = 'car'\nlabel = 'car'\n\
                    [[objects]]\nkind = 'bicycle'\nlabel = 'bicycle'\n\
                    [[objects]]\nkind = 'person'\nlabel = 'person'\n\
                    [[cameras]]\nname = 'c'\npath = 'roads'\nframes = 1\n";
        let spec: Spec = toml::from_str(text).unwrap();
        let labels = path_labels(
            &spec.annotations,
            &spec.objects,
            &spec.cameras[0],
            Vec::new(),
        );
        let names: Vec<&str> = labels.categories.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names, ["car", "bicycle", "rider", "person", "lamp"]);
        let ids: Vec<u32> = labels.categories.iter().map(|c| c.id).collect();
        assert_eq!(ids, [1, 2, 3, 4, 5]);
    }

    #[test]
    fn words_come_after_the_classes_when_text_is_listed_and_stay_out_of_yolo() {
        let text = "version = 1\nname = 'a'\n[layout.generate]\n[buildings]\nwidths = [5, 5]\n\
                    [annotations]\nyolo = true\n\
                    [[objects]]\nkind = 'text'\nlabel = 'text'\n\
                    [[objects]]\nkind = 'car'\nlabel = 'car'\n\
                    [[cameras]]\nname = 'c'\npath = 'roads'\nframes = 1\n";
        let spec: Spec = toml::from_str(text).unwrap();
        let object = |class: &str, text: Option<&str>| ClassedObject {
            class: class.into(),
            label: ObjectLabel {
                name: format!("{class}_0000"),
                box3d: None,
                keypoints: None,
                category: None,
                text: text.map(String::from),
                attributes: Default::default(),
                sign: None,
            },
        };
        let labels =
            |objects| path_labels(&spec.annotations, &spec.objects, &spec.cameras[0], objects);
        let with_text = labels(vec![object("text", Some("Open Late")), object("car", None)]);
        let names: Vec<&str> = with_text
            .categories
            .iter()
            .map(|c| c.name.as_str())
            .collect();
        assert_eq!(names, ["text", "car", "lamp", "word"]);
        assert_eq!(with_text.categories[3].id, 4);
        let yolo = with_text.yolo.unwrap().names_file();
        assert_eq!(yolo, "text\ncar\nlamp\n");
        // No text object in the scene: no word category.
        let without = labels(vec![object("car", None)]);
        assert_eq!(without.categories.len(), 3);
    }

    /// With `sign_categories`, COCO has a category per sign type in catalogue order, a
    /// stop sign's label is `traffic_sign/stop`'s, and YOLO's classes are the same names
    /// in the same order (class k is category k + 1); off, one `traffic_sign`.
    #[test]
    fn sign_categories_split_coco_and_yolo_alike() {
        let sign = |kind: &str| ClassedObject {
            class: "traffic_sign".to_owned(),
            label: ObjectLabel {
                name: format!("sign_{kind}"),
                box3d: None,
                keypoints: None,
                category: None,
                text: None,
                attributes: BTreeMap::new(),
                sign: Some(crate::annotate::object_label::SignLabel {
                    kind: kind.to_owned(),
                    centre: [0.0; 3],
                    normal: [1.0, 0.0, 0.0],
                    back_category: None,
                }),
            },
        };
        for on in [false, true] {
            let text = format!(
                "version = 1\nname = 'a'\n[layout.generate]\n[buildings]\nwidths = [5, 5]\n\
                 [[objects]]\nkind = 'car'\nlabel = 'car'\n[[objects]]\nkind = 'sign'\nlabel = 'traffic_sign'\nsigns = ['yield']\n\
                 [annotations]\nyolo = true\nsign_categories = {on}\n\
                 [[cameras]]\nname = 'c'\npath = 'roads'\nframes = 1\n"
            );
            let spec: Spec = toml::from_str(&text).unwrap();
            let objects = vec![sign("stop"), sign("bus_stop")];
            let labels = path_labels(&spec.annotations, &spec.objects, &spec.cameras[0], objects);
            let names: Vec<&str> = labels.categories.iter().map(|c| c.name.as_str()).collect();
            let yolo = labels.yolo.unwrap().names_file();
            assert_eq!(yolo.lines().collect::<Vec<_>>(), names);
            let id = |name: &str| {
                labels
                    .categories
                    .iter()
                    .find(|c| c.name == name)
                    .map(|c| c.id)
            };
            if on {
                assert_eq!(names.len(), 2 + SignKind::ALL.len());
                assert_eq!(names[1], "traffic_sign/stop");
                assert_eq!(names[SignKind::ALL.len()], "traffic_sign/bus_stop");
                assert_eq!(labels.labels[0].category, id("traffic_sign/stop"));
                assert_eq!(labels.labels[1].category, id("traffic_sign/bus_stop"));
            } else {
                assert_eq!(names, ["car", "traffic_sign", "lamp"]);
                assert_eq!(labels.labels[0].category, id("traffic_sign"));
            }
        }
    }
}
