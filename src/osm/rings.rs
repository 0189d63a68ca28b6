//! Polygons: rings joined from a multipolygon's member ways, shoelace areas, point in ring.

/// Joins ways (node id sequences) into closed rings, end to end, in the members' order:
/// each ring starts with the first way not used yet and takes, again and again, the first
/// unused way that continues it at either end (reversed if need be), until it closes.
/// `None` when a ring cannot close (a member missing from an extract cut at the box).
pub fn join(ways: &[&[i64]]) -> Option<Vec<Vec<i64>>> {
    let mut used = vec![false; ways.len()];
    let mut rings = Vec::new();
    while let Some(first) = used.iter().position(|u| !u) {
        used[first] = true;
        let mut ring: Vec<i64> = ways[first].to_vec();
        while ring.len() < 2 || ring.first() != ring.last() {
            let end = *ring.last()?;
            let next = (0..ways.len()).find(|&i| {
                !used[i] && (ways[i].first() == Some(&end) || ways[i].last() == Some(&end))
            })?;
            used[next] = true;
            if ways[next].first() == Some(&end) {
                ring.extend_from_slice(&ways[next][1..]);
            } else {
                ring.extend(ways[next].iter().rev().skip(1));
            }
        }
        ring.pop();
        if ring.len() >= 3 {
            rings.push(ring);
        }
    }
    Some(rings)
}

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ways_join_into_rings_whatever_their_direction() {
        // A square in three ways, the middle one drawn backwards, and a triangle of its own.
        let a: &[i64] = &[1, 2, 3];
        let b: &[i64] = &[4, 3];
        let c: &[i64] = &[4, 1];
        let t: &[i64] = &[7, 8, 9, 7];
        let rings = join(&[a, t, b, c]).unwrap();
        assert_eq!(rings, vec![vec![1, 2, 3, 4], vec![7, 8, 9]]);
        // A gap: the ring cannot close.
        assert_eq!(join(&[a, b]), None);
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
