//! Frames of one camera path → COCO JSON bytes that pycocotools loads.

use std::io::{self, Write};

use serde::{Deserialize, Serialize};
use serde_json::{Value, json};

use super::box3d::{Box3d, LevelCamera};
use super::coco_words::{WORD_CATEGORY, plate_window, word_annotation};
use super::frame_annotations::{FrameAnnotations, summarize};
use super::frame_input::{FrameInput, Thresholds};
use super::icdar::word_lines;
use super::keypoints::{KEYPOINT_NAMES, Keypoint, SKELETON, labelled};
use super::object_label::{Category, ObjectLabel};
use super::round;

/// COCO JSON bytes for frames held in memory: [`CocoWriter`] fed with each frame's
/// [`summarize`].
pub fn coco(
    categories: &[Category],
    labels: &[ObjectLabel],
    frames: &[FrameInput],
    thresholds: &Thresholds,
) -> Vec<u8> {
    let mut writer = CocoWriter::new(categories);
    for frame in frames {
        writer.push(&summarize(labels, frame, thresholds));
    }
    writer.finish()
}

/// Builds one camera path's COCO JSON (pycocotools loads it) frame by frame, holding only
/// the text of its lines.
///
/// - `images`: `id` (frame index + 1), `file_name`, `width`, `height`, and the extra keys
///   `intrinsics` `{fx, fy, cx, cy}` (pixels) and `pose` `{eye, target, up}` (metres, x
///   east, y up, z south; `up` the direction of the image's top, +y for a level camera),
///   with the path's drawn `heading`, `pitch`, `roll` (degrees) and `height` (metres)
///   when it draws them, and, when the frame has a depth image, `depth`
///   `{file_name, format, scale}` (metres per stored unit), and `conditions` when the
///   frames stage records the weather and sensor values the frame drew.
/// - ignore regions: a listed object that shows pixels but misses the thresholds is
///   written with `iscrowd` 1 and its RLE mask, so pycocotools' COCOeval (and loaders
///   that follow it) neither rewards nor punishes a detection of it.
/// - `categories`: `id`, `name`, in the order given; a category whose annotations carry
///   keypoints also `keypoints` (COCO's 17 names) and `skeleton` (its 19 limbs, 1-based).
/// - `annotations`, numbered from 1 over all frames in frame then instance-id order, for
///   every labelled object whose category is listed: `id`,
///   `image_id`, `category_id`, `bbox` `[x, y, w, h]` = tight box of the visible pixels
///   (inside the image by construction), `area` = visible pixel count, `iscrowd` 0 when
///   it passes the thresholds, else 1 (an ignore region), `segmentation` = compressed RLE
///   `{"size": [h, w], "counts": …}` exactly as pycocotools' `maskUtils.encode` gives it;
///   then the extra keys `cityspec_instance` (the value in the instance image), `name`,
///   `cityspec_ignored` on an ignore region (why: `pixels`, `fraction` or `contrast`),
///   `full_bbox` (the box of the pixels the object would cover with nothing in front of
///   it and no image edge to cut it: it may reach past the image; `null` when unknown),
///   `visible_fraction` (visible ÷ those pixels, so occlusion and truncation both lower
///   it; or `null`), for a person or rider when the frame has its keypoints
///   (`keypoints = true`) `num_keypoints` and `keypoints` `[x, y, v] × 17` (see
///   [`super::project_keypoints`]; all 0 on an ignore region) and, for text objects,
///   `text` (the plate's whole text; its words are
///   `word` annotations, below) and `attributes` `{text_font, text_style, text_light}`
///   (style `shop`, `banner`, `painted` or `street`; light `backlit`, `lamp_lit` or
///   `unlit`: how it is lit after dusk); for a sign
///   seen from the front `attributes` `{"sign_type": "stop"}`. A sign seen from behind is not its
///   category: it takes the category `<label>_back` when that is listed, else it is left out.
/// - `word` annotations (when the categories hold `word`): right after each
///   annotated text object's, one per ICDAR line it has in the frame ([`super::icdar`]),
///   in reading order: `category_id` the `word` category, `segmentation` an RLE mask of
///   the pixels of the word's projected quad (cut to the plate's visible box) that the
///   plate shows, occluders cut out (all the quad's pixels when the plate shows none of
///   them), `bbox` that mask's tight box and `area` its pixel count, `iscrowd` 1 exactly where ICDAR writes `###`, with the reason in
///   `cityspec_ignored` (the plate's, or `hidden`, `small`, `empty`, `unsplit`), then
///   `cityspec_instance` and `name` of the plate (so `(image_id, cityspec_instance)` finds
///   the plate's annotation), `word_index` (the word's place in the plate's text, split at
///   spaces; `null` for a plate without quads, whose one line is its box and whole text),
///   `text` (the word, also when `iscrowd` is 1) and `visible_fraction`.
///
/// Keys are written in that order, one image, category or annotation per line. Intrinsics
/// and the visible fraction are rounded to 6 decimals, poses and full boxes to 3; a
/// non-finite number becomes `null`.
pub struct CocoWriter {
    categories: Vec<Category>,
    frames: Vec<CocoLines>,
}

