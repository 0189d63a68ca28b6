//! The road tour: roads in id order, on the right-hand lane, frames evenly spaced by arc length.

use rand::Rng;
use serde::{Deserialize, Serialize};

use super::aim::{Aim, aimed_pose};
use super::leg::{Leg, legs, map_legs, stations, stations_at};
use super::{CameraPose, mm};
use crate::model::{OsmMap, ParsedLayout};
use crate::rng;
use crate::spec::FrameRule;

/// The default pitch of a road camera, degrees: the look-at point drops a tenth of the
/// look-ahead (atan 0.1 = 5.71°).
pub const ROAD_PITCH: f64 = -5.711;

/// How a camera drives along the roads.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RoadPath {
    /// Frames over the whole tour: a count, or one every so many metres of the tour.
    pub frames: FrameRule,
    /// Heading, pitch, roll and eye height, drawn per frame.
    pub aim: Aim,
    /// How far ahead along the road the camera looks, metres (must be positive).
    pub look_ahead: f64,
    /// Largest target offset across the road and up or down, metres: the yaw/pitch jitter.
    pub jitter: f64,
    /// Distance of the lane from the centre line, right of the driving direction, metres
    /// (clamped to the road surface).
    pub lane_offset: f64,
    /// A timed drive instead of frames spread over the tour ([`Drive`]).
    pub drive: Option<Drive>,
}

/// A timed drive: frame `i` at `i / fps` seconds, `speed · i / fps` metres along the tour.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Drive {
    /// Frames a second (positive, finite).
    pub fps: f64,
    /// Metres a second (positive, finite).
    pub speed: f64,
}

/// Drives along the roads: the path visits roads in id order, driving on the right-hand
/// lane (offset from the centre line by `lane_offset`, right of the driving direction, but
/// never off the road surface), from the road's start, continuing through crossings, to
/// `look_ahead` metres before the road surface ends (the layout border or a dead end, or the
/// far edge of the road a T-junction runs into), so the look-at point never leaves the road.
/// A road too short for that is skipped; if every road is, all are driven whole. Frames are
/// evenly spaced by arc length over the whole tour of length `L` ([`tour_length`]): `n`
/// frames (`frames` as [`FrameRule::frames`] of `L`), frame `i` at `(i + ½)·L/n`. Each
/// frame draws its heading (from the direction of travel), pitch, roll and eye height
/// from `aim` (`rng::stream(seed, "cameras/aim", frame)`); the target is `look_ahead`
/// metres along that view, plus a seeded jitter (`rng::stream(seed, "cameras", frame)`)
/// of up to `jitter` metres across the road and up or down.
///
/// Driving "start to end" is east on horizontal roads (right = south, +z) and south on
/// vertical ones (right = west, −x). Between roads the camera jumps; the jump does not count
/// as arc length. No poses when there are no frames, there is no road of positive length,
/// or a parameter is out of range (`metres_per_pixel` and `look_ahead` must be positive and
/// finite, `jitter` non-negative and finite, `aim` valid ([`Aim::is_valid`]),
/// `lane_offset` finite, a spacing
/// positive and finite).
pub fn road_path(
    layout: &ParsedLayout,
    metres_per_pixel: f64,
    path: &RoadPath,
    seed: u64,
) -> Vec<CameraPose> {
    road_path_draws(layout, metres_per_pixel, path, seed, 1)
        .into_iter()
        .filter_map(|draws| draws.into_iter().next())
        .collect()
}

/// [`road_path`]'s frames, each with `draws` poses (at least one) from the same place:
/// the pose [`road_path`] gives first, then further draws of the aim and the jitter,
/// continuing frame `i`'s two streams. A caller that finds a draw unusable (its view
/// blocked) takes the next one.
pub fn road_path_draws(
    layout: &ParsedLayout,
    metres_per_pixel: f64,
    path: &RoadPath,
    seed: u64,
    draws: usize,
) -> Vec<Vec<CameraPose>> {
    let valid = metres_per_pixel.is_finite() && metres_per_pixel > 0.0 && sound(path);
    if !valid {
        return Vec::new();
    }
    let legs = legs(layout, metres_per_pixel, path.lane_offset, path.look_ahead);
    tour(&legs, path, seed, draws)
}

