//! WebDataset output (`[output] layout = "webdataset"`): a camera path's frames as tar
//! shards of `samples_per_shard` samples, `frames/<camera>/wds/000000.tar`, …
//!
//! A sample is one frame: `000000.rgb.png`, `000000.ids.png`, `000000.depth.png` (or
//! `.depth.npy`), `000000.json` (its COCO image entry and annotations, with the ids of
//! the path's `coco.json`, its sun and drawn conditions) and, when written,
//! `000000.yolo.txt` and `000000.icdar.txt`, members in name order. The tars are
//! byte-reproducible: the `tar` crate writes ustar headers with everything fixed here
//! (mode 0644, uid and gid 0, no user or group name, mtime 0), so the same frames give the
//! same bytes on every machine, whoever rendered them. A member name over 100 bytes that
//! ustar's prefix field cannot hold goes in a GNU long-name entry before its header.

use std::io::{self, Write};

use serde_json::Value;

use crate::annotate::CocoLines;

/// Version of the tar and sample layout (in the path's key with this layout). 2: headers
/// written by the `tar` crate, whose checksum field is seven digits and a NUL (ours was six
/// digits, a NUL and a space).
pub const VERSION: u32 = 2;

/// The sample member name of frame file `rest` (relative to `frames/<camera>/`), or
/// `None` when it is not one frame's file: `rgb/000007.png` → `000007.rgb.png`.
pub fn member_name(rest: &str) -> Option<String> {
    let (dir, file) = rest.split_once('/')?;
    let (stem, extension) = file.split_once('.')?;
    let (kind, stem) = match dir {
        "rgb" | "ids" | "depth" | "yolo" => (dir, stem),
        "icdar" => ("icdar", stem.strip_prefix("gt_")?),
        _ => return None,
    };
    let numbered = stem.len() >= 6 && stem.bytes().all(|b| b.is_ascii_digit());
    numbered.then(|| format!("{stem}.{kind}.{extension}"))
}

/// The frame index of a member name (`000007.rgb.png` → 7).
pub fn member_frame(member: &str) -> Option<usize> {
    member.split_once('.')?.0.parse().ok()
}

/// `NNNNNN.json`: the frame's COCO image entry, its annotations (numbered from
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
    fn member_names_follow_the_webdataset_convention() {
        assert_eq!(member_name("rgb/000007.png").unwrap(), "000007.rgb.png");
        assert_eq!(member_name("depth/000007.npy").unwrap(), "000007.depth.npy");
        assert_eq!(
            member_name("icdar/gt_000007.txt").unwrap(),
            "000007.icdar.txt"
        );
        assert_eq!(member_name("yolo/000007.txt").unwrap(), "000007.yolo.txt");
        assert_eq!(member_name("yolo/classes.txt"), None);
        assert_eq!(member_name("coco.json"), None);
        assert_eq!(member_frame("000007.rgb.png"), Some(7));
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
