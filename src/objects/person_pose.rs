//! A person's [`Pose`], height, build and stride → its [`Skeleton`]: the joints of a simple
//! rig in the person's own frame, the 17 COCO keypoints among them, from which
//! `person.rs` builds the figure's limbs (so a keypoint always lies on the mesh).
//!
//! Coordinates are a [`super::vehicle_parts::Frame`]'s local `(u, y, v)`: `u` forward, `y`
//! up from the soles, `v` to the person's right; the person's left is `−v`. `Frame::at`
//! maps a joint into the world.
//!
//! Legs swing in the `(u, y)` plane (the left leg forward by the stride, the right back),
//! their knees bent a little forward. Each arm is a two-bone chain (upper arm 0.17 h,
//! forearm 0.14 h, then the hand 0.065 h): a swinging or hanging arm is laid out by its
//! angles, any other by a wrist target and the way its elbow points, solved in closed form
//! ([`two_bone`]).

use crate::model::geometry::{cross, dot, normalize, sub, trig};

/// What a person is doing: walking or standing, and what the arms do. Its
/// [`Pose::name`] is the person's `pose` attribute.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pose {
    /// Walking, arms swinging against the legs.
    Walking,
    /// Walking, looking at a phone held before the chest.
    WalkingPhone,
    /// Walking, a phone held to the ear.
    WalkingCall,
    /// Walking, a bag hanging from one hand.
    WalkingBag,
    /// Walking, hands in the trouser pockets.
    WalkingPockets,
    /// Standing, arms hanging.
    Standing,
    /// Standing, looking at a phone.
    StandingPhone,
    /// Standing, a phone held to the ear.
    StandingCall,
    /// Standing, a bag in one hand.
    StandingBag,
    /// Standing, arms crossed before the chest.
    ArmsCrossed,
    /// Standing, hands in the trouser pockets.
    HandsInPockets,
}

/// What one arm does.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Arm {
    /// Hanging from the shoulder, swung this many degrees forward (negative: back).
    Swing(f64),
    /// Holding a phone before the chest.
    Phone,
    /// Holding a phone to the ear.
    Call,
    /// Crossed over the other before the chest.
    Crossed,
    /// Hand in the trouser pocket.
    Pocket,
    /// Hanging nearly straight, holding a bag's handles.
    Bag,
}

/// Something a hand holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Prop {
    Phone,
    Bag,
}

impl Pose {
    /// Walking poses and their weights (they add to 1).
    pub const WALKING: [(Pose, f64); 5] = [
        (Pose::Walking, 0.5),
        (Pose::WalkingPhone, 0.15),
        (Pose::WalkingCall, 0.07),
        (Pose::WalkingBag, 0.18),
        (Pose::WalkingPockets, 0.1),
    ];
    /// Standing poses and their weights (they add to 1).
    pub const STANDING: [(Pose, f64); 6] = [
        (Pose::Standing, 0.3),
        (Pose::StandingPhone, 0.2),
        (Pose::StandingCall, 0.1),
        (Pose::StandingBag, 0.1),
        (Pose::ArmsCrossed, 0.15),
        (Pose::HandsInPockets, 0.15),
    ];

    /// The pose of `poses` that `t` (uniform in [0, 1)) falls on by weight.
    pub fn pick(poses: &[(Pose, f64)], t: f64) -> Pose {
        let mut left = t;
        for &(pose, weight) in poses {
            if left < weight {
                return pose;
            }
            left -= weight;
        }
        poses[poses.len() - 1].0
    }

