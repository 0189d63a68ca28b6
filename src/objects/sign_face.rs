//! A sign kind (and speed) → its 256 px face texture and its outline in texture space.
//!
//! The outline is the plate's real shape (octagon, triangle, 16-gon circle, square,
//! diamond, a wide rectangle), so the plate geometry — and an annotation box from it — is
//! exactly the sign. Each texture fills its whole square with the shape's rim colour first,
//! so the outline's edges never show anything but the sign. The faces follow Germany's
//! catalogue (StVO): a warning is a white triangle with a red rim and a black pictogram, a
//! prohibition a white disc with a red rim, a command a blue disc with a white pictogram,
//! information a blue square or rectangle. Pictograms are simplified, drawn from bars,
//! discs and polygons.

use ab_glyph::PxScale;
use image::{Rgb, RgbImage};
use imageproc::drawing::{draw_filled_circle_mut, draw_polygon_mut, draw_text_mut, text_size};
use imageproc::point::Point;

use super::text_plate::FONT;
use super::trig::cos_sin_deg;
use crate::spec::SignKind;

/// Side of a sign texture in pixels.
pub const SIZE: u32 = 256;

const RED: Rgb<u8> = Rgb([200, 16, 32]);
const WHITE: Rgb<u8> = Rgb([245, 245, 245]);
const BLUE: Rgb<u8> = Rgb([16, 72, 170]);
const BLACK: Rgb<u8> = Rgb([20, 20, 20]);
const YELLOW: Rgb<u8> = Rgb([250, 190, 0]);
const AMBER: Rgb<u8> = Rgb([245, 140, 0]);
const GREEN: Rgb<u8> = Rgb([0, 120, 60]);
const SIGNAL_GREEN: Rgb<u8> = Rgb([20, 170, 70]);

/// A plate's shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Shape {
    Octagon,
    /// A triangle, point down (give way).
    Down,
    /// A triangle, point up (warnings).
    Up,
    Round,
    Square,
    /// A rectangle twice as wide as high (one way).
    Wide,
    Diamond,
}

fn shape(kind: SignKind) -> Shape {
    use SignKind::*;
    match kind {
        Stop => Shape::Octagon,
        Yield => Shape::Down,
        PriorityJunction | Danger | Crossroads | BendLeft | BendRight | Slippery | RoadNarrows
        | RoadWorks | TrafficSignals | Pedestrians | Children | Cyclists => Shape::Up,
        SpeedLimit | NoEntry | NoParking | NoStopping | NoOvertaking | NoVehicles
        | NoMotorVehicles | NoBicycles | TurnRight | StraightOrRight | CyclePath | Footpath
        | SharedPath | BusStop => Shape::Round,
        PedestrianCrossing | Parking | DeadEnd => Shape::Square,
        OneWay => Shape::Wide,
        PriorityRoad => Shape::Diamond,
    }
}

/// The sign's outline in texture coordinates (u right, v down, 0–1), counter-clockwise as
/// seen on the texture (from the sign's front), convex.
pub fn outline(kind: SignKind) -> Vec<[f64; 2]> {
    let ring = |n: u32, start: f64| -> Vec<[f64; 2]> {
        (0..n)
            .map(|k| {
                // Angles increase anticlockwise on screen: v runs down, so subtract sin.
                let (c, s) = cos_sin_deg(start + 360.0 * f64::from(k) / f64::from(n));
                [0.5 + 0.5 * c, 0.5 - 0.5 * s]
            })
            .collect()
    };
    match shape(kind) {
        Shape::Octagon => ring(8, 22.5),
        Shape::Down => vec![[0.0, 0.06], [0.5, 0.93], [1.0, 0.06]],
        Shape::Up => vec![[0.5, 0.07], [0.0, 0.93], [1.0, 0.93]],
        Shape::Round => ring(16, 0.0),
        Shape::Square => vec![[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]],
        Shape::Wide => vec![[0.0, 0.27], [0.0, 0.73], [1.0, 0.73], [1.0, 0.27]],
        Shape::Diamond => vec![[0.5, 0.0], [0.0, 0.5], [0.5, 1.0], [1.0, 0.5]],
    }
}

