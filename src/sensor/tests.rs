//! Tests of the sensor stage as a whole: one small synthetic frame through `develop`.

use super::*;
use crate::spec::{SensorSpec, Weather, WeatherSpec};

/// 64 × 48: a grey ground below the horizon row (depth growing to the horizon), a wall
/// 20 m ahead in the middle columns, sky above.
fn scene() -> (Vec<[f32; 3]>, Vec<f32>, CameraPose, [f64; 4]) {
    let (w, h) = (64usize, 48usize);
    let pose = CameraPose::level([0.0, 1.5, 0.0], [0.0, 1.5, -10.0]);
    let k = [40.0, 40.0, 32.0, 24.0];
    let mut linear = vec![[0.45, 0.62, 0.9]; w * h];
    let mut depth = vec![0.0f32; w * h];
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            if (24..40).contains(&x) && y >= 10 {
                linear[i] = [0.3, 0.2, 0.15];
                depth[i] = 20.0;
            } else if y > 24 {
                // The ground: depth where the ray meets y = 0.
                let b = (y as f32 + 0.5 - 24.0) / 40.0;
                linear[i] = [0.2, 0.2, 0.2];
                depth[i] = (1.5 / b).min(20.0);
            }
        }
    }
    (linear, depth, pose, k)
}

fn develop_with(c: &Conditions) -> Developed {
    let (linear, depth, pose, intrinsics) = scene();
    develop(
        &SensorFrame {
            width: 64,
            height: 48,
            linear: &linear,
            depth: &depth,
            pose,
            intrinsics,
            motion: None,
            shutter: None,
            horizon: [0.45, 0.62, 0.9],
            clouds: CloudLight {
                sun_direction: [0.0, 0.8, -0.6],
                sun_colour: [1.0, 0.95, 0.9],
                sky: [0.3, 0.4, 0.6],
            },
            scene_exposure: 1.0,
        },
        c,
    )
}

fn conditions(weather: &str, sensor: &str) -> Conditions {
    let w: WeatherSpec = toml::from_str(weather).unwrap();
    let s: SensorSpec = toml::from_str(sensor).unwrap();
    draw(&w, &s, 5, 0)
}

#[test]
fn developing_is_deterministic_and_every_effect_changes_the_image() {
    let plain = develop_with(&Conditions::plain());
    assert_eq!(plain, develop_with(&Conditions::plain()));
    for (weather, sensor) in [
        ("kind = \"overcast\"", ""),
        ("kind = \"fog\"", ""),
        ("kind = \"rain\"", ""),
        ("", "noise = 0.02\nshot_noise = 0.01"),
        ("", "jpeg_quality = 40"),
        ("", "vignetting = 0.5"),
        ("", "chromatic_aberration = 3"),
        ("", "motion_blur = 2"),
        ("", "exposure = \"fixed\"\nev = 1"),
    ] {
        let c = conditions(weather, sensor);
        let got = develop_with(&c);
        assert_eq!(got, develop_with(&c), "{weather} {sensor}");
        assert_ne!(got.rgb, plain.rgb, "{weather} {sensor}");
    }
}

#[test]
fn fog_fades_the_far_wall_more_than_the_near_ground() {
    let fog = develop_with(&conditions("kind = \"fog\"\nfog_density = 0.05", ""));
    let plain = develop_with(&Conditions::plain());
    let diff = |x: u32, y: u32| {
        let (a, b) = (fog.rgb.get_pixel(x, y), plain.rgb.get_pixel(x, y));
        (0..3)
            .map(|k| (i32::from(a[k]) - i32::from(b[k])).abs())
            .sum::<i32>()
    };
    let c = conditions("kind = \"fog\"", "");
    assert_eq!(c.weather, Weather::Fog);
    // The wall 20 m away turns towards the fog colour; the ground just below the camera
    // (about 1.6 m away) barely changes beyond the exposure shift.
    assert!(
        diff(30, 20) > diff(5, 47) + 30,
        "{} {}",
        diff(30, 20),
        diff(5, 47)
    );
}

#[test]
fn travel_direction_follows_the_path_and_skips_jumps() {
    let pose = |x: f64, z: f64, tx: f64, tz: f64| CameraPose::level([x, 1.6, z], [tx, 1.6, tz]);
    // Three frames east along a road, then a jump to a road heading north.
    let poses = [
        pose(0.0, 0.0, 50.0, 0.0),
        pose(5.0, 0.0, 55.0, 0.0),
        pose(10.0, 0.0, 60.0, 0.0),
        pose(300.0, 200.0, 300.0, 150.0),
        pose(300.0, 195.0, 300.0, 145.0),
    ];
    let east = travel_direction(&poses, 2).unwrap();
    assert!((east[0] - 1.0).abs() < 1e-9, "{east:?}");
    let north = travel_direction(&poses, 3).unwrap();
    assert!((north[2] + 1.0).abs() < 1e-9, "{north:?}");
    assert_eq!(travel_direction(&poses[..1], 0), Some([1.0, 0.0, 0.0]));
    assert_eq!(travel_direction(&poses, 9), None);
}
