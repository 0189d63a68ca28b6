//! What OSM tags say about a road's cross-section, a building's height and a node's
//! furniture, with the defaults cityspec uses where the map is silent (`docs/osm.md`).

use crate::model::FeatureKind;

/// A lane's width where a road gives `lanes` but no `width`, metres.
pub const LANE_WIDTH: f64 = 3.25;
/// A floor's height for `building:levels`, metres.
pub const FLOOR_HEIGHT: f64 = 3.0;
/// A sidewalk's width where the map gives none (`sidewalk:width`), metres.
pub const SIDEWALK_WIDTH: f64 = 2.0;

/// The value of `key` among `tags`.
pub fn get<'a>(tags: &[(&str, &'a str)], key: &str) -> Option<&'a str> {
    tags.iter().find(|(k, _)| *k == key).map(|(_, v)| *v)
}

/// The tallest height, lift or roof rise the reader takes, metres (the tallest building
/// stands 828 m): a taller value is a mapping error, read as not given.
pub const MAX_HEIGHT: f64 = 1000.0;

/// The widest carriageway the reader takes from `width` or `lanes`, metres: a wider value
/// is a mapping error, read as not given.
pub const MAX_ROAD_WIDTH: f64 = 100.0;
/// The widest sidewalk the reader takes from `sidewalk:width`, metres (the same rule).
pub const MAX_SIDEWALK_WIDTH: f64 = 20.0;

/// A height in metres from an OSM value ([`metres`]) up to [`MAX_HEIGHT`].
pub fn height_metres(value: &str) -> Option<f64> {
    metres(value).filter(|h| *h <= MAX_HEIGHT)
}

/// A length in metres from an OSM value: `12`, `12.5 m`, `12m`, `40'`, `40 ft`, `40'6"`.
/// `None` for anything else, or a length that is not positive.
pub fn metres(value: &str) -> Option<f64> {
    let v = value.trim().replace(',', ".");
    let parsed = if let Some((feet, rest)) = v.split_once('\'') {
        let inches = rest.trim().trim_end_matches('"').trim();
        let inches: f64 = if inches.is_empty() {
            0.0
        } else {
            inches.parse().ok()?
        };
        Some(feet.trim().parse::<f64>().ok()? * 0.3048 + inches * 0.0254)
    } else if let Some(feet) = v.strip_suffix("ft") {
        Some(feet.trim().parse::<f64>().ok()? * 0.3048)
    } else {
        v.strip_suffix('m').unwrap_or(&v).trim().parse::<f64>().ok()
    };
    parsed.filter(|m| m.is_finite() && *m > 0.0)
}

/// Highway classes cars drive on.
pub fn drivable(class: &str) -> bool {
    matches!(
        class,
        "motorway"
            | "trunk"
            | "primary"
            | "secondary"
            | "tertiary"
            | "unclassified"
            | "residential"
            | "living_street"
            | "service"
            | "road"
            | "motorway_link"
            | "trunk_link"
            | "primary_link"
            | "secondary_link"
            | "tertiary_link"
    )
}

/// Highway values that are not ways at all (areas, planned or removed roads).
pub fn not_a_way(class: &str) -> bool {
    matches!(
        class,
        "proposed" | "construction" | "abandoned" | "razed" | "platform" | "rest_area" | "services"
    )
}

/// Lanes of a class when the map gives neither `width` nor `lanes`.
fn default_lanes(class: &str) -> f64 {
    match class.trim_end_matches("_link") {
        _ if class.ends_with("_link") => 1.0,
        "motorway" | "trunk" | "primary" => 4.0,
        "secondary" | "tertiary" | "unclassified" | "residential" | "road" => 2.0,
        "living_street" => 1.5,
        "service" => 1.0,
        _ => 0.0,
    }
}

/// Whether a way of highway `class` is a path drawn on the ground it crosses: a footway,
/// path, cycleway, bridleway or track (not steps), not on a bridge (a tunnel or a way
/// below ground the caller leaves out).
pub fn ground_path(class: &str, tags: &[(&str, &str)]) -> bool {
    matches!(
        class,
        "footway" | "path" | "cycleway" | "bridleway" | "track"
    ) && get(tags, "bridge").is_none_or(|b| b == "no")
        && get(tags, "layer")
            .and_then(|l| l.trim().parse::<i32>().ok())
            .is_none_or(|l| l == 0)
}

