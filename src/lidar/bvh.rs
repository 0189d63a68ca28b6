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
    /// The triangles in `order`, so that a leaf reads one run of memory.
    ordered: Vec<Tri>,
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

/// Longest edge a triangle of the hierarchy keeps, metres: longer ones (the ground, roads,
/// walls) are halved across their longest edge until none is, so that few leaves' boxes
/// span a street and a ray near the ground visits fewer nodes.
const MAX_EDGE: f32 = 20.0;

/// `t` (triangle `parent`) as pieces of edges at most [`MAX_EDGE`], appended to `out`.
fn split_long(t: Tri, parent: u32, out: &mut Vec<(Tri, u32)>) {
    let mut todo = vec![t];
    while let Some(t) = todo.pop() {
        let len =
            |a: [f32; 3], b: [f32; 3]| (0..3).map(|k| (a[k] - b[k]) * (a[k] - b[k])).sum::<f32>();
        let edges = [len(t[0], t[1]), len(t[1], t[2]), len(t[2], t[0])];
        let mut e = 0;
        for k in 1..3 {
            if edges[k] > edges[e] {
                e = k;
            }
        }
        if edges[e] <= MAX_EDGE * MAX_EDGE || !edges[e].is_finite() {
            out.push((t, parent));
            continue;
        }
        let (a, b, c) = (t[e], t[(e + 1) % 3], t[(e + 2) % 3]);
        let m: [f32; 3] = std::array::from_fn(|k| 0.5 * (a[k] + b[k]));
        todo.push([m, b, c]);
        todo.push([a, m, c]);
    }
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
    pub fn build(original: &[Tri]) -> Bvh {
        let mut pieces: Vec<(Tri, u32)> = Vec::with_capacity(original.len());
        for (i, t) in original.iter().enumerate() {
            split_long(*t, i as u32, &mut pieces);
        }
        let tris: Vec<Tri> = pieces.iter().map(|p| p.0).collect();
        let tris = &tris[..];
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * tris.len() / LEAF + 1),
            order: (0..tris.len() as u32).collect(),
            ordered: Vec::new(),
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
        bvh.ordered = bvh.order.iter().map(|&i| tris[i as usize]).collect();
        for i in &mut bvh.order {
            *i = pieces[*i as usize].1;
        }
        bvh
    }

    /// Triangles the hierarchy holds (long ones split into pieces).
    pub fn triangles(&self) -> usize {
        self.ordered.len()
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

    /// The closest hit of the ray `origin + t·dir` with `t` in `(0, t_max)`. The nearer
    /// child is visited first and a node farther than the best hit so far is skipped, so
    /// a ray reads few leaves beyond the one it stops in.
    pub fn closest(&self, origin: [f32; 3], dir: [f32; 3], t_max: f32) -> Option<Hit> {
        let inv = dir.map(|d| 1.0 / d);
        let oi: [f32; 3] = std::array::from_fn(|k| origin[k] * inv[k]);
        let mut best: Option<Hit> = None;
        let mut reach = t_max;
        // Nodes still to visit, with the distance where the ray enters their box.
        let mut stack = [(0u32, 0.0f32); 64];
        let mut top = 0;
        let mut next = slab(&self.nodes[0], oi, inv, reach).map(|_| 0u32);
        while let Some(n) = next.take() {
            let node = &self.nodes[n as usize];
            if node.count == 0 {
                let (l, r) = (node.start, node.start + 1);
                let tl = slab(&self.nodes[l as usize], oi, inv, reach);
                let tr = slab(&self.nodes[r as usize], oi, inv, reach);
                next = match (tl, tr) {
                    (Some(a), Some(b)) => {
                        let ((near, _), far) = if a <= b {
                            ((l, a), (r, b))
                        } else {
                            ((r, b), (l, a))
                        };
                        stack[top] = far;
                        top += 1;
                        Some(near)
                    }
                    (Some(_), None) => Some(l),
                    (None, Some(_)) => Some(r),
                    (None, None) => None,
                };
            } else {
                let run = node.start as usize..(node.start + node.count) as usize;
                for (tri, &i) in self.ordered[run.clone()].iter().zip(&self.order[run]) {
                    if let Some(t) = intersect(tri, origin, dir)
                        && t < reach
                    {
                        reach = t;
                        best = Some(Hit { t, triangle: i });
                    }
                }
            }
            while next.is_none() && top > 0 {
                top -= 1;
                let (n, entry) = stack[top];
                next = (entry <= reach).then_some(n);
            }
        }
        best
    }
}

/// Where the ray enters `node`'s box, if it does before `reach` (`oi`: the ray's origin
/// times `inv`, its direction's reciprocal, per axis).
#[inline]
fn slab(node: &Node, oi: [f32; 3], inv: [f32; 3], reach: f32) -> Option<f32> {
    let a = [0, 1, 2].map(|k| node.min[k] * inv[k] - oi[k]);
    let b = [0, 1, 2].map(|k| node.max[k] * inv[k] - oi[k]);
    let t0 = a[0]
        .min(b[0])
        .max(a[1].min(b[1]))
        .max(a[2].min(b[2]))
        .max(0.0);
    let t1 = a[0]
        .max(b[0])
        .min(a[1].max(b[1]))
        .min(a[2].max(b[2]))
        .min(reach);
    (t0 <= t1).then_some(t0)
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
            let fast = bvh.closest(o, d, 1e6).map(|h| (h.t, h.triangle));
            assert_eq!(fast, brute);
            hits += usize::from(fast.is_some());
        }
        assert!(hits > 200, "{hits} rays hit");
    }
}