/// The face texture of `kind`; `speed` is the number on a speed-limit sign.
pub fn draw(kind: SignKind, speed: u32) -> RgbImage {
    if kind == SignKind::BendRight {
        // 103-20 is 103-10 mirrored; the triangle is symmetric.
        return image::imageops::flip_horizontal(&draw(SignKind::BendLeft, speed));
    }
    let mut image = base(kind);
    match shape(kind) {
        Shape::Up => warning(&mut image, kind),
        Shape::Round => round(&mut image, kind, speed),
        _ => other(&mut image, kind),
    }
    image
}

/// The face without its pictogram: the plate's colours, rim and field.
fn base(kind: SignKind) -> RgbImage {
    use SignKind::*;
    let mut image = RgbImage::from_pixel(SIZE, SIZE, RED);
    let scaled = |image: &mut RgbImage, by: f64, about: [f64; 2], colour| {
        let ring: Vec<Point<i32>> = outline(kind)
            .iter()
            .map(|p| {
                point(
                    about[0] + (p[0] - about[0]) * by,
                    about[1] + (p[1] - about[1]) * by,
                )
            })
            .collect();
        draw_polygon_mut(image, &ring, colour);
    };
    match kind {
        Stop => {
            scaled(&mut image, 0.9, [0.5, 0.5], WHITE);
            scaled(&mut image, 0.82, [0.5, 0.5], RED);
        }
        Yield => scaled(&mut image, 0.6, [0.5, 0.35], WHITE),
        NoEntry => {}
        _ if shape(kind) == Shape::Up => scaled(&mut image, 0.8, [0.5, 0.64], WHITE),
        NoParking | NoStopping => disc(&mut image, [0.5, 0.5], 0.38, BLUE),
        TurnRight | StraightOrRight | CyclePath | Footpath | SharedPath => {
            image = RgbImage::from_pixel(SIZE, SIZE, WHITE);
            disc(&mut image, [0.5, 0.5], 0.47, BLUE);
        }
        BusStop => {
            image = RgbImage::from_pixel(SIZE, SIZE, GREEN);
            disc(&mut image, [0.5, 0.5], 0.42, YELLOW);
        }
        PriorityRoad => {
            image = RgbImage::from_pixel(SIZE, SIZE, BLACK);
            scaled(&mut image, 0.95, [0.5, 0.5], WHITE);
            scaled(&mut image, 0.62, [0.5, 0.5], YELLOW);
        }
        PedestrianCrossing | Parking | DeadEnd | OneWay => {
            image = RgbImage::from_pixel(SIZE, SIZE, BLUE);
        }
        _ => disc(&mut image, [0.5, 0.5], 0.39, WHITE),
    }
    image
}

/// A warning's black pictogram, in the white triangle (its centre about (0.5, 0.64)).
fn warning(image: &mut RgbImage, kind: SignKind) {
    use SignKind::*;
    let c = BLACK;
    match kind {
        Danger => {
            poly(
                image,
                &[[0.47, 0.43], [0.53, 0.43], [0.515, 0.69], [0.485, 0.69]],
                c,
            );
            disc(image, [0.5, 0.77], 0.035, c);
        }
        Crossroads => {
            bar(image, [0.4, 0.47], [0.6, 0.81], 0.06, c);
            bar(image, [0.6, 0.47], [0.4, 0.81], 0.06, c);
        }
        PriorityJunction => {
            bar(image, [0.5, 0.5], [0.5, 0.83], 0.08, c);
            poly(image, &[[0.45, 0.51], [0.5, 0.41], [0.55, 0.51]], c);
            bar(image, [0.37, 0.67], [0.63, 0.67], 0.035, c);
        }
        BendLeft => {
            bar(image, [0.57, 0.84], [0.57, 0.62], 0.07, c);
            disc(image, [0.57, 0.62], 0.035, c);
            bar(image, [0.57, 0.62], [0.46, 0.51], 0.07, c);
            poly(image, &[[0.38, 0.43], [0.51, 0.46], [0.41, 0.56]], c);
        }
        Slippery => {
            car_side(image, [0.5, 0.55], 0.24, c);
            for x in [0.43, 0.57] {
                bar(image, [x, 0.66], [x + 0.035, 0.73], 0.025, c);
                bar(image, [x + 0.035, 0.73], [x - 0.01, 0.8], 0.025, c);
                bar(image, [x - 0.01, 0.8], [x + 0.02, 0.85], 0.025, c);
            }
        }
        RoadNarrows => {
            for s in [-1.0, 1.0] {
                let x = |d: f64| 0.5 + s * d;
                bar(image, [x(0.1), 0.84], [x(0.1), 0.7], 0.04, c);
                bar(image, [x(0.1), 0.7], [x(0.04), 0.58], 0.04, c);
                bar(image, [x(0.04), 0.58], [x(0.04), 0.44], 0.04, c);
            }
        }
        RoadWorks => {
            person(image, [0.56, 0.84], 0.3, c);
            bar(image, [0.53, 0.66], [0.42, 0.8], 0.025, c);
            poly(image, &[[0.33, 0.85], [0.41, 0.76], [0.48, 0.85]], c);
        }
        TrafficSignals => {
            poly(
                image,
                &[[0.43, 0.43], [0.43, 0.85], [0.57, 0.85], [0.57, 0.43]],
                c,
            );
            disc(image, [0.5, 0.5], 0.045, RED);
            disc(image, [0.5, 0.64], 0.045, AMBER);
            disc(image, [0.5, 0.78], 0.045, SIGNAL_GREEN);
        }
        Pedestrians => person(image, [0.5, 0.85], 0.4, c),
        Children => {
            person(image, [0.44, 0.85], 0.38, c);
            person(image, [0.6, 0.85], 0.25, c);
        }
        Cyclists => {
            bicycle(image, [0.5, 0.74], 0.32, c, WHITE);
            disc(image, [0.53, 0.47], 0.03, c);
            bar(image, [0.52, 0.52], [0.46, 0.66], 0.04, c);
            bar(image, [0.52, 0.54], [0.58, 0.63], 0.025, c);
        }
        _ => {}
    }
}

