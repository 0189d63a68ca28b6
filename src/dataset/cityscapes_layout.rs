//! The Cityscapes folder `cityscapes/`, laid out as `cityscapesscripts` reads it:
//! `leftImg8bit/<split>/<city>/<name>_leftImg8bit.png` (the frame),
//! `gtFine/<split>/<city>/<name>_gtFine_{labelIds,instanceIds,color}.png`,
//! `gtFine/cityscapes_panoptic_<split>.json` with its folder of `<name>_gtFine_panoptic.png`
//! (what its `createPanopticImgs` makes of the `instanceIds`), and `labels.json`, the
//! label table with the extra classes.
//!
//! A frame's `<name>` is `<city>_<sequence>_<frame>`: the city is the camera's name (`_`
//! written `-`, since Cityscapes' names split at `_`), the sequence the camera's index in
//! the spec, the frame its index; six digits each. Every image is the camera path's own
//! file under a second name ([`DatasetFile::Same`]).

use std::collections::BTreeMap;

use super::{CameraFiles, DatasetError, DatasetFile, Member};
use crate::annotate::{CityscapesLabel, PanopticImage, Segment, panoptic_json};
use crate::spec::SPLIT_NAMES;

/// Cityscapes' name of frame `frame` of the spec's camera `index`, named `camera`.
pub fn cityscapes_name(camera: &str, index: usize, frame: usize) -> String {
    format!("{}_{index:06}_{frame:06}", camera.replace('_', "-"))
}

/// A camera path's `panoptic.json`, as far as the layout reads it.
#[derive(serde::Deserialize)]
struct CameraPanoptic {
    images: Vec<CameraImage>,
    annotations: Vec<PanopticAnnotation>,
}

#[derive(serde::Deserialize)]
struct CameraImage {
    width: u32,
    height: u32,
    file_name: String,
}

#[derive(serde::Deserialize)]
struct PanopticAnnotation {
    segments_info: Vec<Segment>,
}

/// Adds the folder's files to `files`. Every camera in `cameras` has a `panoptic.json`.
pub(super) fn add(
    cameras: &[CameraFiles],
    members: &[Member],
    read: &dyn Fn(&str) -> Result<Vec<u8>, DatasetError>,
    files: &mut BTreeMap<String, DatasetFile>,
) -> Result<(), DatasetError> {
    let documents = cameras
        .iter()
        .map(|c| {
            let name = format!("frames/{}/panoptic.json", c.name);
            let bytes = c
                .panoptic
                .ok_or_else(|| DatasetError(format!("{name} missing")))?;
            let document: CameraPanoptic =
                serde_json::from_slice(bytes).map_err(|e| DatasetError(format!("{name}: {e}")))?;
            if document.images.len() != document.annotations.len() {
                return Err(DatasetError(format!(
                    "{name}: {} images but {} annotations",
                    document.images.len(),
                    document.annotations.len()
                )));
            }
            Ok(document)
        })
        .collect::<Result<Vec<_>, _>>()?;
    let Some(first) = cameras.first() else {
        return Ok(());
    };
    let labels_file = format!("frames/{}/semantic/labels.json", first.name);
    let labels = labels(&read(&labels_file)?, &labels_file)?;
    let mut panoptic: Vec<Vec<PanopticImage>> = vec![Vec::new(); SPLIT_NAMES.len()];
    for m in members {
        let image = member(cameras[m.camera].name, &documents[m.camera], m, files)?;
        panoptic[m.split].push(image);
    }
    for (split, images) in SPLIT_NAMES.iter().zip(&panoptic) {
        if !images.is_empty() {
            files.insert(
                format!("cityscapes/gtFine/cityscapes_panoptic_{split}.json"),
                DatasetFile::Bytes(panoptic_json(&labels, images)),
            );
        }
    }
    files.insert(
        "cityscapes/labels.json".to_owned(),
        DatasetFile::Same(labels_file),
    );
    Ok(())
}

/// Adds member `m`'s files (camera `camera`, whose `panoptic.json` is `document`) and
/// returns its image of the split's panoptic document.
fn member(
    camera: &str,
    document: &CameraPanoptic,
    m: &Member,
    files: &mut BTreeMap<String, DatasetFile>,
) -> Result<PanopticImage, DatasetError> {
    let image = document.images.get(m.frame).ok_or_else(|| {
        DatasetError(format!(
            "frames/{camera}/panoptic.json: no image {}",
            m.frame + 1
        ))
    })?;
    let split = SPLIT_NAMES[m.split];
    let name = cityscapes_name(camera, m.camera, m.frame);
    let city = camera.replace('_', "-");
    let source = |suffix: &str| format!("frames/{camera}/semantic/{:06}_{suffix}.png", m.frame);
    let gt = format!("cityscapes/gtFine/{split}/{city}/{name}_gtFine");
    for (file, same) in [
        (
            format!("cityscapes/leftImg8bit/{split}/{city}/{name}_leftImg8bit.png"),
            format!("frames/{camera}/{}", image.file_name),
        ),
        (format!("{gt}_labelIds.png"), source("labelIds")),
        (format!("{gt}_instanceIds.png"), source("instanceIds")),
        (format!("{gt}_color.png"), source("color")),
        (
            format!("cityscapes/gtFine/cityscapes_panoptic_{split}/{name}_gtFine_panoptic.png"),
            source("panoptic"),
        ),
    ] {
        if files
            .insert(file.clone(), DatasetFile::Same(same))
            .is_some()
        {
            return Err(DatasetError(format!("two frames would both be {file}")));
        }
    }
    Ok(PanopticImage {
        id: serde_json::Value::String(name.clone()),
        width: image.width,
        height: image.height,
        // As `createPanopticImgs` names it: the instanceIds file's name with `_instanceIds`
        // made `_leftImg8bit`.
        file_name: format!("{name}_gtFine_leftImg8bit.png"),
        segments_file: format!("{name}_gtFine_panoptic.png"),
        segments: document.annotations[m.frame].segments_info.clone(),
    })
}

/// The label table of a camera path's `semantic/labels.json`.
fn labels(bytes: &[u8], name: &str) -> Result<Vec<CityscapesLabel>, DatasetError> {
    #[derive(serde::Deserialize)]
    struct Table {
        labels: Vec<CityscapesLabel>,
    }
    let table: Table =
        serde_json::from_slice(bytes).map_err(|e| DatasetError(format!("{name}: {e}")))?;
    Ok(table.labels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_split_into_city_sequence_and_frame_at_underscores() {
        let name = cityscapes_name("side_walk", 2, 17);
        assert_eq!(name, "side-walk_000002_000017");
        assert_eq!(name.split('_').count(), 3);
    }
}
