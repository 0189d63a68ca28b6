//! A map's buildings → the walls that face a road, for wall text (`wall_text::Walls`),
//! clad as `scene::map_city` clads them ([`map_cladding`], [`Tiling::Floors`]).
//!
//! A wall is an edge of a building's outer ring at least [`MIN_WALL`] long (courtyards
//! face no road). It faces a road when the line out of its middle along its outward
//! normal reaches a paved carriageway within [`REACH`] before it enters any building (its
//! own included: a wing in front). Its plates stand between [`MIN_HEIGHT`] above the
//! kerb and [`TOP_CLEARANCE`] below the top of its walls: the lowest eaves of the volumes
//! the scene builds that stand on the ground along it ([`ground_eave`]: the building's
//! roof, or a lower part of it), so no plate reaches into a roof or hangs in the air. A
//! building lifted off the ground there (`min_height`) takes none. The facade's windows
//! on it are [`floor_window_rects`].

use super::wall_text::{MIN_HEIGHT, TOP_CLEARANCE, Tiling, Wall, floor_window_rects};
use crate::model::geometry::KERB_Y;
use crate::model::geometry::massing::{ground_eave, volumes};
use crate::model::geometry::polygon::{bounds, contains, distance, left_normal, nearest};
use crate::model::{FacadeSet, OsmMap, PavedSegment, map_cladding};

/// The farthest a carriageway may lie in front of a wall that faces it, metres: a wide
/// sidewalk and a front garden.
pub const REACH: f64 = 20.0;
/// The shortest wall that takes text, metres.
pub const MIN_WALL: f64 = 2.0;
/// How finely the line in front of a wall is followed, metres.
const STEP: f64 = 0.5;

/// Every wall of `map`'s buildings that faces a road, in building then edge order, clad
/// in the facades `map_cladding(map, facades, seed)` gives. Pure and deterministic.
pub fn map_facing_walls(map: &OsmMap, facades: &FacadeSet, seed: u64) -> Vec<Wall> {
    let cladding = map_cladding(map, facades, seed);
    let paved: Vec<PavedSegment> = map.paved_segments().collect();
    let boxes: Vec<[f64; 4]> = map.buildings.iter().map(|b| bounds(&b.outer)).collect();
    let mut walls = Vec::new();
    for (i, (b, c)) in map.buildings.iter().zip(&cladding).enumerate() {
        let volumes = volumes(b, c.height);
        let facade = c.usable(facades);
        let ring = &b.outer;
        for e in 0..ring.len() {
            let (a, z) = (ring[e], ring[(e + 1) % ring.len()]);
            let length = distance(a, z);
            let Some(normal) = left_normal(a, z).filter(|_| length >= MIN_WALL) else {
                continue;
            };
            let top = ground_eave(&volumes, a, z, [-normal[0], -normal[1]]);
            let band = [KERB_Y + MIN_HEIGHT, KERB_Y + top - TOP_CLEARANCE];
            if band[1] <= band[0] {
                continue;
            }
            let middle = [(a[0] + z[0]) / 2.0, (a[1] + z[1]) / 2.0];
            if !faces_road(map, &paved, &boxes, middle, normal) {
                continue;
            }
            let (repeat, tiling, windows) = match facade {
                Some(f) => {
                    let floor = f.height / f64::from(f.floors);
                    let windows =
                        floor_window_rects(&f.windows, [length, top, f.width], floor, f.floors);
                    let floors = f.floors;
                    (f.width, Tiling::Floors { floor, floors }, windows)
                }
                None => (length, Tiling::Stretched, Vec::new()),
            };
            walls.push(Wall {
                building: i as u32,
                // Seen from the front the edge runs right to left: its end is the left,
                // where the facade starts (`MeshBuilder::wall`).
                origin: z,
                right: [normal[1], -normal[0]],
                normal,
                length,
                band,
                facade: facade.and(c.facade),
                repeat,
                height: top,
                windows,
                tiling,
            });
        }
    }
    walls
}

