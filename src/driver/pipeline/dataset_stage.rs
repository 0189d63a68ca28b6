//! The dataset stage: every camera path's frames (evaluated first), read back from the
//! cache where the stage needs their bytes, handed to [`dataset::assemble`].

use std::collections::BTreeMap;
use std::sync::Arc;

use super::super::BuildError;
use super::super::decode_error::DecodeError;
use super::super::stages::Stage;
use super::Pipeline;
use super::evaluate::evaluated;
use crate::cache::{Blob, Outputs};
use crate::dataset::{self, CameraFiles, DatasetError, DatasetFile, DatasetInput};

impl Pipeline<'_> {
    /// `coco/<split>.json` and `yolo/`, when the spec has `[splits]`.
    pub(super) fn need_dataset(&mut self) -> Result<(), BuildError> {
        self.stage(
            Stage::Dataset,
            None,
            |p| &mut p.dataset,
            |p| (0..p.cameras()).try_for_each(|camera| p.need_frames(camera)),
            |p, ()| Ok(((), p.dataset_outputs()?)),
        )
    }

    fn dataset_outputs(&self) -> Result<Outputs, BuildError> {
        let invalid = |e: DatasetError| BuildError::Decode {
            stage: Stage::Dataset.name(),
            source: DecodeError::Inputs(e.0),
        };
        let Some(inputs) = &self.inputs.dataset else {
            return Ok(Outputs::new());
        };
        // A camera path's output by name (`frames/<camera>/…`), with its camera's outputs.
        let blob = |name: &str| -> Option<&Blob> {
            let camera = name.strip_prefix("frames/")?.split('/').next()?;
            let index = (0..self.cameras()).find(|&c| self.camera_name(c) == camera)?;
            evaluated(&self.frames[index]).outputs.get(name)
        };
        let read = |name: &str| -> Result<Vec<u8>, DatasetError> {
            let missing = || DatasetError(format!("{name} missing"));
            match blob(name).ok_or_else(missing)? {
                Blob::Bytes(bytes) | Blob::Stored(_, Some(bytes)) => Ok(bytes.to_vec()),
                Blob::Stored(object, None) => self
                    .cache
                    .read_object(object)
                    .map_err(|why| DatasetError(format!("{name}: cache object {why}"))),
            }
        };
        // A file the camera path writes only with some switch on.
        let optional = |name: &str| -> Result<Option<Vec<u8>>, BuildError> {
            blob(name).map(|_| read(name).map_err(invalid)).transpose()
        };
        let mut cocos = Vec::new();
        let mut classes = Vec::new();
        let mut panoptic = Vec::new();
        for camera in &inputs.cameras {
            cocos.push(read(&format!("frames/{camera}/coco.json")).map_err(invalid)?);
            panoptic.push(optional(&format!("frames/{camera}/panoptic.json"))?);
            let names = format!("frames/{camera}/yolo/classes.txt");
            let utf8 = |bytes| String::from_utf8(bytes).map_err(|_| format!("{names}: not UTF-8"));
            classes.push(
                optional(&names)?
                    .map(utf8)
                    .transpose()
                    .map_err(|e| invalid(DatasetError(e)))?,
            );
        }
        let cameras: Vec<CameraFiles> = inputs
            .cameras
            .iter()
            .zip(&cocos)
            .zip(&classes)
            .zip(&panoptic)
            .map(|(((name, coco), classes), panoptic)| CameraFiles {
                name,
                coco,
                yolo_classes: classes.as_deref(),
                panoptic: panoptic.as_deref(),
            })
            .collect();
        let input = DatasetInput {
            splits: &inputs.splits,
            yolo: inputs.yolo,
            cityscapes: inputs.cityscapes,
            seed: inputs.seed,
            cameras: &cameras,
            webdataset: inputs.webdataset.map(|n| n as usize),
        };
        let files = dataset::assemble(&input, &read).map_err(invalid)?;
        blobs(files, &blob).map_err(invalid)
    }
}

/// The stage's files as outputs: a [`DatasetFile::Same`] is the camera path's blob of that
/// name (`blob`), the same cache object, so no bytes are copied.
fn blobs<'b>(
    files: BTreeMap<String, DatasetFile>,
    blob: &dyn Fn(&str) -> Option<&'b Blob>,
) -> Result<Outputs, DatasetError> {
    files
        .into_iter()
        .map(|(name, file)| {
            let blob = match file {
                DatasetFile::Same(source) => match blob(&source) {
                    Some(Blob::Stored(object, _)) => Blob::Stored(object.clone(), None),
                    Some(blob) => blob.clone(),
                    None => return Err(DatasetError(format!("{source} missing"))),
                },
                DatasetFile::Bytes(bytes) => Blob::Bytes(Arc::new(bytes)),
            };
            Ok((name, blob))
        })
        .collect()
}