/// A round sign's pictogram: on a white disc with a red rim (prohibitions) or on a blue
/// disc (commands).
fn round(image: &mut RgbImage, kind: SignKind, speed: u32) {
    use SignKind::*;
    match kind {
        SpeedLimit => centred_text(image, &speed.to_string(), 110.0, BLACK),
        NoEntry => poly(
            image,
            &[[0.2, 0.42], [0.2, 0.58], [0.8, 0.58], [0.8, 0.42]],
            WHITE,
        ),
        NoParking => bar(image, [0.23, 0.23], [0.77, 0.77], 0.085, RED),
        NoStopping => {
            bar(image, [0.23, 0.23], [0.77, 0.77], 0.085, RED);
            bar(image, [0.77, 0.23], [0.23, 0.77], 0.085, RED);
        }
        NoOvertaking => {
            car_rear(image, [0.36, 0.52], 0.22, RED);
            car_rear(image, [0.64, 0.52], 0.22, BLACK);
        }
        NoMotorVehicles => car_side(image, [0.5, 0.53], 0.5, BLACK),
        NoBicycles => bicycle(image, [0.5, 0.55], 0.56, BLACK, WHITE),
        TurnRight => {
            bar(image, [0.42, 0.8], [0.42, 0.48], 0.1, WHITE);
            disc(image, [0.42, 0.48], 0.05, WHITE);
            bar(image, [0.42, 0.48], [0.6, 0.48], 0.1, WHITE);
            poly(image, &[[0.6, 0.34], [0.78, 0.48], [0.6, 0.62]], WHITE);
        }
        StraightOrRight => {
            bar(image, [0.4, 0.82], [0.4, 0.36], 0.09, WHITE);
            poly(image, &[[0.28, 0.38], [0.4, 0.2], [0.52, 0.38]], WHITE);
            bar(image, [0.4, 0.62], [0.62, 0.62], 0.09, WHITE);
            poly(image, &[[0.62, 0.5], [0.78, 0.62], [0.62, 0.74]], WHITE);
        }
        CyclePath => bicycle(image, [0.5, 0.52], 0.6, WHITE, BLUE),
        Footpath => {
            person(image, [0.43, 0.8], 0.5, WHITE);
            person(image, [0.61, 0.8], 0.32, WHITE);
        }
        SharedPath => {
            bar(image, [0.1, 0.5], [0.9, 0.5], 0.03, WHITE);
            bicycle(image, [0.5, 0.33], 0.38, WHITE, BLUE);
            person(image, [0.43, 0.8], 0.24, WHITE);
            person(image, [0.58, 0.8], 0.17, WHITE);
        }
        BusStop => centred_text(image, "H", 150.0, GREEN),
        _ => {}
    }
}

