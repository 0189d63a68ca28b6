//! The reader against hand-made extracts (every rule on a few elements) and the committed
//! cut of Helsinki in both formats.

use super::*;
use crate::model::{FeatureKind, OsmElement};

/// A block of a made-up town near 60° N: a building way with a height, a multipolygon
/// building with a courtyard, a road that leaves the box, a footway, a pedestrian area,
/// an open building way, a way naming a missing node, and furniture.
const TOWN: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<osm version="0.6">
  <bounds minlat="60.0000000" minlon="25.0000000" maxlat="60.0010000" maxlon="25.0020000"/>
  <node id="1" lat="60.0002" lon="25.0002"/>
  <node id="2" lat="60.0002" lon="25.0004"/>
  <node id="3" lat="60.0004" lon="25.0004"/>
  <node id="4" lat="60.0004" lon="25.0002"/>
  <node id="11" lat="60.0005" lon="25.0010"/>
  <node id="12" lat="60.0005" lon="25.0016"/>
  <node id="13" lat="60.0009" lon="25.0016"/>
  <node id="14" lat="60.0009" lon="25.0010"/>
  <node id="21" lat="60.0006" lon="25.0012"/>
  <node id="22" lat="60.0006" lon="25.0014"/>
  <node id="23" lat="60.0008" lon="25.0014"/>
  <node id="24" lat="60.0008" lon="25.0012"/>
  <node id="31" lat="60.0001" lon="25.0000"/>
  <node id="32" lat="60.0001" lon="25.0010"/>
  <node id="33" lat="60.0001" lon="25.0030"><tag k="highway" v="traffic_signals"/></node>
  <node id="41" lat="60.0003" lon="25.0006"><tag k="natural" v="tree"/></node>
  <node id="42" lat="60.0003" lon="25.0007"><tag k="highway" v="street_lamp"/></node>
  <node id="43" lat="60.0003" lon="25.0008"><tag k="amenity" v="bench"/></node>
  <node id="44" lat="60.0003" lon="25.0009"><tag k="traffic_sign" v="FI:C32"/></node>
  <node id="45" lat="60.0001" lon="25.0005"><tag k="highway" v="crossing"/></node>
  <node id="46" lat="60.0020" lon="25.0005"><tag k="natural" v="tree"/></node>
  <way id="100">
    <nd ref="1"/><nd ref="2"/><nd ref="3"/><nd ref="4"/><nd ref="1"/>
    <tag k="building" v="apartments"/><tag k="height" v="18 m"/><tag k="roof:shape" v="gabled"/><tag k="roof:height" v="4,5"/>
  </way>
  <way id="101"><nd ref="11"/><nd ref="12"/><nd ref="13"/></way>
  <way id="102"><nd ref="13"/><nd ref="14"/><nd ref="11"/></way>
  <way id="103"><nd ref="21"/><nd ref="22"/><nd ref="23"/><nd ref="24"/><nd ref="21"/></way>
  <way id="104"><nd ref="1"/><nd ref="2"/><nd ref="3"/><tag k="building" v="yes"/></way>
  <way id="200">
    <nd ref="31"/><nd ref="32"/><nd ref="33"/>
    <tag k="highway" v="residential"/><tag k="lanes" v="2"/><tag k="name" v="Testikatu"/>
    <tag k="sidewalk" v="right"/><tag k="parking:lane:right" v="parallel"/>
    <tag k="parking:lane:left" v="no_stopping"/>
  </way>
  <way id="201"><nd ref="1"/><nd ref="4"/><tag k="highway" v="footway"/></way>
  <way id="202">
    <nd ref="1"/><nd ref="2"/><nd ref="3"/><nd ref="1"/>
    <tag k="highway" v="pedestrian"/><tag k="area" v="yes"/>
  </way>
  <way id="203"><nd ref="1"/><nd ref="999"/><tag k="highway" v="service"/></way>
  <relation id="300">
    <member type="way" ref="101" role="outer"/>
    <member type="way" ref="102" role="outer"/>
    <member type="way" ref="103" role="inner"/>
    <tag k="type" v="multipolygon"/><tag k="building" v="yes"/><tag k="building:levels" v="4"/>
  </relation>
  <relation id="301">
    <member type="way" ref="101" role="outer"/>
    <member type="way" ref="777" role="outer"/>
    <tag k="type" v="multipolygon"/><tag k="building" v="yes"/>
  </relation>
</osm>
"#;

