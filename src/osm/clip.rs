//! Polylines cut to a rectangle (Liang–Barsky per segment).

/// The pieces of `line` inside the rectangle `[min_x, min_z, max_x, max_z]`, each with at
/// least two distinct points.
pub fn clip(line: &[[f64; 2]], rect: [f64; 4]) -> Vec<Vec<[f64; 2]>> {
    let mut pieces: Vec<Vec<[f64; 2]>> = Vec::new();
    let mut current: Vec<[f64; 2]> = Vec::new();
    for pair in line.windows(2) {
        match segment(pair[0], pair[1], rect) {
            Some((a, b, cut_end)) => {
                if current.last() != Some(&a) {
                    flush(&mut current, &mut pieces);
                    current.push(a);
                }
                current.push(b);
                if cut_end {
                    flush(&mut current, &mut pieces);
                }
            }
            None => flush(&mut current, &mut pieces),
        }
    }
    flush(&mut current, &mut pieces);
    pieces
}

fn flush(current: &mut Vec<[f64; 2]>, pieces: &mut Vec<Vec<[f64; 2]>>) {
    current.dedup();
    if current.len() >= 2 {
        pieces.push(std::mem::take(current));
    }
    current.clear();
}

/// The part of segment `p → q` inside `rect`, and whether it stops short of `q`.
fn segment(p: [f64; 2], q: [f64; 2], rect: [f64; 4]) -> Option<([f64; 2], [f64; 2], bool)> {
    let d = [q[0] - p[0], q[1] - p[1]];
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (num, den) in [
        (p[0] - rect[0], -d[0]),
        (rect[2] - p[0], d[0]),
        (p[1] - rect[1], -d[1]),
        (rect[3] - p[1], d[1]),
    ] {
        if den == 0.0 {
            if num < 0.0 {
                return None;
            }
        } else {
            let t = num / den;
            if den < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| {
        if t == 0.0 {
            p
        } else if t == 1.0 {
            q
        } else {
            [p[0] + t * d[0], p[1] + t * d[1]]
        }
    };
    Some((at(t0), at(t1), t1 < 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_leaving_and_coming_back_is_two_pieces() {
        let rect = [0.0, 0.0, 10.0, 10.0];
        let line = [
            [-5.0, 5.0],
            [5.0, 5.0],
            [5.0, 15.0],
            [8.0, 15.0],
            [8.0, 5.0],
        ];
        let pieces = clip(&line, rect);
        assert_eq!(
            pieces,
            vec![
                vec![[0.0, 5.0], [5.0, 5.0], [5.0, 10.0]],
                vec![[8.0, 10.0], [8.0, 5.0]]
            ]
        );
        // Wholly inside: unchanged; wholly outside: nothing.
        assert_eq!(
            clip(&[[1.0, 1.0], [2.0, 2.0]], rect),
            vec![vec![[1.0, 1.0], [2.0, 2.0]]]
        );
        assert!(clip(&[[11.0, 1.0], [12.0, 2.0]], rect).is_empty());
    }
}
