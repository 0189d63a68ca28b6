//! A text plate's style + the seed + its name → how it is lit after dusk; and the plates'
//! images → atlas pages and materials, one set of pages per way of lighting.
//!
//! | light | plates | material | after dusk |
//! |---|---|---|---|
//! | [`PlateLight::Backlit`] | every street-name plate, [`BACKLIT_SHOP_SHARE`] of shop signs | the page's texture, emission [`BACKLIT_EMISSION`] times the texture (`emissive_textured`) | the face glows as a lit panel does: pale paper bright, dark letters dark |
//! | [`PlateLight::LampLit`] | the other shop signs, [`LAMP_LIT_BANNER_SHARE`] of banners, [`LAMP_LIT_PAINTED_SHARE`] of painted text, the rear number plate of a car in a driving lane (its plate lamp; the car chooses, not the draw) | the page's texture, named with [`crate::model::LAMP_LIT_SUFFIX`] | the renderer puts a small lamp over it (`render::scene_lighting`) |
//! | [`PlateLight::Unlit`] | the rest | the page's texture | dark but for street lamps, windows and cars |
//!
//! By day none of it shows: emission and the lamps' lights scale with the lighting's
//! `emission` (0 by day), so a day frame's bytes are the same as without it.
//!
//! The draw is the plate's own stream, `rng::stream(seed, "plate_light/<wall>/<rect>", 0)`,
//! keyed by where the plate is (not by its name, which the replay of grouped entries
//! numbers again): it takes nothing from the entry's stream, so no other object moves.

use image::RgbImage;
use rand::RngExt;
use rayon::prelude::*;

use super::Placing;
use super::atlas_layout::{self, AtlasLayout};
use super::plate_style::PlateStyle;
use crate::model::{LAMP_LIT_SUFFIX, Texture};

/// Emission of a backlit face at full night (linear RGB, times its texture): white paper
/// glows about as bright as a lamp's pool on the pavement at the night exposure.
pub const BACKLIT_EMISSION: [f32; 3] = [0.62, 0.6, 0.56];
/// Share of shop signs that are backlit (the others are lamp-lit).
pub const BACKLIT_SHOP_SHARE: f64 = 0.6;
/// Share of banners a lamp lights (the others stay dark).
pub const LAMP_LIT_BANNER_SHARE: f64 = 0.5;
/// Share of painted wall text a lamp lights (the others stay dark).
pub const LAMP_LIT_PAINTED_SHARE: f64 = 0.25;

/// How a text plate is lit after dusk.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum PlateLight {
    Unlit,
    Backlit,
    LampLit,
}

impl PlateLight {
    pub const ALL: [PlateLight; 3] = [PlateLight::Unlit, PlateLight::Backlit, PlateLight::LampLit];

    /// The light of the plate of `style` at `place` (a key naming where it is: its wall
    /// and rectangle), drawn from its own stream.
    pub fn draw(style: PlateStyle, seed: u64, place: &str) -> PlateLight {
        let mut rng = crate::rng::stream(seed, &format!("plate_light/{place}"), 0);
        let u: f64 = rng.random();
        match style {
            PlateStyle::Street => PlateLight::Backlit,
            PlateStyle::Shop if u < BACKLIT_SHOP_SHARE => PlateLight::Backlit,
            PlateStyle::Shop => PlateLight::LampLit,
            PlateStyle::Banner if u < LAMP_LIT_BANNER_SHARE => PlateLight::LampLit,
            PlateStyle::Painted if u < LAMP_LIT_PAINTED_SHARE => PlateLight::LampLit,
            // A number plate's light is its car's: see `number_plate`.
            PlateStyle::Banner | PlateStyle::Painted | PlateStyle::Number => PlateLight::Unlit,
        }
    }

    /// The `text_light` COCO attribute.
    pub fn name(self) -> &'static str {
        match self {
            PlateLight::Unlit => "unlit",
            PlateLight::Backlit => "backlit",
            PlateLight::LampLit => "lamp_lit",
        }
    }

    /// The material name of page `i` of `page_name`'s pages lit this way: unlit pages keep
    /// the plain `<page_name>_<i>`.
    fn page_material(self, page_name: &str, i: usize) -> String {
        match self {
            PlateLight::Unlit => format!("{page_name}_{i}"),
            PlateLight::Backlit => format!("{page_name}_backlit_{i}"),
            PlateLight::LampLit => format!("{page_name}_{i}{LAMP_LIT_SUFFIX}"),
        }
    }
}

