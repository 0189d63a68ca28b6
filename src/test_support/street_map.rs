//! A hand-made map for the map stages' tests: two streets meeting, a building, the map's
//! lamps and trees.

use crate::model::{
    FeatureKind, GeoBox, LeftOut, MapBuilding, MapFeature, MapRoad, OsmElement, OsmMap,
};

/// A 300 × 200 m map (x −150…150, z −100…100):
///
/// - road 0, way 10: two-way, 12 m wide with 3 m sidewalks, west to east along z = 0 from
///   x −150 to 0, then bending to run north-east to (100, −100);
/// - road 1, way 11: one-way, 8 m wide with 2 m sidewalks, south from (−50, 0) to
///   (−50, 100);
/// - road 2, way 12: a footway (no surface) along z = 40;
/// - a 20 × 20 m building 10 m south of road 0's kerb (z 19…39, x −120…−100);
/// - lamps at (−100, −8) beside road 0 and (−20, 0) on its centreline, one 60 m from any
///   road; trees at (−80, 8.5) on the sidewalk, (−60, 2) on the carriageway and
///   (−110, 25) inside the building.
pub fn street_map() -> OsmMap {
    let road = |way, oneway, surface, centreline: Vec<[f64; 2]>, width: f64, side: f64| {
        let segments = centreline.len() - 1;
        let length = centreline
            .windows(2)
            .map(|w| crate::model::geometry::polygon::distance(w[0], w[1]))
            .sum();
        MapRoad {
            way,
            piece: 0,
            class: if surface { "residential" } else { "footway" }.to_owned(),
            drivable: surface,
            centreline,
            length,
            width,
            width_from: "width".to_owned(),
            sidewalks: [side; 2],
            parking: [None; 2],
            oneway,
            roundabout: false,
            surface,
            fitted: if surface {
                vec![[width, side, side]; segments]
            } else {
                Vec::new()
            },
            name: None,
            clipped: false,
        }
    };
    let feature = |node, kind, at| MapFeature {
        node,
        kind,
        at,
        tag: String::new(),
    };
    let b = vec![
        [-120.0, 19.0],
        [-100.0, 19.0],
        [-100.0, 39.0],
        [-120.0, 39.0],
    ];
    OsmMap {
        bounds: GeoBox {
            south: 60.0,
            west: 25.0,
            north: 60.002,
            east: 25.005,
        },
        origin: [60.001, 25.0025],
        metres_per_degree: [55_800.0, 111_412.0],
        extent: [-150.0, -100.0, 150.0, 100.0],
        buildings: vec![MapBuilding {
            area: 400.0,
            height: Some(12.0),
            height_from: "height".to_owned(),
            ..MapBuilding::new(OsmElement::Way(1), 0, b, Vec::new())
        }],
        roads: vec![
            road(
                10,
                false,
                true,
                vec![[-150.0, 0.0], [0.0, 0.0], [100.0, -100.0]],
                12.0,
                3.0,
            ),
            road(11, true, true, vec![[-50.0, 0.0], [-50.0, 100.0]], 8.0, 2.0),
            road(
                12,
                false,
                false,
                vec![[-150.0, 40.0], [150.0, 40.0]],
                2.0,
                0.0,
            ),
        ],
        features: vec![
            feature(1, FeatureKind::StreetLamp, [-100.0, -8.0]),
            feature(2, FeatureKind::StreetLamp, [-20.0, 0.0]),
            feature(3, FeatureKind::StreetLamp, [100.0, 80.0]),
            feature(4, FeatureKind::Tree, [-80.0, 8.5]),
            feature(5, FeatureKind::Tree, [-60.0, 2.0]),
            feature(6, FeatureKind::Tree, [-110.0, 25.0]),
        ],
        carriageway: Vec::new(),
        sidewalks: Vec::new(),
        blocks: Vec::new(),
        green: Vec::new(),
        paths: Vec::new(),
        squares: Vec::new(),
        left_out: LeftOut::default(),
    }
}
