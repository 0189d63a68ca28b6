//! Decoded RGB texture → mip chain, sampled trilinearly with wrap = repeat.
//!
//! Texels are stored in linear light as 16-bit integers in units of 2⁻¹⁵ (1.0 = 32768;
//! the finest step is a tenth of 8-bit sRGB's darkest one), four lanes per texel with the
//! fourth zero, so a bilinear tap reads four aligned 8-byte texels and blends all channels
//! at once without a decoding table. Level 0 is the texture's sRGB bytes decoded through
//! the fixed table and rounded. Each further level halves width and height (rounding
//! down, at least 1) and averages 2 × 2 texels in linear light, rounding half up, in
//! integers. Sampling blends in linear; slanted footprints are filtered anisotropically
//! (up to [`MAX_ANISOTROPY`] trilinear taps along their long side). Trilinear blends two
//! levels only across the middle quarter of a level step and reads one level elsewhere
//! ("brilinear"): five eighths of the texel reads, with no band a frame shows (half a
//! step's blend cost 3 % of a street frame and looked the same).

use std::sync::OnceLock;

use image::RgbImage;

use crate::model::geometry::rounding::{floor, round};
use crate::model::srgb::srgb;

/// Most trilinear taps one sample spreads along a slanted footprint (and the largest
/// footprint aspect ratio filtered without blur).
pub(crate) const MAX_ANISOTROPY: f64 = 4.0;

/// Where `taps` anisotropic taps sit along the footprint's long axis (in units of its
/// length, centred on the pixel): `(k + ½) / taps − ½`, per number of taps.
const TAP_OFFSETS: [[f64; 4]; 5] = {
    let mut table = [[0.0; 4]; 5];
    let mut taps = 1;
    while taps < 5 {
        let mut k = 0;
        while k < taps {
            table[taps][k] = (k as f64 + 0.5) / taps as f64 - 0.5;
            k += 1;
        }
        taps += 1;
    }
    table
};

/// Each tap's share of the sample, per number of taps.
const TAP_SHARE: [f32; 5] = [1.0, 1.0, 0.5, 1.0 / 3.0, 0.25];

/// How one pixel's texture sample is filtered ([`MipTexture::footprint`]): how many
/// trilinear taps (1–[`MAX_ANISOTROPY`]), at which level of detail (level-0 texels per
/// pixel, log2; NaN reads level 0), a tap apart along `axis` (uv per pixel).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Footprint {
    taps: u32,
    lod: f64,
    axis: [f64; 2],
}

/// A texture with its mip levels, finest first.
///
/// Level 0 is decoded from the kept sRGB bytes the first time a sample reads it: a view
/// from afar (the overview) reads only coarse levels, and level 0 is three quarters of a
/// chain's memory. Level 1 is halved straight from the sRGB bytes, decoded row by row, so
/// every level holds the same values as when level 0 was made first.
pub(crate) struct MipTexture {
    /// The texture's sRGB bytes, level 0's source.
    source: RgbImage,
    /// Level 0, once a sample has read it.
    base: OnceLock<Level>,
    /// Levels 1 and up.
    coarser: Vec<Level>,
    /// Level 0's size.
    width: u32,
    height: u32,
}

struct Level {
    width: u32,
    height: u32,
    /// Linear RGB in units of 1 / [`ONE`] and a zero lane, row-major.
    texels: Vec<Texel>,
}

/// One texel: linear red, green, blue in units of 1 / [`ONE`], and a zero.
type Texel = [u16; 4];

/// The stored value of linear 1.0: a power of two, so scaling back is exact.
const ONE: f32 = 32768.0;

/// `1 / ONE`, exact.
const PER_UNIT: f32 = 1.0 / ONE;