/// Where a plate's image went: its material and its uv spans on that material's page.
pub(crate) struct PlateSlot {
    pub material: u32,
    pub uv: ([f64; 2], [f64; 2]),
}

/// Packs `images` (plate `i` lit as `lights[i]`) onto atlas pages, one set of pages per
/// light, registers one material per page and returns each plate's slot, in plate order.
pub(crate) fn pack_pages(
    images: Vec<RgbImage>,
    lights: &[PlateLight],
    page_name: &str,
    placing: &mut Placing,
) -> Vec<PlateSlot> {
    let mut images: Vec<Option<RgbImage>> = images.into_iter().map(Some).collect();
    let mut slots: Vec<Option<PlateSlot>> = (0..images.len()).map(|_| None).collect();
    for light in PlateLight::ALL {
        let members: Vec<usize> = (0..lights.len()).filter(|&i| lights[i] == light).collect();
        if members.is_empty() {
            continue;
        }
        let group: Vec<RgbImage> = members.iter().filter_map(|&i| images[i].take()).collect();
        let sizes: Vec<[u32; 2]> = group.iter().map(|m| [m.width(), m.height()]).collect();
        let atlas = AtlasLayout::pack(&sizes, atlas_layout::PAGE);
        let pages: Vec<Texture> = (0..atlas.pages.len())
            .into_par_iter()
            .map(|page| Texture::from_rgb(String::new(), atlas.paint(page, &group)))
            .collect();
        let materials: Vec<u32> = pages
            .iter()
            .enumerate()
            .map(|(i, page)| {
                let name = light.page_material(page_name, i);
                if light == PlateLight::Backlit {
                    let m = placing.add(&name, [1.0; 3], Some(page), BACKLIT_EMISSION);
                    placing.texture_emission(m);
                    m
                } else {
                    placing.add(&name, [1.0; 3], Some(page), [0.0; 3])
                }
            })
            .collect();
        for (k, &i) in members.iter().enumerate() {
            slots[i] = Some(PlateSlot {
                material: materials[atlas.slots[k].page],
                uv: atlas.uv_spans(k),
            });
        }
    }
    slots
        .into_iter()
        .map(|s| s.expect("every plate has one light, so one group"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn share(style: PlateStyle, light: PlateLight) -> f64 {
        let n = 2000;
        let hits = (0..n)
            .filter(|i| PlateLight::draw(style, 7, &format!("text_{i:04}")) == light)
            .count();
        hits as f64 / f64::from(n)
    }

    #[test]
    fn shop_signs_and_street_plates_are_always_lit_and_wall_text_sometimes() {
        assert_eq!(share(PlateStyle::Street, PlateLight::Backlit), 1.0);
        assert_eq!(share(PlateStyle::Shop, PlateLight::Unlit), 0.0);
        let backlit = share(PlateStyle::Shop, PlateLight::Backlit);
        assert!((backlit - BACKLIT_SHOP_SHARE).abs() < 0.04, "{backlit}");
        let banner = share(PlateStyle::Banner, PlateLight::LampLit);
        assert!((banner - LAMP_LIT_BANNER_SHARE).abs() < 0.04, "{banner}");
        let painted = share(PlateStyle::Painted, PlateLight::LampLit);
        assert!((painted - LAMP_LIT_PAINTED_SHARE).abs() < 0.04, "{painted}");
        assert_eq!(share(PlateStyle::Painted, PlateLight::Backlit), 0.0);
    }

    #[test]
    fn the_draw_is_the_plates_own_seeded_choice() {
        let draws = |seed| {
            (0..64).map(move |i| PlateLight::draw(PlateStyle::Shop, seed, &format!("text_{i:04}")))
        };
        assert!(draws(1).eq(draws(1)));
        assert!(!draws(1).eq(draws(2)));
    }
}