/// One frame's part of a COCO document: its image line, and its annotation lines without
/// their `id` (which counts annotations over all earlier frames, so a frame rendered on
/// its own cannot know it; [`write_coco`] puts it in front).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct CocoLines {
    pub image: String,
    /// Each a JSON object's text, `{"image_id":…}`, the `id` key left out.
    pub annotations: Vec<String>,
}

impl CocoLines {
    /// Frame `frame`'s lines; its image id is `image_id` (frame index + 1), `conditions`
    /// is recorded as the image's `conditions` after its `pose` unless it is null.
    pub fn of(
        categories: &[Category],
        frame: &FrameAnnotations,
        conditions: &Value,
        image_id: u64,
    ) -> CocoLines {
        let image = image_entry(frame, conditions, image_id);
        let word_category = categories
            .iter()
            .find(|c| c.name == WORD_CATEGORY)
            .map(|c| c.id);
        let mut annotations = Vec::new();
        for object in &frame.objects {
            let Some(category) = object.category else {
                continue;
            };
            if !categories.iter().any(|c| c.id == category) {
                continue;
            }
            let v = &object.visible;
            let mut annotation = json!({
                "image_id": image_id,
                "category_id": category,
                "bbox": v.bounds.bbox(),
                "area": v.pixels,
                "iscrowd": u8::from(!object.passes()),
                "segmentation": {"size": v.rle.size, "counts": v.rle.to_compressed()},
                "cityspec_instance": v.id,
                "name": object.label.name,
                "full_bbox": object.full_box.map(|b| b.map(|x| round(x, 1e3))),
                "visible_fraction": object.fraction.and_then(|f| round(f, 1e6)),
            });
            if let Value::Object(map) = &mut annotation {
                if let Some(why) = object.ignored {
                    map.insert("cityspec_ignored".into(), Value::from(why.name()));
                }
                if let Some(keypoints) = frame.keypoints.get(&v.id) {
                    let (count, keypoints) = keypoints_json(keypoints, object.passes());
                    map.insert("num_keypoints".into(), count);
                    map.insert("keypoints".into(), keypoints);
                }
                if let Some(text) = &object.label.text {
                    map.insert("text".into(), Value::String(text.clone()));
                }
                let mut attributes = object.label.attributes.clone();
                if let Some(kind) = object.subclass {
                    attributes.insert("sign_type".into(), kind.to_string());
                }
                let box3d = object.label.box3d.as_ref();
                if !attributes.is_empty() || box3d.is_some() {
                    let mut attributes = json!(attributes);
                    if let Some(b) = box3d {
                        attributes["box3d"] = box3d_json(frame, b);
                    }
                    map.insert("attributes".into(), attributes);
                }
            }
            annotations.push(annotation.to_string());
            if let Some(word) = word_category {
                let lines = word_lines(frame, object);
                if lines.is_empty() {
                    continue;
                }
                // The plate's pixels, decoded once for all its words.
                let shown = plate_window(object);
                for line in lines {
                    annotations.extend(word_annotation(&line, object, &shown, word, image_id));
                }
            }
        }
        CocoLines {
            image: image.to_string(),
            annotations,
        }
    }
}