impl MipTexture {
    /// The mip chain of `image` (an empty image samples as black).
    pub(crate) fn new(image: RgbImage) -> MipTexture {
        let (width, height) = (image.width(), image.height());
        let base = OnceLock::new();
        if width == 0 || height == 0 {
            let _ = base.set(Level {
                width: 1,
                height: 1,
                texels: vec![[0; 4]],
            });
            return MipTexture {
                source: image,
                base,
                coarser: Vec::new(),
                width: 1,
                height: 1,
            };
        }
        let mut coarser: Vec<Level> = Vec::new();
        if width > 1 || height > 1 {
            let table = decode_table();
            let (sw, sh) = (width as usize, height as usize);
            let rows = image.as_raw();
            let decode_row = |y: usize, out: &mut Vec<Texel>| {
                out.clear();
                out.extend(decoded(&table, &rows[y.min(sh - 1) * sw * 3..][..sw * 3]));
            };
            let (mut r0, mut r1) = (Vec::with_capacity(sw), Vec::with_capacity(sw));
            coarser.push(Level::halved(width, height, |y, out_row| {
                decode_row(2 * y, &mut r0);
                decode_row(2 * y + 1, &mut r1);
                halve_row(&r0, &r1, out_row);
            }));
            loop {
                let last = coarser.last().expect("level 1 exists");
                if last.width == 1 && last.height == 1 {
                    break;
                }
                let next = last.halve();
                coarser.push(next);
            }
        }
        MipTexture {
            source: image,
            base,
            coarser,
            width,
            height,
        }
    }

    /// Level `i` (0 is the finest), decoding level 0 on first use.
    #[inline]
    fn level(&self, i: usize) -> &Level {
        if i == 0 {
            self.base.get_or_init(|| Level {
                width: self.width,
                height: self.height,
                texels: decoded(&decode_table(), self.source.as_raw()).collect(),
            })
        } else {
            &self.coarser[i - 1]
        }
    }

    /// The texture's mean linear colour (1.0 = white): its coarsest level's one texel.
    pub(crate) fn mean(&self) -> [f32; 3] {
        let texel = self.level(self.level_count() - 1).texels[0];
        [0, 1, 2].map(|k| f32::from(texel[k]) / ONE)
    }

    /// Number of levels.
    fn level_count(&self) -> usize {
        self.coarser.len() + 1
    }

    /// Linear colour at `(u, v)` (v down; any real value, the texture repeats), filtered
    /// anisotropically from the uv derivatives per screen pixel:
    /// `d = [du/dx, dv/dx, du/dy, dv/dy]` ([`MipTexture::footprint`], then
    /// [`MipTexture::sample_at`]).
    #[cfg(test)]
    pub(crate) fn sample(&self, u: f64, v: f64, d: [f64; 4], max_taps: f64) -> [f32; 3] {
        self.sample_at(u, v, &self.footprint(d, max_taps))
    }

    /// How a pixel with uv derivatives `d = [du/dx, dv/dx, du/dy, dv/dy]` is filtered.
    ///
    /// A pixel's footprint on a wall seen at a slant is long and thin. Choosing the mip
    /// level from its long side (plain trilinear) blurs text across the short side; from its
    /// short side alone it shimmers along the long one. So the level comes from the long
    /// side ÷ the anisotropy (at most `max_taps`, itself at most [`MAX_ANISOTROPY`]), and
    /// that many trilinear taps are spread along the long side and averaged.
    pub(crate) fn footprint(&self, d: [f64; 4], max_taps: f64) -> Footprint {
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        let x2 = (d[0] * w) * (d[0] * w) + (d[1] * h) * (d[1] * h);
        let y2 = (d[2] * w) * (d[2] * w) + (d[3] * h) * (d[3] * h);
        let (major2, minor2, axis) = if x2 >= y2 {
            (x2, y2, [d[0], d[1]])
        } else {
            (y2, x2, [d[2], d[3]])
        };
        if major2.is_nan() {
            // Level 0, one bilinear tap (a NaN level reads level 0).
            return Footprint {
                taps: 1,
                lod: f64::NAN,
                axis,
            };
        }
        // Taps: the footprint's aspect ratio `√(major2 / minor2)`, rounded up, at most
        // `max_taps`; and one texel apart at most: a footprint shorter than that many
        // level-0 texels (a magnified texture, seen from near) reads level 0 with one tap
        // per texel of its length, one under a texel long a single bilinear tap. Found by
        // comparing squares: `k` taps do when `k² ≥ major2 / minor2` or `k² ≥ major2`.
        let cap = max_taps.clamp(1.0, MAX_ANISOTROPY);
        // `ceil(cap)`, for `cap` in 1–4 (NaN gives 0 either way), without the general
        // function's range checks: a sample's longest dependency chain runs through it.
        let whole = cap as u32;
        let most = whole + u32::from(f64::from(whole) < cap);
        let taps = (1..most)
            .find(|&k| {
                let k2 = f64::from(k * k);
                k2 >= major2 || k2 * minor2 >= major2
            })
            .unwrap_or(most);
        let log_major2 = log2_approx(major2);
        if taps <= 1 {
            return Footprint {
                taps: 1,
                lod: 0.5 * log_major2,
                axis,
            };
        }
        // The level of detail: log2 of the long footprint side ÷ the taps' spread, the
        // spread being the aspect ratio (or the length in texels), at most `max_taps`.
        let log_ratio2 = (log_major2 - log2_approx(minor2))
            .min(log_major2)
            .clamp(0.0, log2_approx(cap * cap));
        Footprint {
            taps,
            lod: 0.5 * (log_major2 - log_ratio2),
            axis,
        }
    }

