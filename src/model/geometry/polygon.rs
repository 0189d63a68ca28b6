//! Polygons in the horizontal plane `[x, z]` (metres, x east, z south): shoelace areas,
//! point in ring, the normal to the left of a direction, triangles.

/// The shoelace area of a ring (first point not repeated): positive when it turns from +x
/// towards +z.
pub fn signed_area(ring: &[[f64; 2]]) -> f64 {
    let n = ring.len();
    let mut twice = 0.0;
    for i in 0..n {
        let [x0, z0] = ring[i];
        let [x1, z1] = ring[(i + 1) % n];
        twice += x0 * z1 - x1 * z0;
    }
    twice / 2.0
}

/// The unit normal to the left of the direction `a → b` (x east, z south: for a way
/// running east, north), or `None` when `a` is `b`.
pub fn left_normal(a: [f64; 2], b: [f64; 2]) -> Option<[f64; 2]> {
    let (dx, dz) = (b[0] - a[0], b[1] - a[1]);
    let len = (dx * dx + dz * dz).sqrt();
    (len > 0.0).then(|| [dz / len, -dx / len])
}

/// The unit vector from `a` towards `b`; None where they coincide.
pub fn direction(a: [f64; 2], b: [f64; 2]) -> Option<[f64; 2]> {
    let len = distance(a, b);
    (len > 0.0).then(|| [(b[0] - a[0]) / len, (b[1] - a[1]) / len])
}

/// The point of segment `a`–`b` nearest to `p`.
pub fn nearest(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> [f64; 2] {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len2 = d[0] * d[0] + d[1] * d[1];
    if len2 == 0.0 {
        return a;
    }
    let t = (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0);
    [a[0] + t * d[0], a[1] + t * d[1]]
}

/// The distance from `p` to `q`.
pub fn distance(p: [f64; 2], q: [f64; 2]) -> f64 {
    let (dx, dz) = (q[0] - p[0], q[1] - p[1]);
    (dx * dx + dz * dz).sqrt()
}

/// The unit direction of `ring`'s longest side (the first, of equal ones; the ring
/// closes), or `None` when no side has length.
pub fn longest_side(ring: &[[f64; 2]]) -> Option<[f64; 2]> {
    let n = ring.len();
    let (mut best, mut d) = (0.0, None);
    for i in 0..n {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        let len = distance(a, b);
        if len > best {
            (best, d) = (len, Some([(b[0] - a[0]) / len, (b[1] - a[1]) / len]));
        }
    }
    d
}

/// Whether `p` lies inside `ring` (even–odd rule).
pub fn contains(ring: &[[f64; 2]], p: [f64; 2]) -> bool {
    let n = ring.len();
    let mut inside = false;
    let mut j = n - 1;
    for i in 0..n {
        let (a, b) = (ring[i], ring[j]);
        if (a[1] > p[1]) != (b[1] > p[1])
            && p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0]
        {
            inside = !inside;
        }
        j = i;
    }
    inside
}

/// The distance from `p` to the nearest point on the edges of the closed `ring`
/// (infinite for an empty ring).
pub fn ring_distance(ring: &[[f64; 2]], p: [f64; 2]) -> f64 {
    (0..ring.len())
        .map(|e| distance(p, nearest(ring[e], ring[(e + 1) % ring.len()], p)))
        .fold(f64::INFINITY, f64::min)
}

/// `[min_x, min_z, max_x, max_z]` of `ring`.
pub fn bounds(ring: &[[f64; 2]]) -> [f64; 4] {
    let far = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    ring.iter().fold(far, |[a, b, c, d], &[x, z]| {
        [a.min(x), b.min(z), c.max(x), d.max(z)]
    })
}

/// The triangles of `outer` less `holes` (ear clipping, `earcut`), as points; none for a
/// ring of fewer than three points or a polygon earcut cannot cut.
pub fn triangles(outer: &[[f64; 2]], holes: &[Vec<[f64; 2]>]) -> Vec<[[f64; 2]; 3]> {
    let (points, indices) = triangulated(outer, holes);
    indices
        .chunks_exact(3)
        .map(|t| [0, 1, 2].map(|k| points[t[k] as usize]))
        .collect()
}

/// `outer`'s points then each hole's (of three points or more), and the triangles of
/// `outer` less `holes` as indices into them, three to a triangle (`earcut`); no
/// triangles for a ring of fewer than three points or a polygon earcut cannot cut.
pub fn triangulated(outer: &[[f64; 2]], holes: &[Vec<[f64; 2]>]) -> (Vec<[f64; 2]>, Vec<u32>) {
    let mut points: Vec<[f64; 2]> = outer.to_vec();
    let mut starts: Vec<u32> = Vec::with_capacity(holes.len());
    for hole in holes.iter().filter(|h| h.len() >= 3) {
        starts.push(points.len() as u32);
        points.extend_from_slice(hole);
    }
    let mut indices: Vec<u32> = Vec::new();
    if outer.len() >= 3 {
        earcut::Earcut::new().earcut(points.iter().copied(), &starts, &mut indices);
    }
    (points, indices)
}

/// The area of triangle `[a, b, c]`, whichever way it turns.
pub fn triangle_area([a, b, c]: [[f64; 2]; 3]) -> f64 {
    ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).abs() / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_with_a_hole_is_cut_into_triangles_covering_its_area() {
        let square = [[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]];
        let hole = vec![[1.0, 1.0], [1.0, 3.0], [3.0, 3.0], [3.0, 1.0]];
        let cut = triangles(&square, &[hole]);
        let area: f64 = cut.iter().map(|&t| triangle_area(t)).sum();
        assert!((area - 12.0).abs() < 1e-9, "{area}");
        // No triangle covers the hole's middle.
        assert!(!cut.iter().any(|t| contains(t, [2.0, 2.0])));
        assert!(triangles(&square[..2], &[]).is_empty());
    }

    #[test]
    fn area_and_inside_of_a_square() {
        let square = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        assert_eq!(signed_area(&square), 4.0);
        let back: Vec<_> = square.iter().rev().copied().collect();
        assert_eq!(signed_area(&back), -4.0);
        assert!(contains(&square, [1.0, 1.0]));
        assert!(!contains(&square, [3.0, 1.0]));
    }
}
