//! One ICDAR line of a text object in a frame → its COCO `word` annotation: the pixels of
//! the word's quad (cut to the plate's visible box) that the plate shows as an RLE
//! segmentation, its box and area, its
//! transcription, `iscrowd` 1 exactly where ICDAR writes `###`, and the plate it belongs
//! to (fields in [`super::CocoWriter`]).

use serde_json::{Value, json};

use super::icdar::WordLine;
use super::rle::{MaskWindow, Rle};
use super::round;
use super::shown_object::ShownObject;

/// The category of the words of text objects: appended after the others by
/// [`super::path_labels`] when a listed class carries text (or placed where `classes` lists
/// it).
pub const WORD_CATEGORY: &str = "word";

/// The `word` annotation of one ICDAR line of the text `object` (category `category`;
/// `shown`: the object's visible mask over its box and one pixel beyond, from
/// [`plate_window`]), `None` when its quad has nothing inside
/// the object's visible box.
pub(super) fn word_annotation(
    line: &WordLine,
    object: &ShownObject,
    shown: &MaskWindow,
    category: u32,
    image_id: u64,
) -> Option<String> {
    let b = object.visible.bounds;
    let bounds = [b.x_min, b.y_min, b.x_max + 1, b.y_max + 1].map(f64::from);
    let polygon = match line.quad {
        Some(quad) => clip_to_box(&quad, bounds),
        None => vec![
            [bounds[0], bounds[1]],
            [bounds[2], bounds[1]],
            [bounds[2], bounds[3]],
            [bounds[0], bounds[3]],
        ],
    };
    // Corners to 2 decimals, as ICDAR writes them.
    let polygon: Vec<[f64; 2]> = polygon
        .iter()
        .map(|p| Some([round(p[0], 1e2)?, round(p[1], 1e2)?]))
        .collect::<Option<_>>()?;
    let area = polygon_area(&polygon);
    if polygon.len() < 3 || area.is_nan() || area <= 0.0 {
        return None;
    }
    // An RLE mask like every other annotation's (a column of one type for readers such as
    // Hugging Face datasets): the pixels of the polygon its plate shows.
    let (rle, [x0, y0, x1, y1], pixels) = word_mask(&polygon, shown, object.visible.rle.size)?;
    let mut annotation = json!({
        "image_id": image_id,
        "category_id": category,
        "bbox": [x0, y0, x1 - x0, y1 - y0],
        "area": pixels,
        "iscrowd": u8::from(line.unreadable.is_some()),
        "segmentation": {"size": rle.size, "counts": rle.to_compressed()},
        "cityspec_instance": object.visible.id,
        "name": object.label.name,
        "word_index": line.index,
        "text": line.word,
        "visible_fraction": line.visible.and_then(|f| round(f, 1e6)),
    });
    if let (Some(why), Value::Object(map)) = (line.unreadable, &mut annotation) {
        map.insert("cityspec_ignored".into(), Value::from(why));
    }
    Some(annotation.to_string())
}

/// The text object's visible mask, decoded over its box and one pixel beyond on the right
/// and below (where a sliver word's first corner may fall): all its words need.
pub(super) fn plate_window(object: &ShownObject) -> MaskWindow {
    let b = object.visible.bounds;
    let [h, w] = object.visible.rle.size;
    let bounds = [b.x_min, b.y_min, (b.x_max + 2).min(w), (b.y_max + 2).min(h)];
    object.visible.rle.window(bounds)
}

/// The part of the convex polygon `quad` inside the box `[x0, y0, x1, y1]`
/// (Sutherland–Hodgman, one box edge at a time).
fn clip_to_box(quad: &[[f64; 2]; 4], [x0, y0, x1, y1]: [f64; 4]) -> Vec<[f64; 2]> {
    // Each edge: the coordinate it bounds, its value, and whether points keep below it.
    let edges = [(0, x0, false), (0, x1, true), (1, y0, false), (1, y1, true)];
    let mut points = quad.to_vec();
    for (k, limit, below) in edges {
        let keep = |p: &[f64; 2]| if below { p[k] <= limit } else { p[k] >= limit };
        let mut out = Vec::with_capacity(points.len() + 1);
        for (i, p) in points.iter().enumerate() {
            let q = points[(i + 1) % points.len()];
            if keep(p) {
                out.push(*p);
            }
            if keep(p) != keep(&q) {
                let t = (limit - p[k]) / (q[k] - p[k]);
                let mut cut = [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])];
                cut[k] = limit;
                out.push(cut);
            }
        }
        points = out;
        if points.is_empty() {
            break;
        }
    }
    points
}