    /// Linear colour at `(u, v)` (v down; any real value, the texture repeats), filtered
    /// over `footprint`: its taps, each trilinear at its level of detail, spread along its
    /// long axis and averaged.
    pub(crate) fn sample_at(&self, u: f64, v: f64, footprint: &Footprint) -> [f32; 3] {
        let Footprint { taps, lod, axis } = *footprint;
        if taps <= 1 {
            return rgb(self.trilinear(u, v, lod));
        }
        let mut sum = [0f32; 4];
        for &t in &TAP_OFFSETS[taps as usize][..taps as usize] {
            let c = self.trilinear(u + t * axis[0], v + t * axis[1], lod);
            for (s, c) in sum.iter_mut().zip(c) {
                *s += c;
            }
        }
        let share = TAP_SHARE[taps as usize];
        rgb(sum.map(|s| s * share))
    }

    /// Trilinear sample at level of detail `lod` (level-0 texels per pixel, log2), with
    /// the zero lane.
    fn trilinear(&self, u: f64, v: f64, lod: f64) -> [f32; 4] {
        let top = (self.level_count() - 1) as f64;
        if lod.is_nan() || lod <= 0.0 {
            return self.level(0).bilinear(u, v);
        }
        if lod >= top {
            return self.level(self.level_count() - 1).bilinear(u, v);
        }
        let base = floor(lod);
        let i = base as usize;
        // Blended only across the middle quarter of a level step; the outer three eighths
        // on each side read one level.
        let t = ((lod - base) as f32 - 0.375) * 4.0;
        if t <= 0.0 {
            return self.level(i).bilinear(u, v);
        }
        if t >= 1.0 {
            return self.level(i + 1).bilinear(u, v);
        }
        let a = self.level(i).bilinear(u, v);
        let b = self.level(i + 1).bilinear(u, v);
        std::array::from_fn(|c| a[c] + (b[c] - a[c]) * t)
    }
}

impl Level {
    /// The next level: half the width and height (rounding down, at least 1).
    fn halve(&self) -> Level {
        let (sw, sh) = (self.width as usize, self.height as usize);
        let row = |y: usize| &self.texels[y.min(sh - 1) * sw..][..sw];
        Level::halved(self.width, self.height, |y, out_row| {
            halve_row(row(2 * y), row(2 * y + 1), out_row);
        })
    }

    /// The level half the size of a `width` × `height` one, each of its rows filled by
    /// `fill(y, row)`.
    fn halved(width: u32, height: u32, mut fill: impl FnMut(usize, &mut [Texel])) -> Level {
        let width = (width / 2).max(1);
        let height = (height / 2).max(1);
        let mut texels = vec![[0u16; 4]; width as usize * height as usize];
        for (y, out_row) in texels.chunks_exact_mut(width as usize).enumerate() {
            fill(y, out_row);
        }
        Level {
            width,
            height,
            texels,
        }
    }

