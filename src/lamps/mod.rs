//! Lamps stage: layout image + roads + palette → [`Lamp`] sites on the strips beside roads;
//! on a map, [`map_lamps`]: its own lamps, and the same rule along its streets' polylines.
//!
//! The paper's rule ("every 100 px along each road on the green strips of both sides, none
//! inside a crossing, of two too close one removed") is one code for both inputs
//! (`seed.rs`): streets as [`PavedSegment`] polylines, candidates along them, pruning. A
//! layout's part, made exact:
//!
//! 1. Each road is a street of one segment ([`Road::paved`]), its low side (above / left)
//!    seeded first; candidates at along-positions `start + spacing/2 + k·spacing` while
//!    `< end`.
//! 2. At a candidate, the *run* is the number of strip-coloured pixels (nearest palette
//!    colour within tolerance) counted outward from the road edge, in the candidate's
//!    along-pixel column. A candidate with run 0 is dropped: it is not on a strip, and
//!    beyond a crossing's edge lies road, so no lamp stands inside a crossing.
//! 3. The lamp stands mid-strip: `across = edge ∓ depth/2` with `depth = min(run, typical
//!    depth of that side)` (see `RoadSide::typical_depth` for why the cap).
//! 4. Over all roads in (road id, side, along) order, a lamp closer than `min_distance` to
//!    one already kept is removed. Ids are consecutive in that order.
//!
//! `facing` is the unit vector from the lamp to the road's centre line. The strips' typical
//! depths are read in parallel; results are collected in road order, so any thread count
//! gives the same list.

/// Bump when this stage's output bytes change: it is part of the stage's cache key.
pub const VERSION: u32 = 1;

mod map_lamps;
mod road_side;
mod seed;

pub use map_lamps::map_lamps;

use image::RgbImage;
use rayon::prelude::*;

use crate::model::{Axis, Lamp, ParsedLayout, PavedSegment, Road};
use crate::spec::Palette;
use road_side::{RoadSide, Side};
use seed::{SideIndex, Street};