/// The pixels (centres inside) of the convex `polygon` that `shown` (its plate's mask,
/// decoded over the plate's box and one pixel beyond) holds, or all of them
/// when the plate shows none (a hidden word stays a region, marked crowd by ICDAR's rules),
/// or the one pixel under its first corner when it covers no pixel centre (a sliver): the
/// mask in a frame of `size` = `[height, width]`, its tight box `[x0, y0, x1, y1]`
/// (end-exclusive) and its pixel count. `None` for an empty window.
fn word_mask(
    polygon: &[[f64; 2]],
    shown: &MaskWindow,
    size: [u32; 2],
) -> Option<(Rle, [u32; 4], u64)> {
    let [h, w] = size;
    let [wx0, wy0, wx1, wy1] = shown.bounds;
    let lo = |k: usize, min: u32, max: u32| {
        let v = polygon.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
        (v.floor().max(0.0) as u32).clamp(min, max)
    };
    let hi = |k: usize, min: u32, max: u32| {
        let v = polygon
            .iter()
            .map(|p| p[k])
            .fold(f64::NEG_INFINITY, f64::max);
        (v.ceil().max(0.0) as u32).clamp(min, max)
    };
    let (bx0, by0) = (lo(0, wx0, wx1), lo(1, wy0, wy1));
    let (bx1, by1) = (hi(0, wx0, wx1), hi(1, wy0, wy1));
    let mut quad = MaskWindow {
        bounds: shown.bounds,
        pixels: vec![false; shown.pixels.len()],
    };
    let mut mask = quad.clone();
    let (mut any_quad, mut any_shown) = (false, false);
    let row = (wx1 - wx0) as usize;
    for y in by0..by1 {
        for x in bx0..bx1 {
            if inside(polygon, [f64::from(x) + 0.5, f64::from(y) + 0.5]) {
                let i = (y - wy0) as usize * row + (x - wx0) as usize;
                quad.pixels[i] = true;
                any_quad = true;
                if shown.pixels[i] {
                    mask.pixels[i] = true;
                    any_shown = true;
                }
            }
        }
    }
    if !any_quad {
        let x = (polygon[0][0].max(0.0) as u32).clamp(wx0, wx1.checked_sub(1)?);
        let y = (polygon[0][1].max(0.0) as u32).clamp(wy0, wy1.checked_sub(1)?);
        let one = MaskWindow {
            bounds: [x, y, x + 1, y + 1],
            pixels: vec![true],
        };
        return Some((Rle::from_window(&one, h, w), one.bounds, 1));
    }
    let mask = if any_shown { mask } else { quad };
    let (mut b, mut pixels) = ([u32::MAX, u32::MAX, 0, 0], 0u64);
    for y in by0..by1 {
        for x in bx0..bx1 {
            if mask.get(x, y) {
                b = [b[0].min(x), b[1].min(y), b[2].max(x + 1), b[3].max(y + 1)];
                pixels += 1;
            }
        }
    }
    Some((Rle::from_window(&mask, h, w), b, pixels))
}

/// Whether the point `c` lies inside the convex `polygon` or on its edge, whatever its
/// winding.
fn inside(polygon: &[[f64; 2]], c: [f64; 2]) -> bool {
    let (mut any_neg, mut any_pos) = (false, false);
    for (i, a) in polygon.iter().enumerate() {
        let b = polygon[(i + 1) % polygon.len()];
        let side = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        any_neg |= side < 0.0;
        any_pos |= side > 0.0;
    }
    !(any_neg && any_pos)
}

