//! The ultralytics folder `yolo/`: `data.yaml` (and `dataset.yaml`, the same bytes, the
//! name FiftyOne's `YOLOv5Dataset` reads), and each frame's image and label file under
//! `images/<split>/` and `labels/<split>/` (ultralytics finds a label by replacing
//! `/images/` with `/labels/` in the image's path).

use std::collections::BTreeMap;
use std::fmt::Write as _;

use super::coco_split::CameraCoco;
use super::{DatasetError, DatasetFile, DatasetInput, Member, stem};
use crate::spec::SPLIT_NAMES;

/// Adds the folder's files to `files`.
pub(super) fn add(
    input: &DatasetInput,
    documents: &[CameraCoco],
    members: &[Member],
    read: &dyn Fn(&str) -> Result<Vec<u8>, DatasetError>,
    files: &mut BTreeMap<String, DatasetFile>,
) -> Result<(), DatasetError> {
    // The classes of every camera merged by name, in order of first appearance; a camera
    // whose classes are not that list's first lines gets its label files renumbered.
    let mut names: Vec<&str> = Vec::new();
    let per_camera: Vec<Vec<&str>> = input
        .cameras
        .iter()
        .map(|c| c.yolo_classes.unwrap_or_default().lines().collect())
        .collect();
    for classes in &per_camera {
        for name in classes {
            if !names.contains(name) {
                names.push(name);
            }
        }
    }
    let renumber: Vec<Option<Vec<usize>>> = per_camera
        .iter()
        .map(|classes| {
            let ids: Vec<usize> = classes
                .iter()
                .map(|c| names.iter().position(|n| n == c).unwrap_or_default())
                .collect();
            (!ids.iter().enumerate().all(|(i, id)| i == *id)).then_some(ids)
        })
        .collect();
    for m in members {
        let camera = documents[m.camera].camera;
        if input.cameras[m.camera].yolo_classes.is_none() {
            return Err(DatasetError(format!(
                "frames/{camera}/yolo/classes.txt missing: the path wrote no YOLO files"
            )));
        }
        let split = SPLIT_NAMES[m.split];
        let stem = stem(camera, m.frame);
        let image = documents[m.camera].file_name(m.frame).ok_or_else(|| {
            DatasetError(format!(
                "frames/{camera}/coco.json: image {} has no file_name",
                m.frame + 1
            ))
        })?;
        let label = format!("frames/{camera}/yolo/{:06}.txt", m.frame);
        let label = match &renumber[m.camera] {
            None => DatasetFile::Same(label),
            Some(ids) => DatasetFile::Bytes(renumbered(&read(&label)?, ids, &label)?),
        };
        for (name, file) in [
            (
                format!("yolo/images/{split}/{stem}.png"),
                DatasetFile::Same(format!("frames/{camera}/{image}")),
            ),
            (format!("yolo/labels/{split}/{stem}.txt"), label),
        ] {
            if files.insert(name.clone(), file).is_some() {
                return Err(DatasetError(format!("two frames would both be {name}")));
            }
        }
    }
    // The same bytes under FiftyOne's default name: the output folder hard-links them.
    let yaml = data_yaml(input, &names).into_bytes();
    files.insert(
        "yolo/dataset.yaml".to_owned(),
        DatasetFile::Bytes(yaml.clone()),
    );
    files.insert("yolo/data.yaml".to_owned(), DatasetFile::Bytes(yaml));
    Ok(())
}

/// A label file with each line's class id `k` replaced by `ids[k]`.
fn renumbered(bytes: &[u8], ids: &[usize], name: &str) -> Result<Vec<u8>, DatasetError> {
    let bad = || DatasetError(format!("{name}: not YOLO lines of its classes.txt"));
    let text = std::str::from_utf8(bytes).map_err(|_| bad())?;
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        let (class, rest) = line.split_once(' ').ok_or_else(bad)?;
        let class: usize = class.parse().map_err(|_| bad())?;
        let id = ids.get(class).ok_or_else(bad)?;
        let _ = writeln!(out, "{id} {rest}");
    }
    Ok(out.into_bytes())
}

/// `data.yaml`: no `path`, so ultralytics takes the folder the file is in; `val` is the
/// train folder when there is no val split (ultralytics needs one).
fn data_yaml(input: &DatasetInput, names: &[&str]) -> String {
    let shares = input.splits.shares();
    let mut out = String::from(
        "# The YOLO dataset of this build (cityspec): `yolo train data=yolo/data.yaml`;\n\
         # dataset.yaml is the same file, for FiftyOne's YOLOv5Dataset.\n\
         # Paths are relative to this file's folder; images/<split>/X.png has labels/<split>/X.txt.\n",
    );
    for (k, split) in SPLIT_NAMES.iter().enumerate() {
        if shares[k] > 0.0 {
            let _ = writeln!(out, "{split}: images/{split}");
        } else if *split == "val" {
            let _ = writeln!(out, "val: images/train  # no val split in [splits]");
        }
    }
    out.push_str("names:\n");
    for (k, name) in names.iter().enumerate() {
        let quoted = serde_json::Value::from(*name).to_string();
        let _ = writeln!(out, "  {k}: {quoted}");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renumbering_maps_each_line_s_class() {
        let got = renumbered(b"0 0.5 0.5 0.1 0.1\n1 0.2 0.2 0.1 0.1\n", &[2, 0], "x").unwrap();
        assert_eq!(got, b"2 0.5 0.5 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
        assert!(renumbered(b"5 0.5 0.5 0.1 0.1\n", &[2, 0], "x").is_err());
        assert!(renumbered(b"car\n", &[2, 0], "x").is_err());
    }
}
