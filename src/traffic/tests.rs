use std::collections::BTreeMap;

use image::RgbImage;

use super::*;
use crate::model::{Facade, FacadeSet, Roof, SceneObject, Texture};
use crate::objects::{ObjectsInput, insert};
use crate::spec::ObjectSpec;
use crate::test_support::{TestCity, test_city};

const SEED: u64 = 11;

/// A city with cars and ridden bicycles in its lanes and signal poles at its corners:
/// its layout, objects and their roles.
fn city() -> (ParsedLayout, Vec<SceneObject>, Vec<Option<TrafficRole>>) {
    let texture = Texture::from_rgb("t", RgbImage::new(4, 4));
    let facades = FacadeSet {
        facades: vec![Facade {
            name: "a".to_owned(),
            floors: 4,
            height: 12.0,
            width: 12.0,
            molding: [0, 0, 0],
            colour: [128, 128, 128],
            roof: 0,
            windows: Vec::new(),
            texture: texture.clone(),
        }],
        roofs: vec![Roof {
            name: "r".to_owned(),
            colour: [0, 0, 0],
            tile: 3.0,
            texture,
        }],
    };
    let TestCity {
        layout,
        lamps,
        buildings,
        ..
    } = test_city(SEED, &[12.0]);
    let specs: Vec<ObjectSpec> = [
        "kind = \"car\"\nlabel = \"car\"\ncount = 160\nparked = 0.0\n",
        "kind = \"bicycle\"\nlabel = \"bicycle\"\ncount = 40\nparked = 0.0\n",
        "kind = \"traffic_light\"\nlabel = \"traffic_light\"\ncount = 12\n",
        "kind = \"tree\"\nlabel = \"tree\"\ncount = 60\n",
        "kind = \"person\"\nlabel = \"person\"\ncount = 300\ncrossing = 0.1\nwaiting = 0.1\n",
    ]
    .iter()
    .map(|t| toml::from_str(t).unwrap())
    .collect();
    let inserted = insert(&ObjectsInput {
        specs: &specs,
        layout: &layout,
        lamps: &lamps,
        buildings: &buildings,
        facades: &facades,
        widths: None,
        meshes: &BTreeMap::new(),
        metres_per_pixel: 1.0,
        seed: SEED,
    })
    .unwrap();
    let roles = inserted.info.iter().map(|i| i.traffic.clone()).collect();
    (layout, inserted.objects, roles)
}

fn traffic(ego: &[(f64, [f64; 2])]) -> (Traffic, Vec<Option<TrafficRole>>, ParsedLayout) {
    traffic_with(&TrafficSpec::default(), ego)
}

/// The city's traffic under `spec`.
fn traffic_with(
    spec: &TrafficSpec,
    ego: &[(f64, [f64; 2])],
) -> (Traffic, Vec<Option<TrafficRole>>, ParsedLayout) {
    let (layout, _, roles) = city();
    let traffic = plan(&TrafficInput {
        spec,
        layout: &layout,
        metres_per_pixel: 1.0,
        roles: &roles,
        lamps: Some([[1, 2], [3, 4], [5, 6]]),
        seed: SEED,
        ego,
    });
    (traffic, roles, layout)
}

/// The times the tests look at: 0 to 120 s every 0.1 s.
fn times() -> impl Iterator<Item = f64> {
    (0..=1200).map(|k| f64::from(k) / 10.0)
}

#[test]
fn the_city_has_lanes_heads_and_carried_objects() {
    let (t, roles, _) = traffic(&[]);
    let vehicles = roles
        .iter()
        .filter(|r| matches!(r, Some(TrafficRole::Vehicle(_))))
        .count();
    let walking = roles
        .iter()
        .filter(|r| matches!(r, Some(TrafficRole::Pedestrian(_))))
        .count();
    let drivers: usize = t.lanes.iter().map(|l| l.drivers.len()).sum();
    assert!(vehicles > 60, "{vehicles}");
    assert!(walking > 100, "{walking}");
    assert_eq!(drivers, vehicles + walking);
    assert!(t.lanes.iter().any(|l| l.drivers.len() >= 3));
    assert!(t.heads.len() >= 20, "{}", t.heads.len());
    // Every ridden bicycle carries its rider.
    assert!(t.carried.len() >= 20, "{}", t.carried.len());
}

#[test]
fn at_time_zero_and_before_everything_stands_where_the_scene_has_it() {
    let (t, roles, _) = traffic(&[]);
    for time in [-5.0, 0.0] {
        let m = t.at(time);
        let movers = roles
            .iter()
            .filter(|r| {
                matches!(
                    r,
                    Some(
                        TrafficRole::Vehicle(_)
                            | TrafficRole::Carried { .. }
                            | TrafficRole::Pedestrian(_)
                    )
                )
            })
            .count();
        assert_eq!(m.moves.len(), movers);
        assert!(m.moves.iter().all(|(_, o)| *o == [0.0; 3]), "{time}");
        assert!(m.moves.windows(2).all(|w| w[0].0 < w[1].0));
    }
}