    /// The snake_case name the `pose` attribute carries.
    pub fn name(self) -> &'static str {
        match self {
            Pose::Walking => "walking",
            Pose::WalkingPhone => "walking_phone",
            Pose::WalkingCall => "walking_call",
            Pose::WalkingBag => "walking_bag",
            Pose::WalkingPockets => "walking_pockets",
            Pose::Standing => "standing",
            Pose::StandingPhone => "standing_phone",
            Pose::StandingCall => "standing_call",
            Pose::StandingBag => "standing_bag",
            Pose::ArmsCrossed => "arms_crossed",
            Pose::HandsInPockets => "hands_in_pockets",
        }
    }

    /// What the hand on `holding` side holds, if anything.
    pub fn prop(self) -> Option<Prop> {
        match self {
            Pose::WalkingPhone | Pose::WalkingCall | Pose::StandingPhone | Pose::StandingCall => {
                Some(Prop::Phone)
            }
            Pose::WalkingBag | Pose::StandingBag => Some(Prop::Bag),
            _ => None,
        }
    }

    /// The two arms, left then right, of a figure swinging its arms `swing` degrees (the
    /// right arm forward), a prop held in the hand on side `holding` (−1 left, 1 right).
    fn arms(self, swing: f64, holding: f64) -> [Arm; 2] {
        let free = [Arm::Swing(-swing), Arm::Swing(swing)];
        let busy = |arm: Arm| {
            if holding < 0.0 {
                [arm, free[1]]
            } else {
                [free[0], arm]
            }
        };
        match self {
            Pose::Walking | Pose::Standing => free,
            Pose::WalkingPhone | Pose::StandingPhone => busy(Arm::Phone),
            Pose::WalkingCall | Pose::StandingCall => busy(Arm::Call),
            Pose::WalkingBag | Pose::StandingBag => busy(Arm::Bag),
            Pose::WalkingPockets | Pose::HandsInPockets => [Arm::Pocket, Arm::Pocket],
            Pose::ArmsCrossed => [Arm::Crossed, Arm::Crossed],
        }
    }
}

/// COCO keypoint indices of the body joints, the left one; the right one follows it.
pub const SHOULDER: usize = 5;
pub const ELBOW: usize = 7;
pub const WRIST: usize = 9;
pub const HIP: usize = 11;
pub const KNEE: usize = 13;
pub const ANKLE: usize = 15;

/// Where a figure's joints are, in its own frame (metres).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Skeleton {
    /// The 17 COCO keypoints in COCO's order: nose, left and right eye, left and right ear,
    /// then left and right shoulder, elbow, wrist, hip, knee and ankle.
    pub keypoints: [[f64; 3]; 17],
    /// Where each hand ends (fingertips), left then right.
    pub hand_tips: [[f64; 3]; 2],
    /// Where the held prop hangs or lies: from the holding hand's tip, along this unit
    /// direction.
    pub prop_direction: [f64; 3],
}

/// Upper arm, forearm and hand lengths, in heights.
const UPPER_ARM: f64 = 0.17;
const FOREARM: f64 = 0.14;
const HAND: f64 = 0.065;
/// Shoulder joints: height, and distance out from the spine in widths `s`.
const SHOULDER_Y: f64 = 0.8;
const SHOULDER_V: f64 = 0.225;
/// Hip joints: height, and distance out from the spine in widths.
const HIP_Y: f64 = 0.5;
const HIP_V: f64 = 0.09;
/// Ankle height, in heights.
const ANKLE_Y: f64 = 0.045;