/// Area of a simple polygon (shoelace), whatever its winding.
fn polygon_area(points: &[[f64; 2]]) -> f64 {
    let n = points.len();
    let twice: f64 = (0..n)
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum();
    twice.abs() / 2.0
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;
    use crate::annotate::{Category, FrameInput, Thresholds, coco, icdar, summarize, word_fixture};
    use crate::model::CameraPose;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> [[f64; 2]; 4] {
        [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
    }

    #[test]
    fn a_quad_is_cut_to_the_box_and_keeps_its_area_inside() {
        let half = clip_to_box(&rect(-2.0, 0.0, 2.0, 2.0), [0.0, 0.0, 10.0, 10.0]);
        assert_eq!(polygon_area(&half), 4.0);
        assert!(half.iter().all(|p| p[0] >= 0.0));
        // A slanted quad wholly inside is unchanged; one wholly outside is gone.
        let slanted = [[1.0, 1.0], [5.0, 2.0], [5.0, 4.0], [1.0, 3.0]];
        assert_eq!(
            clip_to_box(&slanted, [0.0, 0.0, 10.0, 10.0]),
            slanted.to_vec()
        );
        assert!(clip_to_box(&rect(20.0, 0.0, 30.0, 2.0), [0.0, 0.0, 10.0, 10.0]).is_empty());
    }

    /// `word_fixture`'s plates; categories text 1, word 2.
    #[test]
    fn one_word_annotation_per_icdar_line_inside_its_plate_crowd_where_icdar_does_not_care() {
        let (img, labels, quads) = word_fixture();
        let frame = FrameInput {
            file_name: "f.png".into(),
            instance: &img,
            rgb: None,
            intrinsics: [1.0, 1.0, 10.0, 3.0],
            pose: CameraPose::level([0.0; 3], [0.0, 0.0, 1.0]),
            full: BTreeMap::new(),
            quads,
            depth: None,
        };
        let thresholds = Thresholds {
            min_pixels: 2,
            min_fraction: 0.0,
        };
        let categories = ["text", WORD_CATEGORY].map(|name| Category {
            id: if name == "text" { 1 } else { 2 },
            name: name.into(),
            keypoints: false,
        });
        let doc: Value = serde_json::from_slice(&coco(
            &categories,
            &labels,
            std::slice::from_ref(&frame),
            &thresholds,
        ))
        .unwrap();
        let lines = icdar(&summarize(&labels, &frame, &thresholds));
        let annotations = doc["annotations"].as_array().unwrap();
        let plates: Vec<&Value> = annotations
            .iter()
            .filter(|a| a["category_id"] == 1)
            .collect();
        let words: Vec<&Value> = annotations
            .iter()
            .filter(|a| a["category_id"] == 2)
            .collect();
        assert_eq!(plates.len(), 5);
        assert_eq!(words.len(), lines.lines().count());
        for (word, line) in words.iter().zip(lines.lines()) {
            let transcription = line.splitn(9, ',').nth(8).unwrap();
            if transcription == "###" {
                assert_eq!(word["iscrowd"], 1, "{word}");
                assert!(word["cityspec_ignored"].is_string());
            } else {
                assert_eq!(word["iscrowd"], 0, "{word}");
                assert_eq!(word["text"], transcription);
            }
            let plate = plates
                .iter()
                .find(|p| p["cityspec_instance"] == word["cityspec_instance"])
                .expect("a word's plate is annotated");
            let [wx, wy, ww, wh] = [0, 1, 2, 3].map(|k| word["bbox"][k].as_f64().unwrap());
            let [px, py, pw, ph] = [0, 1, 2, 3].map(|k| plate["bbox"][k].as_f64().unwrap());
            assert!(ww > 0.0 && wh > 0.0, "{word}");
            assert!(wx >= px && wy >= py && wx + ww <= px + pw && wy + wh <= py + ph);
            // An RLE like the plates' (one type per field for columnar readers), its area the
            // mask's pixels: the whole box here, where the quads are rectangles on pixels.
            let rle = &word["segmentation"];
            assert_eq!(rle["size"], json!([6, 20]), "{word}");
            let mask = Rle::from_compressed(rle["counts"].as_str().unwrap(), 6, 20).unwrap();
            assert_eq!(mask.area(), word["area"].as_u64().unwrap());
            assert_eq!(word["area"].as_f64().unwrap(), ww * wh, "rectangles here");
        }
        let texts: Vec<&str> = words.iter().map(|w| w["text"].as_str().unwrap()).collect();
        assert_eq!(texts, ["Write", "Group", "Edge", "Hidden", "Gone", "Ok"]);
        // Words follow their plate; "Edge" is cut to the plate at the image's edge, "Hidden"
        // to the 3 columns its plate shows.
        assert_eq!(words[2]["bbox"], json!([14, 0, 6, 3]));
        assert_eq!(words[3]["bbox"], json!([0, 4, 3, 2]));
        assert_eq!(words[3]["cityspec_ignored"], "hidden");
        assert_eq!(words[1]["cityspec_ignored"], "small");
        assert_eq!(words[5]["word_index"], Value::Null);
        assert_eq!(words[0]["word_index"], 0);
        assert_eq!(words[1]["word_index"], 1);
    }
}
