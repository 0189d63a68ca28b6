//! Quads and boxes (f64 metres) → one [`Mesh`] (f32), wound counter-clockwise from the front.

use super::vector::{UP, cross, dot, neg, sub};
use crate::model::Mesh;

/// Accumulates the triangles of one material.
///
/// Geometry is computed in f64 and rounded to f32 only when stored, so shared corners of
/// neighbouring quads round to the same f32 values.
pub struct MeshBuilder {
    mesh: Mesh,
}

impl MeshBuilder {
    pub fn new(material: u32) -> Self {
        MeshBuilder {
            mesh: Mesh {
                material,
                ..Mesh::default()
            },
        }
    }

    /// Adds a planar quad with corners in order around its edge, facing `normal` (unit).
    ///
    /// The winding is chosen from the corners and `normal`, so callers may list the corners
    /// either way round. A quad of (near) zero area is skipped: it would only add
    /// degenerate triangles.
    pub fn quad(&mut self, corners: [[f64; 3]; 4], normal: [f64; 3], uvs: [[f64; 2]; 4]) {
        self.face(&corners, normal, &uvs, &[0, 1, 2, 0, 2, 3]);
    }

    /// Adds a triangle facing the side of `normal` (unit), wound to face it; one of (near)
    /// zero area is skipped.
    pub fn triangle(&mut self, corners: [[f64; 3]; 3], normal: [f64; 3], uvs: [[f64; 2]; 3]) {
        self.face(&corners, normal, &uvs, &[0, 1, 2]);
    }

    /// A planar face of `corners` in order round its edge (triangles `fan`, indices into
    /// them), wound to face `normal`'s side: reversed when the first three corners turn
    /// the other way. Skipped when those three span (near) zero area.
    fn face(&mut self, corners: &[[f64; 3]], normal: [f64; 3], uvs: &[[f64; 2]], fan: &[u32]) {
        let [a, b, c] = [corners[0], corners[1], corners[2]];
        let n = cross(sub(b, a), sub(c, a));
        let twice_area = dot(n, n).sqrt();
        if twice_area.is_nan() || twice_area < 1e-6 {
            return;
        }
        let flip = dot(n, normal) < 0.0;
        let base = self.mesh.positions.len() as u32;
        let count = corners.len();
        for k in 0..count {
            // Reversed: the first corner stays, the rest run backwards.
            let i = if flip { (count - k) % count } else { k };
            self.mesh.positions.push(to_f32(corners[i]));
            self.mesh.normals.push(to_f32(normal));
            self.mesh.uvs.push([uvs[i][0] as f32, uvs[i][1] as f32]);
        }
        self.mesh.indices.extend(fan.iter().map(|i| base + i));
    }

    /// A horizontal quad `[x0, x1] × [z0, z1]` at height `y`, facing up, with uv = metres /
    /// `tile` (u east, v south: v grows downwards in the image as z grows southwards).
    pub fn floor(&mut self, x: [f64; 2], z: [f64; 2], y: f64, tile: f64) {
        let corners = [
            [x[0], y, z[0]],
            [x[1], y, z[0]],
            [x[1], y, z[1]],
            [x[0], y, z[1]],
        ];
        let uvs = corners.map(|p| [p[0] / tile, p[2] / tile]);
        self.quad(corners, UP, uvs);
    }

