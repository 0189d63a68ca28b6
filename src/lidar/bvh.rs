//! A bounding-volume hierarchy over triangles: binned SAH build, a flat node array and
//! stack traversal for the closest hit.

/// A triangle's three corners.
pub type Tri = [[f32; 3]; 3];

/// Bins per axis the build sorts centroids into.
const BINS: usize = 12;
/// The most triangles a leaf holds.
const LEAF: usize = 4;

/// One node: its box, and either two children (`count == 0`: `start` is the left child,
/// the right one follows it) or a leaf's run `start..start + count` of [`Bvh::order`].
#[derive(Clone, Copy)]
struct Node {
    min: [f32; 3],
    max: [f32; 3],
    start: u32,
    count: u32,
}

/// The hierarchy: nodes (the root first) and the triangle indices its leaves run over.
pub struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

/// The closest hit of a ray: distance along it and the triangle's index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f32,
    pub triangle: u32,
}

fn bounds(tris: &[Tri], order: &[u32]) -> ([f32; 3], [f32; 3]) {
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    for &i in order {
        for p in &tris[i as usize] {
            for k in 0..3 {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
            }
        }
    }
    (min, max)
}

fn centroid(t: &Tri, k: usize) -> f32 {
    (t[0][k] + t[1][k] + t[2][k]) / 3.0
}

fn area(min: [f32; 3], max: [f32; 3]) -> f32 {
    let d = [max[0] - min[0], max[1] - min[1], max[2] - min[2]];
    if d.iter().any(|v| *v < 0.0) {
        return 0.0;
    }
    2.0 * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0])
}

impl Bvh {
    /// The hierarchy of `tris` (binned surface-area heuristic, 12 bins per axis).
    pub fn build(tris: &[Tri]) -> Bvh {
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * tris.len() / LEAF + 1),
            order: (0..tris.len() as u32).collect(),
        };
        let (min, max) = bounds(tris, &bvh.order);
        bvh.nodes.push(Node {
            min,
            max,
            start: 0,
            count: tris.len() as u32,
        });
        let mut todo = vec![0usize];
        while let Some(n) = todo.pop() {
            if let Some(children) = bvh.split(tris, n) {
                todo.extend(children);
            }
        }
        bvh
    }

    /// Splits node `n` where the binned SAH is cheapest; its children's indices, or `None`
    /// when it stays a leaf.
    fn split(&mut self, tris: &[Tri], n: usize) -> Option<[usize; 2]> {
        let Node { start, count, .. } = self.nodes[n];
        if (count as usize) <= LEAF {
            return None;
        }
        let run = start as usize..(start + count) as usize;
        let (axis, cut, lo, hi) = self.best_cut(tris, run.clone())?;
        let order = &mut self.order[run.clone()];
        let scale = BINS as f32 / (hi - lo);
        let bin =
            |i: u32| (((centroid(&tris[i as usize], axis) - lo) * scale) as usize).min(BINS - 1);
        let mut left = 0;
        for i in 0..order.len() {
            if bin(order[i]) < cut {
                order.swap(i, left);
                left += 1;
            }
        }
        if left == 0 || left == order.len() {
            return None;
        }
        let first = self.nodes.len();
        for (s, c) in [
            (start, left as u32),
            (start + left as u32, count - left as u32),
        ] {
            let (bmin, bmax) = bounds(tris, &self.order[s as usize..(s + c) as usize]);
            self.nodes.push(Node {
                min: bmin,
                max: bmax,
                start: s,
                count: c,
            });
        }
        self.nodes[n].start = first as u32;
        self.nodes[n].count = 0;
        Some([first, first + 1])
    }

    /// The axis and bin boundary of the cheapest split of `run` (with the centroids' span
    /// on that axis), if one is cheaper than a leaf.
    fn best_cut(
        &self,
        tris: &[Tri],
        run: std::ops::Range<usize>,
    ) -> Option<(usize, usize, f32, f32)> {
        let order = &self.order[run];
        let mut best: Option<(f32, usize, usize, f32, f32)> = None;
        for axis in 0..3 {
            let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
            for &i in order {
                let c = centroid(&tris[i as usize], axis);
                lo = lo.min(c);
                hi = hi.max(c);
            }
            if hi - lo <= 1e-6 {
                continue;
            }
            let scale = BINS as f32 / (hi - lo);
            let mut boxes = [([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]); BINS];
            let mut counts = [0usize; BINS];
            for &i in order {
                let t = &tris[i as usize];
                let b = (((centroid(t, axis) - lo) * scale) as usize).min(BINS - 1);
                counts[b] += 1;
                for p in t {
                    for (k, v) in p.iter().enumerate() {
                        boxes[b].0[k] = boxes[b].0[k].min(*v);
                        boxes[b].1[k] = boxes[b].1[k].max(*v);
                    }
                }
            }
            for cut in 1..BINS {
                let side = |range: std::ops::Range<usize>| {
                    let mut min = [f32::INFINITY; 3];
                    let mut max = [f32::NEG_INFINITY; 3];
                    let mut n = 0;
                    for b in range {
                        n += counts[b];
                        for k in 0..3 {
                            min[k] = min[k].min(boxes[b].0[k]);
                            max[k] = max[k].max(boxes[b].1[k]);
                        }
                    }
                    area(min, max) * n as f32
                };
                let cost = side(0..cut) + side(cut..BINS);
                if best.is_none_or(|b| cost < b.0) {
                    best = Some((cost, axis, cut, lo, hi));
                }
            }
        }
        let (cost, axis, cut, lo, hi) = best?;
        let (min, max) = bounds(tris, order);
        (cost < area(min, max) * order.len() as f32).then_some((axis, cut, lo, hi))
    }

    /// The closest hit of the ray `origin + t·dir` with `t` in `(0, t_max)`.
    pub fn closest(
        &self,
        tris: &[Tri],
        origin: [f32; 3],
        dir: [f32; 3],
        t_max: f32,
    ) -> Option<Hit> {
        let inv = dir.map(|d| 1.0 / d);
        let mut best: Option<Hit> = None;
        let mut reach = t_max;
        let mut stack = [0u32; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top] as usize];
            if !slab(node, origin, inv, reach) {
                continue;
            }
            if node.count == 0 {
                stack[top] = node.start;
                stack[top + 1] = node.start + 1;
                top += 2;
                continue;
            }
            for &i in &self.order[node.start as usize..(node.start + node.count) as usize] {
                if let Some(t) = intersect(&tris[i as usize], origin, dir)
                    && t < reach
                {
                    reach = t;
                    best = Some(Hit { t, triangle: i });
                }
            }
        }
        best
    }
}

