//! Pedestrians: standing in the strips, waiting at and walking across zebra crossings.

use super::*;
use crate::model::Axis;
use crate::model::geometry::{KERB_Y, RoadRect};

#[test]
fn people_stand_in_the_strips_apart_from_each_other_and_from_trunks() {
    let city = city();
    let specs = [
        spec(EntryKind::Sign, "traffic_sign", 60),
        spec(EntryKind::Tree, "tree", 200),
        spec(EntryKind::Car, "car", 300),
        spec(EntryKind::Person, "person", 300),
    ];
    let mpp = 0.55;
    let inserted = insert_at(&city, mpp, &specs);
    // Where an object stands: the mean of its vertices on its lowest level (a person's
    // soles, a tree trunk's foot), and that level.
    let foot = |meshes: &[crate::model::Mesh]| -> ([f64; 2], f64) {
        let points: Vec<[f64; 3]> = meshes
            .iter()
            .flat_map(|m| &m.positions)
            .map(|p| p.map(f64::from))
            .collect();
        let low = points.iter().map(|p| p[1]).fold(f64::MAX, f64::min);
        let soles: Vec<&[f64; 3]> = points.iter().filter(|p| p[1] < low + 1e-4).collect();
        let n = soles.len() as f64;
        let mean = soles
            .iter()
            .fold([0.0, 0.0], |a, p| [a[0] + p[0] / n, a[1] + p[2] / n]);
        (mean, low)
    };
    let people: Vec<[f64; 2]> = inserted
        .objects
        .iter()
        .filter(|o| o.class == "person")
        .map(|o| {
            let (at, low) = foot(&o.meshes);
            assert!((low - KERB_Y).abs() < 1e-4, "{} stands at {low}", o.name);
            assert!(o.name.starts_with("person_"));
            at
        })
        .collect();
    assert_eq!(inserted.placed[3] as usize, people.len());
    assert!(people.len() >= 250, "{} people", people.len());
    let trunks: Vec<[f64; 2]> = inserted
        .objects
        .iter()
        .filter(|o| o.class == "tree")
        .map(|o| foot(&o.meshes[..1]).0)
        .collect();
    let apart = |a: [f64; 2], b: [f64; 2]| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
    // Soles centre 2 cm ahead of the spot a person took: 5 cm of slack.
    for (i, &p) in people.iter().enumerate() {
        for &q in &people[i + 1..] {
            assert!(apart(p, q) >= 2.0 * person::ROOM - 0.05, "{p:?} {q:?}");
        }
        for &t in &trunks {
            assert!(
                apart(p, t) >= person::ROOM + tree::TRUNK_ROOM - 0.05,
                "{p:?} {t:?}"
            );
        }
        // Off the roads: in a strip, at least CURB_ROOM from the curb.
        for r in &city.layout.roads {
            let px = RoadRect::of(r);
            let inside = (px.x[0] * mpp - person::CURB_ROOM + 0.05
                ..=px.x[1] * mpp + person::CURB_ROOM - 0.05)
                .contains(&p[0])
                && (px.y[0] * mpp - person::CURB_ROOM + 0.05
                    ..=px.y[1] * mpp + person::CURB_ROOM - 0.05)
                    .contains(&p[1]);
            assert!(!inside, "{p:?} on or by road {r:?}");
        }
    }
}

/// Every zebra crossing of `city` at `mpp` metres a pixel: its road's index and its
/// along-road range, metres.
fn zebras_of(city: &City, mpp: f64) -> Vec<(usize, [f64; 2])> {
    crate::model::geometry::zebras::road_stretches(&city.layout, mpp)
        .into_iter()
        .enumerate()
        .flat_map(|(i, s)| s.zebras.into_iter().map(move |(z, _)| (i, z)))
        .collect()
}

/// An object's middle seen from above (the mean of its vertices' x and z) and its lowest
/// point's height.
fn plan_middle_and_low(object: &SceneObject) -> ([f64; 2], f64) {
    let points: Vec<[f64; 3]> = object
        .meshes
        .iter()
        .flat_map(|m| &m.positions)
        .map(|p| p.map(f64::from))
        .collect();
    let low = points.iter().map(|p| p[1]).fold(f64::MAX, f64::min);
    let n = points.len() as f64;
    let mid = points
        .iter()
        .fold([0.0, 0.0], |a, p| [a[0] + p[0] / n, a[1] + p[2] / n]);
    (mid, low)
}

