//! Intrinsic Delaunay triangulation by edge flips on edge lengths
//! (Bobenko and Springborn 2007; Fisher, Springborn, Bobenko and Schroeder
//! 2007), with intrinsic mollification (Sharp and Crane 2020) so that
//! zero-area triangles get well-defined, finite cotangents.
//!
//! The chapter (section 2.2.2) warns that obtuse triangles make cotangent weights
//! negative and linear systems unstable; the cotangent Laplacian of the
//! intrinsic Delaunay triangulation has only non-negative weights, satisfies
//! a maximum principle, and equals the ordinary one on a mesh that is
//! already Delaunay. The vertex set and the surface metric are unchanged:
//! only which pairs of vertices are joined by (geodesic) edges changes.

use sprs::CsMat;

use super::pattern::EdgePattern;

use crate::error::{MeshError, Result};
use crate::ids::{HalfedgeId, VertexId};
use crate::mesh::TriMesh;

/// Options of [`IntrinsicTriangulation::delaunay`].
#[derive(Debug, Clone, PartialEq)]
pub struct IntrinsicOptions {
    /// Mollification: every triangle's lengths must satisfy the triangle
    /// inequality with a margin of at least `mollify * mean edge length`;
    /// all lengths are lengthened by the smallest epsilon that achieves it
    /// (Sharp and Crane 2020). 0 disables it.
    pub mollify: f64,
    /// An edge is flipped when its cotangent weight is below `-tolerance`.
    pub tolerance: f64,
    /// Safety limit on flips, as a multiple of the edge count.
    pub max_flips_per_edge: usize,
}

impl Default for IntrinsicOptions {
    fn default() -> Self {
        Self { mollify: 1e-6, tolerance: 1e-12, max_flips_per_edge: 100 }
    }
}

/// A triangulation of the mesh's vertices by intrinsic edges: faces (which may
/// differ from the mesh's after flips) with the length of every half-edge.
/// Edges without a twin (boundary, non-manifold, inconsistently oriented) are
/// never flipped. Lengths are kept in the mesh's
/// [`crate::units::length_unit`] (a power of two, so no digit changes), so
/// that flips and cotangents neither over- nor underflow whatever the unit.
#[derive(Debug, Clone)]
pub struct IntrinsicTriangulation {
    vertex_count: usize,
    faces: Vec<[u32; 3]>,
    /// Half-edge lengths divided by `unit`.
    lengths: Vec<f64>,
    unit: f64,
    twin: Vec<HalfedgeId>,
    flips: usize,
}

impl IntrinsicTriangulation {
    /// The mesh itself as an intrinsic triangulation (lengths from positions),
    /// mollified by `mollify` (see [`IntrinsicOptions::mollify`]).
    ///
    /// # Errors
    /// [`MeshError::InvalidOption`] for a mollification that is negative or not finite.
    pub fn from_mesh(mesh: &TriMesh, mollify: f64) -> Result<Self> {
        if !(mollify >= 0.0 && mollify.is_finite()) {
            return Err(MeshError::InvalidOption { name: "mollify", reason: format!("{mollify} is not >= 0") });
        }
        let conn = mesh.connectivity();
        let unit = crate::units::length_unit(mesh);
        let p = mesh.positions();
        let mut lengths: Vec<f64> = (0..conn.halfedge_count())
            .map(|h| {
                let h = HalfedgeId(h as u32);
                crate::geometry::norm((p[conn.dest(h).idx()] - p[conn.origin(h).idx()]) / unit)
            })
            .collect();
        let twin = (0..conn.halfedge_count())
            .map(|h| conn.twin(HalfedgeId(h as u32)).unwrap_or(HalfedgeId::INVALID))
            .collect();
        if mollify > 0.0 && !lengths.is_empty() {
            let mean = lengths.iter().sum::<f64>() / lengths.len() as f64;
            let delta = mollify * mean;
            // Smallest eps with l_i + l_j - l_k + eps >= delta in every face.
            let eps = lengths
                .chunks_exact(3)
                .map(|l| {
                    let slack = (l[0] + l[1] - l[2]).min(l[1] + l[2] - l[0]).min(l[2] + l[0] - l[1]);
                    delta - slack
                })
                .fold(0.0f64, f64::max);
            if eps > 0.0 {
                lengths.iter_mut().for_each(|l| *l += eps);
            }
        }
        Ok(Self { vertex_count: mesh.vertex_count(), faces: mesh.faces().to_vec(), lengths, unit, twin, flips: 0 })
    }

