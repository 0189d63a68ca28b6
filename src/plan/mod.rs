//! Plan stage: parsed layout + lamps + buildings → [`CityPlan`] in metres (`plan.json`).
//!
//! Pixels become metres by one factor: x = image x · m, z = image y · m. Every coordinate,
//! length, area and facing component is rounded to 3 decimals (the millimetre; 0.001 m² for
//! areas) so `plan.json` prints short, stable numbers; `-0` becomes `0`. Block outlines are pixel indices in the model, so their corners become
//! pixel centres: `(i + 0.5) · m`.

/// Bump when this stage's output bytes change: it is part of the stage's cache key.
pub const VERSION: u32 = 1;

use crate::model::geometry::mm;
use crate::model::{
    Axis, Block, Building, CityPlan, Lamp, ParsedLayout, PlanBlock, PlanBuilding, PlanLamp,
    PlanRoad, Road,
};

/// The plan in metres (x = image x, z = image y, times `metres_per_pixel`), coordinates
/// rounded to the millimetre so plan.json prints cleanly.
pub fn assemble(
    layout: &ParsedLayout,
    lamps: &[Lamp],
    buildings: &[Building],
    metres_per_pixel: f64,
) -> CityPlan {
    let m = metres_per_pixel;
    let pt = |x: f64, z: f64| [mm(x * m), mm(z * m)];
    CityPlan {
        size: pt(f64::from(layout.width), f64::from(layout.height)),
        metres_per_pixel: m,
        blocks: layout.blocks.iter().map(|b| plan_block(b, m)).collect(),
        roads: layout.roads.iter().map(|r| plan_road(r, m)).collect(),
        lamps: lamps
            .iter()
            .map(|l| PlanLamp {
                id: l.id,
                position: pt(l.position[0], l.position[1]),
                road: l.road,
                facing: [mm(l.facing[0]), mm(l.facing[1])],
            })
            .collect(),
        buildings: buildings
            .iter()
            .map(|b| {
                let f = b.footprint;
                PlanBuilding {
                    id: b.id,
                    block: b.block,
                    centre: pt(
                        (f64::from(f.x0) + f64::from(f.x1)) / 2.0,
                        (f64::from(f.y0) + f64::from(f.y1)) / 2.0,
                    ),
                    width: mm(f64::from(f.x1.saturating_sub(f.x0)) * m),
                    kind: b.kind,
                }
            })
            .collect(),
    }
}

fn plan_block(block: &Block, m: f64) -> PlanBlock {
    let b = block.bbox;
    PlanBlock {
        id: block.id,
        min: [mm(f64::from(b.x0) * m), mm(f64::from(b.y0) * m)],
        max: [mm(f64::from(b.x1) * m), mm(f64::from(b.y1) * m)],
        area: mm(block.area as f64 * m * m),
        outline: block
            .outline
            .iter()
            .map(|&[x, y]| [mm((f64::from(x) + 0.5) * m), mm((f64::from(y) + 0.5) * m)])
            .collect(),
    }
}

