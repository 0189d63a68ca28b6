//! Buildings + facades → each building's facade and wall height.
//!
//! The scene stage clads the buildings with these facades and the objects stage puts text
//! on the same walls, so both read the choice and the height from here.
//!
//! With no spec widths, `building.kind` is the facade index (paper): a kind beyond the
//! facade list takes facade `kind % n`. With spec widths, the facade is drawn from
//! `crate::rng::stream(seed, "facade", building.id)`. A building is its facade's height,
//! or [`PLAIN_HEIGHT`] when the facade's height is not a positive number or there are no
//! facades at all.

use rand::RngExt;

use crate::model::{Building, Facade, FacadeSet};

/// Height of a building that has no usable facade, in metres.
pub const PLAIN_HEIGHT: f64 = 12.0;

/// What decides every building's facade: the set, whether the spec gives building widths,
/// and the spec's seed.
#[derive(Clone, Copy, Debug)]
pub struct FacadeChoice<'a> {
    pub facades: &'a FacadeSet,
    /// The spec's explicit building widths (metres), if any: then facades are drawn at
    /// random and tiled along the wall.
    pub widths: Option<&'a [f64]>,
    pub seed: u64,
}

impl FacadeChoice<'_> {
    /// The facade index of `building` (None when the set has no facades).
    pub fn of(&self, building: &Building) -> Option<usize> {
        let n = self.facades.facades.len();
        if n == 0 {
            return None;
        }
        Some(match self.widths {
            None => building.kind as usize % n,
            Some(_) => {
                let mut rng = crate::rng::stream(self.seed, "facade", u64::from(building.id));
                rng.random_range(0..n)
            }
        })
    }

    /// Every building's wall height in metres (above the block surface), in input order.
    pub fn heights(&self, buildings: &[Building]) -> Vec<f64> {
        buildings
            .iter()
            .map(|b| facade_height(self.of(b).map(|c| &self.facades.facades[c])))
            .collect()
    }
}

/// The wall height of a building clad with `facade` (see the module's fallbacks).
pub fn facade_height(facade: Option<&Facade>) -> f64 {
    facade.map_or(PLAIN_HEIGHT, |f| {
        if usable(f.height) {
            f.height
        } else {
            PLAIN_HEIGHT
        }
    })
}

/// Whether a facade or roof measure can be used: finite and positive.
pub fn usable(v: f64) -> bool {
    v.is_finite() && v > 0.0
}
