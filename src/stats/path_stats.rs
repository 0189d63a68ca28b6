//! One camera path's folder (`frames/<name>/`: `ids/*.png`, `coco.json`) + the kind of each
//! instance id → [`PathStats`].

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use rayon::prelude::*;
use serde::Serialize;
use serde_json::Value;

use super::StatsError;

/// What one camera path's frames show.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PathStats {
    /// The path's folder name.
    pub name: String,
    /// Frames (images in `coco.json`).
    pub frames: usize,
    /// Pixels over all `ids/` images.
    pub pixels: u64,
    /// Share of the pixels per object kind (`sky` for id 0, `unknown` for ids past the
    /// scene's objects), largest first.
    pub kinds: Vec<KindShare>,
    /// Median over frames of the labelled objects (`iscrowd` 0) of all classes.
    pub labelled_per_frame: f64,
    /// p25, p50, p75 of the labelled boxes' heights in pixels, all classes; `None` when
    /// there are none.
    pub box_height: Option<[f64; 3]>,
    /// Per COCO category, in the file's order.
    pub classes: Vec<ClassStats>,
    /// Per variant attribute (`facade`, `species`, `body`, `appearance`, `pose`), over the
    /// instances seen in the path (at least one pixel in its `ids/` images).
    pub diversity: Vec<Diversity>,
    /// Labelled objects and ignore regions by reason, all categories.
    pub visibility: Visibility,
}

/// The attributes that name the variant an object was drawn as.
pub const VARIANT_ATTRIBUTES: [&str; 5] = ["facade", "species", "body", "appearance", "pose"];

/// How varied one attribute is over the instances a path shows.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Diversity {
    pub attribute: String,
    /// Instances seen that carry the attribute.
    pub instances: u64,
    /// Distinct values among them.
    pub variants: usize,
    /// The most used value (the first by name among equals) and its share of `instances`;
    /// None when no instance carries the attribute.
    pub most_used: Option<String>,
    pub most_used_share: f64,
}

/// A path's positives and ignore regions.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Visibility {
    /// Annotations with `iscrowd` 0.
    pub positives: u64,
    /// Ignore regions (`iscrowd` 1) per `cityspec_ignored` reason (`pixels`, `fraction`,
    /// `contrast`; `unknown` when absent), by name.
    pub ignored: BTreeMap<String, u64>,
}

/// One object kind's pixels.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct KindShare {
    pub kind: String,
    pub pixels: u64,
    /// `pixels` ÷ all pixels of the path.
    pub share: f64,
}

/// One COCO category of a path.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ClassStats {
    pub name: String,
    /// Labelled objects (`iscrowd` 0) over all frames.
    pub labelled: u64,
    /// Ignore regions (`iscrowd` 1: shown but under the thresholds) over all frames.
    pub ignored: u64,
    /// Of those, the ones the final image hides (`cityspec_ignored: contrast`: darkness,
    /// fog, rain) rather than their size or the share of them in view.
    pub faint: u64,
    /// Median over frames of its labelled objects per frame.
    pub per_frame: f64,
    /// p25, p50, p75 of its labelled boxes' heights in pixels.
    pub box_height: Option<[f64; 3]>,
}

/// The COCO category of the words of text objects (`annotate`'s `word`): counted in its
/// own row, not in the all-classes figures, which count each plate once.
pub(super) const WORD_CATEGORY: &str = "word";

/// Measures the path folder `dir`; `kinds[k]` is the kind of instance id `k + 1`.
/// `attributes[k]` those of id `k + 1` (missing entries: none).
pub fn measure_path(
    dir: &Path,
    kinds: &[String],
    attributes: &[BTreeMap<String, String>],
) -> Result<PathStats, StatsError> {
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let (pixels, shares, seen) = kind_shares(dir, kinds)?;
    let coco = Coco::read(dir.join("coco.json"))?;
    let images = coco.image_ids()?;
    let categories = coco.categories()?;
    let mut tally = coco.tally(&images, &categories)?;
    // A word is part of its plate: the all-classes figures count the plates.
    let mut all_heights: Vec<f64> = tally
        .heights
        .iter()
        .zip(&categories)
        .filter(|(_, (_, name))| name != WORD_CATEGORY)
        .flat_map(|(h, _)| h.iter().copied())
        .collect();
    let classes = categories
        .iter()
        .enumerate()
        .map(|(c, (_, name))| ClassStats {
            name: name.clone(),
            labelled: tally.per_frame[c].iter().sum(),
            ignored: tally.ignored[c],
            faint: tally.faint[c],
            per_frame: median_count(&tally.per_frame[c]),
            box_height: quartiles(&mut tally.heights[c]),
        })
        .collect();
    Ok(PathStats {
        name,
        frames: images.len(),
        pixels,
        kinds: shares,
        labelled_per_frame: median_count(&tally.all_per_frame),
        box_height: quartiles(&mut all_heights),
        classes,
        diversity: diversity(attributes, &seen),
        visibility: Visibility {
            positives: tally.all_per_frame.iter().sum(),
            ignored: tally.reasons,
        },
    })
}

