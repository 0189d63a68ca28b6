//! Streets: road surfaces, markings and lamps.

use super::*;
use crate::model::geometry::RoadRect;

#[test]
fn lamps_stand_at_their_sites_with_an_emissive_head_towards_the_road() {
    let city = city(None);
    let scene = scene_of(&city, None);
    let lamps: Vec<&SceneObject> = of_class(&scene, "lamp").collect();
    for (object, lamp) in lamps.iter().zip(&city.lamps) {
        let [metal, head] = &object.meshes[..] else {
            panic!("{}: pole and head", object.name)
        };
        let head_material = &scene.materials[head.material as usize];
        assert_eq!(head_material.name, "lamp_head");
        assert!(head_material.emissive.iter().all(|&e| e > 0.0));
        assert_eq!(scene.materials[metal.material as usize].emissive, [0.0; 3]);
        // The pole's lowest ring is centred on the site.
        let ring: Vec<[f64; 3]> = (0..metal.positions.len() as u32)
            .map(|i| position(metal, i))
            .filter(|p| p[1] == 0.0)
            .collect();
        assert!(!ring.is_empty());
        let cx = ring.iter().map(|p| p[0]).sum::<f64>() / ring.len() as f64;
        let cz = ring.iter().map(|p| p[2]).sum::<f64>() / ring.len() as f64;
        assert!((cx - lamp.position[0]).abs() < 1e-3 && (cz - lamp.position[1]).abs() < 1e-3);
        // The head hangs out along `facing`.
        let n = head.positions.len() as f64;
        let hx = head.positions.iter().map(|p| f64::from(p[0])).sum::<f64>() / n;
        let hz = head.positions.iter().map(|p| f64::from(p[2])).sum::<f64>() / n;
        let (dx, dz) = (hx - lamp.position[0], hz - lamp.position[1]);
        let along = dx * lamp.facing[0] + dz * lamp.facing[1];
        let across = dx * lamp.facing[1] - dz * lamp.facing[0];
        assert!(
            along > 1.0 && across.abs() < 1e-3,
            "{}: {along} {across}",
            object.name
        );
        // The night light shines from just under the head's middle (1 px = 1 m here).
        let light = crate::scene::light_position(lamp, 1.0);
        let bottom = head
            .positions
            .iter()
            .map(|p| f64::from(p[1]))
            .fold(f64::INFINITY, f64::min);
        assert!((light[0] - hx).abs() < 1e-3 && (light[2] - hz).abs() < 1e-3);
        assert!(
            light[1] < bottom && light[1] > bottom - 0.1,
            "{light:?} {bottom}"
        );
    }
}

#[test]
fn markings_stay_out_of_crossings_and_on_their_road() {
    let city = city(None);
    let scene = scene_of(&city, None);
    let rects: Vec<RoadRect> = city.layout.roads.iter().map(RoadRect::of).collect();
    let (mut dashes, mut bars) = (0, 0);
    for object in of_class(&scene, "marking") {
        // No two markings of a road overlap: lines stop short of the zebra crossings.
        let pieces: Vec<RoadRect> = object.meshes[0]
            .positions
            .chunks(4)
            .map(plan_rect)
            .collect();
        for (i, a) in pieces.iter().enumerate() {
            for b in &pieces[i + 1..] {
                assert!(!a.overlaps(b), "{}: {a:?} overlaps {b:?}", object.name);
            }
        }
        let id: usize = object.name["marking_".len()..].parse().unwrap();
        for dash in pieces {
            dashes += 1;
            if quad_is_zebra_bar(&dash) {
                bars += 1;
            }
            let own = &rects[id];
            let inside = own.x[0] <= dash.x[0]
                && dash.x[1] <= own.x[1]
                && own.y[0] <= dash.y[0]
                && dash.y[1] <= own.y[1];
            assert!(inside, "{}: {dash:?} off its road", object.name);
            for (j, other) in rects.iter().enumerate() {
                assert!(
                    j == id || !dash.overlaps(other),
                    "{}: {dash:?} in road {j}",
                    object.name
                );
            }
        }
    }
    assert!(dashes > 100, "{dashes}");
    // The test city's crossings have zebra crossings on their approaches.
    assert!(bars > 20, "{bars} zebra bars");
}

/// The plan rectangle (x and z extents) of a flat quad's corners.
fn plan_rect(quad: &[[f32; 3]]) -> RoadRect {
    let xs = quad.iter().map(|p| f64::from(p[0]));
    let zs = quad.iter().map(|p| f64::from(p[2]));
    RoadRect {
        x: [
            xs.clone().fold(f64::INFINITY, f64::min),
            xs.fold(f64::NEG_INFINITY, f64::max),
        ],
        y: [
            zs.clone().fold(f64::INFINITY, f64::min),
            zs.fold(f64::NEG_INFINITY, f64::max),
        ],
    }
}

/// Whether a marking quad (its plan rectangle, layout pixels) is a zebra crossing's bar: 3 m
/// along the road, 0.5 m across (the test city's scale is 1 m a pixel).
fn quad_is_zebra_bar(r: &RoadRect) -> bool {
    let (w, h) = (r.x[1] - r.x[0], r.y[1] - r.y[0]);
    let near = |a: f64, b: f64| (a - b).abs() < 1e-3;
    (near(w, 3.0) && near(h, 0.5)) || (near(w, 0.5) && near(h, 3.0))
}

#[test]
fn road_surfaces_do_not_overlap_and_cover_every_road() {
    let city = city(None);
    let scene = scene_of(&city, None);
    let mut pieces: Vec<RoadRect> = Vec::new();
    let mut area = 0.0;
    for object in of_class(&scene, "road") {
        for quad in object.meshes[0].positions.chunks(4) {
            let piece = plan_rect(quad);
            assert!(
                pieces.iter().all(|p| !p.overlaps(&piece)),
                "{}",
                object.name
            );
            area += piece.area();
            pieces.push(piece);
        }
    }
    // Full-span roads: the union is every road's area minus each crossing counted once.
    let rects: Vec<RoadRect> = city.layout.roads.iter().map(RoadRect::of).collect();
    let mut union = 0.0;
    for (i, r) in rects.iter().enumerate() {
        union += r
            .minus_all(&rects[..i])
            .iter()
            .map(RoadRect::area)
            .sum::<f64>();
    }
    let crossings: f64 = rects
        .iter()
        .enumerate()
        .flat_map(|(i, a)| rects[i + 1..].iter().map(move |b| (a, b)))
        .filter(|(a, b)| a.overlaps(b))
        .map(|(a, b)| {
            (a.x[1].min(b.x[1]) - a.x[0].max(b.x[0])) * (a.y[1].min(b.y[1]) - a.y[0].max(b.y[0]))
        })
        .sum();
    let total: f64 = rects.iter().map(RoadRect::area).sum();
    assert_eq!(area, union);
    assert_eq!(union, total - crossings);
}