fn town() -> OsmMap {
    read(TOWN.as_bytes(), None).unwrap()
}

#[test]
fn buildings_are_their_rings_with_courtyards_and_heights() {
    let map = town();
    let p = Projection::new(60.0005, 25.001);
    let [dx, dz] = p.metres_per_degree;
    let keys: Vec<_> = map.buildings.iter().map(|b| (b.element, b.part)).collect();
    assert_eq!(
        keys,
        [(OsmElement::Way(100), 0), (OsmElement::Relation(300), 0)]
    );
    let way = &map.buildings[0];
    // 0.0002° × 0.0002°, to the projection's arithmetic.
    assert!(
        (way.area - 0.0002 * dx * 0.0002 * dz).abs() < 1e-6,
        "{}",
        way.area
    );
    assert_eq!(way.outer.len(), 4);
    assert_eq!(
        (way.height, way.height_from.as_str()),
        (Some(18.0), "height")
    );
    assert_eq!(way.roof_shape.as_deref(), Some("gabled"));
    assert_eq!(way.roof_height, Some(4.5));
    assert_eq!(way.kind, "apartments");
    let rel = &map.buildings[1];
    assert_eq!(rel.holes.len(), 1);
    let expected = (0.0006 * 0.0004 - 0.0002 * 0.0002) * dx * dz;
    assert!(
        (rel.area - expected).abs() < 1e-6,
        "{} {expected}",
        rel.area
    );
    assert!(
        crate::model::geometry::polygon::signed_area(&rel.outer) > 0.0
            && crate::model::geometry::polygon::signed_area(&rel.holes[0]) < 0.0
    );
    assert_eq!(
        (rel.height, rel.height_from.as_str()),
        (Some(4.0 * FLOOR_HEIGHT), "levels")
    );
    // The open way 104 and the relation naming the missing way 777.
    assert_eq!(map.left_out.buildings_open, 1);
    assert_eq!(map.left_out.buildings_incomplete, 1);
}

#[test]
fn roads_are_cut_at_the_box_and_areas_are_not_roads() {
    let map = town();
    let ids: Vec<_> = map.roads.iter().map(|r| (r.way, r.piece)).collect();
    // 202 is a pedestrian area; 203 names node 999, which the file lacks.
    assert_eq!(ids, [(200, 0), (201, 0)]);
    assert_eq!(map.left_out.ways_missing_nodes, 1);
    let road = &map.roads[0];
    assert!(road.clipped && road.drivable);
    assert_eq!(road.name.as_deref(), Some("Testikatu"));
    assert_eq!(
        (road.width, road.width_from.as_str()),
        (2.0 * LANE_WIDTH, "lanes")
    );
    assert_eq!(road.sidewalks, [0.0, SIDEWALK_WIDTH]);
    assert_eq!(road.parking, [Some(false), Some(true)]);
    assert_eq!(
        map.roads[1].parking,
        [None, None],
        "the footway says nothing"
    );
    // From the box's west edge (25.000°) to its east edge (25.002°) along 60.0001° N.
    let last = *road.centreline.last().unwrap();
    assert!(
        (last[0] - map.extent[2]).abs() < 1e-9,
        "{last:?} {:?}",
        map.extent
    );
    let degree = map.metres_per_degree[0];
    assert!(
        (road.length - 0.002 * degree).abs() < 1e-6,
        "{}",
        road.length
    );
    let footway = &map.roads[1];
    assert!(!footway.drivable && !footway.clipped);
}

#[test]
fn furniture_is_the_nodes_tags_inside_the_box() {
    let kinds: Vec<_> = town().features.iter().map(|f| (f.node, f.kind)).collect();
    // 33 (signals) and 46 (a tree) lie outside the box.
    assert_eq!(
        kinds,
        [
            (41, FeatureKind::Tree),
            (42, FeatureKind::StreetLamp),
            (43, FeatureKind::Bench),
            (44, FeatureKind::TrafficSign),
            (45, FeatureKind::Crossing),
        ]
    );
}

#[test]
fn element_order_does_not_change_the_map() {
    // Ways and relations first, nodes last (as a hand-edited file may have them).
    let lines: Vec<&str> = TOWN.lines().collect();
    let nodes: Vec<&str> = lines
        .iter()
        .copied()
        .filter(|l| l.trim_start().starts_with("<node"))
        .collect();
    let rest: Vec<&str> = lines
        .iter()
        .copied()
        .filter(|l| !l.trim_start().starts_with("<node"))
        .collect();
    let closing = rest.len() - 1; // before `</osm>`
    let mut shuffled: Vec<&str> = rest[..closing].to_vec();
    shuffled.extend(nodes.iter().rev());
    shuffled.extend(&rest[closing..]);
    let text = shuffled.join("\n");
    assert_eq!(read(text.as_bytes(), None).unwrap(), town());
}

