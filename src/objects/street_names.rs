//! Street-name specs + street corners → `street_pole_NNNN` poles carrying two double-sided
//! plates, each face a `text_NNNN` text object naming one of the two streets that meet.
//!
//! Every road gets one name for the whole city: a word from the entry's word source and a
//! suffix (`St`, `Ave`, …) drawn from `rng::stream(seed, "street_names", road id)`, so a
//! street reads the same at all its corners. A sign stands at a corner half a strip from
//! both curbs ([`GroundSpots::corners`]), in a random order of the corners; a corner whose
//! circle is taken (a lamp, a sign of an earlier entry) is skipped. The plate naming a
//! street runs along it, so drivers on the crossing street read it face on; the two plates
//! are stacked on the pole's top, in a random order. Plates are drawn like wall text
//! ([`super::wall_text::finish_plates`]): per word ICDAR quads, font and style attributes
//! (`text_style = "street"`).

use rand::RngExt;
use rand_pcg::Pcg64;

use super::ground_spots::{Footprint, GroundSpots};
use super::plate_style::PlateStyle;
use super::text_font::TextFont;
use super::text_plate::{self, Background, TextPlate};
use super::wall_text::{self, Placed, Tiling, Wall};
use super::{ObjectsError, Placing};
use crate::model::geometry::{KERB_Y, MeshBuilder};
use crate::spec::{ObjectSpec, TextCase};

/// Height of the pole's top (the lower plate's bottom edge) above the sidewalk, metres.
pub const POLE_HEIGHT: f64 = 2.6;
/// Half the pole's thickness, metres.
pub const POLE_HALF: f64 = 0.04;
/// Gap between the two plates (a bracket bridges it), metres.
pub const PLATE_GAP: f64 = 0.06;
/// Half the plate body's thickness; the text faces stand [`wall_text::WALL_OFFSET`] off
/// its middle plane, just outside it.
pub const BODY_HALF: f64 = 0.02;
/// Suffixes a street's name ends with.
pub const SUFFIXES: [&str; 6] = ["St", "Ave", "Rd", "Blvd", "Lane", "Way"];
/// Faces street-name plates are lettered in: the plain sans and display faces signs use.
const FONTS: [TextFont; 4] = [
    TextFont::Sans,
    TextFont::Condensed,
    TextFont::Display,
    TextFont::Slab,
];
/// Plate and letter colours of street-name signs as cities paint them: white on green,
/// white on blue, black on white, white on black, white on brown.
const COLOURS: [([u8; 3], [u8; 3]); 5] = [
    ([20, 105, 60], [250, 250, 245]),
    ([25, 65, 150], [250, 250, 245]),
    ([245, 245, 240], [15, 15, 15]),
    ([25, 25, 28], [250, 250, 245]),
    ([95, 55, 30], [250, 245, 235]),
];

/// Paint of the pole (signal poles share it).
pub(super) const POLE_GREY: [f32; 3] = [0.3, 0.31, 0.33];

/// A street corner a sign may stand at: where, and the names and directions of the two
/// streets that meet there (each plate runs along its street).
#[derive(Clone, Debug, PartialEq)]
pub struct NamedCorner {
    pub position: [f64; 2],
    pub streets: [(String, [f64; 2]); 2],
}

/// Places up to `spec.count` street-name signs at a layout's corners; returns how many
/// poles stand.
pub fn place(
    spec: &ObjectSpec,
    rng: &mut Pcg64,
    spots: &mut GroundSpots,
    placing: &mut Placing,
) -> Result<u32, ObjectsError> {
    let source = wall_text::word_source(spec, placing)?;
    let list: Vec<&str> = source.iter().map(String::as_str).collect();
    let names: Vec<String> = placing
        .input
        .layout
        .roads
        .iter()
        .map(|road| street_name(spec, &list, placing.input.seed, road.id))
        .collect();
    // The horizontal road's plate runs along x, the vertical one's along z.
    let corners: Vec<NamedCorner> = (spots.shuffled_corners(rng).into_iter())
        .map(|corner| NamedCorner {
            position: corner.position,
            streets: [
                (names[corner.roads[0] as usize].clone(), [1.0, 0.0]),
                (names[corner.roads[1] as usize].clone(), [0.0, 1.0]),
            ],
        })
        .collect();
    Ok(place_at(
        spec,
        rng,
        &corners,
        &mut |f| spots.claim(f),
        placing,
    ))
}

