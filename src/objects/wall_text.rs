//! Buildings + roads + text specs → `text_NNNN` plates on the walls that face a road.
//!
//! A wall faces a road when a road lies straight in front of it (overlapping it along the
//! wall) no farther than [`ROAD_REACH`] strip widths away. A plate stands between
//! [`MIN_HEIGHT`] above the block surface and [`TOP_CLEARANCE`] below the roof, wholly on
//! its wall, [`WALL_OFFSET`] in front of it, and keeps [`SPACING`] from the plates already
//! on that wall and [`WINDOW_MARGIN`] from the facade's window boxes (so no plate covers a
//! window). A wall with another building between it and the road does not face the road.
//! Each plate draws a style ([`PlateStyle::WALL_MIX`]), a font ([`TextFont::ALL`]) and a
//! colour pair ([`text_colours`]); painted text is drawn straight onto the wall's own
//! pixels, primed where the raw wall fails the contrast floor ([`text_colours::primed`]).
//! An entry's plate images share a few atlas pages (`atlas_layout`), one material per
//! page and per way the plates are lit after dusk ([`PlateLight`]), each plate's uvs
//! covering its own rectangle.

use std::collections::BTreeMap;

use image::RgbImage;
use rand::RngExt;
use rand_pcg::Pcg64;
use rayon::prelude::*;

use super::footprint_grid::FootprintGrid;
use super::ground_spots::Footprint;
use super::plate_light::{self, PlateLight};
use super::plate_style::{PlateStyle, SHOP_BAND};
use super::text_colours::{self, luminance};
use super::text_font::TextFont;
use super::text_plate::{self, Background, TextPlate};
use super::{
    ATTEMPTS, GIVE_UP, ObjectInfo, ObjectsError, ObjectsInput, Placing, WORDS, parse_words,
};
use crate::model::SceneObject;
use crate::model::geometry::rounding::{floor, round};
use crate::model::geometry::{KERB_Y, MeshBuilder, RoadRect, strip_width_px};
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
/// Gap kept between a plate and a window box, in metres.
pub const WINDOW_MARGIN: f64 = 0.15;
/// Draws of a plate (words, size, style, font) tried before a plate is left out.
pub const REDRAWS: u32 = 24;
/// Share of hard (low-contrast) painted text, as for plates.
const HARD_SHARE: f64 = text_colours::HARD_SHARE;

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
    /// The facade that clads it (index into the facade set), if any.
    pub facade: Option<usize>,
    /// Metres of wall one facade repeat covers (the wall's length when it is not tiled).
    pub repeat: f64,
    /// The wall's height above the block surface, in metres.
    pub height: f64,
    /// The facade's window boxes on this wall, `[u0, y0, u1, y1]` in metres.
    pub windows: Vec<[f64; 4]>,
    /// How its facade is laid on it.
    pub tiling: Tiling,
}

/// How a facade is laid on a wall, `repeat` metres of wall to one facade width.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tiling {
    /// A layout building's (`scene::buildings`): stretched over the wall's height, its
    /// width repeating from the wall's left edge seen from the front.
    Stretched,
    /// A map building's (`scene::map_city`): at floor scale, the facade's ground floor
    /// (`floor` metres of its `floors`) along the bottom and its upper floors repeating
    /// above, its width repeating from the wall's left edge.
    Floors { floor: f64, floors: u32 },
}

impl Wall {
    /// The facade's texture coordinates `(u, v)` (v down from the facade's top) at `u`
    /// metres right of the wall's left edge and height `y`.
    pub fn texture_at(&self, u: f64, y: f64) -> [f64; 2] {
        match self.tiling {
            Tiling::Stretched => [
                (u / self.repeat).rem_euclid(1.0),
                1.0 - (y - KERB_Y) / self.height,
            ],
            Tiling::Floors { floor, floors } => {
                let ground_v = 1.0 - 1.0 / f64::from(floors);
                let upper = floor * f64::from(floors - 1);
                let h = y - KERB_Y;
                let v = if h < floor || upper <= 0.0 {
                    1.0 - (h / floor).min(1.0) * (1.0 - ground_v)
                } else {
                    ground_v * (1.0 - ((h - floor) / upper).fract())
                };
                [(u / self.repeat).rem_euclid(1.0), v]
            }
        }
    }
}

