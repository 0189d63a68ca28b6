//! Dataset stage: every camera path's frames and annotations + `[splits]` → the
//! dataset-level files: `coco/<split>.json` (one COCO document per split over all
//! cameras) and, with YOLO on, the ultralytics folder `yolo/` (`data.yaml`,
//! `images/<split>/<camera>_<NNNNNN>.png`, `labels/<split>/<camera>_<NNNNNN>.txt`).
//!
//! The stage decides which split each frame is in ([`assign`]), names the files and
//! writes the documents. It makes no image: an image of `yolo/images/` is the camera's
//! `frames/<camera>/rgb/` file under a second name ([`DatasetFile::Same`]), the same cache
//! object, which the output folder hard-links; so is a label file whose class ids need no
//! renumbering.
//!
//! | file | what |
//! |---|---|
//! | `coco/<split>.json` | the split's frames of every camera; image ids unique over the dataset (cameras in spec order, frames in order, from 1), annotation ids from 1 in each file; `file_name` relative to the output folder (`frames/<camera>/rgb/NNNNNN.png`); categories merged by name |
//! | `yolo/data.yaml` (and `yolo/dataset.yaml`, the same bytes, the name FiftyOne's YOLOv5 importer reads) | `train`/`val`/`test` folders relative to `yolo/`, `names` from the cameras' `yolo/classes.txt` |
//! | `yolo/images/<split>/`, `yolo/labels/<split>/` | one image and one label file per frame, named `<camera>_<NNNNNN>` |
//! | `wds/<split>/NNNNNN.tar` | with the WebDataset layout, instead of `yolo/`: the split's samples, the cameras' own (keys `<camera>_<NNNNNN>`), in the order of its COCO images, whose `file_name` is then the sample's `<key>.png` |
//! | `cityscapes/` | with `[annotations] cityscapes = true` and the files layout: `leftImg8bit/` and `gtFine/` as Cityscapes lays them out, COCO panoptic per split, `labels.json` (`cityscapes_layout.rs`) |

use std::collections::BTreeMap;

mod cityscapes_layout;
mod coco_split;
mod split_assignment;
mod wds_split;
mod yolo_layout;

pub use cityscapes_layout::cityscapes_name;
pub use split_assignment::{assign, counts};

use crate::spec::{SPLIT_NAMES, SplitsSpec};

/// Bump when this stage's output bytes change: it is part of the stage's cache key.
pub const VERSION: u32 = 2;

/// What the stage reads of one camera path's outputs.
pub struct CameraFiles<'a> {
    pub name: &'a str,
    /// `frames/<camera>/coco.json`.
    pub coco: &'a [u8],
    /// `frames/<camera>/yolo/classes.txt`, when the path writes YOLO files.
    pub yolo_classes: Option<&'a str>,
    /// `frames/<camera>/panoptic.json`, when the path writes Cityscapes-format files.
    pub panoptic: Option<&'a [u8]>,
}

/// One file of the dataset.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DatasetFile {
    /// The bytes of the camera path's output of this name (`frames/<camera>/…`).
    Same(String),
    /// New bytes.
    Bytes(Vec<u8>),
}

/// What the stage is asked.
pub struct DatasetInput<'a> {
    pub splits: &'a SplitsSpec,
    /// Whether the ultralytics folder is written (`[annotations] yolo = true`).
    pub yolo: bool,
    /// Whether the Cityscapes folder is written (`[annotations] cityscapes = true`).
    pub cityscapes: bool,
    pub seed: u64,
    pub cameras: &'a [CameraFiles<'a>],
    /// With `[output] layout = "webdataset"`, samples per shard: each split's shards
    /// `wds/<split>/NNNNNN.tar` (`wds_split.rs`) instead of the ultralytics folder.
    pub webdataset: Option<usize>,
}

/// A camera path's outputs that do not read as the frames stage writes them.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct DatasetError(pub String);

/// One frame of the dataset: its camera (index), its frame index, its split.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Member {
    pub camera: usize,
    pub frame: usize,
    pub split: usize,
}

/// The dataset's files by name. `read` hands a camera path's output by name (a label file
/// to renumber).
pub fn assemble(
    input: &DatasetInput,
    read: &dyn Fn(&str) -> Result<Vec<u8>, DatasetError>,
) -> Result<BTreeMap<String, DatasetFile>, DatasetError> {
    let documents = input
        .cameras
        .iter()
        .map(|c| coco_split::CameraCoco::parse(c.name, c.coco))
        .collect::<Result<Vec<_>, _>>()?;
    let frames: Vec<(&str, usize)> = documents.iter().map(|d| (d.camera, d.frames())).collect();
    let members = assign(input.splits, input.seed, &frames);
    let mut files = BTreeMap::new();
    for (split, name) in SPLIT_NAMES.iter().enumerate() {
        if input.splits.shares()[split] > 0.0 {
            let in_split: Vec<Member> = members
                .iter()
                .filter(|m| m.split == split)
                .copied()
                .collect();
            files.insert(
                format!("coco/{name}.json"),
                DatasetFile::Bytes(coco_split::document(
                    &documents,
                    &in_split,
                    input.webdataset,
                )?),
            );
        }
    }
    if let Some(per_shard) = input.webdataset {
        wds_split::add(&documents, &members, per_shard, read, &mut files)?;
    } else if input.yolo {
        yolo_layout::add(input, &documents, &members, read, &mut files)?;
    }
    // With WebDataset the Cityscapes images are members of the samples instead.
    if input.cityscapes && input.webdataset.is_none() {
        cityscapes_layout::add(input.cameras, &members, read, &mut files)?;
    }
    Ok(files)
}

/// The stem of frame `frame` of camera `camera` in the ultralytics folder: unique over
/// the dataset, since camera names are (and hold no `/`).
pub fn stem(camera: &str, frame: usize) -> String {
    format!("{camera}_{frame:06}")
}
