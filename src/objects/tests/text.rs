//! Text on walls: where the plates go, their atlas pages, styles and words.

use std::collections::BTreeSet;

use super::*;
use crate::model::geometry::{KERB_Y, RoadRect, cross, dot, sub};
use crate::objects::wall_text::{self, MIN_HEIGHT, TOP_CLEARANCE, WALL_OFFSET, Walls};

#[test]
fn text_quads_lie_on_their_walls_without_overlapping() {
    let city = city();
    let specs = [ObjectSpec {
        letter_height: [0.5, 1.5],
        ..spec(EntryKind::Text, "text", 150)
    }];
    let inserted = run(&city, &specs).unwrap();
    assert!(inserted.objects.len() > 100, "{}", inserted.objects.len());
    let walls = Walls::new(&input(&city, &specs));
    let heights: BTreeMap<u32, f64> = city
        .buildings
        .iter()
        .map(|b| {
            let f = &city.facades.facades[b.kind as usize];
            (b.id, f.height)
        })
        .collect();
    // Per wall: the plates found on it, as [u0, y0, u1, y1].
    let mut on_wall: BTreeMap<usize, Vec<[f64; 4]>> = BTreeMap::new();
    for (object, info) in inserted.objects.iter().zip(&inserted.info) {
        let mesh = &object.meshes[0];
        let points: Vec<[f64; 3]> = mesh.positions.iter().map(|p| p.map(f64::from)).collect();
        let (w, wall) = walls
            .walls()
            .iter()
            .enumerate()
            .find(|(_, wall)| {
                points.iter().all(|p| {
                    let out = (p[0] - wall.origin[0]) * wall.normal[0]
                        + (p[2] - wall.origin[1]) * wall.normal[1];
                    (out - WALL_OFFSET).abs() < 1e-4 && {
                        let u = (p[0] - wall.origin[0]) * wall.right[0]
                            + (p[2] - wall.origin[1]) * wall.right[1];
                        (-1e-4..=wall.length + 1e-4).contains(&u)
                    }
                })
            })
            .unwrap_or_else(|| panic!("{} is on no wall", object.name));
        let u: Vec<f64> = points
            .iter()
            .map(|p| {
                (p[0] - wall.origin[0]) * wall.right[0] + (p[2] - wall.origin[1]) * wall.right[1]
            })
            .collect();
        let y: Vec<f64> = points.iter().map(|p| p[1]).collect();
        let rect = [
            u.iter().copied().fold(f64::INFINITY, f64::min),
            y.iter().copied().fold(f64::INFINITY, f64::min),
            u.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            y.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        ];
        let top = KERB_Y + heights[&wall.building];
        assert!(rect[1] >= KERB_Y + MIN_HEIGHT - 1e-4, "{rect:?}");
        assert!(rect[3] <= top - TOP_CLEARANCE + 1e-4, "{rect:?}");
        // Faces outward: every triangle's winding and stored normal.
        for t in mesh.indices.chunks(3) {
            let p = |k: usize| points[t[k] as usize];
            let n = cross(sub(p(1), p(0)), sub(p(2), p(0)));
            let outward = [wall.normal[0], 0.0, wall.normal[1]];
            assert!(dot(n, outward) > 0.0);
            assert_eq!(mesh.normals[t[0] as usize].map(f64::from), outward);
        }
        // One box per word, each inside the plate, on the same plane, left to right.
        let text = info.text.as_deref().unwrap();
        assert_eq!(info.corners.len(), text.split(' ').count(), "{text}");
        for corners in &info.corners {
            for c in corners {
                let cu = (c[0] - wall.origin[0]) * wall.right[0]
                    + (c[2] - wall.origin[1]) * wall.right[1];
                assert!(rect[0] - 1e-4 <= cu && cu <= rect[2] + 1e-4);
                assert!(rect[1] - 1e-4 <= c[1] && c[1] <= rect[3] + 1e-4);
            }
            assert!(corners[0][1] > corners[3][1], "top above bottom");
        }
        let along = |c: [f64; 3]| {
            (c[0] - wall.origin[0]) * wall.right[0] + (c[2] - wall.origin[1]) * wall.right[1]
        };
        for pair in info.corners.windows(2) {
            assert!(
                along(pair[0][1]) <= along(pair[1][0]) + 1e-6,
                "{text}: words in order"
            );
        }
        on_wall.entry(w).or_default().push(rect);
    }
    assert!(
        on_wall.values().any(|r| r.len() > 1),
        "no wall holds two plates"
    );
    for rects in on_wall.values() {
        for (i, a) in rects.iter().enumerate() {
            for b in &rects[i + 1..] {
                let apart = a[2] <= b[0] || b[2] <= a[0] || a[3] <= b[1] || b[3] <= a[1];
                assert!(apart, "{a:?} overlaps {b:?}");
            }
        }
    }
}

