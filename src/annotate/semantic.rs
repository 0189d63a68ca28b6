//! A frame's instance image → its Cityscapes-format labels: the `labelIds` image (8-bit
//! label id per pixel), the `instanceIds` image (16-bit: `id × 1000 + k` for the k-th
//! object, from 0, of a label with instances; the label id for the rest), the `color`
//! image (each label's colour) and the COCO panoptic image and segments (`id = R + 256·G +
//! 256²·B` = the `instanceIds` value; labels ignored in evaluation left 0), exactly as
//! `cityscapesscripts`' `createPanopticImgs` makes them from `instanceIds`.
//!
//! Objects are numbered in instance-id order, so the numbering is the same whichever
//! machine renders the frame. A label's 1000th object and later ones in one frame are
//! written without a number (`id` alone, Cityscapes' group of objects, `iscrowd` 1 in
//! panoptic).

use image::{GrayImage, ImageBuffer, Luma, RgbImage};
use serde::{Deserialize, Serialize};

use serde_json::json;

use super::cityscapes::{CityscapesLabel, SemanticClasses};

/// One panoptic segment, as COCO panoptic's `segments_info` holds it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Segment {
    pub id: u32,
    pub category_id: u8,
    pub area: u64,
    /// `[x, y, width, height]` of the segment's pixels.
    pub bbox: [u32; 4],
    pub iscrowd: u8,
}

/// A frame's Cityscapes-format images and panoptic segments.
pub struct SemanticFrame {
    pub label_ids: GrayImage,
    pub instance_ids: ImageBuffer<Luma<u16>, Vec<u16>>,
    pub color: RgbImage,
    pub panoptic: RgbImage,
    /// By segment id.
    pub segments: Vec<Segment>,
}

/// Frame labels from its instance image (`0` the sky, `k + 1` the scene's object `k`).
pub fn semantic(
    classes: &SemanticClasses,
    instance: &ImageBuffer<Luma<u32>, Vec<u32>>,
) -> SemanticFrame {
    let (width, height) = instance.dimensions();
    // Which instance ids the frame shows (an id past the scene's is `unlabeled`).
    let ids = classes.of_instance.len();
    let mut shown = vec![false; ids + 1];
    for &id in instance.as_raw() {
        shown[(id as usize).min(ids)] = true;
    }
    // Each shown object's instanceIds value: numbered per label in instance-id order.
    let mut counts = [0u32; 256];
    let values: Vec<u16> = (0..=ids)
        .map(|id| {
            let label = classes.label_of(id as u32);
            let k = &mut counts[usize::from(label.id)];
            let value = if shown[id] && label.has_instances && *k < 1000 {
                *k += 1;
                u32::from(label.id) * 1000 + *k - 1
            } else {
                u32::from(label.id)
            };
            value as u16
        })
        .collect();
    let raw = instance.as_raw();
    let label_ids = GrayImage::from_raw(
        width,
        height,
        raw.iter().map(|&id| classes.label_of(id).id).collect(),
    )
    .expect("one label a pixel");
    let instance_ids = ImageBuffer::from_raw(
        width,
        height,
        raw.iter()
            .map(|&id| values[(id as usize).min(ids)])
            .collect(),
    )
    .expect("one value a pixel");
    let color = RgbImage::from_raw(
        width,
        height,
        label_ids
            .as_raw()
            .iter()
            .flat_map(|&id| classes.labels[usize::from(id)].color)
            .collect(),
    )
    .expect("one colour a pixel");
    let (panoptic, segments) = panoptic(classes, &instance_ids);
    SemanticFrame {
        label_ids,
        instance_ids,
        color,
        panoptic,
        segments,
    }
}

/// The panoptic image and segments of an `instanceIds` image, as `createPanopticImgs`.
fn panoptic(
    classes: &SemanticClasses,
    instance_ids: &ImageBuffer<Luma<u16>, Vec<u16>>,
) -> (RgbImage, Vec<Segment>) {
    let (width, height) = instance_ids.dimensions();
    // Per value: pixel count and box [x0, y0, x1, y1].
    let mut found = vec![(0u64, [u32::MAX, u32::MAX, 0, 0]); 1 << 16];
    for (x, y, value) in instance_ids.enumerate_pixels() {
        let (area, b) = &mut found[usize::from(value[0])];
        *area += 1;
        *b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
    }
    let found = (0..=u16::MAX).zip(found).filter(|(_, (area, _))| *area > 0);
    // The label of an instanceIds value (`unlabeled` for one past the table, which
    // `semantic` never writes).
    let label = |value: u16| {
        let id = if value < 1000 { value } else { value / 1000 };
        classes
            .labels
            .get(usize::from(id))
            .unwrap_or(&classes.labels[0])
    };
    let segments: Vec<Segment> = found
        .filter(|(value, _)| !label(*value).ignore_in_eval)
        .map(|(value, (area, b))| {
            let label = label(value);
            Segment {
                id: u32::from(value),
                category_id: label.id,
                area,
                bbox: [b[0], b[1], b[2] - b[0] + 1, b[3] - b[1] + 1],
                iscrowd: u8::from(value < 1000 && label.has_instances),
            }
        })
        .collect();
    let panoptic = RgbImage::from_fn(width, height, |x, y| {
        let value = instance_ids.get_pixel(x, y)[0];
        if label(value).ignore_in_eval {
            image::Rgb([0, 0, 0])
        } else {
            let [lo, hi] = value.to_le_bytes();
            image::Rgb([lo, hi, 0])
        }
    });
    (panoptic, segments)
}