    /// Bilinear sample at texel centres `+0.5`, wrapping at both edges.
    #[inline]
    fn bilinear(&self, u: f64, v: f64) -> [f32; 4] {
        let (w, h) = (i64::from(self.width), i64::from(self.height));
        let tx = u * w as f64 - 0.5;
        let ty = v * h as f64 - 0.5;
        let (ix, ax) = floor_split(tx);
        let (iy, ay) = floor_split(ty);
        let x0 = wrap(ix, w);
        let y0 = wrap(iy, h);
        let x1 = if x0 + 1 == w { 0 } else { x0 + 1 };
        let y1 = if y0 + 1 == h { 0 } else { y0 + 1 };
        let row0 = (y0 * w) as usize;
        let row1 = (y1 * w) as usize;
        // Whole texels, all four lanes at once (the hottest function of a frame).
        let at = |row: usize, x: i64| -> [f32; 4] { self.texels[row + x as usize].map(f32::from) };
        let (p00, p10, p01, p11) = (at(row0, x0), at(row0, x1), at(row1, x0), at(row1, x1));
        std::array::from_fn(|c| {
            let top = p00[c] + (p10[c] - p00[c]) * ax;
            let bottom = p01[c] + (p11[c] - p01[c]) * ax;
            (top + (bottom - top) * ay) * PER_UNIT
        })
    }
}

/// sRGB byte → stored linear value.
fn decode_table() -> [u16; 256] {
    let table = srgb();
    std::array::from_fn(|s| round(f64::from(table.to_linear(s as u8) * ONE)) as u16)
}

/// The texels of sRGB bytes `rgb` (three per texel), through `table`.
fn decoded<'a>(table: &'a [u16; 256], rgb: &'a [u8]) -> impl Iterator<Item = Texel> + 'a {
    let (texels, _) = rgb.as_chunks::<3>();
    texels.iter().map(|&[r, g, b]| {
        [
            table[usize::from(r)],
            table[usize::from(g)],
            table[usize::from(b)],
            0,
        ]
    })
}

/// One row of the next level from two source rows (the same row twice at an odd
/// height's end): each output texel averages 2 × 2 source texels, rounding half up, the
/// last column repeated at an odd width's end.
fn halve_row(r0: &[Texel], r1: &[Texel], out_row: &mut [Texel]) {
    let last = r0.len() - 1;
    for (x, out) in out_row.iter_mut().enumerate() {
        let x0 = (2 * x).min(last);
        let x1 = (2 * x + 1).min(last);
        *out = std::array::from_fn(|c| {
            let sum = u32::from(r0[x0][c])
                + u32::from(r0[x1][c])
                + u32::from(r1[x0][c])
                + u32::from(r1[x1][c]);
            ((sum + 2) / 4) as u16
        });
    }
}

/// The colour lanes of a four-lane sample.
#[inline]
fn rgb(c: [f32; 4]) -> [f32; 3] {
    [c[0], c[1], c[2]]
}

/// `(floor(t) as i64, (t − floor(t)) as f32)` in one conversion: the texel and the
/// fraction past it. The same values as through [`floor`] wherever `|t| < 2^63` (`as i64`
/// saturates beyond; a texel is wrapped into the texture anyway), NaN giving texel 0 and a
/// NaN fraction as before.
#[inline]
fn floor_split(t: f64) -> (i64, f32) {
    let i = t as i64;
    // Truncation rounds toward zero: one less for negative fractions. `i as f64` is exact
    // wherever `t` has a fraction (|t| < 2^52).
    let i = if i as f64 > t { i.saturating_sub(1) } else { i };
    (i, (t - i as f64) as f32)
}

/// `i.rem_euclid(n)`, without the division for the usual case of `i` already in range or
/// one texture repeat outside it.
#[inline]
fn wrap(i: i64, n: i64) -> i64 {
    if (0..n).contains(&i) {
        i
    } else if (-n..0).contains(&i) {
        i + n
    } else {
        i.rem_euclid(n)
    }
}

