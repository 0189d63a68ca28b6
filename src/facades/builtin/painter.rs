//! Painter: a [`Design`] → a [`Canvas`] with the facade drawn and every part annotated.
//!
//! Rows from the top: sky (background), parapet, the top molding (the crop line is its
//! bottom edge), the cornice, then the floors, top floor first, each `floor_px` high. The
//! ground floor starts with a molding (string course) and ends in a plinth; it holds shops,
//! or windows and a front door.

use rand_pcg::Pcg64;

use crate::model::PxRect;

use super::super::cmp_label::CmpLabel;
use super::canvas::{Canvas, rect, scale};
use super::design::{Awning, Design, Ground, Style, Wall};
use super::{parts, wall};

const SKY: u32 = 16;
const PARAPET: u32 = 22;
const TOP_MOLDING: u32 = 10;
const CORNICE: u32 = 22;
const STRING_COURSE: u32 = 10;
const PLINTH: u32 = 10;

/// First row below the top molding: where the loader crops.
pub const CROP_TOP: u32 = SKY + PARAPET + TOP_MOLDING;

/// Paints `d`, drawing texture noise from `rng`.
pub fn paint(d: &Design, rng: &mut Pcg64) -> Canvas {
    let width = d.width();
    let floors_top = CROP_TOP + CORNICE;
    let height = floors_top + d.floors * d.floor_px;
    let mut c = Canvas::new(width, height);

    wall::sky(&mut c, rect(0, 0, width, SKY));
    c.label_only(CmpLabel::Background, rect(0, 0, width, SKY));
    wall::wall(&mut c, rect(0, SKY, width, height), d.wall, rng);
    c.shade(rect(0, SKY, width, SKY + 4), 0.85);

    let top_molding = rect(0, SKY + PARAPET, width, CROP_TOP);
    c.part(CmpLabel::Molding, top_molding);
    wall::molding(&mut c, top_molding, d.trim, rng);
    let cornice = rect(0, CROP_TOP, width, floors_top);
    c.part(CmpLabel::Cornice, cornice);
    wall::cornice(&mut c, cornice, d.trim, rng);

    let ground_top = height - d.floor_px;
    if d.rusticated {
        let stone = match d.wall {
            Wall::Stone(stone) => scale(stone, 0.94),
            _ => d.trim,
        };
        let r = rect(0, ground_top, width, height);
        wall::courses(&mut c, r, stone, [64, 18, 3], 0.55, rng);
    }
    if d.timber {
        let posts: Vec<u32> = (0..=d.bays)
            .map(|b| (d.margin_px + b * d.bay_px).saturating_sub(4))
            .chain([0, width - 7])
            .collect();
        let mut posts = posts;
        posts.sort_unstable();
        posts.dedup();
        let rails: Vec<u32> = (0..d.floors).map(|f| floors_top + f * d.floor_px).collect();
        let wood = [[62, 44, 32], [48, 36, 30], [84, 56, 36]][d.door_bay as usize % 3];
        wall::timber(
            &mut c,
            rect(0, floors_top, width, ground_top),
            &posts,
            &rails,
            wood,
        );
    }
    if d.pilasters {
        let w = d.margin_px * 2 / 3;
        for x0 in [
            (d.margin_px - w) / 2,
            width - d.margin_px + (d.margin_px - w) / 2,
        ] {
            let r = rect(x0, floors_top + 7, x0 + w, ground_top);
            c.part(CmpLabel::Pillar, r);
            wall::pilaster(&mut c, r, d.trim, rng);
        }
    }
    for floor in 0..d.floors - 1 {
        let y0 = floors_top + floor * d.floor_px;
        if d.style == Style::Modern && floor > 0 {
            let band = rect(0, y0 - 3, width, y0 + 4);
            c.part(CmpLabel::Deco, band);
            c.fill_grain(band, d.trim, 3, rng);
            wall::shadow_below(&mut c, band, 3);
        }
        for bay in 0..d.bays {
            upper_bay(&mut c, d, y0, bay, rng);
        }
    }
    ground_floor(&mut c, d, ground_top, rng);
    weather(&mut c, width, height);
    c
}

/// The window (and its sill, lintel, shutters or balcony) of one bay of an upper floor.
fn upper_bay(c: &mut Canvas, d: &Design, y0: u32, bay: u32, rng: &mut Pcg64) {
    let fp = f64::from(d.floor_px);
    let balcony = d.style == Style::Balconies && (bay % 2 == 1 || d.bays < 3);
    let win = if balcony {
        let w = px(f64::from(d.bay_px) * (d.window_w + 0.08));
        bay_rect(d, bay, w, y0 + px(fp * 0.14), y0 + px(fp * 0.86))
    } else {
        let w = px(f64::from(d.bay_px) * d.window_w);
        let top = y0 + px(fp * 0.2);
        bay_rect(d, bay, w, top, top + px(fp * d.window_h))
    };
    if d.lintels {
        parts::lintel(c, win, d.trim);
    }
    if d.arched {
        parts::arch(
            c,
            win,
            (win.width() / 2).min(px(fp * 0.16)),
            d.frame,
            d.trim,
        );
    }
    if d.shutters {
        let slack = (d.bay_px - win.width()) / 2;
        parts::shutters(
            c,
            win,
            (win.width() / 2).min(slack.saturating_sub(5)),
            d.accent,
        );
    }
    parts::window(c, win, d.frame, rng);
    if d.grid {
        parts::grid_bars(c, win, 4, 3, d.frame);
    }
    if balcony {
        let metal = if d.frame[0] > 150 {
            [40, 42, 46]
        } else {
            d.frame
        };
        parts::balcony(c, win, px(fp * 0.3), d.trim, metal);
    } else if matches!(
        d.style,
        Style::Modern | Style::GlassOffice | Style::TiledModern
    ) {
        parts::sill(c, win, scale(d.frame, 1.3));
    } else {
        parts::sill(c, win, d.trim);
    }
}

