//! RGB pixel + palette → `PixelClass`: which layout element a pixel was drawn as.

use crate::spec::Palette;

/// The layout element a pixel shows, by nearest palette colour within the tolerance.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PixelClass {
    Road,
    Line,
    Block,
    Strip,
    /// Farther than `tolerance` from every palette colour.
    Unknown,
}

impl PixelClass {
    /// The nearest palette colour (Euclidean RGB distance) if it lies within
    /// `palette.tolerance`; on a tie the earlier of road, line, block, strip wins.
    pub(crate) fn of(rgb: [u8; 3], palette: &Palette) -> PixelClass {
        let candidates = [
            (palette.road.0, PixelClass::Road),
            (palette.line.0, PixelClass::Line),
            (palette.block.0, PixelClass::Block),
            (palette.strip.0, PixelClass::Strip),
        ];
        let distance2 = |c: [u8; 3]| -> u32 {
            (0..3)
                .map(|i| (i32::from(rgb[i]) - i32::from(c[i])).pow(2) as u32)
                .sum()
        };
        let mut best = (u32::MAX, PixelClass::Unknown);
        for (colour, class) in candidates {
            let d = distance2(colour);
            if d < best.0 {
                best = (d, class);
            }
        }
        let tolerance = u64::from(palette.tolerance);
        if u64::from(best.0) <= tolerance * tolerance {
            best.1
        } else {
            PixelClass::Unknown
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classifies_by_nearest_colour_within_tolerance() {
        let palette = Palette::default();
        let cases = [
            ([128, 128, 128], PixelClass::Road),
            ([255, 220, 0], PixelClass::Line),
            ([40, 80, 220], PixelClass::Block),
            ([40, 170, 60], PixelClass::Strip),
            ([50, 160, 70], PixelClass::Strip), // JPEG-ish noise
            ([255, 255, 255], PixelClass::Unknown),
            ([0, 0, 0], PixelClass::Unknown),
        ];
        for (rgb, want) in cases {
            assert_eq!(PixelClass::of(rgb, &palette), want, "{rgb:?}");
        }
        let strict = Palette {
            tolerance: 0,
            ..Palette::default()
        };
        assert_eq!(PixelClass::of([41, 170, 60], &strict), PixelClass::Unknown);
        assert_eq!(PixelClass::of([40, 170, 60], &strict), PixelClass::Strip);
    }
}