/// A plate placed on a wall, waiting for its place on an atlas page.
pub(crate) struct Placed {
    pub name: String,
    pub wall: usize,
    pub rect: [f64; 4],
    pub plate: TextPlate,
    pub background: Background,
    pub ink: [u8; 3],
    pub text: String,
    pub corners: Vec<[[f64; 3]; 4]>,
    /// How it is lit after dusk when its maker decides (a car's plates); `None`: drawn.
    pub light: Option<PlateLight>,
}

/// The walls facing roads, and the plates placed on each so far: `[u0, y0, u1, y1]`.
pub struct Walls {
    walls: Vec<Wall>,
    placed: BTreeMap<usize, Vec<[f64; 4]>>,
    /// Decoded facade images (for painted text), by facade index, decoded when first used.
    images: BTreeMap<usize, Option<RgbImage>>,
}

impl Walls {
    pub fn new(input: &ObjectsInput) -> Walls {
        Walls::of(facing_walls(input))
    }

    /// These walls, with no plates on them yet (a map's: `map_walls`).
    pub fn of(walls: Vec<Wall>) -> Walls {
        Walls {
            walls,
            placed: BTreeMap::new(),
            images: BTreeMap::new(),
        }
    }

    #[cfg(test)]
    pub fn walls(&self) -> &[Wall] {
        &self.walls
    }

    /// Places `spec.count` text plates (fewer if they do not fit), their images packed onto
    /// shared atlas pages, one material per page.
    pub fn place(
        &mut self,
        spec: &ObjectSpec,
        rng: &mut Pcg64,
        placing: &mut Placing,
    ) -> Result<(), ObjectsError> {
        let source = word_source(spec, placing)?;
        let list: Vec<&str> = source.iter().map(String::as_str).collect();
        if self.walls.is_empty() {
            return Ok(());
        }
        let mut placed: Vec<Placed> = Vec::new();
        // Per placed plate: for painted text, the seed of the stream that picks its ink.
        let mut inks: Vec<Option<u64>> = Vec::new();
        let mut misses = 0;
        for _ in 0..spec.count {
            if misses >= GIVE_UP {
                break;
            }
            // A plate that fits no free wall is drawn again, new words, size, style and
            // font, up to REDRAWS times: the walls' free room bounds `count`, not the first
            // draw's luck (the redraws favour smaller plates a little).
            let mut fitted = None;
            for _ in 0..REDRAWS {
                let text = words(spec, &list, rng);
                let height = uniform(rng, spec.letter_height);
                let style = pick_style(rng);
                let font = match TextFont::ALL[rng.random_range(0..TextFont::ALL.len())] {
                    // Hairline serifs painted on brick do not read: paint the slab serif.
                    TextFont::Serif if style == PlateStyle::Painted => TextFont::Slab,
                    font => font,
                };
                let plate = TextPlate::measure(&text, text_plate::letter_px(height), font, style);
                let metres_per_px = height / f64::from(plate.letter_px);
                let size = [
                    f64::from(plate.width) * metres_per_px,
                    f64::from(plate.height) * metres_per_px,
                ];
                if let Some((w, rect)) = self.find_spot(rng, size, style) {
                    fitted = Some((text, style, plate, metres_per_px, w, rect));
                    break;
                }
            }
            let Some((text, style, plate, metres_per_px, w, rect)) = fitted else {
                misses += 1;
                continue;
            };
            misses = 0;
            self.placed.entry(w).or_default().push(rect);
            // Painted text shows the wall behind it: its wall patch, ink and priming are
            // made after the (serial) placing, every plate in parallel, from a stream of
            // its own seeded here. A painted plate on a wall without a facade image is
            // drawn as a banner.
            let painted = style == PlateStyle::Painted && self.wall_image(w, placing).is_some();
            let (background, ink) = if painted {
                inks.push(Some(rng.random::<u64>()));
                (Background::Wall(RgbImage::new(0, 0)), [0; 3])
            } else {
                let (paper, ink) = text_colours::pair(rng);
                inks.push(None);
                (Background::Paper(paper), ink)
            };
            let plate = match style {
                PlateStyle::Painted if !painted => TextPlate {
                    style: PlateStyle::Banner,
                    ..plate
                },
                _ => plate,
            };
            let corners = word_corners(&self.walls[w], rect, &plate, metres_per_px);
            placed.push(Placed {
                name: placing.name("text"),
                wall: w,
                rect,
                plate,
                background,
                ink,
                text,
                corners,
                light: None,
            });
        }
        // The ink keeps the contrast floor against the patch's mean (a seeded minority
        // below it), and the floor holds against the wall pixels behind the letters, not
        // only their mean: brick with light mortar is primed first.
        let (walls, images) = (&self.walls, &self.images);
        placed.par_iter_mut().zip(&inks).for_each(|(p, seed)| {
            let wall = &walls[p.wall];
            let image = wall.facade.and_then(|f| images.get(&f)?.as_ref());
            let (Some(seed), Some(image)) = (seed, image) else {
                return;
            };
            let patch = wall_patch(image, wall, p.rect, &p.plate);
            let mut rng = crate::rng::stream(*seed, "painted-text-ink", 0);
            let hard = rng.random::<f64>() < HARD_SHARE;
            p.ink = text_colours::ink_for(&mut rng, mean_luminance(&patch), hard);
            p.background = Background::Wall(text_colours::primed(patch, p.ink, hard));
        });
        finish_plates(
            spec,
            &self.walls,
            placed,
            &format!("{}_atlas", spec.label),
            placing,
        );
        Ok(())
    }

