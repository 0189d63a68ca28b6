//! `[splits]` → the split of every frame: per camera (`by = "frame"`) or over the cameras
//! (`by = "camera"`), counts from the shares, members drawn from the seed.

use rand::seq::SliceRandom;

use super::Member;
use crate::spec::{SplitBy, SplitsSpec};

/// How many of `n` items go to train, val and test: val and test get their share of `n`
/// rounded to the nearest, train the rest. A split with a share gets at least one item
/// while there are enough (a val split of 5 % of 10 frames is 1 frame, not none: a
/// training tool refuses an empty val folder), taken from the largest other split.
pub fn counts(n: usize, shares: [f64; 3]) -> [usize; 3] {
    let used = shares.iter().filter(|s| **s > 0.0).count();
    let floor = |k: usize| usize::from(shares[k] > 0.0 && n >= used);
    let mut c = [0usize; 3];
    for k in 1..3 {
        c[k] = ((n as f64 * shares[k]).round() as usize).max(floor(k));
    }
    while c[1] + c[2] + floor(0) > n {
        // Take from the larger of val and test while it keeps its own floor.
        let k = if c[1] - floor(1) >= c[2] - floor(2) {
            1
        } else {
            2
        };
        if c[k] == floor(k) {
            break;
        }
        c[k] -= 1;
    }
    c[0] = n.saturating_sub(c[1] + c[2]);
    c
}

/// Every frame's split, cameras in the order given, each camera's frames in order.
/// `cameras` is each camera's name and number of frames. The draw for a camera depends
/// on the seed and its name only, so adding a camera moves no other camera's frames.
pub fn assign(splits: &SplitsSpec, seed: u64, cameras: &[(&str, usize)]) -> Vec<Member> {
    let shares = splits.shares();
    let mut members = Vec::new();
    match splits.by {
        SplitBy::Frame => {
            for (camera, &(name, frames)) in cameras.iter().enumerate() {
                let of_frame =
                    shuffled_splits(counts(frames, shares), seed, &format!("frames/{name}"));
                members.extend(
                    of_frame
                        .into_iter()
                        .enumerate()
                        .map(|(frame, split)| Member {
                            camera,
                            frame,
                            split,
                        }),
                );
            }
        }
        SplitBy::Camera => {
            let of_camera = shuffled_splits(counts(cameras.len(), shares), seed, "cameras");
            for (camera, &(_, frames)) in cameras.iter().enumerate() {
                members.extend((0..frames).map(|frame| Member {
                    camera,
                    frame,
                    split: of_camera[camera],
                }));
            }
        }
    }
    members
}

/// `counts[k]` items of split `k`, in an order drawn from `seed` and `what`: item `i`'s
/// split.
fn shuffled_splits(counts: [usize; 3], seed: u64, what: &str) -> Vec<usize> {
    let mut splits: Vec<usize> = (0..3)
        .flat_map(|k| std::iter::repeat_n(k, counts[k]))
        .collect();
    let mut rng = crate::rng::stream(seed, &format!("splits/{what}"), 0);
    splits.shuffle(&mut rng);
    splits
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_follow_the_shares_within_rounding() {
        let cases: &[(usize, [f64; 3], [usize; 3])] = &[
            (100, [0.8, 0.2, 0.0], [80, 20, 0]),
            (10, [0.8, 0.1, 0.1], [8, 1, 1]),
            (7, [0.7, 0.15, 0.15], [5, 1, 1]),
            (10, [0.95, 0.05, 0.0], [9, 1, 0]),
            (2, [0.5, 0.5, 0.0], [1, 1, 0]),
            (2, [0.8, 0.1, 0.1], [2, 0, 0]),
            (1, [0.8, 0.2, 0.0], [1, 0, 0]),
            (0, [0.8, 0.2, 0.0], [0, 0, 0]),
            (12, [1.0, 0.0, 0.0], [12, 0, 0]),
        ];
        for &(n, shares, want) in cases {
            let got = counts(n, shares);
            assert_eq!(got, want, "{n} {shares:?}");
            assert_eq!(got.iter().sum::<usize>(), n);
        }
    }

    fn spec(by: SplitBy) -> SplitsSpec {
        SplitsSpec {
            train: 0.6,
            val: 0.2,
            test: 0.2,
            by,
        }
    }

    #[test]
    fn frames_are_split_per_camera_by_seed_and_name() {
        let cameras = [("street", 50), ("aerial", 10)];
        let a = assign(&spec(SplitBy::Frame), 7, &cameras);
        assert_eq!(a, assign(&spec(SplitBy::Frame), 7, &cameras));
        assert_ne!(a, assign(&spec(SplitBy::Frame), 8, &cameras));
        let street = |m: &[Member], k| m.iter().filter(|m| m.camera == 0 && m.split == k).count();
        assert_eq!([0, 1, 2].map(|k| street(&a, k)), [30, 10, 10]);
        // Dropping the other camera leaves the street's draw as it was.
        let alone = assign(&spec(SplitBy::Frame), 7, &cameras[..1]);
        assert_eq!(alone[..], a[..50]);
    }

    #[test]
    fn cameras_go_whole_to_one_split() {
        let cameras = [("a", 3), ("b", 4), ("c", 5), ("d", 6), ("e", 7)];
        let m = assign(&spec(SplitBy::Camera), 1, &cameras);
        for camera in 0..cameras.len() {
            let splits: Vec<usize> = m
                .iter()
                .filter(|x| x.camera == camera)
                .map(|x| x.split)
                .collect();
            assert!(splits.windows(2).all(|w| w[0] == w[1]), "camera {camera}");
        }
        let per_split = |k| {
            (0..cameras.len())
                .filter(|&c| m.iter().any(|x| x.camera == c && x.split == k))
                .count()
        };
        assert_eq!([0, 1, 2].map(per_split), [3, 1, 1]);
    }
}