#[test]
fn a_box_keeps_what_lies_inside_it() {
    // The west half of the town: building 100 stays, relation 300 (east) goes.
    let west = GeoBox {
        south: 60.0,
        west: 25.0,
        north: 60.001,
        east: 25.0008,
    };
    let map = read(TOWN.as_bytes(), Some(west)).unwrap();
    assert_eq!(map.buildings.len(), 1);
    assert_eq!(map.left_out.buildings_outside, 1);
    assert_eq!(map.bounds, west);
    for road in &map.roads {
        for &[x, z] in &road.centreline {
            assert!(
                x >= map.extent[0] - 1e-9 && x <= map.extent[2] + 1e-9,
                "{x}"
            );
            assert!(
                z >= map.extent[1] - 1e-9 && z <= map.extent[3] + 1e-9,
                "{z}"
            );
        }
    }
}

#[test]
fn pbf_and_xml_of_one_cut_give_the_same_map() {
    // tests/fixtures/osm: a few blocks of Kamppi, Helsinki, written by
    // tests/external/osm_cut.py in both formats (© OpenStreetMap contributors, ODbL).
    let xml = read(include_bytes!("../../tests/fixtures/osm/kamppi.osm"), None).unwrap();
    let pbf = read(
        include_bytes!("../../tests/fixtures/osm/kamppi.osm.pbf"),
        None,
    )
    .unwrap();
    assert_eq!(xml, pbf);
    assert_eq!(xml.buildings.len(), 44);
    assert!(xml.roads.iter().filter(|r| r.drivable).count() > 100);
    assert!(xml.buildings.iter().any(|b| !b.holes.is_empty()));
}

#[test]
fn what_is_not_an_extract_is_refused_without_panicking() {
    let png = crate::model::encode_png(&image::RgbImage::new(4, 4));
    assert!(matches!(
        read(&png, None),
        Err(OsmError::Xml { .. } | OsmError::NotOsm)
    ));
    assert!(matches!(read(b"", None), Err(OsmError::NotOsm)));
    assert!(matches!(
        read(b"<html></html>", None),
        Err(OsmError::NotOsm)
    ));
    let broken = "<osm><node id=\"1\" lat=\"60\" lon=\"25\"></way></osm>";
    assert!(matches!(
        read(broken.as_bytes(), None),
        Err(OsmError::Xml { .. })
    ));
    let off = "<osm><node id=\"1\" lat=\"95\" lon=\"25\"/></osm>";
    let err = read(off.as_bytes(), None).unwrap_err().to_string();
    assert!(err.contains("lat 95"), "{err}");
    let no_id = "<osm><node lat=\"60\" lon=\"25\"/></osm>";
    let err = read(no_id.as_bytes(), None).unwrap_err().to_string();
    assert!(err.contains("<node> has no id"), "{err}");
    assert!(matches!(read(b"<osm></osm>", None), Err(OsmError::NoNodes)));
    // A PBF cut short anywhere is an error, never a panic.
    let pbf = include_bytes!("../../tests/fixtures/osm/kamppi.osm.pbf");
    for len in [16, 200, 5_000, pbf.len() / 2, pbf.len() - 1] {
        assert!(
            matches!(read(&pbf[..len], None), Err(OsmError::Pbf(_))),
            "{len}"
        );
    }
    let inverted = GeoBox {
        south: 60.001,
        west: 25.0,
        north: 60.0,
        east: 25.002,
    };
    assert!(matches!(
        read(TOWN.as_bytes(), Some(inverted)),
        Err(OsmError::Box(_))
    ));
}

