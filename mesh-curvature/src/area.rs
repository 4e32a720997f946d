//! The area a vertex stands for, which turns integrated curvature into
//! pointwise curvature.

use mesh_kernel::operators::{lumped_mass, MassKind};
use mesh_kernel::TriMesh;

/// Which vertex area divides integrated curvature.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum AreaKind {
    /// Mixed Voronoi area of Meyer, Desbrun, Schroeder and Barr 2003 (the
    /// area for which the angle defect and the cotangent formula are the
    /// integrals of K and H).
    #[default]
    MixedVoronoi,
    /// One third of the area of each incident face.
    Barycentric,
}

impl AreaKind {
    /// The mesh-kernel mass kind behind it.
    pub fn mass_kind(self) -> MassKind {
        match self {
            Self::MixedVoronoi => MassKind::MixedVoronoi,
            Self::Barycentric => MassKind::Barycentric,
        }
    }
}

/// Per-vertex area of the given kind ([`mesh_kernel::operators::lumped_mass`]). O(F).
pub fn vertex_areas(mesh: &TriMesh, kind: AreaKind) -> Vec<f64> {
    lumped_mass(mesh, kind.mass_kind())
}