/// Frame `frame`'s COCO image entry: file, size, intrinsics, pose, depth file and drawn
/// `conditions` (unless null).
fn image_entry(frame: &FrameAnnotations, conditions: &Value, image_id: u64) -> Value {
    let [fx, fy, cx, cy] = frame.intrinsics.map(|v| round(v, 1e6));
    let mut pose = json!({
        "eye": frame.pose.eye.map(|v| round(v, 1e3)),
        "target": frame.pose.target.map(|v| round(v, 1e3)),
        "up": frame.pose.up.map(|v| round(v, 1e6)),
    });
    if let Some(a) = frame.pose.angles {
        for (key, value) in [
            ("heading", a.heading),
            ("pitch", a.pitch),
            ("roll", a.roll),
            ("height", a.height),
        ] {
            pose[key] = json!(round(value, 1e3));
        }
    }
    let mut image = json!({
        "id": image_id,
        "file_name": frame.file_name,
        "width": frame.width,
        "height": frame.height,
        "intrinsics": {"fx": fx, "fy": fy, "cx": cx, "cy": cy},
        "pose": pose,
    });
    if let (Some(t), Value::Object(map)) = (frame.pose.time, &mut image) {
        map.insert("time".into(), json!(round(t, 1e6)));
    }
    if let (Some(depth), Value::Object(map)) = (&frame.depth, &mut image) {
        map.insert(
            "depth".into(),
            json!({"file_name": depth.file_name, "format": depth.format, "scale": depth.scale}),
        );
    }
    if let (false, Value::Object(map)) = (conditions.is_null(), &mut image) {
        map.insert("conditions".into(), conditions.clone());
    }
    image
}

impl CocoWriter {
    pub fn new(categories: &[Category]) -> CocoWriter {
        CocoWriter {
            categories: categories.to_vec(),
            frames: Vec::new(),
        }
    }

    /// Appends the next frame (image ids follow the order of the calls).
    pub fn push(&mut self, frame: &FrameAnnotations) {
        self.push_with_conditions(frame, &Value::Null);
    }

    /// [`CocoWriter::push`], recording `conditions` (the weather and sensor values the
    /// frame drew) as the image entry's `conditions` after its `pose`, unless it is null.
    pub fn push_with_conditions(&mut self, frame: &FrameAnnotations, conditions: &Value) {
        let image_id = self.frames.len() as u64 + 1;
        self.frames
            .push(CocoLines::of(&self.categories, frame, conditions, image_id));
    }

    /// The whole document.
    pub fn finish(self) -> Vec<u8> {
        let mut out = Vec::new();
        write_coco(&mut out, &self.categories, |pass| {
            self.frames.iter().try_for_each(pass)
        })
        .expect("writing to memory does not fail");
        out
    }
}

