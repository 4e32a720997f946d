//! Edge weights of the fixed-boundary parameterizations: every method of the
//! section 2.4 of the "Digital Shape Processing" thesis chapter solves the same system `sum_j w_ij (q_i - q_j) = 0`
//! (eq. 2.13) with the boundary fixed, and differs only in its weights w_ij.
//!
//! | weights | w_ij | symmetric | reference |
//! |---|---|---|---|
//! | [`Uniform`] | 1 / \|N(i)\| | after row scaling | Tutte, eq. 2.12-2.13 |
//! | [`MeanValue`] | (tan(a_ij / 2) + tan(b_ij / 2)) / \|p_i - p_j\| | no | Floater 2003 |
//! | [`Harmonic`] | cot alpha_ij + cot beta_ij | yes | eq. 2.14-2.15, Pinkall-Polthier 1993 |
//! | [`Authalic`] | (cot gamma_ij + cot delta_ij) / \|p_i - p_j\|^2 | no | eq. 2.16, Desbrun-Meyer-Alliez 2002 |
//! | [`Intrinsic`] | lambda conformal + mu authalic | if mu = 0 | Desbrun-Meyer-Alliez 2002 |
//!
//! Angles: alpha_ij, beta_ij are opposite the edge ij; a_ij, b_ij are the
//! angles at p_i of the two faces of the edge; gamma_ij, delta_ij are the
//! angles at p_j of the two faces of the edge.
//!
//! Every weight is a sum of one term per face of the edge: a [`Weights`]
//! implementation computes, for a half-edge i -> j, the terms its face adds
//! to w_ij and to w_ji from that face's [`LocalTriangle`] alone, so each face
//! is measured once. Zero-area faces would give infinite cotangents and
//! tangents: [`WeightContext`] replaces each of them by an equilateral
//! triangle of the same mean edge length (uniform weights on that face), see
//! [`crate::DegeneratePolicy`].

use glam::DVec3;
use mesh_kernel::{Connectivity, FaceId, HalfedgeId, TriMesh};

/// Relative area below which a face counts as degenerate: twice its area is
/// at most this times its longest edge squared (as in
/// `mesh_kernel::clean::is_degenerate_triangle`).
pub const DEGENERATE_TOLERANCE: f64 = 1e-12;

/// What a weight term may know about its edge besides the face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeInfo {
    /// Number of faces on the edge (1 on the boundary, 2 inside).
    pub faces: usize,
    /// Mean edge length of the mesh (a length scale).
    pub mean_edge_length: f64,
}

/// The weights of one parameterization method: w_ij of eq. 2.13 for each
/// directed edge i -> j, as a sum of one term per face of the edge. Weights
/// may be scaled by any positive factor per equation i without changing the
/// solution.
pub trait Weights {
    /// For the half-edge i -> j whose face is `t` (i at corner 0, j at
    /// corner 1, the opposite vertex at corner 2): the terms this face adds
    /// to w_ij and to w_ji. Cost O(1).
    fn face_terms(&self, t: &LocalTriangle, edge: &EdgeInfo) -> [f64; 2];

    /// `true` when w_ij = w_ji for every edge, so that the fixed-boundary
    /// system is symmetric and a Cholesky factorization applies.
    fn is_symmetric(&self) -> bool;
}

/// A face seen from one of its half-edges h = (i -> j), with k the opposite
/// corner: side lengths, corner dot products and twice the area, from which
/// cotangents and half-angle tangents follow without trigonometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalTriangle {
    /// Lengths |p_i p_j|, |p_j p_k|, |p_k p_i|.
    pub len: [f64; 3],
    /// At each corner (i, j, k), the dot product of its two edge vectors.
    pub dot: [f64; 3],
    /// Twice the area (|cross product|), positive.
    pub double_area: f64,
}

impl LocalTriangle {
    /// From three corner positions (i, j, k).
    pub fn new(pi: DVec3, pj: DVec3, pk: DVec3) -> Self {
        let (eij, ejk, eki) = (pj - pi, pk - pj, pi - pk);
        Self {
            len: [eij.length(), ejk.length(), eki.length()],
            dot: [-eki.dot(eij), -eij.dot(ejk), -ejk.dot(eki)],
            double_area: mesh_kernel::geometry::norm(eij.cross(-eki)),
        }
    }

    /// The same triangle seen from its next half-edge (j -> k, opposite i).
    #[inline]
    pub fn rotated(&self) -> Self {
        let [l0, l1, l2] = self.len;
        let [d0, d1, d2] = self.dot;
        Self { len: [l1, l2, l0], dot: [d1, d2, d0], double_area: self.double_area }
    }

    /// The equilateral triangle of side `s`: the stand-in for a zero-area face.
    pub fn equilateral(s: f64) -> Self {
        let s2 = s * s;
        Self { len: [s; 3], dot: [0.5 * s2; 3], double_area: 0.75f64.sqrt() * s2 }
    }

