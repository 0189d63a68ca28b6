//! A timed camera path's COCO lines → MOT Challenge ground truth: `gt/gt.txt` and
//! `seqinfo.ini`, so the path's folder is a MOT sequence (`imDir` is `rgb`).

use std::fmt::Write;

use serde::Deserialize;

use super::coco::CocoLines;

/// What a `gt.txt` line takes from one COCO annotation.
#[derive(Deserialize)]
struct Annotation {
    category_id: u64,
    bbox: [i64; 4],
    iscrowd: u8,
    cityspec_instance: u32,
    #[serde(default)]
    visible_fraction: Option<f64>,
}

/// Frame `frame`'s (0-based) `gt.txt` lines, one per annotation of `coco` not in category
/// `skip` (the words of a plate share its instance id; the plate stands for them):
/// `frame,id,bb_left,bb_top,bb_width,bb_height,conf,class,visibility` with the frame
/// counted from 1, the id the object's instance id (the same object keeps it in every
/// frame), the box COCO's with its corner counted from 1 as MOT's are (`bb_left = x + 1`:
/// motmetrics and TrackEval subtract it), `conf` 1 for a positive and 0 for an ignore region (MOT's
/// "do not consider"), the class COCO's category id and the visibility COCO's visible
/// fraction (1 where it has none).
pub fn mot_lines(frame: usize, coco: &CocoLines, skip: Option<u64>) -> serde_json::Result<String> {
    let mut out = String::new();
    for line in &coco.annotations {
        let a: Annotation = serde_json::from_str(line)?;
        if Some(a.category_id) == skip {
            continue;
        }
        let [x, y, w, h] = a.bbox;
        let conf = u8::from(a.iscrowd == 0);
        let visibility = a.visible_fraction.unwrap_or(1.0);
        let _ = writeln!(
            out,
            "{},{},{},{},{w},{h},{conf},{},{visibility}",
            frame + 1,
            a.cityspec_instance,
            x + 1,
            y + 1,
            a.category_id
        );
    }
    Ok(out)
}

/// The sequence's `seqinfo.ini`: its name, frames in `rgb/`, frame rate and image size.
pub fn mot_seqinfo(name: &str, fps: f64, frames: usize, size: [u32; 2]) -> String {
    format!(
        "[Sequence]\nname={name}\nimDir=rgb\nframeRate={fps}\nseqLength={frames}\n\
         imWidth={}\nimHeight={}\nimExt=.png\n",
        size[0], size[1]
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(annotations: &[&str]) -> CocoLines {
        CocoLines {
            image: String::new(),
            annotations: annotations.iter().map(|s| s.to_string()).collect(),
        }
    }

    #[test]
    fn a_positive_and_an_ignore_region_become_mot_rows_and_words_are_left_out() {
        let coco = lines(&[
            r#"{"image_id":3,"category_id":2,"bbox":[10,20,30,40],"area":5,"iscrowd":0,"cityspec_instance":77,"visible_fraction":0.5}"#,
            r#"{"image_id":3,"category_id":2,"bbox":[1,2,3,4],"area":5,"iscrowd":1,"cityspec_instance":78}"#,
            r#"{"image_id":3,"category_id":9,"bbox":[11,21,5,6],"area":5,"iscrowd":0,"cityspec_instance":77}"#,
        ]);
        assert_eq!(
            mot_lines(2, &coco, Some(9)).unwrap(),
            "3,77,11,21,30,40,1,2,0.5\n3,78,2,3,3,4,0,2,1\n"
        );
        assert!(mot_lines(0, &lines(&["{}"]), None).is_err());
    }

    #[test]
    fn seqinfo_names_the_frames_folder_and_rate() {
        let ini = mot_seqinfo("street", 10.0, 20, [640, 480]);
        assert_eq!(
            ini,
            "[Sequence]\nname=street\nimDir=rgb\nframeRate=10\nseqLength=20\nimWidth=640\n\
             imHeight=480\nimExt=.png\n"
        );
    }
}
