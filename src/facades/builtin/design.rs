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
    /// Office block in a glass curtain wall: a grid of mullions, a lobby and shops below.
    GlassOffice,
    /// Stone classical block: ashlar, arched windows, a rusticated ground floor (arcade or
    /// windows and a door).
    StoneClassical,
    /// Brick industrial loft: large steel-grid windows, garage doors below.
    IndustrialLoft,
    /// Half-timbered house: pale infill between dark timber beams, small windows.
    HalfTimbered,
    /// Painted clapboard (horizontal siding) house, some with shutters.
    Clapboard,
    /// Modernist block clad in small square tiles, shops or garages below.
    TiledModern,
}

const STYLES: [Style; 12] = [
    Style::BrickGrid,
    Style::PlasterShutters,
    Style::Shopfront,
    Style::Balconies,
    Style::Townhouse,
    Style::Modern,
    Style::GlassOffice,
    Style::StoneClassical,
    Style::IndustrialLoft,
    Style::HalfTimbered,
    Style::Clapboard,
    Style::TiledModern,
];

/// Curtain-wall glass tints: blue, green, bronze, grey.
const GLASSES: [Colour; 5] = [
    [70, 96, 120],
    [74, 108, 100],
    [104, 90, 74],
    [88, 94, 102],
    [40, 56, 72],
];
/// Ashlar: limestone, sandstone, grey granite, red sandstone.
const STONES: [Colour; 4] = [
    [206, 198, 178],
    [198, 170, 128],
    [164, 164, 160],
    [164, 104, 84],
];
/// Clapboard paint: white, pale blue, sage, butter, barn red, grey.
const SIDINGS: [Colour; 6] = [
    [232, 230, 222],
    [168, 192, 210],
    [160, 178, 150],
    [230, 210, 150],
    [150, 60, 52],
    [150, 154, 156],
];
/// Tiles: white, cream, terracotta, teal, charcoal.
const TILES: [Colour; 5] = [
    [226, 226, 220],
    [220, 206, 176],
    [182, 104, 72],
    [76, 130, 132],
    [70, 72, 76],
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

/// Whether builtin facade `i` is narrow: 2.7–3.1 floor heights wide, so the narrowest
/// footprint (which fills every leftover in paper Algorithm 1) fits many facades, not one.
fn narrow(i: usize) -> bool {
    (i / STYLES.len()).is_multiple_of(2)
}

/// The wall's material.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wall {
    Brick {
        brick: Colour,
        mortar: Colour,
    },
    Plaster(Colour),
    /// A glass curtain wall of this tint.
    Glass(Colour),
    /// Ashlar stone courses.
    Stone(Colour),
    /// Painted horizontal boards.
    Siding(Colour),
    /// Small square tiles in grout.
    Tiles {
        tile: Colour,
        grout: Colour,
    },
}

/// What the ground floor holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ground {
    /// Windows and a front door.
    Residential,
    /// Shopfronts (and the house door when there are three bays or more).
    Shops(Awning),
    /// Garage doors and a front door.
    Garages,
    /// An arcade: arched openings with shops set back in the shade.
    Arcade,
}

/// What tops a shopfront.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Awning {
    /// A striped canvas awning with a scalloped hem.
    Striped,
    /// A plain canvas awning.
    Plain,
    /// No awning: a flat signage band (fascia).
    Fascia,
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
    /// Ground floor: shops, garages, an arcade, or windows; the door in `door_bay`.
    pub ground: Ground,
    pub door_bay: u32,
    pub pilasters: bool,
    pub shutters: bool,
    pub lintels: bool,
    /// Round-arched window heads.
    pub arched: bool,
    /// Steel-grid windows: extra glazing bars.
    pub grid: bool,
    /// Dark timber beams on the wall (half-timbering).
    pub timber: bool,
    /// The ground floor's wall cut in deep horizontal joints.
    pub rusticated: bool,
}

impl Design {
    /// The design of builtin facade `i`.
    pub fn new(i: usize) -> Design {
        let mut rng = crate::rng::stream(0, "builtin-facades", i as u64);
        let mut d = Design::draw(style_of(i), i / STYLES.len(), &mut rng);
        if narrow(i) {
            d.narrow(&mut rng);
        }
        d
    }