/// Width of a path that is not a road (footway, cycleway, steps, …), metres.
const PATH_WIDTH: f64 = 2.0;

/// A way's carriageway width and where it came from: `width`, else `lanes` × the lane
/// width, else the class's default lanes (a path's default width for non-roads).
pub fn width(class: &str, tags: &[(&str, &str)]) -> (f64, &'static str) {
    let mapped = get(tags, "width").and_then(metres);
    if let Some(w) = mapped.filter(|w| *w <= MAX_ROAD_WIDTH) {
        return (w, "width");
    }
    let lanes = get(tags, "lanes").and_then(|l| l.trim().parse::<f64>().ok());
    let fits = |l: &f64| l.is_finite() && *l >= 1.0 && l * LANE_WIDTH <= MAX_ROAD_WIDTH;
    if let Some(l) = lanes.filter(fits) {
        return (l * LANE_WIDTH, "lanes");
    }
    let lanes = default_lanes(class);
    if lanes > 0.0 {
        (lanes * LANE_WIDTH, "default")
    } else {
        (PATH_WIDTH, "default")
    }
}

/// Sidewalk widths, left and right of the way's direction: from `sidewalk`,
/// `sidewalk:left|right|both` (`separate` means the map draws it as its own way: none
/// here), the width from `sidewalk:width`; where the map is silent, both sides on
/// residential to primary roads and none elsewhere.
pub fn sidewalks(class: &str, tags: &[(&str, &str)]) -> [f64; 2] {
    let width = get(tags, "sidewalk:width")
        .and_then(metres)
        .filter(|w| *w <= MAX_SIDEWALK_WIDTH)
        .unwrap_or(SIDEWALK_WIDTH);
    let yes = |v: &str| matches!(v, "yes" | "both");
    let side = |key: &str| {
        get(tags, key).map(|v| {
            if yes(v) || v == "left" || v == "right" {
                width
            } else {
                0.0
            }
        })
    };
    let both = get(tags, "sidewalk:both").map(|v| if yes(v) { width } else { 0.0 });
    let (mut left, mut right) = match get(tags, "sidewalk") {
        Some("both" | "yes") => (width, width),
        Some("left") => (width, 0.0),
        Some("right") => (0.0, width),
        Some(_) => (0.0, 0.0),
        None => {
            let urban = matches!(
                class,
                "primary"
                    | "secondary"
                    | "tertiary"
                    | "unclassified"
                    | "residential"
                    | "living_street"
            );
            let w = if urban { width } else { 0.0 };
            (w, w)
        }
    };
    if let Some(b) = both {
        (left, right) = (b, b);
    }
    if let Some(l) = side("sidewalk:left") {
        left = l;
    }
    if let Some(r) = side("sidewalk:right") {
        right = r;
    }
    [left, right]
}

/// Whether cars may park at the left and the right kerb of a way (of its direction), or
/// None where its tags are silent: `parking:lane:{both,left,right}` (`parallel`,
/// `diagonal`, `perpendicular`, `marked`: yes; `no_parking`, `no_stopping`, `no`,
/// `fire_lane`, `separate`: no) or the newer `parking:{both,left,right}` (`lane`,
/// `street_side`, `on_kerb`, `half_on_kerb`, `shoulder`, `yes`: yes; `no`, `separate`:
/// no), a side's own tag over `both`, the older scheme's over the newer's; a
/// `no_parking`, `no_stopping` or `no_standing` under `parking:condition:{side|both}` or
/// `parking:{side|both}:restriction` makes it no.
pub fn parking(tags: &[(&str, &str)]) -> [Option<bool>; 2] {
    let value = |v: &str| match v {
        "parallel" | "diagonal" | "perpendicular" | "marked" | "yes" | "lane" | "street_side"
        | "on_kerb" | "half_on_kerb" | "shoulder" => Some(true),
        "no_parking" | "no_stopping" | "no" | "fire_lane" | "separate" => Some(false),
        _ => None,
    };
    let banned = |v: &str| matches!(v, "no_parking" | "no_stopping" | "no_standing");
    ["left", "right"].map(|side| {
        let of = |scheme: &str| {
            let own = get(tags, &format!("{scheme}:{side}")).and_then(value);
            own.or_else(|| get(tags, &format!("{scheme}:both")).and_then(value))
        };
        let restricted = [
            format!("parking:condition:{side}"),
            "parking:condition:both".to_owned(),
            format!("parking:{side}:restriction"),
            "parking:both:restriction".to_owned(),
        ]
        .iter()
        .any(|k| get(tags, k).is_some_and(banned));
        if restricted {
            return Some(false);
        }
        of("parking:lane").or_else(|| of("parking"))
    })
}

