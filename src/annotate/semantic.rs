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
use crate::model::PixelBox;

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
///
/// Everything a pixel gets depends on its instance id alone, so each image is one lookup
/// a pixel in a table per instance id, and the segments come from each shown id's pixel
/// count and box.
pub fn semantic(
    classes: &SemanticClasses,
    instance: &ImageBuffer<Luma<u32>, Vec<u32>>,
) -> SemanticFrame {
    let (width, height) = instance.dimensions();
    // Instance ids past the scene's are `unlabeled`, as `ids` is: all are counted there.
    let ids = classes.of_instance.len();
    let raw = instance.as_raw();
    let index = |id: u32| (id as usize).min(ids);
    let extents = extents(raw, width as usize, ids);
    let label_id: Vec<u8> = (0..=ids).map(|id| classes.label_of(id as u32).id).collect();
    // Each shown object's instanceIds value: numbered per label in instance-id order.
    let mut counts = [0u32; 256];
    let values: Vec<u16> = (0..=ids)
        .map(|id| {
            let label = &classes.labels[usize::from(label_id[id])];
            let k = &mut counts[usize::from(label.id)];
            let value = if extents[id].is_some() && label.has_instances && *k < 1000 {
                *k += 1;
                u32::from(label.id) * 1000 + *k - 1
            } else {
                u32::from(label.id)
            };
            value as u16
        })
        .collect();
    let colour: Vec<[u8; 3]> = label_id
        .iter()
        .map(|&l| classes.labels[usize::from(l)].color)
        .collect();
    let segment_rgb: Vec<[u8; 3]> = values
        .iter()
        .map(|&value| {
            let [lo, hi] = value.to_le_bytes();
            if value_label(classes, value).ignore_in_eval {
                [0, 0, 0]
            } else {
                [lo, hi, 0]
            }
        })
        .collect();
    let per_pixel = |table: &[[u8; 3]]| -> RgbImage {
        let mut bytes = Vec::with_capacity(raw.len() * 3);
        for &id in raw {
            bytes.extend_from_slice(&table[index(id)]);
        }
        RgbImage::from_raw(width, height, bytes).expect("three bytes a pixel")
    };
    let label_ids = raw.iter().map(|&id| label_id[index(id)]).collect();
    let instance_ids = raw.iter().map(|&id| values[index(id)]).collect();
    SemanticFrame {
        label_ids: GrayImage::from_raw(width, height, label_ids).expect("one label a pixel"),
        instance_ids: ImageBuffer::from_raw(width, height, instance_ids)
            .expect("one value a pixel"),
        color: per_pixel(&colour),
        panoptic: per_pixel(&segment_rgb),
        segments: segments(classes, &values, &extents),
    }
}

/// A shown instance id's (or value's) pixel count and box.
type Extent = (u64, PixelBox);

/// Per instance id `0..=ids` (ids past `ids` counted at `ids`): its pixels in `raw` (rows
/// `width` long) and their box, taken a run of equal ids at a time; `None` where the
/// frame does not show it.
fn extents(raw: &[u32], width: usize, ids: usize) -> Vec<Option<Extent>> {
    let mut extents = vec![None; ids + 1];
    for (y, row) in raw.chunks_exact(width.max(1)).enumerate() {
        let mut x = 0;
        while x < row.len() {
            let id = row[x];
            let end = row[x..]
                .iter()
                .position(|&v| v != id)
                .map_or(row.len(), |n| x + n);
            let (first, last, y) = (x as u32, end as u32 - 1, y as u32);
            let (area, b) =
                extents[(id as usize).min(ids)].get_or_insert((0, PixelBox::at(first, y)));
            *area += (end - x) as u64;
            b.include(first, y);
            b.include(last, y);
            x = end;
        }
    }
    extents
}

/// The label of an instanceIds value (`unlabeled` for one past the table, which
/// [`semantic`] never writes).
fn value_label(classes: &SemanticClasses, value: u16) -> &CityscapesLabel {
    let id = if value < 1000 { value } else { value / 1000 };
    classes
        .labels
        .get(usize::from(id))
        .unwrap_or(&classes.labels[0])
}

