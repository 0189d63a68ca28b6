//! Cityscapes' label table and which of its labels each scene object is.
//!
//! The table is Cityscapes' own (`cityscapesscripts` 2.3.0, `helpers/labels.py`, ids
//! 0–33; `license plate`, id −1, never appears in an id image). A class Cityscapes lacks
//! gets an extra label after it: `text` is always 34, other classes (a user's OBJ models:
//! `bench`, …) follow from 35 in name order. An extra label has instances, counts in
//! evaluation, and takes train ids from 19 on (after Cityscapes' 0–18).
//!
//! Which label an object is: its class, when that names an evaluated Cityscapes label
//! (`car`, `truck`, `bus`, `person`, `traffic_sign` as `traffic sign`, …), else its kind's
//! ([`kind_label`]): the grass around the city is `terrain`, blocks and sidewalks
//! `sidewalk`, roads and their markings `road`, lamps and the poles of signs, signals and
//! street-name signs `pole` (Cityscapes' rule: a street light on a pole is pole), trees
//! `vegetation`, and the sky (instance 0) `sky`.

use serde::{Deserialize, Serialize};

use crate::model::ObjectKind;

/// One label: Cityscapes' fields, named as `labels.py` names them.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct CityscapesLabel {
    pub name: String,
    pub id: u8,
    #[serde(rename = "trainId")]
    pub train_id: u8,
    pub category: String,
    #[serde(rename = "catId")]
    pub cat_id: u8,
    #[serde(rename = "hasInstances")]
    pub has_instances: bool,
    #[serde(rename = "ignoreInEval")]
    pub ignore_in_eval: bool,
    pub color: [u8; 3],
    /// Not Cityscapes' own: a class it lacks.
    pub extra: bool,
}

/// A row of `labels.py`: `(name, id, trainId, category, catId, hasInstances,
/// ignoreInEval, color)`.
type Row = (&'static str, u8, u8, &'static str, u8, bool, bool, [u8; 3]);

/// Cityscapes' labels, copied from
/// `cityscapesscripts/helpers/labels.py` (2.3.0); `tests/external/check_cityscapes.py`
/// compares the `labels.json` a build writes with the installed package's table.
const CITYSCAPES: [Row; 34] = [
    ("unlabeled", 0, 255, "void", 0, false, true, [0, 0, 0]),
    ("ego vehicle", 1, 255, "void", 0, false, true, [0, 0, 0]),
    (
        "rectification border",
        2,
        255,
        "void",
        0,
        false,
        true,
        [0, 0, 0],
    ),
    ("out of roi", 3, 255, "void", 0, false, true, [0, 0, 0]),
    ("static", 4, 255, "void", 0, false, true, [0, 0, 0]),
    ("dynamic", 5, 255, "void", 0, false, true, [111, 74, 0]),
    ("ground", 6, 255, "void", 0, false, true, [81, 0, 81]),
    ("road", 7, 0, "flat", 1, false, false, [128, 64, 128]),
    ("sidewalk", 8, 1, "flat", 1, false, false, [244, 35, 232]),
    ("parking", 9, 255, "flat", 1, false, true, [250, 170, 160]),
    (
        "rail track",
        10,
        255,
        "flat",
        1,
        false,
        true,
        [230, 150, 140],
    ),
    (
        "building",
        11,
        2,
        "construction",
        2,
        false,
        false,
        [70, 70, 70],
    ),
    (
        "wall",
        12,
        3,
        "construction",
        2,
        false,
        false,
        [102, 102, 156],
    ),
    (
        "fence",
        13,
        4,
        "construction",
        2,
        false,
        false,
        [190, 153, 153],
    ),
    (
        "guard rail",
        14,
        255,
        "construction",
        2,
        false,
        true,
        [180, 165, 180],
    ),
    (
        "bridge",
        15,
        255,
        "construction",
        2,
        false,
        true,
        [150, 100, 100],
    ),
    (
        "tunnel",
        16,
        255,
        "construction",
        2,
        false,
        true,
        [150, 120, 90],
    ),
    ("pole", 17, 5, "object", 3, false, false, [153, 153, 153]),
    (
        "polegroup",
        18,
        255,
        "object",
        3,
        false,
        true,
        [153, 153, 153],
    ),
    (
        "traffic light",
        19,
        6,
        "object",
        3,
        false,
        false,
        [250, 170, 30],
    ),
    (
        "traffic sign",
        20,
        7,
        "object",
        3,
        false,
        false,
        [220, 220, 0],
    ),
    (
        "vegetation",
        21,
        8,
        "nature",
        4,
        false,
        false,
        [107, 142, 35],
    ),
    ("terrain", 22, 9, "nature", 4, false, false, [152, 251, 152]),
    ("sky", 23, 10, "sky", 5, false, false, [70, 130, 180]),
    ("person", 24, 11, "human", 6, true, false, [220, 20, 60]),
    ("rider", 25, 12, "human", 6, true, false, [255, 0, 0]),
    ("car", 26, 13, "vehicle", 7, true, false, [0, 0, 142]),
    ("truck", 27, 14, "vehicle", 7, true, false, [0, 0, 70]),
    ("bus", 28, 15, "vehicle", 7, true, false, [0, 60, 100]),
    ("caravan", 29, 255, "vehicle", 7, true, true, [0, 0, 90]),
    ("trailer", 30, 255, "vehicle", 7, true, true, [0, 0, 110]),
    ("train", 31, 16, "vehicle", 7, true, false, [0, 80, 100]),
    ("motorcycle", 32, 17, "vehicle", 7, true, false, [0, 0, 230]),
    ("bicycle", 33, 18, "vehicle", 7, true, false, [119, 11, 32]),
];