    /// A wall and a free rectangle `[u0, y0, u1, y1]` of `size` on it: clear of the plates
    /// placed so far and of the windows; a shop sign low on the wall.
    fn find_spot(
        &self,
        rng: &mut Pcg64,
        size: [f64; 2],
        style: PlateStyle,
    ) -> Option<(usize, [f64; 4])> {
        (0..ATTEMPTS).find_map(|_| {
            let w = rng.random_range(0..self.walls.len());
            let wall = &self.walls[w];
            let free_u = wall.length - size[0];
            let mut free_y = wall.band[1] - wall.band[0] - size[1];
            if style == PlateStyle::Shop {
                free_y = free_y.min(SHOP_BAND);
            }
            if free_u < 0.0 || free_y < 0.0 {
                return None;
            }
            let u0 = rng.random::<f64>() * free_u;
            let y0 = wall.band[0] + rng.random::<f64>() * free_y;
            let rect = [u0, y0, u0 + size[0], y0 + size[1]];
            let apart = |r: &[f64; 4], gap: f64| {
                rect[2] + gap <= r[0]
                    || r[2] + gap <= rect[0]
                    || rect[3] + gap <= r[1]
                    || r[3] + gap <= rect[1]
            };
            let clear = self
                .placed
                .get(&w)
                .is_none_or(|rects| rects.iter().all(|r| apart(r, SPACING)))
                && wall.windows.iter().all(|r| apart(r, WINDOW_MARGIN));
            clear.then_some((w, rect))
        })
    }

    /// The facade image cladding wall `w` (decoded when first asked for). `None` when the
    /// wall has no facade or its image does not decode or is empty.
    fn wall_image(&mut self, w: usize, placing: &Placing) -> Option<&RgbImage> {
        let f = self.walls[w].facade?;
        self.images
            .entry(f)
            .or_insert_with(|| {
                let image = placing.input.facades.facades[f].texture.decode().ok()?;
                (image.width() > 0 && image.height() > 0).then_some(image)
            })
            .as_ref()
    }
}