/// The pictograms of the octagon, the triangle point down, the squares, the rectangle and
/// the diamond.
fn other(image: &mut RgbImage, kind: SignKind) {
    use SignKind::*;
    match kind {
        Stop => centred_text(image, "STOP", 78.0, WHITE),
        Parking => centred_text(image, "P", 200.0, WHITE),
        PedestrianCrossing => {
            poly(image, &[[0.5, 0.1], [0.1, 0.88], [0.9, 0.88]], WHITE);
            // Zebra stripes under a walking figure.
            for k in 0..4 {
                let x = 0.27 + 0.12 * f64::from(k);
                poly(
                    image,
                    &[[x, 0.78], [x + 0.07, 0.78], [x + 0.07, 0.83], [x, 0.83]],
                    BLACK,
                );
            }
            person(image, [0.5, 0.75], 0.4, BLACK);
        }
        OneWay => poly(
            image,
            &[
                [0.1, 0.45],
                [0.62, 0.45],
                [0.62, 0.36],
                [0.9, 0.5],
                [0.62, 0.64],
                [0.62, 0.55],
                [0.1, 0.55],
            ],
            WHITE,
        ),
        DeadEnd => {
            bar(image, [0.5, 0.88], [0.5, 0.3], 0.2, WHITE);
            bar(image, [0.22, 0.25], [0.78, 0.25], 0.14, RED);
        }
        _ => {}
    }
}

/// A walking figure standing on `foot` (u, v), `h` high.
fn person(image: &mut RgbImage, foot: [f64; 2], h: f64, c: Rgb<u8>) {
    let [x, y] = foot;
    let top = y - h;
    disc(image, [x + 0.02 * h, top + 0.09 * h], 0.09 * h, c);
    let (shoulder, hip) = ([x, top + 0.23 * h], [x - 0.02 * h, top + 0.56 * h]);
    bar(image, shoulder, hip, 0.17 * h, c);
    bar(image, hip, [x - 0.2 * h, y], 0.12 * h, c);
    bar(image, hip, [x + 0.17 * h, y], 0.12 * h, c);
    bar(image, shoulder, [x - 0.17 * h, top + 0.52 * h], 0.08 * h, c);
    bar(image, shoulder, [x + 0.18 * h, top + 0.48 * h], 0.08 * h, c);
}

/// A bicycle seen from the side, centred on `at`, `w` wide; `bg` shows through its wheels.
fn bicycle(image: &mut RgbImage, at: [f64; 2], w: f64, c: Rgb<u8>, bg: Rgb<u8>) {
    let [x, y] = at;
    let (rear, front) = ([x - 0.3 * w, y + 0.1 * w], [x + 0.3 * w, y + 0.1 * w]);
    for hub in [rear, front] {
        disc(image, hub, 0.2 * w, c);
        disc(image, hub, 0.15 * w, bg);
    }
    let (seat, crank, head) = (
        [x - 0.08 * w, y - 0.18 * w],
        [x, y + 0.1 * w],
        [x + 0.2 * w, y - 0.18 * w],
    );
    let t = 0.045 * w;
    bar(image, rear, seat, t, c);
    bar(image, seat, crank, t, c);
    bar(image, crank, rear, t, c);
    bar(image, seat, head, t, c);
    bar(image, crank, head, t, c);
    bar(image, head, front, t, c);
    bar(
        image,
        [x - 0.15 * w, y - 0.2 * w],
        [x - 0.01 * w, y - 0.2 * w],
        t,
        c,
    );
}

/// A car seen from the side, centred on `at`, `w` long.
fn car_side(image: &mut RgbImage, at: [f64; 2], w: f64, c: Rgb<u8>) {
    let [x, y] = at;
    let h = |k: f64| y + k * w;
    poly(
        image,
        &[
            [x - 0.5 * w, h(-0.08)],
            [x - 0.5 * w, h(0.12)],
            [x + 0.5 * w, h(0.12)],
            [x + 0.5 * w, h(-0.04)],
        ],
        c,
    );
    poly(
        image,
        &[
            [x - 0.3 * w, h(-0.06)],
            [x - 0.18 * w, h(-0.28)],
            [x + 0.18 * w, h(-0.28)],
            [x + 0.34 * w, h(-0.04)],
        ],
        c,
    );
    disc(image, [x - 0.3 * w, h(0.13)], 0.1 * w, c);
    disc(image, [x + 0.3 * w, h(0.13)], 0.1 * w, c);
}

