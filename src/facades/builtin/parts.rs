//! Labelled parts of a facade: windows, sills, lintels, shutters, balconies, doors, shops.
//!
//! Each function draws one part's pixels and records its CMP box through
//! [`Canvas::part`]; the caller decides where parts go (see `painter`).

use rand::RngExt;
use rand_pcg::Pcg64;

use crate::model::PxRect;

use super::super::cmp_label::CmpLabel;
use super::canvas::{Canvas, Colour, mix, rect, scale};
use super::design::Awning;
use super::wall::shadow_below;

/// Glass: sky reflected at the top, a dark room below.
const GLASS_TOP: Colour = [156, 178, 194];
const GLASS_BOTTOM: Colour = [46, 56, 66];
/// Frame bar thickness.
const BAR: u32 = 4;

/// A framed window with a mullion and a transom; some have curtains.
pub fn window(c: &mut Canvas, r: PxRect, frame: Colour, rng: &mut Pcg64) {
    c.part(CmpLabel::Window, r);
    // The recess: a dark reveal around the frame.
    c.shade(
        rect(
            r.x0.saturating_sub(2),
            r.y0.saturating_sub(2),
            r.x1 + 2,
            r.y1,
        ),
        0.72,
    );
    c.fill(r, frame);
    let glass = rect(r.x0 + BAR, r.y0 + BAR, r.x1 - BAR, r.y1 - BAR);
    glass_pane(c, glass, rng);
    if rng.random_bool(0.35) {
        curtains(c, glass, rng);
    }
    let mid = (r.x0 + r.x1) / 2;
    c.fill(rect(mid - 1, r.y0, mid + 2, r.y1), frame);
    let transom = r.y0 + r.height() * 3 / 10;
    c.fill(rect(r.x0, transom, r.x1, transom + 3), frame);
    // Shadow of the lintel on the top of the glass.
    c.shade(rect(glass.x0, glass.y0, glass.x1, glass.y0 + 3), 0.7);
}

/// Glass with a reflection gradient and a faint diagonal glint.
fn glass_pane(c: &mut Canvas, g: PxRect, rng: &mut Pcg64) {
    let tint: i32 = rng.random_range(-14..=14);
    let top = GLASS_TOP.map(|v| super::canvas::add(v, tint));
    let bottom = GLASS_BOTTOM.map(|v| super::canvas::add(v, tint / 2));
    c.gradient(g, top, bottom);
    let phase = rng.random_range(0..40);
    c.each(g, |x, y, p| {
        if (x + 2 * y + phase) % 60 < 8 {
            scale(p, 1.18)
        } else {
            p
        }
    });
}

/// Pale curtains drawn in from both sides of the glass.
fn curtains(c: &mut Canvas, g: PxRect, rng: &mut Pcg64) {
    let cloth = [[226, 218, 196], [200, 190, 170], [190, 170, 150]][rng.random_range(0..3)];
    let w = g.width() / 5;
    for r in [
        rect(g.x0, g.y0 + 3, g.x0 + w, g.y1),
        rect(g.x1 - w, g.y0 + 3, g.x1, g.y1),
    ] {
        c.each(r, |x, _, p| {
            let fold = if (x - r.x0) % 5 == 0 { 0.85 } else { 1.0 };
            scale(mix(p, cloth, 0.8), fold)
        });
    }
}

/// A stone sill under a window, with its shadow on the wall.
pub fn sill(c: &mut Canvas, window: PxRect, trim: Colour) {
    let r = rect(
        window.x0.saturating_sub(5),
        window.y1,
        window.x1 + 5,
        window.y1 + 6,
    );
    c.part(CmpLabel::Sill, r);
    c.fill(r, trim);
    c.shade(rect(r.x0, r.y0, r.x1, r.y0 + 2), 1.12);
    shadow_below(c, r, 4);
}