#[test]
fn text_plates_share_atlas_pages_and_each_maps_to_its_own_plate() {
    let city = city();
    let specs = [
        ObjectSpec {
            letter_height: [0.3, 1.5],
            words: [1, 3],
            ..spec(EntryKind::Text, "text", 150)
        },
        spec(EntryKind::Text, "shop_sign", 30),
    ];
    let inserted = run(&city, &specs).unwrap();
    assert!(inserted.objects.len() > 150, "{}", inserted.objects.len());
    let pages: BTreeSet<u32> = inserted
        .objects
        .iter()
        .map(|o| o.meshes[0].material)
        .collect();
    // Shop frames and banner hems pad plates more than bare text did: still a few pages
    // per light (unlit, backlit, lamp-lit each pack their own: see `plate_light`).
    assert!(pages.len() <= 9, "{} pages for 180 plates", pages.len());
    let decoded: BTreeMap<u32, RgbImage> = pages
        .iter()
        .map(|&m| {
            let t = inserted.materials[m as usize].texture.unwrap();
            (m, inserted.textures[t as usize].decode().unwrap())
        })
        .collect();
    // Per page: the pixel rectangles the plates' uvs cover, [x0, y0, x1, y1).
    let mut on_page: BTreeMap<u32, Vec<[u32; 4]>> = BTreeMap::new();
    for (object, info) in inserted.objects.iter().zip(&inserted.info) {
        let mesh = &object.meshes[0];
        let page = &decoded[&mesh.material];
        let (w, h) = (f64::from(page.width()), f64::from(page.height()));
        let px = |v: f32, size: f64| {
            let p = f64::from(v) * size;
            assert!(
                (p - p.round()).abs() < 1e-3,
                "{}: uv off the pixel grid",
                object.name
            );
            p.round() as u32
        };
        let xs: Vec<u32> = mesh.uvs.iter().map(|uv| px(uv[0], w)).collect();
        let ys: Vec<u32> = mesh.uvs.iter().map(|uv| px(uv[1], h)).collect();
        let rect = [
            *xs.iter().min().unwrap(),
            *ys.iter().min().unwrap(),
            *xs.iter().max().unwrap(),
            *ys.iter().max().unwrap(),
        ];
        // Pixels per metre agree along both sides: the rectangle is this plate's own.
        let quad = |k: usize| mesh.positions[k].map(f64::from);
        let (dx, dz) = (quad(1)[0] - quad(0)[0], quad(1)[2] - quad(0)[2]);
        let across = (dx * dx + dz * dz).sqrt();
        let up = (quad(2)[1] - quad(1)[1]).abs();
        let ratio = f64::from(rect[2] - rect[0]) / across / (f64::from(rect[3] - rect[1]) / up);
        assert!((ratio - 1.0).abs() < 0.02, "{}: {ratio}", object.name);
        // The padding around it repeats its edge pixels; inside, the text stands out from
        // the plate (or the painted wall).
        let pad = crate::objects::atlas_layout::PADDING;
        for y in rect[1] - pad..rect[3] + pad {
            for x in rect[0] - pad..rect[2] + pad {
                let edge = [x.clamp(rect[0], rect[2] - 1), y.clamp(rect[1], rect[3] - 1)];
                if edge != [x, y] {
                    assert_eq!(
                        page.get_pixel(x, y),
                        page.get_pixel(edge[0], edge[1]),
                        "{} at {x},{y}",
                        object.name
                    );
                }
            }
        }
        let colours: BTreeSet<[u8; 3]> = (rect[1]..rect[3])
            .flat_map(|y| (rect[0]..rect[2]).map(move |x| (x, y)))
            .map(|(x, y)| page.get_pixel(x, y).0)
            .collect();
        assert!(
            colours.len() > 2,
            "{}: {} colours",
            object.name,
            colours.len()
        );
        assert!(info.text.is_some());
        on_page.entry(mesh.material).or_default().push(rect);
    }
    for rects in on_page.values() {
        for (i, a) in rects.iter().enumerate() {
            for b in &rects[i + 1..] {
                let apart = a[2] <= b[0] || b[2] <= a[0] || a[3] <= b[1] || b[3] <= a[1];
                assert!(apart, "{a:?} overlaps {b:?}");
            }
        }
    }
    // Each entry has pages of its own.
    let labels_per_page: BTreeSet<(u32, &str)> = inserted
        .objects
        .iter()
        .map(|o| (o.meshes[0].material, o.class.as_str()))
        .collect();
    assert_eq!(labels_per_page.len(), pages.len());
}