#[test]
fn the_picture_shows_buildings_roads_and_furniture() {
    let map = town();
    let img = draw(&map, 512);
    // 112 m across at the most pixels a metre the picture allows (4).
    let s = 4.0;
    assert_eq!(
        img.width(),
        ((map.extent[2] - map.extent[0]) * s).ceil() as u32
    );
    let colours: std::collections::BTreeSet<[u8; 3]> = img.pixels().map(|p| p.0).collect();
    // Ground, carriageway, sidewalk, footway, the two buildings' colours, four dots.
    for c in [
        [236, 234, 226],
        [88, 88, 92],
        [196, 196, 196],
        [214, 190, 150],
        [40, 150, 50],
    ] {
        assert!(colours.contains(&c), "{c:?} missing");
    }
    // The courtyard is ground again: its centre (60.0007, 25.0013).
    let p = Projection::new(60.0005, 25.001);
    let [x, z] = p.project(60.0007, 25.0013);
    let px = img.get_pixel(
        ((x - map.extent[0]) * s) as u32,
        ((z - map.extent[1]) * s) as u32,
    );
    assert_eq!(px.0, [236, 234, 226]);
}

/// A street running east along 60.0005° N in three segments, 6.5 m wide with 2 m
/// sidewalks, between a building 4.5 m north of its first segment, one across its second
/// and one 2 m south of its third.
const FITTED: &str = r#"<osm version="0.6">
  <bounds minlat="60.0000000" minlon="25.0000000" maxlat="60.0010000" maxlon="25.0030000"/>
  <node id="1" lat="60.0005" lon="25.0000"/>
  <node id="2" lat="60.0005" lon="25.0010"/>
  <node id="3" lat="60.0005" lon="25.0020"/>
  <node id="4" lat="60.0005" lon="25.0030"/>
  <node id="11" lat="60.0005404" lon="25.0002"/>
  <node id="12" lat="60.0005404" lon="25.0006"/>
  <node id="13" lat="60.0007" lon="25.0006"/>
  <node id="14" lat="60.0007" lon="25.0002"/>
  <node id="21" lat="60.0004" lon="25.0013"/>
  <node id="22" lat="60.0004" lon="25.0016"/>
  <node id="23" lat="60.0006" lon="25.0016"/>
  <node id="24" lat="60.0006" lon="25.0013"/>
  <node id="31" lat="60.0003" lon="25.0023"/>
  <node id="32" lat="60.0003" lon="25.0026"/>
  <node id="33" lat="60.0004820" lon="25.0026"/>
  <node id="34" lat="60.0004820" lon="25.0023"/>
  <way id="1"><nd ref="1"/><nd ref="2"/><nd ref="3"/><nd ref="4"/>
    <tag k="highway" v="residential"/><tag k="width" v="6.5"/><tag k="sidewalk" v="both"/></way>
  <way id="10"><nd ref="11"/><nd ref="12"/><nd ref="13"/><nd ref="14"/><nd ref="11"/><tag k="building" v="yes"/></way>
  <way id="20"><nd ref="21"/><nd ref="22"/><nd ref="23"/><nd ref="24"/><nd ref="21"/><tag k="building" v="yes"/></way>
  <way id="30"><nd ref="31"/><nd ref="32"/><nd ref="33"/><nd ref="34"/><nd ref="31"/><tag k="building" v="yes"/></way>
</osm>
"#;

#[test]
fn roads_narrow_between_buildings_and_stop_at_one_across_them() {
    let map = read(FITTED.as_bytes(), None).unwrap();
    let road = &map.roads[0];
    let metre = 1.0 / map.metres_per_degree[1]; // degrees of latitude a metre
    let north = 0.0000404 / metre; // the first building's distance, metres
    let south = 0.0000180 / metre; // the third's
    assert!(
        (north - 4.50).abs() < 0.01 && (south - 2.0).abs() < 0.01,
        "{north} {south}"
    );
    let [a, b, c] = [road.fitted[0], road.fitted[1], road.fitted[2]];
    // North (left of east): the carriageway keeps 3.25 m, the left sidewalk what is left.
    assert_eq!(a[0], 6.5);
    assert!((a[1] - (north - fit::MARGIN - 3.25)).abs() < 1e-9, "{a:?}");
    assert_eq!(a[2], 2.0);
    // Across the road: not paved.
    assert_eq!(b, [0.0; 3]);
    // South: the carriageway narrows to the building, no right sidewalk is left.
    assert!((c[0] - 2.0 * (south - fit::MARGIN)).abs() < 1e-9, "{c:?}");
    assert_eq!((c[1], c[2]), (2.0, 0.0));
    assert_eq!(
        (
            map.left_out.segments_narrowed,
            map.left_out.segments_blocked
        ),
        (2, 1)
    );
}

