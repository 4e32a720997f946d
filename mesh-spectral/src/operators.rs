//! The operator pair `(L, M)` of a mesh: which Laplacian and which lumped
//! mass the spectral tools use.

use mesh_core::operators::{self, IntrinsicOptions, IntrinsicTriangulation, MassKind};
use mesh_core::TriMesh;
use sprs::CsMat;

use crate::error::{Result, SpectralError};

/// Which Laplace-Beltrami discretization.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum LaplacianKind {
    /// Cotangent Laplacian of the mesh itself (eq. 2.15; `-igl::cotmatrix`).
    #[default]
    Cotan,
    /// Cotangent Laplacian of the intrinsic Delaunay triangulation (Bobenko
    /// and Springborn 2007): non-negative weights, well defined on
    /// zero-area triangles (mollified lengths).
    IntrinsicDelaunay,
}

/// Which lumped mass matrix (the eigensolver needs a diagonal one).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum LumpedMass {
    /// Mixed Voronoi areas (Meyer et al. 2003; libigl `MASSMATRIX_TYPE_VORONOI`).
    #[default]
    MixedVoronoi,
    /// A third of each incident face's area.
    Barycentric,
}

/// Stiffness and lumped mass of a mesh: `L` (symmetric positive
/// semi-definite, CSR) and the diagonal of `M`. Isolated vertices get a zero
/// row and zero mass (the eigensolver excludes them). O(V + F), plus the
/// edge flips for [`LaplacianKind::IntrinsicDelaunay`].
pub fn laplace_beltrami(mesh: &TriMesh, laplacian: LaplacianKind, mass: LumpedMass) -> Result<(CsMat<f64>, Vec<f64>)> {
    if mesh.face_count() == 0 {
        return Err(SpectralError::Mesh(mesh_core::MeshError::Empty));
    }
    let l = match laplacian {
        LaplacianKind::Cotan => operators::cotan_laplacian(mesh),
        LaplacianKind::IntrinsicDelaunay => {
            IntrinsicTriangulation::delaunay(mesh, &IntrinsicOptions::default())?.cotan_laplacian()
        }
    };
    let kind = match mass {
        LumpedMass::MixedVoronoi => MassKind::MixedVoronoi,
        LumpedMass::Barycentric => MassKind::Barycentric,
    };
    Ok((l, operators::lumped_mass(mesh, kind)))
}
