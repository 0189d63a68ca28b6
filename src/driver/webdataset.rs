//! WebDataset output (`[output] layout = "webdataset"`): a camera path's frames as tar
//! shards of `samples_per_shard` samples, `frames/<camera>/wds/000000.tar`, …
//!
//! A sample is one frame, keyed `<camera>_<NNNNNN>` (the ultralytics folder's stem,
//! [`crate::dataset::stem`]), so the shards of every camera of a build can be read
//! together; a camera name holds no `.` (the spec's schema), where WebDataset splits key
//! from member. Its members, in name order, are the same in every sample of every camera
//! (but for the normals and KITTI files, a camera's own choice), so every loader sees the same columns:
//!
//! | member | what |
//! |---|---|
//! | `<key>.depth.npy` | depth in float32 metres (0 = sky), whatever the camera's `depth` format: a 16-bit PNG's values × its scale |
//! | `<key>.icdar.txt` | the ICDAR word lines; empty where the camera labels no text |
//! | `<key>.ids.png` | instance ids, 8-bit RGB, `id = R + 256·G + 65536·B` |
//! | `<key>.json` | its COCO image entry and annotations (the ids of the path's `coco.json`), sun and drawn conditions |
//! | `<key>.png` | the RGB image |
//! | `<key>.yolo.txt` | the YOLO lines, with `[annotations] yolo = true` (every camera then) |
//! | `<key>.normals.png` | the surface normals (16-bit RGB, as `normals/`), in the samples of a camera with `normals = true` only |
//! | `<key>.label_2.txt`, `<key>.calib.txt` | the KITTI object files, in the samples of a camera with `kitti = true` only |
//! | `<key>.flow.png` | the forward optical flow (KITTI's 16-bit PNG, as `flow/`), in the samples of a camera with `flow = true` but its last |
//! | `<key>.velodyne.bin`, `<key>.lidar.label` (and `<key>.lidar.ply`) | the LiDAR scan and its SemanticKITTI labels (and PLY), in the samples of a camera with a `lidar` only |
//! | `<key>.labelids.png`, `.instanceids.png`, `.color.png`, `.panoptic.png` | the Cityscapes-format images, with `[annotations] cityscapes = true` (every camera then) |
//!
//! The tars are byte-reproducible: the `tar` crate writes ustar headers with everything
//! fixed here (mode 0644, uid and gid 0, no user or group name, mtime 0), so the same frames
//! give the same bytes on every machine, whoever rendered them. A member name over 100 bytes
//! that ustar's prefix field cannot hold goes in a GNU long-name entry before its header.

use std::io::{self, Write};

use serde_json::Value;

use crate::annotate::CocoLines;
use crate::model::image_file::npy_f32;
use crate::spec::DepthFormat;

/// Version of the tar and sample layout (in the path's key with this layout). 2: headers
/// written by the `tar` crate, whose checksum field is seven digits and a NUL (ours was six
/// digits, a NUL and a space). 3: keys `<camera>_<NNNNNN>`, RGB as `<key>.png`, depth always
/// float32 metres in `.depth.npy`, an ICDAR member in every sample. 4: the Cityscapes-format
/// images as members.
pub const VERSION: u32 = 4;

/// A frame file's member of its sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Member {
    Rgb,
    Ids,
    Depth,
    Yolo,
    Icdar,
    /// With the camera's `normals = true`: the surface normals' PNG.
    Normals,
    /// With the camera's `kitti = true`: the KITTI `label_2` lines.
    KittiLabel,
    /// With the camera's `kitti = true`: the KITTI `calib` file.
    KittiCalib,
    /// With the camera's `flow = true`: the flow to the next frame.
    Flow,
    /// With the camera's `lidar`: the scan's `velodyne` records.
    Velodyne,
    /// With the camera's `lidar`: the scan's SemanticKITTI labels.
    LidarLabel,
    /// With the camera's `lidar.ply`: the scan as a PLY.
    LidarPly,
    /// With `[annotations] cityscapes = true`: a frame's Cityscapes image, by its index in
    /// [`super::frames::SEMANTIC_SUFFIXES`].
    Semantic(usize),
}

