//! Road markings on a map (`map_markings`): lane lines by width, dashes that follow the
//! centreline through a bend and stop before a junction, zebras at marked crossings.

use crate::model::geometry::MARKING_Y;
use crate::model::geometry::map_lines::UNMARKED_CROSSING;
use crate::model::geometry::zebras::{DASH, LINE_CLEARANCE, LINE_WIDTH, ZEBRA_DEPTH};
use crate::model::{FeatureKind, MapFeature, ObjectKind, SceneObject};
use crate::scene::map_markings::{lane_lines, map_marking_objects};
use crate::scene::paint::{BAR, BAR_GAP, CURB_CLEARANCE, GAP, STOP_LINE};
use crate::test_support::street_map;

/// The faces of a marking object, quads and triangles, their corners `[x, z]` in order.
fn faces(object: &SceneObject) -> Vec<Vec<[f64; 2]>> {
    let mesh = &object.meshes[0];
    assert!(mesh.positions.iter().all(|p| p[1] == MARKING_Y as f32));
    let corner = |i: u32| {
        let p = mesh.positions[i as usize];
        [f64::from(p[0]), f64::from(p[2])]
    };
    let mut out = Vec::new();
    let mut i = 0;
    while i < mesh.indices.len() {
        // A quad is two triangles fanned from its first corner: 0 1 2, 0 2 3.
        let base = mesh.indices[i];
        let quad = mesh.indices.get(i + 3) == Some(&base);
        let corners = if quad { 4 } else { 3 };
        out.push((0..corners).map(|k| corner(base + k)).collect());
        i += if quad { 6 } else { 3 };
    }
    assert_eq!(
        out.iter().map(Vec::len).sum::<usize>(),
        mesh.positions.len()
    );
    out
}

/// The quads of a marking object: four corners each, `[x, z]`.
fn quads(object: &SceneObject) -> Vec<[[f64; 2]; 4]> {
    (faces(object).into_iter())
        .filter_map(|f| <[[f64; 2]; 4]>::try_from(f).ok())
        .collect()
}

/// A quad's length along `dir` and across it, and its centre.
fn measure(q: &[[f64; 2]; 4], dir: [f64; 2]) -> (f64, f64, [f64; 2]) {
    let along = |p: [f64; 2]| p[0] * dir[0] + p[1] * dir[1];
    let across = |p: [f64; 2]| -p[0] * dir[1] + p[1] * dir[0];
    let span = |f: &dyn Fn([f64; 2]) -> f64| {
        let v: Vec<f64> = q.iter().map(|&p| f(p)).collect();
        v.iter().cloned().fold(f64::MIN, f64::max) - v.iter().cloned().fold(f64::MAX, f64::min)
    };
    let centre = [
        q.iter().map(|p| p[0]).sum::<f64>() / 4.0,
        q.iter().map(|p| p[1]).sum::<f64>() / 4.0,
    ];
    (span(&along), span(&across), centre)
}

fn crossing(node: i64, at: [f64; 2], tag: &str) -> MapFeature {
    MapFeature {
        node,
        kind: FeatureKind::Crossing,
        at,
        tag: tag.to_owned(),
    }
}

const EPS: f64 = 1e-4;

#[test]
fn lanes_split_the_carriageway_by_width_and_direction() {
    // Two-way: a centre line from two lanes up, lane lines within each half.
    assert_eq!(lane_lines(3.25, false), Vec::<f64>::new());
    assert_eq!(lane_lines(6.5, false), vec![0.0]);
    assert_eq!(lane_lines(9.75, false), vec![0.0]);
    assert_eq!(lane_lines(12.0, false), vec![0.0, -3.0, 3.0]);
    // One-way: n lanes, n − 1 lines, evenly.
    assert_eq!(lane_lines(3.25, true), Vec::<f64>::new());
    assert_eq!(lane_lines(6.5, true), vec![0.0]);
    assert_eq!(lane_lines(9.75, true), vec![-1.625, 1.625]);
}