/// Lamp sites along every road of `layout`, on the strip-coloured pixels of both sides.
///
/// A `spacing_px` that is not a positive finite number gives no lamps; a `min_distance_px`
/// that is not positive removes none. Roads with non-finite coordinates are skipped.
pub fn site_lamps(
    image: &RgbImage,
    layout: &ParsedLayout,
    palette: &Palette,
    spacing_px: f64,
    min_distance_px: f64,
) -> Vec<Lamp> {
    if !(spacing_px.is_finite() && spacing_px > 0.0) {
        return Vec::new();
    }
    let mut roads: Vec<&Road> = (layout.roads.iter())
        .filter(|r| {
            let finite = [r.start, r.end, r.line, r.edges[0], r.edges[1]];
            finite.iter().all(|v| v.is_finite()) && r.start < r.end
        })
        .collect();
    roads.sort_by_key(|r| r.id);
    // Each side's typical strip depth reads every pixel column of the road: in parallel,
    // collected in road order.
    let typical: Vec<[Option<u32>; 2]> = roads
        .par_iter()
        .map(|road| {
            [Side::Low, Side::High]
                .map(|side| RoadSide::new(image, palette, road, side).typical_depth())
        })
        .collect();
    // Step 1: each road is a street of one segment, its low side (above, left) seeded first.
    let streets: Vec<Street> = (roads.iter().zip(&typical))
        .map(|(road, depth)| Street {
            segments: vec![road.paved(depth.map(|d| d.map_or(0.0, f64::from)))],
            sides: match road.axis {
                Axis::Horizontal => [0, 1],
                Axis::Vertical => [1, 0],
            },
        })
        .collect();
    // Steps 2 and 3: where the strip is, mid-strip.
    let offset = |segment: &PavedSegment, side: SideIndex, q: [f64; 2]| {
        let i = roads
            .binary_search_by_key(&(segment.road as u32), |r| r.id)
            .ok()?;
        let road = roads[i];
        let side = match (road.axis, side) {
            (Axis::Horizontal, 0) | (Axis::Vertical, 1) => Side::Low,
            _ => Side::High,
        };
        let typical = typical[i][side as usize]?;
        let along = match road.axis {
            Axis::Horizontal => q[0],
            Axis::Vertical => q[1],
        };
        if along >= road.end {
            return None;
        }
        let run = RoadSide::new(image, palette, road, side).run(along.floor() as i64);
        (run > 0).then(|| segment.width / 2.0 + f64::from(run.min(typical)) / 2.0)
    };
    let candidates = seed::candidates(&streets, spacing_px, offset);
    // Step 4.
    seed::keep(Vec::new(), candidates, 0.0, min_distance_px, |_| true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::PixelClass;
    use image::Rgb;

    const ROAD: [u32; 2] = [84, 116];
    const STRIP: u32 = 8;

    /// A 200×200 cross: a horizontal road (id 0) on rows 84..116 and a vertical one (id 1)
    /// on columns 84..116, yellow centre lines on row/column 100, and four blocks each
    /// ringed by an 8-px strip (also along the image border).
    fn cross() -> (RgbImage, ParsedLayout) {
        let p = Palette::default();
        let on_road = |v: u32| ROAD[0] <= v && v < ROAD[1];
        let quadrant = |v: u32| {
            if v < ROAD[0] {
                (0, ROAD[0])
            } else {
                (ROAD[1], 200)
            }
        };
        let image = RgbImage::from_fn(200, 200, |x, y| {
            let colour = if (on_road(y) && y == 100) || (on_road(x) && x == 100) {
                p.line
            } else if on_road(x) || on_road(y) {
                p.road
            } else {
                let ((x0, x1), (y0, y1)) = (quadrant(x), quadrant(y));
                let ring = x < x0 + STRIP || x >= x1 - STRIP || y < y0 + STRIP || y >= y1 - STRIP;
                if ring { p.strip } else { p.block }
            };
            Rgb(colour.0)
        });
        let road = |id, axis| Road {
            id,
            axis,
            start: 0.0,
            end: 200.0,
            line: 100.5,
            edges: [f64::from(ROAD[0]), f64::from(ROAD[1])],
        };
        let layout = ParsedLayout {
            width: 200,
            height: 200,
            blocks: vec![],
            roads: vec![road(0, Axis::Horizontal), road(1, Axis::Vertical)],
        };
        (image, layout)
    }

    /// A 200×100 image with one horizontal dead-end road on rows 34..66 from x = 0 to 120,
    /// ringed by an 8-px strip that also closes its end (x 120..128); blocks elsewhere.
    fn dead_end() -> (RgbImage, ParsedLayout) {
        let p = Palette::default();
        let image = RgbImage::from_fn(200, 100, |x, y| {
            let colour = if x < 120 && (34..66).contains(&y) {
                if y == 50 { p.line } else { p.road }
            } else if x < 128 && (26..74).contains(&y) {
                p.strip
            } else {
                p.block
            };
            Rgb(colour.0)
        });
        let road = Road {
            id: 0,
            axis: Axis::Horizontal,
            start: 0.0,
            end: 120.0,
            line: 50.5,
            edges: [34.0, 66.0],
        };
        (
            image,
            ParsedLayout {
                width: 200,
                height: 100,
                blocks: vec![],
                roads: vec![road],
            },
        )
    }

    /// The same layout mirrored over the diagonal: x ↔ y, horizontal ↔ vertical.
    fn transposed((image, layout): (RgbImage, ParsedLayout)) -> (RgbImage, ParsedLayout) {
        let t = RgbImage::from_fn(image.height(), image.width(), |x, y| *image.get_pixel(y, x));
        let roads = layout
            .roads
            .into_iter()
            .map(|r| Road {
                axis: match r.axis {
                    Axis::Horizontal => Axis::Vertical,
                    Axis::Vertical => Axis::Horizontal,
                },
                ..r
            })
            .collect();
        (
            t,
            ParsedLayout {
                width: layout.height,
                height: layout.width,
                blocks: vec![],
                roads,
            },
        )
    }

    fn class_under(image: &RgbImage, lamp: &Lamp) -> PixelClass {
        let [x, y] = lamp.position;
        Palette::default().classify(image.get_pixel(x.floor() as u32, y.floor() as u32).0)
    }

    fn positions(lamps: &[Lamp]) -> Vec<(u32, [f64; 2])> {
        lamps.iter().map(|l| (l.road, l.position)).collect()
    }

    #[test]
    fn cross_has_lamps_on_both_sides_of_both_roads_spaced_evenly() {
        let (image, layout) = cross();
        let lamps = site_lamps(&image, &layout, &Palette::default(), 50.0, 5.0);
        let mut want = Vec::new();
        for (road, horizontal) in [(0, true), (1, false)] {
            for across in [80.0, 120.0] {
                for along in [25.0, 75.0, 125.0, 175.0] {
                    want.push((
                        road,
                        if horizontal {
                            [along, across]
                        } else {
                            [across, along]
                        },
                    ));
                }
            }
        }
        assert_eq!(positions(&lamps), want);
        for (i, lamp) in lamps.iter().enumerate() {
            assert_eq!(lamp.id, i as u32);
            assert_eq!(class_under(&image, lamp), PixelClass::Strip, "{lamp:?}");
            // facing points from the lamp to the centre line (100.5 across)
            let across = if lamp.road == 0 {
                lamp.position[1]
            } else {
                lamp.position[0]
            };
            let towards = if across < 100.5 { 1.0 } else { -1.0 };
            let want = if lamp.road == 0 {
                [0.0, towards]
            } else {
                [towards, 0.0]
            };
            assert_eq!(lamp.facing, want, "{lamp:?}");
        }
    }

    #[test]
    fn no_lamp_stands_in_the_crossing_or_off_the_strip() {
        let (image, layout) = cross();
        // (spacing, lamps per road side): spacing 200 puts the only candidate at 100,
        // inside the crossing; 64 one of three (96); 10 four of twenty (85 to 115);
        // 33 one of six (115.5: the crossing's last column).
        let cases = [(200.0, 0), (100.0, 2), (64.0, 2), (10.0, 16), (33.0, 5)];
        for (spacing, per_side) in cases {
            let lamps = site_lamps(&image, &layout, &Palette::default(), spacing, 0.0);
            assert_eq!(lamps.len(), 4 * per_side, "spacing {spacing}");
            for lamp in &lamps {
                let [x, y] = lamp.position;
                let in_crossing = (84.0..116.0).contains(&x) && (84.0..116.0).contains(&y);
                assert!(!in_crossing, "spacing {spacing}: {lamp:?}");
                assert_eq!(
                    class_under(&image, lamp),
                    PixelClass::Strip,
                    "spacing {spacing}: {lamp:?}"
                );
            }
        }
    }

    #[test]
    fn lamps_at_a_strip_corner_stay_beside_their_road_and_duplicates_go() {
        let (image, layout) = cross();
        // Spacing 160 puts one candidate per side at along 80: in the corner where the
        // crossing road's strip meets this one. Both roads put a lamp at (80, 80).
        let all = site_lamps(&image, &layout, &Palette::default(), 160.0, 0.0);
        assert_eq!(
            positions(&all),
            vec![
                (0, [80.0, 80.0]),
                (0, [80.0, 120.0]),
                (1, [80.0, 80.0]),
                (1, [120.0, 80.0])
            ]
        );
        let pruned = site_lamps(&image, &layout, &Palette::default(), 160.0, 10.0);
        assert_eq!(
            positions(&pruned),
            vec![(0, [80.0, 80.0]), (0, [80.0, 120.0]), (1, [120.0, 80.0])]
        );
        assert_eq!(
            pruned.iter().map(|l| l.id).collect::<Vec<_>>(),
            vec![0, 1, 2]
        );
    }

    #[test]
    fn lamps_closer_than_min_distance_are_pruned_in_order() {
        let (image, layout) = cross();
        // Candidates every 5 px; greedy pruning at 12 keeps every third: 15 px apart.
        let lamps = site_lamps(&image, &layout, &Palette::default(), 5.0, 12.0);
        for (i, a) in lamps.iter().enumerate() {
            for b in &lamps[i + 1..] {
                let d = ((a.position[0] - b.position[0]).powi(2)
                    + (a.position[1] - b.position[1]).powi(2))
                .sqrt();
                assert!(d >= 12.0, "{a:?} and {b:?} are {d} apart");
            }
        }
        let road0_low: Vec<f64> = lamps
            .iter()
            .filter(|l| l.road == 0 && l.position[1] < 100.0)
            .map(|l| l.position[0])
            .collect();
        assert_eq!(&road0_low[..6], &[2.5, 17.5, 32.5, 47.5, 62.5, 77.5]);
    }

    #[test]
    fn dead_end_road_has_lamps_only_along_its_length() {
        for (name, (image, layout)) in [
            ("horizontal", dead_end()),
            ("vertical", transposed(dead_end())),
        ] {
            let horizontal = layout.roads[0].axis == Axis::Horizontal;
            for (spacing, alongs) in [(50.0, vec![25.0, 75.0]), (40.0, vec![20.0, 60.0, 100.0])] {
                let lamps = site_lamps(&image, &layout, &Palette::default(), spacing, 10.0);
                let mut want = Vec::new();
                for across in [30.0, 70.0] {
                    for &along in &alongs {
                        want.push((
                            0,
                            if horizontal {
                                [along, across]
                            } else {
                                [across, along]
                            },
                        ));
                    }
                }
                assert_eq!(positions(&lamps), want, "{name}, spacing {spacing}");
            }
        }
    }

    #[test]
    fn thread_count_does_not_change_the_lamps() {
        let (image, layout) = cross();
        let run = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| site_lamps(&image, &layout, &Palette::default(), 7.0, 9.0))
        };
        assert_eq!(run(1), run(3));
    }

    #[test]
    fn bad_numbers_give_no_lamps_instead_of_a_panic() {
        let (image, mut layout) = cross();
        for spacing in [0.0, -5.0, f64::NAN, f64::INFINITY] {
            assert!(site_lamps(&image, &layout, &Palette::default(), spacing, 10.0).is_empty());
        }
        // A road outside the image or with NaN coordinates contributes nothing.
        layout.roads = vec![
            Road {
                id: 0,
                axis: Axis::Horizontal,
                start: 500.0,
                end: 900.0,
                line: 600.5,
                edges: [590.0, 610.0],
            },
            Road {
                id: 1,
                axis: Axis::Vertical,
                start: f64::NAN,
                end: 200.0,
                line: 100.5,
                edges: [84.0, 116.0],
            },
        ];
        assert!(site_lamps(&image, &layout, &Palette::default(), 50.0, 10.0).is_empty());
    }
}