/// The extensions of the [`Member::Semantic`] members, in `SEMANTIC_SUFFIXES`' order: in
/// lower case, as the `webdataset` package hands every extension to its users.
const SEMANTIC_EXTENSIONS: [&str; 4] = [
    "labelids.png",
    "instanceids.png",
    "color.png",
    "panoptic.png",
];

impl Member {
    /// What follows the key and its dot in the member's name.
    pub fn extension(self) -> &'static str {
        match self {
            Member::Rgb => "png",
            Member::Ids => "ids.png",
            Member::Depth => "depth.npy",
            Member::Yolo => "yolo.txt",
            Member::Icdar => "icdar.txt",
            Member::Normals => "normals.png",
            Member::KittiLabel => "label_2.txt",
            Member::KittiCalib => "calib.txt",
            Member::Flow => "flow.png",
            Member::Velodyne => "velodyne.bin",
            Member::LidarLabel => "lidar.label",
            Member::LidarPly => "lidar.ply",
            Member::Semantic(k) => SEMANTIC_EXTENSIONS[k.min(SEMANTIC_EXTENSIONS.len() - 1)],
        }
    }
}

/// Frame file `rest` (relative to `frames/<camera>/`) as its frame index and member, or
/// `None` when it is not one frame's file: `rgb/000007.png` → (7, [`Member::Rgb`]).
pub fn frame_file(rest: &str) -> Option<(usize, Member)> {
    let (dir, file) = rest.split_once('/')?;
    let (stem, _) = file.split_once('.')?;
    let (member, stem) = match dir {
        "rgb" => (Member::Rgb, stem),
        "ids" => (Member::Ids, stem),
        "depth" => (Member::Depth, stem),
        "normals" => (Member::Normals, stem),
        "label_2" => (Member::KittiLabel, stem),
        "calib" => (Member::KittiCalib, stem),
        "flow" => (Member::Flow, stem),
        "velodyne" => (Member::Velodyne, stem),
        "labels" => (Member::LidarLabel, stem),
        "lidar" => (Member::LidarPly, stem),
        "yolo" => (Member::Yolo, stem),
        "icdar" => (Member::Icdar, stem.strip_prefix("gt_")?),
        "semantic" => {
            let (stem, suffix) = stem.split_once('_')?;
            let k = super::frames::SEMANTIC_SUFFIXES
                .iter()
                .position(|s| *s == suffix)?;
            (Member::Semantic(k), stem)
        }
        _ => return None,
    };
    let numbered = stem.len() >= 6 && stem.bytes().all(|b| b.is_ascii_digit());
    Some((stem.parse().ok().filter(|_| numbered)?, member))
}

/// Frame `frame` of camera `camera`'s sample key, unique over the build's cameras.
pub fn key(camera: &str, frame: usize) -> String {
    crate::dataset::stem(camera, frame)
}

/// The name of a sample's member: `<key>.<extension>`.
pub fn member_name(key: &str, member: Member) -> String {
    format!("{key}.{}", member.extension())
}

/// The depth member: a depth file of `format` as float32 metres in a `.npy`. An `f32`
/// file is that already; a 16-bit PNG's values are multiplied by the format's scale (in
/// f64, then rounded to f32), so 0 (the sky) stays 0.
pub fn depth_npy(bytes: &[u8], format: DepthFormat) -> io::Result<Vec<u8>> {
    if format == DepthFormat::F32 {
        return Ok(bytes.to_vec());
    }
    let image = image::load_from_memory_with_format(bytes, image::ImageFormat::Png)
        .map_err(io::Error::other)?;
    let image::DynamicImage::ImageLuma16(units) = image else {
        return Err(io::Error::other("a depth PNG that is not 16-bit grey"));
    };
    let scale = format.scale();
    let metres: Vec<f32> = units
        .as_raw()
        .iter()
        .map(|&v| (f64::from(v) * scale) as f32)
        .collect();
    Ok(npy_f32(units.width(), units.height(), &metres))
}

