//! Facade window boxes + share + seed → which window pixels glow at night.
//!
//! A window is one box of one facade texture, in one texture repeat, on one object. It is
//! lit when a hash of `(seed, object instance id, box index, repeat column, repeat row)`,
//! read as a number in [0, 1), is below `share`: every pixel of a window agrees, the same
//! windows are lit in every frame, and the choice does not depend on the camera.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::model::{FacadeSet, Scene};

/// Lit windows at night: window boxes per texture, the share lit, a seed, their colour.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LitWindows {
    /// Window boxes `[u0, v0, u1, v1]` (v down, within 0–1) per index into
    /// [`Scene::textures`].
    pub boxes: BTreeMap<u32, Vec<[f32; 4]>>,
    /// Fraction of windows lit, 0–1.
    pub share: f32,
    pub seed: u64,
    /// Linear colour a lit window glows with.
    pub colour: [f32; 3],
}

impl LitWindows {
    /// Window boxes of `facades`, attached to the scene textures of the same name.
    pub fn from_facades(
        scene: &Scene,
        facades: &FacadeSet,
        share: f32,
        seed: u64,
        colour: [f32; 3],
    ) -> LitWindows {
        let mut boxes = BTreeMap::new();
        for (i, texture) in scene.textures.iter().enumerate() {
            if let Some(f) = facades
                .facades
                .iter()
                .find(|f| f.texture.name == texture.name && !f.windows.is_empty())
            {
                boxes.insert(i as u32, f.windows.clone());
            }
        }
        LitWindows {
            boxes,
            share,
            seed,
            colour,
        }
    }
}

/// Cells per side of the lookup grid over a texture's unit square.
const GRID: usize = 16;

/// [`LitWindows`] arranged for per-pixel lookups.
pub(crate) struct WindowLookup {
    /// Per scene texture: the boxes and, per grid cell, the boxes that touch it.
    per_texture: Vec<Option<Grid>>,
    threshold: f64,
    seed: u64,
    pub(crate) colour: [f32; 3],
}

struct Grid {
    boxes: Vec<[f32; 4]>,
    cells: Vec<Vec<u16>>,
}

impl WindowLookup {
    pub(crate) fn new(windows: &LitWindows, texture_count: usize) -> WindowLookup {
        let mut per_texture: Vec<Option<Grid>> = (0..texture_count).map(|_| None).collect();
        for (&texture, boxes) in &windows.boxes {
            let Some(slot) = per_texture.get_mut(texture as usize) else {
                continue;
            };
            let boxes: Vec<[f32; 4]> = boxes
                .iter()
                .take(usize::from(u16::MAX))
                .filter(|b| b.iter().all(|v| v.is_finite()) && b[0] < b[2] && b[1] < b[3])
                .copied()
                .collect();
            let mut cells = vec![Vec::new(); GRID * GRID];
            for (i, b) in boxes.iter().enumerate() {
                let (cx0, cx1) = (cell(b[0]), cell(b[2]));
                let (cy0, cy1) = (cell(b[1]), cell(b[3]));
                for cy in cy0..=cy1 {
                    for cx in cx0..=cx1 {
                        cells[cy * GRID + cx].push(i as u16);
                    }
                }
            }
            *slot = Some(Grid { boxes, cells });
        }
        WindowLookup {
            per_texture,
            threshold: f64::from(windows.share.clamp(0.0, 1.0)),
            seed: windows.seed,
            colour: windows.colour,
        }
    }

    /// Whether the surface point with texture coordinates `(u, v)` of `texture` on object
    /// `instance` lies in a lit window.
    #[inline]
    pub(crate) fn is_lit(&self, texture: u32, instance: u32, u: f64, v: f64) -> bool {
        let Some(Some(grid)) = self.per_texture.get(texture as usize) else {
            return false;
        };
        let (ru, rv) = (u.floor(), v.floor());
        let (fu, fv) = ((u - ru) as f32, (v - rv) as f32);
        let c = cell(fu).min(GRID - 1) + cell(fv).min(GRID - 1) * GRID;
        for &i in &grid.cells[c] {
            let b = grid.boxes[usize::from(i)];
            if fu >= b[0] && fu < b[2] && fv >= b[1] && fv < b[3] {
                let h = mix(
                    mix(
                        mix(mix(self.seed, u64::from(instance)), u64::from(i)),
                        ru as i64 as u64,
                    ),
                    rv as i64 as u64,
                );
                return ((h >> 11) as f64) * (1.0 / (1u64 << 53) as f64) < self.threshold;
            }
        }
        false
    }
}

fn cell(x: f32) -> usize {
    ((x.clamp(0.0, 1.0) * GRID as f32) as usize).min(GRID - 1)
}

/// One SplitMix64 step over `state ^ value`: a fixed, portable hash.
fn mix(state: u64, value: u64) -> u64 {
    let mut z = (state ^ value).wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn windows(share: f32) -> LitWindows {
        LitWindows {
            boxes: BTreeMap::from([(1, vec![[0.1, 0.1, 0.4, 0.3], [0.6, 0.5, 0.9, 0.9]])]),
            share,
            seed: 7,
            colour: [1.0, 0.8, 0.5],
        }
    }

    #[test]
    fn only_points_in_boxes_of_listed_textures_light() {
        let all = WindowLookup::new(&windows(1.0), 3);
        assert!(all.is_lit(1, 5, 0.2, 0.2));
        assert!(all.is_lit(1, 5, 3.7, -1.2), "repeats light too");
        assert!(!all.is_lit(1, 5, 0.5, 0.2), "between windows");
        assert!(!all.is_lit(0, 5, 0.2, 0.2), "texture without windows");
        assert!(!all.is_lit(9, 5, 0.2, 0.2), "texture out of range");
        let none = WindowLookup::new(&windows(0.0), 3);
        assert!(!none.is_lit(1, 5, 0.2, 0.2));
    }

    #[test]
    fn share_is_about_right_and_whole_windows_agree() {
        let half = WindowLookup::new(&windows(0.5), 3);
        let mut lit = 0;
        for instance in 1..=1000u32 {
            let a = half.is_lit(1, instance, 0.15, 0.15);
            assert_eq!(
                a,
                half.is_lit(1, instance, 0.35, 0.25),
                "one window, one answer"
            );
            lit += usize::from(a);
        }
        assert!((400..600).contains(&lit), "{lit} of 1000 lit");
    }
}