#[test]
fn carriageway_sidewalks_and_blocks_tile_the_box_clear_of_buildings() {
    for map in [read(FITTED.as_bytes(), None).unwrap(), town()] {
        let [x0, z0, x1, z1] = map.extent;
        let area = |ps: &[crate::model::MapPolygon]| ps.iter().map(|p| p.area).sum::<f64>();
        let (c, s, b) = (
            area(&map.carriageway),
            area(&map.sidewalks),
            area(&map.blocks),
        );
        let whole = (x1 - x0) * (z1 - z0);
        assert!(
            ((c + s + b) / whole - 1.0).abs() < 1e-6,
            "{c} + {s} + {b} against {whole}"
        );
        assert!(c > 0.0 && s > 0.0 && !map.blocks.is_empty());
        let inside = |ps: &[crate::model::MapPolygon], p: [f64; 2]| {
            ps.iter().any(|poly| {
                crate::model::geometry::polygon::contains(&poly.outer, p)
                    && !poly
                        .holes
                        .iter()
                        .any(|h| crate::model::geometry::polygon::contains(h, p))
            })
        };
        // No corner or centre of a building lies on the street.
        for building in &map.buildings {
            let n = building.outer.len() as f64;
            let centre = building
                .outer
                .iter()
                .fold([0.0, 0.0], |acc, p| [acc[0] + p[0] / n, acc[1] + p[1] / n]);
            for p in building.outer.iter().copied().chain([centre]) {
                assert!(
                    !inside(&map.carriageway, p) && !inside(&map.sidewalks, p),
                    "{p:?}"
                );
            }
        }
        // Every paved segment's middle is on the carriageway.
        for road in map.roads.iter().filter(|r| r.surface) {
            for (w, f) in road.centreline.windows(2).zip(&road.fitted) {
                let mid = [(w[0][0] + w[1][0]) / 2.0, (w[0][1] + w[1][1]) / 2.0];
                assert_eq!(inside(&map.carriageway, mid), f[0] > 0.0, "{mid:?} {f:?}");
            }
        }
    }
}

/// A street along the box's south edge and, north of it, a park with a pond (a
/// multipolygon), a lawn overlapping the park's east side, an asphalt pitch, and a
/// square overlapping the lawn's east side.
const GREEN: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<osm version="0.6">
  <bounds minlat="60.0000000" minlon="25.0000000" maxlat="60.0010000" maxlon="25.0020000"/>
  <node id="1" lat="60.0001" lon="24.9990"/>
  <node id="2" lat="60.0001" lon="25.0030"/>
  <node id="11" lat="60.0004" lon="25.0002"/>
  <node id="12" lat="60.0004" lon="25.0008"/>
  <node id="13" lat="60.0008" lon="25.0008"/>
  <node id="14" lat="60.0008" lon="25.0002"/>
  <node id="21" lat="60.0005" lon="25.0004"/>
  <node id="22" lat="60.0005" lon="25.0005"/>
  <node id="23" lat="60.0006" lon="25.0005"/>
  <node id="24" lat="60.0006" lon="25.0004"/>
  <node id="31" lat="60.0004" lon="25.0006"/>
  <node id="32" lat="60.0004" lon="25.0012"/>
  <node id="33" lat="60.0008" lon="25.0012"/>
  <node id="34" lat="60.0008" lon="25.0006"/>
  <node id="41" lat="60.0004" lon="25.0014"/>
  <node id="42" lat="60.0004" lon="25.0018"/>
  <node id="43" lat="60.0008" lon="25.0018"/>
  <node id="44" lat="60.0008" lon="25.0014"/>
  <node id="51" lat="60.0005" lon="25.0010"/>
  <node id="52" lat="60.0005" lon="25.0013"/>
  <node id="53" lat="60.0007" lon="25.0013"/>
  <node id="54" lat="60.0007" lon="25.0010"/>
  <way id="100"><nd ref="1"/><nd ref="2"/><tag k="highway" v="residential"/></way>
  <way id="101"><nd ref="11"/><nd ref="12"/><nd ref="13"/><nd ref="14"/><nd ref="11"/></way>
  <way id="102"><nd ref="21"/><nd ref="22"/><nd ref="23"/><nd ref="24"/><nd ref="21"/></way>
  <way id="103">
    <nd ref="31"/><nd ref="32"/><nd ref="33"/><nd ref="34"/><nd ref="31"/>
    <tag k="landuse" v="grass"/>
  </way>
  <way id="104">
    <nd ref="41"/><nd ref="42"/><nd ref="43"/><nd ref="44"/><nd ref="41"/>
    <tag k="leisure" v="pitch"/><tag k="surface" v="asphalt"/>
  </way>
  <way id="105">
    <nd ref="51"/><nd ref="52"/><nd ref="53"/><nd ref="54"/><nd ref="51"/>
    <tag k="place" v="square"/>
  </way>
  <relation id="300">
    <member type="way" ref="101" role="outer"/>
    <member type="way" ref="102" role="inner"/>
    <tag k="type" v="multipolygon"/><tag k="leisure" v="park"/>
  </relation>