/// The wall's own pixels under `rect` (`image` is the facade cladding `wall`), at the
/// plate's size: the background of painted text.
fn wall_patch(image: &RgbImage, wall: &Wall, rect: [f64; 4], plate: &TextPlate) -> RgbImage {
    let (iw, ih) = (f64::from(image.width()), f64::from(image.height()));
    let (pw, ph) = (f64::from(plate.width), f64::from(plate.height));
    // A column's u and a row's height are the same all along it: their taps are found
    // once, not once a pixel.
    let columns: Vec<Tap> = (0..plate.width)
        .map(|x| {
            let u = rect[0] + (f64::from(x) + 0.5) / pw * (rect[2] - rect[0]);
            let [tu, _] = wall.texture_at(u, rect[1]);
            Tap::new(tu * iw - 0.5, image.width())
        })
        .collect();
    let rows: Vec<Tap> = (0..plate.height)
        .map(|y| {
            let height = rect[3] - (f64::from(y) + 0.5) / ph * (rect[3] - rect[1]);
            let [_, tv] = wall.texture_at(rect[0], height);
            Tap::new(tv * ih - 0.5, image.height())
        })
        .collect();
    RgbImage::from_fn(plate.width, plate.height, |x, y| {
        bilinear(image, &columns[x as usize], &rows[y as usize])
    })
}

/// Draws the `placed` plates (their `wall` indexing `walls`), lights each after dusk as
/// its maker chose or else by a draw ([`PlateLight`]), packs them onto atlas pages named
/// `<page_name>_<i>` (one set per light, one material per page) and pushes one text object
/// per plate.
pub(crate) fn finish_plates(
    spec: &ObjectSpec,
    walls: &[Wall],
    placed: Vec<Placed>,
    page_name: &str,
    placing: &mut Placing,
) {
    for (object, info) in plate_objects(&spec.label, walls, placed, page_name, placing) {
        placing.push(object, info);
    }
}

/// As [`finish_plates`], the text objects of class `label` returned in plate order
/// instead of pushed (a car pushes each plate after its car, or keeps its mesh).
pub(crate) fn plate_objects(
    label: &str,
    walls: &[Wall],
    placed: Vec<Placed>,
    page_name: &str,
    placing: &mut Placing,
) -> Vec<(SceneObject, ObjectInfo)> {
    // Drawing the plates and painting and PNG-encoding the pages are the costly parts:
    // all in parallel, each result in its own slot.
    let images: Vec<RgbImage> = placed
        .par_iter()
        .map(|p| p.plate.draw(&p.text, &p.background, p.ink))
        .collect();
    let seed = placing.input.seed;
    // Keyed by where the plate is, not by its name: names are numbered again when the
    // entries placed as two groups are replayed into one (`entry_groups`).
    let lights: Vec<PlateLight> = placed
        .iter()
        .map(|p| {
            p.light.unwrap_or_else(|| {
                let at = format!("{}/{:?}", p.wall, p.rect.map(f64::to_bits));
                PlateLight::draw(p.plate.style, seed, &at)
            })
        })
        .collect();
    let slots = plate_light::pack_pages(images, &lights, page_name, placing);
    placed
        .into_iter()
        .zip(slots)
        .zip(lights)
        .map(|((p, slot), light)| {
            let object = SceneObject {
                name: p.name,
                kind: crate::model::ObjectKind::Text,
                class: label.to_owned(),
                meshes: vec![plate_mesh(&walls[p.wall], p.rect, slot.material, slot.uv)],
            };
            let mut attributes = text_attributes(&p.plate);
            attributes.insert("text_light".to_owned(), light.name().to_owned());
            let info = ObjectInfo {
                traffic: None,
                label: label.to_owned(),
                text: Some(p.text),
                corners: p.corners,
                attributes,
                keypoints: None,
            };
            (object, info)
        })
        .collect()
}

/// The words an entry draws from: its `words_file`'s, else the built-in list. Errors when
/// the file is missing from the driver's reads or holds no word.
pub(crate) fn word_source(
    spec: &ObjectSpec,
    placing: &Placing,
) -> Result<Vec<String>, ObjectsError> {
    match &spec.words_file {
        None => Ok(WORDS.iter().map(|w| (*w).to_owned()).collect()),
        Some(file) => {
            let missing = || ObjectsError::MissingWords { file: file.clone() };
            let bytes = &placing.input.meshes.get(file).ok_or_else(missing)?.obj;
            let words = parse_words(&String::from_utf8_lossy(bytes));
            if words.is_empty() {
                return Err(missing());
            }
            Ok(words)
        }
    }
}