    /// The intrinsic Delaunay triangulation of the mesh: mollify, then flip
    /// every interior edge whose cotangent weight is negative until none is
    /// (each flip strictly improves the triangulation, so this terminates;
    /// typically O(E) flips). Works on any input; edges without twins stay.
    ///
    /// # Errors
    /// [`MeshError::InvalidOption`] for a negative or non-finite tolerance or mollification.
    pub fn delaunay(mesh: &TriMesh, options: &IntrinsicOptions) -> Result<Self> {
        if !(options.tolerance >= 0.0 && options.tolerance.is_finite()) {
            return Err(MeshError::InvalidOption { name: "tolerance", reason: format!("{}", options.tolerance) });
        }
        let mut t = Self::from_mesh(mesh, options.mollify)?;
        t.flip_to_delaunay(options.tolerance, options.max_flips_per_edge.saturating_mul(t.faces.len() * 3 / 2 + 1));
        Ok(t)
    }

    /// Faces of the triangulation (vertex indices of the mesh).
    pub fn faces(&self) -> &[[u32; 3]] {
        &self.faces
    }

    /// Length of half-edge `3 f + k`, from corner k to k + 1 of face f.
    /// O(F) (a copy in the mesh's unit).
    pub fn lengths(&self) -> Vec<f64> {
        self.lengths.iter().map(|l| l * self.unit).collect()
    }

    /// Number of edge flips performed.
    pub fn flip_count(&self) -> usize {
        self.flips
    }

    /// Cotangent of the angle opposite half-edge `h` in its face, from the
    /// three lengths (law of cosines over twice Heron's area). Zero for a
    /// face of zero area (possible only without mollification).
    pub fn opposite_cotan(&self, h: HalfedgeId) -> f64 {
        cotan_from_lengths(self.lengths[h.idx()], self.lengths[h.next().idx()], self.lengths[h.prev().idx()])
    }

    /// Cotangent weight of the edge of `h`: half the sum of the opposite
    /// cotangents of `h` and its twin.
    fn edge_cotan_weight(&self, h: HalfedgeId) -> f64 {
        let t = self.twin[h.idx()];
        let mut w = 0.5 * self.opposite_cotan(h);
        if t.is_valid() {
            w += 0.5 * self.opposite_cotan(t);
        }
        w
    }

    /// Flips non-Delaunay edges until none is left or `max_flips` is reached.
    /// Returns `true` when the triangulation is Delaunay.
    pub fn flip_to_delaunay(&mut self, tolerance: f64, max_flips: usize) -> bool {
        let nh = self.lengths.len();
        let mut queued = vec![false; nh];
        let mut stack: Vec<HalfedgeId> = Vec::new();
        for h in 0..nh {
            let t = self.twin[h];
            if t.is_valid() && (h as u32) < t.0 {
                stack.push(HalfedgeId(h as u32));
                queued[h] = true;
            }
        }
        while let Some(h) = stack.pop() {
            queued[h.idx()] = false;
            let t = self.twin[h.idx()];
            if !t.is_valid() || t.face() == h.face() || self.edge_cotan_weight(h) >= -tolerance {
                // The same test as `is_delaunay_edge` on this edge's five lengths.
                continue;
            }
            if self.flips >= max_flips {
                return false;
            }
            self.flip(h);
            for g in [h.next(), h.prev(), t.next(), t.prev()] {
                let tg = self.twin[g.idx()];
                let key = if tg.is_valid() && tg.0 < g.0 { tg } else { g };
                if tg.is_valid() && !queued[key.idx()] {
                    queued[key.idx()] = true;
                    stack.push(key);
                }
            }
        }
        true
    }

