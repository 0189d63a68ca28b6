//! Run-length masks exactly as pycocotools writes them: column-major runs, compressed string.
//!
//! A mask of `h × w` pixels is read column by column (x outer, y inner). `counts` holds the
//! lengths of alternating runs of 0s and 1s, starting with a (possibly empty) run of 0s; a
//! trailing run of 0s is written only when it is not empty, as `rleEncode` in pycocotools'
//! `maskApi.c` does. The compressed string follows its `rleToString`: each count from the
//! fourth on is replaced by its difference to the count two before, then written as a
//! signed little-endian base-32 number, 5 bits per character plus a continuation bit,
//! offset by ASCII 48.

use thiserror::Error;

/// A run-length encoded binary mask.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rle {
    /// `[height, width]`, the order COCO's `size` uses.
    pub size: [u32; 2],
    /// Alternating run lengths, 0s first.
    pub counts: Vec<u64>,
}

/// A rectangle of a mask, decoded: the pixels of `bounds` = `[x0, y0, x1, y1]`
/// (end-exclusive), row-major (`pixels[(y - y0) * (x1 - x0) + (x - x0)]`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MaskWindow {
    pub bounds: [u32; 4],
    pub pixels: Vec<bool>,
}

impl MaskWindow {
    /// Whether the pixel `(x, y)` is set; false outside the window.
    pub fn get(&self, x: u32, y: u32) -> bool {
        let [x0, y0, x1, y1] = self.bounds;
        (x0..x1).contains(&x)
            && (y0..y1).contains(&y)
            && self.pixels[(y - y0) as usize * (x1 - x0) as usize + (x - x0) as usize]
    }
}

/// Alternating runs being counted, 0s first, as [`Rle::from_row_major`] counts them.
#[derive(Default)]
struct Runs {
    counts: Vec<u64>,
    current: bool,
    run: u64,
}

impl Runs {
    /// `len` more pixels of `value`.
    fn push(&mut self, value: bool, len: u64) {
        if len == 0 {
            return;
        }
        if value != self.current {
            self.counts.push(self.run);
            (self.current, self.run) = (value, 0);
        }
        self.run += len;
    }
}

/// Why a compressed RLE string could not be read.
#[derive(Debug, Error, PartialEq, Eq)]
pub enum RleError {
    #[error("RLE string has a character {0:?} outside '0'..='o'")]
    BadCharacter(char),
    #[error("RLE string ends in the middle of a number")]
    Truncated,
    #[error("RLE string holds a number too large for a count")]
    Overflow,
    #[error("RLE string gives a negative run length")]
    NegativeRun,
    #[error("RLE runs cover {runs} pixels, but the mask has {pixels}")]
    WrongTotal { runs: u64, pixels: u64 },
}

impl Rle {
    /// The RLE of a mask given row-major (`mask[y * width + x]`), for tests and callers
    /// that hold plain masks. Panics if `mask.len() != height × width`.
    pub fn from_row_major(mask: &[bool], height: u32, width: u32) -> Rle {
        assert_eq!(mask.len() as u64, u64::from(height) * u64::from(width));
        let mut counts = Vec::new();
        let (mut current, mut run) = (false, 0u64);
        for x in 0..width as usize {
            for y in 0..height as usize {
                let v = mask[y * width as usize + x];
                if v != current {
                    counts.push(run);
                    (current, run) = (v, 0);
                }
                run += 1;
            }
        }
        counts.push(run);
        Rle {
            size: [height, width],
            counts,
        }
    }

    /// The mask, row-major (`[y * width + x]`).
    pub fn to_row_major(&self) -> Vec<bool> {
        let [h, w] = self.size;
        self.window([0, 0, w, h]).pixels
    }

    /// The pixels of the rectangle `bounds` = `[x0, y0, x1, y1]` (end-exclusive, inside
    /// the mask), decoded without touching the rest: the runs of 0s are skipped whole, so
    /// it costs the pixels set, not the mask's size.
    pub fn window(&self, bounds: [u32; 4]) -> MaskWindow {
        let [x0, y0, x1, y1] = bounds;
        let h = u64::from(self.size[0]);
        let total = h * u64::from(self.size[1]);
        let width = x1.saturating_sub(x0) as usize;
        let mut pixels = vec![false; width * y1.saturating_sub(y0) as usize];
        let mut t = 0u64;
        for (i, &count) in self.counts.iter().enumerate() {
            let end = t.saturating_add(count).min(total);
            if i % 2 == 1 {
                for p in t..end {
                    let (x, y) = ((p / h) as u32, (p % h) as u32);
                    if x >= x1 {
                        break;
                    }
                    if x >= x0 && (y0..y1).contains(&y) {
                        pixels[(y - y0) as usize * width + (x - x0) as usize] = true;
                    }
                }
            }
            t = end;
            if t >= total {
                break;
            }
        }
        MaskWindow { bounds, pixels }
    }