/// Plate style drawn by its share in [`PlateStyle::WALL_MIX`].
fn pick_style(rng: &mut Pcg64) -> PlateStyle {
    let total: u32 = PlateStyle::WALL_MIX.iter().map(|(_, n)| n).sum();
    let mut k = rng.random_range(0..total);
    for (style, n) in PlateStyle::WALL_MIX {
        if k < n {
            return style;
        }
        k -= n;
    }
    PlateStyle::WALL_MIX[0].0
}

/// The COCO attributes of a text object: its plate style and font.
pub fn text_attributes(plate: &TextPlate) -> BTreeMap<String, String> {
    BTreeMap::from([
        ("text_font".to_owned(), plate.font.name().to_owned()),
        ("text_style".to_owned(), plate.style.name().to_owned()),
    ])
}

/// Mean luminance of an image's pixels.
fn mean_luminance(image: &RgbImage) -> f64 {
    let n = (image.width() * image.height()).max(1);
    image.pixels().map(|p| luminance(p.0)).sum::<f64>() / f64::from(n)
}

/// One axis of a bilinear tap: the two texels either side of a texel coordinate (centres
/// on integers), clamped at the image edges, and the second one's weight.
struct Tap {
    near: u32,
    far: u32,
    weight: f64,
}

impl Tap {
    /// The tap at coordinate `t` along an axis of `size` texels (at least 1).
    fn new(t: f64, size: u32) -> Tap {
        let f = floor(t);
        let last = i64::from(size) - 1;
        Tap {
            near: (f as i64).clamp(0, last) as u32,
            far: (f as i64).saturating_add(1).clamp(0, last) as u32,
            weight: t - f,
        }
    }
}

/// Bilinear sample of `image` at the taps `x` and `y`.
fn bilinear(image: &RgbImage, x: &Tap, y: &Tap) -> image::Rgb<u8> {
    let (ax, ay) = (x.weight, y.weight);
    let (p00, p10, p01, p11) = (
        image.get_pixel(x.near, y.near).0,
        image.get_pixel(x.far, y.near).0,
        image.get_pixel(x.near, y.far).0,
        image.get_pixel(x.far, y.far).0,
    );
    image::Rgb(std::array::from_fn(|c| {
        let top = f64::from(p00[c]) * (1.0 - ax) + f64::from(p10[c]) * ax;
        let bottom = f64::from(p01[c]) * (1.0 - ax) + f64::from(p11[c]) * ax;
        round(top * (1.0 - ay) + bottom * ay) as u8
    }))
}

/// The gap from a wall to a road straight in front of it, if the road is in front.
type GapToRoad<'a> = dyn Fn(&RoadRect) -> Option<f64> + 'a;