    /// Flips the edge of `h0` (faces a b c and b a d become d c a and c d b),
    /// keeping the diagonal in the same half-edge slots.
    fn flip(&mut self, h0: HalfedgeId) {
        let h1 = self.twin[h0.idx()];
        let (f0, f1) = (h0.face().idx(), h1.face().idx());
        let (k0, k1) = (h0.corner(), h1.corner());
        let a = self.faces[f0][k0];
        let b = self.faces[f0][(k0 + 1) % 3];
        let c = self.faces[f0][(k0 + 2) % 3];
        let d = self.faces[f1][(k1 + 2) % 3];
        let l = |h: HalfedgeId| self.lengths[h.idx()];
        let (l_ab, l_bc, l_ca, l_ad, l_db) = (l(h0), l(h0.next()), l(h0.prev()), l(h1.next()), l(h1.prev()));
        let l_cd = flipped_length(l_ab, l_bc, l_ca, l_ad, l_db);

        // Old outer half-edges and where they go: f0 becomes (d, c, a), whose
        // slots k0+1, k0+2 hold c->a (old h0.prev) and a->d (old h1.next);
        // f1 becomes (c, d, b), whose slots k1+1, k1+2 hold d->b (old h1.prev)
        // and b->c (old h0.next).
        let moves = [(h0.prev(), h0.next()), (h1.next(), h0.prev()), (h1.prev(), h1.next()), (h0.next(), h1.prev())];
        let new_slot = |old: HalfedgeId| moves.iter().find(|(o, _)| *o == old).map(|(_, n)| *n);
        let outer_twins = moves.map(|(old, _)| self.twin[old.idx()]);
        let outer_lengths = [l_ca, l_ad, l_db, l_bc];

        self.faces[f0] = rotate([d, c, a], k0);
        self.faces[f1] = rotate([c, d, b], k1);
        self.lengths[h0.idx()] = l_cd;
        self.lengths[h1.idx()] = l_cd;
        for (i, (_, slot)) in moves.iter().enumerate() {
            self.lengths[slot.idx()] = outer_lengths[i];
            let t = outer_twins[i];
            let t = if t.is_valid() { new_slot(t).unwrap_or(t) } else { t };
            self.twin[slot.idx()] = t;
            if t.is_valid() {
                self.twin[t.idx()] = *slot;
            }
        }
        self.flips += 1;
    }

    /// Cotangent Laplacian of the intrinsic triangulation (same convention as
    /// [`super::cotan_laplacian`]): symmetric, zero row sums, and, once
    /// Delaunay, non-negative weights on all interior edges. Parallel
    /// intrinsic edges between the same two vertices add up; loops are
    /// skipped. O(F log F) for sorting the edges.
    pub fn cotan_laplacian(&self) -> CsMat<f64> {
        let mut edges: Vec<([VertexId; 2], f64)> = Vec::with_capacity(self.lengths.len() / 2 + 1);
        for h in 0..self.lengths.len() {
            let t = self.twin[h];
            if t.is_valid() && t.0 < h as u32 {
                continue;
            }
            let h = HalfedgeId(h as u32);
            let face = self.faces[h.face().idx()];
            let (i, j) = (face[h.corner()], face[(h.corner() + 1) % 3]);
            if i != j {
                edges.push(([VertexId(i.min(j)), VertexId(i.max(j))], self.edge_cotan_weight(h)));
            }
        }
        edges.sort_unstable_by_key(|(e, _)| *e);
        let mut pairs: Vec<[VertexId; 2]> = Vec::with_capacity(edges.len());
        let mut weights: Vec<f64> = Vec::with_capacity(edges.len());
        for (e, w) in edges {
            match (pairs.last(), weights.last_mut()) {
                (Some(last), Some(sum)) if *last == e => *sum += w,
                _ => {
                    pairs.push(e);
                    weights.push(w);
                }
            }
        }
        EdgePattern::new(self.vertex_count, &pairs).laplacian(&weights)
    }

