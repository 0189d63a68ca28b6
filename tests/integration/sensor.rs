//! The sensor stage changes the RGB frames: a camera path built with weather and sensor
//! effects has the same ids and depth as without them, and labels the same objects with the
//! same boxes and masks; only which of them stand out enough in the final image to be
//! positives may differ. So do the headlights of a night drive's own car.

use crate::common;

use cityspec::driver;
use common::{Workspace, tree};

#[test]
fn weather_and_sensor_change_rgb_only() {
    let ws = Workspace::with_spec("randomized");
    ws.edit_spec("randomized", |spec| {
        // Every frame foggy or rainy, so each one differs from the clear render.
        spec.set("cameras[0].frames", 4)
            .set("weather.kind", ["fog", "rain"]);
    });
    driver::build(&ws.spec("randomized"), &ws.options()).unwrap();
    let with = tree(&ws.out().join("randomized/frames/street"));

    ws.edit_spec("randomized", |spec| {
        spec.remove("cameras[0].sensor").remove("weather");
    });
    driver::build(&ws.spec("randomized"), &ws.options()).unwrap();
    let without = tree(&ws.out().join("randomized/frames/street"));

    assert_eq!(
        with.keys().collect::<Vec<_>>(),
        without.keys().collect::<Vec<_>>()
    );
    let mut rgb = 0;
    for (name, bytes) in &with {
        let plain = &without[name];
        if name.starts_with("ids/") || name.starts_with("depth/") {
            assert!(bytes == plain, "{name} changed");
        } else if name.starts_with("rgb/") {
            assert!(bytes != plain, "{name} unchanged by fog or rain");
            rgb += 1;
        }
    }
    assert_eq!(rgb, 4);
    // Labels: the same objects; weather and sensor decide only which stand out enough to
    // be positives.
    common::same_objects_but_for_contrast(&with["coco.json"], &without["coco.json"]);
    let coco: serde_json::Value = serde_json::from_slice(&with["coco.json"]).unwrap();
    assert!(coco["annotations"].as_array().unwrap().len() > 5);

    // Each image records what it drew; poses.json the same values.
    let doc: serde_json::Value = serde_json::from_slice(&with["coco.json"]).unwrap();
    let poses: serde_json::Value = serde_json::from_slice(&with["poses.json"]).unwrap();
    for (image, frame) in doc["images"]
        .as_array()
        .unwrap()
        .iter()
        .zip(poses["frames"].as_array().unwrap())
    {
        let conditions = &image["conditions"];
        let weather = conditions["weather"].as_str().unwrap();
        assert!(weather == "fog" || weather == "rain", "{weather}");
        let quality = conditions["jpeg_quality"].as_f64().unwrap();
        assert!((60.0..=95.0).contains(&quality), "{quality}");
        assert_eq!(&frame["conditions"], conditions);
        // The sun it was lit by, too.
        let sun = &conditions["sun"];
        assert!(
            sun["elevation"].is_number() && sun["azimuth"].is_number(),
            "{sun}"
        );
    }
}

/// Mean of the lower half of an RGB PNG, 0–255.
fn lower_half_mean(png: &[u8]) -> f64 {
    let image = image::load_from_memory(png).unwrap().to_rgb8();
    let half = image.height() / 2;
    let values: Vec<f64> = image
        .rows()
        .skip(half as usize)
        .flatten()
        .flat_map(|p| p.0.map(f64::from))
        .collect();
    values.iter().sum::<f64>() / values.len() as f64
}

#[test]
fn a_night_drive_lights_the_road_ahead_with_its_own_headlights_in_rgb_only() {
    let ws = Workspace::with_spec("night");
    // night.toml extends day.toml: its city and frames are day's.
    ws.shrink("day");
    driver::build(&ws.spec("night"), &ws.options()).unwrap();
    let with = tree(&ws.out().join("night/frames/street"));
    ws.edit_spec("night", |spec| {
        spec.insert("cameras[0].headlights", false);
    });
    driver::build(&ws.spec("night"), &ws.options()).unwrap();
    let without = tree(&ws.out().join("night/frames/street"));

    assert_eq!(
        with.keys().collect::<Vec<_>>(),
        without.keys().collect::<Vec<_>>()
    );
    let (mut lit, mut dark, mut changed) = (0.0, 0.0, 0);
    for (name, bytes) in &with {
        let plain = &without[name];
        if name.starts_with("ids/") || name.starts_with("depth/") {
            assert!(bytes == plain, "{name} changed");
        } else if name.starts_with("rgb/") {
            changed += usize::from(bytes != plain);
            lit += lower_half_mean(bytes);
            dark += lower_half_mean(plain);
        }
    }
    assert!(changed > 0, "no frame changed");
    // The road ahead is brighter with them on.
    assert!(lit > dark + 2.0, "lower halves: {lit} with, {dark} without");
    common::same_objects_but_for_contrast(&with["coco.json"], &without["coco.json"]);
    for (doc, on) in [(&with, true), (&without, false)] {
        let poses: serde_json::Value = serde_json::from_slice(&doc["poses.json"]).unwrap();
        for frame in poses["frames"].as_array().unwrap() {
            assert_eq!(frame["conditions"]["headlights"], on, "{frame}");
        }
    }
}