/// Writes a COCO document to `out` from per-frame lines that `frames` hands, in frame
/// order, to the function it is given. `frames` is called twice (images come before the
/// categories, annotations after them), so the caller can read its frames from disk each
/// time and memory does not grow with their number.
pub fn write_coco<W: Write>(
    out: &mut W,
    categories: &[Category],
    mut frames: impl FnMut(&mut dyn FnMut(&CocoLines) -> io::Result<()>) -> io::Result<()>,
) -> io::Result<()> {
    write!(
        out,
        "{{\"info\":{},\n\"licenses\":[]",
        json!({"description": "cityspec annotations", "version": super::VERSION})
    )?;
    out.write_all(b",\n\"images\":[")?;
    let mut first = true;
    frames(&mut |lines| item(out, &mut first, &lines.image))?;
    out.write_all(b"],\n\"categories\":[")?;
    let mut first = true;
    for c in categories {
        let mut category = json!({"id": c.id, "name": c.name});
        if c.keypoints {
            category["keypoints"] = json!(KEYPOINT_NAMES);
            category["skeleton"] = json!(SKELETON);
        }
        item(out, &mut first, &category.to_string())?;
    }
    out.write_all(b"],\n\"annotations\":[")?;
    let mut first = true;
    let mut id = 0u64;
    frames(&mut |lines| {
        for body in &lines.annotations {
            id += 1;
            // `{"image_id":…}` → `{"id":N,"image_id":…}`.
            let rest = body.strip_prefix('{').unwrap_or(body);
            item(out, &mut first, &format!("{{\"id\":{id},{rest}"))?;
        }
        Ok(())
    })?;
    out.write_all(b"]}\n")
}

/// Writes one item of a JSON list: a newline, after a comma unless it is the first.
fn item<W: Write>(out: &mut W, first: &mut bool, text: &str) -> io::Result<()> {
    let sep: &[u8] = if std::mem::take(first) { b"\n" } else { b",\n" };
    out.write_all(sep)?;
    out.write_all(text.as_bytes())
}

/// COCO `num_keypoints` and `keypoints` (`x, y` to 2 decimals, `v` an integer, `[0, 0, 0]`
/// where `v` is 0) of an object that `passes`; an ignore region is no person to find, so
/// none of its keypoints is labelled.
fn keypoints_json(keypoints: &[Keypoint; 17], passes: bool) -> (Value, Value) {
    let keypoints = if passes { keypoints } else { &[[0.0; 3]; 17] };
    let flat: Vec<Value> = keypoints
        .iter()
        .flat_map(|&[x, y, v]| {
            if v > 0.0 {
                [json!(round(x, 1e2)), json!(round(y, 1e2)), json!(v as u8)]
            } else {
                [json!(0), json!(0), json!(0)]
            }
        })
        .collect();
    (json!(labelled(keypoints)), Value::Array(flat))
}

