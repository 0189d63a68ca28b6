//! Buildings + roads + text specs → `text_NNNN` plates on the walls that face a road.
//!
//! A wall faces a road when a road lies straight in front of it (overlapping it along the
//! wall) no farther than [`ROAD_REACH`] strip widths away. A plate stands between
//! [`MIN_HEIGHT`] above the block surface and [`TOP_CLEARANCE`] below the roof, wholly on
//! its wall, [`WALL_OFFSET`] in front of it, and keeps [`SPACING`] from the plates already
//! on that wall. An entry's plate images share a few atlas pages ([`AtlasLayout`]), one
//! material per page, each plate's uvs covering its own rectangle.

use std::collections::BTreeMap;

use image::RgbImage;
use rand::RngExt;
use rand_pcg::Pcg64;
use rayon::prelude::*;

use super::atlas_layout::{self, AtlasLayout};
use super::text_plate::{self, TextPlate};
use super::{ATTEMPTS, ObjectInfo, ObjectsInput, Placing, WORDS};
use crate::model::{SceneObject, Texture};
use crate::scene::buildings::building_heights;
use crate::scene::mesh_builder::MeshBuilder;
use crate::scene::road_rect::RoadRect;
use crate::scene::{KERB_Y, SceneInput, strip_width_px};
use crate::spec::{ObjectSpec, TextCase};

/// Lowest plate edge above the block surface, in metres.
pub const MIN_HEIGHT: f64 = 2.5;
/// Room left between the highest plate edge and the roof, in metres.
pub const TOP_CLEARANCE: f64 = 1.0;
/// Distance of a plate in front of its wall (against z-fighting), in metres.
pub const WALL_OFFSET: f64 = 0.025;
/// Gap kept between two plates on one wall, in metres.
pub const SPACING: f64 = 0.2;
/// How many strip widths (plus one pixel) a road may lie from a wall that faces it.
pub const ROAD_REACH: f64 = 2.0;

/// One building wall that faces a road, in metres.
#[derive(Clone, Debug, PartialEq)]
pub struct Wall {
    pub building: u32,
    /// The wall's bottom-left corner (x, z) seen from the front, on the wall's plane.
    pub origin: [f64; 2],
    /// Unit vector along the wall to the right, seen from the front (x, z).
    pub right: [f64; 2],
    /// Unit outward normal (x, z).
    pub normal: [f64; 2],
    pub length: f64,
    /// Heights (y) plates may use: `[bottom, top]`.
    pub band: [f64; 2],
}

/// A plate placed on a wall, waiting for its place on an atlas page.
struct Placed {
    name: String,
    wall: usize,
    rect: [f64; 4],
    plate: TextPlate,
    /// Paper and ink.
    colours: ([u8; 3], [u8; 3]),
    text: String,
    corners: [[f64; 3]; 4],
}

/// The walls facing roads, and the plates placed on each so far: `[u0, y0, u1, y1]`.
pub struct Walls {
    walls: Vec<Wall>,
    placed: BTreeMap<usize, Vec<[f64; 4]>>,
}

impl Walls {
    pub fn new(input: &ObjectsInput) -> Walls {
        Walls {
            walls: facing_walls(input),
            placed: BTreeMap::new(),
        }
    }

    #[cfg(test)]
    pub fn walls(&self) -> &[Wall] {
        &self.walls
    }