/// [`road_path_draws`] on a map's roads: each road with a surface driven along its
/// centreline in the way's direction, paved segment by paved segment, on the right-hand
/// lane (`lane_offset` right of the centreline, kept a metre inside the kerb), each run of
/// consecutive paved segments to `look_ahead` metres before it ends (see
/// `leg::map_legs`).
pub fn map_road_path_draws(
    map: &OsmMap,
    path: &RoadPath,
    seed: u64,
    draws: usize,
) -> Vec<Vec<CameraPose>> {
    if !sound(path) {
        return Vec::new();
    }
    let legs = map_legs(map, path.lane_offset, path.look_ahead);
    tour(&legs, path, seed, draws)
}

/// [`map_road_path_draws`]' first draws: a map's [`road_path`].
pub fn map_road_path(map: &OsmMap, path: &RoadPath, seed: u64) -> Vec<CameraPose> {
    map_road_path_draws(map, path, seed, 1)
        .into_iter()
        .filter_map(|draws| draws.into_iter().next())
        .collect()
}

/// Whether `path`'s settings are in range.
fn sound(path: &RoadPath) -> bool {
    path.look_ahead.is_finite()
        && path.look_ahead > 0.0
        && path.jitter.is_finite()
        && path.jitter >= 0.0
        && path.aim.is_valid()
        && path.lane_offset.is_finite()
}

/// The frames along `legs`, `draws` poses each (see [`road_path_draws`]).
fn tour(legs: &[Leg], path: &RoadPath, seed: u64, draws: usize) -> Vec<Vec<CameraPose>> {
    let total: f64 = legs.iter().map(|l| l.length).sum();
    let n = path.frames.frames(total);
    if let Some(drive) = path.drive {
        return timed(legs, total, n, drive, path, seed);
    }
    stations(legs, n)
        .into_iter()
        .zip(0u64..)
        .map(|((eye, dir), i)| {
            let mut aim = rng::stream(seed, "cameras/aim", i);
            let mut jitter = rng::stream(seed, "cameras", i);
            (0..draws.max(1))
                .map(|_| drawn_pose(eye, dir, path, &mut aim, &mut jitter))
                .collect()
        })
        .collect()
}

/// A pose at `eye` driving along `dir`: the aim and the target's jitter drawn from the two
/// streams.
fn drawn_pose(
    eye: [f64; 2],
    dir: [f64; 2],
    path: &RoadPath,
    aim: &mut impl Rng,
    jitter: &mut impl Rng,
) -> CameraPose {
    let angles = path.aim.draw(aim);
    let mut pose = aimed_pose(eye, dir, (1.0, 0.0), angles, path.look_ahead);
    let yaw = signed_unit(jitter.next_u64()) * path.jitter;
    let pitch = signed_unit(jitter.next_u64()) * path.jitter;
    offset_target(&mut pose, dir, [yaw, pitch]);
    pose
}

/// Moves `pose`'s target `yaw_pitch[0]` metres right of the driving direction `dir` and
/// `yaw_pitch[1]` up, to the millimetre.
fn offset_target(pose: &mut CameraPose, dir: [f64; 2], [yaw, pitch]: [f64; 2]) {
    let right = [-dir[1], dir[0]];
    pose.target = [
        mm(pose.target[0] + right[0] * yaw),
        mm(pose.target[1] + pitch),
        mm(pose.target[2] + right[1] * yaw),
    ];
}

