//! The cameras' WebDataset shards (`frames/<camera>/wds/NNNNNN.tar`) + the split of every
//! frame → each split's shards over every camera, `wds/<split>/NNNNNN.tar`, of
//! `samples_per_shard` samples, in the order of the split's `coco/<split>.json` images.
//!
//! A sample is its camera's sample byte for byte: its members' ustar headers and padded
//! data, copied from the camera's shard (keys `<camera>_<NNNNNN>`, unique over the
//! dataset), so a split's shards are as reproducible as the cameras' and need no tar
//! writer here. Each split shard is made in memory: the stage holds every split's shards
//! until it hands them on (see ARCHITECTURE.md's known costs).

use std::collections::BTreeMap;
use std::ops::Range;

use super::coco_split::CameraCoco;
use super::{DatasetError, DatasetFile, Member, stem};
use crate::spec::SPLIT_NAMES;

/// A camera's shard: its name, bytes and samples' byte ranges by key.
type Shard = (String, Vec<u8>, BTreeMap<String, Range<usize>>);

/// The two zero blocks that end a tar.
const END: [u8; 1024] = [0; 1024];

/// Adds `wds/<split>/NNNNNN.tar` for each split of `members` (every frame, in dataset
/// order) to `files`; `read` hands a camera's shard by name.
pub(super) fn add(
    documents: &[CameraCoco],
    members: &[Member],
    per_shard: usize,
    read: &dyn Fn(&str) -> Result<Vec<u8>, DatasetError>,
    files: &mut BTreeMap<String, DatasetFile>,
) -> Result<(), DatasetError> {
    let per_shard = per_shard.max(1);
    // The camera shard last read.
    let mut shard: Option<Shard> = None;
    for (split, name) in SPLIT_NAMES.iter().enumerate() {
        let in_split = members.iter().filter(|m| m.split == split);
        let mut tars: Vec<Vec<u8>> = Vec::new();
        for (n, m) in in_split.enumerate() {
            let camera = documents[m.camera].camera;
            let source = format!("frames/{camera}/wds/{:06}.tar", m.frame / per_shard);
            if shard
                .as_ref()
                .is_none_or(|(read_name, ..)| *read_name != source)
            {
                let bytes = read(&source)?;
                let samples =
                    samples(&bytes).map_err(|why| DatasetError(format!("{source}: {why}")))?;
                shard = Some((source.clone(), bytes, samples));
            }
            let (_, bytes, samples) = shard.as_ref().expect("read above");
            let key = stem(camera, m.frame);
            let range = samples
                .get(&key)
                .ok_or_else(|| DatasetError(format!("{source}: no sample {key}")))?;
            if n % per_shard == 0 {
                tars.push(Vec::new());
            }
            let tar = tars.last_mut().expect("pushed above");
            tar.extend_from_slice(&bytes[range.clone()]);
        }
        for (n, mut tar) in tars.into_iter().enumerate() {
            tar.extend_from_slice(&END);
            files.insert(format!("wds/{name}/{n:06}.tar"), DatasetFile::Bytes(tar));
        }
    }
    Ok(())
}