/// A 3D box as COCO `attributes.box3d`: in world metres (`center_world`, `yaw_world`,
/// radians about +y) and in the frame's KITTI camera (`center_cam`, the volume's centre,
/// and `rotation_y`; see [`super::kitti`]), with `size` `[length, width, height]`.
fn box3d_json(frame: &FrameAnnotations, b: &Box3d) -> Value {
    let r = |v: f64| round(v, 1e4);
    let mut out = json!({
        "center_world": b.centre.map(r),
        "size": b.size.map(r),
        "yaw_world": r(b.yaw),
    });
    if let Some(camera) = LevelCamera::of(&frame.pose) {
        let (_, rotation_y) = camera.kitti_pose(b);
        out["center_cam"] = json!(camera.point(b.centre).map(r));
        out["rotation_y"] = json!(r(rotation_y));
    }
    out
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;
    use crate::annotate::{Rle, SignLabel, test_image};
    use crate::model::CameraPose;

    fn categories() -> Vec<Category> {
        ["building", "sign", "text"]
            .iter()
            .zip(1..)
            .map(|(name, id)| Category {
                id,
                name: name.to_string(),
                keypoints: false,
            })
            .collect()
    }

    fn labels() -> Vec<ObjectLabel> {
        let label = |name: &str, category, text: Option<&str>| ObjectLabel {
            name: name.into(),
            box3d: None,
            keypoints: None,
            category,
            text: text.map(String::from),
            attributes: Default::default(),
            sign: None,
        };
        vec![
            label("building_0", Some(1), None),
            label("sign_0", Some(2), None),
            label("sign_1", Some(2), None),
            label("ground", None, None),
            label("text_0", Some(3), Some("OPEN")),
        ]
    }

    /// 8 × 5: building 1 partly behind sign 2 (2 px, too few) and text 5 (no projected
    /// count known); sign 3 shows 4 of its 40 px; ground 4 along the bottom.
    fn frame_image() -> image::ImageBuffer<image::Luma<u32>, Vec<u32>> {
        test_image(&[
            &[1, 1, 1, 1, 1, 0, 3, 3],
            &[1, 2, 2, 1, 1, 0, 3, 3],
            &[1, 1, 5, 5, 1, 0, 0, 0],
            &[1, 1, 5, 5, 1, 0, 0, 0],
            &[4, 4, 4, 4, 4, 4, 4, 4],
        ])
    }

    fn frame<'a>(
        name: &str,
        img: &'a image::ImageBuffer<image::Luma<u32>, Vec<u32>>,
    ) -> FrameInput<'a> {
        FrameInput {
            file_name: name.into(),
            instance: img,
            rgb: None,
            intrinsics: [400.0, 400.0, 4.0, 2.5],
            pose: CameraPose::level([1.0, 1.6, -0.0], [11.0, 0.6, 0.1234567]),
            full: BTreeMap::from([
                (1, ([0.0, 0.0, 5.0, 4.0], 24)),
                (2, ([1.0, 1.0, 2.0, 1.0], 2)),
                (3, ([6.0, -3.5, 8.0, 5.0], 40)),
            ]),
            quads: BTreeMap::new(),
            depth: None,
        }
    }

    const THRESHOLDS: Thresholds = Thresholds {
        min_pixels: 3,
        min_fraction: 0.25,
    };

    #[test]
    fn people_carry_their_keypoints_and_an_ignore_region_carries_none() {
        // Person 1 fills the left of a 6 × 4 image, person 2 shows 2 px (an ignore
        // region), a building 3 the rest; everything 5 m away.
        let img = test_image(&[
            &[1, 1, 1, 3, 3, 3],
            &[1, 1, 1, 3, 3, 3],
            &[1, 1, 1, 3, 2, 2],
            &[1, 1, 1, 3, 3, 3],
        ]);
        let depth = image::ImageBuffer::from_pixel(6, 4, image::Luma([5.0f32]));
        let person = |name: &str, keypoints| ObjectLabel {
            name: name.into(),
            box3d: None,
            keypoints: Some(keypoints),
            category: Some(1),
            text: None,
            attributes: Default::default(),
            sign: None,
        };
        // Looking down −z from the origin, fx = fy = 10, centre (3, 2): 5 cm behind the
        // surface at (2, 1.5), visible; 1 m behind it, hidden; far right, outside.
        let mut world = [[-0.505, 0.2525, -5.05]; 17];
        world[3] = [-0.505, 0.2525, -6.0];
        world[16] = [10.0, 0.0, -5.0];
        let labels = vec![
            person("person_0", world),
            person("person_1", [[1.5, 0.0, -5.0]; 17]),
            ObjectLabel {
                keypoints: None,
                category: Some(2),
                name: "building_0".into(),
                ..person("", world)
            },
        ];
        let mut frame = frame("f.png", &img);
        frame.pose = CameraPose::level([0.0; 3], [0.0, 0.0, -10.0]);
        frame.intrinsics = [10.0, 10.0, 3.0, 2.0];
        frame.full.clear();
        frame.depth = Some(&depth);
        let categories = ["person", "building"].map(|name| Category {
            id: if name == "person" { 1 } else { 2 },
            name: name.into(),
            keypoints: name == "person",
        });
        let doc: Value =
            serde_json::from_slice(&coco(&categories, &labels, &[frame], &THRESHOLDS)).unwrap();
        let person = &doc["categories"][0];
        assert_eq!(person["keypoints"][0], "nose");
        assert_eq!(person["keypoints"][16], "right_ankle");
        assert_eq!(person["skeleton"].as_array().unwrap().len(), 19);
        assert_eq!(person["skeleton"][0], json!([16, 14]));
        assert_eq!(doc["categories"][1], json!({"id": 2, "name": "building"}));
        let annotations = doc["annotations"].as_array().unwrap();
        let [seen, small, building] = [0, 1, 2].map(|i| &annotations[i]);
        let k = seen["keypoints"].as_array().unwrap();
        assert_eq!(k.len(), 51);
        assert_eq!(k[..3], [json!(2.0), json!(1.5), json!(2)]);
        assert_eq!(k[9..12], [json!(2.16), json!(1.58), json!(1)]);
        assert_eq!(k[48..], [json!(0), json!(0), json!(0)]);
        assert_eq!(seen["num_keypoints"], 16);
        assert_eq!(small["iscrowd"], 1);
        assert_eq!(small["num_keypoints"], 0);
        assert!(
            small["keypoints"]
                .as_array()
                .unwrap()
                .iter()
                .all(|v| v == 0)
        );
        assert!(building.get("keypoints").is_none() && building.get("num_keypoints").is_none());
    }

    #[test]
    fn annotates_visible_pixels_and_drops_small_or_hidden_objects() {
        let (a, b) = (
            frame_image(),
            test_image(&[&[0, 0, 0], &[0, 3, 3], &[0, 3, 0]]),
        );
        let mut f1 = frame("f1.png", &b);
        f1.full.clear();
        let frames = [frame("f0.png", &a), f1];
        let bytes = coco(&categories(), &labels(), &frames, &THRESHOLDS);
        let doc: Value = serde_json::from_slice(&bytes).unwrap();

        let images = doc["images"].as_array().unwrap();
        assert_eq!(images.len(), 2);
        assert_eq!(
            images[0].to_string(),
            r#"{"id":1,"file_name":"f0.png","width":8,"height":5,"intrinsics":{"fx":400.0,"fy":400.0,"cx":4.0,"cy":2.5},"pose":{"eye":[1.0,1.6,0.0],"target":[11.0,0.6,0.123],"up":[0.0,1.0,0.0]}}"#
        );
        assert_eq!(
            doc["categories"][2].to_string(),
            r#"{"id":3,"name":"text"}"#
        );

        let anns = doc["annotations"].as_array().unwrap();
        let summary: Vec<(u64, u64, u64, String, u64)> = anns
            .iter()
            .map(|a| {
                let n = |k: &str| a[k].as_u64().unwrap();
                (
                    n("id"),
                    n("image_id"),
                    n("cityspec_instance"),
                    a["bbox"].to_string(),
                    n("iscrowd"),
                )
            })
            .collect();
        // Sign 2 (2 px) and sign 3 in frame 0 (10 %) miss the thresholds: ignore regions;
        // the ground has no category; sign 3 in frame 1 has no projected count, so only
        // its pixels count.
        assert_eq!(
            summary,
            [
                (1, 1, 1, "[0,0,5,4]".to_string(), 0),
                (2, 1, 2, "[1,1,2,1]".to_string(), 1),
                (3, 1, 3, "[6,0,2,2]".to_string(), 1),
                (4, 1, 5, "[2,2,2,2]".to_string(), 0),
                (5, 2, 3, "[1,1,2,2]".to_string(), 0),
            ]
        );
        assert_eq!(anns[1]["area"], 2);
        assert_eq!(anns[2]["visible_fraction"], 0.1);
        let building = &anns[0];
        assert_eq!(building["area"], 14);
        assert_eq!(building["iscrowd"], 0);
        assert_eq!(building["category_id"], 1);
        assert_eq!(building["name"], "building_0");
        assert_eq!(building["full_bbox"].to_string(), "[0.0,0.0,5.0,4.0]");
        // 14 of 24 projected pixels, to 6 decimals.
        assert_eq!(building["visible_fraction"], 0.583333);
        assert!(building.get("text").is_none());
        let text = &anns[3];
        assert_eq!(text["text"], "OPEN");
        assert_eq!(text["full_bbox"], Value::Null);
        assert_eq!(text["visible_fraction"], Value::Null);

        // The segmentation decodes to exactly the visible pixels.
        for ann in anns {
            let img = if ann["image_id"] == 1 { &a } else { &b };
            let seg = &ann["segmentation"];
            let [h, w] = [0, 1].map(|i| seg["size"][i].as_u64().unwrap() as u32);
            assert_eq!((w, h), img.dimensions());
            let rle = Rle::from_compressed(seg["counts"].as_str().unwrap(), h, w).unwrap();
            let id = ann["cityspec_instance"].as_u64().unwrap() as u32;
            let mask: Vec<bool> = img.pixels().map(|p| p.0[0] == id).collect();
            assert_eq!(rle.to_row_major(), mask);
            assert_eq!(rle.area(), ann["area"].as_u64().unwrap());
        }
    }

    #[test]
    fn output_is_stable_and_one_entry_per_line() {
        let a = frame_image();
        let frames = [frame("f0.png", &a)];
        let first = coco(&categories(), &labels(), &frames, &THRESHOLDS);
        assert_eq!(first, coco(&categories(), &labels(), &frames, &THRESHOLDS));
        let text = String::from_utf8(first).unwrap();
        // info, licenses, images + 1, categories + 3, annotations + 4.
        assert_eq!(text.lines().count(), 2 + 2 + 4 + 5);
        assert!(
            text.lines()
                .nth(5)
                .unwrap()
                .starts_with(r#"{"id":1,"name":"building"}"#)
        );
    }

    #[test]
    fn a_sign_is_its_category_only_from_the_front() {
        // A stop sign facing east (+x), seen from the east, then from the west with and
        // without a back category listed.
        let img = test_image(&[&[1, 1], &[1, 1]]);
        let sign = |back_category| ObjectLabel {
            name: "sign_0".into(),
            box3d: None,
            keypoints: None,
            category: Some(2),
            text: None,
            attributes: Default::default(),
            sign: Some(SignLabel {
                kind: "stop".into(),
                centre: [0.0, 2.0, 0.0],
                normal: [1.0, 0.0, 0.0],
                back_category,
            }),
        };
        let seen_from = |x: f64| {
            let mut f = frame("f.png", &img);
            f.full.clear();
            f.pose.eye = [x, 1.6, 0.3];
            f
        };
        let mut with_back = categories();
        with_back.push(Category {
            id: 4,
            name: "sign_back".into(),
            keypoints: false,
        });
        let annotate = |label: ObjectLabel, x: f64| {
            let bytes = coco(&with_back, &[label], &[seen_from(x)], &THRESHOLDS);
            let doc: Value = serde_json::from_slice(&bytes).unwrap();
            doc["annotations"].as_array().unwrap().clone()
        };
        let front = annotate(sign(Some(4)), 5.0);
        assert_eq!(front.len(), 1);
        assert_eq!(front[0]["category_id"], 2);
        assert_eq!(
            front[0]["attributes"].to_string(),
            r#"{"sign_type":"stop"}"#
        );
        let back = annotate(sign(Some(4)), -5.0);
        assert_eq!(back.len(), 1);
        assert_eq!(back[0]["category_id"], 4);
        assert!(back[0].get("attributes").is_none());
        assert!(annotate(sign(None), -5.0).is_empty());
    }

    #[test]
    fn no_frames_still_give_a_loadable_document() {
        let bytes = coco(&categories(), &labels(), &[], &THRESHOLDS);
        let doc: Value = serde_json::from_slice(&bytes).unwrap();
        assert_eq!(doc["images"], json!([]));
        assert_eq!(doc["annotations"], json!([]));
        assert_eq!(doc["categories"].as_array().unwrap().len(), 3);
    }

    #[test]
    fn unlisted_categories_and_unlabelled_ids_are_not_annotated() {
        let img = test_image(&[&[1, 1, 9, 9]]);
        let frames = [frame("f.png", &img)];
        let only_signs = [Category {
            id: 2,
            name: "sign".into(),
            keypoints: false,
        }];
        let doc: Value =
            serde_json::from_slice(&coco(&only_signs, &labels(), &frames, &THRESHOLDS)).unwrap();
        assert_eq!(doc["annotations"], json!([]));
    }
}
