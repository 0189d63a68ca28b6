//! The cameras' `coco.json` → one COCO document per split: images renumbered over the
//! dataset, `file_name`s made relative to the output folder, categories merged by name.

use std::collections::BTreeMap;

use serde::Deserialize;
use serde_json::value::RawValue;
use serde_json::{Map, Value};

use super::{DatasetError, Member};
use crate::annotate::{Category, CocoLines, write_coco};

/// One camera path's COCO document, read back.
pub(super) struct CameraCoco<'a> {
    pub camera: &'a str,
    images: Vec<Map<String, Value>>,
    categories: Vec<Category>,
    /// Per image (by index), its annotations as the document has them (borrowed, not
    /// parsed: a path's annotations parsed at once took ten times its `coco.json`).
    annotations: Vec<Vec<&'a RawValue>>,
}

/// A `coco.json` as read: its annotations left raw.
#[derive(Deserialize)]
struct Document<'a> {
    images: Vec<Map<String, Value>>,
    categories: Vec<Map<String, Value>>,
    #[serde(borrow)]
    annotations: Vec<&'a RawValue>,
}

/// What an annotation is read for before it is written again.
#[derive(Deserialize)]
struct AnnotationIds {
    #[serde(default)]
    image_id: u64,
}

impl<'a> CameraCoco<'a> {
    /// `bytes`, as the frames stage writes `frames/<camera>/coco.json`: image `i` has id
    /// `i + 1` and file name `rgb/NNNNNN.png` for frame `i`.
    pub fn parse(camera: &'a str, bytes: &'a [u8]) -> Result<CameraCoco<'a>, DatasetError> {
        let bad = |why: String| DatasetError(format!("frames/{camera}/coco.json: {why}"));
        let doc: Document = serde_json::from_slice(bytes).map_err(|e| bad(e.to_string()))?;
        let images = doc.images;
        for (i, image) in images.iter().enumerate() {
            if image.get("id").and_then(Value::as_u64) != Some(i as u64 + 1) {
                return Err(bad(format!("image {i} has not id {}", i + 1)));
            }
        }
        let categories = doc
            .categories
            .into_iter()
            .map(|c| {
                Ok(Category {
                    id: c
                        .get("id")
                        .and_then(Value::as_u64)
                        .ok_or_else(|| bad("a category without id".into()))?
                        as u32,
                    name: c
                        .get("name")
                        .and_then(Value::as_str)
                        .ok_or_else(|| bad("a category without name".into()))?
                        .to_owned(),
                    keypoints: c.get("keypoints").is_some(),
                })
            })
            .collect::<Result<Vec<_>, DatasetError>>()?;
        let mut annotations = vec![Vec::new(); images.len()];
        for a in doc.annotations {
            let ids: AnnotationIds =
                serde_json::from_str(a.get()).map_err(|e| bad(e.to_string()))?;
            let image = ids.image_id as usize;
            let slot = image
                .checked_sub(1)
                .and_then(|i| annotations.get_mut(i))
                .ok_or_else(|| bad(format!("an annotation of image {image}, which it lacks")))?;
            slot.push(a);
        }
        Ok(CameraCoco {
            camera,
            images,
            categories,
            annotations,
        })
    }

    pub fn frames(&self) -> usize {
        self.images.len()
    }

    /// Frame `frame`'s image file, relative to `frames/<camera>/`.
    pub fn file_name(&self, frame: usize) -> Option<&str> {
        self.images.get(frame)?.get("file_name")?.as_str()
    }
}

/// The categories of every camera merged by name, in order of first appearance, numbered
/// from 1 (with keypoints when any camera's has them); and per camera, its category ids → the merged ones.
fn merged_categories(documents: &[CameraCoco]) -> (Vec<Category>, Vec<BTreeMap<u64, u32>>) {
    let mut merged: Vec<Category> = Vec::new();
    let maps = documents
        .iter()
        .map(|d| {
            d.categories
                .iter()
                .map(|c| {
                    let id = match merged.iter_mut().find(|m| m.name == c.name) {
                        Some(m) => {
                            m.keypoints |= c.keypoints;
                            m.id
                        }
                        None => {
                            let id = merged.len() as u32 + 1;
                            merged.push(Category { id, ..c.clone() });
                            id
                        }
                    };
                    (u64::from(c.id), id)
                })
                .collect()
        })
        .collect();
    (merged, maps)
}