/// A tar's samples: each key's members' byte range (their headers and padded data; a GNU
/// long-name entry with the member it names). A sample's members lie together, as
/// WebDataset needs them.
fn samples(tar: &[u8]) -> Result<BTreeMap<String, Range<usize>>, String> {
    let mut samples: BTreeMap<String, Range<usize>> = BTreeMap::new();
    let mut last: Option<String> = None;
    let mut at = 0;
    // Where the member (or the long-name entry before it) starts, and that long name.
    let mut start = 0;
    let mut long_name: Option<String> = None;
    while at + 512 <= tar.len() && tar[at..at + 512].iter().any(|&b| b != 0) {
        let header = &tar[at..at + 512];
        let size = octal(&header[124..136]).ok_or("a header's size is not octal")?;
        let data = at + 512;
        let end = data + size.div_ceil(512) * 512;
        if end > tar.len() {
            return Err("a member runs past the end".into());
        }
        if header[156] == b'L' {
            let name = &tar[data..data + size];
            let name = name.split(|&b| b == 0).next().unwrap_or_default();
            long_name = Some(String::from_utf8_lossy(name).into_owned());
            at = end;
            continue;
        }
        let name = match long_name.take() {
            Some(name) => name,
            None => {
                let name = field(&header[..100]).unwrap_or_default();
                match field(&header[345..500]) {
                    Some(prefix) => format!("{prefix}/{name}"),
                    None => name,
                }
            }
        };
        let key = name
            .split_once('.')
            .map(|(key, _)| key.to_owned())
            .ok_or_else(|| format!("member {name} has no extension"))?;
        if last.as_ref() == Some(&key) {
            samples.get_mut(&key).expect("inserted before").end = end;
        } else if samples.insert(key.clone(), start..end).is_some() {
            return Err(format!("the members of sample {key} are not together"));
        }
        last = Some(key);
        at = end;
        start = end;
    }
    Ok(samples)
}

/// A NUL-padded header text field, `None` when empty.
fn field(bytes: &[u8]) -> Option<String> {
    let text = bytes.split(|&b| b == 0).next().unwrap_or_default();
    (!text.is_empty()).then(|| String::from_utf8_lossy(text).into_owned())
}

/// A NUL- or space-ended octal header field.
fn octal(bytes: &[u8]) -> Option<usize> {
    let text = std::str::from_utf8(bytes).ok()?;
    let text = text.trim_matches(|c: char| c == '\0' || c == ' ');
    usize::from_str_radix(text, 8).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ustar member as the frames stage writes it (`tar` crate, fixed fields).
    fn tar(members: &[(&str, &[u8])]) -> Vec<u8> {
        let mut tar = tar::Builder::new(Vec::new());
        for (name, bytes) in members {
            let mut header = tar::Header::new_ustar();
            header.set_mode(0o644);
            header.set_mtime(0);
            header.set_size(bytes.len() as u64);
            tar.append_data(&mut header, name, *bytes).unwrap();
        }
        tar.into_inner().unwrap()
    }

    #[test]
    fn samples_are_the_byte_ranges_of_their_members() {
        let long = format!("{}.png", "k".repeat(120));
        let bytes = tar(&[
            ("a_000000.json", b"{}"),
            ("a_000000.png", &[7; 600]),
            (&long, b"x"),
            ("a_000001.json", b"[]"),
        ]);
        let found = samples(&bytes).unwrap();
        let keys: Vec<&str> = found.keys().map(String::as_str).collect();
        assert_eq!(keys, ["a_000000", "a_000001", &long[..120]]);
        assert_eq!(found["a_000000"], 0..512 + 512 + 512 + 1024);
        let a1 = found["a_000001"].clone();
        assert_eq!(a1.end, bytes.len() - 1024);
        // A sample's range is a tar of its own once two zero blocks end it.
        let mut alone = bytes[a1].to_vec();
        alone.extend_from_slice(&END);
        assert_eq!(alone, tar(&[("a_000001.json", b"[]")]));
        let mut long_alone = bytes[found[&long[..120]].clone()].to_vec();
        long_alone.extend_from_slice(&END);
        assert_eq!(long_alone, tar(&[(&long, b"x")]));
    }

    #[test]
    fn a_sample_split_apart_or_a_cut_tar_is_refused() {
        let apart = tar(&[("a.json", b"1"), ("b.json", b"2"), ("a.png", b"3")]);
        assert!(samples(&apart).unwrap_err().contains("not together"));
        let whole = tar(&[("a.json", &[1; 700])]);
        assert!(
            samples(&whole[..1024])
                .unwrap_err()
                .contains("past the end")
        );
        assert!(samples(&tar(&[("noext", b"1")])).is_err());
    }
}
