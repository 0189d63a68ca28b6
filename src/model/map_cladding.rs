//! A map building's facade and height: the one choice the scene clads it with
//! (`scene::map_city`) and the objects put wall text on (`objects::map_walls`).
//!
//! Building `i`'s facade is drawn from `rng::stream(seed, "map-facade", i)` (a building
//! the place stage put on the map keeps the facade it was sized for), then its seeded
//! floors; it is as tall as the map says, else those floors of its facade.

use std::ops::RangeInclusive;

use rand::RngExt;

use super::{Facade, FacadeSet, OsmMap};

/// Floors a building without a mapped height gets, drawn uniformly.
pub const SEEDED_FLOORS: RangeInclusive<u32> = 3..=7;
/// A floor's height where a building has no usable facade, metres.
const PLAIN_FLOOR: f64 = 3.0;

/// How one map building is clad.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapCladding {
    /// Its facade (index in the set); `None` when the set is empty.
    pub facade: Option<usize>,
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
            let mut out = MapCladding {
                facade: sized.or(drawn),
                height: 0.0,
            };
            let floor = (out.usable(set)).map_or(PLAIN_FLOOR, |f| f.height / f64::from(f.floors));
            out.height = b.height.unwrap_or(f64::from(floors) * floor);
            out
        })
        .collect()
}
