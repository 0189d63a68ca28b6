//! Poles at the roadside: traffic signs, street-name signs, traffic lights.

use std::collections::BTreeSet;

use super::*;
use crate::model::Axis;
use crate::model::geometry::{KERB_Y, RoadRect, cross, dot, sub};
use crate::objects::ground_spots::travel;
use crate::spec::{Palette, SignKind};

#[test]
fn signs_stand_on_the_strip_facing_oncoming_traffic() {
    let city = city();
    let inserted = run(&city, &[spec(EntryKind::Sign, "traffic_sign", 40)]).unwrap();
    // Each sign is its pole (class `pole`) and then its plate: face and back.
    assert_eq!(inserted.objects.len(), 80);
    let strip = Palette::default().strip.0;
    let mut kinds = BTreeSet::new();
    for (k, pair) in inserted.objects.chunks_exact(2).enumerate() {
        let [pole_object, object] = pair else {
            unreachable!("chunks of two")
        };
        assert_eq!(
            (pole_object.kind, pole_object.class.as_str()),
            (crate::model::ObjectKind::SignPole, "pole")
        );
        assert_eq!(object.kind, crate::model::ObjectKind::Sign);
        let ([pole], [face, back]) = (&pole_object.meshes[..], &object.meshes[..]) else {
            panic!("{}: not one pole mesh and a face and a back", object.name)
        };
        kinds.insert(inserted.materials[face.material as usize].name.clone());
        assert!(inserted.materials[face.material as usize].texture.is_some());
        assert!(inserted.materials[back.material as usize].texture.is_none());
        // The pole's axis: the mean of its corners.
        let n = pole.positions.len() as f64;
        let foot = [
            pole.positions.iter().map(|p| f64::from(p[0])).sum::<f64>() / n,
            pole.positions.iter().map(|p| f64::from(p[2])).sum::<f64>() / n,
        ];
        let min_y = pole
            .positions
            .iter()
            .map(|p| f64::from(p[1]))
            .fold(f64::INFINITY, f64::min);
        assert!((min_y - KERB_Y).abs() < 1e-5);
        let pixel = city.image.get_pixel(foot[0] as u32, foot[1] as u32).0;
        assert_eq!(pixel, strip, "{} at {foot:?}", object.name);
        for lamp in &city.lamps {
            let (dx, dz) = (lamp.position[0] - foot[0], lamp.position[1] - foot[1]);
            let d = (dx * dx + dz * dz).sqrt();
            assert!(d >= 2.0, "{} {d} m from a lamp", object.name);
        }
        // The road it signs (at a corner another is as near), the side the sign stands
        // on, its lane's traffic.
        let signed = inserted.sign_faces[&(2 * k + 1)].road;
        let road = &city.layout.roads[signed as usize];
        let rect = RoadRect::of(road);
        let dx = (rect.x[0] - foot[0]).max(foot[0] - rect.x[1]).max(0.0);
        let dy = (rect.y[0] - foot[1]).max(foot[1] - rect.y[1]).max(0.0);
        let gap = match road.axis {
            Axis::Horizontal => dy,
            Axis::Vertical => dx,
        };
        assert!(gap <= 8.0);
        let high = match road.axis {
            Axis::Horizontal => foot[1] > road.line,
            Axis::Vertical => foot[0] > road.line,
        };
        let h = travel(road.axis, high);
        let normal = face.normals[0].map(f64::from);
        assert_eq!(
            [normal[0], normal[2]],
            [-h[0] + 0.0, -h[1] + 0.0],
            "{}",
            object.name
        );
        for t in face.indices.chunks(3) {
            let p = |k: usize| face.positions[t[k] as usize].map(f64::from);
            assert!(dot(cross(sub(p(1), p(0)), sub(p(2), p(0))), normal) > 0.0);
        }
    }
    assert!(kinds.len() >= 5, "{kinds:?}");
}

#[test]
fn signs_only_of_the_listed_kinds() {
    let city = city();
    let specs = [ObjectSpec {
        signs: vec![SignKind::Stop],
        ..spec(EntryKind::Sign, "stop_sign", 5)
    }];
    let inserted = run(&city, &specs).unwrap();
    let faces: BTreeSet<&str> = inserted
        .objects
        .iter()
        .filter(|o| o.kind == crate::model::ObjectKind::Sign)
        .map(|o| {
            inserted.materials[o.meshes[0].material as usize]
                .name
                .as_str()
        })
        .collect();
    assert_eq!(faces, BTreeSet::from(["sign_stop"]));
    // One texture for all five stop signs.
    assert_eq!(inserted.textures.len(), 1);
}

