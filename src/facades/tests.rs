//! Stage tests: the builtin set through the loader, side files, bad data, determinism.

use std::sync::OnceLock;

use image::{Rgb, RgbImage};

use super::builtin::{COUNT, Design};
use super::cmp_box::{CmpBox, parse_cmp_xml, write_cmp_xml};
use super::cmp_label::CmpLabel;
use super::*;
use crate::model::PxRect;

fn builtin_cached() -> &'static FacadeSource {
    static SOURCE: OnceLock<FacadeSource> = OnceLock::new();
    SOURCE.get_or_init(builtin)
}

fn processed_builtin() -> &'static FacadeSet {
    static SET: OnceLock<FacadeSet> = OnceLock::new();
    SET.get_or_init(|| {
        let (set, warnings) = process(builtin_cached(), 3.0, OnError::Error).unwrap();
        assert_eq!(warnings, vec![]);
        set
    })
}

#[test]
fn builtin_set_loads_with_the_floors_the_generator_drew() {
    let source = builtin_cached();
    let set = processed_builtin();
    assert!(set.facades.len() >= 24);
    assert_eq!(set.facades.len(), COUNT);
    assert_eq!(source.origin, "builtin");
    for (i, (facade, file)) in set.facades.iter().zip(&source.files).enumerate() {
        let design = Design::new(i);
        assert_eq!(facade.name, file.name);
        assert_eq!(
            facade.floors, design.floors,
            "{}: window-row estimate",
            facade.name
        );
        assert_eq!(facade.height, f64::from(design.floors) * 3.0);
        let (cw, ch) = (
            f64::from(facade.texture.width),
            f64::from(facade.texture.height),
        );
        assert!((facade.width - cw / ch * facade.height).abs() < 1e-9);
        assert!(
            (6.0..=30.0).contains(&facade.width),
            "{}: {} m",
            facade.name,
            facade.width
        );

        let photo = painted(&file.photo);
        // The crop removes the sky, parapet and top molding, and keeps everything below.
        assert_eq!(facade.texture.width, photo.width());
        assert_eq!(facade.texture.height, photo.height() - builtin_crop_top());
        assert!((3..=8).contains(&facade.floors));
        assert!((250..=700).contains(&photo.width()), "{}", photo.width());
        assert!(!facade.windows.is_empty());
        for w in &facade.windows {
            assert!(
                w[0] >= 0.0 && w[1] >= 0.0 && w[2] <= 1.0 && w[3] <= 1.0,
                "{w:?}"
            );
            assert!(w[0] < w[2] && w[1] < w[3], "{w:?}");
        }
        assert!((facade.roof as usize) < set.roofs.len());
    }
    let mut photos: Vec<&[u8]> = source
        .files
        .iter()
        .map(|f| painted(&f.photo).as_raw().as_slice())
        .collect();
    photos.sort();
    photos.dedup();
    assert_eq!(photos.len(), COUNT, "builtin facades are distinct");
}

/// The pixels of a builtin photo (painted, never encoded).
fn painted(photo: &Photo) -> &RgbImage {
    match photo {
        Photo::Painted(image) => image,
        Photo::File(_) => panic!("a builtin photo is painted pixels"),
    }
}

#[test]
fn builtin_painted_and_processed_in_one_pass_is_the_same_set() {
    let (set, warnings) = process_builtin(3.0, OnError::Error).unwrap();
    assert_eq!(warnings, vec![]);
    assert_eq!(&set, processed_builtin());
    for (a, b) in set.facades.iter().zip(&processed_builtin().facades) {
        assert_eq!(a.texture.png, b.texture.png, "{}", a.name);
    }
}

fn builtin_crop_top() -> u32 {
    super::builtin::crop_top()
}

