//! A camera path cut into chunks, so that its frames can be rendered by several machines
//! (shards) sharing one cache, and the path's files assembled afterwards from what they
//! left there, without rendering anything.
//!
//! - The path's **plan** (`frames-plan`, one per camera): its poses, categories and YOLO
//!   classes ([`PathPlan`]). Everything that needs the whole path, computed once.
//! - Its **chunks** (`frames-chunk`): frames `[k·CHUNK_FRAMES, (k+1)·CHUNK_FRAMES)`, each
//!   an entry naming the frames' files and `summary.jsonl`, one [`FrameRecord`] per frame.
//!   A chunk's key is the path's key and the chunk's frame range, nothing else: not the
//!   number of shards, so one machine, 4 shards and 16 shards share chunks.
//! - The **path** (`frames`, the artifact stage): every chunk's frame files plus
//!   `coco.json` (streamed into the cache from the records, two passes, memory flat in the
//!   number of frames), `poses.json`, `preview.png` and `yolo/classes.txt`. A one-machine
//!   build goes through the same chunks, so its bytes are a sharded build's bytes.

use std::io::{self, Write};
use std::ops::Range;
use std::sync::Arc;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::codec;
use super::frames::{self, FrameRecord, PathFrames};
use super::stage_key::StageKey;
use super::webdataset::{self, Member};
use crate::annotate::{self, Category};
use crate::cache::{Blob, Cache, Hashing, ObjectRef, Outputs};
use crate::model::CameraPose;
use crate::spec::{CameraSpec, OutputLayout, OutputSpec};

/// Frames per chunk. Fixed (never derived from the number of shards): chunk keys must be
/// the same whoever renders them. Ten frames of a 200-frame path give 20 chunks, enough to
/// balance 2 to 7 shards within one chunk of each other.
pub const CHUNK_FRAMES: usize = 10;

/// Version of the chunk and plan formats (`summary.jsonl`, `path.json`).
pub const VERSION: u32 = 1;

/// The name of a chunk's records among its outputs.
pub const SUMMARY: &str = "summary.jsonl";

/// The name of a plan's only output.
pub const PLAN: &str = "path.json";

/// What a camera path's files need besides its frames: decided once for the whole path.
#[derive(Debug, Serialize, Deserialize)]
pub struct PathPlan {
    pub poses: Vec<CameraPose>,
    pub categories: Vec<Category>,
    /// `yolo/classes.txt`, when the path writes YOLO files.
    pub yolo: Option<String>,
    /// `instances.json`: every instance id's kind, class and category on this path.
    pub instances: crate::model::Instances,
    /// The scene's Cityscapes labels, when the path writes Cityscapes-format files.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub semantic: Option<annotate::SemanticClasses>,
}

/// The frame ranges of a path of `frames` frames.
pub fn ranges(frames: usize) -> Vec<Range<usize>> {
    (0..frames.div_ceil(CHUNK_FRAMES))
        .map(|k| k * CHUNK_FRAMES..((k + 1) * CHUNK_FRAMES).min(frames))
        .collect()
}

/// The plan's key: the path's.
pub fn plan_key(frames_key: &str) -> String {
    StageKey::new("frames-plan", VERSION)
        .input("frames", frames_key)
        .finish()
}

/// A chunk's key: the path's key and its frame range.
pub fn chunk_key(frames_key: &str, range: &Range<usize>) -> String {
    StageKey::new("frames-chunk", VERSION)
        .spec("frames", &[range.start, range.end])
        .input("frames", frames_key)
        .finish()
}