/// A car seen from behind, centred on `at`, `w` wide.
fn car_rear(image: &mut RgbImage, at: [f64; 2], w: f64, c: Rgb<u8>) {
    let [x, y] = at;
    let h = |k: f64| y + k * w;
    poly(
        image,
        &[
            [x - 0.5 * w, h(-0.05)],
            [x - 0.5 * w, h(0.35)],
            [x + 0.5 * w, h(0.35)],
            [x + 0.5 * w, h(-0.05)],
        ],
        c,
    );
    poly(
        image,
        &[
            [x - 0.4 * w, h(-0.05)],
            [x - 0.3 * w, h(-0.4)],
            [x + 0.3 * w, h(-0.4)],
            [x + 0.4 * w, h(-0.05)],
        ],
        c,
    );
    for s in [-1.0, 1.0] {
        let u = x + s * 0.32 * w;
        poly(
            image,
            &[
                [u - 0.12 * w, h(0.3)],
                [u - 0.12 * w, h(0.5)],
                [u + 0.12 * w, h(0.5)],
                [u + 0.12 * w, h(0.3)],
            ],
            c,
        );
    }
}

/// A filled polygon from texture points (0–1).
fn poly(image: &mut RgbImage, points: &[[f64; 2]], c: Rgb<u8>) {
    let points: Vec<Point<i32>> = points.iter().map(|p| point(p[0], p[1])).collect();
    draw_polygon_mut(image, &points, c);
}

/// A straight stroke from `a` to `b`, `width` wide (texture units).
fn bar(image: &mut RgbImage, a: [f64; 2], b: [f64; 2], width: f64, c: Rgb<u8>) {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
    if len <= 0.0 {
        return;
    }
    let n = [-d[1] / len * width / 2.0, d[0] / len * width / 2.0];
    poly(
        image,
        &[
            [a[0] + n[0], a[1] + n[1]],
            [b[0] + n[0], b[1] + n[1]],
            [b[0] - n[0], b[1] - n[1]],
            [a[0] - n[0], a[1] - n[1]],
        ],
        c,
    );
}

/// A filled disc of radius `r` (texture units).
fn disc(image: &mut RgbImage, at: [f64; 2], r: f64, c: Rgb<u8>) {
    let s = f64::from(SIZE);
    let centre = ((at[0] * s).round() as i32, (at[1] * s).round() as i32);
    draw_filled_circle_mut(image, centre, (r * s).round() as i32, c);
}

/// Texture point at `(u, v)` in 0–1.
fn point(u: f64, v: f64) -> Point<i32> {
    let s = f64::from(SIZE);
    Point::new((u * s).round() as i32, (v * s).round() as i32)
}

