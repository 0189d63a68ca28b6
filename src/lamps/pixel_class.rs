//! RGB pixel + palette → `PixelClass`: which layout element a pixel was drawn as.

use crate::spec::{Palette, PaletteColour};

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
    pub(crate) fn of(rgb: [u8; 3], palette: &Palette) -> PixelClass {
        match palette.classify(rgb) {
            Some(PaletteColour::Road) => PixelClass::Road,
            Some(PaletteColour::Line) => PixelClass::Line,
            Some(PaletteColour::Block) => PixelClass::Block,
            Some(PaletteColour::Strip) => PixelClass::Strip,
            None => PixelClass::Unknown,
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