#[test]
fn traffic_moves_keeps_its_lane_and_never_reverses() {
    let (t, roles, _) = traffic(&[]);
    let mut last: BTreeMap<u32, [f64; 3]> = BTreeMap::new();
    for time in times() {
        for (id, o) in t.at(time).moves {
            let Some(TrafficRole::Vehicle(v)) = &roles[id as usize - 1] else {
                continue;
            };
            let run = o[0] * v.travel[0] + o[2] * v.travel[1];
            // Along its travel only: nothing sideways, nothing up.
            assert!((o[0] * v.travel[1] - o[2] * v.travel[0]).abs() < 1e-9 && o[1] == 0.0);
            if let Some(p) = last.get(&id) {
                let before = p[0] * v.travel[0] + p[2] * v.travel[1];
                assert!(run >= before - 1e-9, "{id} went back at {time}");
                // Never faster than the fastest vehicle (a follower held back catches up
                // at the speed of the one ahead).
                assert!(
                    run - before <= 45.0 / 3.6 * 0.1 + 1e-9,
                    "{id} too fast at {time}"
                );
            }
            last.insert(id, o);
        }
    }
    // Most vehicles got somewhere in two minutes.
    let far = last
        .values()
        .filter(|o| o[0].abs() + o[2].abs() > 20.0)
        .count();
    assert!(far * 2 > last.len(), "{far} of {}", last.len());
}

/// Each vehicle's rectangle of road at time `time`: `(x, z)` ranges and its road's axis.
fn footprints(
    t: &Traffic,
    roles: &[Option<TrafficRole>],
    time: f64,
) -> Vec<(u32, [[f64; 2]; 2], f64)> {
    t.at(time)
        .moves
        .into_iter()
        .filter_map(|(id, o)| {
            let Some(TrafficRole::Vehicle(v)) = &roles[id as usize - 1] else {
                return None;
            };
            let c = [v.centre[0] + o[0], v.centre[1] + o[2]];
            let (hx, hz) = if v.travel[0] != 0.0 {
                (v.half[0], v.half[1])
            } else {
                (v.half[1], v.half[0])
            };
            let axis = if v.travel[0] != 0.0 { 0.0 } else { 1.0 };
            Some((id, [[c[0] - hx, c[0] + hx], [c[1] - hz, c[1] + hz]], axis))
        })
        .collect()
}

fn overlap(a: [[f64; 2]; 2], b: [[f64; 2]; 2]) -> bool {
    a[0][0] < b[0][1] && b[0][0] < a[0][1] && a[1][0] < b[1][1] && b[1][0] < a[1][1]
}

#[test]
fn no_two_vehicles_ever_overlap_not_even_crossing_a_junction() {
    let (t, roles, layout) = traffic(&[]);
    let junctions = junctions::junctions(&layout, 1.0);
    let mut crossings = 0;
    for time in times() {
        let f = footprints(&t, &roles, time);
        for (i, a) in f.iter().enumerate() {
            for b in &f[i + 1..] {
                assert!(!overlap(a.1, b.1), "{} and {} at {time}", a.0, b.0);
            }
        }
        // Cross traffic never shares a junction: vehicles of both roads in one at once.
        for j in &junctions {
            let rect = [j.x, j.z];
            let inside: Vec<f64> = f
                .iter()
                .filter(|v| overlap(v.1, rect))
                .map(|v| v.2)
                .collect();
            crossings += inside.len();
            assert!(
                !(inside.contains(&0.0) && inside.contains(&1.0)),
                "junction {:?} at {time}: {:?}",
                j.roads,
                f.iter().filter(|v| overlap(v.1, rect)).collect::<Vec<_>>()
            );
        }
    }
    assert!(crossings > 100, "{crossings}");
}

