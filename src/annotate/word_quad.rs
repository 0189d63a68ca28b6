//! A word's projected quad + the instance image → [`WordQuad`]: the quad and how much of the
//! word the frame shows (occlusion and the image edge both count).

/// One word of a text object as a frame shows it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WordQuad {
    /// Projected corners, clockwise from the top-left of the writing, in pixels (they may
    /// lie outside the image).
    pub quad: [[f64; 2]; 4],
    /// Pixels whose centre lies in the quad, inside the image, that show the word's object
    /// ÷ the quad's area; at most 1, 0 for a degenerate quad.
    pub visible: f64,
}

impl WordQuad {
    /// Measures `quad` against an image of `width × height` pixels, where `shows(x, y)` says
    /// whether pixel `(x, y)` shows the word's object.
    pub fn measure(
        quad: [[f64; 2]; 4],
        width: u32,
        height: u32,
        shows: impl Fn(u32, u32) -> bool,
    ) -> WordQuad {
        let area = polygon_area(&quad);
        let finite = quad.iter().flatten().all(|c| c.is_finite());
        if !finite || area < 1e-9 {
            return WordQuad { quad, visible: 0.0 };
        }
        let lo = |i: usize| quad.iter().map(|p| p[i]).fold(f64::INFINITY, f64::min);
        let hi = |i: usize| quad.iter().map(|p| p[i]).fold(f64::NEG_INFINITY, f64::max);
        let x0 = lo(0).floor().max(0.0) as u32;
        let y0 = lo(1).floor().max(0.0) as u32;
        let x1 = (hi(0).ceil().max(0.0) as u32).min(width);
        let y1 = (hi(1).ceil().max(0.0) as u32).min(height);
        let mut seen = 0u64;
        for y in y0..y1 {
            for x in x0..x1 {
                let p = [f64::from(x) + 0.5, f64::from(y) + 0.5];
                if inside(&quad, p) && shows(x, y) {
                    seen += 1;
                }
            }
        }
        WordQuad {
            quad,
            visible: (seen as f64 / area).min(1.0),
        }
    }

    /// The quad's length along the writing: the mean of its top and bottom edges.
    pub fn length(&self) -> f64 {
        let d = |a: [f64; 2], b: [f64; 2]| {
            let (dx, dy) = (a[0] - b[0], a[1] - b[1]);
            (dx * dx + dy * dy).sqrt()
        };
        (d(self.quad[0], self.quad[1]) + d(self.quad[3], self.quad[2])) / 2.0
    }
}

/// Area of a simple polygon (shoelace), whatever its winding.
fn polygon_area(p: &[[f64; 2]; 4]) -> f64 {
    let mut twice = 0.0;
    for i in 0..4 {
        let (a, b) = (p[i], p[(i + 1) % 4]);
        twice += a[0] * b[1] - b[0] * a[1];
    }
    twice.abs() / 2.0
}

/// Whether `q` lies inside the convex quad `p` (either winding; edges count).
fn inside(p: &[[f64; 2]; 4], q: [f64; 2]) -> bool {
    let side = |i: usize| {
        let (a, b) = (p[i], p[(i + 1) % 4]);
        (b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0])
    };
    let s = [side(0), side(1), side(2), side(3)];
    s.iter().all(|&v| v >= 0.0) || s.iter().all(|&v| v <= 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_word_half_past_the_edge_or_half_covered_is_half_visible() {
        let quad = [[-2.0, 0.0], [2.0, 0.0], [2.0, 2.0], [-2.0, 2.0]];
        let w = WordQuad::measure(quad, 10, 10, |_, _| true);
        assert_eq!(w.visible, 0.5);
        let quad = [[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [0.0, 2.0]];
        let w = WordQuad::measure(quad, 10, 10, |x, _| x < 2);
        assert_eq!(w.visible, 0.5);
        assert_eq!(w.length(), 4.0);
        let w = WordQuad::measure(quad, 10, 10, |_, _| true);
        assert_eq!(w.visible, 1.0);
        let gone = [[20.0, 20.0], [24.0, 20.0], [24.0, 22.0], [20.0, 22.0]];
        assert_eq!(WordQuad::measure(gone, 10, 10, |_, _| true).visible, 0.0);
        let flat = [[1.0, 1.0], [5.0, 1.0], [5.0, 1.0], [1.0, 1.0]];
        assert_eq!(WordQuad::measure(flat, 10, 10, |_, _| true).visible, 0.0);
    }
}