</osm>
"#;

#[test]
fn green_ground_is_the_union_of_the_green_areas_less_their_holes_on_the_blocks() {
    let map = read(GREEN.as_bytes(), None).unwrap();
    let [dx, dz] = map.metres_per_degree;
    // Park 4 × 6, lawn 4 × 6, their overlap 4 × 2, the pond 1 × 1 (in 0.0001°); not the
    // asphalt pitch.
    let expected = (24.0 + 24.0 - 8.0 - 1.0) * 1e-8 * dx * dz;
    let area: f64 = map.green.iter().map(|g| g.shape.area).sum();
    assert!(
        (area - expected).abs() < 1e-6 * expected,
        "{area} {expected}"
    );
    // The square 2 × 3, less its 2 × 2 under the lawn: grass wins.
    let expected = 2.0 * 1e-8 * dx * dz;
    let area: f64 = map.squares.iter().map(|g| g.shape.area).sum();
    assert!(
        (area - expected).abs() < 1e-6 * expected,
        "{area} {expected}"
    );
    assert_eq!(
        map.green.len(),
        1,
        "one piece: the park and the lawn joined"
    );
    let green = &map.green[0];
    assert_eq!(green.shape.holes.len(), 1, "the pond");
    // On its block, clear of the street.
    let block = &map.blocks[green.block as usize];
    use crate::model::geometry::polygon::contains;
    assert!(green.shape.outer.iter().all(|&p| contains(&block.outer, p)));
    for street in map.carriageway.iter().chain(&map.sidewalks) {
        assert!(
            green
                .shape
                .outer
                .iter()
                .all(|&p| !contains(&street.outer, p))
        );
    }
    // The same from a file with the park before its ways and nodes.
    let (start, end) = (
        GREEN.find("  <relation").unwrap(),
        GREEN.find("</osm>").unwrap(),
    );
    let first = GREEN.find("  <node").unwrap();
    let reordered = format!(
        "{}{}{}{}",
        &GREEN[..first],
        &GREEN[start..end],
        &GREEN[first..start],
        &GREEN[end..]
    );
    let again = read(reordered.as_bytes(), None).unwrap();
    assert_eq!((again.green, again.squares), (map.green, map.squares));
}

#[test]
fn paths_across_the_green_are_their_strokes_cut_to_the_green() {
    // A footway 2 m wide (the default) from west of the park to the pitch, along a
    // parallel (a straight line east in metres); a footbridge and a tunnel beside it, and
    // steps.
    let ways = r#"  <node id="61" lat="60.00075" lon="25.0000"/>
  <node id="62" lat="60.00075" lon="25.0016"/>
  <node id="63" lat="60.00070" lon="25.0000"/>
  <node id="64" lat="60.00070" lon="25.0016"/>
  <node id="65" lat="60.00045" lon="25.0000"/>
  <node id="66" lat="60.00045" lon="25.0016"/>
  <way id="110"><nd ref="61"/><nd ref="62"/><tag k="highway" v="footway"/></way>
  <way id="111"><nd ref="63"/><nd ref="64"/><tag k="highway" v="footway"/><tag k="bridge" v="yes"/></way>
  <way id="112"><nd ref="65"/><nd ref="66"/><tag k="highway" v="path"/><tag k="tunnel" v="yes"/></way>
  <way id="113"><nd ref="63"/><nd ref="66"/><tag k="highway" v="steps"/></way>
"#;
    let at = GREEN.find("  <relation").unwrap();
    let text = format!("{}{ways}{}", &GREEN[..at], &GREEN[at..]);
    let map = read(text.as_bytes(), None).unwrap();
    let [dx, _] = map.metres_per_degree;
    // The green along the footway: the park and the lawn, 25.0002° to 25.0012° east.
    let expected = 2.0 * 0.0010 * dx;
    let area: f64 = map.paths.iter().map(|p| p.shape.area).sum();
    assert!((area - expected).abs() < 1e-3, "{area} {expected}");
    assert_eq!(map.paths.len(), 1);
    // On the green's block, and the green itself is as the map has it.
    let (path, green) = (&map.paths[0], &map.green[0]);
    assert_eq!(path.block, green.block);
    let without = read(GREEN.as_bytes(), None).unwrap();
    assert_eq!(map.green, without.green);
    assert!(without.paths.is_empty());
    // Every corner in the green or on its edge (within a millimetre).
    use crate::model::geometry::polygon::{contains, ring_distance};
    let ring = &green.shape.outer;
    assert!((path.shape.outer.iter()).all(|&p| contains(ring, p) || ring_distance(ring, p) < 1e-3));
}

