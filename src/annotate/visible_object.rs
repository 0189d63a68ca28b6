//! One pass over an instance-id image → every instance's visible pixels: box, count, RLE.

use std::collections::BTreeMap;

use image::{ImageBuffer, Luma};

use super::rle::Rle;
use crate::model::PixelBox;

/// What one instance shows in a frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VisibleObject {
    /// The value in the instance image (object index + 1).
    pub id: u32,
    /// Tight box of the visible pixels.
    pub bounds: PixelBox,
    /// Visible pixel count.
    pub pixels: u64,
    /// The visible pixels as a COCO RLE.
    pub rle: Rle,
}

/// Every non-zero id of `image`, in id order, with its visible box, count and RLE.
///
/// Occlusion is handled by construction: a pixel belongs to the one instance the renderer
/// wrote there, so a partly covered object keeps only the pixels it shows. The image is
/// walked once, column by column (the order COCO's RLE runs in), extending each id's
/// current run or opening a new one. Ids are up to 24 bits and a frame shows few of them,
/// so they are looked up in an ordered map, with the previous pixel's id as a shortcut
/// (runs down a column mostly share one id).
pub fn scan(image: &ImageBuffer<Luma<u32>, Vec<u32>>) -> Vec<VisibleObject> {
    let (w, h) = image.dimensions();
    let raw = image.as_raw();
    let mut slots: BTreeMap<u32, usize> = BTreeMap::new();
    let mut found: Vec<(u32, Acc)> = Vec::new();
    let mut last: Option<(u32, usize)> = None;
    for x in 0..w {
        for y in 0..h {
            let id = raw[y as usize * w as usize + x as usize];
            if id == 0 {
                continue;
            }
            let t = u64::from(x) * u64::from(h) + u64::from(y);
            let slot = match last {
                Some((seen, slot)) if seen == id => slot,
                _ => *slots.entry(id).or_insert_with(|| {
                    found.push((id, Acc::new(x, y)));
                    found.len() - 1
                }),
            };
            last = Some((id, slot));
            found[slot].1.add(x, y, t);
        }
    }
    let total = u64::from(w) * u64::from(h);
    let mut found: Vec<Option<(u32, Acc)>> = found.into_iter().map(Some).collect();
    slots
        .values()
        .filter_map(|&slot| found[slot].take())
        .map(|(id, acc)| acc.finish(id, [h, w], total))
        .collect()
}

/// Per-id state of the scan.
struct Acc {
    bounds: PixelBox,
    pixels: u64,
    counts: Vec<u64>,
    /// Column-major index just past the last pixel seen.
    end: u64,
}

impl Acc {
    fn new(x: u32, y: u32) -> Acc {
        Acc {
            bounds: PixelBox::at(x, y),
            pixels: 0,
            counts: Vec::new(),
            end: 0,
        }
    }

    fn add(&mut self, x: u32, y: u32, t: u64) {
        self.bounds.include(x, y);
        self.pixels += 1;
        match self.counts.last_mut() {
            Some(run) if self.end == t => *run += 1,
            _ => {
                self.counts.push(t - self.end);
                self.counts.push(1);
            }
        }
        self.end = t + 1;
    }

    fn finish(mut self, id: u32, size: [u32; 2], total: u64) -> VisibleObject {
        if total > self.end {
            self.counts.push(total - self.end);
        }
        VisibleObject {
            id,
            bounds: self.bounds,
            pixels: self.pixels,
            rle: Rle {
                size,
                counts: self.counts,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::annotate::test_image as image;

    #[test]
    fn occluded_object_keeps_only_its_visible_pixels() {
        // Object 1 is a 4 × 3 rectangle; object 2 stands in front of its right half and
        // its bottom row, so 1 shows only a 2 × 2 square.
        let img = image(&[
            &[0, 0, 0, 0, 0, 0],
            &[0, 1, 1, 2, 2, 0],
            &[0, 1, 1, 2, 2, 0],
            &[0, 2, 2, 2, 2, 0],
            &[0, 0, 0, 0, 0, 3],
        ]);
        let found = scan(&img);
        assert_eq!(found.iter().map(|o| o.id).collect::<Vec<_>>(), [1, 2, 3]);
        let [one, two, three] = [&found[0], &found[1], &found[2]];
        assert_eq!((one.bounds.bbox(), one.pixels), ([1, 1, 2, 2], 4));
        assert_eq!((two.bounds.bbox(), two.pixels), ([1, 1, 4, 3], 8));
        assert_eq!((three.bounds.bbox(), three.pixels), ([5, 4, 1, 1], 1));
        // Column-major, 5 rows: object 1 fills rows 1–2 of columns 1 and 2.
        assert_eq!(one.rle.counts, [6, 2, 3, 2, 17]);
        // The last pixel is set: no trailing run of 0s.
        assert_eq!(three.rle.counts, [29, 1]);
        for o in &found {
            let mask: Vec<bool> = img.pixels().map(|p| p.0[0] == o.id).collect();
            assert_eq!(o.rle, Rle::from_row_major(&mask, 5, 6), "id {}", o.id);
            assert_eq!(o.rle.area(), o.pixels);
        }
    }

    #[test]
    fn ids_beyond_sixteen_bits_keep_their_own_pixels() {
        let img = image(&[&[16_777_215, 70_000], &[1, 70_000]]);
        let found = scan(&img);
        let ids: Vec<(u32, u64)> = found.iter().map(|o| (o.id, o.pixels)).collect();
        assert_eq!(ids, [(1, 1), (70_000, 2), (16_777_215, 1)]);
        assert_eq!(found[1].rle.counts, [2, 2]);
    }

    #[test]
    fn empty_image_has_no_objects() {
        assert!(scan(&image(&[&[0, 0], &[0, 0]])).is_empty());
        assert!(scan(&ImageBuffer::new(0, 0)).is_empty());
    }
}
