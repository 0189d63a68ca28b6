//! Facade window boxes + share + seed → which window pixels glow at night.
//!
//! A window is one box of one facade texture, in one texture repeat, on one object. It is
//! lit when a hash of `(seed, object instance id, box index, repeat column, repeat row)`,
//! read as a number in [0, 1), is below `share`: every pixel of a window agrees, the same
//! windows are lit in every frame, and the choice does not depend on the camera.

use std::collections::{BTreeMap, BTreeSet};

use serde::{Deserialize, Serialize};

use super::Light;
use crate::model::{FacadeSet, Scene};

/// Light a lit window spills out, as a multiple of its glow colour: with [`SPILL_NEAR`],
/// about 0.3 on the pavement 3 m in front of a ground-floor window.
const SPILL: f32 = 4.5;
/// Near field of a window's light, metres: about a window's size.
const SPILL_NEAR: f32 = 1.5;
/// How far a window's light reaches, metres.
const SPILL_RANGE: f32 = 10.0;
/// Only windows whose centre is at most this high above their wall's foot spill light
/// (the lowest three floors): higher ones add little below and would only cost.
const SPILL_HEIGHT: f64 = 9.0;
/// The light sits this far in front of the window, so the wall around it stays unlit.
const SPILL_OFFSET: f64 = 0.15;
/// Texture repeats per side of one triangle a wall may hold before it is skipped.
const MAX_REPEATS: f64 = 256.0;

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

impl LitWindows {
    /// A light in front of every lit window of `scene` low enough to light the pavement,
    /// beamed out of the wall (Lambert-like: strongest straight out, none along the wall),
    /// in scene order. Windows are found as `WindowLookup::is_lit` finds them: each box
    /// centre of each texture repeat that lies in a wall triangle of a window texture.
    pub fn spill_lights(&self, scene: &Scene) -> Vec<Light> {
        let lookup = WindowLookup::new(self, scene.textures.len());
        let colour = self.colour.map(|c| c * SPILL);
        let mut out = Vec::new();
        for (o, object) in scene.objects.iter().enumerate() {
            let instance = o as u32 + 1;
            for mesh in &object.meshes {
                let Some(texture) = scene
                    .materials
                    .get(mesh.material as usize)
                    .and_then(|m| m.texture)
                else {
                    continue;
                };
                let Some(Some(grid)) = lookup.per_texture.get(texture as usize) else {
                    continue;
                };
                if mesh.uvs.len() != mesh.positions.len() {
                    continue;
                }
                let spills = MeshSpills {
                    lookup: &lookup,
                    grid,
                    texture,
                    instance,
                    colour,
                };
                spills.collect(mesh, &mut out);
            }
        }
        out
    }
}

/// The lights of one textured mesh's lit windows.
struct MeshSpills<'a> {
    lookup: &'a WindowLookup,
    /// The mesh texture's window boxes.
    grid: &'a Grid,
    texture: u32,
    instance: u32,
    colour: [f32; 3],
}

/// A wall triangle in `f64`: corners `p`, texture coordinates `t`, edges `e1`, `e2` and
/// unit normal `n`; its texture edges `f1`, `f2` and their determinant.
struct WallTriangle {
    p: [[f64; 3]; 3],
    t: [[f64; 2]; 3],
    e1: [f64; 3],
    e2: [f64; 3],
    n: [f64; 3],
    f1: [f64; 2],
    f2: [f64; 2],
    det: f64,
}

