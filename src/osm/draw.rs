//! A picture of an [`OsmMap`] from above, north up: green ground (parks, grass, woods)
//! pale green, squares (and pedestrian areas, car parks) light stone, sidewalks light grey, carriageways dark grey, paths tan, buildings by height (lighter is taller, brick where the map gives no
//! height), courtyards cut out, and the map's furniture as dots (signals red, lamps
//! yellow, trees green, benches brown, signs blue, crossings white).

use image::{Rgb, RgbImage};
use imageproc::drawing::draw_filled_circle_mut;

use crate::model::geometry::polygon::left_normal;
use crate::model::{FeatureKind, MapRoad, OsmMap};

const GROUND: Rgb<u8> = Rgb([236, 234, 226]);
const GREEN: Rgb<u8> = Rgb([190, 222, 170]);
const SQUARE: Rgb<u8> = Rgb([216, 212, 200]);
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
    let open = (map.green.iter().map(|g| (&g.shape, GREEN)))
        .chain(map.squares.iter().map(|g| (&g.shape, SQUARE)));
    let street = [(&map.sidewalks, SIDEWALK), (&map.carriageway, CARRIAGEWAY)]
        .into_iter()
        .flat_map(|(polygons, colour)| polygons.iter().map(move |p| (p, colour)));
    {
        for (p, colour) in open.chain(street) {
            fill_rings(
                &mut img,
                std::iter::once(&p.outer).chain(&p.holes),
                px,
                colour,
            );
        }
    }
    for road in map.roads.iter().filter(|r| !r.surface) {
        let colour = if road.drivable { CARRIAGEWAY } else { PATH };
        band(&mut img, road, px, scale, colour);
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
        fill_rings(
            &mut img,
            std::iter::once(&b.outer).chain(&b.holes),
            px,
            colour,
        );
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

/// Fills the inside of `rings` (metres) by the even–odd rule, so holes stay unpainted:
/// every pixel whose centre lies inside.
fn fill_rings<'a>(
    img: &mut RgbImage,
    rings: impl Iterator<Item = &'a Vec<[f64; 2]>>,
    px: impl Fn([f64; 2]) -> [f64; 2],
    colour: Rgb<u8>,
) {
    let edges: Vec<([f64; 2], [f64; 2])> = rings
        .flat_map(|ring| {
            let n = ring.len();
            (0..n).map(move |i| (ring[i], ring[(i + 1) % n]))
        })
        .map(|(a, b)| (px(a), px(b)))
        .collect();
    let Some((y0, y1)) = edges.iter().fold(None, |acc: Option<(f64, f64)>, (a, b)| {
        let (lo, hi) = (a[1].min(b[1]), a[1].max(b[1]));
        Some(acc.map_or((lo, hi), |(l, h)| (l.min(lo), h.max(hi))))
    }) else {
        return;
    };
    let (w, h) = (i64::from(img.width()), i64::from(img.height()));
    let mut xs: Vec<f64> = Vec::new();
    for y in (y0.floor() as i64).max(0)..=(y1.ceil() as i64).min(h - 1) {
        let cy = y as f64 + 0.5;
        xs.clear();
        for (a, b) in &edges {
            if (a[1] > cy) != (b[1] > cy) {
                xs.push(a[0] + (cy - a[1]) / (b[1] - a[1]) * (b[0] - a[0]));
            }
        }
        xs.sort_by(f64::total_cmp);
        for pair in xs.chunks_exact(2) {
            let from = ((pair[0] - 0.5).ceil() as i64).max(0);
            let to = ((pair[1] - 0.5).floor() as i64).min(w - 1);
            for x in from..=to {
                img.put_pixel(x as u32, y as u32, colour);
            }
        }
    }
}

/// Paints a road without a surface (a path, a road in a tunnel) at its width, round at
/// the joints.
fn band(
    img: &mut RgbImage,
    road: &MapRoad,
    px: impl Fn([f64; 2]) -> [f64; 2],
    scale: f64,
    colour: Rgb<u8>,
) {
    let half = road.width / 2.0;
    for w in road.centreline.windows(2) {
        let (a, b) = (w[0], w[1]);
        let Some(n) = left_normal(a, b) else {
            continue;
        };
        let at = |p: [f64; 2], s: f64| [p[0] + n[0] * s, p[1] + n[1] * s];
        let quad = [at(a, half), at(b, half), at(b, -half), at(a, -half)];
        fill_rings(img, std::iter::once(&quad.to_vec()), &px, colour);
        let r = (half * scale).round() as i32;
        for p in [a, b] {
            let [x, y] = px(p);
            if r > 0 {
                draw_filled_circle_mut(img, (x.round() as i32, y.round() as i32), r, colour);
            }
        }
    }
}