    /// The RLE of a `height × width` mask whose pixels are 0 outside `window`: what
    /// [`Rle::from_row_major`] gives for the whole mask, at the cost of the window's size.
    pub fn from_window(window: &MaskWindow, height: u32, width: u32) -> Rle {
        let [x0, y0, x1, y1] = window.bounds;
        let (h, cols) = (u64::from(height), (x1 - x0) as usize);
        let mut runs = Runs::default();
        runs.push(false, u64::from(x0) * h);
        for x in 0..cols {
            runs.push(false, u64::from(y0));
            for y in 0..(y1 - y0) as usize {
                runs.push(window.pixels[y * cols + x], 1);
            }
            runs.push(false, h - u64::from(y1));
        }
        runs.push(false, u64::from(width - x1) * h);
        runs.counts.push(runs.run);
        Rle {
            size: [height, width],
            counts: runs.counts,
        }
    }

    /// Pixels set.
    pub fn area(&self) -> u64 {
        self.counts.iter().skip(1).step_by(2).sum()
    }

    /// The compressed `counts` string of pycocotools (`rleToString`).
    pub fn to_compressed(&self) -> String {
        let mut out = String::new();
        for (i, &count) in self.counts.iter().enumerate() {
            let mut x = count as i64;
            if i > 2 {
                x -= self.counts[i - 2] as i64;
            }
            loop {
                let mut c = (x & 0x1f) as u8;
                x >>= 5;
                let more = if c & 0x10 != 0 { x != -1 } else { x != 0 };
                if more {
                    c |= 0x20;
                }
                out.push(char::from(c + 48));
                if !more {
                    break;
                }
            }
        }
        out
    }

