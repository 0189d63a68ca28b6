//! The fonts text objects are drawn in: eight OFL/Apache faces of clearly different styles,
//! embedded in the binary (`assets/fonts/<family>/`, each beside its licence), parsed once.
//!
//! A detector trained on one typeface learns that typeface. Real street text mixes serif
//! shop names, condensed and bold display lettering, monospace numbers and hand-painted
//! scripts, so every plate draws its face from this list.

use std::sync::LazyLock;

use ab_glyph::FontRef;

/// One embedded typeface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum TextFont {
    /// EB Garamond 12 Regular: an old-style serif (OFL).
    Serif,
    /// Liberation Sans Bold: a grotesque sans (OFL).
    Sans,
    /// Noto Sans Condensed Bold (OFL).
    Condensed,
    /// Fira Code Medium: monospace (OFL).
    Mono,
    /// League Spartan Bold: a geometric bold display face (OFL).
    Display,
    /// Comic Neue Bold: handwriting-like (OFL).
    Hand,
    /// Lobster: a bold connected script (OFL).
    Script,
    /// Roboto Slab Bold: a slab serif (Apache-2.0).
    Slab,
}

impl TextFont {
    /// Every face, in a fixed order (plates draw an index into it).
    pub const ALL: [TextFont; 8] = [
        TextFont::Serif,
        TextFont::Sans,
        TextFont::Condensed,
        TextFont::Mono,
        TextFont::Display,
        TextFont::Hand,
        TextFont::Script,
        TextFont::Slab,
    ];

    /// Short name, as recorded in the annotations (`text_font`).
    pub fn name(self) -> &'static str {
        match self {
            TextFont::Serif => "serif",
            TextFont::Sans => "sans",
            TextFont::Condensed => "condensed",
            TextFont::Mono => "mono",
            TextFont::Display => "display",
            TextFont::Hand => "hand",
            TextFont::Script => "script",
            TextFont::Slab => "slab",
        }
    }

    /// The parsed face.
    pub fn face(self) -> &'static FontRef<'static> {
        &FACES[self as usize]
    }

    fn bytes(self) -> &'static [u8] {
        match self {
            TextFont::Serif => {
                include_bytes!("../../assets/fonts/ebgaramond/EBGaramond12-Regular.otf")
            }
            TextFont::Sans => {
                include_bytes!("../../assets/fonts/liberation/LiberationSans-Bold.ttf")
            }
            TextFont::Condensed => {
                include_bytes!("../../assets/fonts/noto-condensed/NotoSans-CondensedBold.ttf")
            }
            TextFont::Mono => include_bytes!("../../assets/fonts/firacode/FiraCode-Medium.ttf"),
            TextFont::Display => {
                include_bytes!("../../assets/fonts/league-spartan/LeagueSpartan-Bold.otf")
            }
            TextFont::Hand => include_bytes!("../../assets/fonts/comic-neue/ComicNeue-Bold.otf"),
            TextFont::Script => include_bytes!("../../assets/fonts/lobster/lobster.otf"),
            TextFont::Slab => {
                include_bytes!("../../assets/fonts/roboto-slab/RobotoSlab-Bold.otf")
            }
        }
    }
}

static FACES: LazyLock<Vec<FontRef<'static>>> = LazyLock::new(|| {
    TextFont::ALL
        .iter()
        .map(|f| FontRef::try_from_slice(f.bytes()).expect("every embedded font parses"))
        .collect()
});

#[cfg(test)]
mod tests {
    use ab_glyph::Font;

    use super::*;

    #[test]
    fn every_face_parses_and_draws_every_ascii_letter() {
        for font in TextFont::ALL {
            let face = font.face();
            for c in ('a'..='z').chain('A'..='Z') {
                let id = face.glyph_id(c);
                assert_ne!(id.0, 0, "{} lacks {c}", font.name());
            }
            assert_eq!(TextFont::ALL[font as usize], font);
        }
    }
}