/// The skeleton of a figure `h` tall and `s` wide (`h / 1.75` times its build) in `pose`,
/// legs swung `stride` degrees, a prop in the hand on side `holding` (−1 left, 1 right).
pub fn skeleton(pose: Pose, h: f64, s: f64, stride: f64, holding: f64) -> Skeleton {
    let mut k = [[0.0; 3]; 17];
    // Face: the head's centre is at (0.01 s, 0.935 h), 0.2 s long and 0.15 s across.
    let head_u = 0.01 * s;
    k[0] = [head_u + 0.09 * s, 0.925 * h, 0.0];
    for (i, side) in [(0, -1.0), (1, 1.0)] {
        k[1 + i] = [head_u + 0.075 * s, 0.945 * h, side * 0.035 * s];
        k[3 + i] = [head_u, 0.935 * h, side * 0.075 * s];
    }
    // Legs: the left forward by `stride`, the right back.
    for (i, side, swing) in [(0, -1.0, stride), (1, 1.0, -stride)] {
        let v = side * HIP_V * s;
        let (cos, sin) = trig::cos_sin_deg(swing);
        let ankle_u = (HIP_Y - ANKLE_Y) * h * sin / cos;
        let bend = 0.012 * h
            + if swing < 0.0 {
                0.03 * h * sin.abs()
            } else {
                0.0
            };
        k[HIP + i] = [0.0, HIP_Y * h, v];
        k[ANKLE + i] = [ankle_u, ANKLE_Y * h, v];
        k[KNEE + i] = [ankle_u / 2.0 + bend, (HIP_Y + ANKLE_Y) * h / 2.0, v];
    }
    let mut hand_tips = [[0.0; 3]; 2];
    let mut prop_direction = [0.0, -1.0, 0.0];
    // The arms swing three quarters as far as the legs.
    for (i, arm) in pose.arms(0.75 * stride, holding).into_iter().enumerate() {
        let side = if i == 0 { -1.0 } else { 1.0 };
        let shoulder = [0.0, SHOULDER_Y * h, side * SHOULDER_V * s];
        let [elbow, wrist, tip] = arm_joints(arm, shoulder, side, h, s);
        k[SHOULDER + i] = shoulder;
        k[ELBOW + i] = elbow;
        k[WRIST + i] = wrist;
        hand_tips[i] = tip;
        if side == holding {
            prop_direction = match arm {
                Arm::Bag => [0.0, -1.0, 0.0],
                _ => normalize(sub(tip, wrist)).unwrap_or([0.0, 1.0, 0.0]),
            };
        }
    }
    Skeleton {
        keypoints: k,
        hand_tips,
        prop_direction,
    }
}

/// Elbow, wrist and fingertips of `arm` hanging from `shoulder` on `side` (−1 left).
fn arm_joints(arm: Arm, shoulder: [f64; 3], side: f64, h: f64, s: f64) -> [[f64; 3]; 3] {
    let (upper, fore, hand) = (UPPER_ARM * h, FOREARM * h, HAND * h);
    // A hanging arm swung `angle` degrees forward, `out` (a slope) away from the body, the
    // forearm `bend` degrees and a share of a forward swing further forward.
    let hang = |angle: f64, out: f64, bend: f64| {
        let (c, sn) = trig::cos_sin_deg(angle);
        let up = normalize([sn, -c, side * out]).unwrap_or([0.0, -1.0, 0.0]);
        let elbow = along(shoulder, up, upper);
        let (c, sn) = trig::cos_sin_deg(angle + bend + 0.3 * angle.max(0.0));
        let d = normalize([sn, -c, side * out]).unwrap_or([0.0, -1.0, 0.0]);
        let wrist = along(elbow, d, fore);
        [elbow, wrist, along(wrist, d, hand)]
    };
    // A wrist reaching for `target`, its elbow pointing along `pole`, the hand along
    // `hand_dir` (None: along the forearm).
    let reach = |target: [f64; 3], pole: [f64; 3], hand_dir: Option<[f64; 3]>| {
        let (elbow, wrist) = two_bone(shoulder, target, [upper, fore], pole);
        let d = hand_dir
            .and_then(normalize)
            .or_else(|| normalize(sub(wrist, elbow)))
            .unwrap_or([0.0, -1.0, 0.0]);
        [elbow, wrist, along(wrist, d, hand)]
    };
    match arm {
        Arm::Swing(angle) => hang(angle, 0.02, 8.0),
        Arm::Bag => hang(0.0, 0.1, 0.0),
        Arm::Phone => reach(
            [0.24 * s, 0.68 * h, side * 0.07 * s],
            [-0.3, -1.0, side],
            Some([0.5, 0.45, -side * 0.3]),
        ),
        Arm::Call => reach(
            [0.03 * s, 0.86 * h, side * 0.13 * s],
            [0.4, -1.0, side],
            Some([0.1, 1.0, -side * 0.35]),
        ),
        Arm::Crossed => reach(
            [(0.2 + side * 0.02) * s, 0.66 * h, -side * 0.1 * s],
            [0.2, -1.0, side],
            None,
        ),
        Arm::Pocket => reach(
            [0.07 * s, 0.53 * h, side * 0.21 * s],
            [-1.0, -0.3, side * 0.8],
            Some([0.25, -1.0, -side * 0.1]),
        ),
    }
}

