//! An OpenStreetMap sign tag → the designs cityspec draws for it ([`designs`]): one
//! plate a code.
//!
//! `traffic_sign=*` holds a country's codes (`DE:206`, `FI:231`), several on one post
//! separated by `;` or `,`, a value in brackets (`DE:274[50]`), or a readable name
//! (`stop`). Each code that names one of our designs (the German StVO's, [`SignKind`])
//! with the same meaning is a plate on the post ([`designs`], in the tag's order):
//! Germany's codes (the designs' own), the Finnish ones of the extract in `assets/osm`
//! (the numbering before 2020, which the extract uses, and the 2020 letters for stop and
//! give way), `stop` and `give_way`.
//! `highway=stop` and `highway=give_way` nodes draw a stop and a give-way sign.
//!
//! Codes without a design of the same meaning are not drawn: a Finnish speed-limit zone
//! (`FI:363`) is a square plate, not the round limit, and a speed limit without a number
//! is left out.

use crate::spec::SignKind;

/// `(code, design)`: a code as the tag writes it, without its country and value.
type Codes = &'static [(&'static str, SignKind)];

/// Germany's Verkehrszeichen (VZ) numbers: the designs follow them.
const DE: Codes = &[
    ("206", SignKind::Stop),
    ("205", SignKind::Yield),
    ("274", SignKind::SpeedLimit),
    ("267", SignKind::NoEntry),
    ("350", SignKind::PedestrianCrossing),
    ("350-10", SignKind::PedestrianCrossing),
    ("350-20", SignKind::PedestrianCrossing),
    ("220", SignKind::OneWay),
    ("220-10", SignKind::OneWay),
    ("220-20", SignKind::OneWay),
    ("286", SignKind::NoParking),
    ("314", SignKind::Parking),
    ("283", SignKind::NoStopping),
    ("276", SignKind::NoOvertaking),
    ("250", SignKind::NoVehicles),
    ("251", SignKind::NoMotorVehicles),
    ("254", SignKind::NoBicycles),
    ("209-20", SignKind::TurnRight),
    ("214", SignKind::StraightOrRight),
    ("237", SignKind::CyclePath),
    ("239", SignKind::Footpath),
    ("240", SignKind::SharedPath),
    ("306", SignKind::PriorityRoad),
    ("301", SignKind::PriorityJunction),
    ("101", SignKind::Danger),
    ("102", SignKind::Crossroads),
    ("103-10", SignKind::BendLeft),
    ("103-20", SignKind::BendRight),
    ("114", SignKind::Slippery),
    ("120", SignKind::RoadNarrows),
    ("123", SignKind::RoadWorks),
    ("131", SignKind::TrafficSignals),
    ("133", SignKind::Pedestrians),
    ("133-10", SignKind::Pedestrians),
    ("133-20", SignKind::Pedestrians),
    ("136", SignKind::Children),
    ("136-10", SignKind::Children),
    ("136-20", SignKind::Children),
    ("138", SignKind::Cyclists),
    ("138-10", SignKind::Cyclists),
    ("138-20", SignKind::Cyclists),
    ("357", SignKind::DeadEnd),
    ("224", SignKind::BusStop),
];

/// Finland's: the numbers of the road traffic decree before 2020 (the extract's), and the
/// 2020 letters of stop and give way.
const FI: Codes = &[
    ("211", SignKind::PriorityRoad),
    ("231", SignKind::Yield),
    ("232", SignKind::Stop),
    ("B5", SignKind::Yield),
    ("B6", SignKind::Stop),
    ("311", SignKind::NoVehicles),
    ("312", SignKind::NoMotorVehicles),
    ("331", SignKind::NoEntry),
    ("361", SignKind::SpeedLimit),
    ("371", SignKind::NoParking),
    ("372", SignKind::NoStopping),
    ("421", SignKind::CyclePath),
    ("422", SignKind::SharedPath),
    ("424", SignKind::Footpath),
    ("511", SignKind::PedestrianCrossing),
    ("521", SignKind::Parking),
    ("551", SignKind::OneWay),
];

