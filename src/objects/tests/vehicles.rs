//! Cars, trees and bicycles: where they stand, what they keep clear of, their lights.

use super::*;
use crate::model::geometry::{KERB_Y, ROAD_Y, RoadRect};

#[test]
fn cars_and_trees_never_overlap_anything_standing() {
    let city = city();
    let specs = [
        spec(EntryKind::Sign, "traffic_sign", 60),
        spec(EntryKind::Tree, "tree", 200),
        spec(EntryKind::Car, "car", 400),
    ];
    // At the example specs' scale: 4.4 m strips, so big crowns stand at the curb.
    let mpp = 0.55;
    let inserted = insert(&ObjectsInput {
        metres_per_pixel: mpp,
        ..input(&city, &specs)
    })
    .unwrap();
    // Ground boxes (x0, x1, z0, z1) and heights (y0, y1) of meshes, from their vertices.
    let bounds = |meshes: &[crate::model::Mesh]| {
        let mut b = [f64::MAX, f64::MIN, f64::MAX, f64::MIN];
        let mut y = [f64::MAX, f64::MIN];
        for p in meshes.iter().flat_map(|m| &m.positions) {
            let p = p.map(f64::from);
            b = [
                b[0].min(p[0]),
                b[1].max(p[0]),
                b[2].min(p[2]),
                b[3].max(p[2]),
            ];
            y = [y[0].min(p[1]), y[1].max(p[1])];
        }
        (b, y)
    };
    // A tree stands on its trunk (its first mesh): a curbside crown reaches over the
    // parking lane, above the cars (checked below).
    let boxes: Vec<(&str, [f64; 4])> = inserted
        .objects
        .iter()
        .map(|o| {
            let standing = if o.class == "tree" {
                &o.meshes[..1]
            } else {
                &o.meshes[..]
            };
            (o.class.as_str(), bounds(standing).0)
        })
        .collect();
    let car_tops: Vec<([f64; 4], f64)> = inserted
        .objects
        .iter()
        .filter(|o| o.class == "car")
        .map(|o| {
            let (b, y) = bounds(&o.meshes);
            (b, y[1])
        })
        .collect();
    let mut over_cars = 0;
    for crown in inserted.objects.iter().filter(|o| o.class == "tree") {
        let (c, y) = bounds(&crown.meshes[1..]);
        for (b, top) in &car_tops {
            if c[0] < b[1] && b[0] < c[1] && c[2] < b[3] && b[2] < c[3] {
                over_cars += 1;
                assert!(
                    y[0] >= top + 0.5,
                    "crown from {} over a car {top} tall",
                    y[0]
                );
            }
        }
    }
    assert!(over_cars > 0, "no crown reaches over a parked car");
    let cars: Vec<[f64; 4]> = boxes.iter().filter(|b| b.0 == "car").map(|b| b.1).collect();
    let trees = boxes.iter().filter(|b| b.0 == "tree").count();
    assert!(
        cars.len() > 200 && trees > 100,
        "{} cars, {trees} trees",
        cars.len()
    );
    for (i, a) in boxes.iter().enumerate() {
        for b in &boxes[i + 1..] {
            if a.0 == "traffic_sign" && b.0 == "traffic_sign" {
                continue;
            }
            let (p, q) = (a.1, b.1);
            // Lights and wheels stand out of a car's footprint by at most 3 cm.
            let overlap = p[0] + 0.03 < q[1] - 0.03
                && q[0] + 0.03 < p[1] - 0.03
                && p[2] + 0.03 < q[3] - 0.03
                && q[2] + 0.03 < p[3] - 0.03;
            let is_tree_pair = a.0 == "tree" || b.0 == "tree";
            // Crowns take circles, so a tree's box may overlap another tree's or a sign's
            // box at a corner; a car's box never overlaps any other object's.
            assert!(
                !overlap || is_tree_pair && a.0 != "car" && b.0 != "car",
                "{a:?} {b:?}"
            );
        }
    }
    // Every car stands wholly on a road.
    for c in &cars {
        let on_road = city.layout.roads.iter().any(|r| {
            let px = RoadRect::of(r);
            let rect = RoadRect {
                x: px.x.map(|v| v * mpp),
                y: px.y.map(|v| v * mpp),
            };
            rect.x[0] <= c[0] + 0.05
                && c[1] - 0.05 <= rect.x[1]
                && rect.y[0] <= c[2] + 0.05
                && c[3] - 0.05 <= rect.y[1]
        });
        assert!(on_road, "{c:?}");
    }
}

