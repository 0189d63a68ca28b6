//! One frame → YOLO txt: `class cx cy w h`, normalised to the image size.

use std::fmt::Write;

use super::frame_annotations::FrameAnnotations;
use super::object_label::Category;

/// YOLO txt for one frame: `class cx cy w h`, one line per object [`super::coco`] would
/// annotate, in instance-id order. `class` is the category's index in `categories` (YOLO
/// classes count from 0); the box is the visible box, its centre and size divided by the
/// image width and height, with 6 decimals.
pub fn yolo(categories: &[Category], frame: &FrameAnnotations) -> String {
    let (width, height) = (f64::from(frame.width), f64::from(frame.height));
    let mut out = String::new();
    for object in &frame.objects {
        if !object.passes {
            continue;
        }
        let Some(class) = object
            .label
            .category
            .and_then(|id| categories.iter().position(|c| c.id == id))
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
            },
            Category {
                id: 20,
                name: "car".into(),
            },
        ];
        let label = |name: &str, category| ObjectLabel {
            name: name.into(),
            category,
            text: None,
            attributes: Default::default(),
        };
        let labels = [
            label("car_0", Some(20)),
            label("sign_0", Some(10)),
            label("tree_0", Some(99)),
        ];
        let frame = FrameInput {
            file_name: "f.png".into(),
            instance: &img,
            intrinsics: [4.0, 4.0, 4.0, 2.0],
            pose: CameraPose::level([0.0; 3], [1.0, 0.0, 0.0]),
            full: BTreeMap::new(),
            quads: BTreeMap::new(),
        };
        let all = Thresholds {
            min_pixels: 1,
            min_fraction: 0.0,
        };
        assert_eq!(
            yolo(&categories, &summarize(&labels, &frame, &all)),
            "1 0.250000 0.250000 0.500000 0.500000\n0 0.937500 0.875000 0.125000 0.250000\n"
        );
        let big = Thresholds {
            min_pixels: 2,
            min_fraction: 0.0,
        };
        assert_eq!(
            yolo(&categories, &summarize(&labels, &frame, &big)),
            "1 0.250000 0.250000 0.500000 0.500000\n"
        );
    }
}