/// A lintel with a keystone over a window.
pub fn lintel(c: &mut Canvas, window: PxRect, trim: Colour) {
    let r = rect(
        window.x0.saturating_sub(4),
        window.y0.saturating_sub(10),
        window.x1 + 4,
        window.y0.saturating_sub(2),
    );
    c.part(CmpLabel::Deco, r);
    c.fill(r, trim);
    let mid = (r.x0 + r.x1) / 2;
    c.fill(
        rect(mid - 5, r.y0.saturating_sub(2), mid + 5, r.y1 + 1),
        scale(trim, 1.08),
    );
    c.shade(rect(r.x0, r.y1 - 2, r.x1, r.y1), 0.8);
}

/// Slatted shutters either side of a window, `width` each.
pub fn shutters(c: &mut Canvas, window: PxRect, width: u32, paint: Colour) {
    let paint = mix(paint, [150, 150, 140], 0.3);
    for r in [
        rect(
            window.x0.saturating_sub(width + 2),
            window.y0,
            window.x0 - 2,
            window.y1,
        ),
        rect(window.x1 + 2, window.y0, window.x1 + width + 2, window.y1),
    ] {
        c.part(CmpLabel::Blind, r);
        c.each(r, |x, y, _| {
            if x == r.x0 || x + 1 == r.x1 {
                scale(paint, 0.7)
            } else if (y - r.y0) % 5 == 4 {
                scale(paint, 0.72)
            } else {
                paint
            }
        });
    }
}

/// A balcony in front of the lower part of a French window: slab and railing.
pub fn balcony(c: &mut Canvas, window: PxRect, rail_h: u32, trim: Colour, metal: Colour) {
    let (x0, x1) = (window.x0.saturating_sub(12), window.x1 + 12);
    let slab = rect(x0, window.y1, x1, window.y1 + 7);
    c.part(CmpLabel::Balcony, rect(x0, window.y1 - rail_h, x1, slab.y1));
    c.fill(slab, trim);
    c.shade(rect(slab.x0, slab.y0, slab.x1, slab.y0 + 2), 1.15);
    shadow_below(c, slab, 8);
    let top = window.y1 - rail_h;
    c.fill(rect(x0, top, x1, top + 4), metal);
    c.fill(rect(x0, window.y1 - 5, x1, window.y1 - 3), metal);
    let mut x = x0;
    while x + 2 <= x1 {
        c.fill(rect(x, top, x + 2, window.y1), metal);
        x += 7;
    }
    c.fill(rect(x1 - 3, top, x1, window.y1), metal);
}

/// A panelled front door with a glazed transom, in a stone surround; `r` reaches the
/// ground.
pub fn door(c: &mut Canvas, r: PxRect, paint: Colour, trim: Colour, rng: &mut Pcg64) {
    c.fill(
        rect(
            r.x0.saturating_sub(6),
            r.y0.saturating_sub(6),
            r.x1 + 6,
            r.y1,
        ),
        trim,
    );
    c.shade(
        rect(
            r.x0.saturating_sub(6),
            r.y0.saturating_sub(6),
            r.x1 + 6,
            r.y0.saturating_sub(4),
        ),
        1.12,
    );
    c.part(CmpLabel::Door, r);
    c.fill(r, scale(paint, 0.6));
    let transom = rect(r.x0 + 3, r.y0 + 3, r.x1 - 3, r.y0 + r.height() / 5);
    glass_pane(c, transom, rng);
    let leaf = rect(r.x0 + 3, transom.y1 + 3, r.x1 - 3, r.y1);
    c.fill(leaf, paint);
    let mid = (leaf.x0 + leaf.x1) / 2;
    c.fill(rect(mid, leaf.y0, mid + 1, leaf.y1), scale(paint, 0.6));
    let (pw, ph) = (leaf.width() / 2, leaf.height() / 2);
    for (px, py) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
        let p = rect(
            leaf.x0 + px * pw + 5,
            leaf.y0 + py * ph + 6,
            leaf.x0 + (px + 1) * pw - 5,
            leaf.y0 + (py + 1) * ph - 6,
        );
        c.shade(p, 0.82);
        c.shade(rect(p.x0, p.y1 - 2, p.x1, p.y1), 1.3);
    }
    c.fill(
        rect(mid + 4, leaf.y0 + ph - 2, mid + 7, leaf.y0 + ph + 2),
        [200, 170, 90],
    );
    c.shade(rect(r.x0, r.y0, r.x1, r.y0 + 4), 0.7);
}

