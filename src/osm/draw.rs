//! A picture of an [`OsmMap`] from above, north up: sidewalks light grey, carriageways dark
//! grey, paths tan, buildings by height (lighter is taller, brick where the map gives no
//! height), courtyards cut out, and the map's furniture as dots (signals red, lamps
//! yellow, trees green, benches brown, signs blue, crossings white).

use image::{Rgb, RgbImage};
use imageproc::drawing::{draw_filled_circle_mut, draw_polygon_mut};
use imageproc::point::Point;

use crate::model::{FeatureKind, MapRoad, OsmMap};

const GROUND: Rgb<u8> = Rgb([236, 234, 226]);
const SIDEWALK: Rgb<u8> = Rgb([196, 196, 196]);
const CARRIAGEWAY: Rgb<u8> = Rgb([88, 88, 92]);
const PATH: Rgb<u8> = Rgb([214, 190, 150]);
const NO_HEIGHT: Rgb<u8> = Rgb([186, 120, 96]);

/// The map drawn with its longer side `max_side` pixels (at most 4 pixels a metre).
pub fn draw(map: &OsmMap, max_side: u32) -> RgbImage {
    let [x0, z0, x1, z1] = map.extent;
    let longer = (x1 - x0).max(z1 - z0).max(1.0);
    let scale = (f64::from(max_side.max(16)) / longer).min(4.0);
    let size = |l: f64| ((l * scale).ceil() as u32).clamp(1, max_side.max(16));
    let mut img = RgbImage::from_pixel(size(x1 - x0), size(z1 - z0), GROUND);
    let px = |p: [f64; 2]| [(p[0] - x0) * scale, (p[1] - z0) * scale];
    for road in map.roads.iter().filter(|r| r.sidewalks != [0.0, 0.0]) {
        band(&mut img, road, true, px, scale, SIDEWALK);
    }
    for road in &map.roads {
        let colour = if road.drivable { CARRIAGEWAY } else { PATH };
        band(&mut img, road, false, px, scale, colour);
    }
    for b in &map.buildings {
        let colour = match b.height {
            Some(h) => {
                let t = (h / 40.0).clamp(0.0, 1.0);
                let v = |a: f64, b: f64| (a + (b - a) * t).round() as u8;
                Rgb([v(120.0, 225.0), v(132.0, 228.0), v(160.0, 240.0)])
            }
            None => NO_HEIGHT,
        };
        fill(&mut img, &b.outer, px, colour);
        for hole in &b.holes {
            fill(&mut img, hole, px, GROUND);
        }
    }
    let dot = (0.8 * scale).round().max(2.0) as i32;
    for f in &map.features {
        let colour = match f.kind {
            FeatureKind::TrafficSignals => Rgb([220, 30, 30]),
            FeatureKind::StreetLamp => Rgb([250, 210, 40]),
            FeatureKind::Tree => Rgb([40, 150, 50]),
            FeatureKind::Bench => Rgb([130, 80, 40]),
            FeatureKind::TrafficSign => Rgb([30, 80, 220]),
            FeatureKind::Crossing => Rgb([255, 255, 255]),
        };
        let [x, y] = px(f.at);
        draw_filled_circle_mut(&mut img, (x.round() as i32, y.round() as i32), dot, colour);
    }
    img
}

/// Fills a ring given in metres.
fn fill(img: &mut RgbImage, ring: &[[f64; 2]], px: impl Fn([f64; 2]) -> [f64; 2], colour: Rgb<u8>) {
    let mut points: Vec<Point<i32>> = ring
        .iter()
        .map(|&p| {
            let [x, y] = px(p);
            Point::new(x.round() as i32, y.round() as i32)
        })
        .collect();
    points.dedup();
    while points.len() > 1 && points.first() == points.last() {
        points.pop();
    }
    if points.len() >= 3 {
        draw_polygon_mut(img, &points, colour);
    }
}

/// Paints `road`'s carriageway, or with `sidewalks` the band from its right sidewalk's
/// outer edge to its left one's (x east, z south: left of the way's direction), round at
/// the joints.
fn band(
    img: &mut RgbImage,
    road: &MapRoad,
    sidewalks: bool,
    px: impl Fn([f64; 2]) -> [f64; 2],
    scale: f64,
    colour: Rgb<u8>,
) {
    let [left, right] = if sidewalks {
        road.sidewalks
    } else {
        [0.0, 0.0]
    };
    let half = (road.width + left + right) / 2.0;
    let shift = (left - right) / 2.0;
    for w in road.centreline.windows(2) {
        let (a, b) = (w[0], w[1]);
        let (dx, dz) = (b[0] - a[0], b[1] - a[1]);
        let len = (dx * dx + dz * dz).sqrt();
        if len == 0.0 {
            continue;
        }
        let n = [dz / len, -dx / len];
        let at = |p: [f64; 2], s: f64| [p[0] + n[0] * s, p[1] + n[1] * s];
        let quad = [
            at(a, shift + half),
            at(b, shift + half),
            at(b, shift - half),
            at(a, shift - half),
        ];
        fill(img, &quad, &px, colour);
        for p in [a, b] {
            let [x, y] = px(at(p, shift));
            let r = (half * scale).round() as i32;
            if r > 0 {
                draw_filled_circle_mut(img, (x.round() as i32, y.round() as i32), r, colour);
            }
        }
    }
}