#[test]
fn every_text_wall_faces_a_nearby_road() {
    let city = city();
    let walls = Walls::new(&input(&city, &[]));
    assert!(walls.walls().len() > 20);
    let rects: Vec<RoadRect> = city.layout.roads.iter().map(RoadRect::of).collect();
    for wall in walls.walls() {
        // Step out of the wall's middle: a road lies within 2 strips + 1 px (8 px strip).
        let mid = [
            wall.origin[0] + wall.right[0] * wall.length / 2.0,
            wall.origin[1] + wall.right[1] * wall.length / 2.0,
        ];
        let hit = (1..=17).any(|d| {
            let p = [
                mid[0] + wall.normal[0] * f64::from(d),
                mid[1] + wall.normal[1] * f64::from(d),
            ];
            rects
                .iter()
                .any(|r| r.x[0] <= p[0] && p[0] <= r.x[1] && r.y[0] <= p[1] && p[1] <= r.y[1])
        });
        assert!(hit, "{wall:?}");
    }
}

/// The plate's rectangle `[u0, y0, u1, y1]` on `wall`, if its quad lies on that wall.
fn plate_rect(object: &SceneObject, wall: &wall_text::Wall) -> Option<[f64; 4]> {
    let points: Vec<[f64; 3]> = object.meshes[0]
        .positions
        .iter()
        .map(|p| p.map(f64::from))
        .collect();
    let along = |p: &[f64; 3]| {
        (p[0] - wall.origin[0]) * wall.right[0] + (p[2] - wall.origin[1]) * wall.right[1]
    };
    let on = points.iter().all(|p| {
        let out =
            (p[0] - wall.origin[0]) * wall.normal[0] + (p[2] - wall.origin[1]) * wall.normal[1];
        (out - WALL_OFFSET).abs() < 1e-4 && (-1e-4..=wall.length + 1e-4).contains(&along(p))
    });
    on.then(|| {
        let u: Vec<f64> = points.iter().map(along).collect();
        let y: Vec<f64> = points.iter().map(|p| p[1]).collect();
        let lo = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = |v: &[f64]| v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        [lo(&u), lo(&y), hi(&u), hi(&y)]
    })
}