/// The `n` frames of a timed drive, one draw each: frame `i` at arc length
/// `start + speed · i / fps` of the tour (`total` metres). The drive stays on one road:
/// a leg long enough for it is drawn, then `start` uniformly on it
/// (`rng::stream(seed, "cameras/drive", 0)`); when no leg is, `start` is drawn over the
/// tour (the drive then runs on from road to road, jumping between them as the tour does,
/// and stops at the tour's end). The aim and the jitter are drawn once, from
/// frame 0's streams, so the camera holds its view; each pose records its time.
fn timed(
    legs: &[Leg],
    total: f64,
    n: u32,
    drive: Drive,
    path: &RoadPath,
    seed: u64,
) -> Vec<Vec<CameraPose>> {
    let sound =
        drive.fps.is_finite() && drive.fps > 0.0 && drive.speed.is_finite() && drive.speed > 0.0;
    if !sound || n == 0 {
        return Vec::new();
    }
    let step = drive.speed / drive.fps;
    let span = step * f64::from(n - 1);
    let mut draw = rng::stream(seed, "cameras/drive", 0);
    // Where each leg starts on the tour, and the legs the whole drive fits on.
    let starts: Vec<f64> = legs
        .iter()
        .scan(0.0, |at, l| {
            let s = *at;
            *at += l.length;
            Some(s)
        })
        .collect();
    let fits: Vec<usize> = (0..legs.len())
        .filter(|&i| legs[i].length >= span)
        .collect();
    let start = if fits.is_empty() {
        unit(draw.next_u64()) * (total - span).max(0.0)
    } else {
        let leg = fits[(unit(draw.next_u64()) * fits.len() as f64) as usize % fits.len()];
        starts[leg] + unit(draw.next_u64()) * (legs[leg].length - span)
    };
    let arcs: Vec<f64> = (0..n)
        .map(|i| (start + step * f64::from(i)).min(total))
        .collect();
    let (mut aim, mut jitter) = (
        rng::stream(seed, "cameras/aim", 0),
        rng::stream(seed, "cameras", 0),
    );
    let angles = path.aim.draw(&mut aim);
    let yaw_pitch = [
        signed_unit(jitter.next_u64()) * path.jitter,
        signed_unit(jitter.next_u64()) * path.jitter,
    ];
    stations_at(legs, &arcs)
        .into_iter()
        .zip(0u32..)
        .map(|((eye, dir), i)| {
            let mut pose = aimed_pose(eye, dir, (1.0, 0.0), angles, path.look_ahead);
            offset_target(&mut pose, dir, yaw_pitch);
            pose.time = Some(f64::from(i) / drive.fps);
            vec![pose]
        })
        .collect()
}

/// A uniform number in `[0, 1)` from 53 random bits, computed the same on every platform.
fn unit(bits: u64) -> f64 {
    ((bits >> 11) as f64) * (1.0 / (1u64 << 53) as f64)
}

/// Length in metres of the tour [`road_path`] drives with this `look_ahead`: the sum of
/// the legs' lengths, each road trimmed as [`road_path`] says. A [`FrameRule::Spacing`]
/// takes its frame count from this length.
pub fn tour_length(layout: &ParsedLayout, metres_per_pixel: f64, look_ahead: f64) -> f64 {
    let valid = metres_per_pixel.is_finite()
        && metres_per_pixel > 0.0
        && look_ahead.is_finite()
        && look_ahead > 0.0;
    if !valid {
        return 0.0;
    }
    legs(layout, metres_per_pixel, 0.0, look_ahead)
        .iter()
        .map(|l| l.length)
        .sum()
}

