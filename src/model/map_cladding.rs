//! A map building's facade and height: the one choice the scene clads it with
//! (`scene::map_city`) and the objects put wall text on (`objects::map_walls`).
//!
//! Building `i`'s facade is drawn from `rng::stream(seed, "map-facade", i)` (a building
//! the place stage put on the map keeps the facade it was sized for), then its seeded
//! floors; it is as tall as the map says, else those floors of its facade. Where the map
//! gives the building a colour (`building:colour`, else that of its largest part with
//! one), its facade is instead the usable one nearest that colour (the facades' mean
//! colours, squared sRGB distance, the first of equals); the draws are made all the same,
//! so no other building's cladding moves. Its roof is the facade's, or the roof nearest
//! the map's `roof:colour` (the building's, else its largest part's) where it gives one.

use std::ops::RangeInclusive;

use rand::RngExt;

use super::{Facade, FacadeSet, MapBuilding, OsmMap};

/// Floors a building without a mapped height gets, drawn uniformly.
pub const SEEDED_FLOORS: RangeInclusive<u32> = 3..=7;
/// A floor's height where a building has no usable facade, metres.
const PLAIN_FLOOR: f64 = 3.0;

/// How one map building is clad.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapCladding {
    /// Its facade (index in the set); `None` when the set is empty.
    pub facade: Option<usize>,
    /// Its roof (index in the set's roofs); `None` when the set has none.
    pub roof: Option<usize>,
    /// Its height above the kerb before a `roof:shape` takes its share, metres.
    pub height: f64,
}

impl MapCladding {
    /// Its facade when that can be laid at floor scale: it has a size and floors.
    pub fn usable<'a>(&self, set: &'a FacadeSet) -> Option<&'a Facade> {
        self.facade.map(|f| &set.facades[f]).filter(|f| usable(f))
    }
}

/// Whether `facade` has a size and floors, so that it can be laid at its own scale.
fn usable(facade: &Facade) -> bool {
    facade.height > 0.0 && facade.width > 0.0 && facade.floors > 0
}

/// Every building of `map`'s cladding, in building order. Pure and deterministic.
pub fn map_cladding(map: &OsmMap, set: &FacadeSet, seed: u64) -> Vec<MapCladding> {
    let facades = &set.facades;
    (map.buildings.iter().enumerate())
        .map(|(i, b)| {
            let mut rng = crate::rng::stream(seed, "map-facade", i as u64);
            let drawn = (!facades.is_empty()).then(|| rng.random_range(0..facades.len()));
            // A placed building keeps the facade it was sized for.
            let sized = b.facade.map(|f| f as usize).filter(|&f| f < facades.len());
            let floors = rng.random_range(SEEDED_FLOORS);
            let coloured = painted(b, |b| b.colour).and_then(|c| nearest_facade(set, c));
            let facade = sized.or(coloured).or(drawn);
            let roofs = |c| nearest(set.roofs.iter().map(|r| r.colour), c);
            let roof = (painted(b, |b| b.roof_colour).and_then(roofs))
                .or_else(|| facade.map(|f| facades[f].roof as usize))
                .filter(|&r| r < set.roofs.len());
            let mut out = MapCladding {
                facade,
                roof,
                height: 0.0,
            };
            let floor = (out.usable(set)).map_or(PLAIN_FLOOR, |f| f.height / f64::from(f.floors));
            out.height = b.height.unwrap_or(f64::from(floors) * floor);
            out
        })
        .collect()
}

/// `colour` of building `b`, else of its largest part (by area, the first of equals) that
/// has one.
fn painted(b: &MapBuilding, colour: impl Fn(&MapBuilding) -> Option<[u8; 3]>) -> Option<[u8; 3]> {
    colour(b).or_else(|| {
        (b.parts.iter())
            .filter(|p| colour(p).is_some())
            .fold(None, |best: Option<&MapBuilding>, p| match best {
                Some(q) if q.area >= p.area => Some(q),
                _ => Some(p),
            })
            .and_then(colour)
    })
}

/// The usable facade of `set` nearest `colour`.
fn nearest_facade(set: &FacadeSet, colour: [u8; 3]) -> Option<usize> {
    let usable: Vec<usize> = (0..set.facades.len())
        .filter(|&f| usable(&set.facades[f]))
        .collect();
    nearest(usable.iter().map(|&f| set.facades[f].colour), colour).map(|k| usable[k])
}

/// The index of the colour of `colours` nearest `colour` (squared sRGB distance, the first
/// of equals).
fn nearest(colours: impl Iterator<Item = [u8; 3]>, colour: [u8; 3]) -> Option<usize> {
    let distance = |c: [u8; 3]| -> u32 {
        (0..3)
            .map(|k| {
                (i32::from(c[k]) - i32::from(colour[k]))
                    .unsigned_abs()
                    .pow(2)
            })
            .sum()
    };
    colours
        .enumerate()
        .min_by_key(|&(i, c)| (distance(c), i))
        .map(|(i, _)| i)
}

#[cfg(test)]
mod tests {
    use image::RgbImage;

    use super::*;
    use crate::model::{Roof, Texture};
    use crate::test_support::street_map;

    /// Facades red, white (unusable: no floors) and grey; roofs black and green.
    fn set() -> FacadeSet {
        let facade = |name: &str, colour, floors| Facade {
            name: name.to_owned(),
            floors,
            height: 12.0,
            width: 10.0,
            molding: colour,
            colour,
            roof: 0,
            windows: Vec::new(),
            texture: Texture::from_rgb(name, RgbImage::new(2, 2)),
        };
        let roof = |name: &str, colour| Roof {
            name: name.to_owned(),
            colour,
            tile: 3.0,
            texture: Texture::from_rgb(name, RgbImage::new(2, 2)),
        };
        FacadeSet {
            facades: vec![
                facade("red", [200, 40, 30], 4),
                facade("white", [250, 250, 250], 0),
                facade("grey", [150, 150, 150], 4),
            ],
            roofs: vec![roof("black", [20, 20, 20]), roof("green", [120, 180, 120])],
        }
    }

    #[test]
    fn a_mapped_colour_picks_the_nearest_usable_facade_and_roof() {
        let mut map = street_map();
        let drawn = map_cladding(&map, &set(), 3)[0];
        assert_eq!(drawn.roof, Some(0), "the facade's roof");
        // White: the white facade cannot be laid at scale; grey is the nearest usable.
        map.buildings[0].colour = Some([255, 255, 255]);
        map.buildings[0].roof_colour = Some([180, 201, 179]);
        let c = map_cladding(&map, &set(), 3)[0];
        assert_eq!((c.facade, c.roof), (Some(2), Some(1)));
        // The draws are made all the same: the seeded height is the drawn one's.
        assert_eq!(c.height, drawn.height);
        // Without its own colour, the building takes its largest coloured part's.
        map.buildings[0].colour = None;
        let mut part = map.buildings[0].clone();
        (part.area, part.colour) = (10.0, Some([255, 0, 0]));
        let mut larger = part.clone();
        (larger.area, larger.colour) = (20.0, Some([140, 140, 140]));
        let mut plain = part.clone();
        (plain.area, plain.colour) = (30.0, None);
        map.buildings[0].parts = vec![part, larger, plain];
        assert_eq!(map_cladding(&map, &set(), 3)[0].facade, Some(2));
        map.buildings[0].parts.swap_remove(1);
        assert_eq!(map_cladding(&map, &set(), 3)[0].facade, Some(0));
    }
}
