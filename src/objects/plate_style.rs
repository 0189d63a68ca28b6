//! Plate styles → how a text plate is padded, decorated and where on a wall it may hang.
//!
//! | style | looks like | where |
//! |---|---|---|
//! | `shop` | a framed sign board | low on the wall, its bottom edge within [`SHOP_BAND`] of [`super::wall_text::MIN_HEIGHT`]: above the shop windows and doors |
//! | `banner` | a cloth strip with coloured hems top and bottom | anywhere on the free wall |
//! | `painted` | letters painted straight on the wall, no plate | anywhere on the free wall |
//! | `street` | a street-name plate with a thin border near its edge | on a pole at a street corner (`street_name` entries) |
//! | `plate` | an EU number plate: white, a thin black rim, a blue band at the left | front and rear of every car (`car` entries, [`super::number_plate`]) |

use image::{Rgb, RgbImage};

/// How far above the lowest plate edge a shop sign's bottom edge may be, in metres.
pub const SHOP_BAND: f64 = 1.2;

/// The blue of an EU number plate's band (sRGB).
pub const EU_BLUE: [u8; 3] = [0, 51, 153];

/// One plate style; recorded per text object (`text_style` in COCO).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum PlateStyle {
    Shop,
    Banner,
    Painted,
    Street,
    /// A car's number plate (`plate`).
    Number,
}

impl PlateStyle {
    /// Wall styles and their shares in tenths: shop 4, banner 2, painted 4.
    pub const WALL_MIX: [(PlateStyle, u32); 3] = [
        (PlateStyle::Shop, 4),
        (PlateStyle::Banner, 2),
        (PlateStyle::Painted, 4),
    ];

    pub fn name(self) -> &'static str {
        match self {
            PlateStyle::Shop => "shop",
            PlateStyle::Banner => "banner",
            PlateStyle::Painted => "painted",
            PlateStyle::Street => "street",
            PlateStyle::Number => "plate",
        }
    }

    /// Margin around the text `[x, y]` as a fraction of the letter size.
    pub fn padding(self) -> [f64; 2] {
        match self {
            PlateStyle::Shop => [0.45, 0.35],
            PlateStyle::Banner => [0.4, 0.5],
            PlateStyle::Painted => [0.15, 0.1],
            PlateStyle::Street => [0.4, 0.3],
            // Room for the blue band at the left; `number_plate` centres the text again
            // on the plate's fixed size.
            PlateStyle::Number => [0.6, 0.05],
        }
    }

    /// Draws the style's frame, hems or rule on a plate of `paper` around `text_box`.
    pub fn decorate(self, image: &mut RgbImage, text_box: [u32; 4], paper: [u8; 3], ink: [u8; 3]) {
        let (w, h) = image.dimensions();
        let letter = text_box[3] - text_box[1];
        let mut fill = |x0: u32, y0: u32, x1: u32, y1: u32, colour: [u8; 3]| {
            for y in y0..y1.min(h) {
                for x in x0..x1.min(w) {
                    image.put_pixel(x, y, Rgb(colour));
                }
            }
        };
        match self {
            PlateStyle::Shop => {
                // A frame in the ink colour, inset a little from the plate's edge.
                let inset = (letter / 10).max(2);
                let t = (letter / 14).max(2);
                let [x0, y0, x1, y1] = [inset, inset, w - inset, h - inset];
                fill(x0, y0, x1, y0 + t, ink);
                fill(x0, y1 - t, x1, y1, ink);
                fill(x0, y0, x0 + t, y1, ink);
                fill(x1 - t, y0, x1, y1, ink);
            }
            PlateStyle::Banner => {
                // Hems: a band of the ink colour mixed halfway with the paper.
                let hem = (text_box[1] / 2).max(1);
                let mix: [u8; 3] =
                    std::array::from_fn(|i| ((u16::from(paper[i]) + u16::from(ink[i])) / 2) as u8);
                fill(0, 0, w, hem, mix);
                fill(0, h - hem, w, h, mix);
            }
            PlateStyle::Street => {
                // A thin border in the ink colour close to the plate's edge.
                let t = (letter / 16).max(1);
                let inset = t;
                let [x0, y0, x1, y1] = [inset, inset, w - inset, h - inset];
                fill(x0, y0, x1, y0 + t, ink);
                fill(x0, y1 - t, x1, y1, ink);
                fill(x0, y0, x0 + t, y1, ink);
                fill(x1 - t, y0, x1, y1, ink);
            }
            PlateStyle::Number => {
                // The EU band (40 of the plate's 520 mm) and a one-pixel rim in the ink.
                let band = (w * 40).div_ceil(520);
                fill(0, 0, band, h, EU_BLUE);
                fill(0, 0, w, 1, ink);
                fill(0, h - 1, w, h, ink);
                fill(0, 0, 1, h, ink);
                fill(w - 1, 0, w, h, ink);
            }
            PlateStyle::Painted => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decorations_stay_outside_the_text_box() {
        for style in [
            PlateStyle::Shop,
            PlateStyle::Banner,
            PlateStyle::Painted,
            PlateStyle::Street,
            PlateStyle::Number,
        ] {
            let [px, py] = style.padding().map(|p| (40.0 * p) as u32);
            let text_box = [px, py, px + 200, py + 40];
            let mut image = RgbImage::from_pixel(200 + 2 * px, 40 + 2 * py, Rgb([250; 3]));
            style.decorate(&mut image, text_box, [250; 3], [0; 3]);
            let mut marked = 0;
            for (x, y, p) in image.enumerate_pixels() {
                if p.0 != [250; 3] {
                    marked += 1;
                    let inside =
                        text_box[0] <= x && x < text_box[2] && text_box[1] <= y && y < text_box[3];
                    assert!(!inside, "{}: {x},{y}", style.name());
                }
            }
            assert_eq!(
                marked == 0,
                style == PlateStyle::Painted,
                "{}",
                style.name()
            );
        }
    }
}