/// log2 of a positive number from its exponent bits and a quadratic in the mantissa
/// (exact at powers of two, continuous, within 0.03 elsewhere); −∞-like for 0 and below.
pub(crate) fn log2_approx(x: f64) -> f64 {
    if x.is_nan() || x <= 0.0 {
        return -1.0e9;
    }
    if x.is_infinite() {
        return 1.0e9;
    }
    let bits = x.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as i64 - 1023;
    let mantissa = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    let t = mantissa - 1.0;
    exponent as f64 + t * (4.0 / 3.0 - t / 3.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Rgb;

    fn checker(size: u32, cell: u32) -> RgbImage {
        RgbImage::from_fn(size, size, |x, y| {
            if (x / cell + y / cell).is_multiple_of(2) {
                Rgb([255, 255, 255])
            } else {
                Rgb([0, 0, 0])
            }
        })
    }

    /// Vertical stripes one texel wide, white on the even columns, 64 × 64.
    fn stripes() -> RgbImage {
        RgbImage::from_fn(64, 64, |x, _| {
            if x % 2 == 0 {
                Rgb([255; 3])
            } else {
                Rgb([0; 3])
            }
        })
    }

    #[test]
    #[allow(clippy::disallowed_methods)] // compares with the platform's log2
    fn log2_is_exact_at_powers_of_two_and_close_between() {
        for (x, expected) in [(1.0, 0.0), (2.0, 1.0), (0.25, -2.0), (1024.0, 10.0)] {
            assert_eq!(log2_approx(x), expected);
        }
        for x in [1.5f64, 3.0, 0.7, 100.0] {
            assert!((log2_approx(x) - x.log2()).abs() < 0.03, "{x}");
        }
        assert!(log2_approx(0.0) < -1.0e8);
    }

    #[test]
    fn chain_halves_down_to_one_texel_and_averages_in_linear() {
        let t = MipTexture::new(checker(4, 1));
        assert_eq!(t.level_count(), 3);
        // Half white, half black in linear light is 0.5 (sRGB 188, not 128).
        assert_eq!(t.level(2).texels, vec![[16384, 16384, 16384, 0]]);
        assert_eq!(t.level(0).texels[..2], [[32768, 32768, 32768, 0], [0; 4]]);
        let odd = MipTexture::new(RgbImage::new(5, 3));
        let sizes: Vec<_> = (0..odd.level_count())
            .map(|i| (odd.level(i).width, odd.level(i).height))
            .collect();
        assert_eq!(sizes, vec![(5, 3), (2, 1), (1, 1)]);
    }

    /// Level 1, halved from the sRGB bytes before level 0 exists, holds what halving the
    /// decoded level 0 gives, for even and odd sizes, and level 0 is made only when read.
    #[test]
    fn level_one_from_srgb_bytes_is_level_zero_halved() {
        for (w, h) in [(8, 6), (7, 5), (1, 9), (9, 1), (2, 2)] {
            let image = RgbImage::from_fn(w, h, |x, y| {
                Rgb([
                    (x * 37 + y * 11) as u8,
                    (x * y * 5) as u8,
                    (255 - x * 3) as u8,
                ])
            });
            let t = MipTexture::new(image);
            assert!(t.base.get().is_none(), "{w} × {h}");
            assert_eq!(t.level(0).halve().texels, t.level(1).texels, "{w} × {h}");
            assert!(t.base.get().is_some());
        }
        let empty = MipTexture::new(RgbImage::new(0, 4));
        assert_eq!(
            (empty.level_count(), &empty.level(0).texels),
            (1, &vec![[0; 4]])
        );
    }

    #[test]
    fn magnified_samples_hit_texels_and_repeat() {
        let t = MipTexture::new(checker(2, 1));
        let still = [0.0; 4];
        // Texel centres of the 2 × 2 checker, also one repeat away and below zero.
        for (u, v, white) in [
            (0.25, 0.25, true),
            (0.75, 0.25, false),
            (1.25, 0.25, true),
            (-0.25, 0.25, false),
            (0.75, -1.25, true),
        ] {
            let c = t.sample(u, v, still, MAX_ANISOTROPY);
            assert_eq!(c, if white { [1.0; 3] } else { [0.0; 3] }, "({u}, {v})");
        }
    }

    #[test]
    fn slanted_footprints_keep_detail_across_their_short_side() {
        // Vertical stripes one texel wide, 64 texels: a footprint 4 texels long along the
        // stripes and 1 across still resolves the stripes (level 0); plain trilinear from
        // the long side would read level 2, flat grey.
        let t = MipTexture::new(stripes());
        let texel = 1.0 / 64.0;
        let white = t.sample(
            0.5 * texel,
            0.5,
            [texel, 0.0, 0.0, 4.0 * texel],
            MAX_ANISOTROPY,
        );
        let black = t.sample(
            1.5 * texel,
            0.5,
            [texel, 0.0, 0.0, 4.0 * texel],
            MAX_ANISOTROPY,
        );
        assert!(white[0] > 0.99 && black[0] < 0.01, "{white:?} {black:?}");
    }

    #[test]
    fn large_footprints_read_coarse_levels() {
        let t = MipTexture::new(checker(64, 1));
        // One screen pixel spans 64 texels: the 1 × 1 level, grey.
        let c = t.sample(0.3, 0.6, [1.0, 0.0, 0.0, 1.0], MAX_ANISOTROPY);
        assert_eq!(c, [0.5; 3]);
        // Half a texel per pixel: level 0, a pure texel at its centre.
        let c = t.sample(
            0.5 / 64.0,
            0.5 / 64.0,
            [0.5 / 64.0, 0.0, 0.0, 0.5 / 64.0],
            MAX_ANISOTROPY,
        );
        assert_eq!(c, [1.0; 3]);
    }

    #[test]
    fn levels_blend_only_across_the_middle_half_of_a_step() {
        // A checker of single texels: level 0 is white at this texel, level 1 grey.
        let t = MipTexture::new(checker(64, 1));
        let (u, v) = (0.5 / 64.0, 0.5 / 64.0);
        let (fine, coarse) = (t.trilinear(u, v, 0.0), t.trilinear(u, v, 1.0));
        assert_ne!(fine, coarse);
        // The outer quarters of the step read one level; its middle is their mean.
        assert_eq!(t.trilinear(u, v, 0.2), fine);
        assert_eq!(t.trilinear(u, v, 0.8), coarse);
        let mid = t.trilinear(u, v, 0.5);
        assert!(
            (mid[0] - 0.5 * (fine[0] + coarse[0])).abs() < 1e-6,
            "{mid:?}"
        );
    }

    #[test]
    fn fewer_taps_read_a_coarser_level_along_the_short_side() {
        // The stripes of `slanted_footprints_keep_detail…` under a footprint 4 texels long
        // and 1 across: 4 taps resolve them (level 0); 2 taps read level 1, where a
        // stripe pair is one grey texel.
        let t = MipTexture::new(stripes());
        let texel = 1.0 / 64.0;
        let d = [texel, 0.0, 0.0, 4.0 * texel];
        let four = t.sample(0.5 * texel, 0.5, d, 4.0);
        let two = t.sample(0.5 * texel, 0.5, d, 2.0);
        assert!(four[0] > 0.99, "{four:?}");
        assert!((0.3..0.7).contains(&two[0]), "{two:?}");
        // More than MAX_ANISOTROPY asks for no more than it.
        assert_eq!(t.sample(0.5 * texel, 0.5, d, 16.0), four);
    }

    #[test]
    fn magnified_footprints_take_one_tap_per_texel_of_their_length() {
        // Horizontal stripes (a copy of `stripes()` turned): rows alternate white and
        // black. A footprint 8:1 but only 0.8 texel long is one bilinear tap at the
        // centre: a white row's centre stays pure white. Spread over 4 taps, as before,
        // its outer taps reached 0.3 texel into the black rows beside it.
        let rows = RgbImage::from_fn(64, 64, |_, y| Rgb([if y % 2 == 0 { 255 } else { 0 }; 3]));
        let t = MipTexture::new(rows);
        let texel = 1.0 / 64.0;
        let (u, v) = (0.5, 0.5 * texel);
        let short = [0.1 * texel, 0.0, 0.0, 0.8 * texel];
        assert_eq!(t.sample(u, v, short, MAX_ANISOTROPY), [1.0; 3]);
        assert_eq!(
            t.sample(u, v, short, MAX_ANISOTROPY),
            rgb(t.trilinear(u, v, -1.0))
        );
        // 2.5 texels long: 3 taps at level 0, a texel apart (rows −1, 0, +1 of 5 in
        // 6ths): the mean of white, black, white's neighbourhood, neither pure colour.
        let longer = [0.1 * texel, 0.0, 0.0, 2.5 * texel];
        let c = t.sample(u, v, longer, MAX_ANISOTROPY);
        assert!(c[0] > 0.2 && c[0] < 0.9, "{c:?}");
    }

    #[test]
    fn floor_split_is_floor_and_fraction() {
        for t in [
            0.0,
            0.25,
            -0.25,
            3.0,
            -3.0,
            -3.5,
            7.75,
            1e15 + 0.5,
            -1e15 - 0.5,
        ] {
            let (i, f) = floor_split(t);
            assert_eq!((i, f), (floor(t) as i64, (t - floor(t)) as f32), "{t}");
        }
        let (i, f) = floor_split(f64::NAN);
        assert!(i == 0 && f.is_nan());
    }
}