/// Renders the frames of `range`: each file into the cache as it is made (or, with
/// `store` false, as `cityspec verify` reruns a stage, only hashed; the RGB images the
/// contact sheet picks, or with `keep_all` every file, for WebDataset tars, are then kept
/// in memory), then `summary.jsonl`. `progress` is told of each frame done. The caller
/// builds what every frame reads first ([`PathFrames::warm`]).
pub fn render_chunk(
    cache: &Cache,
    path: &PathFrames,
    total: usize,
    range: Range<usize>,
    (store, keep_all): (bool, bool),
    progress: impl Fn() + Sync,
) -> io::Result<Outputs> {
    let picks = crate::annotate::contact_sheet_picks(total);
    // A chunk's frames render side by side: a frame's serial tail (sensor, PNG encoding,
    // hashing, storing) overlaps another frame's tiles, where one frame at a time left a
    // core idle. Each frame's files and record are collected per frame and joined in frame
    // order, so the outputs do not depend on which frame finished first.
    let frames: Vec<io::Result<RenderedFrame>> = range
        .into_par_iter()
        .map(|i| {
            let keep = !store && (keep_all || picks.contains(&i));
            let mut files = Vec::new();
            let record = path.render(i, |name, bytes| {
                let blob = if store {
                    Blob::Stored(cache.put_object(&bytes)?, None)
                } else if keep && (keep_all || name.contains("/rgb/")) {
                    Blob::from(bytes)
                } else {
                    Blob::Stored(reference(&bytes), None)
                };
                files.push((name, blob));
                Ok::<_, io::Error>(())
            })?;
            progress();
            Ok((files, record))
        })
        .collect();
    let mut outputs = Outputs::new();
    let mut summary = Vec::new();
    for frame in frames {
        let (files, record) = frame?;
        outputs.extend(files);
        serde_json::to_writer(&mut summary, &record)?;
        summary.push(b'\n');
    }
    let blob = if store {
        Blob::Stored(cache.put_object(&summary)?, None)
    } else {
        Blob::from(summary)
    };
    outputs.insert(SUMMARY.to_owned(), blob);
    Ok(outputs)
}

/// A rendered frame's files (name, blob) and its record.
type RenderedFrame = (Vec<(String, Blob)>, FrameRecord);