    /// Reads a compressed `counts` string (pycocotools' `rleFrString`) for an `h × w` mask,
    /// checking that the runs cover the mask exactly.
    pub fn from_compressed(s: &str, height: u32, width: u32) -> Result<Rle, RleError> {
        let mut counts: Vec<u64> = Vec::new();
        let mut bytes = s.chars().peekable();
        while bytes.peek().is_some() {
            let (mut x, mut k) = (0i64, 0u32);
            loop {
                let ch = bytes.next().ok_or(RleError::Truncated)?;
                let c = (ch as u32)
                    .checked_sub(48)
                    .filter(|c| *c < 64)
                    .ok_or(RleError::BadCharacter(ch))? as i64;
                if 5 * k >= 60 {
                    return Err(RleError::Overflow);
                }
                x |= (c & 0x1f) << (5 * k);
                k += 1;
                if c & 0x20 == 0 {
                    if c & 0x10 != 0 {
                        x |= -1i64 << (5 * k);
                    }
                    break;
                }
            }
            let m = counts.len();
            if m > 2 {
                x = x
                    .checked_add(counts[m - 2] as i64)
                    .ok_or(RleError::Overflow)?;
            }
            if x < 0 {
                return Err(RleError::NegativeRun);
            }
            counts.push(x as u64);
        }
        let pixels = u64::from(height) * u64::from(width);
        let runs = counts
            .iter()
            .try_fold(0u64, |a, &c| a.checked_add(c))
            .ok_or(RleError::Overflow)?;
        if runs != pixels {
            return Err(RleError::WrongTotal { runs, pixels });
        }
        Ok(Rle {
            size: [height, width],
            counts,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::RngExt;

    /// A window decoded from an RLE is that part of the whole mask, and the RLE of a mask
    /// that is 0 outside a window is the whole mask's RLE: random masks and windows, the
    /// frame's edges included.
    #[test]
    fn windows_agree_with_the_whole_mask() {
        let mut rng = crate::rng::stream(5, "rle-window-test", 0);
        for case in 0..300 {
            let (h, w) = (rng.random_range(1..9u32), rng.random_range(1..9u32));
            let x0 = rng.random_range(0..=w);
            let y0 = rng.random_range(0..=h);
            let x1 = rng.random_range(x0..=w);
            let y1 = rng.random_range(y0..=h);
            let density = rng.random_range(0.0..1.0f64);
            let whole: Vec<bool> = (0..h * w).map(|_| rng.random_bool(density)).collect();
            let rle = Rle::from_row_major(&whole, h, w);
            let window = rle.window([x0, y0, x1, y1]);
            for y in 0..h {
                for x in 0..w {
                    let inside = (x0..x1).contains(&x) && (y0..y1).contains(&y);
                    let expected = inside && whole[(y * w + x) as usize];
                    assert_eq!(window.get(x, y), expected, "case {case} at {x},{y}");
                }
            }
            let cut: Vec<bool> = (0..h * w).map(|i| window.get(i % w, i / w)).collect();
            assert_eq!(
                Rle::from_window(&window, h, w),
                Rle::from_row_major(&cut, h, w),
                "case {case}"
            );
            assert_eq!(rle.to_row_major(), whole, "case {case}");
        }
    }

    /// Counts and strings worked out by hand from `rleToString`.
    #[test]
    fn compresses_known_counts() {
        let cases: [(&[u64], &str); 6] = [
            (&[6], "6"),
            (&[2, 3, 1], "231"),
            // 4th and 5th counts are written as differences: 2 − 5 = −3 → 29 → 'M',
            // 1 − 10 = −9 → 23 → 'G'.
            (&[0, 5, 10, 2, 1], "05:MG"),
            // 100 = 3·32 + 4: low digit 4 with the continuation bit (36 → 'T'), then 3.
            (&[100], "T3"),
            // 16 has the sign bit of a 5-bit digit set, so it needs a second digit.
            (&[16], "`0"),
            (&[0, 1, 2, 40, 1, 0], "012W1OhN"),
        ];
        for (counts, expected) in cases {
            let rle = Rle {
                size: [1, counts.iter().sum::<u64>() as u32],
                counts: counts.to_vec(),
            };
            assert_eq!(rle.to_compressed(), expected, "{counts:?}");
            let back = Rle::from_compressed(expected, rle.size[0], rle.size[1]).unwrap();
            assert_eq!(back, rle, "{expected}");
        }
    }

    #[test]
    fn encodes_column_major_from_a_hand_drawn_mask() {
        // 2 rows × 3 columns:    0 1 1
        //                        0 1 0
        // Column by column: 0 0 | 1 1 | 1 0  →  runs 2, 3, 1.
        let mask = [false, true, true, false, true, false];
        let rle = Rle::from_row_major(&mask, 2, 3);
        assert_eq!(rle.counts, vec![2, 3, 1]);
        assert_eq!(rle.area(), 3);
        assert_eq!(rle.to_row_major(), mask);
        // A mask starting with a set pixel starts with an empty run of 0s; one ending with
        // a set pixel has no trailing run.
        let full = Rle::from_row_major(&[true; 4], 2, 2);
        assert_eq!(full.counts, vec![0, 4]);
        assert_eq!(full.to_compressed(), "04");
    }

    #[test]
    fn round_trips_many_masks() {
        // A fixed pseudo-random pattern with long and short runs in a 13 × 17 mask.
        let (h, w) = (13u32, 17u32);
        for pattern in 0..20u64 {
            let mask: Vec<bool> = (0..h * w)
                .map(|i| {
                    let v = u64::from(i).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ pattern;
                    (v >> 7) % (pattern % 5 + 2) == 0 || (i as u64 / 40) % 3 == pattern % 3
                })
                .collect();
            let rle = Rle::from_row_major(&mask, h, w);
            let s = rle.to_compressed();
            assert_eq!(Rle::from_compressed(&s, h, w).unwrap(), rle, "{s}");
            assert_eq!(rle.to_row_major(), mask);
        }
    }

    #[test]
    fn rejects_bad_strings() {
        let cases: [(&str, RleError); 4] = [
            ("2 1", RleError::BadCharacter(' ')),
            ("2T", RleError::Truncated),
            ("2M", RleError::NegativeRun),
            ("24", RleError::WrongTotal { runs: 6, pixels: 4 }),
        ];
        for (s, expected) in cases {
            assert_eq!(Rle::from_compressed(s, 2, 2), Err(expected), "{s}");
        }
        assert_eq!(
            Rle::from_compressed("oooooooooooooo0", 1, 1),
            Err(RleError::Overflow)
        );
    }
}