/// Every wall of every building that faces a road, in (building, north-east-south-west)
/// order.
pub fn facing_walls(input: &ObjectsInput) -> Vec<Wall> {
    let choice = input.facade_choice();
    let chosen = choice.all(input.buildings);
    let heights = choice.heights(&chosen);
    let rects: Vec<RoadRect> = input.layout.roads.iter().map(RoadRect::of).collect();
    let reach = ROAD_REACH * f64::from(strip_width_px(input.layout)) + 1.0;
    let mpp = input.metres_per_pixel;
    // The buildings' footprints in layout pixels, in buckets about a building wide.
    let mut footprints = FootprintGrid::new(32.0);
    for building in input.buildings {
        let f = building.footprint;
        footprints.push(Footprint::Rect(
            [f64::from(f.x0), f64::from(f.x1)],
            [f64::from(f.y0), f64::from(f.y1)],
        ));
    }
    let mut walls = Vec::new();
    for (b, (building, &height)) in input.buildings.iter().zip(&heights).enumerate() {
        let fp = building.footprint;
        let (x0, x1) = (f64::from(fp.x0), f64::from(fp.x1));
        let (y0, y1) = (f64::from(fp.y0), f64::from(fp.y1));
        let overlaps = |a: [f64; 2], b: [f64; 2]| a[0] < b[1] && b[0] < a[1];
        // (normal, bottom-left corner seen from the front, gap to a road in front, the
        // rectangle `gap` ahead of the wall: where a rectangle with a smaller gap must reach)
        type Ahead = fn([f64; 4], f64) -> [f64; 4];
        let sides: [([f64; 2], [f64; 2], &GapToRoad, Ahead); 4] = [
            (
                [0.0, -1.0],
                [x1, y0],
                &|r| (overlaps(r.x, [x0, x1]) && r.y[1] <= y0).then(|| y0 - r.y[1]),
                |[x0, y0, x1, _], g| [x0, y0 - g, x1, y0],
            ),
            (
                [1.0, 0.0],
                [x1, y1],
                &|r| (overlaps(r.y, [y0, y1]) && r.x[0] >= x1).then(|| r.x[0] - x1),
                |[_, y0, x1, y1], g| [x1, y0, x1 + g, y1],
            ),
            (
                [0.0, 1.0],
                [x0, y1],
                &|r| (overlaps(r.x, [x0, x1]) && r.y[0] >= y1).then(|| r.y[0] - y1),
                |[x0, _, x1, y1], g| [x0, y1, x1, y1 + g],
            ),
            (
                [-1.0, 0.0],
                [x0, y0],
                &|r| (overlaps(r.y, [y0, y1]) && r.x[1] <= x0).then(|| x0 - r.x[1]),
                |[x0, y0, _, y1], g| [x0 - g, y0, x0, y1],
            ),
        ];
        let band = [KERB_Y + MIN_HEIGHT, KERB_Y + height - TOP_CLEARANCE];
        if band[1] <= band[0] {
            continue;
        }
        let facade = chosen[b];
        for (normal, corner, gap, ahead) in sides {
            // The nearest road in front must be within reach, and nearer than any other
            // building in front. A building in front nearer than the road lies in the
            // rectangle `to_road` ahead of the wall: only those are asked.
            let Some(to_road) = rects.iter().filter_map(gap).reduce(f64::min) else {
                continue;
            };
            if to_road > reach {
                continue;
            }
            let [a0, a1, a2, a3] = ahead([x0, y0, x1, y1], to_road);
            let probe = Footprint::Rect([a0, a2], [a1, a3]);
            let blocked = footprints.any_near(&probe, |o, f| {
                let &Footprint::Rect(x, y) = f else {
                    return false;
                };
                o != b && gap(&RoadRect { x, y }).is_some_and(|g| g < to_road)
            });
            if blocked {
                continue;
            }
            let length = if normal[0] == 0.0 { x1 - x0 } else { y1 - y0 } * mpp;
            let f = facade.map(|f| &input.facades.facades[f]);
            let repeat = choice.repeat(f, length);
            let windows = f.map_or_else(Vec::new, |f| {
                window_rects(&f.windows, length, repeat, height)
            });
            walls.push(Wall {
                building: building.id,
                origin: [corner[0] * mpp, corner[1] * mpp],
                right: [normal[1], -normal[0]],
                normal,
                length,
                band,
                facade,
                repeat,
                height,
                windows,
                tiling: Tiling::Stretched,
            });
        }
    }
    walls
}

/// A facade's window boxes (texture coordinates, v down from the roof line) as rectangles
/// `[u0, y0, u1, y1]` in metres on a wall `length` long and `height` high whose facade
/// repeats every `repeat` metres.
fn window_rects(windows: &[[f32; 4]], length: f64, repeat: f64, height: f64) -> Vec<[f64; 4]> {
    let copies = (length / repeat).ceil().clamp(1.0, 1000.0) as u32;
    let mut out = Vec::new();
    for k in 0..copies {
        let start = f64::from(k) * repeat;
        for w in windows {
            let [u0, v0, u1, v1] = w.map(f64::from);
            let (a, b) = (start + u0 * repeat, (start + u1 * repeat).min(length));
            if a < b {
                out.push([
                    a,
                    KERB_Y + height * (1.0 - v1),
                    b,
                    KERB_Y + height * (1.0 - v0),
                ]);
            }
        }
    }
    out
}

