//! One pass over an instance-id image → every instance's visible pixels: box, count, RLE.

use std::collections::BTreeMap;

use image::{ImageBuffer, Luma};

use super::rle::Rle;
use crate::model::PixelBox;

/// Columns copied out of the image at a time by [`scan`].
const BAND: usize = 16;

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
/// walked once, column by column (the order COCO's RLE runs in), a run of one id at a
/// time, extending that id's current run or opening a new one. The columns are copied out
/// 16 at a time, so the row-major image is read along its rows. Ids are up to 24
/// bits and a frame shows few of them, so they are looked up in an ordered map, with the
/// previous run's id as a shortcut.
pub fn scan(image: &ImageBuffer<Luma<u32>, Vec<u32>>) -> Vec<VisibleObject> {
    let (w, h) = image.dimensions();
    let (wu, hu) = (w as usize, h as usize);
    let raw = image.as_raw();
    let mut slots: BTreeMap<u32, usize> = BTreeMap::new();
    let mut found: Vec<(u32, Acc)> = Vec::new();
    let mut last: Option<(u32, usize)> = None;
    let mut band = vec![0u32; BAND * hu];
    for x0 in (0..wu).step_by(BAND) {
        let bw = BAND.min(wu - x0);
        for (y, row) in raw.chunks_exact(wu.max(1)).enumerate() {
            for (k, &id) in row[x0..x0 + bw].iter().enumerate() {
                band[k * hu + y] = id;
            }
        }
        for (k, column) in band.chunks_exact(hu.max(1)).take(bw).enumerate() {
            let x = (x0 + k) as u32;
            let mut y = 0;
            while y < hu {
                let id = column[y];
                let len = column[y..].iter().position(|&v| v != id).unwrap_or(hu - y);
                if id != 0 {
                    let slot = match last {
                        Some((seen, slot)) if seen == id => slot,
                        _ => *slots.entry(id).or_insert_with(|| {
                            found.push((id, Acc::new(x, y as u32)));
                            found.len() - 1
                        }),
                    };
                    last = Some((id, slot));
                    let t = u64::from(x) * u64::from(h) + y as u64;
                    found[slot].1.add_run(x, y as u32, len as u32, t);
                }
                y += len;
            }
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

    /// `len` pixels down column `x` from row `y`, at column-major index `t`.
    fn add_run(&mut self, x: u32, y: u32, len: u32, t: u64) {
        self.bounds.include(x, y);
        self.bounds.include(x, y + len - 1);
        self.pixels += u64::from(len);
        match self.counts.last_mut() {
            Some(run) if self.end == t => *run += u64::from(len),
            _ => {
                self.counts.push(t - self.end);
                self.counts.push(u64::from(len));
            }
        }
        self.end = t + u64::from(len);
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
    fn wide_image_with_runs_across_bands_matches_pixel_by_pixel_masks() {
        // 37 columns (two bands of 16 and a part), 23 rows: blocky seeded ids with runs
        // that cross band edges, column ends and each other.
        let (w, h) = (37u32, 23u32);
        let mut state = 12345u32;
        let mut next = || {
            state = state.wrapping_mul(1_103_515_245).wrapping_add(12_345);
            state >> 16
        };
        let blocks: Vec<u32> = (0..64).map(|_| next() % 5).collect();
        let img = ImageBuffer::from_fn(w, h, |x, y| {
            let id = blocks[(x / 5 + 8 * (y / 3)) as usize % 64];
            Luma([if id == 4 { 70_000 } else { id }])
        });
        let found = scan(&img);
        let mut ids: Vec<u32> = img.pixels().map(|p| p.0[0]).filter(|&i| i != 0).collect();
        ids.sort_unstable();
        ids.dedup();
        assert_eq!(found.iter().map(|o| o.id).collect::<Vec<_>>(), ids);
        for o in &found {
            let mask: Vec<bool> = img.pixels().map(|p| p.0[0] == o.id).collect();
            assert_eq!(o.rle, Rle::from_row_major(&mask, h, w), "id {}", o.id);
            assert_eq!(o.pixels, mask.iter().filter(|&&m| m).count() as u64);
            let (xs, ys): (Vec<u32>, Vec<u32>) = (0..w * h)
                .filter(|&i| mask[i as usize])
                .map(|i| (i % w, i / w))
                .unzip();
            let min_max = |v: &[u32]| (*v.iter().min().unwrap(), *v.iter().max().unwrap());
            let ((x0, x1), (y0, y1)) = (min_max(&xs), min_max(&ys));
            assert_eq!(
                o.bounds.bbox(),
                [x0, y0, x1 - x0 + 1, y1 - y0 + 1],
                "id {}",
                o.id
            );
        }
    }

    #[test]
    fn empty_image_has_no_objects() {
        assert!(scan(&image(&[&[0, 0], &[0, 0]])).is_empty());
        assert!(scan(&ImageBuffer::new(0, 0)).is_empty());
    }
}
