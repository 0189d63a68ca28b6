//! `instances.json`: every instance id of a camera path's `ids/` images → what the object
//! is (its kind, set by the stage that made it), its class, the category this path
//! labels it as, its words and attributes.
//!
//! One file per path, written from the same labels as `coco.json`, YOLO and ICDAR, so a
//! reader of the id images (`cityspec stats`, a user's own tools) never has to guess an
//! object's kind from its name.

use super::{Category, PathLabels};
use crate::model::{Instance, Instances, ObjectKind};

/// Every object of the scene (`objects`: each one's kind and class, in scene order) with
/// what `labels` says of it on this path.
pub fn instances(objects: &[(ObjectKind, &str)], labels: &PathLabels) -> Instances {
    let category_name = |id: Option<u32>| -> Option<String> {
        let id = id?;
        labels
            .categories
            .iter()
            .find(|c: &&Category| c.id == id)
            .map(|c| c.name.clone())
    };
    let instances = objects
        .iter()
        .zip(&labels.labels)
        .zip(1u32..)
        .map(|((&(kind, class), label), id)| Instance {
            id,
            name: label.name.clone(),
            kind,
            class: class.to_owned(),
            category: category_name(label.category),
            text: label.text.clone(),
            attributes: label.attributes.clone(),
        })
        .collect();
    Instances { instances }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::annotate::{ObjectLabel, path_labels};
    use crate::spec::Spec;
    use std::collections::BTreeMap;

    #[test]
    fn every_object_is_listed_by_id_with_its_kind_and_this_path_s_category() {
        let text = "version = 1\nname = 'a'\n[layout.generate]\n\
                    [[objects]]\nkind = 'car'\nlabel = 'vehicle'\n\
                    [[cameras]]\nname = 'c'\npath = 'roads'\nframes = 1\n";
        let spec: Spec = toml::from_str(text).expect("the spec parses");
        let object = |name: &str, class: &str| crate::annotate::ClassedObject {
            class: class.to_owned(),
            label: ObjectLabel {
                name: name.to_owned(),
                box3d: None,
                keypoints: None,
                category: None,
                text: None,
                attributes: BTreeMap::new(),
                sign: None,
            },
        };
        let labels = path_labels(
            &spec.annotations,
            &spec.objects,
            &spec.cameras[0],
            vec![object("ground", "ground"), object("car_0001", "vehicle")],
        );
        let listed = instances(
            &[(ObjectKind::Ground, "ground"), (ObjectKind::Car, "vehicle")],
            &labels,
        );
        let ids: Vec<u32> = listed.instances.iter().map(|i| i.id).collect();
        assert_eq!(ids, [1, 2]);
        assert_eq!(listed.instances[0].category, None);
        assert_eq!(listed.instances[1].kind, ObjectKind::Car);
        assert_eq!(listed.instances[1].category.as_deref(), Some("vehicle"));
        let json = serde_json::to_string(&listed).expect("serializes");
        assert!(json.contains("\"kind\":\"car\""), "{json}");
    }
}