/// `p + d · len`.
pub fn along(p: [f64; 3], d: [f64; 3], len: f64) -> [f64; 3] {
    [p[0] + d[0] * len, p[1] + d[1] * len, p[2] + d[2] * len]
}

/// Elbow and wrist of a chain of two bones (`lengths`) from `root` reaching for `target`
/// (pulled in to 99.9 % of the chain's reach when beyond it), the elbow bent towards
/// `pole`. Closed form: the elbow lies on the circle of points `lengths[0]` from the root
/// and `lengths[1]` from the wrist, where the pole's direction meets it.
fn two_bone(
    root: [f64; 3],
    target: [f64; 3],
    lengths: [f64; 2],
    pole: [f64; 3],
) -> ([f64; 3], [f64; 3]) {
    let [a, b] = lengths;
    let d = sub(target, root);
    let Some(dir) = normalize(d) else {
        return (along(root, [0.0, -1.0, 0.0], a), root);
    };
    let dist = dot(d, d)
        .sqrt()
        .clamp((a - b).abs() * 1.001, 0.999 * (a + b));
    let wrist = along(root, dir, dist);
    // Distance along the root→wrist line to the elbow's circle, and its radius.
    let x = (a * a - b * b + dist * dist) / (2.0 * dist);
    let radius = (a * a - x * x).max(0.0).sqrt();
    let side = sub(pole, dir.map(|c| c * dot(pole, dir)));
    let side = normalize(side)
        .or_else(|| normalize(cross(dir, [0.0, 0.0, 1.0])))
        .unwrap_or([1.0, 0.0, 0.0]);
    let elbow = along(along(root, dir, x), side, radius);
    (elbow, wrist)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_bones_keep_their_lengths_and_bend_towards_the_pole() {
        let root = [0.0, 1.4, 0.2];
        for (target, pole) in [
            ([0.3, 1.1, 0.1], [0.0, -1.0, 1.0]),
            ([0.1, 1.6, 0.2], [1.0, 0.0, 0.0]),
            ([2.0, 0.0, 0.0], [0.0, -1.0, 0.0]),
        ] {
            let (elbow, wrist) = two_bone(root, target, [0.3, 0.25], pole);
            let len = |p: [f64; 3], q: [f64; 3]| dot(sub(p, q), sub(p, q)).sqrt();
            assert!((len(root, elbow) - 0.3).abs() < 1e-9, "{elbow:?}");
            assert!((len(elbow, wrist) - 0.25).abs() < 1e-9, "{wrist:?}");
            // The elbow sits on the pole's side of the root–wrist line.
            let mid = [
                (root[0] + wrist[0]) / 2.0,
                (root[1] + wrist[1]) / 2.0,
                (root[2] + wrist[2]) / 2.0,
            ];
            assert!(dot(sub(elbow, mid), pole) > 0.0, "{elbow:?}");
        }
    }

    #[test]
    fn pose_weights_add_to_one_and_pick_every_pose() {
        for poses in [&Pose::WALKING[..], &Pose::STANDING[..]] {
            let sum: f64 = poses.iter().map(|p| p.1).sum();
            assert!((sum - 1.0).abs() < 1e-12);
            let picked: Vec<Pose> = (0..1000)
                .map(|i| Pose::pick(poses, f64::from(i) / 1000.0))
                .collect();
            for (pose, weight) in poses {
                let n = picked.iter().filter(|p| *p == pose).count();
                assert!((n as f64 / 1000.0 - weight).abs() < 0.002, "{pose:?} {n}");
            }
        }
    }
}
