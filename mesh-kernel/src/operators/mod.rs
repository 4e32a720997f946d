//! Discrete operators as sparse matrices (`sprs::CsMat<f64>`, CSR).
//!
//! - [`adjacency_matrix`] (eq. 2.5) and [`uniform_laplacian`] (eq. 2.12);
//! - [`cotan_laplacian`] (eq. 2.15) and the weights behind it;
//! - [`mass`]: barycentric, mixed Voronoi (Meyer et al. 2003) and Galerkin;
//! - [`gradient()`] and [`divergence()`] of piecewise-linear functions (`L = D G`);
//! - [`intrinsic`]: intrinsic Delaunay triangulation by edge flips and its
//!   Laplacian, whose weights are never negative.
//!
//! Sign convention: Laplacians are positive semi-definite, `L_ii = sum_j w_ij`,
//! `L_ij = -w_ij` (geometry-central's convention; libigl's `cotmatrix` is `-L`).
//! All assembly works on non-manifold input: it only needs triangles.

mod corner_batch;
pub mod gradient;
pub mod intrinsic;
pub mod laplacian;
pub mod mass;
mod pattern;

pub use corner_batch::{corner_angles_and_masses_batch, CornerBatch, CORNER_BATCH};
pub use gradient::{divergence, gradient};
pub use intrinsic::{cotan_from_lengths, is_delaunay_edge, IntrinsicOptions, IntrinsicTriangulation};
pub use laplacian::{cotan_laplacian, cotan_laplacian_apply, cotan_weights, halfedge_cotans, LaplacianKind};
pub use mass::{corner_angles_and_masses, corner_masses, lumped_mass, mass_matrix, mixed_voronoi_corners, MassKind};
pub use pattern::EdgePattern;

use sprs::CsMat;

use crate::mesh::TriMesh;

/// Adjacency matrix A (eq. 2.5): A_ij = 1 when an edge joins i and j, else 0.
/// Symmetric, zero diagonal (stored explicitly). O(V + E).
pub fn adjacency_matrix(mesh: &TriMesh) -> CsMat<f64> {
    let conn = mesh.connectivity();
    let pattern = EdgePattern::new(mesh.vertex_count(), conn.edges());
    pattern.symmetric(&vec![1.0; conn.edge_count()], |_, _| 0.0)
}

/// Uniform (graph) Laplacian of eq. 2.12-2.13: row i holds 1 on the diagonal
/// and -1/|N(i)| for each neighbour, so `(L q)_i = q_i - mean of neighbours`.
/// Not symmetric for irregular valences; rows sum to zero; isolated vertices
/// give zero rows. O(V + E).
pub fn uniform_laplacian(mesh: &TriMesh) -> CsMat<f64> {
    let conn = mesh.connectivity();
    let n = mesh.vertex_count();
    let mut degree = vec![0u32; n];
    for [a, b] in conn.edges() {
        degree[a.idx()] += 1;
        degree[b.idx()] += 1;
    }
    let (lo_hi, hi_lo): (Vec<f64>, Vec<f64>) =
        conn.edges().iter().map(|[a, b]| (1.0 / degree[a.idx()] as f64, 1.0 / degree[b.idx()] as f64)).unzip();
    EdgePattern::new(n, conn.edges()).directed(&lo_hi, &hi_lo)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    #[test]
    fn adjacency_counts_valence() {
        let m = shapes::icosphere(1).unwrap();
        let a = adjacency_matrix(&m);
        let conn = m.connectivity();
        for (i, row) in a.outer_iterator().enumerate() {
            let ones = row.iter().filter(|(_, v)| **v == 1.0).count();
            assert_eq!(ones, conn.valence(crate::VertexId::new(i)));
        }
        assert_eq!(a.nnz(), m.vertex_count() + 2 * conn.edge_count());
    }

    #[test]
    fn uniform_rows_sum_to_zero() {
        let m = shapes::disk(3, 1).unwrap();
        let l = uniform_laplacian(&m);
        for row in l.outer_iterator() {
            let s: f64 = row.iter().map(|(_, v)| v).sum();
            assert!(s.abs() < 1e-15);
        }
    }
}
