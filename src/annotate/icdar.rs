//! One frame → ICDAR 2015 text lines: `x1,y1,x2,y2,x3,y3,x4,y4,transcription`.

use std::fmt::Write;

use super::frame_annotations::FrameAnnotations;

/// Visible fraction below which a text is "mostly hidden" and transcribed `###`.
pub const MOSTLY_HIDDEN: f64 = 0.5;

/// ICDAR 2015 lines for the text objects (labels with `text`) visible in one frame, in
/// instance-id order: `x1,y1,x2,y2,x3,y3,x4,y4,transcription`, integer pixel coordinates.
///
/// The quad is the renderer's projected corners (`frame.quads`) when given and finite,
/// rounded to the nearest pixel and clamped into the image (`0..=width−1`,
/// `0..=height−1`: a text cut by the image edge gets the quad of its part inside, never
/// negative coordinates); otherwise the visible box's corner pixels clockwise from
/// the top-left (`x0,y0, x1,y0, x1,y1, x0,y1`, inclusive). The transcription is the text
/// with line breaks and other control characters made spaces, or `###` (ICDAR's "do not
/// care") when the text is mostly hidden — its visible fraction is below one half — or it
/// misses `thresholds`. Every visible text gets a line, so a detector that finds a mostly
/// hidden one is not counted wrong.
pub fn icdar(frame: &FrameAnnotations) -> String {
    let mut out = String::new();
    for object in &frame.objects {
        let Some(text) = &object.label.text else {
            continue;
        };
        let v = &object.visible;
        let b = v.bounds;
        let boxed =
            [[b.x0, b.y0], [b.x1, b.y0], [b.x1, b.y1], [b.x0, b.y1]].map(|p| p.map(i64::from));
        let quad = frame
            .quads
            .get(&v.id)
            .filter(|q| q.iter().flatten().all(|c| c.is_finite() && c.abs() < 1e15))
            .map(|q| {
                q.map(|[x, y]| {
                    [
                        (x.round() as i64).clamp(0, i64::from(frame.width) - 1),
                        (y.round() as i64).clamp(0, i64::from(frame.height) - 1),
                    ]
                })
            })
            .unwrap_or(boxed);
        let hidden = !object.passes || object.fraction.is_some_and(|f| f < MOSTLY_HIDDEN);
        for [x, y] in quad {
            let _ = write!(out, "{x},{y},");
        }
        if hidden {
            out.push_str("###");
        } else {
            out.extend(text.chars().map(|c| if c.is_control() { ' ' } else { c }));
        }
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;
    use crate::annotate::{FrameInput, ObjectLabel, Thresholds, summarize, test_image};
    use crate::cameras::CameraPose;

    #[test]
    fn mostly_hidden_or_too_small_text_is_do_not_care() {
        // Four texts: 1 fully seen, 2 with half of it hidden, 3 with less than half
        // seen, 4 a single pixel; 5 is a building without text.
        let img = test_image(&[
            &[1, 1, 1, 0, 2, 2, 0, 4],
            &[1, 1, 1, 0, 2, 2, 0, 0],
            &[0, 0, 0, 0, 0, 0, 0, 0],
            &[3, 3, 0, 5, 5, 0, 0, 0],
        ]);
        let label = |text: Option<&str>| ObjectLabel {
            name: "x".into(),
            category: Some(1),
            text: text.map(String::from),
            sign: None,
        };
        let labels = [
            label(Some("EXIT")),
            label(Some("line one\nline two, and more")),
            label(Some("CAFE")),
            label(Some("X")),
            label(None),
        ];
        let frame = FrameInput {
            file_name: "f.png".into(),
            instance: &img,
            intrinsics: [1.0, 1.0, 4.0, 2.0],
            pose: CameraPose {
                eye: [0.0; 3],
                target: [0.0, 0.0, 1.0],
            },
            full: BTreeMap::from([
                (1, ([0.0, 0.0, 3.0, 2.0], 6)),
                (2, ([4.0, 0.0, 2.0, 4.0], 8)),
                (3, ([0.0, 3.0, 4.0, 2.0], 5)),
            ]),
            // Corners past the image edges are clamped into it.
            quads: BTreeMap::from([(1, [[-3.4, 0.2], [3.5, -2.0], [9.6, 2.49], [0.0, 2.0]])]),
        };
        let thresholds = Thresholds {
            min_pixels: 2,
            min_fraction: 0.0,
        };
        assert_eq!(
            icdar(&summarize(&labels, &frame, &thresholds)),
            "0,0,4,0,7,2,0,2,EXIT\n\
             4,0,5,0,5,1,4,1,line one line two, and more\n\
             0,3,1,3,1,3,0,3,###\n\
             7,0,7,0,7,0,7,0,###\n"
        );
    }
}
