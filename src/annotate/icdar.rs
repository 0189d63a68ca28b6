//! One frame → ICDAR 2015 word lines: `x1,y1,x2,y2,x3,y3,x4,y4,transcription`.

use std::fmt::Write;

use super::frame_annotations::FrameAnnotations;
use super::shown_object::ShownObject;

/// Visible fraction below which a word is "mostly hidden" and transcribed `###`.
pub const MOSTLY_HIDDEN: f64 = 0.5;
/// Fewest pixels per character along the writing for a word to be transcribed.
pub const MIN_PX_PER_CHAR: f64 = 2.0;

/// ICDAR 2015 lines for the text objects (labels with `text`) visible in one frame: one
/// line per word (ICDAR 2015 is word-level), objects in instance-id order and words in
/// reading order, `x1,y1,x2,y2,x3,y3,x4,y4,transcription` with integer pixel coordinates.
///
/// - The quad is the word's projected ink box (`frame.quads`), clockwise from the top-left
///   of the writing. **At the image edge** each corner is rounded and then clamped into the
///   image (`0..=width−1`, `0..=height−1`), so every coordinate is a pixel of the frame; a
///   word cut by the edge is therefore written as its visible part's hull, and its
///   transcription is kept only while at least half of it is in view (below).
/// - The transcription is the word, or `###` (ICDAR's "do not care") when the word is
///   mostly hidden (less than `MOSTLY_HIDDEN` of its quad shows the object, counting
///   occlusion and the image edge), narrower than `MIN_PX_PER_CHAR` pixels per
///   character, or its object misses the thresholds. A word the frame does not show at
///   all gets no line; every other gets one, so a detector that finds a hard word is not
///   counted wrong.
/// - A text object without word quads (a corner behind the camera) gets one line: its
///   visible box's corner pixels clockwise from the top-left, transcribed only when it is
///   a single word that passes the rules above.
///
/// Control characters in a word become spaces.
pub fn icdar(frame: &FrameAnnotations) -> String {
    let mut out = String::new();
    let clamp = |[x, y]: [f64; 2]| {
        let max = [frame.width.max(1) - 1, frame.height.max(1) - 1].map(i64::from);
        [
            (x.round() as i64).clamp(0, max[0]),
            (y.round() as i64).clamp(0, max[1]),
        ]
    };
    for object in &frame.objects {
        for line in word_lines(frame, object) {
            let quad = match line.quad {
                Some(quad) => quad.map(clamp),
                None => {
                    let b = object.visible.bounds;
                    [
                        [b.x_min, b.y_min],
                        [b.x_max, b.y_min],
                        [b.x_max, b.y_max],
                        [b.x_min, b.y_max],
                    ]
                    .map(|p| p.map(i64::from))
                }
            };
            for [x, y] in quad {
                let _ = write!(out, "{x},{y},");
            }
            if line.unreadable.is_none() {
                out.extend(
                    line.word
                        .chars()
                        .map(|c| if c.is_control() { ' ' } else { c }),
                );
            } else {
                out.push_str("###");
            }
            out.push('\n');
        }
    }
    out
}

/// One ICDAR line of a text object, before it is written: COCO's `word` annotations are
/// made from the same lines, so the two agree word for word.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct WordLine<'a> {
    /// The word's projected quad (it may reach past the image), or `None` for the one line
    /// of a text object without word quads: its visible box.
    pub quad: Option<[[f64; 2]; 4]>,
    /// The word (the whole text for a line without quads).
    pub word: &'a str,
    /// Its place among the text's words (split at spaces); `None` without quads.
    pub index: Option<usize>,
    /// How much of its quad shows the object (`None` without quads).
    pub visible: Option<f64>,
    /// Why it is written `###`: the object's [`super::Ignored`] name, `hidden` (under
    /// [`MOSTLY_HIDDEN`] in view), `small` (under [`MIN_PX_PER_CHAR`]), `empty` (an empty
    /// word) or `unsplit` (several words without quads); `None` when it is transcribed.
    pub unreadable: Option<&'static str>,
}

/// The ICDAR lines of `object` in `frame` (none for an object without text), in reading
/// order, by the rules of [`icdar`].
pub(crate) fn word_lines<'a>(
    frame: &FrameAnnotations,
    object: &ShownObject<'a>,
) -> Vec<WordLine<'a>> {
    let Some(text) = &object.label.text else {
        return Vec::new();
    };
    let v = &object.visible;
    let words: Vec<&'a str> = text.split(' ').collect();
    let ignored = object.ignored.map(|i| i.name());
    let quads = frame.quads.get(&v.id).filter(|q| q.len() == words.len());
    let Some(quads) = quads else {
        let b = v.bounds;
        let wide =
            f64::from(b.x_max - b.x_min + 1) >= MIN_PX_PER_CHAR * text.chars().count() as f64;
        let hidden = object.fraction.is_some_and(|f| f < MOSTLY_HIDDEN);
        let unreadable = ignored
            .or((words.len() != 1).then_some("unsplit"))
            .or(hidden.then_some("hidden"))
            .or((!wide).then_some("small"))
            .or(text.is_empty().then_some("empty"));
        return vec![WordLine {
            quad: None,
            word: text,
            index: None,
            visible: None,
            unreadable,
        }];
    };
    words
        .iter()
        .zip(quads)
        .enumerate()
        .filter(|(_, (_, w))| w.visible > 0.0)
        .map(|(index, (&word, w))| {
            let wide = w.length() >= MIN_PX_PER_CHAR * word.chars().count() as f64;
            let unreadable = ignored
                .or((w.visible < MOSTLY_HIDDEN).then_some("hidden"))
                .or((!wide).then_some("small"))
                .or(word.is_empty().then_some("empty"));
            WordLine {
                quad: Some(w.quad),
                word,
                index: Some(index),
                visible: Some(w.visible),
                unreadable,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;
    use crate::annotate::{FrameInput, Thresholds, summarize, word_fixture};
    use crate::model::CameraPose;

    #[test]
    fn one_line_per_word_with_do_not_care_for_small_hidden_or_cut_words() {
        // See `word_fixture`.
        let (img, labels, quads) = word_fixture();
        let frame = FrameInput {
            file_name: "f.png".into(),
            instance: &img,
            rgb: None,
            intrinsics: [1.0, 1.0, 10.0, 3.0],
            pose: CameraPose::level([0.0; 3], [0.0, 0.0, 1.0]),
            full: BTreeMap::new(),
            quads,
            depth: None,
        };
        let thresholds = Thresholds {
            min_pixels: 2,
            min_fraction: 0.0,
        };
        assert_eq!(
            icdar(&summarize(&labels, &frame, &thresholds)),
            "0,0,10,0,10,3,0,3,Write\n\
             10,0,12,0,12,3,10,3,###\n\
             14,0,19,0,19,3,14,3,Edge\n\
             0,4,12,4,12,5,0,5,###\n\
             14,4,19,4,19,5,14,5,###\n\
             3,4,11,4,11,5,3,5,Ok\n"
        );
    }
}
