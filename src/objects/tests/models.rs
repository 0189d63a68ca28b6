//! User OBJ models (`kind = "mesh"`): loading, textures, errors, where they stand.

use super::*;
use crate::model::geometry::{KERB_Y, ROAD_Y, RoadRect, cross, dot, sub};

#[test]
fn bench_asset_loads_with_its_materials_and_faces_out() {
    let city = city();
    let model = user_mesh::Model::load(BENCH, &city.meshes[BENCH]).unwrap();
    let names: Vec<&str> = model.materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["wood", "metal", "default"]);
    assert_eq!(model.materials[0].colour, [0.45, 0.28, 0.14]);
    assert_eq!(model.min_y, 0.0);
    let triangles: usize = model.parts.iter().map(|p| p.indices.len() / 3).sum();
    assert_eq!(triangles, 6 * 12);
    // Every triangle faces away from its box's centre: the file's faces wind CCW.
    for part in &model.parts {
        for t in part.indices.chunks(3) {
            let p = |k: usize| part.positions[t[k] as usize];
            let n = cross(sub(p(1), p(0)), sub(p(2), p(0)));
            let stored = part.normals[t[0] as usize];
            assert!(dot(n, stored) > 0.0);
        }
    }
}

#[test]
fn meshes_stand_on_sidewalks_and_in_lanes() {
    let city = city();
    let specs = [bench(12, Ground::Sidewalk), bench(8, Ground::Lane)];
    let inserted = run(&city, &specs).unwrap();
    assert_eq!(inserted.objects.len(), 20);
    let wood: Vec<&str> = inserted.materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(
        wood,
        [
            "bench_wood",
            "bench_metal",
            "bench_default",
            "bench_wood_2",
            "bench_metal_2",
            "bench_default_2"
        ]
    );
    let rects: Vec<RoadRect> = city.layout.roads.iter().map(RoadRect::of).collect();
    for (i, object) in inserted.objects.iter().enumerate() {
        let points: Vec<[f32; 3]> = object
            .meshes
            .iter()
            .flat_map(|m| m.positions.clone())
            .collect();
        let min_y = points
            .iter()
            .map(|p| f64::from(p[1]))
            .fold(f64::INFINITY, f64::min);
        let ground = if i < 12 { KERB_Y } else { ROAD_Y };
        assert!((min_y - ground).abs() < 1e-5, "{} {min_y}", object.name);
        let on_road = |p: &[f32; 3]| {
            let (x, z) = (f64::from(p[0]), f64::from(p[2]));
            rects
                .iter()
                .any(|r| r.x[0] <= x && x <= r.x[1] && r.y[0] <= z && z <= r.y[1])
        };
        if i < 12 {
            assert!(points.iter().all(|p| !on_road(p)), "{}", object.name);
        } else {
            assert!(points.iter().all(on_road), "{}", object.name);
        }
    }
}

/// A one-quad OBJ with vt, no normals, a textured MTL and a 2 × 2 PNG.
fn textured_quad() -> MeshFiles {
    let mut png = Vec::new();
    image::DynamicImage::ImageRgb8(RgbImage::from_pixel(2, 2, image::Rgb([9, 99, 199])))
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    MeshFiles {
        obj: b"mtllib q.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
               usemtl poster\nf 1/1 2/2 3/3 4/4\n"
            .to_vec(),
        mtl: Some(b"newmtl poster\nKd 1 1 1\nmap_Kd poster.png\n".to_vec()),
        textures: BTreeMap::from([("poster.png".to_owned(), png)]),
    }
}

#[test]
fn textured_models_keep_their_uvs_flipped_and_get_flat_normals() {
    let model = user_mesh::Model::load("q.obj", &textured_quad()).unwrap();
    let texture = model.materials[0].texture.as_ref().unwrap();
    assert_eq!((texture.width, texture.height), (2, 2));
    let part = &model.parts[0];
    assert_eq!(part.indices.len(), 6);
    for (p, uv) in part.positions.iter().zip(&part.uvs) {
        // vt (0, 0) is the image's bottom-left: v down is 1 there.
        assert_eq!([f64::from(uv[0]), f64::from(uv[1])], [p[0], 1.0 - p[1]]);
    }
    assert!(part.normals.iter().all(|n| *n == [0.0, 0.0, 1.0]));
}

#[test]
fn model_errors_name_the_model() {
    let city = city();
    let specs = [ObjectSpec {
        model: Some("cars/missing.obj".to_owned()),
        ..bench(1, Ground::Lane)
    }];
    let error = run(&city, &specs).unwrap_err();
    assert!(
        matches!(&error, ObjectsError::MissingModel { model } if model == "cars/missing.obj"),
        "{error:?}"
    );
    let mut no_texture = textured_quad();
    no_texture.textures.clear();
    let mut no_mtl = textured_quad();
    no_mtl.mtl = None;
    let mut bad_png = textured_quad();
    bad_png
        .textures
        .insert("poster.png".to_owned(), b"not a png".to_vec());
    let empty = MeshFiles {
        obj: b"# nothing\n".to_vec(),
        ..MeshFiles::default()
    };
    let cases = [
        (
            no_texture,
            "model q.obj: texture poster.png named by its MTL is missing",
        ),
        (
            no_mtl,
            "model q.obj: cannot read its MTL: the OBJ names an MTL file the build did not read",
        ),
        (
            bad_png,
            "model q.obj: texture poster.png is not a PNG or JPEG image",
        ),
        (empty, "model q.obj: has no triangles"),
    ];
    for (files, want) in cases {
        let error = user_mesh::Model::load("q.obj", &files).unwrap_err();
        assert!(error.to_string().starts_with(want), "{error}");
    }
}