/// Cityscapes' ids of the labels cityspec's own kinds are.
const SKY: u8 = 23;

/// The first extra label's id (`text`), and the last id an extra label may take: an
/// `instanceIds` pixel is `id × 1000 + k` in 16 bits, so ids stop at 64.
pub const FIRST_EXTRA: u8 = 34;
pub const LAST_ID: u8 = 64;

/// Cityscapes' own labels.
fn cityscapes() -> impl Iterator<Item = CityscapesLabel> {
    CITYSCAPES.iter().map(
        |&(name, id, train_id, category, cat_id, has_instances, ignore_in_eval, color)| {
            CityscapesLabel {
                name: name.to_owned(),
                id,
                train_id,
                category: category.to_owned(),
                cat_id,
                has_instances,
                ignore_in_eval,
                color,
                extra: false,
            }
        },
    )
}

/// What label a kind's object is: a Cityscapes id, or an extra class by name.
enum Home {
    Label(u8),
    Extra(String),
}

/// The Cityscapes id of `kind`'s objects, or `None` for a kind Cityscapes lacks.
fn kind_label(kind: ObjectKind) -> Option<u8> {
    Some(match kind {
        ObjectKind::Ground => 22,
        ObjectKind::Block | ObjectKind::Sidewalk => 8,
        ObjectKind::Road | ObjectKind::Marking => 7,
        ObjectKind::Building => 11,
        ObjectKind::Lamp
        | ObjectKind::SignPole
        | ObjectKind::SignalPole
        | ObjectKind::StreetPole => 17,
        ObjectKind::Sign => 20,
        ObjectKind::TrafficLight => 19,
        ObjectKind::Car => 26,
        ObjectKind::Bicycle => 33,
        ObjectKind::Rider => 25,
        ObjectKind::Person => 24,
        ObjectKind::Tree | ObjectKind::Hills => 21,
        ObjectKind::Text | ObjectKind::Mesh => return None,
    })
}

fn home(kind: ObjectKind, class: &str) -> Home {
    let spaced = class.replace('_', " ");
    let named = CITYSCAPES
        .iter()
        .find(|l| l.0 == spaced && !l.6)
        .map(|l| l.1);
    match named.or_else(|| kind_label(kind)) {
        Some(id) => Home::Label(id),
        None if kind == ObjectKind::Text => Home::Extra("text".to_owned()),
        None => Home::Extra(class.to_owned()),
    }
}

/// The label table of a scene and each of its objects' label.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SemanticClasses {
    /// Cityscapes' labels, then the extra ones; index = id.
    pub labels: Vec<CityscapesLabel>,
    /// By instance id (0: the sky), the object's label id.
    pub of_instance: Vec<u8>,
}

/// More classes than Cityscapes' instance images can number.
#[derive(Debug, thiserror::Error)]
#[error(
    "the scene has {0} classes Cityscapes lacks; its instance images number at most {max}",
    max = LAST_ID - FIRST_EXTRA + 1
)]
pub struct TooManyClasses(pub usize);