    /// Cotangent of the angle at corner `c` (0 = i, 1 = j, 2 = k).
    #[inline]
    pub fn cot(&self, c: usize) -> f64 {
        self.dot[c] / self.double_area
    }

    /// tan(theta / 2) of the angle theta at corner `c`, as
    /// sin / (1 + cos) = 2A / (|a| |b| + a.b).
    #[inline]
    pub fn tan_half(&self, c: usize) -> f64 {
        let (a, b) = (self.len[(c + 2) % 3], self.len[c]);
        self.double_area / (a * b + self.dot[c])
    }

    /// Length of the edge i j.
    #[inline]
    pub fn edge_length(&self) -> f64 {
        self.len[0]
    }
}

/// Geometry shared by all weights: the mesh, its connectivity, which faces
/// are degenerate and the lengths used in their place. Built once in O(V + F).
#[derive(Debug, Clone)]
pub struct WeightContext<'a> {
    mesh: &'a TriMesh,
    conn: &'a Connectivity,
    degenerate: Vec<FaceId>,
    is_degenerate: Vec<bool>,
    mean_edge_length: f64,
}

impl<'a> WeightContext<'a> {
    /// Classifies the faces of `mesh` (degenerate when twice the area is at
    /// most [`DEGENERATE_TOLERANCE`] times the longest edge squared).
    pub fn new(mesh: &'a TriMesh) -> Self {
        let conn = mesh.connectivity();
        let is_degenerate: Vec<bool> = mesh
            .face_ids()
            .map(|f| mesh_kernel::clean::is_degenerate_triangle(mesh.triangle(f), DEGENERATE_TOLERANCE))
            .collect();
        let degenerate = (0..is_degenerate.len()).filter(|&f| is_degenerate[f]).map(FaceId::new).collect();
        let mean_edge_length = mesh_kernel::geometry::mean_edge_length(mesh);
        Self { mesh, conn, degenerate, is_degenerate, mean_edge_length }
    }

    /// The mesh.
    pub fn mesh(&self) -> &'a TriMesh {
        self.mesh
    }

    /// Its connectivity.
    pub fn connectivity(&self) -> &'a Connectivity {
        self.conn
    }

    /// Faces of (numerically) zero area, whose weights are uniform.
    pub fn degenerate_faces(&self) -> &[FaceId] {
        &self.degenerate
    }

    /// Mean edge length of the mesh.
    pub fn mean_edge_length(&self) -> f64 {
        self.mean_edge_length
    }

    /// The face of `h` seen from `h` (i = origin, j = destination, k =
    /// opposite); a degenerate face is replaced by the equilateral triangle
    /// whose side is its mean edge length (the mesh's mean edge length if
    /// that is zero, 1 if that is zero too).
    pub fn triangle(&self, h: HalfedgeId) -> LocalTriangle {
        let p = self.mesh.positions();
        let (pi, pj, pk) =
            (p[self.conn.origin(h).idx()], p[self.conn.dest(h).idx()], p[self.conn.opposite_vertex(h).idx()]);
        if !self.is_degenerate[h.face().idx()] {
            return LocalTriangle::new(pi, pj, pk);
        }
        let s = (pi.distance(pj) + pj.distance(pk) + pk.distance(pi)) / 3.0;
        let side = if s > 0.0 {
            s
        } else if self.mean_edge_length > 0.0 {
            self.mean_edge_length
        } else {
            1.0 // every vertex at one point: any common scale will do
        };
        LocalTriangle::equilateral(side)
    }

    /// The face `f` seen from its first half-edge (corner 0 -> corner 1),
    /// or its equilateral stand-in.
    #[inline]
    pub fn face_triangle(&self, f: FaceId) -> LocalTriangle {
        self.triangle(HalfedgeId::of_corner(f, 0))
    }
}

/// Tutte's barycentric weights w_ij = 1 / |N(i)| (eq. 2.12-2.13). Each
/// equation i is multiplied by |N(i)|, which leaves the solution unchanged and
/// turns the system into the symmetric graph Laplacian (w_ij = 1).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Uniform;

impl Weights for Uniform {
    fn face_terms(&self, _: &LocalTriangle, edge: &EdgeInfo) -> [f64; 2] {
        // w_ij = 1 per edge, shared among its faces.
        [1.0 / edge.faces as f64; 2]
    }
    fn is_symmetric(&self) -> bool {
        true
    }
}

/// Floater's mean-value weights (Floater 2003): w_ij = (tan(a/2) + tan(b/2))
/// / |p_i - p_j| with a, b the angles at p_i of the faces of edge ij. Always
/// positive, so a convex boundary gives a bijective map (Floater's theorem);
/// reproduces planar meshes (linear precision).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct MeanValue;