/// One image of a COCO panoptic document.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PanopticImage {
    /// An integer (a camera path's frame index + 1) or a string (Cityscapes' image name).
    pub id: serde_json::Value,
    pub width: u32,
    pub height: u32,
    /// The image's file.
    pub file_name: String,
    /// Its panoptic PNG.
    pub segments_file: String,
    pub segments: Vec<Segment>,
}

/// A COCO panoptic document (`images`, `annotations` with `segments_info`, `categories`:
/// the labels counted in evaluation, `isthing` for those with instances), one image and one
/// annotation a line.
pub fn panoptic_json(labels: &[CityscapesLabel], images: &[PanopticImage]) -> Vec<u8> {
    let lines = |items: Vec<serde_json::Value>| -> String {
        let items: Vec<String> = items.iter().map(|v| format!("  {v}")).collect();
        items.join(",\n")
    };
    let image_lines = images
        .iter()
        .map(
            |i| json!({"id": i.id, "width": i.width, "height": i.height, "file_name": i.file_name}),
        )
        .collect();
    let annotation_lines = images
        .iter()
        .map(|i| json!({"image_id": i.id, "file_name": i.segments_file, "segments_info": i.segments}))
        .collect();
    let categories = labels
        .iter()
        .filter(|l| !l.ignore_in_eval)
        .map(|l| {
            json!({"id": l.id, "name": l.name, "color": l.color, "supercategory": l.category,
                   "isthing": u8::from(l.has_instances)})
        })
        .collect();
    format!(
        "{{\"images\": [\n{}\n],\n\"annotations\": [\n{}\n],\n\"categories\": [\n{}\n]}}\n",
        lines(image_lines),
        lines(annotation_lines),
        lines(categories)
    )
    .into_bytes()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::annotate::test_image;
    use crate::model::ObjectKind;

    #[test]
    fn objects_of_labels_with_instances_are_numbered_per_label() {
        let classes = SemanticClasses::of(&[
            (ObjectKind::Road, "road"),
            (ObjectKind::Car, "car"),
            (ObjectKind::Car, "car"),
            (ObjectKind::Person, "person"),
            (ObjectKind::Ground, "ground"),
        ])
        .unwrap();
        let frame = semantic(
            &classes,
            &test_image(&[&[0, 0, 1, 1], &[3, 2, 2, 4], &[3, 3, 1, 5]]),
        );
        assert_eq!(
            frame.label_ids.as_raw(),
            &[23, 23, 7, 7, 26, 26, 26, 24, 26, 26, 7, 22]
        );
        assert_eq!(
            frame.instance_ids.as_raw(),
            &[
                23, 23, 7, 7, 26001, 26000, 26000, 24000, 26001, 26001, 7, 22
            ]
        );
        assert_eq!(frame.color.get_pixel(0, 0).0, [70, 130, 180]);
        assert_eq!(frame.color.get_pixel(1, 1).0, [0, 0, 142]);
        // 26000 = 0x6590: R 0x90, G 0x65.
        assert_eq!(frame.panoptic.get_pixel(1, 1).0, [0x90, 0x65, 0]);
        let ids: Vec<u32> = frame.segments.iter().map(|s| s.id).collect();
        // terrain (22), road, sky, person, both cars; nothing ignored here.
        assert_eq!(ids, [7, 22, 23, 24000, 26000, 26001]);
        let car = &frame.segments[4];
        assert_eq!((car.area, car.bbox, car.iscrowd), (2, [1, 1, 2, 1], 0));
        let road = &frame.segments[0];
        assert_eq!((road.area, road.bbox), (3, [2, 0, 2, 3]));
    }

    #[test]
    fn ignored_labels_are_void_in_panoptic() {
        // An object whose label is ignored in evaluation (`dynamic`, id 5) is void (0) in
        // the panoptic image and has no segment.
        let classes = SemanticClasses::of(&[(ObjectKind::Road, "road")]).unwrap();
        let mut table = classes.clone();
        table.of_instance[1] = 5; // dynamic: ignored in evaluation
        let frame = semantic(&table, &test_image(&[&[0, 1]]));
        assert_eq!(frame.panoptic.get_pixel(1, 0).0, [0, 0, 0]);
        assert_eq!(frame.segments.len(), 1);
        assert_eq!(frame.segments[0].id, 23);
    }

    #[test]
    fn panoptic_documents_list_images_segments_and_evaluated_categories() {
        let classes = SemanticClasses::of(&[(ObjectKind::Car, "car")]).unwrap();
        let frame = semantic(&classes, &test_image(&[&[0, 1]]));
        let image = PanopticImage {
            id: json!(1),
            width: 2,
            height: 1,
            file_name: "rgb/000000.png".to_owned(),
            segments_file: "semantic/000000_panoptic.png".to_owned(),
            segments: frame.segments,
        };
        let document: serde_json::Value =
            serde_json::from_slice(&panoptic_json(&classes.labels, &[image])).unwrap();
        assert_eq!(document["images"][0]["file_name"], "rgb/000000.png");
        let segments = &document["annotations"][0]["segments_info"];
        assert_eq!(segments[1]["id"], 26000);
        assert_eq!(segments[1]["category_id"], 26);
        assert_eq!(segments[1]["bbox"], json!([1, 0, 1, 1]));
        let categories = document["categories"].as_array().unwrap();
        // 19 evaluated Cityscapes labels and the extra `text`.
        assert_eq!(categories.len(), 20);
        assert!(categories.iter().all(|c| c["id"] != 0 && c["id"] != 6));
        assert_eq!(categories[19]["name"], "text");
        assert_eq!(categories[19]["isthing"], 1);
    }
}
