//! Plate sizes → [`AtlasLayout`]: where each text plate goes on a few shared atlas pages (a
//! deterministic shelf packer); plate images → the pages' pixels.
//!
//! Why pages: one texture per plate costs the export a PNG, a hash and a file each, and a
//! city has hundreds of plates. Why cells: plates that share a page can bleed into each
//! other, because the renderer samples trilinearly from mip chains (`render::mip_texture`,
//! levels halve by averaging 2 × 2 texels) and glTF viewers do the same. So each plate sits
//! in a *cell* whose edges lie on multiples of [`ALIGN`] pixels, with at least [`PADDING`]
//! pixels of the plate's own edge pixels repeated outward around it. A texel of mip level
//! `j` (side `s = 2^j` pixels) then never straddles two cells while `s ≤ ALIGN`, and a
//! bilinear sample inside the plate only reaches texels of its own cell while
//! `s ≤ 2 · PADDING`: the sample is at least `PADDING ≥ s / 2` from the cell edge, so both
//! texel centres it blends between lie in the cell. With 8 and 16, levels 0–4 (plates
//! shrunk up to 16 times) are exactly what a texture of its own would give; beyond that the
//! plate is a few pixels on screen and its text unreadable anyway.
//!
//! Page sizes are trimmed to what they hold (multiples of [`ALIGN`], so every clean level's
//! texels line up with level 0). A plate whose cell does not fit a page gets a page of its
//! own, as large as the cell.

use image::RgbImage;

/// Largest page, `[width, height]` in pixels: wide enough for a plate of three long words in
/// the largest letters, low enough that a city's few pages encode in parallel.
pub const PAGE: [u32; 2] = [2048, 1024];
/// Edge pixels repeated around each plate, in pixels.
pub const PADDING: u32 = 8;
/// Cells start and end on multiples of this many pixels (a power of two).
pub const ALIGN: u32 = 16;

/// Where every plate goes, in input order, and the size of every page.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AtlasLayout {
    /// Per page: `[width, height]` in pixels, multiples of [`ALIGN`].
    pub pages: Vec<[u32; 2]>,
    /// Per plate, in the order of the sizes given to [`AtlasLayout::pack`].
    pub slots: Vec<AtlasSlot>,
}

/// One plate's place: its page, its pixels `[x0, y0, x1, y1)` and its padded cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AtlasSlot {
    pub page: usize,
    pub plate: [u32; 4],
    pub cell: [u32; 4],
}

/// The open shelf of the page being filled.
struct Shelf {
    page: usize,
    y: u32,
    height: u32,
    x: u32,
}

impl AtlasLayout {
    /// Packs plates of `sizes` (`[width, height]` in pixels) onto pages of at most `page`
    /// (`[width, height]`) pixels: tallest cells first (ties by width, then input order), left to right
    /// on shelves, a new shelf below when a row is full, a new page when a page is.
    pub fn pack(sizes: &[[u32; 2]], page: [u32; 2]) -> AtlasLayout {
        let cells: Vec<[u32; 2]> = sizes.iter().map(|&s| cell_size(s)).collect();
        let mut order: Vec<usize> = (0..sizes.len()).collect();
        order.sort_by_key(|&i| {
            (
                std::cmp::Reverse(cells[i][1]),
                std::cmp::Reverse(cells[i][0]),
                i,
            )
        });
        let mut pages: Vec<[u32; 2]> = Vec::new();
        let mut slots = vec![
            AtlasSlot {
                page: 0,
                plate: [0; 4],
                cell: [0; 4],
            };
            sizes.len()
        ];
        let mut shelf: Option<Shelf> = None;
        for i in order {
            let [w, h] = cells[i];
            let (p, x, y) = if w > page[0] || h > page[1] {
                pages.push([w, h]);
                (pages.len() - 1, 0, 0)
            } else {
                let s = match shelf.take() {
                    Some(s) if s.x + w <= page[0] => s,
                    Some(s) if s.y + s.height + h <= page[1] => Shelf {
                        page: s.page,
                        y: s.y + s.height,
                        height: 0,
                        x: 0,
                    },
                    _ => {
                        pages.push([0, 0]);
                        Shelf {
                            page: pages.len() - 1,
                            y: 0,
                            height: 0,
                            x: 0,
                        }
                    }
                };
                let at = (s.page, s.x, s.y);
                let extent = &mut pages[s.page];
                extent[0] = extent[0].max(s.x + w);
                extent[1] = extent[1].max(s.y + h);
                shelf = Some(Shelf {
                    x: s.x + w,
                    height: s.height.max(h),
                    ..s
                });
                at
            };
            let [pw, ph] = sizes[i];
            slots[i] = AtlasSlot {
                page: p,
                plate: [x + PADDING, y + PADDING, x + PADDING + pw, y + PADDING + ph],
                cell: [x, y, x + w, y + h],
            };
        }
        AtlasLayout { pages, slots }
    }