    /// A horizontal polygon at height `y`, facing up: `outer` (x, z) less `holes`,
    /// triangulated by ear clipping (`earcut`), uv = metres / `tile` as [`Self::floor`].
    /// Rings need not repeat their first point; a ring of fewer than three points, or a
    /// polygon earcut cannot cut, adds nothing.
    pub fn polygon(&mut self, outer: &[[f64; 2]], holes: &[Vec<[f64; 2]>], y: f64, tile: f64) {
        if outer.len() < 3 {
            return;
        }
        let (points, triangles) = super::polygon::triangulated(outer, holes);
        let base = self.mesh.positions.len() as u32;
        for &[x, z] in &points {
            self.mesh.positions.push(to_f32([x, y, z]));
            self.mesh.normals.push(to_f32(UP));
            self.mesh.uvs.push([(x / tile) as f32, (z / tile) as f32]);
        }
        for t in triangles.chunks_exact(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| points[i as usize]);
            // Counter-clockwise seen from above (y up, so x × z turns the other way).
            let turn = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
            let [i, j, k] = [t[0], t[1], t[2]].map(|i| base + i);
            let tri = if turn < 0.0 { [i, j, k] } else { [i, k, j] };
            self.mesh.indices.extend_from_slice(&tri);
        }
    }

    /// A vertical quad from bottom corner `a` to bottom corner `b` (x, z), from height `y0`
    /// up to `y1`, facing the horizontal unit `normal`. `u` spans `u_span` from the wall's
    /// left to its right as seen from the front; `v` runs `v_span[0]` at the top to
    /// `v_span[1]` at the bottom.
    pub fn wall(
        &mut self,
        a: [f64; 2],
        b: [f64; 2],
        y: [f64; 2],
        normal: [f64; 3],
        u_span: [f64; 2],
        v_span: [f64; 2],
    ) {
        // Looking at the front (along -normal) with y up, "right" is (-normal) × up.
        let right = cross(neg(normal), UP);
        let along = [b[0] - a[0], 0.0, b[1] - a[1]];
        let (left, right_end) = if dot(along, right) >= 0.0 {
            (a, b)
        } else {
            (b, a)
        };
        let corners = [
            [left[0], y[0], left[1]],
            [right_end[0], y[0], right_end[1]],
            [right_end[0], y[1], right_end[1]],
            [left[0], y[1], left[1]],
        ];
        let uvs = [
            [u_span[0], v_span[1]],
            [u_span[1], v_span[1]],
            [u_span[1], v_span[0]],
            [u_span[0], v_span[0]],
        ];
        self.quad(corners, normal, uvs);
    }

    /// An axis-free box: centre of its bottom face `base`, horizontal unit `forward`, half
    /// extents `[along forward, across, ]`, height `height`. All six faces, uv in metres.
    pub fn oriented_box(&mut self, base: [f64; 3], forward: [f64; 2], half: [f64; 2], height: f64) {
        let f = [forward[0], 0.0, forward[1]];
        let s = [-forward[1], 0.0, forward[0]];
        let corner = |i: f64, j: f64, k: f64| {
            [
                base[0] + f[0] * half[0] * i + s[0] * half[1] * j,
                base[1] + height * k,
                base[2] + f[2] * half[0] * i + s[2] * half[1] * j,
            ]
        };
        // (normal, four corners as (i, j, k) signs); the winding is fixed by `quad`.
        let faces: [([f64; 3], [[f64; 3]; 4]); 6] = [
            (
                f,
                [[1., -1., 0.], [1., 1., 0.], [1., 1., 1.], [1., -1., 1.]],
            ),
            (
                neg(f),
                [[-1., -1., 0.], [-1., 1., 0.], [-1., 1., 1.], [-1., -1., 1.]],
            ),
            (
                s,
                [[-1., 1., 0.], [1., 1., 0.], [1., 1., 1.], [-1., 1., 1.]],
            ),
            (
                neg(s),
                [[-1., -1., 0.], [1., -1., 0.], [1., -1., 1.], [-1., -1., 1.]],
            ),
            (
                UP,
                [[-1., -1., 1.], [1., -1., 1.], [1., 1., 1.], [-1., 1., 1.]],
            ),
            (
                neg(UP),
                [[-1., -1., 0.], [1., -1., 0.], [1., 1., 0.], [-1., 1., 0.]],
            ),
        ];
        let w = [2.0 * half[0], 2.0 * half[1], height];
        for (normal, signs) in faces {
            let corners = signs.map(|[i, j, k]| corner(i, j, k));
            // Map each face's two varying signs onto 0..extent metres.
            let uvs = signs.map(|[i, j, k]| {
                let t = |v: f64, e: f64| (v + 1.0) / 2.0 * e;
                if normal[1] != 0.0 {
                    [t(i, w[0]), t(j, w[1])]
                } else if signs.iter().all(|c| c[0] == signs[0][0]) {
                    [t(j, w[1]), (1.0 - k) * w[2]]
                } else {
                    [t(i, w[0]), (1.0 - k) * w[2]]
                }
            });
            self.quad(corners, normal, uvs);
        }
    }

    pub fn is_empty(&self) -> bool {
        self.mesh.indices.is_empty()
    }

    pub fn finish(self) -> Mesh {
        self.mesh
    }
}