/// A building's height and where it came from: `height`, else (`building:levels` +
/// `roof:levels`) × the floor height.
pub fn height(tags: &[(&str, &str)]) -> (Option<f64>, &'static str) {
    if let Some(h) = get(tags, "height").and_then(height_metres) {
        return (Some(h), "height");
    }
    match levels(tags, "building:levels") {
        Some(l) if l > 0.0 => {
            let roof = levels(tags, "roof:levels").unwrap_or(0.0);
            let h = (l + roof) * FLOOR_HEIGHT;
            match h <= MAX_HEIGHT {
                true => (Some(h), "levels"),
                false => (None, "none"),
            }
        }
        _ => (None, "none"),
    }
}

/// How high above the ground a building's or part's walls start: `min_height`, else
/// `building:min_level` × the floor height; `None` on the ground.
pub fn min_height(tags: &[(&str, &str)]) -> Option<f64> {
    let h = match get(tags, "min_height").and_then(height_metres) {
        Some(h) => h,
        None => levels(tags, "building:min_level")? * FLOOR_HEIGHT,
    };
    (h > 0.0 && h <= MAX_HEIGHT).then_some(h)
}

/// A compass bearing in degrees clockwise from north, in `[0, 360)`, from an OSM value
/// (`roof:direction`): degrees (`135`, `-45`, `22.5`), or one of the sixteen points of the
/// compass (`N`, `NNE`, `NE`, … `NNW`, any case); else `None`.
pub fn bearing(value: &str) -> Option<f64> {
    const POINTS: [&str; 16] = [
        "N", "NNE", "NE", "ENE", "E", "ESE", "SE", "SSE", "S", "SSW", "SW", "WSW", "W", "WNW",
        "NW", "NNW",
    ];
    let value = value.trim();
    if let Some(k) = POINTS.iter().position(|p| p.eq_ignore_ascii_case(value)) {
        return Some(22.5 * k as f64);
    }
    let degrees: f64 = value.parse().ok().filter(|d: &f64| d.is_finite())?;
    Some(degrees.rem_euclid(360.0))
}

/// An OSM colour value (`building:colour`, `roof:colour`): `#rrggbb`, `#rgb`, or one of
/// the CSS colour names mappers use most (the HTML 4 sixteen, and brown, beige, grey,
/// orange, pink, tan, cyan, magenta), any case; else `None`.
pub fn colour(value: &str) -> Option<[u8; 3]> {
    let v = value.trim().to_ascii_lowercase();
    if let Some(hex) = v.strip_prefix('#') {
        let digit = |i: usize, n: usize| u8::from_str_radix(hex.get(i..i + n)?, 16).ok();
        return match hex.len() {
            6 => Some([digit(0, 2)?, digit(2, 2)?, digit(4, 2)?]),
            3 => Some([digit(0, 1)? * 17, digit(1, 1)? * 17, digit(2, 1)? * 17]),
            _ => None,
        };
    }
    Some(match v.as_str() {
        "white" => [255, 255, 255],
        "silver" => [192, 192, 192],
        "gray" | "grey" => [128, 128, 128],
        "black" => [0, 0, 0],
        "red" => [255, 0, 0],
        "maroon" => [128, 0, 0],
        "yellow" => [255, 255, 0],
        "olive" => [128, 128, 0],
        "lime" => [0, 255, 0],
        "green" => [0, 128, 0],
        "aqua" | "cyan" => [0, 255, 255],
        "teal" => [0, 128, 128],
        "blue" => [0, 0, 255],
        "navy" => [0, 0, 128],
        "fuchsia" | "magenta" => [255, 0, 255],
        "purple" => [128, 0, 128],
        "brown" => [165, 42, 42],
        "beige" => [245, 245, 220],
        "orange" => [255, 165, 0],
        "pink" => [255, 192, 203],
        "tan" => [210, 180, 140],
        _ => return None,
    })
}