#[test]
fn signal_heads_show_their_junctions_cycle_lamp_by_lamp() {
    let (t, _, _) = traffic(&[]);
    let mut seen = BTreeMap::new();
    for time in times() {
        let m = t.at(time);
        assert_eq!(m.signals.len(), t.heads.len());
        assert_eq!(m.recolour.len(), 3 * t.heads.len());
        for (head, (id, state)) in t.heads.iter().zip(&m.signals) {
            assert_eq!(head.instance, *id);
            let lit: Vec<u32> = m
                .recolour
                .iter()
                .filter(|r| r.instance == *id && [1, 3, 5].contains(&r.to))
                .map(|r| r.to)
                .collect();
            let expected = match *state {
                "red" => 1,
                "amber" => 3,
                _ => 5,
            };
            assert_eq!(lit, vec![expected], "{id} at {time}");
            seen.entry(*id).or_insert_with(Vec::new).push(*state);
        }
    }
    // Two minutes are three cycles: every head goes through all three.
    for states in seen.values() {
        for s in ["red", "amber", "green"] {
            assert!(states.contains(&s));
        }
    }
    // The two heads of a pole look along different roads: never both green.
    for time in times() {
        let m = t.at(time);
        for pair in m.signals.chunks(2) {
            assert!(!(pair.len() == 2 && pair[0].1 == "green" && pair[1].1 == "green"));
        }
    }
}

#[test]
fn a_drive_crosses_its_junctions_on_green() {
    let (_, _, layout) = traffic(&[]);
    let road = layout
        .roads
        .iter()
        .find(|r| r.axis == Axis::Horizontal)
        .unwrap();
    let z = road.line + 2.0;
    // 10 m/s along the road for 30 s.
    let ego: Vec<(f64, [f64; 2])> = (0..300)
        .map(|k| {
            let time = f64::from(k) / 10.0;
            (time, [road.start + 10.0 * time, z])
        })
        .collect();
    let (t, _, _) = traffic(&ego);
    let junctions = junctions::junctions(&layout, 1.0);
    let mut crossed = 0;
    for (j, junction) in junctions.iter().enumerate() {
        for (time, eye) in &ego {
            if junction.distance(*eye) == 0.0 {
                crossed += 1;
                assert_eq!(t.schedules[j].state(Axis::Horizontal, *time), Signal::Green);
                assert_eq!(t.schedules[j].state(Axis::Vertical, *time), Signal::Red);
            }
        }
    }
    assert!(crossed > 10, "{crossed}");
}

#[test]
fn a_schedule_lets_a_vehicle_in_only_on_green_with_time_to_clear() {
    let s = Schedule {
        phase: 3.0,
        cycle: 40.0,
    };
    assert_eq!(s.green(), 15.0);
    for k in 0..4000 {
        let t = f64::from(k) / 50.0 - 20.0;
        for axis in [Axis::Horizontal, Axis::Vertical] {
            for clear in [1.0, 4.0, 12.0] {
                let go = s.entry(axis, t, clear);
                assert!(go >= t);
                assert_eq!(s.state(axis, go), Signal::Green, "{t} {clear}");
                // Clears before the other road's green.
                let other = match axis {
                    Axis::Horizontal => Axis::Vertical,
                    Axis::Vertical => Axis::Horizontal,
                };
                assert!(
                    s.state(other, go + clear - 1e-9) != Signal::Green,
                    "{t} {clear}"
                );
            }
        }
    }
}

/// `[traffic]` with a cycle long enough to walk across the test city's roads (32 m wide
/// at its 1 m a pixel: 27 s at a walk) in the other road's green.
fn wide_roads() -> TrafficSpec {
    TrafficSpec {
        cycle: 80.0,
        ..TrafficSpec::default()
    }
}

/// Each walking person's circle at time `time`: `(instance, centre, radius)`.
fn people(t: &Traffic, roles: &[Option<TrafficRole>], time: f64) -> Vec<(u32, [f64; 2], f64)> {
    t.at(time)
        .moves
        .into_iter()
        .filter_map(|(id, o)| {
            let Some(TrafficRole::Pedestrian(w)) = &roles[id as usize - 1] else {
                return None;
            };
            Some((id, [w.centre[0] + o[0], w.centre[1] + o[2]], w.room))
        })
        .collect()
}