    /// Draws a design of `style` from `rng`; `cycle` (how many times the styles have gone
    /// round before it) picks its wall colour, so no two of a style share one.
    fn draw(style: Style, cycle: usize, rng: &mut Pcg64) -> Design {
        let (floors, bays, wall) = shape(style, cycle, rng);
        let floor_px = rng.random_range(90..=110);
        let bay_px = rng.random_range(88..=112);
        // Narrow townhouses get wider margins: no facade is under 250 px.
        let margin_px = rng
            .random_range(18..=34)
            .max((250u32.saturating_sub(bays * bay_px)).div_ceil(2));
        let ground = ground_of(style, rng);
        let (window_w, window_h) = match style {
            Style::Modern => (rng.random_range(0.62..0.72), rng.random_range(0.52..0.58)),
            Style::Balconies => (rng.random_range(0.46..0.52), rng.random_range(0.50..0.56)),
            Style::GlassOffice => (rng.random_range(0.86..0.92), rng.random_range(0.74..0.8)),
            Style::IndustrialLoft => (rng.random_range(0.7..0.8), rng.random_range(0.6..0.66)),
            Style::HalfTimbered => (rng.random_range(0.34..0.4), rng.random_range(0.44..0.5)),
            Style::TiledModern => (rng.random_range(0.55..0.65), rng.random_range(0.5..0.56)),
            _ => (rng.random_range(0.40..0.50), rng.random_range(0.50..0.58)),
        };
        let metal = [[52, 54, 60], [90, 92, 96], [30, 30, 32]];
        let frame = match style {
            Style::Modern | Style::GlassOffice | Style::IndustrialLoft | Style::TiledModern => {
                pick(rng, &metal)
            }
            _ => pick(rng, &FRAMES),
        };
        let arched = style == Style::StoneClassical
            || (style == Style::PlasterShutters && rng.random_bool(0.4));
        Design {
            style,
            floors,
            floor_px,
            bays,
            bay_px,
            margin_px,
            wall,
            trim: pick(rng, &TRIMS),
            frame,
            accent: pick(rng, &ACCENTS),
            window_w,
            window_h,
            ground,
            door_bay: rng.random_range(0..bays),
            pilasters: matches!(
                style,
                Style::Townhouse | Style::BrickGrid | Style::StoneClassical
            ) && rng.random_bool(0.6),
            shutters: style == Style::PlasterShutters
                || (style == Style::Clapboard && rng.random_bool(0.5)),
            lintels: matches!(
                style,
                Style::BrickGrid | Style::Townhouse | Style::IndustrialLoft
            ) || (style == Style::PlasterShutters && !arched),
            arched,
            grid: style == Style::IndustrialLoft,
            timber: style == Style::HalfTimbered,
            rusticated: style == Style::StoneClassical,
        }
    }

    /// Makes the design 2.7–3.1 floors wide (at least 250 px): fewer or narrower bays.
    fn narrow(&mut self, rng: &mut Pcg64) {
        let target =
            ((rng.random_range(2.7..3.1) * f64::from(self.floor_px)).round() as u32).max(250);
        self.bays = ((target - 36) / self.bay_px).clamp(2, 3);
        self.bay_px = self.bay_px.min((target - 36) / self.bays);
        self.margin_px = (target - self.bays * self.bay_px) / 2;
        self.door_bay = self.door_bay.min(self.bays - 1);
    }

    pub fn width(&self) -> u32 {
        self.bays * self.bay_px + 2 * self.margin_px
    }
}

fn pick(rng: &mut Pcg64, list: &[Colour]) -> Colour {
    list[rng.random_range(0..list.len())]
}