#[test]
fn dashes_follow_the_centreline_and_stop_before_the_junction() {
    let map = street_map();
    let objects = map_marking_objects(&map, 3);
    // Road 0 (two-way, 12 m: lines at 0 and ±3) and road 1 (one-way, 8 m: a line at 0);
    // the footway has none.
    let names: Vec<&str> = objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["marking_0000", "marking_0001"]);
    assert!(objects.iter().all(|o| o.kind == ObjectKind::Marking));
    let road0 = quads(&objects[0]);
    // Road 1 meets road 0's first segment at (−50, 0), from the south: road 0's lines keep
    // road 1's half-width (4 m) and the clearance from it, road 1's road 0's (6 m).
    for q in &road0 {
        let (along, across, c) = if q.iter().all(|p| p[0] <= EPS) {
            measure(q, [1.0, 0.0])
        } else {
            let d = std::f64::consts::FRAC_1_SQRT_2;
            measure(q, [d, -d])
        };
        assert!((across - LINE_WIDTH).abs() < EPS, "{q:?}");
        assert!(along <= DASH + EPS, "{q:?}");
        // On a line: 0 or ±3 m from the centreline.
        let off = if c[0] <= 0.0 {
            c[1]
        } else {
            (c[0] + c[1]) * std::f64::consts::FRAC_1_SQRT_2
        };
        assert!(
            [0.0, 3.0, -3.0].iter().any(|l| (off - l).abs() < 0.01),
            "{q:?}"
        );
        for p in q {
            assert!((p[0] + 50.0).abs() >= 4.0 + LINE_CLEARANCE - EPS, "{q:?}");
        }
    }
    // Dashes on both sides of the bend at (0, 0), on each of its three lines.
    let before = road0
        .iter()
        .filter(|q| q.iter().all(|p| p[0] < 0.0))
        .count();
    let after = road0
        .iter()
        .filter(|q| q.iter().all(|p| p[0] > 0.0))
        .count();
    assert!(before >= 3 * 10 && after >= 3 * 10, "{before} {after}");
    // The bend runs on: the dash pattern is counted along the centreline, so dashes and
    // gaps alternate across it (one dash may be split into two quads there).
    let centre: Vec<f64> = road0
        .iter()
        .filter(|q| q.iter().all(|p| p[0] < -55.0 && p[1].abs() < 1.0))
        .map(|q| q.iter().map(|p| p[0]).fold(f64::MIN, f64::max))
        .collect();
    for pair in centre.windows(2) {
        assert!(
            ((pair[1] - pair[0]) - (DASH + GAP)).abs() < EPS,
            "{centre:?}"
        );
    }
    // Road 1's line keeps road 0's half-width and the clearance from the junction.
    let road1 = quads(&objects[1]);
    assert!(!road1.is_empty());
    for q in &road1 {
        let (along, across, c) = measure(q, [0.0, 1.0]);
        assert!((along - DASH).abs() < EPS && (across - LINE_WIDTH).abs() < EPS);
        assert!((c[0] + 50.0).abs() < EPS, "{q:?}");
        assert!(
            q.iter().all(|p| p[1] >= 6.0 + LINE_CLEARANCE - EPS),
            "{q:?}"
        );
    }
}