#[test]
fn a_way_one_way_against_its_nodes_runs_the_traffic_s_way() {
    let xml = r#"<?xml version="1.0" encoding="UTF-8"?>
<osm version="0.6">
  <bounds minlat="60.0000000" minlon="25.0000000" maxlat="60.0010000" maxlon="25.0020000"/>
  <node id="1" lat="60.0005" lon="25.0002"/>
  <node id="2" lat="60.0005" lon="25.0010"/>
  <way id="300"><nd ref="1"/><nd ref="2"/>
    <tag k="highway" v="residential"/><tag k="oneway" v="-1"/><tag k="sidewalk" v="left"/>
    <tag k="parking:lane:right" v="parallel"/>
  </way>
</osm>"#;
    let map = read(xml.as_bytes(), None).unwrap();
    let road = &map.roads[0];
    assert!(road.oneway);
    // The traffic runs west: the centreline from node 2 to node 1.
    let [a, b] = [road.centreline[0], road.centreline[1]];
    assert!(a[0] > b[0], "{:?}", road.centreline);
    // The way's left sidewalk is on the traffic's right, its right kerb's parking on
    // the traffic's left.
    assert_eq!(road.sidewalks, [0.0, SIDEWALK_WIDTH]);
    assert_eq!(road.parking, [Some(true), None]);
    let forward = read(xml.replace("\"-1\"", "\"yes\"").as_bytes(), None).unwrap();
    let road = &forward.roads[0];
    assert!(road.centreline[0][0] < road.centreline[1][0]);
    assert_eq!(road.sidewalks, [SIDEWALK_WIDTH, 0.0]);
    assert_eq!(road.parking, [None, Some(true)]);
}

#[test]
fn ground_paths_are_footways_paths_and_cycleways_off_bridges() {
    assert!(tags::ground_path("footway", &[]));
    assert!(tags::ground_path("cycleway", &[("layer", "0")]));
    assert!(tags::ground_path("path", &[("bridge", "no")]));
    assert!(!tags::ground_path("footway", &[("bridge", "yes")]));
    assert!(!tags::ground_path("footway", &[("layer", "1")]));
    assert!(!tags::ground_path("steps", &[]));
    assert!(!tags::ground_path("residential", &[]));
}

#[test]
fn green_tags_are_grass_parks_and_woods_and_squares_are_paved_open_ground() {
    let green = |tags: &[(&str, &str)]| tags::green(tags);
    assert!(green(&[("leisure", "park")]));
    assert!(green(&[("landuse", "grass")]));
    assert!(green(&[("natural", "wood")]));
    assert!(green(&[("leisure", "pitch")]));
    assert!(green(&[("leisure", "pitch"), ("surface", "grass")]));
    assert!(!green(&[("leisure", "pitch"), ("surface", "asphalt")]));
    assert!(!green(&[("landuse", "residential")]));
    assert!(!green(&[("amenity", "parking")]));
    let square = |tags: &[(&str, &str)]| tags::square(tags);
    assert!(square(&[("place", "square")]));
    assert!(square(&[("highway", "pedestrian"), ("area", "yes")]));
    assert!(
        !square(&[("highway", "pedestrian")]),
        "a street, not an area"
    );
    assert!(square(&[("amenity", "parking")]));
    assert!(!square(&[
        ("amenity", "parking"),
        ("parking", "underground")
    ]));
}