fn slab(node: &Node, origin: [f32; 3], inv: [f32; 3], reach: f32) -> bool {
    let (mut t0, mut t1) = (0.0f32, reach);
    for k in 0..3 {
        let a = (node.min[k] - origin[k]) * inv[k];
        let b = (node.max[k] - origin[k]) * inv[k];
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    t0 <= t1
}

/// Möller–Trumbore: the distance along `dir` to `tri`, either side facing.
pub fn intersect(tri: &Tri, origin: [f32; 3], dir: [f32; 3]) -> Option<f32> {
    let sub = |a: [f32; 3], b: [f32; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f32; 3], b: [f32; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let e1 = sub(tri[1], tri[0]);
    let e2 = sub(tri[2], tri[0]);
    let p = cross(dir, e2);
    let det = dot(e1, p);
    if det.abs() < 1e-12 {
        return None;
    }
    let inv = 1.0 / det;
    let s = sub(origin, tri[0]);
    let u = dot(s, p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = cross(s, e1);
    let v = dot(dir, q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = dot(e2, q) * inv;
    (t > 1e-4).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::RngExt;

    fn soup(n: usize) -> Vec<Tri> {
        let mut rng = crate::rng::stream(7, "bvh-test", 0);
        (0..n)
            .map(|_| {
                let c: [f32; 3] = std::array::from_fn(|_| rng.random_range(-50.0..50.0));
                std::array::from_fn(|_| std::array::from_fn(|k| c[k] + rng.random_range(-2.0..2.0)))
            })
            .collect()
    }

    /// Every ray's hit through the hierarchy is the brute-force closest hit.
    #[test]
    fn bvh_hits_equal_brute_force() {
        let tris = soup(3000);
        let bvh = Bvh::build(&tris);
        let mut rng = crate::rng::stream(7, "bvh-rays", 0);
        let mut hits = 0;
        for _ in 0..2000 {
            let o: [f32; 3] = std::array::from_fn(|_| rng.random_range(-60.0..60.0));
            let d: [f32; 3] = std::array::from_fn(|_| rng.random_range(-1.0..1.0f32));
            let brute = (0..tris.len())
                .filter_map(|i| intersect(&tris[i], o, d).map(|t| (t, i as u32)))
                .filter(|(t, _)| *t < 1e6)
                .min_by(|a, b| a.0.total_cmp(&b.0));
            let fast = bvh.closest(&tris, o, d, 1e6).map(|h| (h.t, h.triangle));
            assert_eq!(fast, brute);
            hits += usize::from(fast.is_some());
        }
        assert!(hits > 200, "{hits} rays hit");
    }
}
