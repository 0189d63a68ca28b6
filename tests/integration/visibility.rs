//! Labels only on what a camera can see: every positive (`iscrowd` 0) of the example specs
//! stands out in the frame's final RGB image by at least `annotate::MIN_CONTRAST`, measured
//! here again from the files a build writes; what does not is an ignore region saying so.

use crate::common;

use std::fs;
use std::path::Path;

use cityspec::annotate::MIN_CONTRAST;
use common::{Workspace, quiet_options};
use image::RgbImage;
use serde_json::Value;

/// Every example spec with cameras (`cmp`, `drawn` and `mirrored` have none), the day city
/// shrunk, with it the variants that extend it: night, dusk, fog and rain are where objects
/// fade.
const SPECS: [&str; 10] = [
    "day",
    "night",
    "dusk",
    "fog",
    "rain",
    "randomized",
    "signs",
    "text",
    "sensors",
    "drive",
];

/// An annotation's contrast as `docs/output-formats.md` defines it: on 8-bit sRGB luma, the
/// larger of its pixels' spread and the distance of their mean from the other pixels of
/// its box grown by a quarter of its larger side (at least 2 px).
fn contrast(rgb: &RgbImage, ids: &RgbImage, id: u32, bbox: [u32; 4]) -> f64 {
    let (w, h) = rgb.dimensions();
    let [x, y, bw, bh] = bbox;
    let grow = ((bw.max(bh)) / 4).max(2);
    let (mut inside, mut outside) = (Vec::new(), Vec::new());
    for py in y.saturating_sub(grow)..(y + bh + grow).min(h) {
        for px in x.saturating_sub(grow)..(x + bw + grow).min(w) {
            let [r, g, b] = rgb.get_pixel(px, py).0;
            let l = 0.2126 * f64::from(r) + 0.7152 * f64::from(g) + 0.0722 * f64::from(b);
            let [i0, i1, i2] = ids.get_pixel(px, py).0;
            let here = u32::from(i0) | u32::from(i1) << 8 | u32::from(i2) << 16;
            if here == id {
                &mut inside
            } else {
                &mut outside
            }
            .push(l);
        }
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let m = mean(&inside);
    let spread =
        (inside.iter().map(|l| (l - m) * (l - m)).sum::<f64>() / inside.len() as f64).sqrt();
    let apart = if outside.is_empty() {
        0.0
    } else {
        (m - mean(&outside)).abs()
    };
    spread.max(apart)
}

/// Every annotation of a camera path: (positives, ignored for contrast) that break the rule,
/// and how many it checked of each.
fn check_path(camera: &Path) -> (Vec<String>, [usize; 2]) {
    let coco: Value = serde_json::from_slice(&fs::read(camera.join("coco.json")).unwrap()).unwrap();
    let mut wrong = Vec::new();
    let mut counts = [0, 0];
    for image in coco["images"].as_array().unwrap() {
        let file = image["file_name"].as_str().unwrap();
        let rgb = image::open(camera.join(file)).unwrap().to_rgb8();
        let ids = image::open(camera.join(file.replace("rgb/", "ids/")))
            .unwrap()
            .to_rgb8();
        let annotations = coco["annotations"]
            .as_array()
            .unwrap()
            .iter()
            // Words (`word_index`) take their plate's verdict; the plate is checked.
            .filter(|a| a["image_id"] == image["id"] && a.get("word_index").is_none());
        for a in annotations {
            let bbox: Vec<u32> = a["bbox"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap() as u32)
                .collect();
            let id = a["cityspec_instance"].as_u64().unwrap() as u32;
            let c = contrast(&rgb, &ids, id, [bbox[0], bbox[1], bbox[2], bbox[3]]);
            let positive = a["iscrowd"] == 0;
            let faint = a["cityspec_ignored"] == "contrast";
            // A hair of slack for the two sums' rounding.
            if (positive && c < MIN_CONTRAST - 1e-6) || (faint && c >= MIN_CONTRAST + 1e-6) {
                wrong.push(format!(
                    "{}: {} {} contrast {c:.2}",
                    camera.display(),
                    file,
                    a["name"]
                ));
            }
            counts[0] += usize::from(positive);
            counts[1] += usize::from(faint);
        }
    }
    (wrong, counts)
}

#[test]
fn every_positive_of_the_examples_stands_out_in_its_frame() {
    let ws = Workspace::with_spec("day");
    ws.shrink_day();
    let mut wrong = Vec::new();
    let mut totals = Vec::new();
    for name in SPECS {
        let options = quiet_options(ws.out(), ws.cache());
        cityspec::driver::build(&ws.spec(name), &options).unwrap_or_else(|e| panic!("{name}: {e}"));
        let frames = ws.out().join(name).join("frames");
        let mut counts = [0, 0];
        for camera in fs::read_dir(&frames).unwrap() {
            let (w, c) = check_path(&camera.unwrap().path());
            wrong.extend(w);
            counts = [counts[0] + c[0], counts[1] + c[1]];
        }
        totals.push((name, counts));
    }
    assert!(
        wrong.is_empty(),
        "{} labels break the rule:\n{}",
        wrong.len(),
        wrong.join("\n")
    );
    // The rule decides something: positives everywhere, and faint objects at night.
    assert!(
        totals.iter().all(|(_, [positives, _])| *positives > 0),
        "{totals:?}"
    );
    let night = totals.iter().find(|(n, _)| *n == "night").unwrap().1;
    assert!(night[1] > 0, "no object fades at night: {totals:?}");
}