/// A shopfront filling `r`: frame, kick plate, glass panes, a glazed door, and an awning
/// above `r` reaching `awning_h` over it.
pub fn shop(
    c: &mut Canvas,
    r: PxRect,
    frame: Colour,
    (awning, kind): (Colour, Awning),
    awning_h: u32,
    rng: &mut Pcg64,
) {
    c.part(CmpLabel::Shop, r);
    c.fill(r, frame);
    let kick = r.y1 - 14;
    c.shade(rect(r.x0, kick, r.x1, kick + 2), 0.7);
    let inner = rect(r.x0 + 5, r.y0 + 5, r.x1 - 5, kick);
    glass_pane(c, inner, rng);
    // Shelves and goods glimpsed through the glass.
    for _ in 0..3 {
        let y = rng.random_range(inner.y0 + inner.height() / 3..inner.y1 - 3);
        c.shade(rect(inner.x0, y, inner.x1, y + 2), 1.35);
    }
    let panes = (inner.width() / 60).max(2);
    let pane_w = inner.width() / panes;
    for i in 1..panes {
        let x = inner.x0 + i * pane_w;
        c.fill(rect(x - 2, inner.y0, x + 2, inner.y1), frame);
    }
    let d = rect(inner.x1 - pane_w + 6, inner.y0 + 8, inner.x1 - 4, r.y1);
    if d.width() >= 20 {
        c.part(CmpLabel::Door, d);
        c.fill(d, frame);
        glass_pane(c, rect(d.x0 + 5, d.y0 + 5, d.x1 - 5, d.y1 - 14), rng);
        c.fill(
            rect(d.x0 + 5, (d.y0 + d.y1) / 2, d.x1 - 5, (d.y0 + d.y1) / 2 + 3),
            scale(frame, 1.4),
        );
    }
    let a = rect(
        r.x0.saturating_sub(4),
        r.y0.saturating_sub(4),
        r.x1 + 4,
        r.y0 + awning_h,
    );
    if kind == Awning::Fascia {
        // A flat signage band over the glass, lit along its top edge.
        let band = rect(a.x0, a.y0, a.x1, a.y0 + (awning_h * 3 / 5).max(10));
        c.part(CmpLabel::Deco, band);
        c.fill(band, scale(awning, 0.8));
        c.shade(rect(band.x0, band.y0, band.x1, band.y0 + 2), 1.3);
        shadow_below(c, band, 3);
        return;
    }
    c.part(CmpLabel::Deco, a);
    let stripe_light = mix(awning, [240, 236, 226], 0.85);
    let striped = kind == Awning::Striped;
    c.each(a, |x, y, _| {
        let base = if !striped || ((x - a.x0) / 12).is_multiple_of(2) {
            awning
        } else {
            stripe_light
        };
        // Slope shading: the canvas darkens towards its lower edge, with a scalloped hem.
        let t = f64::from(y - a.y0) / f64::from(a.height());
        let hem = y + 5 >= a.y1 && (!striped || ((x - a.x0) % 12) as i32 - 6 > 0);
        scale(base, if hem { 0.7 } else { 1.05 - 0.25 * t })
    });
    shadow_below(c, a, 8);
}