    /// Places `spec.count` text plates (fewer if they do not fit), their images packed onto
    /// shared atlas pages, one material per page.
    pub fn place(&mut self, spec: &ObjectSpec, rng: &mut Pcg64, placing: &mut Placing) {
        if self.walls.is_empty() {
            return;
        }
        let mut placed: Vec<Placed> = Vec::new();
        for _ in 0..spec.count {
            let text = words(spec, rng);
            let height = uniform(rng, spec.letter_height);
            let (paper, ink) = colours(rng);
            let plate = TextPlate::measure(&text, text_plate::letter_px(height));
            let metres_per_px = height / f64::from(plate.letter_px);
            let size = [
                f64::from(plate.width) * metres_per_px,
                f64::from(plate.height) * metres_per_px,
            ];
            let Some((w, rect)) = self.find_spot(rng, size) else {
                continue;
            };
            self.placed.entry(w).or_default().push(rect);
            let corners = text_corners(&self.walls[w], rect, &plate, metres_per_px);
            placed.push(Placed {
                name: placing.name("text"),
                wall: w,
                rect,
                plate,
                colours: (paper, ink),
                text,
                corners,
            });
        }
        // Drawing the plates and painting and PNG-encoding the pages are the costly parts:
        // all in parallel, each result in its own slot.
        let images: Vec<RgbImage> = placed
            .par_iter()
            .map(|p| p.plate.draw(&p.text, p.colours.0, p.colours.1))
            .collect();
        let sizes: Vec<[u32; 2]> = placed
            .iter()
            .map(|p| [p.plate.width, p.plate.height])
            .collect();
        let atlas = AtlasLayout::pack(&sizes, atlas_layout::PAGE);
        let pages: Vec<Texture> = (0..atlas.pages.len())
            .into_par_iter()
            .map(|page| Texture::from_rgb(String::new(), &atlas.paint(page, &images)))
            .collect();
        let materials: Vec<u32> = pages
            .iter()
            .enumerate()
            .map(|(i, page)| {
                let name = format!("{}_atlas_{i}", spec.label);
                placing.book.add(&name, [1.0; 3], Some(page), [0.0; 3])
            })
            .collect();
        for (i, p) in placed.into_iter().enumerate() {
            let material = materials[atlas.slots[i].page];
            let object = SceneObject {
                name: p.name,
                class: spec.label.clone(),
                meshes: vec![plate_mesh(
                    &self.walls[p.wall],
                    p.rect,
                    material,
                    atlas.uv_spans(i),
                )],
            };
            placing.push(
                object,
                ObjectInfo {
                    label: spec.label.clone(),
                    text: Some(p.text),
                    corners: Some(p.corners),
                },
            );
        }
    }

    /// A wall and a free rectangle `[u0, y0, u1, y1]` of `size` on it.
    fn find_spot(&self, rng: &mut Pcg64, size: [f64; 2]) -> Option<(usize, [f64; 4])> {
        (0..ATTEMPTS).find_map(|_| {
            let w = rng.random_range(0..self.walls.len());
            let wall = &self.walls[w];
            let free_u = wall.length - size[0];
            let free_y = wall.band[1] - wall.band[0] - size[1];
            if free_u < 0.0 || free_y < 0.0 {
                return None;
            }
            let u0 = rng.random::<f64>() * free_u;
            let y0 = wall.band[0] + rng.random::<f64>() * free_y;
            let rect = [u0, y0, u0 + size[0], y0 + size[1]];
            let clear = self.placed.get(&w).is_none_or(|rects| {
                rects.iter().all(|r| {
                    rect[2] + SPACING <= r[0]
                        || r[2] + SPACING <= rect[0]
                        || rect[3] + SPACING <= r[1]
                        || r[3] + SPACING <= rect[1]
                })
            });
            clear.then_some((w, rect))
        })
    }
}

/// The gap from a wall to a road straight in front of it, if the road is in front.
type GapToRoad<'a> = dyn Fn(&RoadRect) -> Option<f64> + 'a;

/// Every wall of every building that faces a road, in (building, north-east-south-west)
/// order.
pub fn facing_walls(input: &ObjectsInput) -> Vec<Wall> {
    let scene_input = SceneInput {
        layout: input.layout,
        lamps: input.lamps,
        buildings: input.buildings,
        facades: input.facades,
        widths: input.widths,
        metres_per_pixel: input.metres_per_pixel,
        seed: input.seed,
    };
    let heights = building_heights(&scene_input);
    let rects: Vec<RoadRect> = input.layout.roads.iter().map(RoadRect::of).collect();
    let reach = ROAD_REACH * f64::from(strip_width_px(input.layout)) + 1.0;
    let mpp = input.metres_per_pixel;
    let mut walls = Vec::new();
    for (building, &height) in input.buildings.iter().zip(&heights) {
        let fp = building.footprint;
        let (x0, x1) = (f64::from(fp.x0), f64::from(fp.x1));
        let (y0, y1) = (f64::from(fp.y0), f64::from(fp.y1));
        let overlaps = |a: [f64; 2], b: [f64; 2]| a[0] < b[1] && b[0] < a[1];
        // (normal, bottom-left corner seen from the front, gap to a road in front)
        let sides: [([f64; 2], [f64; 2], &GapToRoad); 4] = [
            ([0.0, -1.0], [x1, y0], &|r| {
                (overlaps(r.x, [x0, x1]) && r.y[1] <= y0).then(|| y0 - r.y[1])
            }),
            ([1.0, 0.0], [x1, y1], &|r| {
                (overlaps(r.y, [y0, y1]) && r.x[0] >= x1).then(|| r.x[0] - x1)
            }),
            ([0.0, 1.0], [x0, y1], &|r| {
                (overlaps(r.x, [x0, x1]) && r.y[0] >= y1).then(|| r.y[0] - y1)
            }),
            ([-1.0, 0.0], [x0, y0], &|r| {
                (overlaps(r.y, [y0, y1]) && r.x[1] <= x0).then(|| x0 - r.x[1])
            }),
        ];
        let band = [KERB_Y + MIN_HEIGHT, KERB_Y + height - TOP_CLEARANCE];
        if band[1] <= band[0] {
            continue;
        }
        for (normal, corner, gap) in sides {
            let faces_road = rects.iter().filter_map(gap).any(|g| g <= reach);
            if !faces_road {
                continue;
            }
            let length = if normal[0] == 0.0 { x1 - x0 } else { y1 - y0 } * mpp;
            walls.push(Wall {
                building: building.id,
                origin: [corner[0] * mpp, corner[1] * mpp],
                right: [normal[1], -normal[0]],
                normal,
                length,
                band,
            });
        }
    }
    walls
}

