//! Where a car stands → its registration; a registration → its EU number plate (white,
//! 520 × 110 mm, a blue band at the left, black letters 75 mm tall); a car's frame → the
//! faces its front and rear plates hang on, as text faces for
//! [`super::wall_text::plate_objects`].
//!
//! A registration reads as a German one: a real district code of 1–3 letters, one or two
//! letters and a number of 1–4 digits without a leading zero, at most 8 of them in all
//! (`B AB 1234`, `HH X 17`): three words, so three ICDAR quads. It is drawn from a stream
//! of its own keyed by where the car stands, so plates take nothing from the entry's
//! stream and no car moves for them.

use rand::RngExt;
use rand_pcg::Pcg64;

use super::plate_style::PlateStyle;
use super::text_font::TextFont;
use super::text_plate::TextPlate;
use super::vehicle_parts::Frame;
use super::wall_text::{Tiling, Wall};

/// The plate's size, metres (EU: 520 × 110 mm).
pub const SIZE: [f64; 2] = [0.52, 0.11];
/// The plate image's size, pixels (2.5 mm a pixel).
pub const PIXELS: [u32; 2] = [208, 44];
/// The EU letter height, pixels (75 mm): no glyph's ink is taller.
const INK_HEIGHT: u32 = 30;
/// Room kept between the ink and the band or the right edge, pixels.
const MARGIN: u32 = 6;
/// Letter sizes tried, largest first, until the registration fits.
const LETTER_PX: [u32; 2] = [16, 64];
/// The face plates are lettered in: a bold condensed sans, as the DIN plate face is.
pub const FONT: TextFont = TextFont::Condensed;
/// Paper and letters (sRGB).
pub const PAPER: [u8; 3] = [238, 238, 232];
pub const INK: [u8; 3] = [18, 18, 18];

/// District codes registrations start with (German cities and districts).
const DISTRICTS: [&str; 36] = [
    "B", "M", "HH", "K", "F", "S", "D", "DO", "E", "HB", "H", "L", "DD", "N", "KA", "MA", "BN",
    "MS", "WI", "KI", "HD", "A", "AC", "BI", "BO", "GE", "OB", "MZ", "DU", "WU", "R", "HRO", "FFB",
    "LDS", "HG", "GL",
];

/// The registration of the car standing at `at` (x, z metres), from its own stream.
pub fn registration(seed: u64, at: [f64; 2]) -> String {
    let mut rng = crate::rng::stream(seed, &format!("number_plate/{:?}", at.map(f64::to_bits)), 0);
    registration_from(&mut rng)
}

/// A registration drawn from `rng`.
fn registration_from(rng: &mut Pcg64) -> String {
    let district = DISTRICTS[rng.random_range(0..DISTRICTS.len())];
    let letters: String = (0..rng.random_range(1..=2))
        .map(|_| char::from(b'A' + rng.random_range(0..26u8)))
        .collect();
    let room = 8 - district.len() - letters.len();
    let digits = rng.random_range(1..=room.min(4)) as u32;
    let number = rng.random_range(10u32.pow(digits - 1)..10u32.pow(digits));
    format!("{district} {letters} {number}")
}

/// The plate of `text`: [`PIXELS`] in size, the letters as large as fit (their ink at
/// most [`INK_HEIGHT`] tall and clear of the band), centred right of the band.
pub fn measure(text: &str) -> TextPlate {
    let band = (PIXELS[0] * 40).div_ceil(520);
    let room = PIXELS[0] - band - 2 * MARGIN;
    let ink = |p: &TextPlate| {
        p.words
            .iter()
            .fold([f32::MAX, f32::MAX, f32::MIN, f32::MIN], |b, w| {
                [
                    b[0].min(w[0]),
                    b[1].min(w[1]),
                    b[2].max(w[2]),
                    b[3].max(w[3]),
                ]
            })
    };
    let fits = |p: &TextPlate| {
        let b = ink(p);
        b[2] - b[0] <= room as f32 && b[3] - b[1] <= INK_HEIGHT as f32
    };
    let plate = (LETTER_PX[0]..=LETTER_PX[1])
        .rev()
        .map(|px| TextPlate::measure(text, px, FONT, PlateStyle::Number))
        .find(fits)
        .unwrap_or_else(|| TextPlate::measure(text, LETTER_PX[0], FONT, PlateStyle::Number));
    let b = ink(&plate);
    let target = [
        f64::from(band + MARGIN) + (f64::from(room) - f64::from(b[2] - b[0])) / 2.0,
        (f64::from(PIXELS[1]) - f64::from(b[3] - b[1])) / 2.0,
    ];
    // Whole pixels, so the glyphs land on the pixel grid as they were measured.
    let shift = [
        (target[0] - f64::from(b[0])).round() as f32,
        (target[1] - f64::from(b[1])).round() as f32,
    ];
    let clamp = |v: f32, max: u32| v.clamp(0.0, max as f32) as u32;
    let [x0, y0, x1, y1] = plate.text_box.map(|v| v as f32);
    TextPlate {
        width: PIXELS[0],
        height: PIXELS[1],
        text_box: [
            clamp(x0 + shift[0], PIXELS[0]),
            clamp(y0 + shift[1], PIXELS[1]),
            clamp(x1 + shift[0], PIXELS[0]),
            clamp(y1 + shift[1], PIXELS[1]),
        ],
        words: plate
            .words
            .iter()
            .map(|w| {
                [
                    w[0] + shift[0],
                    w[1] + shift[1],
                    w[2] + shift[0],
                    w[3] + shift[1],
                ]
            })
            .collect(),
        origin: [plate.origin[0] + shift[0], plate.origin[1] + shift[1]],
        ..plate
    }
}