fn centred_text(image: &mut RgbImage, text: &str, px: f32, colour: Rgb<u8>) {
    let scale = PxScale::from(px);
    let (w, h) = text_size(scale, &*FONT, text);
    let x = (SIZE as i32 - w as i32) / 2;
    let y = (SIZE as i32 - h as i32) / 2;
    draw_text_mut(image, colour, x, y, scale, &*FONT, text);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outlines_are_convex_counter_clockwise_inside_the_texture() {
        for kind in SignKind::ALL {
            let ring = outline(kind);
            assert!(ring.len() >= 3, "{kind:?}");
            for (i, p) in ring.iter().enumerate() {
                assert!((0.0..=1.0).contains(&p[0]) && (0.0..=1.0).contains(&p[1]));
                let q = ring[(i + 1) % ring.len()];
                let r = ring[(i + 2) % ring.len()];
                // Counter-clockwise on screen with v down is a negative cross product.
                let cross = (q[0] - p[0]) * (r[1] - q[1]) - (q[1] - p[1]) * (r[0] - q[0]);
                assert!(cross < 0.0, "{kind:?} at {i}");
            }
        }
    }

    /// Mean absolute difference per channel, 0–255.
    fn distance(a: &RgbImage, b: &RgbImage) -> f64 {
        let sum: u64 = a
            .as_raw()
            .iter()
            .zip(b.as_raw())
            .map(|(x, y)| u64::from(x.abs_diff(*y)))
            .sum();
        sum as f64 / a.as_raw().len() as f64
    }

    /// Every type its own face: no two faces closer than 4/255 on average (mirrored bends,
    /// the smallest pair, differ by about twice that), and the face's pixels outside its
    /// outline are only the rim colour its corner shows.
    #[test]
    fn faces_are_square_and_differ() {
        let faces: Vec<RgbImage> = SignKind::ALL.iter().map(|&k| draw(k, 50)).collect();
        assert!(faces.len() >= 20);
        let mut closest = (f64::INFINITY, 0, 0);
        for (i, f) in faces.iter().enumerate() {
            assert_eq!(f.dimensions(), (SIZE, SIZE));
            for (j, g) in faces.iter().enumerate().skip(i + 1) {
                let d = distance(f, g);
                if d < closest.0 {
                    closest = (d, i, j);
                }
            }
        }
        let (d, i, j) = closest;
        let names = (SignKind::ALL[i], SignKind::ALL[j]);
        assert!(d > 4.0, "{names:?} differ by {d:.2}");
        assert_ne!(
            draw(SignKind::SpeedLimit, 30),
            draw(SignKind::SpeedLimit, 50)
        );
        // The stop sign's centre is red, its lettering white.
        let stop = &faces[0];
        assert!(stop.pixels().filter(|p| **p == WHITE).count() > 2000);
    }

    /// Whether texture point `p` lies inside the convex, counter-clockwise `ring`.
    fn inside(ring: &[[f64; 2]], p: [f64; 2]) -> bool {
        (0..ring.len()).all(|i| {
            let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
            (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]) <= 0.0
        })
    }

    /// The pictogram stays inside the plate: the pixels outside the outline (which the
    /// plate never shows) are all the face's rim colour, and the outline covers a fair
    /// share of the texture.
    #[test]
    fn pictograms_lie_inside_the_outline() {
        for kind in SignKind::ALL {
            let face = draw(kind, 50);
            let ring = outline(kind);
            let s = f64::from(SIZE);
            let mut outside = std::collections::BTreeSet::new();
            let mut covered = 0;
            for (x, y, p) in face.enumerate_pixels() {
                let uv = [(f64::from(x) + 0.5) / s, (f64::from(y) + 0.5) / s];
                // A pixel's width of slack at the edge, where both colours meet.
                let grown: Vec<[f64; 2]> = ring
                    .iter()
                    .map(|q| [0.5 + (q[0] - 0.5) * 1.02, 0.5 + (q[1] - 0.5) * 1.02])
                    .collect();
                if inside(&ring, uv) {
                    covered += 1;
                } else if !inside(&grown, uv) {
                    outside.insert(p.0);
                }
            }
            assert!(
                outside.len() <= 1,
                "{kind:?}: {outside:?} outside its outline"
            );
            assert!(covered > (SIZE * SIZE) as usize / 3, "{kind:?}");
        }
    }

    /// Writes every face (speed limits at 50) side by side, 8 a row, named by number, to
    /// the PNG `CITYSPEC_SIGN_SHEET` names: a contact sheet to look at. Checks the sheet's
    /// size either way.
    #[test]
    fn contact_sheet() {
        let cols = 8;
        let rows = SignKind::ALL.len().div_ceil(cols) as u32;
        let cell = SIZE + 40;
        let mut sheet = RgbImage::from_pixel(cols as u32 * cell, rows * cell, Rgb([128; 3]));
        for (k, &kind) in SignKind::ALL.iter().enumerate() {
            let (x, y) = ((k % cols) as u32 * cell, (k / cols) as u32 * cell);
            image::imageops::replace(
                &mut sheet,
                &draw(kind, 50),
                i64::from(x + 20),
                i64::from(y + 4),
            );
            let label = format!("{} {}", kind.number(), kind.name());
            let scale = PxScale::from(18.0);
            draw_text_mut(
                &mut sheet,
                BLACK,
                x as i32 + 4,
                (y + SIZE + 10) as i32,
                scale,
                &*FONT,
                &label,
            );
        }
        assert_eq!(sheet.dimensions(), (8 * cell, rows * cell));
        if let Some(path) = std::env::var_os("CITYSPEC_SIGN_SHEET") {
            sheet.save(path).expect("the contact sheet is written");
        }
    }
}
