//! Sensor stage benchmark, printing the median milliseconds per 640 × 480 frame of
//! `sensor::develop` under each condition:
//! `cargo bench --bench sensor`. The frames path must stay at 30 frames/s or more by day
//! (issue 11), so the plain condition has to cost a few milliseconds. Timings are printed,
//! never asserted.

use std::hint::black_box;
use std::time::Instant;

use cityspec::model::CameraPose;
use cityspec::sensor::{self, Conditions, SensorFrame};
use cityspec::spec::{SensorSpec, WeatherSpec};
use image::{Rgb, RgbImage};

const W: u32 = 640;
const H: u32 = 480;

fn main() {
    let runs: usize = std::env::var("BENCH_RUNS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(15);
    let (rgb, depth) = street();
    let pose = CameraPose::level([0.0, 1.6, 0.0], [0.0, 1.6, -10.0]);
    println!(
        "cityspec sensor benchmark: {W}x{H}, rayon threads: {}",
        rayon::current_num_threads()
    );
    println!("| condition | ms per frame (median of {runs}) |\n|---|---|");
    let linear = sensor::decode_srgb(&rgb);
    let cases = [
        (
            "plain (clear, no clouds, auto exposure, tone curve)",
            "clouds = 0",
            "",
        ),
        ("clouds over half the sky", "clouds = 0.5", ""),
        ("overcast", "kind = \"overcast\"", ""),
        ("fog", "kind = \"fog\"", ""),
        ("rain", "kind = \"rain\"", ""),
        (
            "noise + vignetting + aberration",
            "",
            "noise = 0.01\nshot_noise = 0.004\nvignetting = 0.3\nchromatic_aberration = 1.5",
        ),
        ("motion blur 0.4 m", "", "motion_blur = 0.4"),
        ("JPEG quality 80", "", "jpeg_quality = 80"),
        (
            "rain + every sensor effect",
            "kind = \"rain\"",
            "noise = 0.01\nshot_noise = 0.004\nvignetting = 0.3\nchromatic_aberration = 1.5\nmotion_blur = 0.4\njpeg_quality = 80",
        ),
    ];
    for (name, weather, sensor_table) in cases {
        let weather: WeatherSpec = toml::from_str(weather).expect("a weather table");
        let sensor_spec: SensorSpec = toml::from_str(sensor_table).expect("a sensor table");
        let c: Conditions = sensor::draw(&weather, &sensor_spec, 7, 0);
        let frame = SensorFrame {
            width: W,
            height: H,
            linear: &linear,
            depth: &depth,
            pose,
            intrinsics: [554.0, 554.0, 320.0, 240.0],
            motion: None,
            shutter: None,
            horizon: [0.7, 0.8, 0.95],
            clouds: sensor::CloudLight {
                sun_direction: [0.0, 0.8, -0.6],
                sun_colour: [1.0, 0.95, 0.9],
                sky: [0.3, 0.4, 0.6],
            },
            scene_exposure: 1.0,
        };
        let ms = median(runs, || {
            black_box(sensor::develop(&frame, &c));
        });
        println!("| {name} | {ms:.2} |");
    }
}

/// Median milliseconds of `runs` calls of `f`.
fn median(runs: usize, mut f: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..runs.max(1))
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64() * 1000.0
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

/// A street-like frame: sky above the horizon, a road below whose depth grows towards the
/// horizon, walls 15 m to either side with a stripe pattern.
fn street() -> (RgbImage, Vec<f32>) {
    let mut rgb = RgbImage::new(W, H);
    let mut depth = vec![0.0f32; (W * H) as usize];
    for y in 0..H {
        for x in 0..W {
            let i = (y * W + x) as usize;
            let below = y as f32 + 0.5 - 240.0;
            let side = (x as f32 + 0.5 - 320.0).abs();
            let (colour, d) = if side > 200.0 && y > 100 {
                let stripe = if (y / 12) % 2 == 0 { 150 } else { 110 };
                ([stripe, 90, 70], 15.0 * 554.0 / side)
            } else if below > 0.0 {
                ([90, 90, 95], (1.6 * 554.0 / below).min(200.0))
            } else {
                ([170, 200, 235], 0.0)
            };
            rgb.put_pixel(x, y, Rgb(colour));
            depth[i] = d;
        }
    }
    (rgb, depth)
}