/// Whether the line from `middle` along `normal` reaches a paved carriageway within
/// [`REACH`] before it enters a building.
fn faces_road(
    map: &OsmMap,
    paved: &[PavedSegment],
    boxes: &[[f64; 4]],
    middle: [f64; 2],
    normal: [f64; 2],
) -> bool {
    let end = [middle[0] + normal[0] * REACH, middle[1] + normal[1] * REACH];
    let near: Vec<&PavedSegment> = (paved.iter())
        .filter(|s| distance(middle, nearest(s.a, s.b, middle)) <= REACH + s.width / 2.0)
        .collect();
    if near.is_empty() {
        return false;
    }
    let (lo, hi) = (
        [middle[0].min(end[0]), middle[1].min(end[1])],
        [middle[0].max(end[0]), middle[1].max(end[1])],
    );
    let in_the_way: Vec<usize> = (boxes.iter().enumerate())
        .filter(|(_, b)| b[0] <= hi[0] && lo[0] <= b[2] && b[1] <= hi[1] && lo[1] <= b[3])
        .map(|(j, _)| j)
        .collect();
    let steps = (REACH / STEP) as usize;
    for k in 1..=steps {
        let t = k as f64 * STEP;
        let p = [middle[0] + normal[0] * t, middle[1] + normal[1] * t];
        if in_the_way.iter().any(|&j| {
            let b = &map.buildings[j];
            contains(&b.outer, p) && !b.holes.iter().any(|h| contains(h, p))
        }) {
            return false;
        }
        if near
            .iter()
            .any(|s| distance(p, nearest(s.a, s.b, p)) < s.width / 2.0)
        {
            return true;
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use image::RgbImage;

    use super::*;
    use crate::model::{Facade, Texture};
    use crate::test_support::street_map;

    /// One facade 4 floors (12 m) high and 10 m wide, with a window in its ground floor
    /// (u 0.1…0.3) and one in its upper floors (u 0.6…0.8, v 0.1…0.2).
    fn facades() -> FacadeSet {
        FacadeSet {
            facades: vec![Facade {
                name: "a".to_owned(),
                floors: 4,
                height: 12.0,
                width: 10.0,
                molding: [0, 0, 0],
                colour: [128, 128, 128],
                roof: 0,
                windows: vec![[0.1, 0.8, 0.3, 0.95], [0.6, 0.1, 0.8, 0.2]],
                texture: Texture::from_rgb("t", RgbImage::new(4, 4)),
            }],
            roofs: Vec::new(),
        }
    }

    #[test]
    fn the_wall_facing_the_street_is_found_left_edge_first() {
        // The building (x −120…−100, z 19…39) stands 13 m south of road 0's kerb; its
        // north wall faces it, the others face no paved road within reach.
        let mut map = street_map();
        map.buildings[0].height = Some(14.0);
        let walls = map_facing_walls(&map, &facades(), 5);
        assert_eq!(walls.len(), 1, "{walls:?}");
        let w = &walls[0];
        // Seen from the north, looking south, the left edge is the east end.
        assert_eq!(w.origin, [-100.0, 19.0]);
        assert_eq!(w.right, [-1.0, 0.0]);
        assert_eq!(w.normal, [0.0, -1.0]);
        assert_eq!((w.length, w.height, w.repeat), (20.0, 14.0, 10.0));
        assert_eq!(w.band, [KERB_Y + MIN_HEIGHT, KERB_Y + 14.0 - TOP_CLEARANCE]);
        assert_eq!(w.facade, Some(0));
        assert_eq!(
            w.tiling,
            Tiling::Floors {
                floor: 3.0,
                floors: 4
            }
        );
        // The ground floor's window once per facade width, 0.6…2.4 m up (v 0.95…0.8 of
        // its 0.25 of v over 3 m); the upper one on every upper floor repeat below 14 m
        // (at 3 m + 9 m × (0.75 − v) / 0.75: only the first, the second's starts at
        // 18.6 m).
        let near = |a: [f64; 4], b: [f64; 4]| a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-6);
        let y = KERB_Y;
        let expected = [
            [1.0, y + 0.6, 3.0, y + 2.4],
            [6.0, y + 9.6, 8.0, y + 10.8],
            [11.0, y + 0.6, 13.0, y + 2.4],
            [16.0, y + 9.6, 18.0, y + 10.8],
        ];
        assert_eq!(w.windows.len(), expected.len(), "{:?}", w.windows);
        for (got, want) in w.windows.iter().zip(expected) {
            assert!(near(*got, want), "{got:?} != {want:?}");
        }
        // The texture there is the window's: the scene's floor-scale mapping.
        let [u, v] = w.texture_at(7.0, y + 10.2);
        assert!((u - 0.7).abs() < 1e-9 && (v - 0.15).abs() < 1e-6, "{u} {v}");
        let [_, v] = w.texture_at(2.0, y + 0.3);
        assert!((v - (1.0 - 0.1 * 0.25)).abs() < 1e-9, "{v}");
        // Its second upper repeat starts at 12 m: v back at the ground floor's top.
        let [_, v] = w.texture_at(2.0, y + 12.0 + 1e-9);
        assert!((v - 0.75).abs() < 1e-6, "{v}");
    }

    #[test]
    fn a_building_in_front_or_a_rising_roof_shortens_what_faces_the_street() {
        let mut map = street_map();
        map.buildings[0].height = Some(14.0);
        // A kiosk between the wall's middle and the road.
        let mut kiosk = map.buildings[0].clone();
        kiosk.outer = vec![
            [-112.0, 10.0],
            [-108.0, 10.0],
            [-108.0, 14.0],
            [-112.0, 14.0],
        ];
        map.buildings.push(kiosk);
        let walls = map_facing_walls(&map, &facades(), 5);
        // The kiosk's own north wall faces the road; the building behind it does not.
        assert!(walls.iter().all(|w| w.building == 1), "{walls:?}");
        assert_eq!(walls.len(), 1);
        // A gabled roof with a mapped height: the text keeps below its eaves. Over the
        // 20 m deep footprint it rises 0.6 × 10 = 6 m, so the eaves are at 8 m.
        let mut map = street_map();
        map.buildings[0].height = Some(14.0);
        map.buildings[0].roof_shape = Some("gabled".to_owned());
        let walls = map_facing_walls(&map, &facades(), 5);
        assert_eq!(walls[0].band[1], KERB_Y + 8.0 - TOP_CLEARANCE);
        assert_eq!(walls[0].height, 8.0);
        // A shape the scene lays flat: the walls, and the text, reach the top.
        map.buildings[0].roof_shape = Some("saltbox".to_owned());
        let walls = map_facing_walls(&map, &facades(), 5);
        assert_eq!(walls[0].band[1], KERB_Y + 14.0 - TOP_CLEARANCE);
        // A height from levels is the walls': the roof rises above them.
        map.buildings[0].roof_shape = Some("gabled".to_owned());
        map.buildings[0].height_from = "levels".to_owned();
        let walls = map_facing_walls(&map, &facades(), 5);
        assert_eq!(walls[0].band[1], KERB_Y + 14.0 - TOP_CLEARANCE);
        map.buildings[0].height_from = "height".to_owned();
        // Too low for a plate: none.
        map.buildings[0].height = Some(4.0);
        assert!(map_facing_walls(&map, &facades(), 5).is_empty());
    }

    #[test]
    fn text_keeps_below_the_lowest_part_along_the_wall_and_off_a_lifted_one() {
        let mut map = street_map();
        map.buildings[0].height = Some(14.0);
        // A 6 m wing on the ground at the west end of the street front.
        let mut wing = map.buildings[0].clone();
        wing.outer = vec![
            [-120.0, 19.0],
            [-120.0, 29.0],
            [-110.0, 29.0],
            [-110.0, 19.0],
        ];
        wing.outer.reverse();
        wing.height = Some(6.0);
        map.buildings[0].parts.push(wing);
        let walls = map_facing_walls(&map, &facades(), 5);
        assert_eq!(walls.len(), 1);
        assert_eq!(walls[0].band[1], KERB_Y + 6.0 - TOP_CLEARANCE);
        assert_eq!(walls[0].height, 6.0);
        // The wing lifted 3 m: the rest of the building stands under it, 14 m tall.
        map.buildings[0].parts[0].min_height = Some(3.0);
        let walls = map_facing_walls(&map, &facades(), 5);
        assert_eq!(walls[0].band[1], KERB_Y + 14.0 - TOP_CLEARANCE);
        // The whole building lifted 3 m: nothing of its street front is on the ground.
        map.buildings[0].min_height = Some(3.0);
        assert!(map_facing_walls(&map, &facades(), 5).is_empty());
    }
}