/// The path's outputs from its chunks' (in frame order): their frame files, and
/// `coco.json`, `poses.json`, `preview.png`, `yolo/classes.txt` assembled from their
/// records; with `[output] layout = "webdataset"` the frames' files go into tar shards
/// instead ([`webdataset`]). With `store` false nothing is written to the cache.
// Long on purpose: two passes over the chunks' records run side by side (coco.json into
// the cache, and the poses, preview and first ids), sharing the closures that read the
// chunks one at a time; apart, each would take the chunks, the cache and the plan.
pub fn assemble(
    cache: &Cache,
    camera: &CameraSpec,
    plan: &PathPlan,
    chunks: &[Outputs],
    store: bool,
    output: &OutputSpec,
) -> io::Result<Outputs> {
    let dir = format!("frames/{}", camera.name);
    let webdataset = output.layout == OutputLayout::Webdataset;
    // With WebDataset the frames' files go into the tars, not the folder.
    let mut outputs: Outputs = chunks
        .iter()
        .flat_map(|chunk| chunk.iter().filter(|(name, _)| name.as_str() != SUMMARY))
        .filter(|_| !webdataset)
        .map(|(name, blob)| (name.clone(), without_bytes(blob)))
        .collect();
    let read = |blob: &Blob| -> io::Result<Arc<Vec<u8>>> {
        match blob {
            Blob::Stored(object, None) => cache
                .read_object(object)
                .map(Arc::new)
                .map_err(io::Error::other),
            Blob::Bytes(bytes) | Blob::Stored(_, Some(bytes)) => Ok(Arc::clone(bytes)),
        }
    };
    // Every chunk's records, one chunk in memory at a time.
    let each_record = |f: &mut dyn FnMut(usize, FrameRecord) -> io::Result<()>| {
        let mut i = 0;
        for chunk in chunks {
            let summary = chunk
                .get(SUMMARY)
                .ok_or_else(|| io::Error::other("a chunk lacks its summary"))?;
            for line in read(summary)?
                .split(|&b| b == b'\n')
                .filter(|l| !l.is_empty())
            {
                f(i, serde_json::from_slice(line)?)?;
                i += 1;
            }
        }
        Ok::<_, io::Error>(())
    };
    let coco = |out: &mut dyn Write| {
        let mut out = io::BufWriter::new(out);
        annotate::write_coco(&mut out, &plan.categories, |pass| {
            each_record(&mut |_, record| pass(&record.coco))
        })?;
        out.flush()
    };
    let picks = crate::annotate::contact_sheet_picks(plan.poses.len());
    // A plate's words share its instance id: MOT's rows are the plates.
    let words = plan
        .categories
        .iter()
        .find(|c| c.name == annotate::WORD_CATEGORY)
        .map(|c| u64::from(c.id));
    // Each frame's drawn conditions, the preview's frames, and per frame the id of its
    // first annotation in coco.json (for the WebDataset samples).
    let records = || {
        let mut drawn = Vec::with_capacity(plan.poses.len());
        let mut sheet = Vec::with_capacity(picks.len());
        let mut first_ids = Vec::with_capacity(plan.poses.len());
        let mut panoptic = Vec::new();
        let mut mot = String::new();
        let mut annotations = 1u64;
        each_record(&mut |i, record| {
            if camera.fps.is_some() {
                mot += &annotate::mot_lines(i, &record.coco, words).map_err(io::Error::other)?;
            }
            if plan.semantic.is_some() {
                let segments = record.panoptic.ok_or_else(|| {
                    io::Error::other(format!("frame {i}'s record lacks its panoptic segments"))
                })?;
                panoptic.push(segments);
            }
            first_ids.push(annotations);
            annotations += record.coco.annotations.len() as u64;
            if picks.contains(&i) {
                let name = format!("{dir}/rgb/{i:06}.png");
                let blob = chunks
                    .get(i / CHUNK_FRAMES)
                    .and_then(|chunk| chunk.get(&name))
                    .ok_or_else(|| io::Error::other(format!("a chunk lacks {name}")))?;
                sheet.push((read(blob)?, record.sheet));
            }
            drawn.push((record.conditions, record.traffic));
            Ok(())
        })?;
        // The picked frames decoded on every core, in order.
        let sheet = sheet
            .into_par_iter()
            .map(|(png, boxes)| Ok((codec::decode_png(&png).map_err(io::Error::other)?, boxes)))
            .collect::<io::Result<Vec<_>>>()?;
        Ok::<_, io::Error>((drawn, sheet, first_ids, panoptic, mot))
    };
    // coco.json is written while the other pass over the records gathers the rest.
    let (coco, gathered) = rayon::join(
        || {
            if store {
                cache.put_object_with(coco)
            } else {
                let mut sink = Hashing::new(io::sink());
                coco(&mut sink)?;
                Ok(sink.finish())
            }
        },
        records,
    );
    outputs.insert(format!("{dir}/coco.json"), Blob::Stored(coco?, None));
    let (drawn, sheet, first_ids, panoptic, mot) = gathered?;
    if drawn.len() != plan.poses.len() {
        return Err(io::Error::other(format!(
            "the chunks hold {} frames, the path {}",
            drawn.len(),
            plan.poses.len()
        )));
    }
    let mut files = path_files(&dir, camera, plan, drawn, sheet);
    if let Some(semantic) = &plan.semantic {
        files.extend(panoptic_files(&dir, camera, semantic, panoptic));
    }
    if let Some(fps) = camera.fps {
        let size = [camera.resolution[0], camera.resolution[1]];
        let seqinfo = annotate::mot_seqinfo(&camera.name, fps, plan.poses.len(), size);
        files.push((format!("{dir}/gt/gt.txt"), mot.into_bytes()));
        files.push((format!("{dir}/seqinfo.ini"), seqinfo.into_bytes()));
    }
    if webdataset {
        let tars = Tars {
            dir: &dir,
            camera,
            chunks,
            first_ids: &first_ids,
            per_tar: output.samples_per_shard.max(1) as usize,
            read: &read,
        };
        tars.store_all(cache, store, plan.poses.len(), &mut outputs)?;
    }
    for (name, bytes) in files {
        let object = if store {
            cache.put_object(&bytes)?
        } else {
            reference(&bytes)
        };
        outputs.insert(name, Blob::Stored(object, None));
    }
    Ok(outputs)
}

