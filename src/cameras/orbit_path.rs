//! The overview orbit: points around the city on a circle, found without trigonometry.

use super::{CameraPose, mm};
use crate::model::ParsedLayout;

/// An overview: `frames` poses around the city at `height` metres, all looking at the
/// city centre on the ground.
///
/// The eyes lie on the circle through the layout's corners (radius half its diagonal).
/// Without trigonometry: frame `i` takes the point at `i/frames` of the way around the
/// perimeter of a square centred on the city, starting due north and turning clockwise
/// seen from above (north → east → south → west), and pushes it out radially onto the
/// circle. Spacing is even along the square, so the angular step varies smoothly (by up to
/// a factor of two between the square's edge middles and its corners).
///
/// No poses when `frames` is 0, the layout is empty, or `metres_per_pixel` is not a
/// positive finite number or `height` is not finite.
pub fn orbit_path(
    layout: &ParsedLayout,
    metres_per_pixel: f64,
    frames: u32,
    height: f64,
) -> Vec<CameraPose> {
    match layout_area(layout, metres_per_pixel) {
        Some(area) => orbit_path_around(area, frames, height),
        None => Vec::new(),
    }
}

/// The orbit of [`orbit_path`] around the box `[min_x, min_z, max_x, max_z]` (metres):
/// a map's extent (`OsmMap::extent`), or a layout's `[0, 0, width, height]`. No poses
/// when `frames` is 0, the box is empty or not finite, or `height` is not finite.
pub fn orbit_path_around(area: [f64; 4], frames: u32, height: f64) -> Vec<CameraPose> {
    let [x0, z0, x1, z1] = area;
    let (w, h) = (x1 - x0, z1 - z0);
    let radius = (w * w + h * h).sqrt() / 2.0;
    if frames == 0 || !height.is_finite() || !(radius > 0.0 && radius.is_finite()) {
        return Vec::new();
    }
    let centre = [(x0 + x1) / 2.0, (z0 + z1) / 2.0];
    (0..frames)
        .map(|i| {
            let [u, v] = square_point(f64::from(i) / f64::from(frames));
            let r = radius / (u * u + v * v).sqrt();
            CameraPose::level(
                [mm(centre[0] + u * r), mm(height), mm(centre[1] + v * r)],
                [mm(centre[0]), 0.0, mm(centre[1])],
            )
        })
        .collect()
}

/// Length in metres of the circle [`orbit_path`] flies (radius half the layout's
/// diagonal); 0 when `metres_per_pixel` is not a positive finite number. A
/// [`FrameRule::Spacing`](crate::spec::FrameRule) takes its frame count from this length;
/// the frames are then that far apart on average (the orbit's steps vary, see
/// [`orbit_path`]).
pub fn orbit_length(layout: &ParsedLayout, metres_per_pixel: f64) -> f64 {
    layout_area(layout, metres_per_pixel).map_or(0.0, orbit_length_around)
}

/// Length in metres of the circle [`orbit_path_around`] flies around `area`; 0 for a
/// box that is not finite.
pub fn orbit_length_around(area: [f64; 4]) -> f64 {
    let (w, h) = (area[2] - area[0], area[3] - area[1]);
    let length = std::f64::consts::PI * (w * w + h * h).sqrt();
    if length.is_finite() { length } else { 0.0 }
}

/// A layout's box in metres, `[0, 0, width, height]`; None when `metres_per_pixel` is
/// not a positive finite number.
fn layout_area(layout: &ParsedLayout, metres_per_pixel: f64) -> Option<[f64; 4]> {
    let m = metres_per_pixel;
    (m.is_finite() && m > 0.0).then(|| {
        let (w, h) = (f64::from(layout.width) * m, f64::from(layout.height) * m);
        [0.0, 0.0, w, h]
    })
}

