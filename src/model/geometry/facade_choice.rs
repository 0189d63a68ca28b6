//! Buildings + facades → each building's facade, wall height and facade repeat.
//!
//! The scene stage clads the buildings with these facades, the objects stage puts text on
//! the same walls and the driver names each building's facade in its annotations, so all
//! three read the choice from here ([`FacadeChoice::all`], one pure function of the
//! buildings, the set, the spec's widths and seed).
//!
//! **Balanced choice.** Paper Algorithm 1 gives every building a *kind*, one footprint
//! width per facade, and the smallest width fills every leftover: clad by kind (the paper's
//! rule, facade = `kind`), one facade stood on 513 of `day.toml`'s 842 buildings. So each
//! building takes, among the facades that *fit* its wall, the one used least so far; ties
//! are broken by `crate::rng::stream(seed, "facade-balance", 0)`. Buildings are visited in
//! input order (their ids), so neighbours in a block rarely share a facade. Footprints stay
//! exactly where Algorithm 1 put them.
//!
//! What fits:
//! - with no spec widths, a facade fits a wall `W` metres long when `k ≥ 1` copies of it,
//!   each stretched by at most [`MAX_STRETCH`] (±20 %), cover the wall: `k = round(W / w)`,
//!   `|W / (k w) − 1| ≤ 0.2`. The texture's u then runs `0..k`. A building's own kind's
//!   facade always fits (it is its width); when nothing fits (a facade with no usable
//!   width), the building takes facade `kind % n`, the paper's rule;
//! - with spec widths, facades tile along the wall at their own width (u runs
//!   `0..W / w`), so every facade fits and the choice is balanced over the whole set.
//!
//! A set of n facades cannot go under 1/n: a user's CMP folder of 6 facades would clad about a
//! sixth of the buildings with each. A building is its facade's height, or
//! [`PLAIN_HEIGHT`] when the facade's height is not a positive number or there are no
//! facades at all.

use rand::RngExt;

use crate::model::{Building, Facade, FacadeSet};

/// Height of a building that has no usable facade, in metres.
pub const PLAIN_HEIGHT: f64 = 12.0;

/// How far a facade may be stretched or squeezed along a wall and still fit it: ±20 %.
pub const MAX_STRETCH: f64 = 0.2;

/// What decides every building's facade: the set, whether the spec gives building widths,
/// the layout's scale and the spec's seed.
#[derive(Clone, Copy, Debug)]
pub struct FacadeChoice<'a> {
    pub facades: &'a FacadeSet,
    /// The spec's explicit building widths (metres), if any: then facades are tiled along
    /// the wall at their own width.
    pub widths: Option<&'a [f64]>,
    pub metres_per_pixel: f64,
    pub seed: u64,
}

impl FacadeChoice<'_> {
    /// Every building's facade index, in input order (None when the set has no facades).
    /// See the module docs for the rule.
    pub fn all(&self, buildings: &[Building]) -> Vec<Option<usize>> {
        let facades = &self.facades.facades;
        let n = facades.len();
        if n == 0 {
            return vec![None; buildings.len()];
        }
        let mut used = vec![0u32; n];
        let mut rng = crate::rng::stream(self.seed, "facade-balance", 0);
        let mut fitting: Vec<usize> = Vec::with_capacity(n);
        buildings
            .iter()
            .map(|building| {
                let wall = self.wall_length(building);
                fitting.clear();
                fitting.extend((0..n).filter(|&f| self.fits(&facades[f], wall)));
                let least = fitting.iter().map(|&f| used[f]).min();
                let choice = match least {
                    None => building.kind as usize % n,
                    Some(least) => {
                        fitting.retain(|&f| used[f] == least);
                        fitting[rng.random_range(0..fitting.len())]
                    }
                };
                used[choice] += 1;
                Some(choice)
            })
            .collect()
    }

    /// Every building's wall height in metres (above the block surface), given `choice`
    /// (from [`FacadeChoice::all`]), in input order.
    pub fn heights(&self, choice: &[Option<usize>]) -> Vec<f64> {
        choice
            .iter()
            .map(|c| facade_height(c.map(|c| &self.facades.facades[c])))
            .collect()
    }

    /// The metres one copy of `facade` spans along a wall `length` metres long: its own
    /// width with spec widths, else the wall split into the nearest whole number of
    /// copies. The wall itself when the facade has no usable width (or there is none).
    pub fn repeat(&self, facade: Option<&Facade>, length: f64) -> f64 {
        match facade {
            Some(f) if usable(f.width) && self.widths.is_some() => f.width,
            Some(f) if usable(f.width) => length / copies(length, f.width),
            _ => length,
        }
    }

    /// The footprint's side in metres (footprints are squares).
    fn wall_length(&self, building: &Building) -> f64 {
        let fp = building.footprint;
        f64::from(fp.x1.saturating_sub(fp.x0)) * self.metres_per_pixel
    }

    /// Whether `facade` may clad a wall `length` metres long.
    fn fits(&self, facade: &Facade, length: f64) -> bool {
        if !usable(facade.width) {
            return false;
        }
        if self.widths.is_some() {
            return true;
        }
        let stretch = length / (copies(length, facade.width) * facade.width);
        (stretch - 1.0).abs() <= MAX_STRETCH + 1e-9
    }
}