/// Floors, bays and wall of a `style` design; the wall colour is the `cycle`-th of its list
/// (offset by the style), every list at least as long as the cycles (5).
fn shape(style: Style, cycle: usize, rng: &mut Pcg64) -> (u32, u32, Wall) {
    let k = cycle + STYLES.iter().position(|&s| s == style).unwrap_or(0);
    let nth = |list: &[Colour]| list[k % list.len()];
    let brick = |rng: &mut Pcg64| Wall::Brick {
        brick: nth(&BRICKS),
        mortar: pick(rng, &[[200, 196, 186], [170, 166, 158], [120, 116, 110]]),
    };
    let plaster = |_: &mut Pcg64| Wall::Plaster(nth(&PLASTERS));
    let floors = |rng: &mut Pcg64, low: u32, high: u32| rng.random_range(low..=high);
    match style {
        Style::BrickGrid => (floors(rng, 4, 7), floors(rng, 3, 5), brick(rng)),
        Style::PlasterShutters => (floors(rng, 3, 6), floors(rng, 3, 5), plaster(rng)),
        Style::Shopfront => {
            let wall = if rng.random_bool(0.5) {
                brick(rng)
            } else {
                plaster(rng)
            };
            (floors(rng, 3, 6), floors(rng, 3, 5), wall)
        }
        Style::Balconies => (floors(rng, 4, 8), floors(rng, 3, 5), plaster(rng)),
        Style::Townhouse => (floors(rng, 3, 5), floors(rng, 2, 3), brick(rng)),
        Style::Modern => (floors(rng, 5, 8), floors(rng, 3, 5), plaster(rng)),
        Style::GlassOffice => (
            floors(rng, 5, 8),
            floors(rng, 3, 5),
            Wall::Glass(nth(&GLASSES)),
        ),
        Style::StoneClassical => (
            floors(rng, 4, 6),
            floors(rng, 3, 5),
            Wall::Stone(nth(&STONES)),
        ),
        Style::IndustrialLoft => (floors(rng, 3, 6), floors(rng, 2, 4), brick(rng)),
        Style::HalfTimbered => {
            let infill = pick(
                rng,
                &[
                    [232, 224, 206],
                    [226, 214, 188],
                    [236, 230, 214],
                    [214, 196, 160],
                ],
            );
            (floors(rng, 3, 4), floors(rng, 2, 4), Wall::Plaster(infill))
        }
        Style::Clapboard => (
            floors(rng, 3, 4),
            floors(rng, 2, 4),
            Wall::Siding(nth(&SIDINGS)),
        ),
        Style::TiledModern => {
            let tile = nth(&TILES);
            let grout = if tile[0] > 150 {
                [170, 168, 160]
            } else {
                [200, 198, 190]
            };
            (
                floors(rng, 4, 8),
                floors(rng, 3, 5),
                Wall::Tiles { tile, grout },
            )
        }
    }
}

/// The ground floor of a `style` design.
fn ground_of(style: Style, rng: &mut Pcg64) -> Ground {
    let awning =
        |rng: &mut Pcg64| [Awning::Striped, Awning::Plain, Awning::Fascia][rng.random_range(0..3)];
    match style {
        Style::Shopfront => Ground::Shops(awning(rng)),
        Style::Modern | Style::GlassOffice => Ground::Shops(Awning::Fascia),
        Style::BrickGrid | Style::Balconies if rng.random_bool(0.3) => Ground::Shops(awning(rng)),
        Style::StoneClassical if rng.random_bool(0.5) => Ground::Arcade,
        Style::IndustrialLoft => Ground::Garages,
        Style::TiledModern if rng.random_bool(0.5) => Ground::Garages,
        Style::TiledModern => Ground::Shops(Awning::Plain),
        Style::HalfTimbered if rng.random_bool(0.4) => Ground::Shops(Awning::Plain),
        _ => Ground::Residential,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn designs_have_plausible_proportions() {
        for i in 0..120 {
            let d = Design::new(i);
            assert_eq!(d, Design::new(i));
            assert!((3..=8).contains(&d.floors), "{i}: {d:?}");
            assert!((90..=110).contains(&d.floor_px), "{i}: {d:?}");
            assert!((250..=700).contains(&d.width()), "{i}: {} px", d.width());
            assert!(d.door_bay < d.bays);
        }
    }
}