#[test]
fn builtin_boxes_lie_inside_their_images_and_match_the_label_masks() {
    for file in &builtin_cached().files {
        let photo = painted(&file.photo);
        let (w, h) = (photo.width(), photo.height());
        let xml = file.xml.as_deref().unwrap();
        // Every normalised coordinate written lies in 0–1 (the parser would clamp it).
        for value in xml.split(['<', '>']).filter_map(|s| s.parse::<f64>().ok()) {
            assert!((0.0..=12.0).contains(&value), "{}: {value}", file.name);
        }
        for part in xml.split("<points>").skip(1) {
            let coords: Vec<f64> = part
                .split("</points>")
                .next()
                .unwrap()
                .split(['<', '>'])
                .filter_map(|s| s.parse().ok())
                .collect();
            assert_eq!(coords.len(), 4);
            assert!(
                coords.iter().all(|c| (0.0..=1.0).contains(c)),
                "{}: {coords:?}",
                file.name
            );
        }
        let boxes = parse_cmp_xml(xml, w, h).unwrap();
        let labels = image::load_from_memory(file.labels.as_ref().unwrap())
            .unwrap()
            .to_luma8();
        assert_eq!(labels.dimensions(), (w, h));
        assert!(labels.pixels().all(|p| (1..=12).contains(&p[0])));
        for label in [
            CmpLabel::Window,
            CmpLabel::Door,
            CmpLabel::Sill,
            CmpLabel::Cornice,
            CmpLabel::Molding,
        ] {
            assert!(
                boxes.iter().any(|b| b.label == label),
                "{}: no {}",
                file.name,
                label.name()
            );
        }
        for b in &boxes {
            assert!(b.rect.x1 <= w && b.rect.y1 <= h);
            if b.label == CmpLabel::Window {
                let (cx, cy) = ((b.rect.x0 + b.rect.x1) / 2, (b.rect.y0 + b.rect.y1) / 2);
                assert_eq!(
                    labels.get_pixel(cx, cy)[0],
                    CmpLabel::Window.mask_value(),
                    "{}",
                    file.name
                );
            }
        }
    }
    let all: Vec<CmpLabel> = builtin_cached()
        .files
        .iter()
        .flat_map(|f| {
            let photo = painted(&f.photo);
            parse_cmp_xml(f.xml.as_deref().unwrap(), photo.width(), photo.height()).unwrap()
        })
        .map(|b| b.label)
        .collect();
    for label in [
        CmpLabel::Balcony,
        CmpLabel::Shop,
        CmpLabel::Blind,
        CmpLabel::Deco,
        CmpLabel::Pillar,
    ] {
        assert!(
            all.contains(&label),
            "no {} anywhere in the set",
            label.name()
        );
    }
}

#[test]
fn builtin_is_byte_identical_and_process_is_thread_count_independent() {
    assert_eq!(&builtin(), builtin_cached());
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| process(builtin_cached(), 3.0, OnError::Error).unwrap())
    };
    let (one, _) = run(1);
    let (three, _) = run(3);
    assert_eq!(&one, processed_builtin());
    assert_eq!(one, three);
    for (a, b) in one.facades.iter().zip(&three.facades) {
        assert_eq!(a.texture.png, b.texture.png);
    }
}

/// A small hand-made facade: a molding at rows 0–10, then `rows` rows of two windows.
fn small_file(name: &str, rows: u32) -> FacadeFile {
    let (w, h) = (80, 10 + rows * 40 + 20);
    let mut image = RgbImage::from_pixel(w, h, Rgb([200, 180, 150]));
    let mut boxes = vec![CmpBox {
        label: CmpLabel::Molding,
        rect: PxRect {
            x0: 0,
            y0: 0,
            x1: w,
            y1: 10,
        },
    }];
    for x in 0..10 {
        for y in 0..10 {
            image.put_pixel(x * 8, y, Rgb([90, 150, 120]));
        }
    }
    for r in 0..rows {
        for c in 0..2 {
            let rect = PxRect {
                x0: 10 + c * 40,
                y0: 20 + r * 40,
                x1: 30 + c * 40,
                y1: 45 + r * 40,
            };
            boxes.push(CmpBox {
                label: CmpLabel::Window,
                rect,
            });
        }
    }
    let mut photo = Vec::new();
    image::codecs::jpeg::JpegEncoder::new_with_quality(&mut photo, 90)
        .encode_image(&image)
        .unwrap();
    FacadeFile {
        name: name.to_string(),
        photo: Photo::File(photo),
        xml: Some(write_cmp_xml(&boxes, w, h)),
        labels: None,
    }
}

fn source(files: Vec<FacadeFile>, floors: Option<&str>) -> FacadeSource {
    FacadeSource {
        origin: "data/cmp".to_string(),
        files,
        floors: floors.map(str::to_string),
    }
}

#[test]
fn small_facade_is_cropped_sized_and_roofed() {
    let (set, _) = process(&source(vec![small_file("a", 3)], None), 3.0, OnError::Error).unwrap();
    let f = &set.facades[0];
    assert_eq!((f.floors, f.texture.width, f.texture.height), (3, 80, 140));
    assert_eq!(f.height, 9.0);
    assert!((f.width - 80.0 / 140.0 * 9.0).abs() < 1e-12);
    // The molding is mostly the wall colour with a few green stripes; JPEG blurs a little.
    for (c, expected) in f.molding.iter().zip([189, 177, 147]) {
        assert!((i32::from(*c) - expected).abs() <= 6, "{:?}", f.molding);
    }
    assert_eq!(set.roofs[f.roof as usize].name, "sand");
    assert_eq!(f.windows.len(), 6);
    assert_eq!(
        f.windows[0],
        [10.0 / 80.0, 10.0 / 140.0, 30.0 / 80.0, 35.0 / 140.0]
    );
}