#[test]
fn only_cars_in_the_driving_lanes_have_their_lights_on() {
    let city = city();
    for (parked, on) in [(1.0, false), (0.0, true)] {
        let specs = [ObjectSpec {
            parked,
            ..spec(EntryKind::Car, "car", 30)
        }];
        let inserted = run(&city, &specs).unwrap();
        assert!(inserted.objects.len() > 5, "{}", inserted.objects.len());
        let material = |name: &str| inserted.materials.iter().find(|m| m.name == name);
        for lens in ["car_headlight", "car_taillight"] {
            let lit = material(lens);
            let off = material(&format!("{lens}_off"));
            assert_eq!(
                (lit.is_some(), off.is_some()),
                (on, !on),
                "{lens}, parked {parked}"
            );
            if let Some(lit) = lit {
                assert!(lit.emissive.iter().any(|&e| e > 0.0));
            }
            if let Some(off) = off {
                assert_eq!(off.emissive, [0.0; 3]);
            }
        }
    }
}

#[test]
fn every_car_carries_a_front_and_a_rear_plate_a_text_object_when_the_spec_makes_text() {
    use crate::model::LAMP_LIT_SUFFIX;
    let city = city();
    let cars = ObjectSpec {
        parked: 0.5,
        ..spec(EntryKind::Car, "car", 30)
    };
    // With a `text` entry: each car is followed by its two plates, text objects.
    let specs = [spec(EntryKind::Text, "text", 4), cars.clone()];
    let inserted = run(&city, &specs).unwrap();
    let first_car = inserted
        .objects
        .iter()
        .position(|o| o.class == "car")
        .unwrap();
    let objects = &inserted.objects[first_car..];
    let info = &inserted.info[first_car..];
    assert_eq!(objects.len() % 3, 0);
    assert_eq!(inserted.placed[1] as usize, objects.len() / 3);
    assert!(objects.len() / 3 > 20, "{} cars", objects.len() / 3);
    let material = |m: u32| &inserted.materials[m as usize];
    let (mut lit, mut unlit) = (0, 0);
    for ((cars, infos), k) in objects.chunks(3).zip(info.chunks(3)).zip(0..) {
        let (car, plates) = (&cars[0], &cars[1..]);
        assert_eq!(car.class, "car", "object {k}");
        let (lo, hi) = mesh_bounds(&car.meshes);
        let text = infos[1].text.clone().unwrap();
        let lane_car = car
            .meshes
            .iter()
            .any(|m| material(m.material).name == "car_headlight");
        for (end, (plate, i)) in plates.iter().zip(&infos[1..]).enumerate() {
            assert_eq!(plate.class, "text");
            assert_eq!(plate.kind, crate::model::ObjectKind::Text);
            assert!(plate.name.starts_with("text_"), "{}", plate.name);
            // The same registration at both ends; a word a group, each with its quad.
            assert_eq!(i.text.as_deref(), Some(text.as_str()));
            assert_eq!(i.corners.len(), 3, "{text}");
            assert_eq!(i.attributes["text_style"], "plate");
            // The rear plate of a car in a lane is lit by its lamp after dusk.
            let light = &i.attributes["text_light"];
            let want = if end == 1 && lane_car {
                "lamp_lit"
            } else {
                "unlit"
            };
            assert_eq!(light, want, "{}", car.name);
            let page = &material(plate.meshes[0].material).name;
            assert_eq!(
                page.contains(LAMP_LIT_SUFFIX),
                light == "lamp_lit",
                "{page}"
            );
            (lit, unlit) = if light == "lamp_lit" {
                (lit + 1, unlit)
            } else {
                (lit, unlit + 1)
            };
            // 520 × 110 mm, upright, at the car's end, within its width and below its
            // headlights' top.
            let (plo, phi) = mesh_bounds(&plate.meshes);
            let across = (phi[0] - plo[0]).max(phi[2] - plo[2]);
            assert!((across - 0.52).abs() < 1e-3, "{across}");
            assert!((phi[1] - plo[1] - 0.11).abs() < 1e-4);
            assert!(
                plo[1] > lo[1] + 0.3 && phi[1] < hi[1] - 0.4,
                "{plo:?} {phi:?}"
            );
            let outside = (0..3)
                .step_by(2)
                .any(|a| plo[a] < lo[a] - 0.03 || phi[a] > hi[a] + 0.03);
            assert!(!outside, "{} plate {end} off its car", car.name);
            for quad in &i.corners {
                for p in quad {
                    assert!((0..3).all(|a| plo[a] - 1e-4 <= p[a] && p[a] <= phi[a] + 1e-4));
                }
            }
        }
    }
    assert!(lit > 0 && unlit > lit, "{lit} lit, {unlit} unlit");
    // Without one (wall text of another class instead, so the cars draw from the same
    // entry's stream): the same cars, each plate a textured quad of its car.
    let alone = run(&city, &[spec(EntryKind::Text, "shop_sign", 4), cars]).unwrap();
    let alone: Vec<&SceneObject> = alone
        .objects
        .iter()
        .filter(|o| o.class != "shop_sign")
        .collect();
    assert_eq!(alone.len(), objects.len() / 3);
    for (car, with) in alone.into_iter().zip(objects.chunks(3)) {
        assert_eq!(car.class, "car");
        let textured: Vec<&Mesh> = car.meshes.iter().filter(|m| !m.uvs.is_empty()).collect();
        assert_eq!(textured.len(), 2, "{}", car.name);
        let plates: Vec<Mesh> = with[1..].iter().flat_map(|o| o.meshes.clone()).collect();
        assert_eq!(
            mesh_bounds(&car.meshes),
            mesh_bounds(&[&with[0].meshes[..], &plates[..]].concat())
        );
    }
}