/// As [`window_rects`], on a wall `length` long and `height` high clad at floor scale
/// ([`Tiling::Floors`]) with a facade `repeat` metres wide: each window of the ground
/// floor once, each of the upper floors once per repeat of them up to `height`, each
/// once per facade width from the wall's left edge.
pub fn floor_window_rects(
    windows: &[[f32; 4]],
    [length, height, repeat]: [f64; 3],
    floor: f64,
    floors: u32,
) -> Vec<[f64; 4]> {
    let ground_v = 1.0 - 1.0 / f64::from(floors);
    let upper = floor * f64::from(floors - 1);
    // Per window, the heights above the kerb of its v span in each repeat of the floors:
    // on the ground floor, then on each repeat of the upper floors below `height`.
    let spans: Vec<Vec<[f64; 2]>> = (windows.iter())
        .map(|w| {
            let [v0, v1] = [w[1], w[3]].map(f64::from);
            let mut spans = Vec::new();
            if v1 > ground_v {
                let h = |v: f64| (1.0 - v) / (1.0 - ground_v) * floor;
                spans.push([h(v1), h(v0.max(ground_v))]);
            }
            let mut base = floor;
            while v0 < ground_v && upper > 0.0 && base < height {
                let h = |v: f64| base + (ground_v - v) / ground_v * upper;
                spans.push([h(v1.min(ground_v)), h(v0)]);
                base += upper;
            }
            spans
        })
        .collect();
    let copies = (length / repeat).ceil().clamp(1.0, 1000.0) as u32;
    let mut out = Vec::new();
    for k in 0..copies {
        let start = f64::from(k) * repeat;
        for (w, spans) in windows.iter().zip(&spans) {
            let [u0, u1] = [w[0], w[2]].map(f64::from);
            let (a, b) = (start + u0 * repeat, (start + u1 * repeat).min(length));
            for &[y0, y1] in spans {
                if a < b && y0 < height {
                    out.push([a, KERB_Y + y0, b, KERB_Y + y1.min(height)]);
                }
            }
        }
    }
    out
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

/// Every word's ink box corners: top-left, top-right, bottom-right, bottom-left from the
/// front.
pub(crate) fn word_corners(
    wall: &Wall,
    rect: [f64; 4],
    plate: &TextPlate,
    m_per_px: f64,
) -> Vec<[[f64; 3]; 4]> {
    plate
        .words
        .iter()
        .map(|word| {
            let [bx0, by0, bx1, by1] = word.map(|v| f64::from(v) * m_per_px);
            let (u0, u1) = (rect[0] + bx0, rect[0] + bx1);
            // Image rows run down from the plate's top edge.
            let (top, bottom) = (rect[3] - by0, rect[3] - by1);
            [
                wall_point(wall, u0, top, WALL_OFFSET),
                wall_point(wall, u1, top, WALL_OFFSET),
                wall_point(wall, u1, bottom, WALL_OFFSET),
                wall_point(wall, u0, bottom, WALL_OFFSET),
            ]
        })
        .collect()
}

fn uniform(rng: &mut Pcg64, range: [f64; 2]) -> f64 {
    range[0] + rng.random::<f64>() * (range[1] - range[0])
}

/// The words of one plate drawn from `list`, in the spec's case.
pub fn words(spec: &ObjectSpec, list: &[&str], rng: &mut Pcg64) -> String {
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
            let word = list[rng.random_range(0..list.len())];
            match case {
                TextCase::Upper => word.to_uppercase(),
                TextCase::Lower => word.to_lowercase(),
                TextCase::Title => {
                    let mut chars = word.chars();
                    chars.next().map_or_else(String::new, |first| {
                        first
                            .to_uppercase()
                            .chain(chars.flat_map(char::to_lowercase))
                            .collect()
                    })
                }
                TextCase::Mixed => word.to_owned(),
            }
        })
        .collect();
    words.join(" ")
}
