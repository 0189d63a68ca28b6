//! Design: a builtin facade's number → its style, size and colours (drawn, not painted).
//!
//! The design is drawn from its own stream, `crate::rng::stream(0, "builtin-facades", i)`,
//! apart from the painter's noise, so tests can ask how many floors facade `i` has without
//! drawing it.

use rand::RngExt;
use rand_pcg::Pcg64;

use super::canvas::Colour;

/// Styles, cycled through by facade number.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// Brick apartment block: grid of framed windows with sills and lintels.
    BrickGrid,
    /// Plaster apartment block with shutters.
    PlasterShutters,
    /// Plaster or brick block over a row of shopfronts with awnings.
    Shopfront,
    /// Apartment block with balconies and railings.
    Balconies,
    /// Narrow brick townhouse with pilasters and a front door.
    Townhouse,
    /// Plain modern block: wide windows, dark frames, shops below.
    Modern,
}

const STYLES: [Style; 6] = [
    Style::BrickGrid,
    Style::PlasterShutters,
    Style::Shopfront,
    Style::Balconies,
    Style::Townhouse,
    Style::Modern,
];

const BRICKS: [Colour; 5] = [
    [150, 72, 52],
    [172, 96, 66],
    [126, 60, 48],
    [186, 140, 100],
    [110, 78, 64],
];
const PLASTERS: [Colour; 8] = [
    [226, 214, 188],
    [214, 186, 150],
    [200, 208, 202],
    [232, 224, 210],
    [206, 160, 128],
    [188, 196, 210],
    [220, 200, 120],
    [176, 186, 164],
];
/// Molding, cornice and sill colours: stone, terracotta, slate, sand, verdigris.
const TRIMS: [Colour; 6] = [
    [196, 192, 182],
    [176, 94, 66],
    [82, 88, 98],
    [206, 186, 146],
    [104, 150, 128],
    [236, 232, 222],
];
const FRAMES: [Colour; 5] = [
    [240, 240, 236],
    [44, 58, 48],
    [92, 62, 42],
    [52, 54, 60],
    [214, 206, 190],
];
const ACCENTS: [Colour; 6] = [
    [150, 40, 40],
    [40, 90, 60],
    [40, 60, 120],
    [190, 150, 40],
    [110, 50, 90],
    [60, 60, 64],
];

/// The style of builtin facade `i`.
fn style_of(i: usize) -> Style {
    STYLES[i % STYLES.len()]
}

/// The wall's material.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wall {
    Brick { brick: Colour, mortar: Colour },
    Plaster(Colour),
}

/// Everything the painter needs to draw one facade.
#[derive(Clone, Debug, PartialEq)]
pub struct Design {
    pub style: Style,
    /// Floors below the top molding, ground floor included.
    pub floors: u32,
    pub floor_px: u32,
    pub bays: u32,
    pub bay_px: u32,
    /// Wall left and right of the bays.
    pub margin_px: u32,
    pub wall: Wall,
    pub trim: Colour,
    pub frame: Colour,
    /// Awnings, shutters, door paint.
    pub accent: Colour,
    /// Window width and height as fractions of the bay and of the floor.
    pub window_w: f64,
    pub window_h: f64,
    /// Ground floor: shops, or windows and a door in `door_bay`.
    pub shops: bool,
    pub door_bay: u32,
    pub pilasters: bool,
    pub shutters: bool,
    pub lintels: bool,
}

impl Design {
    /// The design of builtin facade `i`.
    pub fn new(i: usize) -> Design {
        let mut rng = crate::rng::stream(0, "builtin-facades", i as u64);
        Design::draw(style_of(i), &mut rng)
    }

    /// Draws a design of `style` from `rng`.
    fn draw(style: Style, rng: &mut Pcg64) -> Design {
        let pick = |rng: &mut Pcg64, list: &[Colour]| list[rng.random_range(0..list.len())];
        let brick = |rng: &mut Pcg64| Wall::Brick {
            brick: pick(rng, &BRICKS),
            mortar: pick(rng, &[[200, 196, 186], [170, 166, 158], [120, 116, 110]]),
        };
        let plaster = |rng: &mut Pcg64| Wall::Plaster(pick(rng, &PLASTERS));
        let (floors, bays, wall) = match style {
            Style::BrickGrid => (rng.random_range(4..=7), rng.random_range(3..=5), brick(rng)),
            Style::PlasterShutters => (
                rng.random_range(3..=6),
                rng.random_range(3..=5),
                plaster(rng),
            ),
            Style::Shopfront => {
                let wall = if rng.random_bool(0.5) {
                    brick(rng)
                } else {
                    plaster(rng)
                };
                (rng.random_range(3..=6), rng.random_range(3..=5), wall)
            }
            Style::Balconies => (
                rng.random_range(4..=8),
                rng.random_range(3..=5),
                plaster(rng),
            ),
            Style::Townhouse => (rng.random_range(3..=5), rng.random_range(2..=3), brick(rng)),
            Style::Modern => (
                rng.random_range(5..=8),
                rng.random_range(3..=5),
                plaster(rng),
            ),
        };
        let floor_px = rng.random_range(90..=110);
        let bay_px = rng.random_range(88..=112);
        // Narrow townhouses get wider margins: no facade is under 250 px.
        let margin_px = rng
            .random_range(18..=34)
            .max((250u32.saturating_sub(bays * bay_px)).div_ceil(2));
        let shops = match style {
            Style::Shopfront | Style::Modern => true,
            Style::BrickGrid | Style::Balconies => rng.random_bool(0.3),
            Style::PlasterShutters | Style::Townhouse => false,
        };
        let (window_w, window_h) = match style {
            Style::Modern => (rng.random_range(0.62..0.72), rng.random_range(0.52..0.58)),
            Style::Balconies => (rng.random_range(0.46..0.52), rng.random_range(0.50..0.56)),
            _ => (rng.random_range(0.40..0.50), rng.random_range(0.50..0.58)),
        };
        Design {
            style,
            floors,
            floor_px,
            bays,
            bay_px,
            margin_px,
            wall,
            trim: pick(rng, &TRIMS),
            frame: if style == Style::Modern {
                pick(rng, &[[52, 54, 60], [90, 92, 96], [30, 30, 32]])
            } else {
                pick(rng, &FRAMES)
            },
            accent: pick(rng, &ACCENTS),
            window_w,
            window_h,
            shops,
            door_bay: rng.random_range(0..bays),
            pilasters: matches!(style, Style::Townhouse | Style::BrickGrid) && rng.random_bool(0.6),
            shutters: style == Style::PlasterShutters,
            lintels: matches!(
                style,
                Style::BrickGrid | Style::Townhouse | Style::PlasterShutters
            ),
        }
    }

    pub fn width(&self) -> u32 {
        self.bays * self.bay_px + 2 * self.margin_px
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn designs_have_plausible_proportions() {
        for i in 0..60 {
            let d = Design::new(i);
            assert_eq!(d, Design::new(i));
            assert!((3..=8).contains(&d.floors), "{i}: {d:?}");
            assert!((90..=110).contains(&d.floor_px), "{i}: {d:?}");
            assert!((250..=700).contains(&d.width()), "{i}: {} px", d.width());
            assert!(d.door_bay < d.bays);
        }
    }
}