#[test]
fn crossers_walk_across_the_zebras_near_the_centre_line() {
    use crate::model::geometry::MARKING_Y;
    use crate::objects::person::ZEBRA_REACH;
    let city = city();
    let mpp = 0.55;
    let specs = [
        spec(EntryKind::Car, "car", 200),
        ObjectSpec {
            crossing: 1.0,
            ..spec(EntryKind::Person, "person", 40)
        },
    ];
    let inserted = insert_at(&city, mpp, &specs);
    let zebras = zebras_of(&city, mpp);
    assert!(!zebras.is_empty());
    let people: Vec<&SceneObject> = inserted
        .objects
        .iter()
        .filter(|o| o.class == "person")
        .collect();
    assert_eq!(people.len(), 40);
    assert_eq!(inserted.placed[1], 40);
    for person in people {
        let (mid, low) = plan_middle_and_low(person);
        assert!((low - MARKING_Y).abs() < 1e-4, "{} at {low}", person.name);
        // Its middle lies on a zebra, within reach of the centre line.
        let on_zebra = zebras.iter().any(|&(i, [a, b])| {
            let road = &city.layout.roads[i];
            let (along, across) = match road.axis {
                Axis::Horizontal => (mid[0], mid[1]),
                Axis::Vertical => (mid[1], mid[0]),
            };
            a - 0.1 <= along
                && along <= b + 0.1
                && (across - road.line * mpp).abs() <= ZEBRA_REACH + 0.1
        });
        assert!(on_zebra, "{} at {mid:?}", person.name);
    }
    // Without crossers an entry places no one on the road.
    let specs = [spec(EntryKind::Person, "person", 40)];
    let strips = run(&city, &specs).unwrap();
    for person in &strips.objects {
        let low = person
            .meshes
            .iter()
            .flat_map(|m| &m.positions)
            .map(|p| f64::from(p[1]))
            .fold(f64::MAX, f64::min);
        assert!((low - KERB_Y).abs() < 1e-4);
    }
}

#[test]
fn people_waiting_stand_at_the_zebras_ends_facing_the_road() {
    use crate::objects::person::{CURB_ROOM, ROOM, WAITING_DEPTH};
    let city = city();
    let mpp = 0.55;
    let zebras = zebras_of(&city, mpp);
    // Where a point in metres lies against zebra `i`'s road: along it, and how far past
    // its nearer curb (negative on the road).
    let beside = |i: usize, p: [f64; 2]| {
        let road = &city.layout.roads[i];
        let (along, across) = match road.axis {
            Axis::Horizontal => (p[0], p[1]),
            Axis::Vertical => (p[1], p[0]),
        };
        let (low, high) = (road.edges[0] * mpp, road.edges[1] * mpp);
        (along, (low - across).max(across - high))
    };
    let at_an_end = |p: [f64; 2], slack: f64| {
        zebras.iter().any(|&(i, [a, b])| {
            let (along, past) = beside(i, p);
            a - slack <= along
                && along <= b + slack
                && CURB_ROOM - slack <= past
                && past <= CURB_ROOM + WAITING_DEPTH + slack
        })
    };
    // The spots: at a zebra's end in the strip, apart, their travel straight at the road.
    let specs: [ObjectSpec; 0] = [];
    let objects_input = ObjectsInput {
        metres_per_pixel: mpp,
        ..input(&city, &specs)
    };
    let mut spots = crate::objects::ground_spots::GroundSpots::new(&objects_input);
    let mut rng = crate::rng::stream(7, "test", 0);
    let mut found = 0;
    for k in 0..20 {
        let from_curb = CURB_ROOM + WAITING_DEPTH * f64::from(k % 3) / 2.0;
        let Some(way) = spots.zebra_kerb(&mut rng, ROOM, from_curb, 40) else {
            continue;
        };
        let spot = way.spot;
        // It crosses to the same distance past the far curb.
        let far = [0, 1].map(|k| spot.position[k] + spot.travel[k] * way.reach);
        assert!((beside(spot.road as usize, far).1 - from_curb).abs() < 1e-9);
        found += 1;
        assert!(at_an_end(spot.position, 1e-6), "{:?}", spot.position);
        let road = road_of(&city, spot.road);
        let step = spot.position.map(|v| v / mpp);
        let ahead = [step[0] + spot.travel[0], step[1] + spot.travel[1]];
        let centre = |q: [f64; 2]| match road.axis {
            Axis::Horizontal => (q[1] - road.line).abs(),
            Axis::Vertical => (q[0] - road.line).abs(),
        };
        assert!(
            (centre(step) - centre(ahead) - 1.0).abs() < 1e-9,
            "{:?} from {:?}",
            spot.travel,
            spot.position
        );
    }
    assert!(found >= 15, "{found}");
    // An entry that waits: all placed, on the kerb, and those at the ends are as many
    // as the ends hold (the others stand in the strips).
    let specs = [ObjectSpec {
        waiting: 1.0,
        ..spec(EntryKind::Person, "person", 30)
    }];
    let inserted = insert_at(&city, mpp, &specs);
    assert_eq!(inserted.placed[0], 30);
    let mut waiting = 0;
    for person in &inserted.objects {
        let (mid, low) = plan_middle_and_low(person);
        assert!((low - KERB_Y).abs() < 1e-4, "{} at {low}", person.name);
        if at_an_end(mid, ROOM) {
            waiting += 1;
        }
    }
    assert!(waiting >= 15, "{waiting} of 30 at the zebras' ends");
    // Without `waiting`, the same entry's people stand along the strips: few by chance
    // at a zebra's end.
    let specs = [spec(EntryKind::Person, "person", 30)];
    let strips = insert_at(&city, mpp, &specs);
    let by_chance = strips
        .objects
        .iter()
        .filter(|person| at_an_end(plan_middle_and_low(person).0, ROOM))
        .count();
    assert!(by_chance < waiting / 2, "{by_chance} vs {waiting}");
}