/// A building (way 10, 4 levels) with three parts: a tower on the ground that is also
/// tagged `building=church` (way 11), a storey lifted over a passage (way 12), and a part
/// in no building (way 13); and a canopy lifted on its own (way 14).
const PARTS: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<osm version="0.6">
  <bounds minlat="60.0000000" minlon="25.0000000" maxlat="60.0010000" maxlon="25.0020000"/>
  <node id="1" lat="60.0002" lon="25.0002"/>
  <node id="2" lat="60.0002" lon="25.0008"/>
  <node id="3" lat="60.0006" lon="25.0008"/>
  <node id="4" lat="60.0006" lon="25.0002"/>
  <node id="5" lat="60.0002" lon="25.0004"/>
  <node id="6" lat="60.0004" lon="25.0004"/>
  <node id="7" lat="60.0004" lon="25.0002"/>
  <node id="8" lat="60.0006" lon="25.0004"/>
  <node id="21" lat="60.0008" lon="25.0012"/>
  <node id="22" lat="60.0008" lon="25.0014"/>
  <node id="23" lat="60.0009" lon="25.0014"/>
  <node id="31" lat="60.0001" lon="25.0012"/>
  <node id="32" lat="60.0001" lon="25.0016"/>
  <node id="33" lat="60.0003" lon="25.0016"/>
  <node id="34" lat="60.0003" lon="25.0012"/>
  <way id="10">
    <nd ref="1"/><nd ref="2"/><nd ref="3"/><nd ref="4"/><nd ref="1"/>
    <tag k="building" v="yes"/><tag k="building:levels" v="4"/>
  </way>
  <way id="11">
    <nd ref="1"/><nd ref="5"/><nd ref="6"/><nd ref="7"/><nd ref="1"/>
    <tag k="building" v="church"/><tag k="building:part" v="yes"/><tag k="height" v="30"/>
    <tag k="roof:shape" v="dome"/><tag k="roof:orientation" v="across"/>
  </way>
  <way id="12">
    <nd ref="7"/><nd ref="6"/><nd ref="8"/><nd ref="4"/><nd ref="7"/>
    <tag k="building:part" v="yes"/><tag k="building:levels" v="6"/>
    <tag k="building:min_level" v="2"/><tag k="roof:shape" v="skillion"/>
    <tag k="roof:direction" v="SE"/>
  </way>
  <way id="13">
    <nd ref="21"/><nd ref="22"/><nd ref="23"/><nd ref="21"/><tag k="building:part" v="yes"/>
  </way>
  <way id="14">
    <nd ref="31"/><nd ref="32"/><nd ref="33"/><nd ref="34"/><nd ref="31"/>
    <tag k="building" v="roof"/><tag k="height" v="4"/><tag k="min_height" v="2.5"/>
  </way>
</osm>
"#;

#[test]
fn building_parts_go_to_the_building_they_stand_in() {
    let map = read(PARTS.as_bytes(), None).unwrap();
    let keys: Vec<_> = map.buildings.iter().map(|b| b.element).collect();
    // Way 11 is a part, though it is tagged `building` too.
    assert_eq!(keys, [OsmElement::Way(10), OsmElement::Way(14)]);
    let b = &map.buildings[0];
    assert_eq!((b.height, b.min_height), (Some(12.0), None));
    let parts: Vec<_> = b.parts.iter().map(|p| p.element).collect();
    assert_eq!(parts, [OsmElement::Way(11), OsmElement::Way(12)]);
    let [tower, storey] = [&b.parts[0], &b.parts[1]];
    assert_eq!(tower.kind, "church");
    assert_eq!(
        (tower.height, tower.height_from.as_str(), tower.min_height),
        (Some(30.0), "height", None)
    );
    assert_eq!(tower.roof_shape.as_deref(), Some("dome"));
    assert!(tower.roof_across && !storey.roof_across);
    assert_eq!(
        (tower.roof_direction, storey.roof_direction),
        (None, Some(135.0))
    );
    assert_eq!(
        (storey.height, storey.min_height),
        (Some(6.0 * FLOOR_HEIGHT), Some(2.0 * FLOOR_HEIGHT))
    );
    assert!(tower.parts.is_empty() && storey.parts.is_empty());
    // A sixth of the building's footprint each.
    assert!((tower.area - b.area / 6.0).abs() < 1e-6 * b.area);
    assert!((storey.area - b.area / 6.0).abs() < 1e-6 * b.area);
    assert_eq!(map.left_out.parts_alone, 1, "way 13 stands in no building");
    let canopy = &map.buildings[1];
    assert_eq!((canopy.height, canopy.min_height), (Some(4.0), Some(2.5)));
    assert!(canopy.parts.is_empty());
}