/// The face a plate hangs on at `u` along the car in `frame` (its front, `facing` 1, or
/// its rear, −1), the plate's bottom edge `bottom` metres above the ground, and the plate's
/// rectangle on it (`[u0, y0, u1, y1]`, as on a wall): the plate stands
/// [`super::wall_text::WALL_OFFSET`] in front of the body's face.
pub fn face(frame: &Frame, u: f64, facing: f64, bottom: f64) -> (Wall, [f64; 4]) {
    let n = frame.dir(facing, 0.0, 0.0);
    let normal = [n[0], n[2]];
    let right = [normal[1], -normal[0]];
    let centre = frame.at(u, 0.0, 0.0);
    let y0 = frame.origin[1] + bottom;
    let [w, h] = SIZE;
    let wall = Wall {
        building: u32::MAX,
        origin: [
            centre[0] - right[0] * w / 2.0,
            centre[2] - right[1] * w / 2.0,
        ],
        right,
        normal,
        length: w,
        band: [y0, y0 + h],
        facade: None,
        repeat: w,
        height: h,
        windows: Vec::new(),
        tiling: Tiling::Stretched,
    };
    (wall, [0.0, y0, w, y0 + h])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::objects::text_plate::Background;

    #[test]
    fn registrations_read_as_german_ones_and_vary() {
        let mut rng = crate::rng::stream(3, "test", 0);
        let drawn: Vec<String> = (0..400).map(|_| registration_from(&mut rng)).collect();
        for r in &drawn {
            let words: Vec<&str> = r.split(' ').collect();
            assert_eq!(words.len(), 3, "{r}");
            assert!(DISTRICTS.contains(&words[0]), "{r}");
            assert!((1..=2).contains(&words[1].len()), "{r}");
            assert!(words[1].bytes().all(|b| b.is_ascii_uppercase()), "{r}");
            assert!(words[2].bytes().all(|b| b.is_ascii_digit()), "{r}");
            assert!(!words[2].starts_with('0') && words[2].len() <= 4, "{r}");
            assert!(r.len() - 2 <= 8, "{r}");
        }
        let distinct: std::collections::BTreeSet<&String> = drawn.iter().collect();
        assert!(distinct.len() > 390, "{}", distinct.len());
        assert_eq!(registration(1, [2.0, 3.0]), registration(1, [2.0, 3.0]));
        assert_ne!(registration(1, [2.0, 3.0]), registration(1, [2.0, 3.5]));
    }

    #[test]
    fn the_letters_fill_the_plate_right_of_the_band_and_no_ink_leaves_their_words() {
        let band = (PIXELS[0] * 40).div_ceil(520);
        for text in ["B A 1", "HRO XY 123", "M AB 1234", "LDS W 9999", "HH QQ 88"] {
            let plate = measure(text);
            assert_eq!([plate.width, plate.height], PIXELS);
            assert_eq!(plate.words.len(), 3);
            for w in &plate.words {
                assert!(w[0] >= (band + MARGIN - 1) as f32, "{text}: {w:?}");
                assert!(w[2] <= (PIXELS[0] - MARGIN + 1) as f32, "{text}: {w:?}");
                assert!(
                    w[1] >= 4.0 && w[3] <= PIXELS[1] as f32 - 4.0,
                    "{text}: {w:?}"
                );
            }
            // Capitals and digits nearly 75 mm tall: the plate is read, not squinted at.
            let tall = plate.words.iter().map(|w| w[3] - w[1]).fold(0.0, f32::max);
            assert!(tall >= 24.0, "{text}: {tall}");
            let image = plate.draw(text, &Background::Paper(PAPER), INK);
            let mut blue = 0;
            for (x, y, p) in image.enumerate_pixels() {
                let (xf, yf) = (x as f32 + 0.5, y as f32 + 0.5);
                let rim = x == 0 || y == 0 || x == PIXELS[0] - 1 || y == PIXELS[1] - 1;
                if p.0 == super::super::plate_style::EU_BLUE {
                    blue += 1;
                    assert!(x < band, "{text}: blue at {x},{y}");
                } else if p.0 != PAPER && !rim {
                    let inside = plate.words.iter().any(|w| {
                        w[0] - 1.0 <= xf && xf <= w[2] + 1.0 && w[1] - 1.0 <= yf && yf <= w[3] + 1.0
                    });
                    assert!(inside, "{text}: ink at {x},{y}");
                }
            }
            assert!(blue > 500, "{text}: {blue}");
        }
    }

    #[test]
    fn plates_face_out_of_the_front_and_the_rear() {
        let frame = Frame {
            origin: [10.0, 0.0, 5.0],
            forward: [0.0, 1.0],
        };
        let (front, rect) = face(&frame, 4.6, 1.0, 0.45);
        assert_eq!(front.normal, [0.0, 1.0]);
        assert_eq!(rect, [0.0, 0.45, SIZE[0], 0.45 + SIZE[1]]);
        let (rear, _) = face(&frame, 0.0, -1.0, 0.5);
        assert_eq!(rear.normal, [0.0, -1.0]);
        // Both plates are centred across the car.
        for (wall, z) in [(&front, 9.6), (&rear, 5.0)] {
            let mid = [
                wall.origin[0] + wall.right[0] * SIZE[0] / 2.0,
                wall.origin[1] + wall.right[1] * SIZE[0] / 2.0,
            ];
            assert!(
                (mid[0] - 10.0).abs() < 1e-9 && (mid[1] - z).abs() < 1e-9,
                "{mid:?}"
            );
        }
    }
}
