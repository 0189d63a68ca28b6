//! Convex profiles, prisms and polygons (f64 metres) → flat-shaded [`Mesh`]es for the
//! built-in cars and trees.
//!
//! Every face is wound counter-clockwise around the outward normal it is given (the winding
//! is chosen from the corners, as `MeshBuilder::quad` does), and its vertices carry that
//! normal: the renderer shades faces flat, so low-poly solids read as solids. No uvs (an
//! empty list): these materials are plain colours, and the OBJ and GLB then carry none.

use crate::model::Mesh;
use crate::model::geometry::{cross, dot, sub};

/// A local frame on the ground: `origin` (x, y, z), horizontal unit `forward` (x, z). Local
/// coordinates are `(u, y, v)`: `u` along forward, `y` up, `v` to the right of forward.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    pub origin: [f64; 3],
    pub forward: [f64; 2],
}

impl Frame {
    /// The right-hand side of `forward` (x east, z south): `(-f.z, f.x)`.
    pub fn right(&self) -> [f64; 2] {
        [-self.forward[1], self.forward[0]]
    }

    /// World position of local `(u, y, v)`.
    pub fn at(&self, u: f64, y: f64, v: f64) -> [f64; 3] {
        let (f, r) = (self.forward, self.right());
        [
            self.origin[0] + f[0] * u + r[0] * v,
            self.origin[1] + y,
            self.origin[2] + f[1] * u + r[1] * v,
        ]
    }

    /// World direction of local `(u, y, v)`.
    pub fn dir(&self, u: f64, y: f64, v: f64) -> [f64; 3] {
        let (f, r) = (self.forward, self.right());
        [f[0] * u + r[0] * v, y, f[1] * u + r[1] * v]
    }
}

/// Accumulates flat-shaded triangles of one material.
pub struct Solid {
    mesh: Mesh,
}

impl Solid {
    pub fn new(material: u32) -> Self {
        Solid {
            mesh: Mesh {
                material,
                ..Mesh::default()
            },
        }
    }

    /// A planar convex polygon (corners in order around its edge, either way round) facing
    /// `normal`, as a fan. Polygons of (near) zero area are skipped.
    pub fn polygon(&mut self, corners: &[[f64; 3]], normal: [f64; 3]) {
        if corners.len() < 3 {
            return;
        }
        let mut area = [0.0; 3];
        for k in 1..corners.len() - 1 {
            let c = cross(sub(corners[k], corners[0]), sub(corners[k + 1], corners[0]));
            area = [area[0] + c[0], area[1] + c[1], area[2] + c[2]];
        }
        let turn = dot(area, normal);
        if turn.is_nan() || turn.abs() <= 1e-9 {
            return;
        }
        let base = self.mesh.positions.len() as u32;
        for p in corners {
            self.mesh.positions.push(p.map(|v| v as f32));
            self.mesh.normals.push(normal.map(|v| v as f32));
        }
        for k in 1..corners.len() as u32 - 1 {
            if turn > 0.0 {
                self.mesh.indices.extend([base, base + k, base + k + 1]);
            } else {
                self.mesh.indices.extend([base, base + k + 1, base + k]);
            }
        }
    }

    /// A triangle facing away from `inside` (a point behind it).
    pub fn triangle_out(&mut self, corners: [[f64; 3]; 3], inside: [f64; 3]) {
        let n = cross(sub(corners[1], corners[0]), sub(corners[2], corners[0]));
        let len = dot(n, n).sqrt();
        if len.is_nan() || len <= 1e-12 {
            return;
        }
        let mut n = n.map(|v| v / len);
        if dot(n, sub(corners[0], inside)) < 0.0 {
            n = n.map(|v| -v);
        }
        self.polygon(&corners, n);
    }

    /// A convex side profile `(u, y)` extruded across `v ∈ [v0, v1]` in `frame`: both
    /// caps and every edge face, each facing out. `skip` leaves out the edge faces whose
    /// index (edge `k` runs from point `k` to `k + 1`) it holds, for another material.
    pub fn prism(&mut self, frame: &Frame, profile: &[[f64; 2]], v: [f64; 2], skip: &[usize]) {
        let n = profile.len();
        if n < 3 {
            return;
        }
        let centre = centroid(profile);
        let side = |vv: f64| -> Vec<[f64; 3]> {
            profile.iter().map(|p| frame.at(p[0], p[1], vv)).collect()
        };
        let right = frame.dir(0.0, 0.0, 1.0);
        self.polygon(&side(v[1]), right);
        self.polygon(&side(v[0]), right.map(|x| -x));
        for k in (0..n).filter(|k| !skip.contains(k)) {
            self.profile_face(frame, profile, centre, k, v);
        }
    }

    /// Edge face `k` of a convex `profile` extruded across `v` (see [`Solid::prism`]).
    pub fn profile_face(
        &mut self,
        frame: &Frame,
        profile: &[[f64; 2]],
        centre: [f64; 2],
        k: usize,
        v: [f64; 2],
    ) {
        let (a, b) = (profile[k], profile[(k + 1) % profile.len()]);
        let Some(out) = outward(a, b, centre) else {
            return;
        };
        let normal = frame.dir(out[0], out[1], 0.0);
        let corners = [
            frame.at(a[0], a[1], v[0]),
            frame.at(b[0], b[1], v[0]),
            frame.at(b[0], b[1], v[1]),
            frame.at(a[0], a[1], v[1]),
        ];
        self.polygon(&corners, normal);
    }