#[test]
fn marked_crossings_get_zebras_and_the_lines_keep_clear() {
    let mut map = street_map();
    map.features.extend([
        // On road 0, marked; 0.3 m off its centreline (still on it).
        crossing(20, [-100.0, 0.3], "highway=crossing"),
        // Unmarked, both ways the map says so.
        crossing(21, [-130.0, 0.0], UNMARKED_CROSSING[0]),
        crossing(22, [-70.0, 0.0], UNMARKED_CROSSING[1]),
        // In the junction with road 1: its bars would lie on road 1's carriageway.
        crossing(23, [-52.0, 0.0], "highway=crossing"),
        // Off every road (on the footway).
        crossing(24, [0.0, 40.0], "highway=crossing"),
    ]);
    let objects = map_marking_objects(&map, 3);
    let road0 = quads(&objects[0]);
    let bars: Vec<(f64, f64, [f64; 2])> = road0
        .iter()
        .map(|q| measure(q, [1.0, 0.0]))
        .filter(|m| (m.1 - BAR).abs() < EPS)
        .collect();
    // 12 m less the clearances: 11.4 m holds 10 bars (10 × 0.5 + 9 × 0.6 = 10.4).
    assert_eq!(bars.len(), 10, "{bars:?}");
    for (along, _, c) in &bars {
        assert!((along - ZEBRA_DEPTH).abs() < EPS);
        assert!((c[0] + 100.0).abs() < EPS, "{c:?}");
    }
    let (lo, hi) = bars.iter().fold((f64::MAX, f64::MIN), |(lo, hi), b| {
        (lo.min(b.2[1] - BAR / 2.0), hi.max(b.2[1] + BAR / 2.0))
    });
    assert!((lo + 6.0 - CURB_CLEARANCE - 0.5).abs() < EPS, "{lo}");
    assert!((hi - 6.0 + CURB_CLEARANCE + 0.5).abs() < EPS, "{hi}");
    assert!(
        bars.windows(2)
            .all(|b| (b[1].2[1] - b[0].2[1] - BAR - BAR_GAP).abs() < EPS)
    );
    // The lines stop the clearance before the zebra; the unmarked crossings and the one in
    // the junction leave the lines as they were.
    for q in &road0 {
        let (_, across, c) = measure(q, [1.0, 0.0]);
        if (across - LINE_WIDTH).abs() < EPS && c[0] < 0.0 {
            for p in q {
                let d = (p[0] + 100.0).abs();
                assert!(d >= ZEBRA_DEPTH / 2.0 + LINE_CLEARANCE - EPS, "{q:?}");
            }
        }
    }
    // Each stretch left holds its own centred dashes: [−150, −103] five with 4 m either
    // side, [−97, −55.5] (to the junction's clearance) five with 1.25 m; past the junction
    // the lines are as without the crossings, and road 1's too.
    let starts = |range: [f64; 2]| -> Vec<f64> {
        let mut v: Vec<f64> = road0
            .iter()
            .filter(|q| {
                q.iter()
                    .all(|p| p[0] > range[0] && p[0] < range[1] && p[1].abs() < 0.1)
            })
            .map(|q| q.iter().map(|p| p[0]).fold(f64::MAX, f64::min))
            .collect();
        v.sort_by(f64::total_cmp);
        v
    };
    let expect = |first: f64| {
        (0..5)
            .map(|k| first + 9.0 * f64::from(k))
            .collect::<Vec<_>>()
    };
    let close = |a: Vec<f64>, b: Vec<f64>| {
        a.len() == b.len() && a.iter().zip(&b).all(|(x, y)| (x - y).abs() < EPS)
    };
    assert!(
        close(starts([-150.0, -103.0]), expect(-146.0)),
        "{:?}",
        starts([-150.0, -103.0])
    );
    assert!(
        close(starts([-97.0, -55.0]), expect(-95.75)),
        "{:?}",
        starts([-97.0, -55.0])
    );
    let plain = map_marking_objects(&street_map(), 3);
    let past = |qs: &[[[f64; 2]; 4]]| -> Vec<[[f64; 2]; 4]> {
        qs.iter()
            .filter(|q| q.iter().all(|p| p[0] > -50.0))
            .copied()
            .collect()
    };
    assert_eq!(past(&road0), past(&quads(&plain[0])));
    assert!(!past(&road0).is_empty());
    assert_eq!(objects[1], plain[1]);
}

