//! Mass matrices: the area associated with each vertex (lumped) or the full
//! Galerkin matrix of piecewise-linear hat functions.

use sprs::CsMat;

use super::corner_batch::{corner_masses_batch, CornerBatch, CORNER_BATCH};
use super::pattern::EdgePattern;
use crate::error::MeshError;
use crate::geometry::TriangleParts;
use crate::mesh::TriMesh;

/// Which mass matrix.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum MassKind {
    /// One third of each incident face's area (lumped).
    Barycentric,
    /// Mixed Voronoi areas of Meyer, Desbrun, Schroeder and Barr 2003: the
    /// Voronoi area inside non-obtuse triangles, and half / a quarter of the
    /// area of obtuse ones at the obtuse / other corners (lumped; libigl's
    /// `MASSMATRIX_TYPE_VORONOI`). Sums to the total area.
    #[default]
    MixedVoronoi,
    /// Full Galerkin mass M_ij = integral of phi_i phi_j: area/6 on the
    /// diagonal and area/12 off it, per face.
    Galerkin,
}

crate::named_choice!(MassKind, "mass", MeshError);

impl MassKind {
    /// Every choice, in the order of the names `barycentric`, `voronoi`, `galerkin`.
    pub const ALL: [Self; 3] = [Self::Barycentric, Self::MixedVoronoi, Self::Galerkin];

    /// The name parsed and displayed.
    pub fn name(self) -> &'static str {
        match self {
            Self::Barycentric => "barycentric",
            Self::MixedVoronoi => "voronoi",
            Self::Galerkin => "galerkin",
        }
    }
}

/// Per-vertex lumped areas. For [`MassKind::Galerkin`] this is the row sum of
/// the Galerkin matrix, which equals the barycentric area. Isolated vertices
/// get zero. O(F), eight faces at a time (the corner areas of the Gaussian
/// curvature's batches, without the angles), on several threads
/// ([`crate::par::scatter_batched`]), with a result that does not depend
/// on their count: bit for bit the face-by-face sums. One face at a time,
/// the mixed Voronoi mass took 2.45-2.49 ms on a 40,962-vertex icosphere
/// and 32.4-32.5 ms at 470,274 vertices in file order, against 1.18-1.21
/// and 17.3-17.4 in batches (one core, alternated, 2026-12-06).
pub fn lumped_mass(mesh: &TriMesh, kind: MassKind) -> Vec<f64> {
    crate::par::scatter_batched(
        mesh.vertex_count(),
        mesh.faces(),
        mesh.positions(),
        0.0,
        |first| {
            let mut corners: CornerBatch = [[(0.0, 0.0); 3]; CORNER_BATCH];
            corner_masses_batch(mesh, first, kind, &mut corners);
            corners
        },
        #[inline(always)]
        |m, (_, share): (f64, f64)| *m += share,
    )
}

/// What one triangle adds to the lumped mass of each of its corners: a third
/// of its area (barycentric and Galerkin rows) or its mixed Voronoi shares
/// (Meyer, Desbrun, Schroeder and Barr 2003; [`mixed_voronoi_corners`]).
#[inline]
pub fn corner_masses(tri: [glam::DVec3; 3], kind: MassKind) -> [f64; 3] {
    TriangleParts::new(tri).masses(kind)
}

/// The corner angles of a triangle ([`crate::geometry::triangle_angles`])
/// and its corner masses ([`corner_masses`]), from one set of edges: what
/// the angle defect needs at each vertex.
#[inline]
pub fn corner_angles_and_masses(tri: [glam::DVec3; 3], kind: MassKind) -> ([f64; 3], [f64; 3]) {
    let parts = TriangleParts::new(tri);
    (parts.angles(), parts.masses(kind))
}

/// The part of a triangle's area given to each corner by the mixed Voronoi
/// rule (Meyer, Desbrun, Schroeder and Barr 2003, figure 4): the Voronoi
/// region when no angle is obtuse, otherwise half of the area at the obtuse
/// corner and a quarter at the others. Shares sum to the triangle's area;
/// zero-area triangles give zeros. Per-corner weights of curvature estimators
/// (Rusinkiewicz 2004) use it directly.
pub fn mixed_voronoi_corners(tri: [glam::DVec3; 3]) -> [f64; 3] {
    TriangleParts::new(tri).masses(MassKind::MixedVoronoi)
}