#[test]
fn street_name_signs_stand_at_corners_and_name_each_street_alike() {
    let city = city();
    let specs = [ObjectSpec {
        letter_height: [0.18, 0.24],
        ..spec(EntryKind::StreetName, "text", 12)
    }];
    let inserted = run(&city, &specs).unwrap();
    assert_eq!(inserted.placed, [12]);
    let poles = inserted
        .objects
        .iter()
        .filter(|o| o.class == "pole")
        .count();
    let texts: Vec<usize> = (0..inserted.objects.len())
        .filter(|&i| inserted.objects[i].class == "text")
        .collect();
    assert_eq!((poles, texts.len()), (12, 48));
    // Each plate face: a name and a suffix, two word quads, above the pole's top, the
    // street style; the two faces of a plate look opposite ways.
    let mut names = BTreeSet::new();
    for &i in &texts {
        let info = &inserted.info[i];
        let text = info.text.as_deref().unwrap();
        let (word, suffix) = text.split_once(' ').unwrap();
        assert!(
            crate::objects::street_names::SUFFIXES.contains(&suffix),
            "{text}"
        );
        assert!(!word.is_empty());
        names.insert(text.to_owned());
        assert_eq!(info.corners.len(), 2, "{text}");
        assert_eq!(info.attributes["text_style"], "street");
        for quad in &info.corners {
            for p in quad {
                assert!(
                    p[1] > KERB_Y + crate::objects::street_names::POLE_HEIGHT,
                    "{p:?}"
                );
            }
        }
    }
    // One name per road: at most as many names as roads.
    assert!(names.len() <= city.layout.roads.len(), "{names:?}");
    assert!(names.len() >= 2);
    // Placing is deterministic; a larger count than corners falls short, never panics.
    assert_eq!(run(&city, &specs).unwrap(), inserted);
    let many = [spec(EntryKind::StreetName, "text", 10_000)];
    let all = run(&city, &many).unwrap();
    assert!(all.placed[0] > 12 && all.placed[0] < 10_000);
}

#[test]
fn traffic_lights_stand_at_corners_with_one_head_along_each_road() {
    use crate::objects::traffic_lights::{HEAD_OFFSET, HEAD_SIZE, POLE_HEIGHT};
    let city = city();
    let specs = [spec(EntryKind::TrafficLight, "traffic_light", 10)];
    let inserted = run(&city, &specs).unwrap();
    assert_eq!(inserted.placed, [10]);
    let objects = &inserted.objects;
    assert_eq!(objects.len(), 30);
    // Bounding box of an object's meshes, and of one mesh.
    let bounds = mesh_bounds;
    let centre = |(lo, hi): ([f64; 3], [f64; 3])| [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0);
    let mut states = BTreeSet::new();
    for pole_and_heads in objects.chunks(3) {
        let [pole, heads @ ..] = pole_and_heads else {
            unreachable!()
        };
        assert!(pole.name.starts_with("signal_pole_") && pole.class == "pole");
        let (lo, hi) = bounds(&pole.meshes);
        assert!((hi[1] - lo[1] - POLE_HEIGHT).abs() < 1e-4);
        let foot = centre((lo, hi));
        let mut offsets = Vec::new();
        let mut signals = Vec::new();
        for head in heads {
            assert!(head.name.starts_with("traffic_light_"), "{}", head.name);
            assert_eq!(head.class, "traffic_light");
            let i = objects.iter().position(|o| o.name == head.name).unwrap();
            let state = inserted.info[i].attributes["state"].clone();
            // The body: a head's height, HEAD_OFFSET out from the pole along x or z.
            let body = centre(bounds(&head.meshes[..1]));
            let d = [body[0] - foot[0], body[2] - foot[2]];
            assert!(
                (d[0].abs() - HEAD_OFFSET).abs() < 1e-3 && d[1].abs() < 1e-3
                    || (d[1].abs() - HEAD_OFFSET).abs() < 1e-3 && d[0].abs() < 1e-3,
                "{d:?}"
            );
            let (blo, bhi) = bounds(&head.meshes[..1]);
            assert!((bhi[1] - blo[1] - HEAD_SIZE[0]).abs() < 1e-4);
            // Three lenses in front of the body, red over amber over green; only the one
            // the state names glows.
            let lenses = &head.meshes[2..];
            assert_eq!(lenses.len(), 3);
            let mut lit = Vec::new();
            let mut last_y = f64::INFINITY;
            for (lens, colour) in lenses.iter().zip(["red", "amber", "green"]) {
                let material = &inserted.materials[lens.material as usize];
                assert!(material.name.starts_with(&format!("signal_{colour}_")));
                let c = centre(bounds(std::slice::from_ref(lens)));
                assert!(c[1] < last_y);
                last_y = c[1];
                let out = [c[0] - foot[0], c[2] - foot[2]];
                assert!(out[0] * d[0] + out[1] * d[1] > HEAD_OFFSET * HEAD_OFFSET);
                if material.emissive.iter().any(|&e| e > 0.0) {
                    lit.push(colour);
                }
            }
            assert_eq!(lit, [state.as_str()]);
            offsets.push(d);
            signals.push(state.clone());
            states.insert(state);
        }
        // One head along each road, away from each other; one road has red.
        assert!(offsets[0][0] * offsets[1][0] + offsets[0][1] * offsets[1][1] == 0.0);
        signals.sort();
        assert!(
            signals == ["green", "red"] || signals == ["amber", "red"],
            "{signals:?}"
        );
    }
    assert!(
        states.contains("red") && states.contains("green"),
        "{states:?}"
    );
    // Deterministic; a larger count than corners falls short, never panics.
    assert_eq!(run(&city, &specs).unwrap(), inserted);
    let many = [spec(EntryKind::TrafficLight, "traffic_light", 10_000)];
    let all = run(&city, &many).unwrap();
    assert!(all.placed[0] >= 10 && all.placed[0] < 10_000);
}

