//! A seeded stream → text and background colour pairs with a WCAG-style luminance-contrast
//! floor, and a seeded minority of hard, low-contrast pairs.
//!
//! Contrast is WCAG 2's ratio `(L_light + 0.05) / (L_dark + 0.05)` of relative luminances.
//! The sRGB transfer curve is approximated by `c^2.5` (`c² · √c`: only `*` and `sqrt`, so
//! the same bits on every platform); next to WCAG's exact curve it moves a ratio by a few
//! percent at most, which does not matter for a floor.

use image::{Rgb, RgbImage};
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
    // Each channel's linear value looked up: the same numbers as worked out per pixel,
    // for the hundreds of thousands of wall pixels behind painted text.
    let lin = &*LINEAR;
    0.2126 * lin[usize::from(c[0])]
        + 0.7152 * lin[usize::from(c[1])]
        + 0.0722 * lin[usize::from(c[2])]
}

/// `c^2.5` of each 8-bit channel value `c / 255`, as `c² · √c`.
static LINEAR: std::sync::LazyLock<[f64; 256]> = std::sync::LazyLock::new(|| {
    std::array::from_fn(|v| {
        let x = v as f64 / 255.0;
        x * x * x.sqrt()
    })
});

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

/// Share of a wall patch's pixels allowed below the floor against the ink (mortar lines,
/// window reveals): the floor holds against the rest.
pub const PATCH_QUANTILE: f64 = 0.1;

/// How far a painted patch is faded towards a flat ground coat when the raw wall does not
/// keep the floor against the ink: the first of these that does is used.
const PRIMER_STEPS: [f64; 4] = [0.35, 0.6, 0.8, 1.0];

/// The wall patch behind painted text, primed where the raw wall fails the floor: the
/// contrast of `ink` against the patch pixel at [`PATCH_QUANTILE`] from the ink's side
/// (the darkest tenth for light ink, the lightest for dark) must reach
/// [`CONTRAST_FLOOR`]. Where it does not, the patch is faded towards a ground coat (the
/// patch's mean colour lightened behind dark ink, darkened behind light ink), as sign
/// painters prime a brick wall, in [`PRIMER_STEPS`]; a plain white or black coat if even the
/// full coat fails. A hard pair keeps the raw wall.
pub fn primed(patch: RgbImage, ink: [u8; 3], hard: bool) -> RgbImage {
    if hard || patch.width() == 0 || patch.height() == 0 {
        return patch;
    }
    let ink_l = luminance(ink);
    let n = f64::from(patch.width() * patch.height());
    let mean: [u8; 3] = std::array::from_fn(|c| {
        (patch.pixels().map(|p| f64::from(p.0[c])).sum::<f64>() / n).round() as u8
    });
    let mean_l = patch.pixels().map(|p| luminance(p.0)).sum::<f64>() / n;
    let dark_ink = ink_l < mean_l;
    if worst_contrast(&patch, ink_l, dark_ink) >= CONTRAST_FLOOR {
        return patch;
    }
    let coat: [u8; 3] = std::array::from_fn(|c| {
        let v = f64::from(mean[c]);
        if dark_ink {
            v + (255.0 - v) * 0.8
        } else {
            v * 0.2
        }
        .round() as u8
    });
    for a in PRIMER_STEPS {
        // Each channel value's faded value, once: the same numbers as per pixel.
        let fade: [[u8; 256]; 3] = std::array::from_fn(|c| {
            std::array::from_fn(|v| (v as f64 * (1.0 - a) + f64::from(coat[c]) * a).round() as u8)
        });
        let mut faded = patch.clone();
        for p in faded.pixels_mut() {
            p.0 = std::array::from_fn(|c| fade[c][usize::from(p.0[c])]);
        }
        if worst_contrast(&faded, ink_l, dark_ink) >= CONTRAST_FLOOR {
            return faded;
        }
    }
    let plain = if dark_ink { [255; 3] } else { [0; 3] };
    RgbImage::from_pixel(patch.width(), patch.height(), Rgb(plain))
}

/// The ink's contrast against the patch pixel [`PATCH_QUANTILE`] in from the ink's side.
fn worst_contrast(patch: &RgbImage, ink: f64, dark_ink: bool) -> f64 {
    let mut lums: Vec<f64> = patch.pixels().map(|p| luminance(p.0)).collect();
    let k = ((lums.len() - 1) as f64 * PATCH_QUANTILE) as usize;
    // Dark ink is hurt by the darkest background pixels, light ink by the lightest. Only
    // that one rank is needed: selected, not sorted (the same value a sort puts there).
    let rank = if dark_ink { k } else { lums.len() - 1 - k };
    let near = *lums.select_nth_unstable_by(rank, f64::total_cmp).1;
    contrast(ink, near)
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
    fn primed_patches_keep_the_floor_and_hard_ones_stay_raw() {
        // Brick: dark red courses with light mortar lines, one row in four.
        let brick = RgbImage::from_fn(60, 40, |_, y| {
            Rgb(if y % 4 == 0 {
                [200, 195, 185]
            } else {
                [110, 45, 30]
            })
        });
        let mut rng = crate::rng::stream(3, "text_colours_test", 1);
        let mut primed_some = 0;
        for _ in 0..200 {
            let mean_l = brick.pixels().map(|p| luminance(p.0)).sum::<f64>() / 2400.0;
            let ink = ink_for(&mut rng, mean_l, false);
            let out = primed(brick.clone(), ink, false);
            let dark = luminance(ink) < mean_l;
            assert!(
                worst_contrast(&out, luminance(ink), dark) >= CONTRAST_FLOOR,
                "{ink:?}"
            );
            primed_some += usize::from(out != brick);
            assert_eq!(primed(brick.clone(), ink, true), brick);
        }
        // Light ink on dark brick keeps the raw wall only when the mortar allows it.
        assert!(primed_some > 0);
    }

    #[test]
    fn luminance_spans_black_to_white() {
        assert_eq!(luminance([0; 3]), 0.0);
        assert!((luminance([255; 3]) - 1.0).abs() < 1e-12);
        assert!((contrast(1.0, 0.0) - 21.0).abs() < 1e-12);
    }
}