/// The COCO document of `members` (one split's frames, in dataset order). With
/// `webdataset` (samples per shard) an image's `file_name` is its sample's RGB member
/// (`<camera>_<NNNNNN>.png`) in the split's shards, and its depth the float32 metres of
/// `<camera>_<NNNNNN>.depth.npy`.
pub(super) fn document(
    documents: &[CameraCoco],
    members: &[Member],
    webdataset: Option<usize>,
) -> Result<Vec<u8>, DatasetError> {
    let (categories, maps) = merged_categories(documents);
    // Image ids over the whole dataset: cameras in order, frames in order, from 1.
    let mut first_id = Vec::with_capacity(documents.len());
    let mut next = 1u64;
    for d in documents {
        first_id.push(next);
        next += d.frames() as u64;
    }
    // Each member's lines made as the writer asks for them, never all at once: it reads
    // the images in its first pass, the annotations in its second.
    let lines = |m: &Member, with_annotations: bool| -> Result<CocoLines, DatasetError> {
        let d = &documents[m.camera];
        let id = first_id[m.camera] + m.frame as u64;
        let mut image = d.images[m.frame].clone();
        image.insert("id".into(), Value::from(id));
        if webdataset.is_some() {
            let key = super::stem(d.camera, m.frame);
            image.insert("file_name".into(), Value::from(format!("{key}.png")));
            let depth = serde_json::json!({
                "file_name": format!("{key}.depth.npy"),
                "format": "f32",
                "scale": 1.0,
            });
            image.insert("depth".into(), depth);
        } else {
            let dir = format!("frames/{}/", d.camera);
            prefix(&mut image, &dir);
            if let Some(Value::Object(depth)) = image.get_mut("depth") {
                prefix(depth, &dir);
            }
        }
        let bad = |why: String| DatasetError(format!("frames/{}/coco.json: {why}", d.camera));
        let annotations = d.annotations[m.frame]
            .iter()
            .filter(|_| with_annotations)
            .map(|raw| {
                let mut a: Map<String, Value> =
                    serde_json::from_str(raw.get()).map_err(|e| bad(e.to_string()))?;
                a.shift_remove("id");
                a.insert("image_id".into(), Value::from(id));
                let category = a.get("category_id").and_then(Value::as_u64).unwrap_or(0);
                let merged = maps[m.camera].get(&category).ok_or_else(|| {
                    bad(format!(
                        "an annotation of category {category}, which it does not list"
                    ))
                })?;
                a.insert("category_id".into(), Value::from(*merged));
                Ok(Value::Object(a).to_string())
            })
            .collect::<Result<Vec<_>, DatasetError>>()?;
        Ok(CocoLines {
            image: Value::Object(image).to_string(),
            annotations,
        })
    };
    let mut out = Vec::new();
    let mut failed = None;
    let mut passes = 0;
    let written = write_coco(&mut out, &categories, |pass| {
        passes += 1;
        members.iter().try_for_each(|m| match lines(m, passes > 1) {
            Ok(lines) => pass(&lines),
            Err(e) => {
                failed = Some(e);
                Err(std::io::Error::other("a member's lines"))
            }
        })
    });
    match (written, failed) {
        (_, Some(e)) => Err(e),
        (Ok(()), None) => Ok(out),
        (Err(e), None) => Err(DatasetError(format!("writing a split's COCO: {e}"))),
    }
}

/// `file_name` made relative to the output folder.
fn prefix(object: &mut Map<String, Value>, dir: &str) {
    if let Some(Value::String(name)) = object.get_mut("file_name") {
        *name = format!("{dir}{name}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_merged_category_has_keypoints_when_any_cameras_has_them() {
        let doc = |categories: &str| {
            format!(r#"{{"images":[],"categories":[{categories}],"annotations":[]}}"#)
        };
        let plain = doc(r#"{"id":1,"name":"car"},{"id":2,"name":"person"}"#);
        let keyed = doc(r#"{"id":1,"name":"person","keypoints":["nose"],"skeleton":[]}"#);
        let documents = [
            CameraCoco::parse("a", plain.as_bytes()).unwrap(),
            CameraCoco::parse("b", keyed.as_bytes()).unwrap(),
        ];
        let (merged, maps) = merged_categories(&documents);
        let seen: Vec<_> = merged
            .iter()
            .map(|c| (c.name.as_str(), c.id, c.keypoints))
            .collect();
        assert_eq!(seen, [("car", 1, false), ("person", 2, true)]);
        assert_eq!(maps[1][&1], 2);
    }
}