impl MeshSpills<'_> {
    /// Appends to `out` a light per lit window box centre in `mesh`'s wall triangles, at
    /// most [`SPILL_HEIGHT`] above the mesh's lowest point.
    fn collect(&self, mesh: &crate::model::Mesh, out: &mut Vec<Light>) {
        let foot = mesh
            .positions
            .iter()
            .map(|p| f64::from(p[1]))
            .fold(f64::INFINITY, f64::min);
        // A window on the diagonal of a wall's two triangles counts once.
        let mut seen = BTreeSet::new();
        for tri in mesh.indices.chunks_exact(3) {
            let Some(corners) = tri
                .iter()
                .map(|&i| {
                    let i = i as usize;
                    Some((*mesh.positions.get(i)?, *mesh.uvs.get(i)?))
                })
                .collect::<Option<Vec<_>>>()
            else {
                continue;
            };
            if let Some(wall) = WallTriangle::new(&corners) {
                self.collect_in(&wall, foot, &mut seen, out);
            }
        }
    }

    /// The lights of the lit windows whose box centres, in any texture repeat, lie in
    /// `wall`; `seen` holds the windows (repeat and box) already lit.
    fn collect_in(
        &self,
        wall: &WallTriangle,
        foot: f64,
        seen: &mut BTreeSet<(i64, i64, usize)>,
        out: &mut Vec<Light>,
    ) {
        let WallTriangle {
            p,
            t,
            e1,
            e2,
            n,
            f1,
            f2,
            det,
        } = wall;
        let lo = |k: usize| t.iter().map(|t| t[k]).fold(f64::INFINITY, f64::min).floor();
        let hi = |k: usize| {
            t.iter()
                .map(|t| t[k])
                .fold(f64::NEG_INFINITY, f64::max)
                .ceil()
        };
        let (u0, u1, v0, v1) = (lo(0), hi(0), lo(1), hi(1));
        if !(u1 - u0 <= MAX_REPEATS && v1 - v0 <= MAX_REPEATS) {
            return;
        }
        let mut rv = v0;
        while rv < v1 {
            let mut ru = u0;
            while ru < u1 {
                for (i, b) in self.grid.boxes.iter().enumerate() {
                    let cu = ru + f64::from(b[0] + b[2]) * 0.5;
                    let cv = rv + f64::from(b[1] + b[3]) * 0.5;
                    let (du, dv) = (cu - t[0][0], cv - t[0][1]);
                    let a = (du * f2[1] - dv * f2[0]) / det;
                    let c = (f1[0] * dv - f1[1] * du) / det;
                    if a < 0.0 || c < 0.0 || a + c > 1.0 {
                        continue;
                    }
                    let at = std::array::from_fn::<f64, 3, _>(|k| p[0][k] + a * e1[k] + c * e2[k]);
                    if at[1] - foot > SPILL_HEIGHT
                        || !seen.insert((ru as i64, rv as i64, i))
                        || !self.lookup.is_lit(self.texture, self.instance, cu, cv)
                    {
                        continue;
                    }
                    out.push(Light {
                        position: std::array::from_fn(|k| (at[k] + n[k] * SPILL_OFFSET) as f32),
                        colour: self.colour,
                        range: SPILL_RANGE,
                        near: SPILL_NEAR,
                        aim: n.map(|v| v as f32),
                        edge: 0.0,
                        cutoff: None,
                    });
                }
                ru += 1.0;
            }
            rv += 1.0;
        }
    }
}