#[test]
fn zebra_spots_travel_across_their_road_and_never_overlap() {
    let city = city();
    let specs: [ObjectSpec; 0] = [];
    let input = input(&city, &specs);
    let mut spots = crate::objects::ground_spots::GroundSpots::new(&input);
    let mut rng = crate::rng::stream(7, "test", 0);
    let mut ways: Vec<[[f64; 2]; 2]> = Vec::new();
    for _ in 0..30 {
        let Some(way) = spots.zebra(&mut rng, 0.6, 2.4, 0.45, 40) else {
            continue;
        };
        let spot = way.spot;
        let road = road_of(&city, spot.road);
        let (across, along) = match road.axis {
            Axis::Horizontal => ([0.0, 1.0], [1.0, 0.0]),
            Axis::Vertical => ([1.0, 0.0], [0.0, 1.0]),
        };
        let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
        let d = dot(spot.travel, across);
        assert!((d.abs() - 1.0).abs() < 1e-12, "{:?}", spot.travel);
        // In the half of its zebra on its right (heading h, the right is (−h.z, h.x)).
        let right = [-spot.travel[1], spot.travel[0]];
        let [a, b] = way.crossing.zebra;
        let from_middle = dot(spot.position, along) - (a + b) / 2.0;
        assert!(
            from_middle * dot(right, along) >= 0.6 - 1e-9,
            "{from_middle}"
        );
        // To 0.45 m past the far curb.
        let mpp = input.metres_per_pixel;
        let end = dot(spot.position, across) + d * way.reach;
        let curb = if d > 0.0 {
            road.edges[1]
        } else {
            road.edges[0]
        } * mpp;
        assert!((end - curb - d * 0.45).abs() < 1e-9, "{end} {curb}");
        // The ways (start to end, 0.6 either side) never share ground.
        let (c0, l) = (dot(spot.position, across), dot(spot.position, along));
        let (l, c) = ([l - 0.6, l + 0.6], [c0.min(end) - 0.6, c0.max(end) + 0.6]);
        let mine = match road.axis {
            Axis::Horizontal => [l, c],
            Axis::Vertical => [c, l],
        };
        let apart = |a: [f64; 2], b: [f64; 2]| a[1] <= b[0] + 1e-9 || b[1] <= a[0] + 1e-9;
        for w in &ways {
            assert!(
                apart(mine[0], w[0]) || apart(mine[1], w[1]),
                "{mine:?} {w:?}"
            );
        }
        ways.push(mine);
    }
    assert!(ways.len() >= 12, "{}", ways.len());
}

/// The objects of `specs` inserted into `city` at `mpp` metres per pixel.
fn insert_at(city: &City, mpp: f64, specs: &[ObjectSpec]) -> Inserted {
    insert(&ObjectsInput {
        metres_per_pixel: mpp,
        ..input(city, specs)
    })
    .unwrap()
}

/// The road of `city` with id `id`.
fn road_of(city: &City, id: u32) -> &crate::model::Road {
    city.layout.roads.iter().find(|r| r.id == id).unwrap()
}

#[test]
fn a_walker_walks_up_to_what_stands_in_its_way_but_not_to_other_walkers() {
    use crate::objects::ground_spots::{Footprint, GroundSpots};
    let city = city();
    let specs: [ObjectSpec; 0] = [];
    let input = input(&city, &specs);
    let mut spots = GroundSpots::new(&input);
    let mut rng = crate::rng::stream(7, "test", 0);
    let mut checked = 0;
    for _ in 0..40 {
        let Some(spot) = spots.strip_at(&mut rng, 0.6, 1.0, 40) else {
            continue;
        };
        spots.mark_walker();
        let (p, t) = (spot.position, spot.travel);
        let free = spots.free_run(p, t, 0.6, spot.road);
        if free < 8.0 {
            continue;
        }
        // Another walker 5 m ahead is no obstacle (it walks on); a post 0.3 m aside of
        // the walker's line 6 m ahead is.
        let at = |d: f64, aside: f64| {
            [
                p[0] + t[0] * d - t[1] * aside,
                p[1] + t[1] * d + t[0] * aside,
            ]
        };
        if !spots.claim(Footprint::Circle(at(5.0, 0.0), 0.6)) {
            continue;
        }
        spots.mark_walker();
        assert_eq!(spots.free_run(p, t, 0.6, spot.road), free);
        if !spots.claim(Footprint::Circle(at(6.5, 0.3), 0.2)) {
            continue;
        }
        let want = 6.5 - (0.8f64 * 0.8 - 0.3 * 0.3).sqrt();
        let got = spots.free_run(p, t, 0.6, spot.road);
        assert!((got - want.min(free)).abs() < 1e-9, "{got} vs {want}");
        // One beside its band is not in the way.
        let post = at(3.0, 1.5);
        if spots.claim(Footprint::Circle(post, 0.2)) {
            assert_eq!(spots.free_run(p, t, 0.6, spot.road), got);
        }
        checked += 1;
    }
    assert!(checked >= 5, "{checked}");
}
