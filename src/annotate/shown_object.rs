//! Visible objects of a frame joined with their labels, and whether they pass the thresholds.

use super::contrast::{MIN_CONTRAST, contrast};
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
    /// Why it does not pass ([`ShownObject::passes`]), if it does not.
    pub ignored: Option<Ignored>,
}

impl ShownObject<'_> {
    /// Whether it shows at least `min_pixels`, where known `min_fraction`, and, when the
    /// frame's RGB image is known, [`MIN_CONTRAST`]. Objects that do not are written as COCO
    /// ignore regions (`iscrowd` 1), with [`ShownObject::ignored`] saying why.
    pub fn passes(&self) -> bool {
        self.ignored.is_none()
    }
}

/// Why a labelled object in view is an ignore region rather than a positive.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Ignored {
    /// Fewer visible pixels than `min_pixels`.
    Pixels,
    /// Less of itself in view than `min_fraction` (hidden or cut off by the image edge).
    Fraction,
    /// Its pixels barely differ from their surroundings or from each other in the final
    /// image (darkness, fog, rain): under [`MIN_CONTRAST`].
    Contrast,
}

impl Ignored {
    /// Its name in COCO's `cityspec_ignored` and `cityspec stats`.
    pub fn name(self) -> &'static str {
        match self {
            Ignored::Pixels => "pixels",
            Ignored::Fraction => "fraction",
            Ignored::Contrast => "contrast",
        }
    }
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
            let (category, subclass) = match &label.sign {
                Some(sign) if sign.front_seen_from(frame.pose.eye) => {
                    (label.category, Some(sign.kind.as_str()))
                }
                Some(sign) => (sign.back_category, None),
                None => (label.category, None),
            };
            let ignored = if visible.pixels < thresholds.min_pixels {
                Some(Ignored::Pixels)
            } else if fraction.is_some_and(|f| f < thresholds.min_fraction) {
                Some(Ignored::Fraction)
            } else {
                // Measured only where it decides something: on a labelled object.
                let faint = |rgb| contrast(rgb, frame.instance, visible.id, visible.bounds);
                frame
                    .rgb
                    .filter(|_| category.is_some())
                    .is_some_and(|rgb| faint(rgb) < MIN_CONTRAST)
                    .then_some(Ignored::Contrast)
            };
            Some(ShownObject {
                full_box: full.map(|(b, _)| *b),
                visible,
                label,
                category,
                subclass,
                fraction,
                ignored,
            })
        })
        .collect()
}