/// Readable values, any country.
const NAMES: Codes = &[("stop", SignKind::Stop), ("give_way", SignKind::Yield)];

/// The designs and the numbers on them (a speed limit's; 0 on other signs) that a node's
/// sign tag (`key=value`, as [`crate::model::MapFeature::tag`] holds it) is drawn with:
/// one for each of its codes that has one, in the tag's order (a repeated code too);
/// empty when none has.
pub fn designs(tag: &str) -> Vec<(SignKind, u32)> {
    let Some((key, value)) = tag.split_once('=') else {
        return Vec::new();
    };
    match (key, value) {
        ("highway", "stop") => return vec![(SignKind::Stop, 0)],
        ("highway", "give_way") => return vec![(SignKind::Yield, 0)],
        ("traffic_sign", _) => {}
        _ => return Vec::new(),
    }
    value
        .split([';', ','])
        .filter_map(|code| code_design(code.trim()))
        .collect()
}

/// One code's design: `CC:code[value]` or a readable name.
fn code_design(code: &str) -> Option<(SignKind, u32)> {
    let (code, value) = match code.split_once('[') {
        Some((code, rest)) => (code, rest.strip_suffix(']')),
        None => (code, None),
    };
    let (table, code) = match code.split_once(':') {
        Some(("DE", code)) => (DE, code),
        Some(("FI", code)) => (FI, code),
        Some(_) => return None,
        None => (NAMES, code),
    };
    let kind = table.iter().find(|(c, _)| *c == code)?.1;
    if kind != SignKind::SpeedLimit {
        return Some((kind, 0));
    }
    // A limit is drawn with its number: whole km/h, two or three digits.
    let speed: u32 = value?.trim().parse().ok()?;
    (5..=130).contains(&speed).then_some((kind, speed))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn design(tag: &str) -> Option<(SignKind, u32)> {
        designs(tag).first().copied()
    }

    #[test]
    fn every_code_with_a_design_is_a_plate_in_the_tags_order() {
        assert_eq!(
            designs("traffic_sign=FI:372;FI:8xx;DE:274[50],FI:372"),
            vec![
                (SignKind::NoStopping, 0),
                (SignKind::SpeedLimit, 50),
                (SignKind::NoStopping, 0)
            ]
        );
        assert_eq!(designs("highway=stop"), vec![(SignKind::Stop, 0)]);
    }

    #[test]
    fn the_first_code_with_a_design_draws_the_sign() {
        assert_eq!(design("traffic_sign=DE:206"), Some((SignKind::Stop, 0)));
        assert_eq!(design("traffic_sign=FI:231"), Some((SignKind::Yield, 0)));
        assert_eq!(
            design("traffic_sign=FI:373;FI:372"),
            Some((SignKind::NoStopping, 0))
        );
        assert_eq!(
            design("traffic_sign=DE:1020-30,DE:274[30]"),
            Some((SignKind::SpeedLimit, 30))
        );
        assert_eq!(design("traffic_sign=stop"), Some((SignKind::Stop, 0)));
        assert_eq!(design("highway=give_way"), Some((SignKind::Yield, 0)));
        assert_eq!(
            design("traffic_sign=FI:551[left]"),
            Some((SignKind::OneWay, 0))
        );
    }

    #[test]
    fn codes_without_a_design_of_their_meaning_draw_nothing() {
        // A zone limit, a limit without its number or out of range, an unknown country,
        // a code we have no design for, not a sign at all.
        for tag in [
            "traffic_sign=FI:363[30]",
            "traffic_sign=DE:274",
            "traffic_sign=DE:274[fast]",
            "traffic_sign=DE:274[500]",
            "traffic_sign=GB:601.1",
            "traffic_sign=FI:332",
            "traffic_sign=city_limit",
            "natural=tree",
            "no tag",
        ] {
            assert_eq!(design(tag), None, "{tag}");
        }
    }
}