/// A count of levels under `key`: a finite number, not negative.
fn levels(tags: &[(&str, &str)], key: &str) -> Option<f64> {
    get(tags, key)
        .and_then(|l| l.trim().parse::<f64>().ok())
        .filter(|l| l.is_finite() && *l >= 0.0)
}

/// Whether a closed way's or a multipolygon's tags make it green ground: grass, a park, a
/// garden, woods and the like (`docs/osm.md`). A pitch or a playground is green only when
/// its `surface` is grass or not given (a tennis court or a sandpit is not).
pub fn green(tags: &[(&str, &str)]) -> bool {
    let grassy = matches!(get(tags, "surface"), None | Some("grass"));
    match (
        get(tags, "leisure"),
        get(tags, "landuse"),
        get(tags, "natural"),
    ) {
        (Some("park" | "garden" | "dog_park" | "common" | "nature_reserve"), ..) => true,
        (Some("pitch" | "playground"), ..) => grassy,
        (
            _,
            Some(
                "grass" | "meadow" | "village_green" | "recreation_ground" | "forest" | "cemetery"
                | "allotments" | "flowerbed" | "orchard" | "greenfield" | "plant_nursery",
            ),
            _,
        ) => true,
        (.., Some("wood" | "scrub" | "grassland" | "heath")) => true,
        _ => false,
    }
}

/// Whether a closed way's or a multipolygon's tags make it paved open ground: a square,
/// a pedestrian area, a car park or a market place (`docs/osm.md`).
pub fn square(tags: &[(&str, &str)]) -> bool {
    let area = get(tags, "area") == Some("yes");
    get(tags, "place") == Some("square")
        || (area && matches!(get(tags, "highway"), Some("pedestrian" | "footway")))
        || (matches!(get(tags, "amenity"), Some("parking" | "marketplace"))
            && get(tags, "parking").is_none_or(|p| p == "surface"))
}

/// The furniture a node's tags make, each with the tag that says what it is: its signs,
/// then what its `highway`, `natural` or `amenity` tag makes it (`furniture`). A node may
/// be both: a sign on a lamp post, a stop sign (`highway=stop`, whose stop line the
/// markings draw) with its code.
///
/// A post's signs are `traffic_sign=*` and, for the plates below it, `traffic_sign:2`,
/// `traffic_sign:3`, … (as the Finnish and other mappers tag them): one
/// `traffic_sign=…` tag with their values joined by `;`, top to bottom.
pub fn features(tags: &[(&str, &str)]) -> Vec<(FeatureKind, String)> {
    let mut below: Vec<(u32, &str)> = (tags.iter())
        .filter_map(|(k, v)| {
            let n: u32 = k.strip_prefix("traffic_sign:")?.parse().ok()?;
            (n >= 2).then_some((n, *v))
        })
        .collect();
    below.sort_unstable();
    let codes: Vec<&str> = (get(tags, "traffic_sign").into_iter())
        .chain(below.iter().map(|(_, v)| *v))
        .collect();
    let sign = (!codes.is_empty()).then(|| {
        (
            FeatureKind::TrafficSign,
            format!("traffic_sign={}", codes.join(";")),
        )
    });
    sign.into_iter().chain(furniture(tags)).collect()
}

