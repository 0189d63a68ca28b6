//! The KITTI files of rendered frames, read back as the devkit reads them: every labelled
//! object's 8 box corners, projected through the written `P2`, contain the full 2D box the
//! renderer measured for it (where the box lies wholly in front of the camera).

use std::collections::BTreeMap;

use crate::annotate::{self, Box3d, Category, FrameInput, ObjectLabel, Thresholds};
use crate::model::{CameraPose, Material, Mesh, ObjectKind, Scene, SceneObject};
use crate::render::{self, Intrinsics, Lighting};

/// An upright box's mesh: its 6 faces, with outward vertex normals (so the renderer winds
/// them to face out).
fn box_mesh(b: &Box3d) -> Mesh {
    let c = b.corners().map(|p| p.map(|v| v as f32));
    let centre = b.centre.map(|v| v as f32);
    let faces = [
        [0, 1, 2, 3],
        [4, 5, 6, 7],
        [0, 1, 5, 4],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 0, 4, 7],
    ];
    let mut mesh = Mesh::default();
    for f in faces {
        let mid: [f32; 3] =
            std::array::from_fn(|k| f.iter().map(|&i| c[i][k]).sum::<f32>() / 4.0 - centre[k]);
        let len = (mid[0] * mid[0] + mid[1] * mid[1] + mid[2] * mid[2]).sqrt();
        let base = mesh.positions.len() as u32;
        for &i in &f {
            mesh.positions.push(c[i]);
            mesh.normals.push(mid.map(|v| v / len));
            mesh.uvs.push([0.0, 0.0]);
        }
        mesh.indices.extend([0, 1, 2, 0, 2, 3].map(|k| base + k));
    }
    mesh
}

fn scene(boxes: &[Box3d]) -> Scene {
    let ground = Box3d {
        centre: [0.0, -0.05, 0.0],
        size: [400.0, 400.0, 0.1],
        yaw: 0.0,
    };
    let object = |name: String, b: &Box3d| SceneObject {
        name,
        kind: ObjectKind::Mesh,
        class: "car".into(),
        meshes: vec![box_mesh(b)],
    };
    let mut objects = vec![object("ground".into(), &ground)];
    objects.extend(
        boxes
            .iter()
            .enumerate()
            .map(|(i, b)| object(format!("car_{i}"), b)),
    );
    Scene {
        textures: Vec::new(),
        materials: vec![Material {
            name: "m".into(),
            colour: [0.5; 3],
            texture: None,
            emissive: [0.0; 3],
            emissive_textured: false,
        }],
        objects,
    }
}

/// `name: v v v …` of a calib file, as numbers.
fn calib_row(calib: &str, name: &str) -> Vec<f64> {
    let line = calib
        .lines()
        .find(|l| l.starts_with(&format!("{name}:")))
        .unwrap();
    let values = line.split_whitespace().skip(1).map(|v| v.parse().unwrap());
    values.collect()
}

/// The devkit's `computeBox3D`: corners of `h w l x y z ry` in the label's camera.
fn devkit_corners(v: &[f64]) -> [[f64; 3]; 8] {
    let (h, w, l, ry) = (v[0], v[1], v[2], v[6]);
    let xs = [
        l / 2.0,
        l / 2.0,
        -l / 2.0,
        -l / 2.0,
        l / 2.0,
        l / 2.0,
        -l / 2.0,
        -l / 2.0,
    ];
    let ys = [0.0, 0.0, 0.0, 0.0, -h, -h, -h, -h];
    let zs = [
        w / 2.0,
        -w / 2.0,
        -w / 2.0,
        w / 2.0,
        w / 2.0,
        -w / 2.0,
        -w / 2.0,
        w / 2.0,
    ];
    let (c, s) = (libm::cos(ry), libm::sin(ry));
    std::array::from_fn(|i| {
        [
            c * xs[i] + s * zs[i] + v[3],
            ys[i] + v[4],
            -s * xs[i] + c * zs[i] + v[5],
        ]
    })
}