fn to_f32(v: [f64; 3]) -> [f32; 3] {
    [v[0] as f32, v[1] as f32, v[2] as f32]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Geometric normal of triangle `t` of `mesh`, from the cross product of its edges.
    fn face_normal(mesh: &Mesh, t: usize) -> [f64; 3] {
        let p = |k: usize| mesh.positions[mesh.indices[3 * t + k] as usize].map(f64::from);
        cross(sub(p(1), p(0)), sub(p(2), p(0)))
    }

    #[test]
    fn quad_winds_towards_its_normal_whichever_way_the_corners_are_listed() {
        let ccw = [[0., 0., 0.], [1., 0., 0.], [1., 0., 1.], [0., 0., 1.]];
        let mut cw = ccw;
        cw.reverse();
        for (corners, normal) in [(ccw, UP), (cw, UP), (ccw, neg(UP)), (cw, neg(UP))] {
            let mut b = MeshBuilder::new(0);
            b.quad(corners, normal, [[0.0; 2]; 4]);
            let mesh = b.finish();
            assert_eq!(mesh.indices.len(), 6);
            for t in 0..2 {
                let n = face_normal(&mesh, t);
                assert!(dot(n, normal) > 0.0, "{corners:?} {normal:?}");
            }
        }
    }

    #[test]
    fn zero_area_quads_are_skipped() {
        let mut b = MeshBuilder::new(0);
        b.quad([[1.0, 2.0, 3.0]; 4], UP, [[0.0; 2]; 4]);
        b.floor([0.0, 0.0], [0.0, 5.0], 0.0, 1.0);
        assert!(b.is_empty());
    }

    #[test]
    fn wall_puts_u_zero_on_the_left_seen_from_the_front() {
        // Front facing north (-z): seen from the north, west (x = 0) is on the right.
        let mut b = MeshBuilder::new(0);
        b.wall(
            [0.0, 0.0],
            [4.0, 0.0],
            [0.0, 3.0],
            [0.0, 0.0, -1.0],
            [0.0, 1.0],
            [0.0, 1.0],
        );
        let mesh = b.finish();
        for (p, uv) in mesh.positions.iter().zip(&mesh.uvs) {
            assert_eq!(uv[0], if p[0] == 4.0 { 0.0 } else { 1.0 }, "{p:?}");
            assert_eq!(uv[1], if p[1] == 3.0 { 0.0 } else { 1.0 }, "{p:?}");
        }
        for t in 0..2 {
            assert!(face_normal(&mesh, t)[2] < 0.0);
        }
    }

    #[test]
    fn oriented_box_faces_point_out_of_the_box() {
        let inv = std::f64::consts::FRAC_1_SQRT_2;
        let mut b = MeshBuilder::new(0);
        let base = [10.0, 1.0, -3.0];
        b.oriented_box(base, [inv, inv], [0.5, 0.2], 0.3);
        let mesh = b.finish();
        assert_eq!(mesh.indices.len(), 36);
        let centre = [base[0], base[1] + 0.15, base[2]];
        for t in 0..12 {
            let n = face_normal(&mesh, t);
            let p = mesh.positions[mesh.indices[3 * t] as usize].map(f64::from);
            assert!(dot(n, sub(p, centre)) > 0.0, "triangle {t}");
            let stored = mesh.normals[mesh.indices[3 * t] as usize].map(f64::from);
            assert!(dot(n, stored) > 0.0, "triangle {t}");
        }
    }

    #[test]
    fn a_polygon_with_a_hole_is_its_area_facing_up() {
        let mut mesh = MeshBuilder::new(0);
        let outer = [[0.0, 0.0], [10.0, 0.0], [10.0, 6.0], [0.0, 6.0]];
        let hole = vec![[2.0, 2.0], [2.0, 4.0], [4.0, 4.0], [4.0, 2.0]];
        mesh.polygon(&outer, &[hole], 1.5, 2.0);
        let mesh = mesh.finish();
        let mut area = 0.0;
        for t in mesh.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| mesh.positions[t[k] as usize].map(f64::from));
            let n = cross(sub(b, a), sub(c, a));
            // Counter-clockwise seen from above: the face's normal points up.
            assert!(dot(n, UP) > 0.0, "{a:?} {b:?} {c:?}");
            area += n[1] / 2.0;
        }
        assert!((area - (60.0 - 4.0)).abs() < 1e-9, "{area}");
        assert!(mesh.positions.iter().all(|p| p[1] == 1.5));
        assert_eq!(mesh.uvs[1], [5.0, 0.0]);
        // Fewer than three points: nothing.
        let mut none = MeshBuilder::new(0);
        none.polygon(&[[0.0, 0.0], [1.0, 0.0]], &[], 0.0, 1.0);
        assert!(none.is_empty());
    }
}