/// The ground floor: string course, plinth, then shops or windows and a door.
fn ground_floor(c: &mut Canvas, d: &Design, y0: u32, rng: &mut Pcg64) {
    let width = d.width();
    let bottom = y0 + d.floor_px;
    let course = rect(0, y0, width, y0 + STRING_COURSE);
    c.part(CmpLabel::Molding, course);
    wall::molding(c, course, d.trim, rng);
    wall::plinth(c, rect(0, bottom - PLINTH, width, bottom), d.trim, rng);
    let fp = f64::from(d.floor_px);
    let door_w = px(f64::from(d.bay_px) * 0.5).max(44);
    let door = bay_rect(d, d.door_bay, door_w, y0 + px(fp * 0.24), bottom);
    match d.ground {
        Ground::Residential => {
            for bay in (0..d.bays).filter(|&b| b != d.door_bay) {
                let w = px(f64::from(d.bay_px) * d.window_w);
                let top = y0 + px(fp * 0.26);
                let win = bay_rect(d, bay, w, top, top + px(fp * d.window_h));
                parts::window(c, win, d.frame, rng);
                if d.grid {
                    parts::grid_bars(c, win, 4, 3, d.frame);
                }
                parts::sill(c, win, d.trim);
            }
            parts::door(c, door, d.accent, d.trim, rng);
        }
        Ground::Garages => {
            for bay in (0..d.bays).filter(|&b| b != d.door_bay) {
                let w = px(f64::from(d.bay_px) * 0.84);
                let r = bay_rect(d, bay, w, y0 + STRING_COURSE + px(fp * 0.22), bottom - 2);
                let paint = [[150, 152, 150], [96, 100, 104], d.accent][bay as usize % 3];
                parts::garage(c, r, paint, d.trim, rng);
            }
            parts::door(c, door, d.accent, d.trim, rng);
        }
        Ground::Arcade => {
            parts::door(c, door, d.accent, d.trim, rng);
            for bay in (0..d.bays).filter(|&b| b != d.door_bay) {
                let w = px(f64::from(d.bay_px) * 0.78);
                let r = bay_rect(d, bay, w, y0 + STRING_COURSE + px(fp * 0.08), bottom - 2);
                parts::arcade(c, r, scale(d.accent, 0.55), d.accent, rng);
            }
        }
        Ground::Shops(awning) => shops(c, d, (door, awning), y0, rng),
    }
}

/// Shops in runs of at most two bays, the house door in its own bay when there are three
/// bays or more.
fn shops(c: &mut Canvas, d: &Design, (door, awning): (PxRect, Awning), y0: u32, rng: &mut Pcg64) {
    let fp = f64::from(d.floor_px);
    let bottom = y0 + d.floor_px;
    let house_door = d.bays >= 3;
    let glass_top = y0 + STRING_COURSE + px(fp * 0.2);
    let mut bay = 0;
    while bay < d.bays {
        if house_door && bay == d.door_bay {
            parts::door(c, door, d.accent, d.trim, rng);
            bay += 1;
            continue;
        }
        let mut end = bay + 1;
        if end < d.bays && !(house_door && end == d.door_bay) && (end - bay) < 2 {
            end += 1;
        }
        let x0 = d.margin_px + bay * d.bay_px + 6;
        let x1 = d.margin_px + end * d.bay_px - 6;
        let frame = if matches!(d.style, Style::Modern | Style::GlassOffice) {
            d.frame
        } else {
            scale(d.accent, 0.55)
        };
        parts::shop(
            c,
            rect(x0, glass_top, x1, bottom - 2),
            frame,
            (d.accent, awning),
            px(fp * 0.16),
            rng,
        );
        bay = end;
    }
}

/// A rectangle `w` wide centred in `bay`, rows `y0..y1`.
fn bay_rect(d: &Design, bay: u32, w: u32, y0: u32, y1: u32) -> PxRect {
    let cx = d.margin_px + bay * d.bay_px + d.bay_px / 2;
    rect(cx - w / 2, y0, cx - w / 2 + w, y1)
}

/// Soft light from above: the facade darkens a little towards the street.
fn weather(c: &mut Canvas, width: u32, height: u32) {
    for y in SKY..height {
        let t = f64::from(y - SKY) / f64::from(height - SKY);
        c.shade(rect(0, y, width, y + 1), 1.03 - 0.1 * t);
    }
}

fn px(v: f64) -> u32 {
    v.round() as u32
}