    /// An axis-aligned box in `frame`: `u`, `y`, `v` ranges, all six faces.
    pub fn cuboid(&mut self, frame: &Frame, u: [f64; 2], y: [f64; 2], v: [f64; 2]) {
        let profile = [[u[0], y[0]], [u[1], y[0]], [u[1], y[1]], [u[0], y[1]]];
        self.prism(frame, &profile, v, &[]);
    }

    /// A straight bar from `a` to `b` in the (u, y) plane, `thickness` across it in that
    /// plane and spanning `v` (tubes, limbs): a prism of the four-sided profile. Nothing for
    /// a bar of no length.
    pub fn bar(&mut self, frame: &Frame, a: [f64; 2], b: [f64; 2], thickness: f64, v: [f64; 2]) {
        let d = [b[0] - a[0], b[1] - a[1]];
        let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
        if len.is_nan() || len <= 1e-9 {
            return;
        }
        let n = [-d[1] / len * thickness / 2.0, d[0] / len * thickness / 2.0];
        let profile = [
            [a[0] - n[0], a[1] - n[1]],
            [b[0] - n[0], b[1] - n[1]],
            [b[0] + n[0], b[1] + n[1]],
            [a[0] + n[0], a[1] + n[1]],
        ];
        self.prism(frame, &profile, v, &[]);
    }

    pub fn is_empty(&self) -> bool {
        self.mesh.indices.is_empty()
    }

    pub fn finish(self) -> Mesh {
        self.mesh
    }
}

/// The mean of the points (inside a convex polygon).
pub fn centroid(points: &[[f64; 2]]) -> [f64; 2] {
    let n = points.len().max(1) as f64;
    let s = points
        .iter()
        .fold([0.0, 0.0], |s, p| [s[0] + p[0], s[1] + p[1]]);
    [s[0] / n, s[1] / n]
}

/// The unit normal of edge `a → b` pointing away from `centre`; None for a zero edge.
fn outward(a: [f64; 2], b: [f64; 2], centre: [f64; 2]) -> Option<[f64; 2]> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
    if len.is_nan() || len <= 1e-12 {
        return None;
    }
    let mut n = [d[1] / len, -d[0] / len];
    let mid = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
    if n[0] * (mid[0] - centre[0]) + n[1] * (mid[1] - centre[1]) < 0.0 {
        n = [-n[0], -n[1]];
    }
    Some(n)
}

/// Meshes of the non-empty solids.
pub fn finish_all(solids: Vec<Solid>) -> Vec<Mesh> {
    solids
        .into_iter()
        .filter(|s| !s.is_empty())
        .map(Solid::finish)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every triangle of `mesh` faces away from `inside`, and its stored normal agrees.
    pub fn assert_closed_outward(mesh: &Mesh, inside: [f64; 3]) {
        for t in 0..mesh.indices.len() / 3 {
            let p = |k: usize| mesh.positions[mesh.indices[3 * t + k] as usize].map(f64::from);
            let n = cross(sub(p(1), p(0)), sub(p(2), p(0)));
            assert!(dot(n, sub(p(0), inside)) > 0.0, "triangle {t}");
            let stored = mesh.normals[mesh.indices[3 * t] as usize].map(f64::from);
            assert!(dot(n, stored) > 0.0, "triangle {t}");
        }
    }

    #[test]
    fn prisms_face_out_in_any_frame() {
        let inv = std::f64::consts::FRAC_1_SQRT_2;
        for forward in [[1.0, 0.0], [0.0, -1.0], [inv, inv]] {
            let frame = Frame {
                origin: [5.0, 0.1, -2.0],
                forward,
            };
            let profile = [[0.0, 0.3], [4.0, 0.3], [4.2, 0.8], [3.0, 1.0], [0.0, 1.0]];
            let mut solid = Solid::new(0);
            solid.prism(&frame, &profile, [-0.9, 0.9], &[]);
            let mesh = solid.finish();
            // Two pentagon caps (3 triangles each) and five edge quads.
            assert_eq!(mesh.indices.len() / 3, 6 + 10);
            let c = centroid(&profile);
            assert_closed_outward(&mesh, frame.at(c[0], c[1], 0.0));
        }
    }

    #[test]
    fn skipped_faces_are_left_out() {
        let frame = Frame {
            origin: [0.0; 3],
            forward: [1.0, 0.0],
        };
        let mut solid = Solid::new(0);
        solid.cuboid(&frame, [0.0, 1.0], [0.0, 1.0], [0.0, 1.0]);
        assert_eq!(solid.finish().indices.len(), 36);
        let mut solid = Solid::new(0);
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        solid.prism(&frame, &square, [0.0, 1.0], &[2]);
        assert_eq!(solid.finish().indices.len(), 30);
    }
}
