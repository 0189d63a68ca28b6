//! Visible objects of a frame joined with their labels, and whether they pass the thresholds.

use super::frame_input::{FrameInput, Thresholds};
use super::object_label::ObjectLabel;
use super::visible_object::{VisibleObject, scan};

/// A labelled object that shows at least one pixel in a frame.
#[derive(Clone, Debug)]
pub struct ShownObject<'a> {
    pub visible: VisibleObject,
    pub label: &'a ObjectLabel,
    /// Its category in this frame: the label's, except for a sign seen from behind, which
    /// takes its back category (or none).
    pub category: Option<u32>,
    /// A sign seen from the front: its type (`stop`, …).
    pub subclass: Option<&'a str>,
    /// Full projected box `[x, y, w, h]`, when the renderer gave it.
    pub full_box: Option<[f64; 4]>,
    /// Visible ÷ projected pixels (at most 1), when the projected count is known and
    /// positive.
    pub fraction: Option<f64>,
    /// Whether it shows at least `min_pixels` and, where known, `min_fraction`. Objects
    /// that do not are written as COCO ignore regions (`iscrowd` 1).
    pub passes: bool,
}

/// The labelled objects visible in `frame`, in instance-id order. Ids without a label
/// (beyond `labels`) are ignored.
pub fn shown<'a>(
    labels: &'a [ObjectLabel],
    frame: &FrameInput,
    thresholds: &Thresholds,
) -> Vec<ShownObject<'a>> {
    scan(frame.instance)
        .into_iter()
        .filter_map(|visible| {
            let label = labels.get((visible.id as usize).checked_sub(1)?)?;
            let full = frame.full.get(&visible.id);
            let fraction = full
                .filter(|(_, projected)| *projected > 0)
                .map(|(_, projected)| (visible.pixels as f64 / *projected as f64).min(1.0));
            let passes = visible.pixels >= thresholds.min_pixels
                && fraction.is_none_or(|f| f >= thresholds.min_fraction);
            let (category, subclass) = match &label.sign {
                Some(sign) if sign.front_seen_from(frame.pose.eye) => {
                    (label.category, Some(sign.kind.as_str()))
                }
                Some(sign) => (sign.back_category, None),
                None => (label.category, None),
            };
            Some(ShownObject {
                full_box: full.map(|(b, _)| *b),
                visible,
                label,
                category,
                subclass,
                fraction,
                passes,
            })
        })
        .collect()
}