/// The world point `u` metres right of the wall's left edge, `y` up, `out` in front of it.
pub fn wall_point(wall: &Wall, u: f64, y: f64, out: f64) -> [f64; 3] {
    [
        wall.origin[0] + wall.right[0] * u + wall.normal[0] * out,
        y,
        wall.origin[1] + wall.right[1] * u + wall.normal[1] * out,
    ]
}

/// The plate's quad, `uv` = (u span, v span) of its rectangle on its atlas page.
fn plate_mesh(
    wall: &Wall,
    rect: [f64; 4],
    material: u32,
    (u, v): ([f64; 2], [f64; 2]),
) -> crate::model::Mesh {
    let a = wall_point(wall, rect[0], 0.0, WALL_OFFSET);
    let b = wall_point(wall, rect[2], 0.0, WALL_OFFSET);
    let mut mesh = MeshBuilder::new(material);
    mesh.wall(
        [a[0], a[2]],
        [b[0], b[2]],
        [rect[1], rect[3]],
        [wall.normal[0], 0.0, wall.normal[1]],
        u,
        v,
    );
    mesh.finish()
}

/// The text box's corners: top-left, top-right, bottom-right, bottom-left from the front.
fn text_corners(wall: &Wall, rect: [f64; 4], plate: &TextPlate, m_per_px: f64) -> [[f64; 3]; 4] {
    let [bx0, by0, bx1, by1] = plate.text_box.map(|v| f64::from(v) * m_per_px);
    let (u0, u1) = (rect[0] + bx0, rect[0] + bx1);
    // Image rows run down from the plate's top edge.
    let (top, bottom) = (rect[3] - by0, rect[3] - by1);
    [
        wall_point(wall, u0, top, WALL_OFFSET),
        wall_point(wall, u1, top, WALL_OFFSET),
        wall_point(wall, u1, bottom, WALL_OFFSET),
        wall_point(wall, u0, bottom, WALL_OFFSET),
    ]
}

fn uniform(rng: &mut Pcg64, range: [f64; 2]) -> f64 {
    range[0] + rng.random::<f64>() * (range[1] - range[0])
}

/// The words of one plate, in the spec's case.
pub fn words(spec: &ObjectSpec, rng: &mut Pcg64) -> String {
    let [low, high] = spec.words;
    let n = rng.random_range(low.max(1)..=high.max(low).max(1));
    let case = match spec.case {
        TextCase::Mixed => {
            [TextCase::Lower, TextCase::Upper, TextCase::Title][rng.random_range(0..3)]
        }
        case => case,
    };
    let words: Vec<String> = (0..n)
        .map(|_| {
            let word = WORDS[rng.random_range(0..WORDS.len())];
            match case {
                TextCase::Upper => word.to_ascii_uppercase(),
                TextCase::Title => {
                    let mut w = word.to_owned();
                    w[..1].make_ascii_uppercase();
                    w
                }
                _ => word.to_owned(),
            }
        })
        .collect();
    words.join(" ")
}

/// A plate colour and an ink colour with strong contrast: one light, one dark.
fn colours(rng: &mut Pcg64) -> ([u8; 3], [u8; 3]) {
    let light: [u8; 3] = std::array::from_fn(|_| rng.random_range(185..=255));
    let dark: [u8; 3] = std::array::from_fn(|_| rng.random_range(0..=70));
    if rng.random::<bool>() {
        (light, dark)
    } else {
        (dark, light)
    }
}
