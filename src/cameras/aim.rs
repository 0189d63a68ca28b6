//! Aim ranges + a seeded stream → the drawn heading, pitch, roll and height of one frame,
//! and the pose they give from a point on the ground and a direction.
//!
//! Angles become directions through `libm`'s sine and cosine: pure Rust, so every platform
//! computes the same bits (the platform's own `sin`/`cos` may differ in the last bit).

use rand::Rng;
use serde::{Deserialize, Serialize};

use super::{CameraPose, mm};
use crate::model::PoseAngles;
use crate::model::geometry::cos_sin_deg;
use crate::spec::{CameraPath, CameraSpec, ValueRange};

/// Ranges of a moving camera's aim, drawn per frame (degrees; height in metres).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Aim {
    pub heading: ValueRange,
    pub pitch: ValueRange,
    pub roll: ValueRange,
    pub height: ValueRange,
}

impl Aim {
    /// The camera's ranges, with its path's defaults for those it leaves out: roads look
    /// down the lane ([`ROAD_PITCH`](super::ROAD_PITCH) down); sidewalks look around,
    /// from the street on the left to the shop fronts on the right; objects turn the aim a
    /// little off the object so it is not always in the centre.
    pub fn of(camera: &CameraSpec) -> Aim {
        let (heading, pitch) = match camera.path {
            CameraPath::Roads | CameraPath::Orbit => {
                (ValueRange::Fixed(0.0), ValueRange::Fixed(super::ROAD_PITCH))
            }
            CameraPath::Sidewalks => (
                ValueRange::Between([-120.0, 120.0]),
                ValueRange::Between([-10.0, 10.0]),
            ),
            CameraPath::Objects => (
                ValueRange::Between([-15.0, 15.0]),
                ValueRange::Between([-8.0, 8.0]),
            ),
        };
        Aim {
            heading: camera.heading.unwrap_or(heading),
            pitch: camera.pitch.unwrap_or(pitch),
            roll: camera.roll.unwrap_or(ValueRange::Fixed(0.0)),
            height: camera.height,
        }
    }

    /// Whether every range is finite and heights are positive.
    pub fn is_valid(&self) -> bool {
        [self.heading, self.pitch, self.roll, self.height]
            .iter()
            .all(|r| r.is_finite())
            && self.height.ends()[0] > 0.0
            && self.pitch.ends()[0] > -90.0
            && self.pitch.ends()[1] < 90.0
    }

    /// One frame's angles: four draws in a fixed order (heading, pitch, roll, height), each
    /// rounded to a thousandth so the written record gives back the same pose.
    pub fn draw(&self, stream: &mut impl Rng) -> PoseAngles {
        let mut next = |range: ValueRange| mm(range.at(unit(stream.next_u64())));
        PoseAngles {
            heading: next(self.heading),
            pitch: next(self.pitch),
            roll: next(self.roll),
            height: next(self.height),
        }
    }
}

/// A uniform number in `[0, 1)` from 53 random bits, computed the same on every platform.
pub(super) fn unit(bits: u64) -> f64 {
    ((bits >> 11) as f64) * (1.0 / (1u64 << 53) as f64)
}

/// The pose of an eye at `ground` (`[x, z]`, metres) and `angles.height`, turned
/// `angles.heading` to the right of the horizontal unit direction `dir` (`[x, z]`),
/// pitched `angles.pitch` up from `base_pitch` (`(cos, sin)` of the pitch `dir` already
/// has: the horizontal for a walk, the line of sight for an aimed camera) and rolled by
/// `angles.roll`; the target is `look` metres ahead.
pub(super) fn aimed_pose(
    ground: [f64; 2],
    dir: [f64; 2],
    base_pitch: (f64, f64),
    angles: PoseAngles,
    look: f64,
) -> CameraPose {
    let (ch, sh) = cos_sin_deg(angles.heading);
    // Right of `dir` (x east, z south): clockwise seen from above.
    let right = [-dir[1], dir[0]];
    let h = [ch * dir[0] + sh * right[0], ch * dir[1] + sh * right[1]];
    let (cp, sp) = cos_sin_deg(angles.pitch);
    let (cp, sp) = (
        base_pitch.0 * cp - base_pitch.1 * sp,
        base_pitch.1 * cp + base_pitch.0 * sp,
    );
    let forward = [cp * h[0], sp, cp * h[1]];
    // The level camera's right and up, then the roll turns up towards right.
    let right0 = [-h[1], 0.0, h[0]];
    let up0 = [-sp * h[0], cp, -sp * h[1]];
    let (cr, sr) = cos_sin_deg(angles.roll);
    let up: [f64; 3] = std::array::from_fn(|k| micro(cr * up0[k] + sr * right0[k]));
    let eye = [ground[0], angles.height, ground[1]];
    CameraPose {
        eye: eye.map(mm),
        target: std::array::from_fn(|k| mm(eye[k] + look * forward[k])),
        up,
        angles: Some(angles),
        time: None,
    }
}