/// Places up to `spec.count` street-name signs at `corners`, in their order, a corner
/// whose circle `claim` refuses skipped; returns how many poles stand.
// Long on purpose: one placement loop, whose random draws must stay in this order (each
// changes every later object's); split, the order would be spread over functions.
pub fn place_at(
    spec: &ObjectSpec,
    rng: &mut Pcg64,
    corners: &[NamedCorner],
    claim: &mut dyn FnMut(Footprint) -> bool,
    placing: &mut Placing,
) -> u32 {
    let pole_material = placing.material("street_pole", || (POLE_GREY, None));
    let mut faces: Vec<Wall> = Vec::new();
    let mut placed: Vec<Placed> = Vec::new();
    let mut poles = 0u32;
    for corner in corners {
        if poles >= spec.count {
            break;
        }
        let height = spec.letter_height[0]
            + rng.random::<f64>() * (spec.letter_height[1] - spec.letter_height[0]);
        let font = FONTS[rng.random_range(0..FONTS.len())];
        let (paper, ink) = COLOURS[rng.random_range(0..COLOURS.len())];
        let upper_first: bool = rng.random();
        let letter = text_plate::letter_px(height);
        let metres_per_px = height / f64::from(letter);
        // (plate, text, direction of its street).
        let plates: Vec<(TextPlate, &str, [f64; 2])> = (corner.streets.iter())
            .map(|(name, along)| {
                let plate = TextPlate::measure(name, letter, font, PlateStyle::Street);
                (plate, name.as_str(), *along)
            })
            .collect();
        let size = |p: &TextPlate| {
            [
                f64::from(p.width) * metres_per_px,
                f64::from(p.height) * metres_per_px,
            ]
        };
        let reach = plates
            .iter()
            .map(|(p, ..)| size(p)[0] / 2.0)
            .fold(0.0, f64::max);
        if !claim(Footprint::Circle(corner.position, reach + 0.1)) {
            continue;
        }
        poles += 1;
        let order: [usize; 2] = if upper_first { [1, 0] } else { [0, 1] };
        let [x, z] = corner.position;
        let mut pole = MeshBuilder::new(pole_material);
        pole.oriented_box(
            [x, KERB_Y, z],
            [1.0, 0.0],
            [POLE_HALF, POLE_HALF],
            POLE_HEIGHT,
        );
        let mut bottom = KERB_Y + POLE_HEIGHT;
        for (k, &p) in order.iter().enumerate() {
            let (plate, text, along) = &plates[p];
            let [w, h] = size(plate);
            if k == 1 {
                // The bracket between the plates.
                let half = [BODY_HALF, BODY_HALF];
                pole.oriented_box([x, bottom, z], [1.0, 0.0], half, PLATE_GAP);
                bottom += PLATE_GAP;
            }
            // The plate's body, along its street.
            let along = *along;
            pole.oriented_box([x, bottom, z], along, [w / 2.0, BODY_HALF], h);
            for normal in [[-along[1], along[0]], [along[1], -along[0]]] {
                let right = [normal[1], -normal[0]];
                let face = Wall {
                    building: u32::MAX,
                    origin: [x - right[0] * w / 2.0, z - right[1] * w / 2.0],
                    right,
                    normal,
                    length: w,
                    band: [bottom, bottom + h],
                    facade: None,
                    repeat: w,
                    height: bottom + h - KERB_Y,
                    windows: Vec::new(),
                    tiling: Tiling::Stretched,
                };
                let rect = [0.0, bottom, w, bottom + h];
                let corners = wall_text::word_corners(&face, rect, plate, metres_per_px);
                faces.push(face);
                placed.push(Placed {
                    name: placing.name("text"),
                    wall: faces.len() - 1,
                    rect,
                    plate: plate.clone(),
                    background: Background::Paper(paper),
                    ink,
                    text: (*text).to_owned(),
                    corners,
                    light: None,
                });
            }
            bottom += h;
        }
        let name = placing.name("street_pole");
        placing.push_plain(
            crate::model::ObjectKind::StreetPole,
            name,
            "pole",
            vec![pole.finish()],
        );
    }
    let page_name = format!("{}_street_atlas", spec.label);
    wall_text::finish_plates(spec, &faces, placed, &page_name, placing);
    poles
}

/// The name of road `road`: a word from `list` in the entry's case and a suffix, drawn from
/// the road's own stream so it is the same at every corner and for every entry.
fn street_name(spec: &ObjectSpec, list: &[&str], seed: u64, road: u32) -> String {
    let mut rng = crate::rng::stream(seed, "street_names", u64::from(road));
    let one_word = ObjectSpec {
        words: [1, 1],
        case: match spec.case {
            // Mixed picks per plate; a street keeps one spelling at all its corners.
            TextCase::Mixed => TextCase::Title,
            case => case,
        },
        ..spec.clone()
    };
    let word = wall_text::words(&one_word, list, &mut rng);
    let suffix = SUFFIXES[rng.random_range(0..SUFFIXES.len())];
    let suffix = match one_word.case {
        TextCase::Upper => suffix.to_uppercase(),
        TextCase::Lower => suffix.to_lowercase(),
        _ => suffix.to_owned(),
    };
    format!("{word} {suffix}")
}