    /// Cotangent weights of the interior (flippable) edges, each listed once.
    /// All are >= -tolerance after [`Self::flip_to_delaunay`]. Boundary edges
    /// are not flippable: one opposite an obtuse angle keeps a negative
    /// weight (removing it would need vertex insertion).
    pub fn interior_edge_weights(&self) -> Vec<f64> {
        (0..self.lengths.len())
            .filter(|&h| {
                let t = self.twin[h];
                t.is_valid() && (h as u32) < t.0
            })
            .map(|h| self.edge_cotan_weight(HalfedgeId(h as u32)))
            .collect()
    }

    /// Per-vertex barycentric areas (a third of each face's intrinsic area),
    /// a lumped mass matrix for the intrinsic Laplacian. Sums to the
    /// (mollified) surface area.
    pub fn barycentric_mass(&self) -> Vec<f64> {
        let mut m = vec![0.0; self.vertex_count];
        for (f, tri) in self.faces.iter().enumerate() {
            let l = &self.lengths[3 * f..3 * f + 3];
            let a = heron_area(l[0], l[1], l[2]) / 3.0 * self.unit * self.unit;
            for &v in tri {
                m[v as usize] += a;
            }
        }
        m
    }
}

/// `[x, y, z]` rotated so that `x` lands at position `k`.
fn rotate(v: [u32; 3], k: usize) -> [u32; 3] {
    let mut out = [0; 3];
    for i in 0..3 {
        out[(k + i) % 3] = v[i];
    }
    out
}

/// Cotangent of the angle opposite the side of length `a` in a triangle of
/// sides `a`, `b`, `c` (law of cosines over twice Heron's area), computed in
/// the triangle's own power-of-two unit so that no product of lengths over-
/// or underflows. Zero for a triangle of zero area or non-finite lengths.
pub fn cotan_from_lengths(a: f64, b: f64, c: f64) -> f64 {
    let longest = a.max(b).max(c);
    if !(longest > 0.0 && longest.is_finite()) {
        return 0.0;
    }
    let unit = crate::geometry::power_of_two_near(longest);
    let (a, b, c) = (a / unit, b / unit, c / unit);
    let area4 = 4.0 * heron_area(a, b, c);
    if area4 > 0.0 {
        (b * b + c * c - a * a) / area4
    } else {
        0.0
    }
}

/// The Delaunay test of an interior edge a b between triangles (a, b, c) and
/// (b, a, d), on lengths only: the edge is locally Delaunay when the sum of
/// the cotangents of the two angles opposite it (at c and at d) is at least
/// `-2 * tolerance`, i.e. its cotangent weight is at least `-tolerance`; in
/// the plane, when d is not strictly inside the circumcircle of a b c.
/// [`IntrinsicTriangulation::flip_to_delaunay`] flips exactly the edges that
/// fail this test; the planar Lawson flips of the workspace use it too.
pub fn is_delaunay_edge(l_ab: f64, l_bc: f64, l_ca: f64, l_ad: f64, l_db: f64, tolerance: f64) -> bool {
    0.5 * cotan_from_lengths(l_ab, l_bc, l_ca) + 0.5 * cotan_from_lengths(l_ab, l_ad, l_db) >= -tolerance
}

/// Triangle area from its side lengths, Kahan's numerically stable Heron
/// formula; 0 when the lengths violate the triangle inequality.
pub fn heron_area(a: f64, b: f64, c: f64) -> f64 {
    let mut s = [a, b, c];
    s.sort_unstable_by(|x, y| y.total_cmp(x));
    if !(s[0] > 0.0 && s[0].is_finite()) {
        return 0.0;
    }
    // On the lengths divided by a power of two near the longest (exact), so
    // that the product of four lengths neither over- nor underflows.
    let unit = crate::geometry::power_of_two_near(s[0]);
    let [a, b, c] = s.map(|x| x / unit);
    let p = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
    if p > 0.0 {
        0.25 * p.sqrt() * unit * unit
    } else {
        0.0
    }
}