#[test]
fn side_file_overrides_the_estimate_and_its_bad_lines_are_errors() {
    let files = vec![small_file("a", 3), small_file("b", 2)];
    let (set, warnings) = process(
        &source(files.clone(), Some("# counted by hand\na 5\nc 2\n")),
        3.5,
        OnError::Error,
    )
    .unwrap();
    assert_eq!(
        set.facades.iter().map(|f| f.floors).collect::<Vec<_>>(),
        [5, 2]
    );
    assert_eq!(set.facades[0].height, 17.5);
    assert_eq!(
        warnings,
        [crate::diagnostic::Diagnostic::warning(
            "facade-floors-unmatched",
            "data/cmp: floors file (facades.floors) lists `c`, which has no photo"
        )
        .at("facades.floors")]
    );
    let err = process(&source(files, Some("a 5\nb five\n")), 3.0, OnError::Skip).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("data/cmp: floors file (facades.floors), line 2: "),
        "{err}"
    );
}

#[test]
fn bad_facade_data_errors_or_is_skipped_as_the_spec_says() {
    let mut no_xml = small_file("no_xml", 2);
    no_xml.xml = None;
    let no_windows = small_file("no_windows", 0);
    let mut garbage = small_file("garbage", 2);
    garbage.photo = Photo::File(b"this is not a JPEG".to_vec());
    let mut truncated = small_file("truncated", 2);
    let Photo::File(bytes) = &mut truncated.photo else {
        panic!("small_file makes a file photo");
    };
    bytes.truncate(bytes.len() / 3);
    let mut bad_xml = small_file("bad_xml", 2);
    bad_xml.xml = Some("<object><points>".into());
    let mut low_molding = small_file("low_molding", 2);
    low_molding.xml = Some(write_cmp_xml(
        &[CmpBox {
            label: CmpLabel::Molding,
            rect: PxRect {
                x0: 0,
                y0: 0,
                x1: 80,
                y1: 108,
            },
        }],
        80,
        110,
    ));
    let mut tiny = small_file("tiny", 2);
    let mut tiny_jpeg = Vec::new();
    image::codecs::jpeg::JpegEncoder::new_with_quality(&mut tiny_jpeg, 90)
        .encode_image(&RgbImage::new(4, 6))
        .unwrap();
    tiny.photo = Photo::File(tiny_jpeg);
    let mut tiny_painted = small_file("tiny_painted", 2);
    tiny_painted.photo = Photo::Painted(RgbImage::new(4, 6));
    let cases = [
        (no_xml, "data/cmp/no_xml.xml: missing"),
        (
            tiny,
            "data/cmp/tiny.jpg: the photo is 4×6 px; 8 to 8192 px a side",
        ),
        (
            tiny_painted,
            "data/cmp/tiny_painted.jpg: the photo is 4×6 px; 8 to 8192 px a side",
        ),
        (
            no_windows,
            "data/cmp/no_windows.xml: no window boxes below the first molding",
        ),
        (garbage, "data/cmp/garbage.jpg: not a readable image"),
        (
            truncated,
            "data/cmp/truncated.jpg: not a whole image: found a truncated JPEG",
        ),
        (bad_xml, "data/cmp/bad_xml.xml: not valid XML"),
        (
            low_molding,
            "data/cmp/low_molding.xml: the first molding ends at row 108 of 110",
        ),
    ];
    for (bad, expected) in cases {
        let name = bad.name.clone();
        let files = vec![small_file("good", 2), bad];
        let err = process(&source(files.clone(), None), 3.0, OnError::Error).unwrap_err();
        assert!(err.to_string().starts_with(expected), "{name}: {err}");

        let (set, warnings) = process(&source(files, None), 3.0, OnError::Skip).unwrap();
        assert_eq!(
            set.facades
                .iter()
                .map(|f| f.name.as_str())
                .collect::<Vec<_>>(),
            ["good"]
        );
        assert_eq!(warnings.len(), 1, "{name}");
        assert!(
            warnings[0]
                .message
                .starts_with(&format!("skipped facade {name}: {expected}")),
            "{}",
            warnings[0]
        );
    }
}

#[test]
fn a_set_with_nothing_usable_is_an_error() {
    let mut bad = small_file("bad", 2);
    bad.xml = None;
    let err = process(&source(vec![bad], None), 3.0, OnError::Skip).unwrap_err();
    assert_eq!(
        err.to_string(),
        "data/cmp: no usable facades (1 found, 1 skipped for bad data)"
    );
    let err = process(&source(vec![], None), 3.0, OnError::Error).unwrap_err();
    assert_eq!(
        err.to_string(),
        "data/cmp: no usable facades (0 found, 0 skipped for bad data)"
    );
}

#[test]
fn a_facade_without_molding_is_kept_whole() {
    let mut file = small_file("whole", 2);
    let (w, h) = (80, 110);
    let windows: Vec<CmpBox> = parse_cmp_xml(file.xml.as_deref().unwrap(), w, h)
        .unwrap()
        .into_iter()
        .filter(|b| b.label == CmpLabel::Window)
        .collect();
    file.xml = Some(write_cmp_xml(&windows, w, h));
    let (set, _) = process(&source(vec![file], None), 3.0, OnError::Error).unwrap();
    let f = &set.facades[0];
    assert_eq!((f.texture.width, f.texture.height, f.floors), (w, h, 2));
    assert_eq!(f.windows[0][1], 20.0 / 110.0);
}