impl WallTriangle {
    /// The triangle of `corners` (position, uv), or `None` unless it is a wall (a window
    /// texture on a slope or a roof spills nothing) with uvs that span an area.
    fn new(corners: &[([f32; 3], [f32; 2])]) -> Option<WallTriangle> {
        let p: [[f64; 3]; 3] = std::array::from_fn(|i| corners[i].0.map(f64::from));
        let t: [[f64; 2]; 3] = std::array::from_fn(|i| corners[i].1.map(f64::from));
        let e1 = [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]];
        let e2 = [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]];
        let n = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        if len.is_nan() || len <= 1e-9 || (n[1] / len).abs() > 0.3 {
            return None;
        }
        let n = n.map(|v| v / len);
        let (f1, f2) = (
            [t[1][0] - t[0][0], t[1][1] - t[0][1]],
            [t[2][0] - t[0][0], t[2][1] - t[0][1]],
        );
        let det = f1[0] * f2[1] - f1[1] * f2[0];
        if det.is_nan() || det.abs() <= 1e-12 {
            return None;
        }
        Some(WallTriangle {
            p,
            t,
            e1,
            e2,
            n,
            f1,
            f2,
            det,
        })
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
        self.lit_window(texture, instance, u, v).is_some()
    }

    /// The light a lit window shows at `(u, v)` (None when the point is in no lit window):
    /// the glow colour as the window's room tints it and as what hangs in it shapes it
    /// ([`Room`]), chosen from the hash that lit the window, so every pixel of a window
    /// agrees and neighbours differ.
    #[inline]
    pub(crate) fn glow(&self, texture: u32, instance: u32, u: f64, v: f64) -> Option<[f32; 3]> {
        let (x, y, h) = self.lit_window(texture, instance, u, v)?;
        let room = Room::of(h);
        let k = room.strength * room.pattern.factor(x, y);
        Some([0, 1, 2].map(|c| self.colour[c] * room.tint[c] * k))
    }

    /// The lit window under `(u, v)`: the point's place across its box (0–1 left to right,
    /// top to bottom) and the hash that lit it.
    #[inline]
    fn lit_window(&self, texture: u32, instance: u32, u: f64, v: f64) -> Option<(f32, f32, u64)> {
        let Some(Some(grid)) = self.per_texture.get(texture as usize) else {
            return None;
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
                let lit = ((h >> 11) as f64) * (1.0 / (1u64 << 53) as f64) < self.threshold;
                let across = ((fu - b[0]) / (b[2] - b[0]), (fv - b[1]) / (b[3] - b[1]));
                return lit.then_some((across.0, across.1, h));
            }
        }
        None
    }
}

/// What a lit window shows: the room's light (its tint on the glow colour and strength)
/// and what hangs in the window or stands in the room.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Room {
    tint: [f32; 3],
    strength: f32,
    pattern: Pattern,
}

/// Rooms' lights: warm bulbs, neutral, cool LEDs, a television's blue, a dim lamp.
const TINTS: [([f32; 3], f32); 5] = [
    ([1.0, 1.0, 1.0], 1.0),
    ([1.0, 1.06, 1.25], 0.9),
    ([0.82, 1.0, 1.6], 0.85),
    ([0.45, 0.7, 1.9], 0.55),
    ([1.0, 0.78, 0.6], 0.45),
];

/// How the light falls across a window, from its box coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pattern {
    /// Bare: brightest under the ceiling light, a little dimmer towards the sill.
    Open,
    /// Curtains drawn to both sides.
    Curtains,
    /// Blinds: bright slats between dark ones.
    Blinds,
    /// A lamp's glow over a dark sofa, shelf or table in the lower part.
    Furniture,
}

const PATTERNS: [Pattern; 4] = [
    Pattern::Open,
    Pattern::Curtains,
    Pattern::Blinds,
    Pattern::Furniture,
];

impl Room {
    /// The room of the window the hash `h` lit (bits apart from those that decided it).
    fn of(h: u64) -> Room {
        let r = mix(h, 0x726f_6f6d);
        let (tint, strength) = TINTS[(r % TINTS.len() as u64) as usize];
        let pattern = PATTERNS[((r >> 8) % PATTERNS.len() as u64) as usize];
        // ±15 % from one room to the next.
        let jitter = 0.85 + 0.3 * ((r >> 16) & 0xff) as f32 / 255.0;
        Room {
            tint,
            strength: strength * jitter,
            pattern,
        }
    }
}