/// `<key>.json`: the frame's COCO image entry, its annotations (numbered from
/// `first_id`, as in `coco.json`), sun and conditions.
pub fn sample_json(coco: &CocoLines, first_id: u64, conditions: &Value) -> Vec<u8> {
    let mut text = String::from("{\"image\":");
    text.push_str(&coco.image);
    text.push_str(",\"annotations\":[");
    for (n, body) in coco.annotations.iter().enumerate() {
        if n > 0 {
            text.push(',');
        }
        let rest = body.strip_prefix('{').unwrap_or(body);
        text.push_str(&format!("{{\"id\":{},{rest}", first_id + n as u64));
    }
    text.push_str("],\"conditions\":");
    text.push_str(&conditions.to_string());
    text.push_str("}\n");
    text.into_bytes()
}

/// A tar stream over `out`: [`append`] its members, then [`finish`] it.
pub fn writer<W: Write>(out: W) -> tar::Builder<W> {
    tar::Builder::new(out)
}

/// Appends one regular file: a ustar header with every field fixed but the name, size and
/// checksum, then the bytes padded to 512.
pub fn append<W: Write>(tar: &mut tar::Builder<W>, name: &str, bytes: &[u8]) -> io::Result<()> {
    let mut header = tar::Header::new_ustar();
    header.set_entry_type(tar::EntryType::Regular);
    header.set_mode(0o644);
    header.set_uid(0);
    header.set_gid(0);
    header.set_mtime(0);
    header.set_size(bytes.len() as u64);
    tar.append_data(&mut header, name, bytes)
}