/// Per [`VARIANT_ATTRIBUTES`] entry, its variants over the instances `seen` (by id − 1).
fn diversity(attributes: &[BTreeMap<String, String>], seen: &[bool]) -> Vec<Diversity> {
    VARIANT_ATTRIBUTES
        .iter()
        .map(|&attribute| {
            let mut counts: BTreeMap<&str, u64> = BTreeMap::new();
            for (attrs, _) in attributes.iter().zip(seen).filter(|(_, s)| **s) {
                if let Some(v) = attrs.get(attribute) {
                    *counts.entry(v.as_str()).or_default() += 1;
                }
            }
            let instances: u64 = counts.values().sum();
            let top = counts
                .iter()
                .max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(a.0)))
                .map(|(v, n)| ((*v).to_owned(), *n));
            Diversity {
                attribute: attribute.to_owned(),
                instances,
                variants: counts.len(),
                most_used_share: top
                    .as_ref()
                    .map_or(0.0, |(_, n)| *n as f64 / instances as f64),
                most_used: top.map(|(v, _)| v),
            }
        })
        .collect()
}

/// All pixels of the path's instance images, each kind's share of them, largest first,
/// and per instance id − 1 whether any pixel shows it.
fn kind_shares(
    dir: &Path,
    kinds: &[String],
) -> Result<(u64, Vec<KindShare>, Vec<bool>), StatsError> {
    let (pixels, kind_pixels, seen) = count_kinds(&dir.join("ids"), kinds)?;
    let mut shares: Vec<KindShare> = kind_pixels
        .into_iter()
        .map(|(kind, n)| KindShare {
            kind,
            pixels: n,
            share: if pixels > 0 {
                n as f64 / pixels as f64
            } else {
                0.0
            },
        })
        .collect();
    shares.sort_by(|a, b| b.pixels.cmp(&a.pixels).then(a.kind.cmp(&b.kind)));
    Ok((pixels, shares, seen))
}

/// A path's `coco.json`, parsed.
struct Coco {
    path: PathBuf,
    doc: Value,
}

/// Per category: labelled boxes per frame, their heights, ignore regions; and labelled
/// boxes per frame of all categories.
struct Tally {
    per_frame: Vec<Vec<u64>>,
    all_per_frame: Vec<u64>,
    heights: Vec<Vec<f64>>,
    ignored: Vec<u64>,
    faint: Vec<u64>,
    /// Ignore regions per `cityspec_ignored` reason, all categories.
    reasons: BTreeMap<String, u64>,
}

impl Coco {
    fn read(path: PathBuf) -> Result<Coco, StatsError> {
        let bytes = crate::regular_file::read(&path, crate::regular_file::Follow::Yes).map_err(
            |source| StatsError::Io {
                path: path.clone(),
                source,
            },
        )?;
        match serde_json::from_slice(&bytes) {
            Ok(doc) => Ok(Coco { path, doc }),
            Err(e) => Err(StatsError::Bad {
                path,
                message: e.to_string(),
            }),
        }
    }

    fn bad(&self, message: &str) -> StatsError {
        StatsError::Bad {
            path: self.path.clone(),
            message: message.to_owned(),
        }
    }

    fn list(&self, key: &str) -> Result<&Vec<Value>, StatsError> {
        self.doc[key]
            .as_array()
            .ok_or_else(|| self.bad(&format!("no {key} list")))
    }

    /// The images' ids, in frame order.
    fn image_ids(&self) -> Result<Vec<u64>, StatsError> {
        self.list("images")?
            .iter()
            .map(|i| {
                i["id"]
                    .as_u64()
                    .ok_or_else(|| self.bad("an image without an id"))
            })
            .collect()
    }