impl SemanticClasses {
    /// The labels of a scene whose objects are `objects` (kind, class; in scene order).
    pub fn of(objects: &[(ObjectKind, &str)]) -> Result<SemanticClasses, TooManyClasses> {
        let homes: Vec<Home> = objects.iter().map(|&(k, c)| home(k, c)).collect();
        let mut extras: Vec<&str> = homes
            .iter()
            .filter_map(|h| match h {
                Home::Extra(name) if name != "text" => Some(name.as_str()),
                _ => None,
            })
            .collect();
        extras.sort_unstable();
        extras.dedup();
        extras.insert(0, "text");
        if extras.len() > usize::from(LAST_ID - FIRST_EXTRA) + 1 {
            return Err(TooManyClasses(extras.len()));
        }
        let mut labels: Vec<CityscapesLabel> = cityscapes().collect();
        for (n, name) in (0u8..).zip(&extras) {
            labels.push(CityscapesLabel {
                name: (*name).to_owned(),
                id: FIRST_EXTRA + n,
                train_id: 19 + n,
                category: "object".to_owned(),
                cat_id: 3,
                has_instances: true,
                ignore_in_eval: false,
                color: extra_color(name),
                extra: true,
            });
        }
        let id_of = |name: &str| -> u8 {
            let n = extras.iter().position(|e| *e == name).unwrap_or(0);
            FIRST_EXTRA + n as u8
        };
        let of_instance = std::iter::once(SKY)
            .chain(homes.iter().map(|h| match h {
                Home::Label(id) => *id,
                Home::Extra(name) => id_of(name),
            }))
            .collect();
        Ok(SemanticClasses {
            labels,
            of_instance,
        })
    }

    /// The label of instance `id` (`unlabeled` for an id the scene lacks).
    pub fn label_of(&self, id: u32) -> &CityscapesLabel {
        let label = self.of_instance.get(id as usize).copied().unwrap_or(0);
        &self.labels[usize::from(label)]
    }

    /// `labels.json`: the table, one label a line.
    pub fn labels_json(&self) -> Vec<u8> {
        let mut text = String::from("{\"labels\": [\n");
        for (n, label) in self.labels.iter().enumerate() {
            let line = serde_json::to_string(label).expect("a label serializes");
            text.push_str("  ");
            text.push_str(&line);
            text.push_str(if n + 1 < self.labels.len() {
                ",\n"
            } else {
                "\n"
            });
        }
        text.push_str("]}\n");
        text.into_bytes()
    }
}

/// An extra label's colour: from its name's SHA-256, the same in every build.
fn extra_color(name: &str) -> [u8; 3] {
    use sha2::Digest;
    let digest = sha2::Sha256::digest(name.as_bytes());
    [digest[0], digest[1], digest[2]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_numbers_its_ids_in_order() {
        for (n, label) in cityscapes().enumerate() {
            assert_eq!(usize::from(label.id), n, "{}", label.name);
        }
    }

    #[test]
    fn objects_take_their_class_s_label_or_their_kind_s_or_an_extra_one() {
        let classes = SemanticClasses::of(&[
            (ObjectKind::Ground, "ground"),
            (ObjectKind::Car, "car"),
            (ObjectKind::Car, "bus"),
            (ObjectKind::Mesh, "bench"),
            (ObjectKind::Text, "text"),
            (ObjectKind::Mesh, "truck"),
            (ObjectKind::Mesh, "anchor"),
            (ObjectKind::Lamp, "lamp"),
            (ObjectKind::Sign, "traffic_sign"),
        ])
        .unwrap();
        let names: Vec<&str> = (0..10)
            .map(|id| classes.label_of(id).name.as_str())
            .collect();
        assert_eq!(
            names,
            [
                "sky",
                "terrain",
                "car",
                "bus",
                "bench",
                "text",
                "truck",
                "anchor",
                "pole",
                "traffic sign"
            ]
        );
        // text 34 always; the others by name from 35.
        assert_eq!(classes.label_of(5).id, 34);
        assert_eq!(classes.label_of(7).id, 35);
        assert_eq!(classes.label_of(4).id, 36);
        assert_eq!(classes.label_of(4).train_id, 21);
        assert_eq!(classes.label_of(99).name, "unlabeled");
        assert_eq!(classes.labels.len(), 37);
    }

    #[test]
    fn too_many_extra_classes_are_refused() {
        let names: Vec<String> = (0..31).map(|n| format!("model{n:02}")).collect();
        let objects: Vec<(ObjectKind, &str)> = names
            .iter()
            .map(|n| (ObjectKind::Mesh, n.as_str()))
            .collect();
        assert!(SemanticClasses::of(&objects[..30]).is_ok());
        let error = SemanticClasses::of(&objects).unwrap_err();
        assert_eq!(error.0, 32);
    }

    #[test]
    fn labels_json_reads_back() {
        let classes = SemanticClasses::of(&[(ObjectKind::Mesh, "bench")]).unwrap();
        let json: serde_json::Value = serde_json::from_slice(&classes.labels_json()).unwrap();
        let labels = json["labels"].as_array().unwrap();
        assert_eq!(labels.len(), 36);
        assert_eq!(labels[26]["name"], "car");
        assert_eq!(labels[26]["trainId"], 13);
        assert_eq!(labels[35]["name"], "bench");
        assert_eq!(labels[35]["extra"], true);
    }
}
