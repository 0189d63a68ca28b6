//! Rings joined from a multipolygon's member ways.

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
}