#[test]
fn signals_and_stop_nodes_get_stop_lines_before_them() {
    let mut map = street_map();
    let node = |node, kind, at, tag: &str| MapFeature {
        node,
        kind,
        at,
        tag: tag.to_owned(),
    };
    let signal = FeatureKind::TrafficSignals;
    map.features.extend([
        // Road 0, two-way, 12 m, eastwards: a line each way.
        node(30, signal, [-90.0, 0.0], "highway=traffic_signals"),
        // Road 1, one-way southwards, 8 m: one line, kerb to kerb.
        node(31, signal, [-50.0, 60.0], "highway=traffic_signals"),
        // A stop node (a sign the map puts on the way).
        node(32, FeatureKind::TrafficSign, [-120.0, 0.0], "highway=stop"),
        // A signal 2 m before its zebra: the westbound line stands before the zebra.
        node(33, FeatureKind::Crossing, [-20.0, 0.0], "highway=crossing"),
        node(34, signal, [-22.0, 0.0], "highway=traffic_signals"),
        // In the junction with road 1 (4 m either side of it along road 0).
        node(35, signal, [-50.0, 0.0], "highway=traffic_signals"),
        // Off every road; a give-way node (triangles, not a line).
        node(36, signal, [0.0, 40.0], "highway=traffic_signals"),
        node(
            37,
            FeatureKind::TrafficSign,
            [-135.0, 0.0],
            "highway=give_way",
        ),
        // At road 1's end (a way split at a junction ends so): the traffic coming to it.
        node(38, signal, [-50.0, 100.0], "highway=traffic_signals"),
        // Stopping the westbound (backward) traffic only.
        node(
            39,
            signal,
            [-140.0, 0.0],
            "traffic_signals:direction=backward",
        ),
    ]);
    let objects = map_marking_objects(&map, 3);
    let reach = 6.0 - CURB_CLEARANCE;
    let half = LINE_WIDTH / 2.0;
    // (x range, z range) of each stop line on road 0's straight first part.
    let mut road0: Vec<([f64; 2], [f64; 2])> = quads(&objects[0])
        .iter()
        .filter(|q| q.iter().all(|p| p[0] < 0.0))
        .filter(|q| (measure(q, [1.0, 0.0]).0 - STOP_LINE).abs() < EPS)
        .map(|q| {
            let range = |k: usize| {
                let v = q.iter().map(|p| p[k]);
                [
                    v.clone().fold(f64::MAX, f64::min),
                    v.fold(f64::MIN, f64::max),
                ]
            };
            (range(0), range(1))
        })
        .collect();
    road0.sort_by(|a, b| a.0[0].total_cmp(&b.0[0]));
    let expected = [
        // The backward signal: westbound only.
        ([-139.0, -138.6], [-reach, -half]),
        // The stop node: eastbound on the south half, westbound on the north half.
        ([-121.4, -121.0], [half, reach]),
        ([-119.0, -118.6], [-reach, -half]),
        ([-91.4, -91.0], [half, reach]),
        ([-89.0, -88.6], [-reach, -half]),
        // Before the junction's carriageway, each way.
        ([-55.4, -55.0], [half, reach]),
        ([-45.0, -44.6], [-reach, -half]),
        // Eastbound before the signal, westbound before the zebra (bars −21.5 … −18.5).
        ([-23.4, -23.0], [half, reach]),
        ([-17.5, -17.1], [-reach, -half]),
    ];
    assert_eq!(road0.len(), expected.len(), "{road0:?}");
    for ((x, z), (ex, ez)) in road0.iter().zip(expected) {
        for k in 0..2 {
            assert!(
                (x[k] - ex[k]).abs() < EPS && (z[k] - ez[k]).abs() < EPS,
                "{x:?} {z:?}"
            );
        }
    }
    // Road 1's lines cross its whole width, a metre before each signal; none where it
    // leaves the junction's signal.
    let road1: Vec<[[f64; 2]; 4]> = quads(&objects[1])
        .into_iter()
        .filter(|q| (measure(q, [0.0, 1.0]).0 - STOP_LINE).abs() < EPS)
        .collect();
    assert_eq!(road1.len(), 2);
    for (q, z) in road1.iter().zip([58.8, 98.8]) {
        let (_, across, c) = measure(q, [0.0, 1.0]);
        assert!(
            (across - 2.0 * (4.0 - CURB_CLEARANCE)).abs() < EPS,
            "{across}"
        );
        assert!((c[0] + 50.0).abs() < EPS && (c[1] - z).abs() < EPS, "{c:?}");
    }
    // The dashes keep their clearance from every stop line.
    for q in quads(&objects[0])
        .iter()
        .filter(|q| q.iter().all(|p| p[0] < 0.0))
    {
        if (measure(q, [1.0, 0.0]).1 - LINE_WIDTH).abs() > EPS {
            continue;
        }
        for (x, _) in &expected {
            for p in q {
                let inside =
                    p[0] > x[0] - LINE_CLEARANCE + EPS && p[0] < x[1] + LINE_CLEARANCE - EPS;
                assert!(!inside, "{q:?} by the stop line {x:?}");
            }
        }
    }
}

