//! Preview stage: layout image + parsed layout + lamps + buildings → `plan.png` picture.
//!
//! Like the paper's Fig. 9 (second panel): the layout as drawn, with every building as a
//! yellow-filled square (the block colour showing
//! through a little) with a dark orange 1-px outline, road centre lines in red over the yellow line,
//! and lamps as 3×3 magenta dots, drawn in that order. Direct pixel writes, clipped to the
//! image, so anything outside it is simply not drawn.

/// Bump when this stage's output bytes change: it is part of the stage's cache key.
pub const VERSION: u32 = 1;

use image::{Rgb, RgbImage};

use crate::model::{Axis, Building, Lamp, ParsedLayout};

/// Building outline: a dark orange that reads on blue and on the yellow fill.
pub const BUILDING_OUTLINE: Rgb<u8> = Rgb([200, 90, 0]);
/// Building fill, mixed into the block colour at [`FILL_ALPHA`]/256. Blue and yellow mix
/// to grey (the road colour) at half strength, so the fill is mostly yellow.
pub const BUILDING_FILL: Rgb<u8> = Rgb([255, 240, 60]);
pub const FILL_ALPHA: u16 = 200;
/// Road centre lines.
pub const ROAD_LINE: Rgb<u8> = Rgb([210, 20, 20]);
/// Lamp dots.
pub const LAMP: Rgb<u8> = Rgb([255, 0, 220]);

/// plan.png: the layout image with building squares (outlined, in a colour that reads on
/// blue — the paper uses yellow), lamps (small dots) and road centre lines drawn over it.
pub fn draw(
    image: &RgbImage,
    layout: &ParsedLayout,
    lamps: &[Lamp],
    buildings: &[Building],
) -> RgbImage {
    let mut out = image.clone();
    let (w, h) = (i64::from(out.width()), i64::from(out.height()));
    let put = |out: &mut RgbImage, x: i64, y: i64, paint: &dyn Fn(Rgb<u8>) -> Rgb<u8>| {
        if (0..w).contains(&x) && (0..h).contains(&y) {
            let p = out.get_pixel_mut(x as u32, y as u32);
            *p = paint(*p);
        }
    };
    for b in buildings {
        let f = b.footprint;
        let (x0, y0, x1, y1) = (
            i64::from(f.x0),
            i64::from(f.y0),
            i64::from(f.x1),
            i64::from(f.y1),
        );
        // Clip the loops to the image so a huge bogus footprint costs nothing.
        for y in y0.max(0)..y1.min(h) {
            for x in x0.max(0)..x1.min(w) {
                let edge = x == x0 || x == x1 - 1 || y == y0 || y == y1 - 1;
                if edge {
                    put(&mut out, x, y, &|_| BUILDING_OUTLINE);
                } else {
                    put(&mut out, x, y, &tint);
                }
            }
        }
    }
    for road in &layout.roads {
        if ![road.start, road.end, road.line]
            .iter()
            .all(|v| v.is_finite())
        {
            continue;
        }
        let line = road.line.floor() as i64;
        let extent = match road.axis {
            Axis::Horizontal => w,
            Axis::Vertical => h,
        };
        let first = (road.start.floor() as i64).max(0);
        let last = (road.end.ceil() as i64).min(extent);
        for along in first..last {
            let (x, y) = match road.axis {
                Axis::Horizontal => (along, line),
                Axis::Vertical => (line, along),
            };
            put(&mut out, x, y, &|_| ROAD_LINE);
        }
    }
    for lamp in lamps {
        let [x, y] = lamp.position;
        if !(x.is_finite() && y.is_finite()) {
            continue;
        }
        let (cx, cy) = (x.floor() as i64, y.floor() as i64);
        for dy in -1..=1 {
            for dx in -1..=1 {
                put(&mut out, cx + dx, cy + dy, &|_| LAMP);
            }
        }
    }
    out
}

fn tint(p: Rgb<u8>) -> Rgb<u8> {
    let mix = |a: u8, b: u8| {
        ((u16::from(a) * (256 - FILL_ALPHA) + u16::from(b) * FILL_ALPHA) / 256) as u8
    };
    Rgb([0, 1, 2].map(|i| mix(p.0[i], BUILDING_FILL.0[i])))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{PxRect, Road};
    use crate::spec::Palette;

    const BLUE: Rgb<u8> = Rgb([40, 80, 220]);

    fn scene() -> (RgbImage, ParsedLayout, Vec<Lamp>, Vec<Building>) {
        let image = RgbImage::from_pixel(60, 40, Rgb(Palette::default().block.0));
        let road = Road {
            id: 0,
            axis: Axis::Vertical,
            start: 0.0,
            end: 30.0,
            line: 50.5,
            edges: [45.0, 56.0],
        };
        let layout = ParsedLayout {
            width: 60,
            height: 40,
            blocks: vec![],
            roads: vec![road],
        };
        let lamps = vec![
            Lamp {
                id: 0,
                position: [40.5, 20.5],
                road: 0,
                facing: [1.0, 0.0],
            },
            Lamp {
                id: 1,
                position: [0.2, 39.9],
                road: 0,
                facing: [1.0, 0.0],
            }, // at a corner
        ];
        let buildings = vec![
            Building {
                id: 0,
                block: 0,
                footprint: PxRect {
                    x0: 2,
                    y0: 3,
                    x1: 14,
                    y1: 15,
                },
                kind: 0,
            },
            Building {
                id: 1,
                block: 0,
                footprint: PxRect {
                    x0: 55,
                    y0: 35,
                    x1: 90,
                    y1: 70,
                },
                kind: 1,
            },
        ];
        (image, layout, lamps, buildings)
    }

    #[test]
    fn draws_buildings_roads_and_lamps_and_nothing_else() {
        let (image, layout, lamps, buildings) = scene();
        let out = draw(&image, &layout, &lamps, &buildings);
        assert_eq!(out.dimensions(), image.dimensions());
        let tinted = tint(BLUE);
        assert_ne!(tinted, BLUE);
        assert_ne!(tinted, BUILDING_OUTLINE);
        let cases = [
            ((2, 3), BUILDING_OUTLINE),
            ((13, 14), BUILDING_OUTLINE),
            ((8, 3), BUILDING_OUTLINE),
            ((3, 4), tinted),
            ((8, 9), tinted),
            ((14, 9), BLUE),              // just right of the first building
            ((55, 35), BUILDING_OUTLINE), // the clipped building's corner
            ((59, 39), tinted),           // its inside; its far edges lie off the image
            ((50, 0), ROAD_LINE),
            ((50, 29), ROAD_LINE),
            ((50, 30), BLUE), // the line ends at `end`
            ((39, 19), LAMP),
            ((41, 21), LAMP),
            ((42, 20), BLUE),
            ((0, 39), LAMP),
            ((1, 38), LAMP),
        ];
        for ((x, y), want) in cases {
            assert_eq!(*out.get_pixel(x, y), want, "pixel ({x}, {y})");
        }
        let changed = out
            .pixels()
            .zip(image.pixels())
            .filter(|(a, b)| a != b)
            .count();
        // 12×12 + 5×5 building pixels, 30 line pixels, 9 + 4 lamp pixels.
        assert_eq!(changed, 144 + 25 + 30 + 9 + 4);
    }

    #[test]
    fn same_input_same_picture() {
        let (image, layout, lamps, buildings) = scene();
        assert_eq!(
            draw(&image, &layout, &lamps, &buildings),
            draw(&image, &layout, &lamps, &buildings)
        );
    }
}