    /// The categories' ids and names.
    fn categories(&self) -> Result<Vec<(u64, String)>, StatsError> {
        self.list("categories")?
            .iter()
            .map(|c| Some((c["id"].as_u64()?, c["name"].as_str()?.to_owned())))
            .collect::<Option<_>>()
            .ok_or_else(|| self.bad("a category without an id or name"))
    }

    /// Counts the annotations of the `images` (ids, in frame order) per category.
    fn tally(&self, images: &[u64], categories: &[(u64, String)]) -> Result<Tally, StatsError> {
        let frame_of: BTreeMap<u64, usize> =
            images.iter().enumerate().map(|(i, id)| (*id, i)).collect();
        let mut tally = Tally {
            per_frame: vec![vec![0u64; images.len()]; categories.len()],
            all_per_frame: vec![0u64; images.len()],
            heights: vec![Vec::new(); categories.len()],
            ignored: vec![0u64; categories.len()],
            faint: vec![0u64; categories.len()],
            reasons: BTreeMap::new(),
        };
        for ann in self.list("annotations")? {
            let category = ann["category_id"].as_u64();
            let Some(c) = categories.iter().position(|(id, _)| Some(*id) == category) else {
                return Err(self.bad("an annotation of an unlisted category"));
            };
            if ann["iscrowd"].as_u64() == Some(1) {
                tally.ignored[c] += 1;
                tally.faint[c] += u64::from(ann["cityspec_ignored"] == "contrast");
                let reason = ann["cityspec_ignored"].as_str().unwrap_or("unknown");
                *tally.reasons.entry(reason.to_owned()).or_default() += 1;
                continue;
            }
            let frame = ann["image_id"]
                .as_u64()
                .and_then(|id| frame_of.get(&id))
                .ok_or_else(|| self.bad("an annotation of an unlisted image"))?;
            tally.per_frame[c][*frame] += 1;
            tally.all_per_frame[*frame] += u64::from(categories[c].1 != WORD_CATEGORY);
            tally.heights[c].push(
                ann["bbox"][3]
                    .as_f64()
                    .ok_or_else(|| self.bad("a bbox without a height"))?,
            );
        }
        Ok(tally)
    }
}

/// All pixels, the pixels per kind, and per instance id − 1 whether any pixel shows it.
type KindCounts = (u64, BTreeMap<String, u64>, Vec<bool>);

/// All pixels of the `ids/*.png` images in `dir`, the pixels of each kind, and per instance
/// id − 1 whether any pixel shows it.
fn count_kinds(dir: &Path, kinds: &[String]) -> Result<KindCounts, StatsError> {
    let io = |source| StatsError::Io {
        path: dir.to_path_buf(),
        source,
    };
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .map_err(io)?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "png"))
        .collect();
    files.sort();
    // Kinds as small indices: 0 sky, 1 unknown, then the scene's kinds in name order.
    let mut names: Vec<String> = kinds.to_vec();
    names.sort();
    names.dedup();
    names.retain(|n| n != "sky" && n != "unknown");
    names.splice(0..0, ["sky".to_owned(), "unknown".to_owned()]);
    let index: Vec<usize> = kinds
        .iter()
        .map(|k| names.iter().position(|n| n == k).unwrap_or(1))
        .collect();
    let counts = files
        .par_iter()
        .map(|path| {
            let image = image::open(path).map_err(|e| StatsError::Bad {
                path: path.clone(),
                message: e.to_string(),
            })?;
            let ids = crate::model::unpack_ids(&image.into_rgb8());
            let mut counts = vec![0u64; names.len()];
            let mut seen = vec![false; kinds.len()];
            for &id in ids.as_raw() {
                let k = match id {
                    0 => 0,
                    id => index.get(id as usize - 1).copied().unwrap_or(1),
                };
                counts[k] += 1;
                if let Some(s) = (id as usize).checked_sub(1).and_then(|i| seen.get_mut(i)) {
                    *s = true;
                }
            }
            Ok((counts, seen))
        })
        .collect::<Result<Vec<_>, StatsError>>()?;
    let mut total = vec![0u64; names.len()];
    let mut seen = vec![false; kinds.len()];
    for (c, s) in &counts {
        for (t, n) in total.iter_mut().zip(c) {
            *t += n;
        }
        for (a, b) in seen.iter_mut().zip(s) {
            *a |= b;
        }
    }
    let pixels = total.iter().sum();
    let by_kind = names
        .into_iter()
        .zip(total)
        .filter(|(_, n)| *n > 0)
        .collect();
    Ok((pixels, by_kind, seen))
}