/// A round-arched head over window `r`: an arch `rise` pixels high of frame around glass,
/// with a stone voussoir band outside it.
pub fn arch(c: &mut Canvas, r: PxRect, rise: u32, frame: Colour, trim: Colour) {
    let (cx, half) = (f64::from(r.x0 + r.x1) / 2.0, f64::from(r.width()) / 2.0);
    let (base, rise_f) = (f64::from(r.y0), f64::from(rise.max(1)));
    let around = rect(
        r.x0.saturating_sub(6),
        r.y0.saturating_sub(rise + 6),
        r.x1 + 6,
        r.y0,
    );
    c.each(around, |x, y, p| {
        let dx = (f64::from(x) + 0.5 - cx) / half;
        let dy = (base - f64::from(y) - 0.5) / rise_f;
        let d = (dx * dx + dy * dy).sqrt();
        let ring = 6.0 / half;
        if d < 1.0 - 4.0 / half {
            mix(GLASS_TOP, GLASS_BOTTOM, (1.0 - dy).clamp(0.0, 1.0) * 0.4)
        } else if d < 1.0 {
            frame
        } else if d < 1.0 + ring {
            scale(trim, if dx.abs() < 0.15 { 1.1 } else { 0.97 })
        } else {
            p
        }
    });
}

/// Extra glazing bars over window `r`: a steel grid of `cols × rows` panes.
pub fn grid_bars(c: &mut Canvas, r: PxRect, cols: u32, rows: u32, frame: Colour) {
    for i in 1..cols {
        let x = r.x0 + r.width() * i / cols;
        c.fill(rect(x - 1, r.y0, x + 1, r.y1), frame);
    }
    for j in 1..rows {
        let y = r.y0 + r.height() * j / rows;
        c.fill(rect(r.x0, y - 1, r.x1, y + 1), frame);
    }
}

/// A roller or sectional garage door filling `r` (it reaches the ground), with a lintel.
pub fn garage(c: &mut Canvas, r: PxRect, paint: Colour, trim: Colour, rng: &mut Pcg64) {
    c.fill(
        rect(
            r.x0.saturating_sub(5),
            r.y0.saturating_sub(7),
            r.x1 + 5,
            r.y0,
        ),
        trim,
    );
    shadow_below(c, rect(r.x0, r.y0.saturating_sub(7), r.x1, r.y0), 5);
    c.part(CmpLabel::Door, r);
    let mut noise = super::canvas::Grain::new(rng);
    let sectional = rng.random_bool(0.5);
    c.each(r, |x, y, p| {
        let ly = y - r.y0;
        let line = if sectional {
            ly % 24 < 2 || (x - r.x0) % 40 < 1
        } else {
            ly.is_multiple_of(6)
        };
        let base = mix(paint, p, 0.1).map(|v| super::canvas::add(v, noise.next(3)));
        if line { scale(base, 0.72) } else { base }
    });
    c.shade(rect(r.x0, r.y0, r.x1, r.y0 + 5), 0.7);
}

/// An arcade opening filling `r` (reaching the ground): a round arch on piers, deep shade
/// inside and a shopfront set back in it.
pub fn arcade(c: &mut Canvas, r: PxRect, frame: Colour, awning: Colour, rng: &mut Pcg64) {
    let rise = (r.width() / 2).min(r.height() / 3);
    let glass = rect(r.x0 + 8, r.y0 + rise, r.x1 - 8, r.y1);
    shop(c, glass, frame, (awning, Awning::Fascia), 10, rng);
    let (cx, half) = (f64::from(r.x0 + r.x1) / 2.0, f64::from(r.width()) / 2.0);
    let spring = f64::from(r.y0 + rise);
    c.each(r, |x, y, p| {
        let dx = (f64::from(x) + 0.5 - cx) / half;
        let dy = (spring - f64::from(y) - 0.5) / f64::from(rise.max(1));
        let inside = dy <= 0.0 || dx * dx + dy * dy < 1.0;
        let shade = if f64::from(y) < spring + 14.0 {
            0.45
        } else {
            0.7
        };
        if inside { scale(p, shade) } else { p }
    });
}