impl Weights for MeanValue {
    fn face_terms(&self, t: &LocalTriangle, _: &EdgeInfo) -> [f64; 2] {
        // w_ij takes the angle at p_i (corner 0), w_ji the angle at p_j (corner 1).
        let l = t.edge_length();
        [t.tan_half(0) / l, t.tan_half(1) / l]
    }
    fn is_symmetric(&self) -> bool {
        false
    }
}

/// Discrete harmonic (conformal) weights w_ij = cot alpha_ij + cot beta_ij
/// (eq. 2.14-2.15), the angles opposite the edge: minimizes the Dirichlet
/// energy; negative on edges opposite obtuse angles (then flips are
/// possible); symmetric. A planar mesh with its own boundary is reproduced.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Harmonic;

impl Weights for Harmonic {
    fn face_terms(&self, t: &LocalTriangle, _: &EdgeInfo) -> [f64; 2] {
        [t.cot(2); 2]
    }
    fn is_symmetric(&self) -> bool {
        true
    }
}

/// Discrete authalic weights (eq. 2.16; Desbrun, Meyer and Alliez 2002):
/// w_ij = (cot gamma_ij + cot delta_ij) / |p_i - p_j|^2 with gamma, delta the
/// angles at p_j of the faces of edge ij. Minimizes the discrete authalic
/// (area) energy; asymmetric; reproduces planar meshes.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Authalic;

impl Weights for Authalic {
    fn face_terms(&self, t: &LocalTriangle, _: &EdgeInfo) -> [f64; 2] {
        // w_ij takes the angle at p_j (corner 1), w_ji the angle at p_i (corner 0).
        let l2 = t.edge_length() * t.edge_length();
        [t.cot(1) / l2, t.cot(0) / l2]
    }
    fn is_symmetric(&self) -> bool {
        false
    }
}

/// Intrinsic parameterization weights (Desbrun, Meyer and Alliez 2002):
/// `lambda * conformal + mu * authalic`, the authalic part multiplied by the
/// mesh's mean squared edge length so that the mix does not depend on the
/// mesh's scale. mu = 0 gives exactly [`Harmonic`], lambda = 0 exactly
/// [`Authalic`] (up to a constant factor, which does not change the map).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Intrinsic {
    /// Weight of the conformal (Dirichlet) energy.
    pub lambda: f64,
    /// Weight of the authalic energy.
    pub mu: f64,
}

impl Default for Intrinsic {
    fn default() -> Self {
        Self { lambda: 0.5, mu: 0.5 }
    }
}

impl Weights for Intrinsic {
    fn face_terms(&self, t: &LocalTriangle, edge: &EdgeInfo) -> [f64; 2] {
        let mut w = [0.0; 2];
        if self.lambda != 0.0 {
            w = Harmonic.face_terms(t, edge).map(|x| self.lambda * x);
        }
        if self.mu != 0.0 {
            let scale = self.mu * edge.mean_edge_length * edge.mean_edge_length;
            let a = Authalic.face_terms(t, edge);
            w = [w[0] + scale * a[0], w[1] + scale * a[1]];
        }
        w
    }
    fn is_symmetric(&self) -> bool {
        self.mu == 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn local_triangle_matches_trigonometry() {
        let t = LocalTriangle::new(DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.5, 1.5, 0.3));
        let (pi, pj, pk) = (DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.5, 1.5, 0.3));
        let angles = mesh_kernel::geometry::triangle_angles([pi, pj, pk]);
        for c in 0..3 {
            assert!((t.cot(c) - 1.0 / angles[c].tan()).abs() < 1e-14);
            assert!((t.tan_half(c) - (angles[c] / 2.0).tan()).abs() < 1e-14);
        }
        assert!((t.edge_length() - 2.0).abs() < 1e-15);
        let r = t.rotated();
        assert!((r.cot(2) - t.cot(0)).abs() < 1e-15 && (r.edge_length() - t.len[1]).abs() < 1e-15);
        let e = LocalTriangle::equilateral(3.0);
        for c in 0..3 {
            assert!((e.cot(c) - 1.0 / (PI / 3.0).tan()).abs() < 1e-15);
            assert!((e.tan_half(c) - (PI / 6.0).tan()).abs() < 1e-15);
        }
    }

    #[test]
    fn degenerate_faces_get_finite_weights() {
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0), DVec3::new(1.0, 1.0, 0.0)];
        let m = TriMesh::new(p, vec![[0, 1, 2], [0, 2, 3]]).unwrap();
        let ctx = WeightContext::new(&m);
        assert_eq!(ctx.degenerate_faces(), &[FaceId(0)]);
        for h in 0..6 {
            let t = ctx.triangle(HalfedgeId(h));
            for c in 0..3 {
                assert!(t.cot(c).is_finite() && t.tan_half(c).is_finite());
            }
        }
    }
}