/// The panoptic segments, by value, as `createPanopticImgs` makes them from the
/// instanceIds image: the pixels of every instance id with one value (`values`) together,
/// the values of labels ignored in evaluation left out.
fn segments(classes: &SemanticClasses, values: &[u16], extents: &[Option<Extent>]) -> Vec<Segment> {
    let mut by_value: std::collections::BTreeMap<u16, Extent> = Default::default();
    let shown = values
        .iter()
        .zip(extents)
        .filter_map(|(&v, e)| Some((v, (*e)?)));
    for (value, (area, b)) in shown {
        let (total, joined) = by_value.entry(value).or_insert((0, b));
        *total += area;
        joined.include(b.x_min, b.y_min);
        joined.include(b.x_max, b.y_max);
    }
    by_value
        .into_iter()
        .filter(|(value, _)| !value_label(classes, *value).ignore_in_eval)
        .map(|(value, (area, b))| {
            let label = value_label(classes, value);
            Segment {
                id: u32::from(value),
                category_id: label.id,
                area,
                bbox: b.bbox(),
                iscrowd: u8::from(value < 1000 && label.has_instances),
            }
        })
        .collect()
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
    fn every_pixel_and_segment_is_what_its_instance_makes_it() {
        use rand::RngExt;
        // 1,200 cars (more than a label numbers), people, roads, a `dynamic` object, and
        // ids past the table, in runs of random length over a 197-pixel-wide frame.
        let mut homes = vec![(ObjectKind::Road, "road"); 3];
        homes.extend(vec![(ObjectKind::Car, "car"); 1200]);
        homes.extend(vec![(ObjectKind::Person, "person"); 40]);
        let mut classes = SemanticClasses::of(&homes).unwrap();
        classes.of_instance[1] = 5;
        let past = classes.of_instance.len() as u32;
        let mut rng = crate::rng::stream(3, "semantic-test", 0);
        let (width, height) = (197u32, 121u32);
        let mut raw = Vec::new();
        while raw.len() < (width * height) as usize {
            let id = rng.random_range(0..past + 3);
            raw.extend(std::iter::repeat_n(id, rng.random_range(1..9)));
        }
        raw.truncate((width * height) as usize);
        let frame = semantic(
            &classes,
            &ImageBuffer::from_raw(width, height, raw.clone()).unwrap(),
        );
        // Reference: numbered per label in instance-id order among the ids shown.
        let mut shown: Vec<u32> = raw.iter().map(|&id| id.min(past)).collect();
        shown.sort_unstable();
        shown.dedup();
        let mut counts = [0u32; 256];
        let mut value_of = std::collections::HashMap::new();
        for &id in &shown {
            let label = classes.label_of(id);
            let k = &mut counts[usize::from(label.id)];
            let numbered = label.has_instances && *k < 1000;
            let value =
                u32::from(label.id) * if numbered { 1000 } else { 1 } + *k * u32::from(numbered);
            *k += u32::from(numbered);
            value_of.insert(id, value as u16);
        }
        let mut expected: std::collections::BTreeMap<u16, (u64, [u32; 4])> = Default::default();
        for (i, &id) in raw.iter().enumerate() {
            let (x, y) = (i as u32 % width, i as u32 / width);
            let label = classes.label_of(id);
            let value = value_of[&id.min(past)];
            assert_eq!(frame.label_ids.get_pixel(x, y)[0], label.id);
            assert_eq!(frame.instance_ids.get_pixel(x, y)[0], value);
            assert_eq!(frame.color.get_pixel(x, y).0, label.color);
            let void = value_label(&classes, value).ignore_in_eval;
            let [lo, hi] = value.to_le_bytes();
            let rgb = if void { [0, 0, 0] } else { [lo, hi, 0] };
            assert_eq!(frame.panoptic.get_pixel(x, y).0, rgb);
            if !void {
                let e = expected.entry(value).or_insert((0, [x, y, x, y]));
                e.0 += 1;
                e.1 = [e.1[0].min(x), e.1[1].min(y), e.1[2].max(x), e.1[3].max(y)];
            }
        }
        assert!(counts[26] == 1000 && expected.len() > 1000);
        let got: Vec<(u16, u64, [u32; 4])> = frame
            .segments
            .iter()
            .map(|s| {
                (
                    s.id as u16,
                    s.area,
                    [
                        s.bbox[0],
                        s.bbox[1],
                        s.bbox[0] + s.bbox[2] - 1,
                        s.bbox[1] + s.bbox[3] - 1,
                    ],
                )
            })
            .collect();
        let want: Vec<(u16, u64, [u32; 4])> =
            expected.into_iter().map(|(v, (a, b))| (v, a, b)).collect();
        assert_eq!(got, want);
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