    /// Plate `i`'s texture coordinates on its page: `(u span, v span)`, v down from the
    /// page's top edge, covering exactly the plate's pixels.
    pub fn uv_spans(&self, i: usize) -> ([f64; 2], [f64; 2]) {
        let slot = &self.slots[i];
        let [w, h] = self.pages[slot.page].map(f64::from);
        let [x0, y0, x1, y1] = slot.plate.map(f64::from);
        ([x0 / w, x1 / w], [y0 / h, y1 / h])
    }

    /// The pixels of page `page`: every plate on it copied into its slot, its cell filled
    /// with the plate's nearest edge pixels; the rest black. `images[i]` must have the size
    /// plate `i` was packed with.
    pub fn paint(&self, page: usize, images: &[RgbImage]) -> RgbImage {
        let [w, h] = self.pages[page];
        let mut out = RgbImage::new(w, h);
        let stride = w as usize * 3;
        let on_page = self
            .slots
            .iter()
            .zip(images)
            .filter(|(s, _)| s.page == page);
        for (slot, image) in on_page {
            let [px0, py0, px1, py1] = slot.plate;
            assert_eq!((image.width(), image.height()), (px1 - px0, py1 - py0));
            let [cx0, cy0, cx1, cy1] = slot.cell.map(|v| v as usize);
            let [px0, px1] = [px0, px1].map(|v| v as usize);
            let source_stride = image.width() as usize * 3;
            for y in cy0..cy1 {
                // Rows above and below the plate repeat its first and last row; within a
                // row, pixels left and right of it repeat its first and last pixel.
                let sy = (y as u32).clamp(py0, py1 - 1) - py0;
                let source = &image.as_raw()[sy as usize * source_stride..][..source_stride];
                let row = &mut out.as_mut()[y * stride..][..stride];
                let (first, last) = (&source[..3], &source[source_stride - 3..]);
                for x in cx0..px0 {
                    row[x * 3..x * 3 + 3].copy_from_slice(first);
                }
                row[px0 * 3..px1 * 3].copy_from_slice(source);
                for x in px1..cx1 {
                    row[x * 3..x * 3 + 3].copy_from_slice(last);
                }
            }
        }
        out
    }
}

/// A plate's cell: the plate plus [`PADDING`] on every side, rounded up to [`ALIGN`].
fn cell_size([w, h]: [u32; 2]) -> [u32; 2] {
    [w, h].map(|v| (v.max(1) + 2 * PADDING).next_multiple_of(ALIGN))
}

#[cfg(test)]
mod tests {
    use image::Rgb;

    use super::*;

    /// Plate sizes like a text entry's: varied widths and heights, and two too big for a
    /// page (one too wide, one too tall), and a tiny one.
    fn sizes(n: u32, page: [u32; 2]) -> Vec<[u32; 2]> {
        let mut sizes: Vec<[u32; 2]> = (0..n)
            .map(|i| [20 + (i * 37) % 150, 10 + (i * 13) % 45])
            .collect();
        sizes.push([page[0] + 5, 30]);
        sizes.push([10, page[1] - 2 * PADDING + 1]);
        sizes.push([1, 1]);
        sizes
    }

    fn overlaps(a: [u32; 4], b: [u32; 4]) -> bool {
        a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
    }