/// The point at fraction `t ∈ [0, 1)` of the way around the square `[-1, 1]²` (x east,
/// z south), starting at north `(0, -1)` and going clockwise seen from above.
fn square_point(t: f64) -> [f64; 2] {
    // Perimeter 8, measured from the north-west corner; north is 1 along the top edge.
    let q = (t * 8.0 + 1.0) % 8.0;
    match q {
        q if q < 2.0 => [-1.0 + q, -1.0],
        q if q < 4.0 => [1.0, -1.0 + (q - 2.0)],
        q if q < 6.0 => [1.0 - (q - 4.0), 1.0],
        q => [-1.0, 1.0 - (q - 6.0)],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn layout(width: u32, height: u32) -> ParsedLayout {
        ParsedLayout {
            width,
            height,
            blocks: Vec::new(),
            roads: Vec::new(),
        }
    }

    #[test]
    fn looks_at_the_centre_from_the_circle_through_the_corners() {
        let poses = orbit_path(&layout(300, 400), 0.5, 12, 80.0);
        assert_eq!(poses.len(), 12);
        // 150 m × 200 m: centre (75, 100), radius 125.
        for p in &poses {
            assert_eq!(p.target, [75.0, 0.0, 100.0]);
            assert_eq!(p.eye[1], 80.0);
            let (dx, dz) = (p.eye[0] - 75.0, p.eye[2] - 100.0);
            assert!(((dx * dx + dz * dz).sqrt() - 125.0).abs() < 2e-3, "{p:?}");
        }
        // Starts due north and turns clockwise seen from above: north, east, south, west.
        assert_eq!(poses[0].eye, [75.0, 80.0, -25.0]);
        assert_eq!(poses[3].eye, [200.0, 80.0, 100.0]);
        assert_eq!(poses[6].eye, [75.0, 80.0, 225.0]);
        assert_eq!(poses[9].eye, [-50.0, 80.0, 100.0]);
        assert_eq!(poses, orbit_path(&layout(300, 400), 0.5, 12, 80.0));
    }

    #[test]
    fn square_walk_is_continuous_and_even() {
        let n = 64;
        let points: Vec<[f64; 2]> = (0..n).map(|i| square_point(i as f64 / n as f64)).collect();
        for i in 0..n {
            let (a, b) = (points[i], points[(i + 1) % n]);
            let d = (b[0] - a[0]).abs() + (b[1] - a[1]).abs();
            assert!((d - 8.0 / n as f64).abs() < 1e-12, "{a:?} → {b:?}");
        }
    }

    #[test]
    fn spacing_counts_frames_along_the_circle() {
        use crate::spec::FrameRule;
        // 150 m × 200 m: radius 125 m, circumference 250π ≈ 785.4 m.
        let length = orbit_length(&layout(300, 400), 0.5);
        assert!((length - 785.398).abs() < 1e-3, "{length}");
        assert_eq!(FrameRule::Spacing(10.0).frames(length), 78);
        assert_eq!(FrameRule::Spacing(800.0).frames(length), 1);
        assert_eq!(orbit_length(&layout(300, 400), 0.0), 0.0);
        assert_eq!(orbit_length(&layout(300, 400), f64::NAN), 0.0);
    }

    #[test]
    fn degenerate_inputs_give_no_poses() {
        assert!(orbit_path(&layout(10, 10), 1.0, 0, 5.0).is_empty());
        assert!(orbit_path(&layout(0, 0), 1.0, 4, 5.0).is_empty());
        assert!(orbit_path(&layout(10, 10), f64::NAN, 4, 5.0).is_empty());
        assert!(orbit_path(&layout(10, 10), 1.0, 4, f64::NAN).is_empty());
        assert!(orbit_path_around([0.0, 0.0, f64::INFINITY, 1.0], 4, 5.0).is_empty());
        assert_eq!(orbit_length_around([0.0, 0.0, f64::NAN, 1.0]), 0.0);
    }

    #[test]
    fn a_box_off_the_origin_is_circled_around_its_own_centre() {
        // A map's box, centred on the origin: −150…150 m east, −200…200 m south.
        let poses = orbit_path_around([-150.0, -200.0, 150.0, 200.0], 4, 30.0);
        assert_eq!(poses[0].eye, [0.0, 30.0, -250.0]);
        assert_eq!(poses[1].eye, [250.0, 30.0, 0.0]);
        assert!(poses.iter().all(|p| p.target == [0.0, 0.0, 0.0]));
        // The same orbit as a layout that size, moved by the box's corner.
        let shifted: Vec<[f64; 3]> = orbit_path(&layout(300, 400), 1.0, 4, 30.0)
            .iter()
            .map(|p| [p.eye[0] - 150.0, p.eye[1], p.eye[2] - 200.0])
            .collect();
        let eyes: Vec<[f64; 3]> = poses.iter().map(|p| p.eye).collect();
        assert_eq!(eyes, shifted);
        assert_eq!(
            orbit_length_around([-150.0, -200.0, 150.0, 200.0]),
            500.0 * std::f64::consts::PI
        );
    }
}