impl Pattern {
    /// The share of the room's light at `(x, y)` across the window (0–1 each, y down).
    fn factor(self, x: f32, y: f32) -> f32 {
        let ceiling = 1.15 - 0.35 * y;
        match self {
            Pattern::Open => ceiling,
            Pattern::Curtains if !(0.22..0.78).contains(&x) => 0.3 * ceiling,
            Pattern::Curtains => ceiling,
            Pattern::Blinds if (y * 7.0).fract() < 0.35 => 0.35,
            Pattern::Blinds => 0.9,
            Pattern::Furniture if y > 0.62 && (0.12..0.7).contains(&x) => 0.18,
            Pattern::Furniture => 1.2 - 0.5 * y,
        }
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

    /// A 12 m high wall facing +z, 8 m wide with two texture repeats, as two triangles;
    /// texture 1 (the windows' texture) with v down from its top.
    fn wall_scene() -> Scene {
        use crate::model::{Material, Mesh, SceneObject, Texture};
        let texture = Texture::from_rgb("facade", image::RgbImage::new(2, 2));
        Scene {
            textures: vec![texture.clone(), texture],
            materials: vec![Material {
                name: "wall".into(),
                colour: [1.0; 3],
                texture: Some(1),
                emissive: [0.0; 3],
                emissive_textured: false,
            }],
            objects: vec![SceneObject {
                name: "building_0000".into(),
                kind: crate::model::ObjectKind::Building,
                class: "building".into(),
                meshes: vec![Mesh {
                    material: 0,
                    positions: vec![
                        [0.0, 0.0, 0.0],
                        [8.0, 0.0, 0.0],
                        [8.0, 12.0, 0.0],
                        [0.0, 12.0, 0.0],
                    ],
                    normals: vec![[0.0, 0.0, 1.0]; 4],
                    uvs: vec![[0.0, 1.0], [2.0, 1.0], [2.0, 0.0], [0.0, 0.0]],
                    indices: vec![0, 1, 2, 0, 2, 3],
                }],
            }],
        }
    }

    #[test]
    fn low_lit_windows_spill_light_out_of_the_wall() {
        let lights = windows(1.0).spill_lights(&wall_scene());
        // Per repeat: box 0 (centre v 0.2, 9.6 m up) is too high; box 1 (centre v 0.7,
        // 3.6 m up) spills. Its centre is at u = 0.75 of each 4 m repeat.
        assert_eq!(lights.len(), 2, "{lights:?}");
        for (light, x) in lights.iter().zip([3.0, 7.0]) {
            let p = light.position;
            assert!(
                (p[0] - x).abs() < 1e-4 && (p[1] - 3.6).abs() < 1e-4,
                "{p:?}"
            );
            assert!(p[2] > 0.0 && p[2] < 0.5, "in front of the wall: {p:?}");
            assert_eq!(light.aim, [0.0, 0.0, 1.0]);
        }
        assert!(windows(0.0).spill_lights(&wall_scene()).is_empty());
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

    /// Lit windows vary: among many, every room tint and pattern shows, the light inside
    /// one window is shaped (curtains, blinds, furniture darker than the rest), and an unlit
    /// point has no glow.
    #[test]
    fn lit_windows_show_varied_rooms() {
        let all = WindowLookup::new(&windows(1.0), 3);
        let mut rooms = BTreeSet::new();
        let mut shaped = 0;
        for instance in 1..=400u32 {
            let a = all.glow(1, instance, 0.11, 0.12).unwrap();
            let b = all.glow(1, instance, 0.25, 0.29).unwrap();
            rooms.insert(a.map(f32::to_bits));
            if a != b {
                shaped += 1;
            }
            assert!(
                a.iter().chain(&b).all(|c| (0.0..2.5).contains(c)),
                "{a:?} {b:?}"
            );
        }
        assert!(rooms.len() > 100, "{} distinct window lights", rooms.len());
        assert!(shaped > 200, "{shaped} of 400 windows shaped inside");
        assert!(all.glow(1, 5, 0.5, 0.2).is_none());
        let seen: BTreeSet<_> = (0..2000u64)
            .map(|h| {
                let room = Room::of(h);
                (room.pattern as u8, room.tint.map(f32::to_bits))
            })
            .collect();
        assert_eq!(seen.len(), TINTS.len() * PATTERNS.len());
        assert!(Pattern::Curtains.factor(0.05, 0.5) < 0.5 * Pattern::Curtains.factor(0.5, 0.5));
        assert!(Pattern::Furniture.factor(0.4, 0.9) < 0.3 * Pattern::Furniture.factor(0.4, 0.3));
        assert!(Pattern::Blinds.factor(0.5, 0.01) < 0.5 * Pattern::Blinds.factor(0.5, 0.1));
    }
}