/// `v` rounded to six decimals, with `-0` made `0`: unit vectors print short and stable.
fn micro(v: f64) -> f64 {
    let r = (v * 1e6).round() / 1e6;
    if r == 0.0 { 0.0 } else { r }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn angles(heading: f64, pitch: f64, roll: f64) -> PoseAngles {
        PoseAngles {
            heading,
            pitch,
            roll,
            height: 1.5,
        }
    }

    #[test]
    fn heading_turns_right_pitch_up_and_roll_tilts_up_to_the_right() {
        let level = (1.0, 0.0);
        // Driving east, turned 90° right: looking south (+z).
        let p = aimed_pose(
            [10.0, 20.0],
            [1.0, 0.0],
            level,
            angles(90.0, 0.0, 0.0),
            10.0,
        );
        assert_eq!(p.eye, [10.0, 1.5, 20.0]);
        assert_eq!(p.target, [10.0, 1.5, 30.0]);
        assert_eq!(p.up, [0.0, 1.0, 0.0]);
        // Pitched up 90° − a little: the target is nearly straight above.
        let p = aimed_pose([0.0, 0.0], [1.0, 0.0], level, angles(0.0, 30.0, 0.0), 2.0);
        assert_eq!(p.target, [1.732, 2.5, 0.0]);
        assert_eq!(p.up, [-0.5, 0.866025, 0.0]);
        // Looking east, rolled 90° clockwise: the camera's up is the world's south (right).
        let p = aimed_pose([0.0, 0.0], [1.0, 0.0], level, angles(0.0, 0.0, 90.0), 2.0);
        assert_eq!(p.up, [0.0, 0.0, 1.0]);
        assert_eq!(p.angles, Some(angles(0.0, 0.0, 90.0)));
    }

    #[test]
    fn a_base_pitch_adds_to_the_drawn_pitch() {
        // The line of sight is 30° up; a drawn −30° makes the camera level.
        let base = cos_sin_deg(30.0);
        let p = aimed_pose([0.0, 0.0], [0.0, 1.0], base, angles(0.0, -30.0, 0.0), 4.0);
        assert_eq!(p.target, [0.0, 1.5, 4.0]);
    }

    #[test]
    fn draws_stay_in_their_ranges_and_repeat_per_stream() {
        let aim = Aim {
            heading: ValueRange::Between([-60.0, 60.0]),
            pitch: ValueRange::Fixed(-5.0),
            roll: ValueRange::Between([3.0, -3.0]),
            height: ValueRange::Between([1.4, 1.8]),
        };
        assert!(aim.is_valid());
        for frame in 0..50 {
            let a = aim.draw(&mut crate::rng::stream(1, "t", frame));
            assert_eq!(a, aim.draw(&mut crate::rng::stream(1, "t", frame)));
            assert!((-60.0..=60.0).contains(&a.heading), "{a:?}");
            assert_eq!(a.pitch, -5.0);
            assert!((-3.0..=3.0).contains(&a.roll) && (1.4..=1.8).contains(&a.height));
        }
        let bad = Aim {
            pitch: ValueRange::Fixed(90.0),
            ..aim
        };
        assert!(!bad.is_valid());
    }
}
