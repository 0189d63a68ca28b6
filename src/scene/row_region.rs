//! Pixel regions as sorted x spans per row: grow, subtract, and cut back into [`Band`]s.
//!
//! The sidewalks are built with it: a block's pixels grown by the strip width, minus every
//! pixel already claimed (blocks, roads, earlier sidewalks), so no two surfaces overlap.

use crate::model::Band;

/// A set of pixels of a `width × height` image, row by row: sorted, disjoint, non-touching
/// half-open x spans.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RowRegion {
    width: u32,
    rows: Vec<Vec<[u32; 2]>>,
}

impl RowRegion {
    pub fn new(width: u32, height: u32) -> Self {
        RowRegion {
            width,
            rows: vec![Vec::new(); height as usize],
        }
    }

    pub fn height(&self) -> u32 {
        self.rows.len() as u32
    }

    pub fn row(&self, y: u32) -> &[[u32; 2]] {
        self.rows.get(y as usize).map_or(&[], Vec::as_slice)
    }

    /// Adds `[x0, x1) × [y0, y1)`, clipped to the image.
    pub fn add_rect(&mut self, x: [u32; 2], y: [u32; 2]) {
        let x = [x[0].min(self.width), x[1].min(self.width)];
        if x[0] >= x[1] {
            return;
        }
        let y1 = y[1].min(self.height());
        for row in y[0].min(y1)..y1 {
            self.add_spans(row, &[x]);
        }
    }

    /// Adds every pixel of `bands`.
    pub fn add_bands(&mut self, bands: &[Band]) {
        for band in bands {
            for &span in &band.spans {
                self.add_rect(span, [band.y0, band.y1]);
            }
        }
    }

    /// Adds all of `other` (of the same size).
    pub fn add_region(&mut self, other: &RowRegion) {
        for y in 0..other.height() {
            if !other.row(y).is_empty() {
                self.add_spans(y, other.row(y));
            }
        }
    }

    fn add_spans(&mut self, y: u32, spans: &[[u32; 2]]) {
        let Some(row) = self.rows.get_mut(y as usize) else {
            return;
        };
        row.extend_from_slice(spans);
        normalise(row);
    }

    /// `bands` grown by `by` pixels on every side (a square brush: corners stay square),
    /// clipped to the image.
    pub fn grown(width: u32, height: u32, bands: &[Band], by: u32) -> RowRegion {
        let mut region = RowRegion::new(width, height);
        for band in bands {
            let y = [band.y0.saturating_sub(by), band.y1.saturating_add(by)];
            for &[x0, x1] in &band.spans {
                region.add_rect([x0.saturating_sub(by), x1.saturating_add(by)], y);
            }
        }
        region
    }

    /// The pixels of `self` not in `other`.
    pub fn minus(&self, other: &RowRegion) -> RowRegion {
        let rows = self
            .rows
            .iter()
            .enumerate()
            .map(|(y, row)| subtract(row, other.row(y as u32)))
            .collect();
        RowRegion {
            width: self.width,
            rows,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.rows.iter().all(Vec::is_empty)
    }

    /// The region as bands: runs of consecutive rows with identical spans (empty rows left
    /// out), sorted by `y0`.
    pub fn bands(&self) -> Vec<Band> {
        let mut bands: Vec<Band> = Vec::new();
        for (y, row) in self.rows.iter().enumerate() {
            let y = y as u32;
            if row.is_empty() {
                continue;
            }
            match bands.last_mut() {
                Some(last) if last.y1 == y && last.spans == *row => last.y1 = y + 1,
                _ => bands.push(Band {
                    y0: y,
                    y1: y + 1,
                    spans: row.clone(),
                }),
            }
        }
        bands
    }
}

/// Sorts spans and merges those that overlap or touch; drops empty ones.
fn normalise(spans: &mut Vec<[u32; 2]>) {
    spans.retain(|s| s[0] < s[1]);
    spans.sort_unstable();
    let mut merged: Vec<[u32; 2]> = Vec::with_capacity(spans.len());
    for &s in spans.iter() {
        match merged.last_mut() {
            Some(last) if s[0] <= last[1] => last[1] = last[1].max(s[1]),
            _ => merged.push(s),
        }
    }
    *spans = merged;
}

/// `a` minus `b`, both normalised span lists; the result is normalised.
pub fn subtract(a: &[[u32; 2]], b: &[[u32; 2]]) -> Vec<[u32; 2]> {
    let mut out = Vec::new();
    for &[mut x0, x1] in a {
        for &[c0, c1] in b {
            if c1 <= x0 {
                continue;
            }
            if c0 >= x1 {
                break;
            }
            if c0 > x0 {
                out.push([x0, c0]);
            }
            x0 = x0.max(c1);
            if x0 >= x1 {
                break;
            }
        }
        if x0 < x1 {
            out.push([x0, x1]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn subtract_removes_the_second_spans_from_the_first() {
        type Spans = &'static [[u32; 2]];
        let cases: &[(Spans, Spans, Spans)] = &[
            (&[[0, 10]], &[], &[[0, 10]]),
            (&[[0, 10]], &[[0, 10]], &[]),
            (&[[0, 10]], &[[3, 5]], &[[0, 3], [5, 10]]),
            (&[[0, 10]], &[[0, 2], [8, 20]], &[[2, 8]]),
            (&[[0, 4], [6, 10]], &[[3, 7]], &[[0, 3], [7, 10]]),
            (&[[5, 6]], &[[0, 1], [10, 11]], &[[5, 6]]),
            (
                &[[0, 10], [20, 30]],
                &[[1, 2], [4, 5], [25, 40]],
                &[[0, 1], [2, 4], [5, 10], [20, 25]],
            ),
        ];
        for (a, b, want) in cases {
            assert_eq!(subtract(a, b), *want, "{a:?} - {b:?}");
        }
    }

    #[test]
    fn ring_around_a_rectangle_is_three_bands_with_square_corners() {
        let block = [Band {
            y0: 10,
            y1: 20,
            spans: vec![[10, 30]],
        }];
        let mut own = RowRegion::new(100, 100);
        own.add_bands(&block);
        let ring = RowRegion::grown(100, 100, &block, 8).minus(&own);
        let want = vec![
            Band {
                y0: 2,
                y1: 10,
                spans: vec![[2, 38]],
            },
            Band {
                y0: 10,
                y1: 20,
                spans: vec![[2, 10], [30, 38]],
            },
            Band {
                y0: 20,
                y1: 28,
                spans: vec![[2, 38]],
            },
        ];
        assert_eq!(ring.bands(), want);
    }

    #[test]
    fn growing_clips_to_the_image_and_merges_touching_spans() {
        let block = [
            Band {
                y0: 0,
                y1: 2,
                spans: vec![[0, 2], [5, 8]],
            },
            Band {
                y0: 2,
                y1: 3,
                spans: vec![[0, 8]],
            },
        ];
        let grown = RowRegion::grown(9, 4, &block, 2);
        assert_eq!(
            grown.bands(),
            vec![Band {
                y0: 0,
                y1: 4,
                spans: vec![[0, 9]],
            }]
        );
    }
}