#[test]
fn bicycles_are_parked_on_the_strips_or_ridden_in_the_lanes_with_a_rider_each() {
    use crate::objects::bicycle::RIDDEN_HALF;
    use crate::spec::RIDER_CLASS;
    let city = city();
    let specs = [
        spec(EntryKind::Car, "car", 200),
        ObjectSpec {
            parked: 0.4,
            ..spec(EntryKind::Bicycle, "bicycle", 80)
        },
    ];
    let mpp = 0.55;
    let inserted = insert(&ObjectsInput {
        metres_per_pixel: mpp,
        ..input(&city, &specs)
    })
    .unwrap();
    let bounds = mesh_bounds;
    let cars: Vec<([f64; 3], [f64; 3])> = inserted
        .objects
        .iter()
        .filter(|o| o.class == "car")
        .map(|o| bounds(&o.meshes))
        .collect();
    let first = inserted
        .objects
        .iter()
        .position(|o| o.class != "car")
        .unwrap();
    let rest = &inserted.objects[first..];
    let (mut parked, mut ridden) = (0, 0);
    let mut k = 0;
    let mut footprints: Vec<([f64; 3], [f64; 3])> = Vec::new();
    while k < rest.len() {
        let bike = &rest[k];
        assert!(bike.name.starts_with("bicycle_"), "{}", bike.name);
        assert_eq!(bike.class, "bicycle");
        let (lo, hi) = bounds(&bike.meshes);
        let rider = rest.get(k + 1).filter(|o| o.class == RIDER_CLASS);
        if let Some(rider) = rider {
            // Ridden: on the road, along it (the long side along x or z), the rider over it.
            assert!((lo[1] - ROAD_Y).abs() < 1e-4, "{} at {}", bike.name, lo[1]);
            assert!(rider.name.starts_with("rider_"));
            let (rlo, rhi) = bounds(&rider.meshes);
            assert!(rlo[1] > lo[1] && rhi[1] > hi[1] + 0.5, "{rlo:?} {rhi:?}");
            let both = (
                [0, 1, 2].map(|i| lo[i].min(rlo[i])),
                [0, 1, 2].map(|i| hi[i].max(rhi[i])),
            );
            let size = [both.1[0] - both.0[0], both.1[2] - both.0[2]];
            let (long, short) = (size[0].max(size[1]), size[0].min(size[1]));
            assert!(
                long <= 2.0 * RIDDEN_HALF[0] + 1e-6 && long > 1.6,
                "{size:?}"
            );
            assert!(short <= 2.0 * RIDDEN_HALF[1] + 1e-6, "{size:?}");
            footprints.push(both);
            ridden += 1;
            k += 2;
        } else {
            // Parked: on the sidewalk.
            assert!((lo[1] - KERB_Y).abs() < 1e-4, "{} at {}", bike.name, lo[1]);
            footprints.push((lo, hi));
            parked += 1;
            k += 1;
        }
    }
    assert_eq!(inserted.placed[1] as usize, parked + ridden);
    assert!(
        parked >= 15 && ridden >= 30,
        "{parked} parked, {ridden} ridden"
    );
    // No bicycle overlaps a car or another bicycle (their boxes on the ground).
    let overlap = |a: &([f64; 3], [f64; 3]), b: &([f64; 3], [f64; 3])| {
        a.0[0] < b.1[0] && b.0[0] < a.1[0] && a.0[2] < b.1[2] && b.0[2] < a.1[2]
    };
    for (i, a) in footprints.iter().enumerate() {
        assert!(!cars.iter().any(|c| overlap(a, c)), "{a:?}");
        assert!(!footprints[i + 1..].iter().any(|b| overlap(a, b)), "{a:?}");
    }
    // Deterministic; a huge count falls short without panicking.
    assert_eq!(
        insert(&ObjectsInput {
            metres_per_pixel: mpp,
            ..input(&city, &specs)
        })
        .unwrap(),
        inserted
    );
    let many = [spec(EntryKind::Bicycle, "bicycle", 100_000)];
    let all = run(&city, &many).unwrap();
    assert!(all.placed[0] > 80 && all.placed[0] < 100_000);
}