#[test]
fn give_way_nodes_get_teeth_pointing_at_the_coming_traffic() {
    use crate::scene::paint::{TOOTH_BASE, TOOTH_GAP, TOOTH_LENGTH};
    let mut map = street_map();
    // Road 0, two-way, 12 m wide, eastwards: teeth each way, a metre before the node.
    let give_way = MapFeature {
        node: 37,
        kind: FeatureKind::TrafficSign,
        at: [-135.0, 0.0],
        tag: "highway=give_way".to_owned(),
    };
    map.features.push(give_way);
    let objects = map_marking_objects(&map, 3);
    let teeth: Vec<Vec<[f64; 2]>> = (faces(&objects[0]).into_iter())
        .filter(|f| f.len() == 3)
        .collect();
    // Each half from 0.05 m (half a line) to 5.7 m (the kerb less its clearance) off the
    // centreline: 5.65 m holds 7 teeth of 0.5 m, 0.25 m apart.
    let (half, reach) = (LINE_WIDTH / 2.0, 6.0 - CURB_CLEARANCE);
    let per_side = ((reach - half + TOOTH_GAP) / (TOOTH_BASE + TOOTH_GAP)).floor();
    assert_eq!(per_side, 7.0);
    assert_eq!(teeth.len(), 14);
    for tooth in &teeth {
        // Base two corners at one x, apex at the other (in either winding); z the across
        // position.
        let k = (0..3)
            .find(|&k| (tooth[(k + 1) % 3][0] - tooth[(k + 2) % 3][0]).abs() < EPS)
            .expect("a base across the road");
        let [apex, b0, b1] = [tooth[k], tooth[(k + 1) % 3], tooth[(k + 2) % 3]];
        assert!((b0[0] - b1[0]).abs() < EPS, "{tooth:?}");
        assert!(
            ((b1[1] - b0[1]).abs() - TOOTH_BASE).abs() < EPS,
            "{tooth:?}"
        );
        assert!(
            ((apex[0] - b0[0]).abs() - TOOTH_LENGTH).abs() < EPS,
            "{tooth:?}"
        );
        assert!((apex[1] - (b0[1] + b1[1]) / 2.0).abs() < EPS, "{tooth:?}");
        if apex[1] > 0.0 {
            // Eastbound, on the south half: base a metre before the node, apex west, to
            // the traffic coming from there.
            assert!((b0[0] + 136.0).abs() < EPS && apex[0] < b0[0], "{tooth:?}");
            assert!(b0[1].min(b1[1]) >= half - EPS && b0[1].max(b1[1]) <= reach + EPS);
        } else {
            assert!((b0[0] + 134.0).abs() < EPS && apex[0] > b0[0], "{tooth:?}");
            assert!(b0[1].max(b1[1]) <= -half + EPS && b0[1].min(b1[1]) >= -reach - EPS);
        }
    }
    // Centred across each half: the same room left at both ends.
    let mut south: Vec<f64> = (teeth.iter())
        .filter(|t| t.iter().all(|p| p[1] > 0.0))
        .flat_map(|t| t.iter().map(|p| p[1]))
        .collect();
    south.sort_by(f64::total_cmp);
    let (first, last) = (south[0], south[south.len() - 1]);
    assert!(
        ((first - half) - (reach - last)).abs() < EPS,
        "{first} {last}"
    );
    // The dashes keep their clearance from the teeth (−136.6 … −133.4).
    let clear = [-136.6 - LINE_CLEARANCE, -133.4 + LINE_CLEARANCE];
    for q in quads(&objects[0]) {
        for p in q {
            let inside = p[0] > clear[0] + EPS && p[0] < clear[1] - EPS;
            assert!(!inside, "{q:?} by the teeth");
        }
    }
}