/// The rules on the test city, every type drawn: stop and yield at the mouths of the roads
/// giving way and priority-road signs at the others' (one a mouth, at the stop line, facing
/// the traffic driving in), crossing signs beside the zebra, warnings 30–50 m before a
/// stop line, speed limits 5–15 m past a zebra facing the traffic leaving, and signs off
/// the mouths never within the spacing of one of their type on the same road side.
#[test]
fn signs_stand_by_the_rules() {
    use crate::objects::sign_rules::{LIMIT_AFTER, Mouth, WARNING_BEFORE, mouths};
    use crate::objects::traffic_signs::SPACING;
    let city = city();
    let inserted = run(&city, &[spec(EntryKind::Sign, "traffic_sign", 150)]).unwrap();
    let mouths = mouths(&city.layout, 1.0, SEED);
    let faces: Vec<_> = inserted.sign_faces.values().collect();
    assert!(faces.len() >= 120, "{}", faces.len());
    // Where a face stands along mouth m's road, and whether it faces m's traffic coming
    // in (1), leaving (-1) or neither.
    let along = |m: &Mouth, c: [f64; 3]| match m.axis {
        Axis::Horizontal => c[0],
        Axis::Vertical => c[2],
    };
    let facing = |m: &Mouth, n: [f64; 3]| {
        let t = travel(m.axis, m.in_high());
        let d = -(n[0] * t[0] + n[2] * t[1]);
        if d > 0.99 {
            1
        } else if d < -0.99 {
            -1
        } else {
            0
        }
    };
    let mut at_mouth = vec![0; mouths.len()];
    let mut counts: BTreeMap<&str, u32> = BTreeMap::new();
    for f in &faces {
        let on_road = mouths.iter().enumerate().filter(|(_, m)| m.road == f.road);
        let (rule, ok) = match f.kind {
            SignKind::Stop | SignKind::Yield | SignKind::PriorityRoad => {
                let priority = f.kind == SignKind::PriorityRoad;
                let hit = on_road.clone().find(|(_, m)| {
                    let back = (along(m, f.centre) - m.stop) * -m.dir;
                    m.priority == priority && facing(m, f.normal) == 1 && (0.0..7.0).contains(&back)
                });
                if let Some((k, _)) = hit {
                    at_mouth[k] += 1;
                }
                ("mouth", hit.is_some())
            }
            SignKind::PedestrianCrossing => (
                "zebra",
                on_road.clone().any(|(_, m)| {
                    let a = along(m, f.centre);
                    facing(m, f.normal) == 1 && (m.zebra[0]..=m.zebra[1]).contains(&a)
                }),
            ),
            SignKind::Pedestrians | SignKind::Children => (
                "before",
                on_road.clone().any(|(_, m)| {
                    let back = (along(m, f.centre) - m.stop) * -m.dir;
                    facing(m, f.normal) == 1
                        && (WARNING_BEFORE[0] - 0.1..=WARNING_BEFORE[1] + 0.1).contains(&back)
                }),
            ),
            SignKind::SpeedLimit => (
                "after",
                on_road.clone().any(|(_, m)| {
                    let past = (along(m, f.centre) - m.stop) * -m.dir;
                    facing(m, f.normal) == -1
                        && (LIMIT_AFTER[0] - 0.1..=LIMIT_AFTER[1] + 0.1).contains(&past)
                }),
            ),
            _ => ("free", true),
        };
        assert!(ok, "{:?} at {:?} breaks its rule", f.kind, f.centre);
        *counts.entry(rule).or_default() += 1;
        if rule != "mouth" && rule != "zebra" {
            for g in faces
                .iter()
                .filter(|g| g.kind == f.kind && g.road == f.road && !std::ptr::eq(**g, *f))
            {
                let (dx, dz) = (f.centre[0] - g.centre[0], f.centre[2] - g.centre[2]);
                let d = (dx * dx + dz * dz).sqrt();
                let same_way = f.normal[0] * g.normal[0] + f.normal[2] * g.normal[2] > 0.99;
                assert!(
                    !same_way || d >= SPACING,
                    "{:?}: two {d:.1} m apart",
                    f.kind
                );
            }
        }
    }
    assert!(at_mouth.iter().all(|&n| n <= 1), "{at_mouth:?}");
    for rule in ["mouth", "zebra", "before", "after", "free"] {
        assert!(counts.get(rule).is_some_and(|&n| n >= 2), "{counts:?}");
    }
}
