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

/// The closest hit of a ray: distance along it, the triangle's index, and where the
/// hierarchy keeps that triangle (or the piece of it hit), a hint for the next ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f32,
    pub triangle: u32,
    pub slot: u32,
}

/// What the build reads of a triangle, worked out once: its box and its centroid.
#[derive(Clone, Copy)]
struct Prim {
    min: [f32; 3],
    max: [f32; 3],
    centroid: [f32; 3],
}

impl Prim {
    fn of(t: &Tri) -> Prim {
        Prim {
            // Folded from ±∞ as `bounds` folds, so a NaN corner is skipped, not kept.
            min: std::array::from_fn(|k| t.iter().fold(f32::INFINITY, |b, p| least(p[k], b))),
            max: std::array::from_fn(|k| t.iter().fold(f32::NEG_INFINITY, |b, p| most(p[k], b))),
            centroid: std::array::from_fn(|k| (t[0][k] + t[1][k] + t[2][k]) / 3.0),
        }
    }
}

/// The smaller of a candidate `v` and a running bound `b` (`b` when `v` is NaN, as
/// `f32::min` gives, in one instruction).
#[inline]
fn least(v: f32, b: f32) -> f32 {
    if v < b { v } else { b }
}

/// The larger of a candidate `v` and a running bound `b` (`b` when `v` is NaN).
#[inline]
fn most(v: f32, b: f32) -> f32 {
    if v > b { v } else { b }
}