/// A path's files made from its plan and records: `poses.json`, `preview.png`,
/// `instances.json` and `yolo/classes.txt`.
fn path_files(
    dir: &str,
    camera: &CameraSpec,
    plan: &PathPlan,
    drawn: Vec<(serde_json::Value, Option<serde_json::Value>)>,
    sheet: Vec<(image::RgbImage, Vec<[u32; 5]>)>,
) -> Vec<(String, Vec<u8>)> {
    let mut files = vec![
        (
            format!("{dir}/poses.json"),
            frames::poses_json(camera, &plan.poses, drawn),
        ),
        (
            format!("{dir}/preview.png"),
            frames::preview_png(sheet, &plan.categories),
        ),
        (
            format!("{dir}/instances.json"),
            codec::to_pretty_json(&plan.instances),
        ),
    ];
    if let Some(classes) = &plan.yolo {
        files.push((
            format!("{dir}/yolo/classes.txt"),
            classes.clone().into_bytes(),
        ));
    }
    files
}

/// With Cityscapes-format files: the path's `semantic/labels.json` (the label table) and
/// `panoptic.json` (COCO panoptic over its frames, ids as in `coco.json`).
fn panoptic_files(
    dir: &str,
    camera: &CameraSpec,
    semantic: &annotate::SemanticClasses,
    panoptic: Vec<Vec<annotate::Segment>>,
) -> Vec<(String, Vec<u8>)> {
    let (width, height) = (camera.resolution[0], camera.resolution[1]);
    let images: Vec<annotate::PanopticImage> = panoptic
        .into_iter()
        .enumerate()
        .map(|(i, segments)| annotate::PanopticImage {
            id: serde_json::json!(i + 1),
            width,
            height,
            file_name: format!("rgb/{i:06}.png"),
            segments_file: format!("semantic/{i:06}_panoptic.png"),
            segments,
        })
        .collect();
    vec![
        (
            format!("{dir}/semantic/labels.json"),
            semantic.labels_json(),
        ),
        (
            format!("{dir}/panoptic.json"),
            annotate::panoptic_json(&semantic.labels, &images),
        ),
    ]
}

impl Tars<'_> {
    /// Writes the tars of a path of `frames` frames (into the cache unless `store` is
    /// false) and adds them to `outputs`.
    fn store_all(
        &self,
        cache: &Cache,
        store: bool,
        frames: usize,
        outputs: &mut Outputs,
    ) -> io::Result<()> {
        for (n, start) in (0..frames).step_by(self.per_tar).enumerate() {
            let range = start..(start + self.per_tar).min(frames);
            let object = if store {
                cache.put_object_with(|out| self.write(range, out))?
            } else {
                let mut sink = Hashing::new(io::sink());
                self.write(range, &mut sink)?;
                sink.finish()
            };
            let dir = self.dir;
            outputs.insert(format!("{dir}/wds/{n:06}.tar"), Blob::Stored(object, None));
        }
        Ok(())
    }
}

/// A path's WebDataset tars, from its chunks.
struct Tars<'a> {
    /// `frames/<camera>`.
    dir: &'a str,
    camera: &'a CameraSpec,
    chunks: &'a [Outputs],
    /// Per frame, the id of its first annotation in `coco.json`.
    first_ids: &'a [u64],
    per_tar: usize,
    /// A blob's bytes, from memory or the cache.
    read: &'a dyn Fn(&Blob) -> io::Result<Arc<Vec<u8>>>,
}