/// Length of the other diagonal of the quad made of triangles (a, b, c) and
/// (b, a, d) laid out flat on both sides of a b.
fn flipped_length(l_ab: f64, l_bc: f64, l_ca: f64, l_ad: f64, l_db: f64) -> f64 {
    if l_ab <= 0.0 {
        return l_ca + l_ad;
    }
    let c = crate::geometry::planar_apex(l_ab, l_ca, l_bc);
    let d = crate::geometry::planar_apex(l_ab, l_ad, l_db);
    // c above the shared edge, d mirrored below it.
    ((c.x - d.x).powi(2) + (c.y + d.y).powi(2)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::operators::cotan_laplacian;
    use crate::shapes;
    use glam::DVec3;

    #[test]
    fn delaunay_mesh_is_unchanged() {
        // An icosphere is Delaunay: no flips, same Laplacian.
        let m = shapes::icosphere(2).unwrap();
        let opts = IntrinsicOptions { mollify: 0.0, ..Default::default() };
        let t = IntrinsicTriangulation::delaunay(&m, &opts).unwrap();
        assert_eq!(t.flip_count(), 0);
        let diff = &t.cotan_laplacian() - &cotan_laplacian(&m);
        assert!(diff.data().iter().all(|v| v.abs() < 1e-12));
    }

    #[test]
    fn flips_make_weights_nonnegative() {
        // A grid squashed in y has long diagonals opposite obtuse angles.
        let mut m = shapes::disk(8, 5).unwrap();
        for p in m.positions_mut() {
            p.y *= 0.15;
            p.z = 0.05 * (3.0 * p.x).sin();
        }
        let before = crate::operators::cotan_weights(&m);
        assert!(before.iter().any(|w| *w < 0.0));
        let t = IntrinsicTriangulation::delaunay(&m, &IntrinsicOptions::default()).unwrap();
        assert!(t.flip_count() > 0);
        assert!(t.interior_edge_weights().iter().all(|w| *w >= -1e-12));
        let l = t.cotan_laplacian();
        for row in l.outer_iterator() {
            assert!(row.iter().map(|(_, v)| v).sum::<f64>().abs() < 1e-9);
        }
        let area: f64 = t.barycentric_mass().iter().sum();
        let true_area = crate::geometry::surface_area(&m);
        assert!((area - true_area).abs() < 1e-4 * true_area, "{area} vs {true_area}");
    }

    #[test]
    fn zero_area_triangles_stay_finite() {
        // A fan with collinear corners, like cgal_degtri_sliding.off.
        let p = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
        ];
        let m = TriMesh::new(p, vec![[0, 1, 3], [1, 2, 3], [0, 2, 1], [0, 4, 2]]).unwrap();
        let t = IntrinsicTriangulation::delaunay(&m, &IntrinsicOptions::default()).unwrap();
        let l = t.cotan_laplacian();
        assert!(l.data().iter().all(|v| v.is_finite()));
        assert!(t.interior_edge_weights().iter().all(|w| *w >= -1e-9));
    }

    #[test]
    fn delaunay_edge_test_is_the_empty_circle_test() {
        // a = (0, 0), b = (1, 0), c = (1, 1): the circumcircle has centre
        // (0.5, 0.5); d below a b outside, inside and on it.
        let len = |p: (f64, f64), q: (f64, f64)| ((p.0 - q.0).powi(2) + (p.1 - q.1).powi(2)).sqrt();
        let (a, b, c) = ((0.0, 0.0), (1.0, 0.0), (1.0, 1.0));
        let test = |d: (f64, f64)| is_delaunay_edge(len(a, b), len(b, c), len(c, a), len(a, d), len(d, b), 1e-12);
        assert!(test((0.5, -0.5)), "outside the circle");
        assert!(!test((0.5, -0.1)), "inside the circle of radius 0.707 centred (0.5, 0.5)");
        assert!(test((0.5, 0.5 - 0.5 * 2f64.sqrt())), "co-circular is Delaunay");
        assert!((cotan_from_lengths(1.0, 1.0, 2f64.sqrt()) - 1.0).abs() < 1e-15, "45 degrees");
        assert_eq!(cotan_from_lengths(1.0, 0.5, 0.5), 0.0, "zero area");
    }

    #[test]
    fn heron_is_stable() {
        assert_eq!(heron_area(1.0, 1.0, 2.0), 0.0);
        assert_eq!(heron_area(1.0, 1.0, 3.0), 0.0);
        assert!((heron_area(3.0, 4.0, 5.0) - 6.0).abs() < 1e-15);
    }
}