/// What a node's `highway`, `natural` or `amenity` tag makes it, with the tag that says
/// so; None for anything else.
fn furniture(tags: &[(&str, &str)]) -> Option<(FeatureKind, String)> {
    let tagged = |k: &str, v: &str| format!("{k}={v}");
    match (
        get(tags, "highway"),
        get(tags, "natural"),
        get(tags, "amenity"),
    ) {
        // A signal the map says stops one direction only keeps the tag that says which.
        (Some("traffic_signals"), ..) => Some((
            FeatureKind::TrafficSignals,
            match get(tags, "traffic_signals:direction").or(get(tags, "direction")) {
                Some(way @ ("forward" | "backward")) => tagged(crate::model::SIGNAL_DIRECTION, way),
                _ => tagged("highway", "traffic_signals"),
            },
        )),
        (Some(sign @ ("stop" | "give_way")), ..) => {
            Some((FeatureKind::TrafficSign, tagged("highway", sign)))
        }
        (Some("street_lamp"), ..) => {
            Some((FeatureKind::StreetLamp, tagged("highway", "street_lamp")))
        }
        // A crossing the map says has no markings keeps the tag that says so.
        (Some("crossing"), ..) => Some((
            FeatureKind::Crossing,
            match (get(tags, "crossing"), get(tags, "crossing:markings")) {
                (Some("unmarked"), _) => tagged("crossing", "unmarked"),
                (_, Some("no")) => tagged("crossing:markings", "no"),
                _ => tagged("highway", "crossing"),
            },
        )),
        (_, Some("tree"), _) => Some((FeatureKind::Tree, tagged("natural", "tree"))),
        (.., Some("bench")) => Some((FeatureKind::Bench, tagged("amenity", "bench"))),
        (Some("bench"), ..) => Some((FeatureKind::Bench, tagged("highway", "bench"))),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parking_sides_from_either_scheme_a_side_over_both() {
        assert_eq!(parking(&[("highway", "residential")]), [None, None]);
        assert_eq!(
            parking(&[("parking:lane:both", "parallel")]),
            [Some(true), Some(true)]
        );
        assert_eq!(
            parking(&[
                ("parking:lane:both", "no_stopping"),
                ("parking:lane:right", "diagonal")
            ]),
            [Some(false), Some(true)]
        );
        assert_eq!(
            parking(&[("parking:left", "lane"), ("parking:right", "no")]),
            [Some(true), Some(false)]
        );
        assert_eq!(
            parking(&[("parking:both", "separate")]),
            [Some(false), Some(false)]
        );
        // A lane where a condition or a restriction bans parking: none.
        assert_eq!(
            parking(&[
                ("parking:lane:both", "parallel"),
                ("parking:condition:right", "no_parking")
            ]),
            [Some(true), Some(false)]
        );
        assert_eq!(
            parking(&[
                ("parking:both", "lane"),
                ("parking:both:restriction", "no_stopping")
            ]),
            [Some(false), Some(false)]
        );
        // A value it does not know says nothing.
        assert_eq!(parking(&[("parking:lane:left", "unknown")]), [None, None]);
    }

    #[test]
    fn lengths_read_as_osm_writes_them() {
        assert_eq!(metres("12"), Some(12.0));
        assert_eq!(metres("12.5 m"), Some(12.5));
        assert_eq!(metres("7,5"), Some(7.5));
        assert_eq!(metres("12m"), Some(12.0));
        assert!((metres("40'").unwrap() - 12.192).abs() < 1e-9);
        assert!((metres("40'6\"").unwrap() - 12.3444).abs() < 1e-9);
        assert!((metres("10 ft").unwrap() - 3.048).abs() < 1e-9);
        for bad in ["", "tall", "-3", "0", "NaN", "inf", "3 storeys"] {
            assert_eq!(metres(bad), None, "{bad}");
        }
    }

    #[test]
    fn width_comes_from_width_then_lanes_then_the_class() {
        assert_eq!(width("residential", &[("width", "7.5")]), (7.5, "width"));
        assert_eq!(
            width("residential", &[("lanes", "3")]),
            (3.0 * LANE_WIDTH, "lanes")
        );
        assert_eq!(width("primary", &[]), (4.0 * LANE_WIDTH, "default"));
        assert_eq!(width("primary_link", &[]), (LANE_WIDTH, "default"));
        assert_eq!(width("footway", &[]), (2.0, "default"));
        // A nonsense lanes value falls through to the class.
        assert_eq!(
            width("service", &[("lanes", "many")]),
            (LANE_WIDTH, "default")
        );
        // Past MAX_ROAD_WIDTH: mapping errors, not widths (an extract saying so hung the
        // street surface).
        assert_eq!(
            width("residential", &[("width", "1e30"), ("lanes", "3")]),
            (3.0 * LANE_WIDTH, "lanes")
        );
        assert_eq!(
            width("service", &[("lanes", "1e9")]),
            (LANE_WIDTH, "default")
        );
        assert_eq!(
            sidewalks("residential", &[("sidewalk:width", "1e20")]),
            [SIDEWALK_WIDTH; 2]
        );
    }

    #[test]
    fn sidewalks_follow_the_tags_and_default_by_class() {
        assert_eq!(sidewalks("residential", &[]), [2.0, 2.0]);
        assert_eq!(sidewalks("service", &[]), [0.0, 0.0]);
        assert_eq!(
            sidewalks("residential", &[("sidewalk", "right")]),
            [0.0, 2.0]
        );
        assert_eq!(
            sidewalks("residential", &[("sidewalk", "separate")]),
            [0.0, 0.0]
        );
        assert_eq!(sidewalks("residential", &[("sidewalk", "no")]), [0.0, 0.0]);
        assert_eq!(
            sidewalks(
                "service",
                &[("sidewalk:left", "yes"), ("sidewalk:width", "3")]
            ),
            [3.0, 0.0]
        );
        assert_eq!(
            sidewalks("primary", &[("sidewalk:both", "separate")]),
            [0.0, 0.0]
        );
    }

    #[test]
    fn height_comes_from_height_then_levels() {
        assert_eq!(
            height(&[("height", "21 m"), ("building:levels", "3")]),
            (Some(21.0), "height")
        );
        assert_eq!(
            height(&[("building:levels", "5"), ("roof:levels", "1")]),
            (Some(18.0), "levels")
        );
        assert_eq!(height(&[("building:levels", "0")]), (None, "none"));
        assert_eq!(height(&[("building", "yes")]), (None, "none"));
        // Past MAX_HEIGHT: a mapping error, not a height.
        assert_eq!(height(&[("height", "1e30")]), (None, "none"));
        assert_eq!(height(&[("building:levels", "1e6")]), (None, "none"));
        assert_eq!(min_height(&[("min_height", "1e9")]), None);
        assert_eq!(min_height(&[("building:min_level", "400")]), None);
    }

    #[test]
    fn colours_are_hex_or_css_names() {
        assert_eq!(colour("#cd7f32"), Some([205, 127, 50]));
        assert_eq!(colour(" #99FFFF"), Some([153, 255, 255]));
        assert_eq!(colour("#fa0"), Some([255, 170, 0]));
        assert_eq!(colour("Brown"), Some([165, 42, 42]));
        assert_eq!(colour("grey"), colour("gray"));
        assert_eq!(colour("#12345"), None);
        assert_eq!(colour("#gg0000"), None);
        assert_eq!(colour("sandstone"), None);
    }

    #[test]
    fn min_height_comes_from_min_height_then_min_levels() {
        assert_eq!(
            min_height(&[("min_height", "18"), ("building:min_level", "2")]),
            Some(18.0)
        );
        assert_eq!(min_height(&[("building:min_level", "2.5")]), Some(7.5));
        // On the ground: nothing to lift.
        assert_eq!(min_height(&[("building:min_level", "0")]), None);
        assert_eq!(min_height(&[("min_height", "x")]), None);
        assert_eq!(min_height(&[("height", "12")]), None);
    }

    #[test]
    fn nodes_become_the_furniture_their_tags_name() {
        assert_eq!(
            furniture(&[("highway", "traffic_signals")]).unwrap().0,
            FeatureKind::TrafficSignals
        );
        assert_eq!(
            furniture(&[("highway", "street_lamp")]).unwrap().0,
            FeatureKind::StreetLamp
        );
        assert_eq!(
            furniture(&[("natural", "tree")]).unwrap().0,
            FeatureKind::Tree
        );
        assert_eq!(
            furniture(&[("amenity", "bench")]).unwrap().0,
            FeatureKind::Bench
        );
        assert_eq!(
            features(&[("highway", "give_way"), ("traffic_sign", "DE:205")]),
            vec![
                (FeatureKind::TrafficSign, "traffic_sign=DE:205".to_owned()),
                (FeatureKind::TrafficSign, "highway=give_way".to_owned())
            ]
        );
        // A sign on a lamp post: both.
        assert_eq!(
            features(&[("traffic_sign", "FI:361"), ("highway", "street_lamp")]),
            vec![
                (FeatureKind::TrafficSign, "traffic_sign=FI:361".to_owned()),
                (FeatureKind::StreetLamp, "highway=street_lamp".to_owned())
            ]
        );
        assert_eq!(
            features(&[("traffic_sign", "FI:361")]),
            vec![(FeatureKind::TrafficSign, "traffic_sign=FI:361".to_owned())]
        );
        // The plates below: `traffic_sign:2`, `:3`, … in their order, whatever the tags'.
        let post = [
            ("traffic_sign:10", "FI:372"),
            ("traffic_sign:3", "FI:855a"),
            ("traffic_sign", "FI:371"),
            ("traffic_sign:2", "FI:231;FI:373"),
            ("traffic_sign:1", "FI:511"),
            ("traffic_sign:direction", "forward"),
            ("traffic_sign:x", "FI:332"),
        ];
        assert_eq!(
            features(&post),
            vec![(
                FeatureKind::TrafficSign,
                "traffic_sign=FI:371;FI:231;FI:373;FI:855a;FI:372".to_owned()
            )]
        );
        assert_eq!(
            features(&[("traffic_sign:2", "FI:372")]),
            vec![(FeatureKind::TrafficSign, "traffic_sign=FI:372".to_owned())]
        );
        assert_eq!(
            furniture(&[("highway", "crossing"), ("crossing", "traffic_signals")]),
            Some((FeatureKind::Crossing, "highway=crossing".to_owned()))
        );
        assert_eq!(
            furniture(&[("crossing", "unmarked"), ("highway", "crossing")]),
            Some((FeatureKind::Crossing, "crossing=unmarked".to_owned()))
        );
        assert_eq!(
            furniture(&[("highway", "crossing"), ("crossing:markings", "no")]),
            Some((FeatureKind::Crossing, "crossing:markings=no".to_owned()))
        );
        assert_eq!(
            furniture(&[("highway", "traffic_signals"), ("direction", "backward")]),
            Some((
                FeatureKind::TrafficSignals,
                "traffic_signals:direction=backward".to_owned()
            ))
        );
        assert_eq!(
            furniture(&[
                ("traffic_signals:direction", "forward"),
                ("highway", "traffic_signals")
            ]),
            Some((
                FeatureKind::TrafficSignals,
                "traffic_signals:direction=forward".to_owned()
            ))
        );
        assert_eq!(
            furniture(&[("highway", "traffic_signals"), ("direction", "90")])
                .unwrap()
                .1,
            "highway=traffic_signals"
        );
        assert_eq!(
            furniture(&[("highway", "stop")]),
            Some((FeatureKind::TrafficSign, "highway=stop".to_owned()))
        );
        assert_eq!(features(&[("amenity", "post_box")]), Vec::new());
    }

    #[test]
    fn bearings_read_degrees_and_compass_points() {
        assert_eq!(bearing("135"), Some(135.0));
        assert_eq!(bearing(" 22.5 "), Some(22.5));
        assert_eq!(bearing("-90"), Some(270.0));
        assert_eq!(bearing("720"), Some(0.0));
        assert_eq!(bearing("NNE"), Some(22.5));
        assert_eq!(bearing("sw"), Some(225.0));
        assert_eq!(bearing("W"), Some(270.0));
        for bad in ["", "north", "NaN", "inf", "1e999", "N E"] {
            assert_eq!(bearing(bad), None, "{bad}");
        }
    }
}