/// The median of counts (mean of the middle two for an even number); 0 for none.
fn median_count(counts: &[u64]) -> f64 {
    let mut v: Vec<f64> = counts.iter().map(|&c| c as f64).collect();
    v.sort_by(f64::total_cmp);
    percentile(&v, 0.5).unwrap_or(0.0)
}

fn quartiles(values: &mut [f64]) -> Option<[f64; 3]> {
    values.sort_by(f64::total_cmp);
    Some([
        percentile(values, 0.25)?,
        percentile(values, 0.5)?,
        percentile(values, 0.75)?,
    ])
}

/// The `p` quantile of sorted `values`, interpolated linearly between ranks (NumPy's
/// default); `None` for no values.
pub fn percentile(sorted: &[f64], p: f64) -> Option<f64> {
    let last = sorted.len().checked_sub(1)?;
    let at = p.clamp(0.0, 1.0) * last as f64;
    let lo = at.floor() as usize;
    let hi = (lo + 1).min(last);
    Some(sorted[lo] + (sorted[hi] - sorted[lo]) * (at - lo as f64))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_interpolate_like_numpy() {
        let v = [1.0, 2.0, 3.0, 4.0];
        assert_eq!(percentile(&v, 0.25), Some(1.75));
        assert_eq!(percentile(&v, 0.5), Some(2.5));
        assert_eq!(percentile(&v, 0.75), Some(3.25));
        assert_eq!(percentile(&[7.0], 0.25), Some(7.0));
        assert_eq!(percentile(&[], 0.5), None);
        assert_eq!(median_count(&[0, 5, 1]), 1.0);
    }

    #[test]
    fn a_written_path_is_measured() {
        let temp = tempfile::tempdir().unwrap();
        let dir = temp.path().join("street");
        std::fs::create_dir_all(dir.join("ids")).unwrap();
        // Two 4 × 2 frames: id 0 sky, 1 road, 2 building, 70,000 past the scene.
        let frames: [[u32; 8]; 2] = [[0, 0, 2, 2, 1, 1, 1, 1], [0, 2, 2, 2, 1, 1, 1, 70_000]];
        for (i, ids) in frames.iter().enumerate() {
            let image =
                image::ImageBuffer::from_fn(4, 2, |x, y| image::Luma([ids[(y * 4 + x) as usize]]));
            crate::model::pack_ids(&image)
                .save(dir.join("ids").join(format!("{i:06}.png")))
                .unwrap();
        }
        let coco = r#"{"images":[{"id":1},{"id":2}],
            "categories":[{"id":1,"name":"building"},{"id":2,"name":"road"}],
            "annotations":[
              {"image_id":1,"category_id":1,"bbox":[2,0,2,1],"iscrowd":0},
              {"image_id":2,"category_id":1,"bbox":[1,0,3,1],"iscrowd":0},
              {"image_id":2,"category_id":2,"bbox":[0,1,3,1],"iscrowd":1,
               "cityspec_ignored":"contrast"},
              {"image_id":1,"category_id":2,"bbox":[0,1,1,1],"iscrowd":1,
               "cityspec_ignored":"pixels"}]}"#;
        std::fs::write(dir.join("coco.json"), coco).unwrap();
        let kinds = ["road".to_owned(), "building".to_owned()];
        let stats = measure_path(&dir, &kinds, &[]).unwrap();
        assert_eq!(
            (stats.name.as_str(), stats.frames, stats.pixels),
            ("street", 2, 16)
        );
        let shares: Vec<(&str, u64)> = stats
            .kinds
            .iter()
            .map(|k| (k.kind.as_str(), k.pixels))
            .collect();
        assert_eq!(
            shares,
            [("road", 7), ("building", 5), ("sky", 3), ("unknown", 1)]
        );
        assert_eq!(stats.labelled_per_frame, 1.0);
        let building = &stats.classes[0];
        assert_eq!(
            (building.labelled, building.ignored, building.per_frame),
            (2, 0, 1.0)
        );
        assert_eq!(building.box_height, Some([1.0, 1.0, 1.0]));
        let road = &stats.classes[1];
        assert_eq!(
            (road.labelled, road.ignored, road.per_frame, road.box_height),
            (0, 2, 0.0, None)
        );
        assert_eq!((building.faint, road.faint), (0, 1));
    }
}
