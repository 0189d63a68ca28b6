//! One frame → YOLO txt: `class cx cy w h`, normalised to the image size; and the class
//! names file that goes with it.

use std::collections::BTreeMap;
use std::fmt::Write;

use super::frame_annotations::FrameAnnotations;
use super::object_label::Category;

/// YOLO class ids: the categories in order, each one given subclasses (sign types)
/// replaced by one class per subclass (`traffic_sign/stop`, …) when asked.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct YoloClasses {
    /// Per class: its category and subclass, and its name.
    classes: Vec<(u32, Option<String>, String)>,
}

impl YoloClasses {
    /// One class per category, or per `(category, subclass)` for the categories listed in
    /// `subclasses`, in the order given.
    pub fn new(categories: &[Category], subclasses: &BTreeMap<u32, Vec<String>>) -> YoloClasses {
        let mut classes = Vec::new();
        for c in categories {
            match subclasses.get(&c.id).filter(|s| !s.is_empty()) {
                Some(subs) => {
                    for sub in subs {
                        classes.push((c.id, Some(sub.clone()), format!("{}/{sub}", c.name)));
                    }
                }
                None => classes.push((c.id, None, c.name.clone())),
            }
        }
        YoloClasses { classes }
    }

    /// The class id of an object of `category` (and `subclass`, for a split category).
    pub fn index(&self, category: u32, subclass: Option<&str>) -> Option<usize> {
        self.classes
            .iter()
            .position(|(c, s, _)| *c == category && (s.is_none() || s.as_deref() == subclass))
    }

    /// `classes.txt`: one name per line, line `k` naming class `k`.
    pub fn names_file(&self) -> String {
        self.classes
            .iter()
            .fold(String::new(), |mut out, (_, _, name)| {
                out.push_str(name);
                out.push('\n');
                out
            })
    }
}

/// YOLO txt for one frame: `class cx cy w h`, one line per object [`super::coco`] would
/// annotate with `iscrowd` 0, in instance-id order. `class` is the object's index in
/// `classes` (YOLO classes count from 0); the box is the visible box (inside the image),
/// its centre and size divided by the image width and height, with 6 decimals. YOLO has
/// no ignore regions: objects under the thresholds are left out.
pub fn yolo(classes: &YoloClasses, frame: &FrameAnnotations) -> String {
    let (width, height) = (f64::from(frame.width), f64::from(frame.height));
    let mut out = String::new();
    for object in &frame.objects {
        if !object.passes() {
            continue;
        }
        let Some(class) = object
            .category
            .and_then(|id| classes.index(id, object.subclass))
        else {
            continue;
        };
        let [x, y, w, h] = object.visible.bounds.bbox().map(f64::from);
        let cx = (x + w / 2.0) / width;
        let cy = (y + h / 2.0) / height;
        let _ = writeln!(
            out,
            "{class} {cx:.6} {cy:.6} {:.6} {:.6}",
            w / width,
            h / height
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;
    use crate::annotate::{FrameInput, ObjectLabel, Thresholds, summarize, test_image};
    use crate::model::CameraPose;

    #[test]
    fn boxes_are_normalised_and_classes_count_from_zero() {
        // 8 × 4 image: a 4 × 2 car at (0, 0) and a 1 × 1 sign at (7, 3); a tree without a
        // listed category.
        let img = test_image(&[
            &[1, 1, 1, 1, 0, 0, 0, 0],
            &[1, 1, 1, 1, 0, 3, 0, 0],
            &[0, 0, 0, 0, 0, 0, 0, 0],
            &[0, 0, 0, 0, 0, 0, 0, 2],
        ]);
        let categories = [
            Category {
                id: 10,
                name: "sign".into(),
                keypoints: false,
            },
            Category {
                id: 20,
                name: "car".into(),
                keypoints: false,
            },
        ];
        let label = |name: &str, category| ObjectLabel {
            name: name.into(),
            box3d: None,
            keypoints: None,
            category,
            text: None,
            attributes: Default::default(),
            sign: None,
        };
        let labels = [
            label("car_0", Some(20)),
            label("sign_0", Some(10)),
            label("tree_0", Some(99)),
        ];
        let classes = YoloClasses::new(&categories, &BTreeMap::new());
        assert_eq!(classes.names_file(), "sign\ncar\n");
        let frame = FrameInput {
            file_name: "f.png".into(),
            instance: &img,
            rgb: None,
            intrinsics: [4.0, 4.0, 4.0, 2.0],
            pose: CameraPose::level([0.0; 3], [1.0, 0.0, 0.0]),
            full: BTreeMap::new(),
            quads: BTreeMap::new(),
            depth: None,
        };
        let all = Thresholds {
            min_pixels: 1,
            min_fraction: 0.0,
        };
        assert_eq!(
            yolo(&classes, &summarize(&labels, &frame, &all)),
            "1 0.250000 0.250000 0.500000 0.500000\n0 0.937500 0.875000 0.125000 0.250000\n"
        );
        let big = Thresholds {
            min_pixels: 2,
            min_fraction: 0.0,
        };
        assert_eq!(
            yolo(&classes, &summarize(&labels, &frame, &big)),
            "1 0.250000 0.250000 0.500000 0.500000\n"
        );
    }
}