#[test]
fn plates_keep_clear_of_windows_and_record_style_and_font() {
    let mut city = city();
    // Two window columns per floor.
    for f in &mut city.facades.facades {
        let n = f.floors as f32;
        f.windows = (0..f.floors)
            .flat_map(|row| {
                let (v0, v1) = ((row as f32 + 0.3) / n, (row as f32 + 0.8) / n);
                [[0.1, v0, 0.3, v1], [0.6, v0, 0.8, v1]]
            })
            .collect();
    }
    let specs = [ObjectSpec {
        letter_height: [0.3, 0.8],
        ..spec(EntryKind::Text, "text", 300)
    }];
    let inserted = run(&city, &specs).unwrap();
    assert!(inserted.objects.len() > 100, "{}", inserted.objects.len());
    let walls = Walls::new(&input(&city, &specs));
    assert!(walls.walls().iter().all(|w| !w.windows.is_empty()));
    let mut styles = BTreeSet::new();
    let mut fonts = BTreeSet::new();
    for (object, info) in inserted.objects.iter().zip(&inserted.info) {
        let (wall, rect) = walls
            .walls()
            .iter()
            .find_map(|w| Some((w, plate_rect(object, w)?)))
            .unwrap_or_else(|| panic!("{} is on no wall", object.name));
        for win in &wall.windows {
            let apart =
                rect[2] <= win[0] || win[2] <= rect[0] || rect[3] <= win[1] || win[3] <= rect[1];
            assert!(apart, "{} {rect:?} covers window {win:?}", object.name);
        }
        let style = &info.attributes["text_style"];
        if style == "shop" {
            assert!(rect[1] <= KERB_Y + MIN_HEIGHT + plate_style::SHOP_BAND + 1e-9);
        }
        styles.insert(style.clone());
        fonts.insert(info.attributes["text_font"].clone());
    }
    assert_eq!(styles.len(), 3, "{styles:?}");
    assert!(fonts.len() >= 6, "{fonts:?}");
}

#[test]
fn a_wall_behind_another_building_does_not_face_the_road() {
    let city = city();
    let walls = Walls::new(&input(&city, &[]));
    for wall in walls.walls() {
        let mid = [
            wall.origin[0] + wall.right[0] * wall.length / 2.0,
            wall.origin[1] + wall.right[1] * wall.length / 2.0,
        ];
        // Straight out of the wall's middle, no other building before the road.
        let rects: Vec<RoadRect> = city.layout.roads.iter().map(RoadRect::of).collect();
        for d in 1..=17 {
            let p = [
                mid[0] + wall.normal[0] * f64::from(d),
                mid[1] + wall.normal[1] * f64::from(d),
            ];
            let in_road = rects
                .iter()
                .any(|r| r.x[0] <= p[0] && p[0] <= r.x[1] && r.y[0] <= p[1] && p[1] <= r.y[1]);
            if in_road {
                break;
            }
            let in_building = city.buildings.iter().any(|b| {
                let f = b.footprint;
                b.id != wall.building
                    && f64::from(f.x0) < p[0]
                    && p[0] < f64::from(f.x1)
                    && f64::from(f.y0) < p[1]
                    && p[1] < f64::from(f.y1)
            });
            assert!(!in_building, "{wall:?} looks into a building at {p:?}");
        }
    }
}

#[test]
fn a_word_file_replaces_the_built_in_words() {
    let mut city = city();
    city.meshes.insert(
        "words.txt".to_owned(),
        MeshFiles {
            obj: "# names\nÉcole Bäckerei\nPIZZA\n".as_bytes().to_vec(),
            ..MeshFiles::default()
        },
    );
    let specs = [ObjectSpec {
        words_file: Some("words.txt".to_owned()),
        case: TextCase::Upper,
        ..spec(EntryKind::Text, "text", 40)
    }];
    let inserted = run(&city, &specs).unwrap();
    assert!(!inserted.info.is_empty());
    for info in &inserted.info {
        for word in info.text.as_deref().unwrap().split(' ') {
            assert!(["ÉCOLE", "BÄCKEREI", "PIZZA"].contains(&word), "{word}");
        }
    }
    let missing = [ObjectSpec {
        words_file: Some("nowhere.txt".to_owned()),
        ..spec(EntryKind::Text, "text", 4)
    }];
    let result = run(&city, &missing);
    assert!(
        matches!(&result, Err(ObjectsError::MissingWords { file }) if file == "nowhere.txt"),
        "{:?}",
        result.err()
    );
}
