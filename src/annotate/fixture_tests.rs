//! A synthetic dataset (overlapping rectangles drawn far to near) written as COCO JSON and
//! RGB-packed instance PNGs (`id = R + 256·G + 256²·B`, with ids on both sides of 65,535),
//! for `tests/external/check_coco.py`. Objects under the thresholds are ignore regions.
//!
//! The test writes into a temporary folder and checks the files against the images itself.
//! To run the Python checker on them, keep them:
//!
//! ```sh
//! CITYSPEC_COCO_FIXTURE_DIR=/tmp/coco-fixture cargo test --lib annotate::fixture_tests
//! python3 tests/external/check_coco.py /tmp/coco-fixture/coco.json /tmp/coco-fixture/instance
//! ```

use std::collections::BTreeMap;
use std::path::Path;

use image::{ImageBuffer, Luma};
use rand::RngExt;
use serde_json::Value;

use super::*;
use crate::model::CameraPose;

const W: u32 = 64;
const H: u32 = 48;
const OBJECTS: u32 = 14;
/// Object `n` (2 and up) has instance id `BASE + n`: ids run across the 16-bit limit.
const BASE: u32 = 65_530;

type Instance = ImageBuffer<Luma<u32>, Vec<u32>>;

fn labels() -> Vec<ObjectLabel> {
    (1..=BASE + OBJECTS)
        .map(|id| {
            let n = id.saturating_sub(BASE);
            let (category, text) = match n {
                0 | 1 => (None, None),
                n if n % 4 == 0 => (Some(3), Some(format!("WORD{n}"))),
                n if n % 3 == 0 => (Some(2), None),
                _ => (Some(1), None),
            };
            ObjectLabel {
                name: format!("object_{id:04}"),
                box3d: None,
                keypoints: None,
                category,
                text,
                attributes: Default::default(),
                sign: None,
            }
        })
        .collect()
}

/// One frame: ground (id 1) over the bottom third, then each object as one or two
/// rectangles (some partly off-image) at a random depth, drawn far to near. Returns the
/// image and, per id, the projected box and pixel count ignoring occlusion.
fn draw_frame(frame: u64) -> (Instance, BTreeMap<u32, ([f64; 4], u64)>) {
    let mut rng = crate::rng::stream(1, "annotate-fixture", frame);
    let mut shapes: Vec<(u32, u32, Vec<[i64; 4]>)> = vec![(u32::MAX, 1, vec![[0, 32, 64, 48]])];
    for id in 2..=OBJECTS {
        let mut rect = || {
            let (x, y) = (rng.random_range(-8..60i64), rng.random_range(-8..44i64));
            let (w, h) = (rng.random_range(1..24i64), rng.random_range(1..20i64));
            [x, y, x + w, y + h]
        };
        let mut parts = vec![rect()];
        if id % 5 == 0 {
            parts.push(rect());
        }
        shapes.push((rng.random_range(0..1000u32), BASE + id, parts));
    }
    shapes.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
    let mut image = Instance::new(W, H);
    let mut full = BTreeMap::new();
    for (_, id, parts) in &shapes {
        let mut own = vec![false; (W * H) as usize];
        for r in parts {
            for y in r[1].max(0)..r[3].min(i64::from(H)) {
                for x in r[0].max(0)..r[2].min(i64::from(W)) {
                    image.put_pixel(x as u32, y as u32, Luma([*id]));
                    own[(y * i64::from(W) + x) as usize] = true;
                }
            }
        }
        let x0 = parts.iter().map(|r| r[0]).min().unwrap() as f64;
        let y0 = parts.iter().map(|r| r[1]).min().unwrap() as f64;
        let x1 = parts.iter().map(|r| r[2]).max().unwrap() as f64;
        let y1 = parts.iter().map(|r| r[3]).max().unwrap() as f64;
        let count = own.iter().filter(|p| **p).count() as u64;
        full.insert(*id, ([x0, y0, x1 - x0, y1 - y0], count));
    }
    (image, full)
}

