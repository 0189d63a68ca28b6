//! A seeded stream → text and background colour pairs with a WCAG-style luminance-contrast
//! floor, and a seeded minority of hard, low-contrast pairs.
//!
//! Contrast is WCAG 2's ratio `(L_light + 0.05) / (L_dark + 0.05)` of relative luminances.
//! The sRGB transfer curve is approximated by `c^2.5` (`c² · √c`: only `*` and `sqrt`, so
//! the same bits on every platform); next to WCAG's exact curve it moves a ratio by a few
//! percent at most, which does not matter for a floor.

use rand::RngExt;
use rand_pcg::Pcg64;

/// The floor most pairs keep: WCAG AA for normal text.
pub const CONTRAST_FLOOR: f64 = 4.5;
/// Share of pairs drawn below the floor, as hard cases.
pub const HARD_SHARE: f64 = 0.1;
/// Hard pairs still have this much contrast: faint, but there.
pub const HARD_RANGE: [f64; 2] = [1.6, 3.0];

/// Relative luminance of an sRGB colour (approximate, see the module notes).
pub fn luminance(c: [u8; 3]) -> f64 {
    let lin = |v: u8| {
        let x = f64::from(v) / 255.0;
        x * x * x.sqrt()
    };
    0.2126 * lin(c[0]) + 0.7152 * lin(c[1]) + 0.0722 * lin(c[2])
}

/// The contrast ratio of two luminances, at least 1.
pub fn contrast(a: f64, b: f64) -> f64 {
    (a.max(b) + 0.05) / (a.min(b) + 0.05)
}

/// A colour pair `(background, ink)`: with probability [`HARD_SHARE`] one whose contrast
/// lies in [`HARD_RANGE`], otherwise one at or above [`CONTRAST_FLOOR`].
pub fn pair(rng: &mut Pcg64) -> ([u8; 3], [u8; 3]) {
    let hard = rng.random::<f64>() < HARD_SHARE;
    let background = colour(rng);
    let ink = ink_for(rng, luminance(background), hard);
    (background, ink)
}

/// An ink colour for a background of luminance `background`: hard (low contrast) or not.
pub fn ink_for(rng: &mut Pcg64, background: f64, hard: bool) -> [u8; 3] {
    for _ in 0..64 {
        let ink = colour(rng);
        let c = contrast(luminance(ink), background);
        let fits = if hard {
            (HARD_RANGE[0]..HARD_RANGE[1]).contains(&c)
        } else {
            c >= CONTRAST_FLOOR
        };
        if fits {
            return ink;
        }
    }
    // Rarely reached: black or white, whichever stands out more (a hard case then simply is
    // not hard).
    if contrast(0.0, background) >= contrast(1.0, background) {
        [0; 3]
    } else {
        [255; 3]
    }
}

/// A colour: mostly saturated hues at any lightness, some greys and near-whites/blacks, as
/// signs and paints come.
fn colour(rng: &mut Pcg64) -> [u8; 3] {
    match rng.random_range(0..4) {
        0 => {
            let v = rng.random_range(0..=255u8);
            [v, v, v]
        }
        _ => std::array::from_fn(|_| rng.random_range(0..=255u8)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn most_pairs_clear_the_floor_and_a_minority_is_hard() {
        let mut rng = crate::rng::stream(5, "text_colours_test", 0);
        let n = 4000;
        let ratios: Vec<f64> = (0..n)
            .map(|_| {
                let (b, i) = pair(&mut rng);
                contrast(luminance(b), luminance(i))
            })
            .collect();
        let low = ratios.iter().filter(|&&c| c < CONTRAST_FLOOR).count();
        assert!(low > n / 20 && low < n / 6, "{low} of {n} below the floor");
        assert!(ratios.iter().all(|&c| c >= HARD_RANGE[0]));
    }

    #[test]
    fn luminance_spans_black_to_white() {
        assert_eq!(luminance([0; 3]), 0.0);
        assert!((luminance([255; 3]) - 1.0).abs() < 1e-12);
        assert!((contrast(1.0, 0.0) - 21.0).abs() < 1e-12);
    }
}
