//! CmpLabel: the twelve classes of the CMP Facade Database, by name and mask value.

/// A CMP facade class. The discriminant is the class's value in CMP label masks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum CmpLabel {
    Background = 1,
    Facade = 2,
    Window = 3,
    Door = 4,
    Cornice = 5,
    Sill = 6,
    Balcony = 7,
    Blind = 8,
    Deco = 9,
    Molding = 10,
    Pillar = 11,
    Shop = 12,
}

impl CmpLabel {
    /// Every class, in mask-value order.
    pub const ALL: [CmpLabel; 12] = [
        CmpLabel::Background,
        CmpLabel::Facade,
        CmpLabel::Window,
        CmpLabel::Door,
        CmpLabel::Cornice,
        CmpLabel::Sill,
        CmpLabel::Balcony,
        CmpLabel::Blind,
        CmpLabel::Deco,
        CmpLabel::Molding,
        CmpLabel::Pillar,
        CmpLabel::Shop,
    ];

    /// The `<labelname>` the CMP XML uses for this class.
    pub fn name(self) -> &'static str {
        match self {
            CmpLabel::Background => "background",
            CmpLabel::Facade => "facade",
            CmpLabel::Window => "window",
            CmpLabel::Door => "door",
            CmpLabel::Cornice => "cornice",
            CmpLabel::Sill => "sill",
            CmpLabel::Balcony => "balcony",
            CmpLabel::Blind => "blind",
            CmpLabel::Deco => "deco",
            CmpLabel::Molding => "molding",
            CmpLabel::Pillar => "pillar",
            CmpLabel::Shop => "shop",
        }
    }

    /// The class a `<labelname>` names (trimmed, case-insensitive), if any.
    pub fn from_name(name: &str) -> Option<CmpLabel> {
        let name = name.trim();
        CmpLabel::ALL
            .into_iter()
            .find(|label| label.name().eq_ignore_ascii_case(name))
    }

    /// The value of this class in a CMP label mask (1–12).
    pub fn mask_value(self) -> u8 {
        self as u8
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_mask_values_are_one_to_twelve() {
        for (i, label) in CmpLabel::ALL.into_iter().enumerate() {
            assert_eq!(CmpLabel::from_name(label.name()), Some(label));
            assert_eq!(usize::from(label.mask_value()), i + 1);
        }
        assert_eq!(CmpLabel::from_name(" Window\n"), Some(CmpLabel::Window));
        assert_eq!(CmpLabel::from_name("chimney"), None);
    }
}