/// Whole copies of a facade `width` wide nearest to covering `length`, at least 1.
fn copies(length: f64, width: f64) -> f64 {
    (length / width).round().clamp(1.0, 1000.0)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{PxRect, Texture};

    fn facade(name: &str, width: f64) -> Facade {
        Facade {
            name: name.to_owned(),
            floors: 4,
            height: 12.0,
            width,
            molding: [0; 3],
            colour: [128, 128, 128],
            roof: 0,
            windows: Vec::new(),
            texture: Texture::from_rgb(name, image::RgbImage::new(1, 1)),
        }
    }

    fn set(widths: &[f64]) -> FacadeSet {
        FacadeSet {
            facades: widths
                .iter()
                .enumerate()
                .map(|(i, &w)| facade(&format!("f{i}"), w))
                .collect(),
            roofs: Vec::new(),
        }
    }

    fn building(id: u32, side: u32, kind: u32) -> Building {
        Building {
            id,
            block: 0,
            footprint: PxRect {
                x0: 0,
                y0: 0,
                x1: side,
                y1: side,
            },
            kind,
        }
    }

    #[test]
    fn the_least_used_facade_that_fits_is_chosen_and_the_same_every_time() {
        // Walls of 10 m fit facades 9, 10 and 11 m wide (k = 1) and 5 m (k = 2), not 20 m.
        let facades = set(&[10.0, 9.0, 11.0, 5.0, 20.0]);
        let choose = |seed| FacadeChoice {
            facades: &facades,
            widths: None,
            metres_per_pixel: 1.0,
            seed,
        };
        let buildings: Vec<Building> = (0..40).map(|i| building(i, 10, 0)).collect();
        let chosen = choose(3).all(&buildings);
        assert_eq!(chosen, choose(3).all(&buildings));
        assert_ne!(chosen, choose(4).all(&buildings), "ties follow the seed");
        let mut used = [0; 5];
        for c in chosen.iter().flatten() {
            used[*c] += 1;
        }
        assert_eq!(used, [10, 10, 10, 10, 0]);
        // Two copies of the 5 m facade on a 10 m wall: u runs 0..2.
        assert_eq!(choose(3).repeat(Some(&facades.facades[3]), 10.0), 5.0);
        // A wall nothing fits takes its kind's facade (the paper's rule).
        let odd = [building(0, 3, 7)];
        assert_eq!(choose(3).all(&odd), [Some(7 % 5)]);
    }

    #[test]
    fn with_spec_widths_every_facade_fits_and_tiles_at_its_width() {
        let facades = set(&[10.0, 30.0]);
        let choice = FacadeChoice {
            facades: &facades,
            widths: Some(&[4.0]),
            metres_per_pixel: 1.0,
            seed: 1,
        };
        let chosen = choice.all(&[building(0, 4, 0), building(1, 4, 0)]);
        assert_eq!(chosen.iter().flatten().count(), 2);
        assert_ne!(chosen[0], chosen[1]);
        assert_eq!(choice.repeat(Some(&facades.facades[1]), 4.0), 30.0);
        let none = set(&[]);
        let empty = FacadeChoice {
            facades: &none,
            ..choice
        };
        assert_eq!(empty.all(&[building(0, 4, 0)]), [None]);
    }
}