/// Ends a tar stream (two zero blocks) and hands back its writer.
pub fn finish<W: Write>(tar: tar::Builder<W>) -> io::Result<W> {
    tar.into_inner()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_files_become_members_of_the_camera_s_sample() {
        let cases = [
            (
                "rgb/000007.png",
                Some((7, Member::Rgb)),
                "street_000007.png",
            ),
            (
                "ids/000007.png",
                Some((7, Member::Ids)),
                "street_000007.ids.png",
            ),
            (
                "depth/000007.png",
                Some((7, Member::Depth)),
                "street_000007.depth.npy",
            ),
            (
                "depth/000007.npy",
                Some((7, Member::Depth)),
                "street_000007.depth.npy",
            ),
            (
                "normals/000007.png",
                Some((7, Member::Normals)),
                "street_000007.normals.png",
            ),
            (
                "label_2/000007.txt",
                Some((7, Member::KittiLabel)),
                "street_000007.label_2.txt",
            ),
            (
                "calib/000007.txt",
                Some((7, Member::KittiCalib)),
                "street_000007.calib.txt",
            ),
            (
                "icdar/gt_000007.txt",
                Some((7, Member::Icdar)),
                "street_000007.icdar.txt",
            ),
            (
                "yolo/000007.txt",
                Some((7, Member::Yolo)),
                "street_000007.yolo.txt",
            ),
            (
                "semantic/000007_instanceIds.png",
                Some((7, Member::Semantic(1))),
                "street_000007.instanceids.png",
            ),
            ("semantic/000007_depth.png", None, ""),
            ("semantic/labels.json", None, ""),
            ("yolo/classes.txt", None, ""),
            ("icdar/000007.txt", None, ""),
            ("rgb/07.png", None, ""),
            ("coco.json", None, ""),
        ];
        for (rest, parsed, name) in cases {
            assert_eq!(frame_file(rest), parsed, "{rest}");
            if let Some((frame, member)) = parsed {
                assert_eq!(member_name(&key("street", frame), member), name);
            }
        }
    }

    #[test]
    fn keys_of_two_cameras_differ_and_hold_no_dot() {
        assert_ne!(key("street", 0), key("aerial", 0));
        assert_eq!(key("a-b_c", 12), "a-b_c_000012");
        // WebDataset splits a member's name at the first dot of its base name.
        assert!(!key("street", 3).contains('.'));
    }

    /// The values of a `.npy` of float32 (`npy_f32`'s header), and its shape.
    fn npy_values(npy: &[u8]) -> (String, Vec<f32>) {
        assert_eq!(&npy[..8], b"\x93NUMPY\x01\x00");
        let len = usize::from(u16::from_le_bytes([npy[8], npy[9]]));
        let header = std::str::from_utf8(&npy[10..10 + len]).unwrap().to_owned();
        let values = npy[10 + len..]
            .chunks(4)
            .map(|b| f32::from_le_bytes(b.try_into().unwrap()))
            .collect();
        (header, values)
    }

    #[test]
    fn depth_members_are_float_metres_in_every_format() {
        let units = [0u16, 1, 250, 65_535];
        let png = |values: &[u16]| {
            let image = image::ImageBuffer::<image::Luma<u16>, _>::from_raw(2, 2, values.to_vec());
            let mut out = io::Cursor::new(Vec::new());
            image
                .unwrap()
                .write_to(&mut out, image::ImageFormat::Png)
                .unwrap();
            out.into_inner()
        };
        for (format, metres) in [
            (DepthFormat::Cm16, [0.0, 0.01, 2.5, 655.35]),
            (DepthFormat::Mm16, [0.0, 0.001, 0.25, 65.535]),
        ] {
            let (header, values) = npy_values(&depth_npy(&png(&units), format).unwrap());
            assert!(header.contains("'descr': '<f4'") && header.contains("(2, 2)"));
            assert_eq!(values, metres.map(|m: f64| m as f32), "{format:?}");
        }
        // An f32 file is already the member; 8-bit or broken PNGs are refused.
        let npy = npy_f32(1, 1, &[12.5]);
        assert_eq!(depth_npy(&npy, DepthFormat::F32).unwrap(), npy);
        assert!(depth_npy(b"not a png", DepthFormat::Cm16).is_err());
        let grey8 = image::GrayImage::from_raw(1, 1, vec![7]).unwrap();
        let mut out = io::Cursor::new(Vec::new());
        grey8.write_to(&mut out, image::ImageFormat::Png).unwrap();
        assert!(depth_npy(&out.into_inner(), DepthFormat::Mm16).is_err());
    }

    fn members(tar: &[u8]) -> Vec<(String, Vec<u8>)> {
        let mut archive = tar::Archive::new(tar);
        archive
            .entries()
            .unwrap()
            .map(|entry| {
                let mut entry = entry.unwrap();
                let name = entry.path().unwrap().to_string_lossy().into_owned();
                let mut bytes = Vec::new();
                io::Read::read_to_end(&mut entry, &mut bytes).unwrap();
                (name, bytes)
            })
            .collect()
    }

    #[test]
    fn tar_headers_are_fixed_and_checksummed() {
        let mut tar = writer(Vec::new());
        append(&mut tar, "000000.json", b"{}\n").unwrap();
        let tar = finish(tar).unwrap();
        assert_eq!(tar.len(), 512 + 512 + 1024);
        let header = &tar[..512];
        assert_eq!(&header[..11], b"000000.json");
        assert_eq!(&header[100..124], b"0000644\x000000000\x000000000\x00");
        assert_eq!(&header[124..136], b"00000000003\0");
        assert_eq!(&header[136..148], b"00000000000\0");
        assert_eq!(&header[257..265], b"ustar\x0000");
        assert!(
            header[265..].iter().all(|&b| b == 0),
            "no user or group name"
        );
        let stored = u32::from_str_radix(std::str::from_utf8(&header[148..155]).unwrap(), 8);
        let mut blank = header.to_vec();
        blank[148..156].copy_from_slice(b"        ");
        assert_eq!(
            stored.unwrap(),
            blank.iter().map(|&b| u32::from(b)).sum::<u32>()
        );
        assert_eq!(&tar[512..515], b"{}\n");
        assert_eq!(
            members(&tar),
            [("000000.json".to_owned(), b"{}\n".to_vec())]
        );
    }

    #[test]
    fn member_names_over_100_bytes_round_trip() {
        let long = format!("{}.rgb.png", "7".repeat(120));
        let slashed = format!("{}/{}.json", "a".repeat(90), "b".repeat(60));
        let write = || {
            let mut tar = writer(Vec::new());
            append(&mut tar, &long, b"long").unwrap();
            append(&mut tar, &slashed, b"slashed").unwrap();
            append(&mut tar, "000000.json", b"short").unwrap();
            finish(tar).unwrap()
        };
        let tar = write();
        assert_eq!(
            members(&tar),
            [
                (long.clone(), b"long".to_vec()),
                (slashed.clone(), b"slashed".to_vec()),
                ("000000.json".to_owned(), b"short".to_vec()),
            ]
        );
        assert_eq!(write(), tar, "the same members give the same bytes");
    }
}