#[test]
fn people_walk_on_and_cross_never_touching_each_other_or_a_vehicle() {
    let (t, roles, _) = traffic_with(&wide_roads(), &[]);
    let mut last: BTreeMap<u32, [f64; 2]> = BTreeMap::new();
    for time in times() {
        let p = people(&t, &roles, time);
        // Circles of people apart (touching at most), and off every vehicle's rectangle.
        for (i, a) in p.iter().enumerate() {
            for b in &p[i + 1..] {
                let d = ((a.1[0] - b.1[0]).powi(2) + (a.1[1] - b.1[1]).powi(2)).sqrt();
                assert!(
                    d >= a.2 + b.2 - 1e-6,
                    "{} and {} {d} apart at {time}",
                    a.0,
                    b.0
                );
            }
            for v in footprints(&t, &roles, time) {
                let [x, z] = v.1;
                let dx = a.1[0] - a.1[0].clamp(x[0], x[1]);
                let dz = a.1[1] - a.1[1].clamp(z[0], z[1]);
                assert!(
                    dx * dx + dz * dz >= a.2 * a.2 - 1e-6,
                    "{} and {} at {time}",
                    a.0,
                    v.0
                );
            }
            // Straight on along its travel, never back, at a walk.
            let Some(TrafficRole::Pedestrian(w)) = &roles[a.0 as usize - 1] else {
                unreachable!()
            };
            let moved = [a.1[0] - w.centre[0], a.1[1] - w.centre[1]];
            assert!((moved[0] * w.travel[1] - moved[1] * w.travel[0]).abs() < 1e-9);
            let run = moved[0] * w.travel[0] + moved[1] * w.travel[1];
            assert!(run <= w.reach + 1e-9, "{} beyond its reach at {time}", a.0);
            if let Some(before) = last.get(&a.0) {
                let step = (a.1[0] - before[0]) * w.travel[0] + (a.1[1] - before[1]) * w.travel[1];
                assert!(
                    (-1e-9..=5.4 / 3.6 * 0.1 + 1e-9).contains(&step),
                    "{} at {time}",
                    a.0
                );
            }
            last.insert(a.0, a.1);
        }
    }
    // Most people on the sidewalks got somewhere, and people crossed from both the zebras
    // and their ends.
    let moved = |pick: &dyn Fn(&Walk) -> bool| {
        let (mut all, mut far) = (0, 0);
        for (id, p) in &last {
            let Some(TrafficRole::Pedestrian(w)) = &roles[*id as usize - 1] else {
                continue;
            };
            if pick(w) {
                all += 1;
                let d = ((p[0] - w.centre[0]).powi(2) + (p[1] - w.centre[1]).powi(2)).sqrt();
                far += usize::from(d > 2.0 && (d - w.reach).abs() < 1e-6 || d > 10.0);
            }
        }
        (far, all)
    };
    let (far, all) = moved(&|w| w.crossing.is_none());
    assert!(far * 2 > all, "{far} of {all} on the sidewalks");
    let (far, all) = moved(&|w| w.crossing.is_some_and(|c| c.waiting));
    assert!(
        all >= 5 && far * 10 >= all * 9,
        "{far} of {all} waiting crossed"
    );
    let (far, all) = moved(&|w| w.crossing.is_some_and(|c| !c.waiting));
    assert!(
        all >= 5 && far == all,
        "{far} of {all} on the zebras crossed"
    );
}

#[test]
fn people_wait_at_the_kerb_while_the_road_they_cross_may_go() {
    let (t, roles, layout) = traffic_with(&wide_roads(), &[]);
    let junctions = junctions::junctions(&layout, 1.0);
    let mut crossing = 0;
    for time in times() {
        for (id, c, _) in people(&t, &roles, time) {
            let Some(TrafficRole::Pedestrian(w)) = &roles[id as usize - 1] else {
                unreachable!()
            };
            if !w.crossing.is_some_and(|z| z.waiting) {
                continue;
            }
            let road = layout.roads.iter().find(|r| r.id == w.road).unwrap();
            let across = match road.axis {
                Axis::Horizontal => c[1],
                Axis::Vertical => c[0],
            };
            if !(road.edges[0] < across && across < road.edges[1]) {
                continue;
            }
            // On the road: the road it crosses is red at its junction.
            crossing += 1;
            let j = junctions
                .iter()
                .enumerate()
                .min_by(|a, b| a.1.distance(w.centre).total_cmp(&b.1.distance(w.centre)))
                .unwrap()
                .0;
            assert_eq!(
                t.schedules[j].state(road.axis, time),
                Signal::Red,
                "{id} at {time}"
            );
        }
    }
    assert!(crossing > 100, "{crossing}");
}

#[test]
fn a_drive_never_meets_a_person_crossing() {
    let (_, _, layout) = traffic(&[]);
    for road in layout
        .roads
        .iter()
        .filter(|r| r.axis == Axis::Horizontal)
        .take(3)
    {
        // 8 m/s along the road's right-hand lane from its start, for 40 s.
        let z = road.line + 4.0;
        let ego: Vec<(f64, [f64; 2])> = (0..400)
            .map(|k| {
                let time = f64::from(k) / 10.0;
                (time, [road.start + 8.0 * time, z])
            })
            .collect();
        let (t, roles, _) = traffic_with(&wide_roads(), &ego);
        for (time, eye) in &ego {
            for (id, c, r) in people(&t, &roles, *time) {
                let d = ((c[0] - eye[0]).powi(2) + (c[1] - eye[1]).powi(2)).sqrt();
                assert!(d > r, "{id} at {time}: {d} m from the camera");
            }
        }
    }
}