/// The tight box and pixel count of `id` in `image`, computed the plain way.
fn tight_box(image: &Instance, id: u32) -> Option<([u32; 4], u64)> {
    let pixels: Vec<(u32, u32)> = image
        .enumerate_pixels()
        .filter(|(_, _, p)| p.0[0] == id)
        .map(|(x, y, _)| (x, y))
        .collect();
    let x0 = pixels.iter().map(|p| p.0).min()?;
    let y0 = pixels.iter().map(|p| p.1).min()?;
    let x1 = pixels.iter().map(|p| p.0).max()?;
    let y1 = pixels.iter().map(|p| p.1).max()?;
    Some(([x0, y0, x1 - x0 + 1, y1 - y0 + 1], pixels.len() as u64))
}

fn write_fixture(dir: &Path) -> (Vec<u8>, Vec<Instance>) {
    let images: Vec<_> = (0..4).map(draw_frame).collect();
    let frames: Vec<FrameInput> = images
        .iter()
        .enumerate()
        .map(|(i, (image, full))| FrameInput {
            file_name: format!("frames/{i:06}.png"),
            instance: image,
            rgb: None,
            intrinsics: [32.0, 32.0, 32.0, 24.0],
            pose: CameraPose::level([i as f64, 1.6, 0.0], [i as f64 + 10.0, 0.6, 0.0]),
            full: full.clone(),
            quads: BTreeMap::new(),
            depth: None,
        })
        .collect();
    let categories: Vec<Category> = ["building", "sign", "text"]
        .iter()
        .zip(1..)
        .map(|(n, id)| Category {
            id,
            name: n.to_string(),
            keypoints: false,
        })
        .collect();
    let thresholds = Thresholds {
        min_pixels: 4,
        min_fraction: 0.1,
    };
    let json = coco(&categories, &labels(), &frames, &thresholds);
    std::fs::create_dir_all(dir.join("instance")).unwrap();
    std::fs::write(dir.join("coco.json"), &json).unwrap();
    for (i, (image, _)) in images.iter().enumerate() {
        crate::model::pack_ids(image)
            .save(dir.join("instance").join(format!("{i:06}.png")))
            .unwrap();
    }
    (json, images.into_iter().map(|(i, _)| i).collect())
}

#[test]
fn fixture_boxes_are_tight_boxes_of_the_written_pngs() {
    let temp = tempfile::tempdir().unwrap();
    let dir = std::env::var_os("CITYSPEC_COCO_FIXTURE_DIR")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| temp.path().to_path_buf());
    let (json, images) = write_fixture(&dir);
    assert_eq!(std::fs::read(dir.join("coco.json")).unwrap(), json);
    let doc: Value = serde_json::from_slice(&json).unwrap();
    let anns = doc["annotations"].as_array().unwrap();
    // Enough objects survive occlusion and the thresholds to make the check meaningful,
    // some miss them (ignore regions), and some are wholly hidden.
    let crowd = anns.iter().filter(|a| a["iscrowd"] == 1).count();
    assert!(anns.len() - crowd >= 20, "{} annotations", anns.len());
    assert!(crowd >= 2, "{crowd} ignore regions");
    assert!(anns.len() < 4 * (OBJECTS as usize - 1));
    let ids: Vec<u64> = anns
        .iter()
        .map(|a| a["cityspec_instance"].as_u64().unwrap())
        .collect();
    assert!(ids.iter().any(|&id| id > 65_535) && ids.iter().any(|&id| id <= 65_535));
    for ann in anns {
        let frame = ann["image_id"].as_u64().unwrap() as usize - 1;
        let path = dir.join("instance").join(format!("{frame:06}.png"));
        let read: Instance = crate::model::unpack_ids(&image::open(&path).unwrap().into_rgb8());
        assert_eq!(read, images[frame]);
        let id = ann["cityspec_instance"].as_u64().unwrap() as u32;
        let (bbox, area) = tight_box(&read, id).unwrap();
        assert_eq!(ann["bbox"], serde_json::json!(bbox), "{ann}");
        assert_eq!(ann["area"], area, "{ann}");
        let passes = area >= 4 && ann["visible_fraction"].as_f64().unwrap() >= 0.1;
        assert_eq!(ann["iscrowd"], u8::from(!passes), "{ann}");
    }
}