/// The box around `order`'s triangles.
fn bounds(prims: &[Prim], order: &[u32]) -> ([f32; 3], [f32; 3]) {
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    for &i in order {
        let p = &prims[i as usize];
        for k in 0..3 {
            min[k] = least(p.min[k], min[k]);
            max[k] = most(p.max[k], max[k]);
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

/// Runs at least this long are split with their halves built side by side.
const PARALLEL: usize = 1 << 15;

/// The subtree over `order` (which sits at `start` in the whole order), partitioned in
/// place: its nodes, the root first, a node's two children side by side, child indices
/// relative to the returned nodes and leaf runs to the whole order.
fn subtree(tris: &[Prim], order: &mut [u32], start: u32) -> Vec<Node> {
    if order.len() < PARALLEL {
        return sequential(tris, order, start);
    }
    let (min, max) = bounds(tris, order);
    let Some(left) = partition(tris, order, (min, max)) else {
        return vec![Node {
            min,
            max,
            start,
            count: order.len() as u32,
        }];
    };
    let (l, r) = order.split_at_mut(left);
    let (ln, rn) = rayon::join(
        || subtree(tris, l, start),
        || subtree(tris, r, start + left as u32),
    );
    // [root, left root, right root, the left's other nodes, the right's other nodes].
    let nl = ln.len() as u32;
    let moved = |node: Node, to: &dyn Fn(u32) -> u32| {
        if node.count == 0 {
            Node {
                start: to(node.start),
                ..node
            }
        } else {
            node
        }
    };
    let to_left = |j: u32| if j == 0 { 1 } else { j + 2 };
    let to_right = |j: u32| if j == 0 { 2 } else { j + 1 + nl };
    let mut nodes = Vec::with_capacity(1 + ln.len() + rn.len());
    nodes.push(Node {
        min,
        max,
        start: 1,
        count: 0,
    });
    nodes.push(moved(ln[0], &to_left));
    nodes.push(moved(rn[0], &to_right));
    nodes.extend(ln[1..].iter().map(|n| moved(*n, &to_left)));
    nodes.extend(rn[1..].iter().map(|n| moved(*n, &to_right)));
    nodes
}

/// [`subtree`] on one thread.
fn sequential(tris: &[Prim], order: &mut [u32], start: u32) -> Vec<Node> {
    let (min, max) = bounds(tris, order);
    let mut nodes = vec![Node {
        min,
        max,
        start: 0,
        count: order.len() as u32,
    }];
    let mut todo = vec![0usize];
    while let Some(n) = todo.pop() {
        let Node {
            min,
            max,
            start: s,
            count,
        } = nodes[n];
        let run = s as usize..(s + count) as usize;
        let Some(left) = partition(tris, &mut order[run], (min, max)) else {
            continue;
        };
        let first = nodes.len();
        let left = left as u32;
        for (s, c) in [(s, left), (s + left, count - left)] {
            let (min, max) = bounds(tris, &order[s as usize..(s + c) as usize]);
            nodes.push(Node {
                min,
                max,
                start: s,
                count: c,
            });
        }
        nodes[n].start = first as u32;
        nodes[n].count = 0;
        todo.extend([first, first + 1]);
    }
    for node in nodes.iter_mut().filter(|n| n.count > 0) {
        node.start += start;
    }
    nodes
}

/// Splits `order` (inside `bounds`) where the binned SAH is cheapest, the left part
/// first: its length, or `None` when the run stays a leaf.
fn partition(tris: &[Prim], order: &mut [u32], bounds: ([f32; 3], [f32; 3])) -> Option<usize> {
    if order.len() <= LEAF {
        return None;
    }
    let (axis, cut, lo, hi) = best_cut(tris, order, bounds)?;
    let scale = BINS as f32 / (hi - lo);
    let bin = |i: u32| (((tris[i as usize].centroid[axis] - lo) * scale) as usize).min(BINS - 1);
    let mut left = 0;
    for i in 0..order.len() {
        if bin(order[i]) < cut {
            order.swap(i, left);
            left += 1;
        }
    }
    (left > 0 && left < order.len()).then_some(left)
}

/// The axis and bin boundary of the cheapest split of `order` (inside `bounds`), with
/// the centroids' span on that axis, if one is cheaper than a leaf.
fn best_cut(
    tris: &[Prim],
    order: &[u32],
    (min, max): ([f32; 3], [f32; 3]),
) -> Option<(usize, usize, f32, f32)> {
    let mut best: Option<(f32, usize, usize, f32, f32)> = None;
    for axis in 0..3 {
        let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
        for &i in order {
            let c = tris[i as usize].centroid[axis];
            lo = least(c, lo);
            hi = most(c, hi);
        }
        if hi - lo <= 1e-6 {
            continue;
        }
        let scale = BINS as f32 / (hi - lo);
        let mut boxes = [([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]); BINS];
        let mut counts = [0usize; BINS];
        for &i in order {
            let t = &tris[i as usize];
            let b = (((t.centroid[axis] - lo) * scale) as usize).min(BINS - 1);
            counts[b] += 1;
            for k in 0..3 {
                boxes[b].0[k] = least(t.min[k], boxes[b].0[k]);
                boxes[b].1[k] = most(t.max[k], boxes[b].1[k]);
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
                        min[k] = least(boxes[b].0[k], min[k]);
                        max[k] = most(boxes[b].1[k], max[k]);
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
    (cost < area(min, max) * order.len() as f32).then_some((axis, cut, lo, hi))
}

fn area(min: [f32; 3], max: [f32; 3]) -> f32 {
    let d = [max[0] - min[0], max[1] - min[1], max[2] - min[2]];
    if d.iter().any(|v| *v < 0.0) {
        return 0.0;
    }
    2.0 * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0])
}

impl Bvh {
    /// The hierarchy of `tris` (binned surface-area heuristic, 12 bins per axis). Runs of
    /// at least 32,768 triangles build their two halves side by side; the tree, and
    /// so every hit, is the same whatever the thread count.
    pub fn build(original: &[Tri]) -> Bvh {
        let mut pieces: Vec<(Tri, u32)> = Vec::with_capacity(original.len());
        for (i, t) in original.iter().enumerate() {
            split_long(*t, i as u32, &mut pieces);
        }
        let prims: Vec<Prim> = pieces.iter().map(|p| Prim::of(&p.0)).collect();
        let mut order: Vec<u32> = (0..prims.len() as u32).collect();
        let nodes = subtree(&prims, &mut order, 0);
        let ordered = order.iter().map(|&i| pieces[i as usize].0).collect();
        for i in &mut order {
            *i = pieces[*i as usize].1;
        }
        Bvh {
            nodes,
            order,
            ordered,
        }
    }

    /// Triangles the hierarchy holds (long ones split into pieces).
    pub fn triangles(&self) -> usize {
        self.ordered.len()
    }

    /// The closest hit of the ray `origin + t·dir` with `t` in `(0, t_max)`. The nearer
    /// child is visited first and a node farther than the best hit so far is skipped, so
    /// a ray reads few leaves beyond the one it stops in. `hint` (the slot a neighbouring
    /// ray hit) is tried first: when the ray hits it too, only nodes nearer than that hit
    /// are visited. Of two hits at exactly one distance the hint's is kept.
    pub fn closest(
        &self,
        origin: [f32; 3],
        dir: [f32; 3],
        t_max: f32,
        hint: Option<u32>,
    ) -> Option<Hit> {
        let ray = Ray::new(origin, dir);
        let mut best: Option<Hit> = None;
        let mut reach = t_max;
        if let Some(slot) = hint
            && let Some(tri) = self.ordered.get(slot as usize)
            && let Some(t) = intersect(tri, origin, dir)
            && t < reach
        {
            reach = t;
            best = Some(Hit {
                t,
                triangle: self.order[slot as usize],
                slot,
            });
        }
        // Nodes still to visit, with the distance where the ray enters their box.
        let mut stack = [(0u32, 0.0f32); 64];
        let mut top = 0;
        let root = self.nodes.first().filter(|_| !self.ordered.is_empty());
        let mut next = root.and_then(|r| slab(r, &ray, reach)).map(|_| 0u32);
        while let Some(n) = next.take() {
            let node = &self.nodes[n as usize];
            if node.count == 0 {
                let (l, r) = (node.start, node.start + 1);
                let tl = slab(&self.nodes[l as usize], &ray, reach);
                let tr = slab(&self.nodes[r as usize], &ray, reach);
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
                let slots = node.start..node.start + node.count;
                for ((tri, &i), slot) in self.ordered[run.clone()]
                    .iter()
                    .zip(&self.order[run])
                    .zip(slots)
                {
                    if let Some(t) = intersect(tri, origin, dir)
                        && t < reach
                    {
                        reach = t;
                        best = Some(Hit {
                            t,
                            triangle: i,
                            slot,
                        });
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

/// A ray as the box test reads it: its origin, its direction's reciprocal per axis
/// (±∞ for a zero component) and, per axis, whether it points down that axis.
struct Ray {
    origin: [f32; 3],
    inv: [f32; 3],
    negative: [bool; 3],
}

impl Ray {
    fn new(origin: [f32; 3], dir: [f32; 3]) -> Ray {
        Ray {
            origin,
            inv: dir.map(|d| 1.0 / d),
            negative: dir.map(|d| d.is_sign_negative()),
        }
    }
}

/// Where the ray enters `node`'s box, if it does before `reach`.
///
/// Per axis, the plane the ray meets first (by its direction's sign) gives the entry and
/// the other the exit (Williams et al. 2005), so no axis needs a min and a max. An axis
/// the ray runs parallel to gives ±∞ (outside the slab: no entry) or, when the origin lies
/// on one of its planes, `0 · ∞` = NaN; the comparisons below keep the running bound
/// whenever the candidate is NaN (a comparison with NaN is false), so that axis bounds
/// nothing, as the ray lies in the closed slab. Plain comparisons are one instruction
/// each; `f32::min` and `max`, with their NaN handling, cost a third of a scan.
#[inline]
fn slab(node: &Node, ray: &Ray, reach: f32) -> Option<f32> {
    let mut t0 = 0.0f32;
    let mut t1 = reach;
    for k in 0..3 {
        let (near, far) = if ray.negative[k] {
            (node.max[k], node.min[k])
        } else {
            (node.min[k], node.max[k])
        };
        let enter = (near - ray.origin[k]) * ray.inv[k];
        let exit = (far - ray.origin[k]) * ray.inv[k];
        t0 = if enter > t0 { enter } else { t0 };
        t1 = if exit < t1 { exit } else { t1 };
    }
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
        hits_equal_brute_force(&soup(3000), 2000);
    }

    /// A hierarchy big enough to build its halves side by side: the same hits, and the
    /// same nodes on one thread as on two.
    #[test]
    fn a_parallel_build_hits_the_same_and_is_the_same_on_any_thread_count() {
        let tris = soup(3 * PARALLEL);
        hits_equal_brute_force(&tris, 200);
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let a = one.install(|| Bvh::build(&tris));
        let b = Bvh::build(&tris);
        assert_eq!(a.order, b.order);
        let key = |n: &Node| (n.min, n.max, n.start, n.count);
        assert!(a.nodes.iter().map(key).eq(b.nodes.iter().map(key)));
    }

    /// Rays along the axes (two or one zero components, each of either sign) through a
    /// city-like soup of axis-aligned walls and floors on a whole-metre grid, starting on
    /// the grid's planes too (where a box face may lie in the ray's own plane): the same
    /// closest hits as brute force.
    #[test]
    fn rays_along_the_axes_hit_as_brute_force() {
        let mut rng = crate::rng::stream(7, "bvh-axis", 0);
        let mut tris = Vec::new();
        for _ in 0..1500 {
            let c: [f32; 3] = std::array::from_fn(|_| rng.random_range(-40..40) as f32);
            let (a, b) = (rng.random_range(1..6) as f32, rng.random_range(1..6) as f32);
            let quad: [[f32; 3]; 4] = match rng.random_range(0..3) {
                0 => [[0.0, 0.0, 0.0], [a, 0.0, 0.0], [a, b, 0.0], [0.0, b, 0.0]],
                1 => [[0.0, 0.0, 0.0], [0.0, 0.0, a], [0.0, b, a], [0.0, b, 0.0]],
                _ => [[0.0, 0.0, 0.0], [a, 0.0, 0.0], [a, 0.0, b], [0.0, 0.0, b]],
            };
            let q = quad.map(|p| std::array::from_fn(|k| c[k] + p[k]));
            tris.push([q[0], q[1], q[2]]);
            tris.push([q[0], q[2], q[3]]);
        }
        let bvh = Bvh::build(&tris);
        let mut hits = 0;
        for i in 0..3000 {
            // Whole or half metres: on the walls' planes, or between them.
            let o: [f32; 3] = std::array::from_fn(|_| rng.random_range(-90..90) as f32 * 0.5);
            let mut d = [0.0f32; 3];
            d[i % 3] = if i % 2 == 0 { 1.0 } else { -1.0 };
            if i % 5 == 0 {
                d[(i + 1) % 3] = -0.0;
            }
            if i % 7 == 0 {
                d[(i + 2) % 3] = 0.3;
            }
            let brute = (0..tris.len())
                .filter_map(|k| intersect(&tris[k], o, d).map(|t| (t, k as u32)))
                .filter(|(t, _)| *t < 1e6)
                .min_by(|a, b| a.0.total_cmp(&b.0));
            let fast = bvh.closest(o, d, 1e6, None).map(|h| (h.t, h.triangle));
            assert_eq!(fast.map(|f| f.0), brute.map(|b| b.0), "ray {o:?} {d:?}");
            hits += usize::from(fast.is_some());
        }
        assert!(hits > 300, "{hits} rays hit");
    }

    #[test]
    fn an_empty_hierarchy_hits_nothing() {
        let bvh = Bvh::build(&[]);
        assert_eq!(bvh.closest([0.0; 3], [1.0, 0.0, 0.0], 1e6, Some(0)), None);
    }

    fn hits_equal_brute_force(tris: &[Tri], rays: usize) {
        let bvh = Bvh::build(tris);
        let mut rng = crate::rng::stream(7, "bvh-rays", 0);
        let mut hits = 0;
        for _ in 0..rays {
            let o: [f32; 3] = std::array::from_fn(|_| rng.random_range(-60.0..60.0));
            let d: [f32; 3] = std::array::from_fn(|_| rng.random_range(-1.0..1.0f32));
            let brute = (0..tris.len())
                .filter_map(|i| intersect(&tris[i], o, d).map(|t| (t, i as u32)))
                .filter(|(t, _)| *t < 1e6)
                .min_by(|a, b| a.0.total_cmp(&b.0));
            let fast = bvh.closest(o, d, 1e6, None).map(|h| (h.t, h.triangle));
            // With any hint, hit or missed, the same closest hit.
            let hint = rng.random_range(0..tris.len() as u32);
            let hinted = bvh
                .closest(o, d, 1e6, Some(hint))
                .map(|h| (h.t, h.triangle));
            assert_eq!(hinted, fast);
            assert_eq!(fast, brute);
            hits += usize::from(fast.is_some());
        }
        assert!(hits * 10 > rays, "{hits} rays hit");
    }
}