#[test]
fn projected_kitti_corners_contain_every_full_box() {
    let yaws = [0.0f64, 25.0, -70.0, 90.0, 140.0, 10.0, -35.0];
    let boxes: Vec<Box3d> = yaws
        .iter()
        .enumerate()
        .map(|(i, &yaw)| Box3d {
            centre: [-9.0 + 3.0 * i as f64, 0.75, -8.0 - 4.0 * (i % 3) as f64],
            size: [4.2, 1.8, 1.5],
            yaw: yaw.to_radians(),
        })
        .collect();
    let scene = scene(&boxes);
    let prepared = render::prepare(&scene).unwrap();
    let categories = [Category {
        id: 1,
        name: "car".into(),
        keypoints: false,
    }];
    let labels: Vec<ObjectLabel> = scene
        .objects
        .iter()
        .map(|o| ObjectLabel {
            name: o.name.clone(),
            box3d: Box3d::around(o.meshes[0].positions.iter().map(|p| p.map(f64::from))),
            keypoints: None,
            category: (o.name != "ground").then_some(1),
            text: None,
            attributes: BTreeMap::new(),
            sign: None,
        })
        .collect();
    let k = Intrinsics::from_fov(160, 120, 0.6);
    let lighting = Lighting::day();
    let measure: Vec<u32> = (2..=scene.objects.len() as u32).collect();
    // Level, pitched down, rolled, and turned so boxes leave the image.
    let mut poses = vec![
        CameraPose::level([0.0, 1.6, 2.0], [0.0, 1.6, -10.0]),
        CameraPose::level([1.0, 2.5, 3.0], [-2.0, 0.0, -12.0]),
        CameraPose::level([-3.0, 1.2, 1.0], [4.0, 0.8, -9.0]),
    ];
    poses[2].up = [0.2, 1.0, 0.0];
    let mut checked = 0;
    for pose in &poses {
        let (frame, footprints) =
            render::render_measuring(&prepared, pose, &k, &lighting, 1, &measure);
        let input = FrameInput {
            file_name: "rgb/000000.png".into(),
            instance: &frame.instance,
            rgb: None,
            intrinsics: [k.fx, k.fy, k.cx, k.cy],
            pose: *pose,
            full: footprints
                .iter()
                .map(|f| (f.id, (f.bbox().map(|v| v as f64), f.pixels)))
                .collect(),
            quads: BTreeMap::new(),
            depth: None,
        };
        let thresholds = Thresholds {
            min_pixels: 1,
            min_fraction: 0.0,
        };
        let summary = annotate::summarize(&labels, &input, &thresholds);
        let files = annotate::kitti(&summary, &categories);
        let p2 = calib_row(&files.calib, "P2");
        assert_eq!(p2.len(), 12);
        for name in ["P0", "P1", "P3", "Tr_velo_to_cam", "Tr_imu_to_velo"] {
            assert_eq!(calib_row(&files.calib, name).len(), 12, "{name}");
        }
        assert_eq!(calib_row(&files.calib, "R0_rect").len(), 9);
        let shown: Vec<_> = (summary.objects.iter())
            .filter(|o| o.passes() && o.category.is_some())
            .collect();
        let lines: Vec<&str> = files.label.lines().collect();
        assert_eq!(lines.len(), shown.len(), "{}", files.label);
        assert!(!lines.is_empty());
        for (line, object) in lines.iter().zip(shown) {
            let fields: Vec<&str> = line.split_whitespace().collect();
            assert_eq!((fields.len(), fields[0]), (15, "Car"), "{line}");
            let v: Vec<f64> = fields[8..].iter().map(|f| f.parse().unwrap()).collect();
            let corners = devkit_corners(&v);
            if corners.iter().any(|c| c[2] <= k.near) {
                continue;
            }
            let projected = corners.map(|c| {
                let row = |r: usize| {
                    p2[4 * r] * c[0] + p2[4 * r + 1] * c[1] + p2[4 * r + 2] * c[2] + p2[4 * r + 3]
                };
                [row(0) / row(2), row(1) / row(2)]
            });
            let lo = |a: usize| projected.iter().map(|p| p[a]).fold(f64::INFINITY, f64::min);
            let hi = |a: usize| {
                projected
                    .iter()
                    .map(|p| p[a])
                    .fold(f64::NEG_INFINITY, f64::max)
            };
            // The full box covers pixels [x, x + w) × [y, y + h): their centres lie inside
            // the projection (labels are written to 2 decimals: 0.01 m).
            let [x, y, w, h] = object.full_box.unwrap();
            let slack = 0.6;
            assert!(
                lo(0) <= x + 0.5 + slack && hi(0) >= x + w - 0.5 - slack,
                "{line}: {projected:?} vs {:?}",
                object.full_box
            );
            assert!(
                lo(1) <= y + 0.5 + slack && hi(1) >= y + h - 0.5 - slack,
                "{line}: {projected:?} vs {:?}",
                object.full_box
            );
            // And tightly: the box is the mesh's own.
            assert!(lo(0) >= x - 3.0 && hi(0) <= x + w + 3.0, "{line}: loose");
            checked += 1;
        }
    }
    assert!(checked >= 10, "{checked} boxes checked");
}