/// A uniform number in `[-1, 1)` from 53 random bits, computed the same on every platform.
fn signed_unit(bits: u64) -> f64 {
    ((bits >> 11) as f64) * (1.0 / (1u64 << 52) as f64) - 1.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::geometry::cos_sin_deg;
    use crate::model::{Axis, Road};
    use crate::spec::ValueRange;

    const M: f64 = 0.5;

    /// A 200 × 160 px layout: one horizontal road across (line at y 100.5, surface 85–116),
    /// one vertical road down (line at x 60.5, surface 45–76) crossing it.
    fn layout() -> ParsedLayout {
        ParsedLayout {
            width: 200,
            height: 160,
            blocks: Vec::new(),
            roads: vec![
                Road {
                    id: 1,
                    axis: Axis::Vertical,
                    start: 0.0,
                    end: 160.0,
                    line: 60.5,
                    edges: [45.0, 76.0],
                },
                Road {
                    id: 0,
                    axis: Axis::Horizontal,
                    start: 0.0,
                    end: 200.0,
                    line: 100.5,
                    edges: [85.0, 116.0],
                },
            ],
        }
    }

    /// A level aim at 1.6 m: the target exactly `look_ahead` ahead.
    fn level() -> Aim {
        Aim {
            heading: ValueRange::Fixed(0.0),
            pitch: ValueRange::Fixed(0.0),
            roll: ValueRange::Fixed(0.0),
            height: ValueRange::Fixed(1.6),
        }
    }

    fn path(frames: u32) -> RoadPath {
        RoadPath {
            frames: FrameRule::Count(frames),
            aim: level(),
            look_ahead: 10.0,
            jitter: 0.5,
            lane_offset: 3.0,
            drive: None,
        }
    }

    #[test]
    fn further_draws_start_with_the_road_paths_own_pose() {
        let mut p = path(12);
        p.aim.heading = ValueRange::Between([-80.0, 80.0]);
        let poses = road_path(&layout(), M, &p, 7);
        let draws = road_path_draws(&layout(), M, &p, 7, 3);
        assert_eq!(draws.len(), poses.len());
        for (frame, pose) in draws.iter().zip(&poses) {
            assert_eq!(frame.len(), 3);
            assert_eq!(&frame[0], pose);
            // The same place, other aims.
            assert!(frame.iter().all(|d| d.eye == pose.eye));
            assert_ne!(frame[1].target, frame[0].target);
        }
        // At least one draw is always made.
        assert!(
            road_path_draws(&layout(), M, &p, 7, 0)
                .iter()
                .all(|f| f.len() == 1)
        );
    }

    #[test]
    fn stays_on_the_right_lane_inside_the_layout() {
        let poses = road_path(&layout(), M, &path(40), 7);
        assert_eq!(poses.len(), 40);
        // Horizontal road 0 first (id order), 100 m long, then vertical road 1, 80 m long,
        // each driven up to 10 m (the look-ahead) before the border.
        let (mut east, mut south) = (0, 0);
        for p in &poses {
            assert!((0.0..=90.0).contains(&p.eye[0]) && (0.0..=70.0).contains(&p.eye[2]));
            // The look-at point stays inside the layout, give or take the jitter across.
            assert!(p.target[0] <= 100.0 && p.target[2] <= 80.0, "{p:?}");
            assert_eq!(p.eye[1], 1.6);
            if p.eye[2] == 100.5 * M + 3.0 {
                // Driving east: the lane is south of the centre line, the target ahead.
                assert!((p.target[0] - p.eye[0] - 10.0).abs() < 1e-9, "{p:?}");
                assert!((p.target[2] - p.eye[2]).abs() <= 0.5 + 1e-9);
                east += 1;
            } else {
                // Driving south: the lane is west of the centre line.
                assert_eq!(p.eye[0], 60.5 * M - 3.0, "{p:?}");
                assert!((p.target[2] - p.eye[2] - 10.0).abs() < 1e-9, "{p:?}");
                assert!((p.target[0] - p.eye[0]).abs() <= 0.5 + 1e-9);
                south += 1;
            }
            let drop = p.eye[1] - p.target[1];
            assert!((-0.5 - 1e-9..=0.5 + 1e-9).contains(&drop), "{p:?}");
        }
        // 90 + 70 m over 40 frames: 4 m apart, so 90 m of road 0 hold frames 0..22.
        assert_eq!((east, south), (22, 18));
        assert!(poses[..22].iter().all(|p| p.eye[2] == 53.25));
    }

    #[test]
    fn frames_are_evenly_spaced_by_arc_length() {
        let poses = road_path(&layout(), M, &path(32), 7);
        let step = 160.0 / 32.0;
        assert_eq!(poses[0].eye[0], step / 2.0);
        for pair in poses.windows(2) {
            let (a, b) = (pair[0].eye, pair[1].eye);
            if a[2] == b[2] || a[0] == b[0] {
                let d = (b[0] - a[0]).abs() + (b[2] - a[2]).abs();
                assert!((d - step).abs() < 2e-3, "{a:?} → {b:?}");
            }
        }
        // The jump between roads adds no arc length: frame 18 sits at s = 18.5 · 5 =
        // 92.5 m, which is 2.5 m into road 1 (road 0 is driven for 90 m).
        assert_eq!(poses[17].eye[0], 87.5);
        assert_eq!(poses[18].eye[2], 2.5);
    }

    #[test]
    fn poses_are_reproducible_per_seed() {
        let a = road_path(&layout(), M, &path(25), 11);
        assert_eq!(a, road_path(&layout(), M, &path(25), 11));
        let b = road_path(&layout(), M, &path(25), 12);
        assert_ne!(a, b);
        // The seed moves only the target, never the eye.
        assert!(a.iter().zip(&b).all(|(p, q)| p.eye == q.eye));
        let still = RoadPath {
            jitter: 0.0,
            ..path(25)
        };
        let calm = road_path(&layout(), M, &still, 11);
        assert_eq!(calm, road_path(&layout(), M, &still, 12));
        assert!(calm.iter().all(|p| p.target[1] == 1.6));
    }

    #[test]
    fn lane_offset_is_clamped_to_the_road_surface() {
        let wide = RoadPath {
            lane_offset: 100.0,
            ..path(40)
        };
        let poses = road_path(&layout(), M, &wide, 1);
        assert_eq!(poses[0].eye[2], 116.0 * M);
        assert_eq!(poses[39].eye[0], 45.0 * M);
    }

    #[test]
    fn bad_parameters_give_no_poses() {
        let cases: [(&str, f64, RoadPath); 7] = [
            ("no frames", M, path(0)),
            ("zero scale", 0.0, path(5)),
            ("NaN scale", f64::NAN, path(5)),
            (
                "no look-ahead",
                M,
                RoadPath {
                    look_ahead: 0.0,
                    ..path(5)
                },
            ),
            (
                "negative jitter",
                M,
                RoadPath {
                    jitter: -1.0,
                    ..path(5)
                },
            ),
            (
                "infinite height",
                M,
                RoadPath {
                    aim: Aim {
                        height: ValueRange::Between([1.0, f64::INFINITY]),
                        ..level()
                    },
                    ..path(5)
                },
            ),
            (
                "NaN lane",
                M,
                RoadPath {
                    lane_offset: f64::NAN,
                    ..path(5)
                },
            ),
        ];
        for (name, m, p) in cases {
            assert!(road_path(&layout(), m, &p, 1).is_empty(), "{name}");
        }
        let no_roads = ParsedLayout {
            roads: Vec::new(),
            ..layout()
        };
        assert!(road_path(&no_roads, M, &path(5), 1).is_empty());
    }

    #[test]
    fn tour_length_sums_the_trimmed_roads() {
        // 100 m and 80 m of road, each less the 10 m look-ahead.
        assert_eq!(tour_length(&layout(), M, 10.0), 160.0);
        // Neither road is longer than 100 m of look-ahead: both are driven whole.
        assert_eq!(tour_length(&layout(), M, 100.0), 180.0);
        // Only road 0 is longer than 90 m: it alone is driven, for 10 m.
        assert_eq!(tour_length(&layout(), M, 90.0), 10.0);
        assert_eq!(tour_length(&layout(), -1.0, 10.0), 0.0);
        assert_eq!(tour_length(&layout(), M, 0.0), 0.0);
    }

    #[test]
    fn spacing_sets_the_frame_count_from_the_tour() {
        let spaced = |spacing: f64| RoadPath {
            frames: FrameRule::Spacing(spacing),
            ..path(1)
        };
        // The tour is 160 m: a frame every 4 m is 40 frames, the same poses as asking for 40.
        let poses = road_path(&layout(), M, &spaced(4.0), 7);
        assert_eq!(poses, road_path(&layout(), M, &path(40), 7));
        // ⌊160 / 7⌋ = 22 frames, 160/22 ≈ 7.27 m apart; a spacing longer than the tour
        // still gives one frame, at its middle.
        assert_eq!(road_path(&layout(), M, &spaced(7.0), 7).len(), 22);
        let one = road_path(&layout(), M, &spaced(1000.0), 7);
        assert_eq!(one.len(), 1);
        assert_eq!(one[0].eye[0], 80.0);
        // A spacing of a millimetre would ask for 160,000 frames: capped.
        assert_eq!(
            road_path(&layout(), M, &spaced(0.001), 7).len(),
            crate::spec::MAX_FRAMES as usize
        );
        assert!(road_path(&layout(), M, &spaced(0.0), 7).is_empty());
    }

    #[test]
    fn the_last_frames_look_down_the_road_not_past_its_end() {
        let poses = road_path(
            &layout(),
            M,
            &RoadPath {
                jitter: 0.0,
                ..path(160)
            },
            3,
        );
        // A frame a metre: the last on road 0 looks at x = 89.5 + 10 m, just short of the
        // border at 100 m; the last on road 1 at z = 69.5 + 10 m, short of 80 m.
        assert_eq!((poses[89].eye[0], poses[89].target[0]), (89.5, 99.5));
        assert_eq!((poses[159].eye[2], poses[159].target[2]), (69.5, 79.5));
    }

    #[test]
    fn a_side_road_drives_on_into_the_road_it_meets() {
        // Road 1 now runs down from the top border into road 0 and ends on its line
        // (y 101 px): its surface goes on to road 0's far edge at y 116 px, 58 m.
        let mut t = layout();
        t.roads[0].end = 101.0;
        let poses = road_path(&t, M, &path(200), 5);
        let last = poses.last().unwrap();
        // 90 + 48 m over 200 frames: the last is half a step (0.345 m) short of 48 m.
        assert!((last.eye[2] - (58.0 - 10.0)).abs() < 0.35, "{last:?}");
        assert!(last.target[2] <= 58.0, "{last:?}");
    }

    #[test]
    fn roads_all_shorter_than_the_look_ahead_are_driven_whole() {
        let far = RoadPath {
            look_ahead: 100.0,
            jitter: 0.0,
            ..path(180)
        };
        let poses = road_path(&layout(), M, &far, 1);
        assert_eq!(poses.len(), 180);
        assert_eq!(poses[99].eye[0], 99.5);
        assert_eq!(poses[179].eye[2], 79.5);
    }

    #[test]
    fn ranged_aims_look_around_from_the_same_eyes() {
        let ranged = RoadPath {
            aim: Aim {
                heading: ValueRange::Between([-60.0, 60.0]),
                pitch: ValueRange::Between([-10.0, 5.0]),
                roll: ValueRange::Between([-4.0, 4.0]),
                height: ValueRange::Between([1.2, 2.0]),
            },
            jitter: 0.0,
            ..path(40)
        };
        let poses = road_path(&layout(), M, &ranged, 9);
        let plain = road_path(&layout(), M, &path(40), 9);
        let (mut left, mut right) = (0, 0);
        for (p, q) in poses.iter().zip(&plain) {
            let a = p.angles.unwrap();
            assert_eq!([p.eye[0], p.eye[2]], [q.eye[0], q.eye[2]]);
            assert_eq!(p.eye[1], a.height);
            assert!((1.2..=2.0).contains(&a.height) && (-4.0..=4.0).contains(&a.roll));
            assert!((-60.0..=60.0).contains(&a.heading) && (-10.0..=5.0).contains(&a.pitch));
            // The view turns from the road's direction by the heading: its cosine is the
            // horizontal view's part along the road.
            let d = [p.target[0] - p.eye[0], p.target[2] - p.eye[2]];
            let along = if p.eye[2] == 100.5 * M + 3.0 {
                d[0]
            } else {
                d[1]
            };
            let (ch, _) = cos_sin_deg(a.heading);
            let (cp, _) = cos_sin_deg(a.pitch);
            assert!((along - 10.0 * ch * cp).abs() < 2e-3, "{p:?}");
            if a.heading < 0.0 {
                left += 1
            } else {
                right += 1
            }
        }
        assert!(left > 5 && right > 5, "{left} {right}");
        // Another camera seed draws other angles at the same eyes.
        let other = road_path(&layout(), M, &ranged, 10);
        assert!(other.iter().zip(&poses).any(|(p, q)| p.angles != q.angles));
    }

    #[test]
    fn a_timed_drive_steps_speed_over_fps_with_one_aim_and_its_times() {
        let mut p = path(12);
        p.aim.heading = ValueRange::Between([-30.0, 30.0]);
        p.drive = Some(Drive {
            fps: 10.0,
            speed: 25.0 / 3.6,
        });
        let poses = road_path(&layout(), M, &p, 5);
        assert_eq!(poses.len(), 12);
        for (i, pair) in poses.windows(2).enumerate() {
            let (a, b) = (pair[0], pair[1]);
            let step = ((b.eye[0] - a.eye[0]).powi(2) + (b.eye[2] - a.eye[2]).powi(2)).sqrt();
            // 0.694 m a frame, to the millimetre the poses are rounded to.
            assert!((step - 25.0 / 36.0).abs() < 2e-3, "frame {i}: {step}");
            assert_eq!(a.angles, b.angles, "one aim for the drive");
            assert_eq!(b.time, Some((i + 1) as f64 / 10.0));
        }
        assert_eq!(poses[0].time, Some(0.0));
        // The same seed, the same drive; another seed starts elsewhere.
        assert_eq!(poses, road_path(&layout(), M, &p, 5));
        assert_ne!(poses[0].eye, road_path(&layout(), M, &p, 6)[0].eye);
        // Untimed paths carry no time.
        assert!(
            road_path(&layout(), M, &path(12), 5)
                .iter()
                .all(|q| q.time.is_none())
        );
    }

    #[test]
    fn a_timed_drive_longer_than_the_tour_stops_at_its_end() {
        let mut p = path(400);
        p.drive = Some(Drive {
            fps: 1.0,
            speed: 20.0,
        });
        let poses = road_path(&layout(), M, &p, 1);
        assert_eq!(poses.len(), 400);
        assert_eq!(poses[398].eye, poses[399].eye, "parked at the tour's end");
        let bad = RoadPath {
            drive: Some(Drive {
                fps: 0.0,
                speed: 1.0,
            }),
            ..path(3)
        };
        assert!(road_path(&layout(), M, &bad, 1).is_empty());
    }
}