impl Tars<'_> {
    /// Writes the tar of frames `range` to `out`, one frame's files in memory at a time.
    fn write(&self, range: Range<usize>, out: &mut dyn Write) -> io::Result<()> {
        let mut tar = webdataset::writer(io::BufWriter::new(out));
        for k in range.start / CHUNK_FRAMES..range.end.div_ceil(CHUNK_FRAMES) {
            let chunk = &self.chunks[k];
            let summary = chunk
                .get(SUMMARY)
                .ok_or_else(|| io::Error::other("a chunk lacks its summary"))?;
            let summary = (self.read)(summary)?;
            let records = summary.split(|&b| b == b'\n').filter(|l| !l.is_empty());
            for (i, line) in (k * CHUNK_FRAMES..).zip(records) {
                if !range.contains(&i) {
                    continue;
                }
                let record: FrameRecord = serde_json::from_slice(line)?;
                let key = webdataset::key(&self.camera.name, i);
                let mut members = Vec::new();
                for (name, blob) in chunk {
                    let Some(rest) = name
                        .strip_prefix(self.dir)
                        .and_then(|r| r.strip_prefix('/'))
                    else {
                        continue;
                    };
                    let Some((frame, member)) = webdataset::frame_file(rest) else {
                        continue;
                    };
                    if frame != i {
                        continue;
                    }
                    let bytes = (self.read)(blob)?;
                    let bytes = match member {
                        Member::Depth => {
                            Arc::new(webdataset::depth_npy(&bytes, self.camera.depth)?)
                        }
                        _ => bytes,
                    };
                    members.push((webdataset::member_name(&key, member), bytes));
                }
                // Every sample of every camera has the same members: a path that labels
                // no text has an empty ICDAR member, as a frame without words does.
                let icdar = webdataset::member_name(&key, Member::Icdar);
                if !members.iter().any(|(name, _)| *name == icdar) {
                    members.push((icdar, Arc::new(Vec::new())));
                }
                let json =
                    webdataset::sample_json(&record.coco, self.first_ids[i], &record.conditions);
                members.push((format!("{key}.json"), Arc::new(json)));
                members.sort_by(|a, b| a.0.cmp(&b.0));
                for (member, bytes) in &members {
                    webdataset::append(&mut tar, member, bytes)?;
                }
            }
        }
        webdataset::finish(tar)?.flush()
    }
}

/// The reference `bytes` would have as an object, without storing them.
fn reference(bytes: &[u8]) -> ObjectRef {
    ObjectRef {
        sha256: crate::hash::sha256_hex(bytes),
        bytes: bytes.len() as u64,
    }
}

/// A frame file's blob as the path keeps it: a reference only.
fn without_bytes(blob: &Blob) -> Blob {
    match blob {
        Blob::Stored(object, _) => Blob::Stored(object.clone(), None),
        Blob::Bytes(bytes) => Blob::Stored(reference(bytes), None),
    }
}

/// Which of `shards` shards renders chunk `chunk` of the spec's camera `camera`: round
/// robin, each camera starting one shard further, so short paths do not all land on
/// shard 0.
pub fn owner(camera: usize, chunk: usize, shards: u32) -> u32 {
    ((camera + chunk) % shards as usize) as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_cover_the_path_in_fixed_chunks() {
        assert!(ranges(0).is_empty());
        assert_eq!((ranges(3).len(), ranges(3)[0].clone()), (1, 0..3));
        assert_eq!(ranges(20), [0..10, 10..20]);
        assert_eq!(ranges(21), [0..10, 10..20, 20..21]);
    }

    #[test]
    fn chunk_keys_depend_on_path_and_range_only() {
        let a = chunk_key("path", &(0..10));
        assert_eq!(a, chunk_key("path", &(0..10)));
        assert_ne!(a, chunk_key("path", &(10..20)));
        assert_ne!(a, chunk_key("other", &(0..10)));
        assert_ne!(plan_key("path"), plan_key("other"));
    }

    #[test]
    fn owners_spread_chunks_evenly() {
        for shards in [1u32, 2, 4, 7] {
            let mut counts = vec![0; shards as usize];
            for chunk in 0..20 {
                counts[owner(0, chunk, shards) as usize] += 1;
            }
            let (lo, hi) = (counts.iter().min(), counts.iter().max());
            assert!(hi.unwrap() - lo.unwrap() <= 1, "{shards}: {counts:?}");
        }
    }
}
