//! A sign kind (and speed) → its 256 px face texture and its outline in texture space.
//!
//! The outline is the plate's real shape (octagon, triangle, 16-gon circle, square), so the
//! plate geometry — and an annotation box from it — is exactly the sign. Each texture fills
//! its whole square with the shape's rim colour first, so the outline's edges never show
//! anything but the sign.

use ab_glyph::PxScale;
use image::{Rgb, RgbImage};
use imageproc::drawing::{
    draw_filled_circle_mut, draw_filled_rect_mut, draw_polygon_mut, draw_text_mut, text_size,
};
use imageproc::point::Point;
use imageproc::rect::Rect;

use super::text_plate::FONT;
use super::trig::cos_sin_deg;
use crate::spec::SignKind;

/// Side of a sign texture in pixels.
pub const SIZE: u32 = 256;

const RED: Rgb<u8> = Rgb([200, 16, 32]);
const WHITE: Rgb<u8> = Rgb([245, 245, 245]);
const BLUE: Rgb<u8> = Rgb([16, 72, 170]);
const BLACK: Rgb<u8> = Rgb([20, 20, 20]);

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
    match kind {
        SignKind::Stop => ring(8, 22.5),
        SignKind::Yield => vec![[0.0, 0.06], [0.5, 0.93], [1.0, 0.06]],
        SignKind::SpeedLimit | SignKind::NoEntry | SignKind::NoParking => ring(16, 0.0),
        SignKind::PedestrianCrossing | SignKind::OneWay | SignKind::Parking => {
            vec![[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]]
        }
    }
}

/// The face texture of `kind`; `speed` is the number on a speed-limit sign.
// Long on purpose: one match arm a sign kind, each painting its face; an arm read apart from
// the others hides that they share the outline, colours and sizes above.
pub fn draw(kind: SignKind, speed: u32) -> RgbImage {
    let s = SIZE as i32;
    let c = s / 2;
    match kind {
        SignKind::Stop => {
            let mut image = RgbImage::from_pixel(SIZE, SIZE, RED);
            let inset: Vec<Point<i32>> = outline(kind)
                .iter()
                .map(|p| point(0.5 + (p[0] - 0.5) * 0.9, 0.5 + (p[1] - 0.5) * 0.9))
                .collect();
            draw_polygon_mut(&mut image, &inset, WHITE);
            let inner: Vec<Point<i32>> = outline(kind)
                .iter()
                .map(|p| point(0.5 + (p[0] - 0.5) * 0.82, 0.5 + (p[1] - 0.5) * 0.82))
                .collect();
            draw_polygon_mut(&mut image, &inner, RED);
            centred_text(&mut image, "STOP", 78.0, WHITE);
            image
        }
        SignKind::Yield => {
            let mut image = RgbImage::from_pixel(SIZE, SIZE, RED);
            let inner = [point(0.2, 0.17), point(0.5, 0.72), point(0.8, 0.17)];
            draw_polygon_mut(&mut image, &inner, WHITE);
            image
        }
        SignKind::SpeedLimit => {
            let mut image = RgbImage::from_pixel(SIZE, SIZE, RED);
            draw_filled_circle_mut(&mut image, (c, c), s * 38 / 100, WHITE);
            centred_text(&mut image, &speed.to_string(), 110.0, BLACK);
            image
        }
        SignKind::NoEntry => {
            let mut image = RgbImage::from_pixel(SIZE, SIZE, RED);
            draw_filled_rect_mut(
                &mut image,
                Rect::at(s / 5, c - 20).of_size(SIZE * 3 / 5, 40),
                WHITE,
            );
            image
        }
        SignKind::NoParking => {
            let mut image = RgbImage::from_pixel(SIZE, SIZE, RED);
            draw_filled_circle_mut(&mut image, (c, c), s * 38 / 100, BLUE);
            let bar = [
                point(0.26, 0.20),
                point(0.20, 0.26),
                point(0.74, 0.80),
                point(0.80, 0.74),
            ];
            draw_polygon_mut(&mut image, &bar, RED);
            image
        }
        SignKind::PedestrianCrossing => {
            let mut image = RgbImage::from_pixel(SIZE, SIZE, BLUE);
            let triangle = [point(0.5, 0.1), point(0.1, 0.88), point(0.9, 0.88)];
            draw_polygon_mut(&mut image, &triangle, WHITE);
            // Zebra stripes under a walking figure.
            for k in 0..4 {
                let x = 0.27 + 0.12 * f64::from(k);
                let stripe = [
                    point(x, 0.78),
                    point(x + 0.07, 0.78),
                    point(x + 0.07, 0.83),
                    point(x, 0.83),
                ];
                draw_polygon_mut(&mut image, &stripe, BLACK);
            }
            draw_filled_circle_mut(&mut image, (c, s * 36 / 100), s / 22, BLACK);
            let body = [
                point(0.48, 0.42),
                point(0.54, 0.42),
                point(0.58, 0.58),
                point(0.62, 0.74),
                point(0.56, 0.74),
                point(0.51, 0.61),
                point(0.44, 0.74),
                point(0.38, 0.74),
                point(0.46, 0.57),
            ];
            draw_polygon_mut(&mut image, &body, BLACK);
            image
        }
        SignKind::OneWay => {
            let mut image = RgbImage::from_pixel(SIZE, SIZE, BLUE);
            let arrow = [
                point(0.12, 0.42),
                point(0.6, 0.42),
                point(0.6, 0.28),
                point(0.9, 0.5),
                point(0.6, 0.72),
                point(0.6, 0.58),
                point(0.12, 0.58),
            ];
            draw_polygon_mut(&mut image, &arrow, WHITE);
            image
        }
        SignKind::Parking => {
            let mut image = RgbImage::from_pixel(SIZE, SIZE, BLUE);
            centred_text(&mut image, "P", 200.0, WHITE);
            image
        }
    }
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

    #[test]
    fn faces_are_square_and_differ() {
        let faces: Vec<RgbImage> = SignKind::ALL.iter().map(|&k| draw(k, 50)).collect();
        for (i, f) in faces.iter().enumerate() {
            assert_eq!(f.dimensions(), (SIZE, SIZE));
            for g in &faces[i + 1..] {
                assert_ne!(f, g);
            }
        }
        assert_ne!(
            draw(SignKind::SpeedLimit, 30),
            draw(SignKind::SpeedLimit, 50)
        );
        // The stop sign's centre is red, its lettering white.
        let stop = &faces[0];
        assert!(stop.pixels().filter(|p| **p == WHITE).count() > 2000);
    }
}
