//! Window rows: window boxes (and door/shop boxes) of a cropped facade → estimated floors.
//!
//! Windows whose vertical centres lie within half a median window height of each other are
//! one row (single linkage over the sorted centres), and each row is a floor. A ground floor
//! of shops or doors has no windows, so it would be missed: a door or shop box whose centre
//! lies more than one median window height below the lowest row adds one floor.

use crate::model::PxRect;

/// Floors estimated from the boxes; `None` when there are no windows.
pub fn estimate_floors(windows: &[PxRect], doors_and_shops: &[PxRect]) -> Option<u32> {
    if windows.is_empty() {
        return None;
    }
    let mut heights: Vec<u32> = windows.iter().map(PxRect::height).collect();
    heights.sort_unstable();
    let median = f64::from(heights[heights.len() / 2]);
    let mut centres: Vec<f64> = windows.iter().map(centre_y).collect();
    centres.sort_by(f64::total_cmp);
    let mut rows = 1u32;
    for pair in centres.windows(2) {
        if pair[1] - pair[0] > median / 2.0 {
            rows += 1;
        }
    }
    let lowest = centres[centres.len() - 1];
    let ground = doors_and_shops
        .iter()
        .any(|b| centre_y(b) > lowest + median);
    Some(rows + u32::from(ground))
}

fn centre_y(r: &PxRect) -> f64 {
    f64::from(r.y0 + r.y1) / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x0: u32, y0: u32, x1: u32, y1: u32) -> PxRect {
        PxRect { x0, y0, x1, y1 }
    }

    /// A grid of `rows × cols` windows 50 px high, one row per 100 px, with a little jitter.
    fn grid(rows: u32, cols: u32) -> Vec<PxRect> {
        let mut out = Vec::new();
        for r in 0..rows {
            for c in 0..cols {
                let jitter = (r * 7 + c * 3) % 9;
                out.push(rect(
                    c * 80,
                    r * 100 + 20 + jitter,
                    c * 80 + 40,
                    r * 100 + 70 + jitter,
                ));
            }
        }
        out
    }

    /// What, windows, doors and shops, expected floors.
    type Case = (&'static str, Vec<PxRect>, Vec<PxRect>, Option<u32>);

    #[test]
    fn estimates_table() {
        let door = rect(10, 330, 50, 400); // centre 365, inside the 4th row's band
        let low_door = rect(10, 420, 50, 500); // centre 460, a floor below a 4-row grid
        let shop = rect(0, 415, 300, 495);
        let cases: [Case; 7] = [
            ("no windows", vec![], vec![shop], None),
            ("one window", grid(1, 1), vec![], Some(1)),
            ("4 × 3 grid", grid(4, 3), vec![], Some(4)),
            (
                "door beside ground windows",
                grid(4, 3),
                vec![door],
                Some(4),
            ),
            (
                "door below the windows",
                grid(4, 3),
                vec![low_door],
                Some(5),
            ),
            (
                "shop below the windows",
                grid(4, 3),
                vec![shop, low_door],
                Some(5),
            ),
            (
                "windows of mixed heights",
                {
                    let mut w = grid(3, 2);
                    w.push(rect(200, 10, 240, 90)); // tall window on the first floor
                    w
                },
                vec![],
                Some(3),
            ),
        ];
        for (what, windows, ground, expected) in cases {
            assert_eq!(estimate_floors(&windows, &ground), expected, "{what}");
        }
    }
}