fn plan_road(road: &Road, m: f64) -> PlanRoad {
    let at = |along: f64| match road.axis {
        Axis::Horizontal => [mm(along * m), mm(road.line * m)],
        Axis::Vertical => [mm(road.line * m), mm(along * m)],
    };
    let c = road.centre();
    PlanRoad {
        id: road.id,
        axis: road.axis,
        start: at(road.start),
        end: at(road.end),
        centre: [mm(c[0] * m), mm(c[1] * m)],
        length: mm(road.length() * m),
        width: mm(road.width() * m),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Band, PxRect};

    fn layout() -> ParsedLayout {
        ParsedLayout {
            width: 300,
            height: 200,
            blocks: vec![Block {
                id: 0,
                bbox: PxRect {
                    x0: 10,
                    y0: 20,
                    x1: 50,
                    y1: 60,
                },
                area: 1600,
                outline: vec![[10, 20], [49, 20], [49, 59], [10, 59]],
                bands: vec![Band {
                    y0: 20,
                    y1: 60,
                    spans: vec![[10, 50]],
                }],
            }],
            roads: vec![
                Road {
                    id: 0,
                    axis: Axis::Horizontal,
                    start: 0.0,
                    end: 300.0,
                    line: 80.5,
                    edges: [65.0, 97.0],
                },
                Road {
                    id: 1,
                    axis: Axis::Vertical,
                    start: 10.0,
                    end: 190.0,
                    line: 150.5,
                    edges: [135.0, 167.0],
                },
            ],
        }
    }

    fn lamps() -> Vec<Lamp> {
        vec![Lamp {
            id: 0,
            position: [50.0, 61.0],
            road: 0,
            facing: [0.0, 1.0],
        }]
    }

    fn buildings() -> Vec<Building> {
        vec![Building {
            id: 0,
            block: 0,
            footprint: PxRect {
                x0: 10,
                y0: 20,
                x1: 22,
                y1: 32,
            },
            kind: 0,
        }]
    }

    #[test]
    fn scales_everything_by_metres_per_pixel() {
        let plan = assemble(&layout(), &lamps(), &buildings(), 2.0);
        assert_eq!(plan.size, [600.0, 400.0]);
        assert_eq!(plan.metres_per_pixel, 2.0);
        let b = &plan.blocks[0];
        assert_eq!(
            (b.min, b.max, b.area),
            ([20.0, 40.0], [100.0, 120.0], 6400.0)
        );
        assert_eq!(
            b.outline,
            vec![[21.0, 41.0], [99.0, 41.0], [99.0, 119.0], [21.0, 119.0]]
        );
        let h = &plan.roads[0];
        assert_eq!(
            (h.start, h.end, h.centre),
            ([0.0, 161.0], [600.0, 161.0], [300.0, 161.0])
        );
        assert_eq!((h.length, h.width, h.axis), (600.0, 64.0, Axis::Horizontal));
        let v = &plan.roads[1];
        assert_eq!(
            (v.start, v.end, v.centre),
            ([301.0, 20.0], [301.0, 380.0], [301.0, 200.0])
        );
        assert_eq!((v.length, v.width), (360.0, 64.0));
        assert_eq!(
            plan.lamps[0],
            PlanLamp {
                id: 0,
                position: [100.0, 122.0],
                road: 0,
                facing: [0.0, 1.0]
            }
        );
        assert_eq!(
            plan.buildings[0],
            PlanBuilding {
                id: 0,
                block: 0,
                centre: [32.0, 52.0],
                width: 24.0,
                kind: 0
            }
        );
    }

    #[test]
    fn one_metre_per_pixel_keeps_pixel_numbers() {
        let plan = assemble(&layout(), &lamps(), &buildings(), 1.0);
        assert_eq!(plan.size, [300.0, 200.0]);
        assert_eq!(plan.buildings[0].centre, [16.0, 26.0]);
        assert_eq!(plan.buildings[0].width, 12.0);
        assert_eq!(plan.lamps[0].position, [50.0, 61.0]);
    }

    #[test]
    fn json_prints_millimetres_and_no_negative_zero() {
        // 0.1 m/px makes binary noise (3 · 0.1 = 0.30000000000000004) that must not print.
        let mut l = lamps();
        l[0].position = [3.0, 61.0];
        l[0].facing = [-0.0, 1.0];
        let plan = assemble(&layout(), &l, &buildings(), 0.1);
        let json = serde_json::to_string(&plan).unwrap();
        assert!(json.contains("\"position\":[0.3,6.1]"), "{json}");
        assert!(json.contains("\"facing\":[0.0,1.0]"), "{json}");
        assert!(!json.contains("0000000"), "{json}");
        assert_eq!(
            json,
            serde_json::to_string(&assemble(&layout(), &l, &buildings(), 0.1)).unwrap()
        );
    }
}