impl TriangleParts {
    /// [`corner_masses`]: computed in the triangle's own unit, times the
    /// unit squared.
    #[inline]
    fn masses(&self, kind: MassKind) -> [f64; 3] {
        let square = self.unit * self.unit;
        let area = 0.5 * self.double_area;
        if matches!(kind, MassKind::Barycentric | MassKind::Galerkin) {
            return [area * self.unit * self.unit / 3.0; 3];
        }
        if area <= 0.0 || !area.is_finite() {
            return [0.0; 3];
        }
        let [da, db, dc] = [0, 1, 2].map(|k| self.corner_dot(k));
        // A corner is obtuse when the dot product of its two edges is negative.
        let shares = if da < 0.0 {
            [area / 2.0, area / 4.0, area / 4.0]
        } else if db < 0.0 {
            [area / 4.0, area / 2.0, area / 4.0]
        } else if dc < 0.0 {
            [area / 4.0, area / 4.0, area / 2.0]
        } else {
            // cot at a corner = dot / (2 area); the Voronoi area at a is
            // (|ab|^2 cot C + |ac|^2 cot B) / 8.
            let inv = 1.0 / (2.0 * area);
            let (cot_a, cot_b, cot_c) = (da * inv, db * inv, dc * inv);
            let [l_ab, l_bc, l_ca] = self.len2;
            [
                (l_ab * cot_c + l_ca * cot_b) / 8.0,
                (l_bc * cot_a + l_ab * cot_c) / 8.0,
                (l_ca * cot_b + l_bc * cot_a) / 8.0,
            ]
        };
        // (0 times an overflowed square is 0, not NaN.)
        shares.map(|x| if x == 0.0 { 0.0 } else { x * square })
    }
}

/// The mass matrix of the given kind as a sparse matrix (diagonal for the
/// lumped kinds, edge pattern for Galerkin). O(V + F).
pub fn mass_matrix(mesh: &TriMesh, kind: MassKind) -> CsMat<f64> {
    match kind {
        MassKind::Galerkin => {
            let conn = mesh.connectivity();
            let areas = crate::geometry::face_areas(mesh);
            let mut w = vec![0.0; conn.edge_count()];
            for h in 0..conn.halfedge_count() {
                let h = crate::HalfedgeId(h as u32);
                w[conn.edge(h).idx()] += areas[h.face().idx()] / 12.0;
            }
            // Diagonal: area/6 per face, which is the off-diagonal row sum
            // (two edges of area/12 per face at each corner).
            EdgePattern::new(mesh.vertex_count(), conn.edges()).symmetric(&w, |_, row_sum| row_sum)
        }
        _ => diagonal(lumped_mass(mesh, kind)),
    }
}

/// A diagonal sparse matrix.
pub fn diagonal(values: Vec<f64>) -> CsMat<f64> {
    let n = values.len();
    CsMat::new((n, n), (0..=n).collect(), (0..n).collect(), values)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::triangle_area;
    use crate::shapes;

    #[test]
    fn masses_sum_to_area() {
        for m in [shapes::disk(5, 4).unwrap(), shapes::torus(2.0, 0.5, 24, 8).unwrap(), shapes::cube(3).unwrap()] {
            let area = crate::geometry::surface_area(&m);
            for kind in [MassKind::Barycentric, MassKind::MixedVoronoi, MassKind::Galerkin] {
                let total: f64 = mass_matrix(&m, kind).data().iter().sum();
                assert!((total - area).abs() < 1e-10 * area, "{kind:?}: {total} vs {area}");
                let lumped: f64 = lumped_mass(&m, kind).iter().sum();
                assert!((lumped - area).abs() < 1e-10 * area);
            }
        }
    }

    /// The lumped masses, eight faces at a time and on several threads, are
    /// the face-by-face sums in face order, bit for bit: on a jittered
    /// torus in shuffled face order, with obtuse, zero-area and tiny faces.
    #[test]
    fn lumped_masses_are_the_face_order_sums() {
        let m = shapes::torus(2.0, 0.5, 120, 60).unwrap();
        let mut rng = crate::random::SplitMix64::new(7);
        let mut p = m.positions().to_vec();
        for q in &mut p {
            *q += 0.02 * glam::DVec3::new(rng.signed(), rng.signed(), rng.signed());
        }
        p[5] = p[6];
        p[200] *= 1e-70;
        let mut faces = m.faces().to_vec();
        for i in (1..faces.len()).rev() {
            faces.swap(i, rng.below(i + 1));
        }
        let m = TriMesh::new(p, faces).unwrap();
        for kind in MassKind::ALL {
            let mut expected = vec![0.0; m.vertex_count()];
            for (f, face) in m.faces().iter().enumerate() {
                let shares = corner_masses(m.triangle(crate::FaceId::new(f)), kind);
                for (v, share) in face.iter().zip(shares) {
                    expected[*v as usize] += share;
                }
            }
            let got = lumped_mass(&m, kind);
            assert!(got.iter().zip(&expected).all(|(a, b)| a.to_bits() == b.to_bits()), "{kind}");
        }
    }

    #[test]
    fn voronoi_area_of_equilateral_corner_is_a_third() {
        let h = 3f64.sqrt() / 2.0;
        let tri = [glam::DVec3::ZERO, glam::DVec3::X, glam::DVec3::new(0.5, h, 0.0)];
        let area = triangle_area(tri);
        for s in mixed_voronoi_corners(tri) {
            assert!((s - area / 3.0).abs() < 1e-15);
        }
    }
}