    #[test]
    fn cells_never_overlap_stay_on_their_page_and_are_aligned() {
        let pages = [
            (0, [256, 256]),
            (1, [256, 256]),
            (40, [256, 128]),
            (300, [256, 256]),
            (300, PAGE),
        ];
        for (n, page) in pages {
            let sizes = sizes(n, page);
            let layout = AtlasLayout::pack(&sizes, page);
            assert_eq!(layout.slots.len(), sizes.len());
            for (i, (slot, size)) in layout.slots.iter().zip(&sizes).enumerate() {
                let [pw, ph] = layout.pages[slot.page];
                let [x0, y0, x1, y1] = slot.plate;
                assert_eq!([x1 - x0, y1 - y0], *size, "plate {i} keeps its size");
                let c = slot.cell;
                assert!(c[0] + PADDING <= x0 && c[1] + PADDING <= y0, "{i}: padding");
                assert!(x1 + PADDING <= c[2] && y1 + PADDING <= c[3], "{i}: padding");
                assert!(c[2] <= pw && c[3] <= ph, "{i}: inside page {}", slot.page);
                assert!(c.iter().all(|v| v % ALIGN == 0), "{i}: aligned {c:?}");
                if pw > page[0] || ph > page[1] {
                    let alone = layout.slots.iter().filter(|s| s.page == slot.page).count();
                    assert_eq!(
                        (alone, [pw, ph]),
                        (1, [c[2], c[3]]),
                        "{i}: a page of its own"
                    );
                }
                for other in &layout.slots[i + 1..] {
                    assert!(
                        other.page != slot.page || !overlaps(c, other.cell),
                        "{c:?} overlaps {:?}",
                        other.cell
                    );
                }
            }
            for [w, h] in &layout.pages {
                assert!(w % ALIGN == 0 && h % ALIGN == 0 && *w > 0 && *h > 0);
            }
            // Pages are trimmed to what they hold.
            for (p, &[w, h]) in layout.pages.iter().enumerate() {
                let on = layout.slots.iter().filter(|s| s.page == p);
                assert_eq!(on.clone().map(|s| s.cell[2]).max(), Some(w));
                assert_eq!(on.map(|s| s.cell[3]).max(), Some(h));
            }
        }
    }

    #[test]
    fn packing_is_deterministic_and_fills_pages() {
        let sizes = sizes(800, PAGE);
        let a = AtlasLayout::pack(&sizes, PAGE);
        assert_eq!(a, AtlasLayout::pack(&sizes, PAGE));
        // The order of the sizes given decides nothing but which slot is whose.
        let mut reversed = sizes.clone();
        reversed.reverse();
        let b = AtlasLayout::pack(&reversed, PAGE);
        assert_eq!(a.pages, b.pages);
        // Every page of shelves but the last is mostly used.
        let shelves: Vec<usize> = (0..a.pages.len())
            .filter(|&p| a.pages[p][0] <= PAGE[0] && a.pages[p][1] <= PAGE[1])
            .collect();
        assert!(shelves.len() >= 2, "{:?}", a.pages);
        for &p in &shelves[..shelves.len() - 1] {
            let [w, h] = a.pages[p];
            let used: u32 = a
                .slots
                .iter()
                .filter(|s| s.page == p)
                .map(|s| (s.cell[2] - s.cell[0]) * (s.cell[3] - s.cell[1]))
                .sum();
            assert!(used * 10 >= w * h * 9, "page {p}: {used} of {}", w * h);
        }
    }

    #[test]
    fn uvs_map_each_plate_to_its_own_rectangle() {
        let sizes = sizes(60, [256, 256]);
        let layout = AtlasLayout::pack(&sizes, [256, 256]);
        for (i, slot) in layout.slots.iter().enumerate() {
            let ([u0, u1], [v0, v1]) = layout.uv_spans(i);
            let [w, h] = layout.pages[slot.page].map(f64::from);
            let back = [u0 * w, v0 * h, u1 * w, v1 * h].map(|v| v.round() as u32);
            assert_eq!(back, slot.plate);
            assert!(0.0 <= u0 && u0 < u1 && u1 <= 1.0 && 0.0 <= v0 && v0 < v1 && v1 <= 1.0);
        }
    }

    #[test]
    fn paint_copies_plates_and_pads_with_their_edge_pixels() {
        let sizes = vec![[30, 12], [17, 40], [5, 5], [64, 9]];
        let images: Vec<RgbImage> = sizes
            .iter()
            .enumerate()
            .map(|(i, &[w, h])| {
                RgbImage::from_fn(w, h, |x, y| Rgb([i as u8 * 60 + 10, x as u8, y as u8]))
            })
            .collect();
        let layout = AtlasLayout::pack(&sizes, [128, 64]);
        for page in 0..layout.pages.len() {
            let pixels = layout.paint(page, &images);
            assert_eq!([pixels.width(), pixels.height()], layout.pages[page]);
            for (slot, image) in layout.slots.iter().zip(&images) {
                if slot.page != page {
                    continue;
                }
                let [px0, py0, px1, py1] = slot.plate;
                let [cx0, cy0, cx1, cy1] = slot.cell;
                for y in cy0..cy1 {
                    for x in cx0..cx1 {
                        let sx = x.clamp(px0, px1 - 1) - px0;
                        let sy = y.clamp(py0, py1 - 1) - py0;
                        assert_eq!(pixels.get_pixel(x, y), image.get_pixel(sx, sy));
                    }
                }
            }
        }
    }
}
