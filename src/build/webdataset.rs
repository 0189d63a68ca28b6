//! WebDataset output (`[output] layout = "webdataset"`): a camera path's frames as tar
//! shards of `samples_per_shard` samples, `frames/<camera>/wds/000000.tar`, …
//!
//! A sample is one frame: `000000.rgb.png`, `000000.ids.png`, `000000.depth.png` (or
//! `.depth.npy`), `000000.json` (its COCO image entry and annotations, with the ids of
//! the path's `coco.json`, its sun and drawn conditions) and, when written,
//! `000000.yolo.txt` and `000000.icdar.txt`, members in name order. The tars are
//! byte-reproducible: ustar headers written here with everything fixed (mode 0644, uid and
//! gid 0, no user or group name, mtime 0), so the same frames give the same bytes on every
//! machine, whoever rendered them.

use std::io::{self, Write};

use serde_json::Value;

use crate::annotate::CocoLines;

/// Version of the tar and sample layout (in the path's key with this layout).
pub const VERSION: u32 = 1;

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

/// Appends one regular file to a tar stream: a ustar header with every field fixed but
/// the name, size and checksum, then the bytes padded to 512.
pub fn append(out: &mut dyn Write, name: &str, bytes: &[u8]) -> io::Result<()> {
    if name.len() > 100 {
        return Err(io::Error::other(format!(
            "tar member name too long: {name}"
        )));
    }
    let mut header = [0u8; 512];
    header[..name.len()].copy_from_slice(name.as_bytes());
    let mut field =
        |at: usize, text: &str| header[at..at + text.len()].copy_from_slice(text.as_bytes());
    field(100, "0000644\0"); // mode
    field(108, "0000000\0"); // uid
    field(116, "0000000\0"); // gid
    field(124, &format!("{:011o}\0", bytes.len())); // size
    field(136, "00000000000\0"); // mtime
    field(156, "0"); // a regular file
    field(257, "ustar\0");
    field(263, "00");
    // The checksum: the header's bytes summed with its own field as spaces.
    header[148..156].copy_from_slice(b"        ");
    let sum: u32 = header.iter().map(|&b| u32::from(b)).sum();
    header[148..156].copy_from_slice(format!("{sum:06o}\0 ").as_bytes());
    out.write_all(&header)?;
    out.write_all(bytes)?;
    out.write_all(&[0u8; 512][..(512 - bytes.len() % 512) % 512])
}

/// Ends a tar stream: two zero blocks.
pub fn finish(out: &mut dyn Write) -> io::Result<()> {
    out.write_all(&[0u8; 1024])
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

    #[test]
    fn tar_headers_are_fixed_and_checksummed() {
        let mut tar = Vec::new();
        append(&mut tar, "000000.json", b"{}\n").unwrap();
        finish(&mut tar).unwrap();
        assert_eq!(tar.len(), 512 + 512 + 1024);
        let header = &tar[..512];
        assert_eq!(&header[..11], b"000000.json");
        assert_eq!(&header[124..136], b"00000000003\0");
        assert_eq!(&header[136..148], b"00000000000\0");
        assert_eq!(&header[257..263], b"ustar\0");
        let stored = u32::from_str_radix(std::str::from_utf8(&header[148..154]).unwrap(), 8);
        let mut blank = header.to_vec();
        blank[148..156].copy_from_slice(b"        ");
        assert_eq!(
            stored.unwrap(),
            blank.iter().map(|&b| u32::from(b)).sum::<u32>()
        );
        assert_eq!(&tar[512..515], b"{}\n");
    }
}
