//! The operator pair `(L, M)` of a mesh: which Laplacian and which lumped
//! mass the spectral tools use, and which one was actually taken.

use std::time::Instant;

use mesh_kernel::operators::{LaplacianKind, MassKind};
use mesh_kernel::TriMesh;
use sprs::CsMat;

use crate::error::{Result, SpectralError};

/// What [`pencil`] built: the Laplacian taken (never `Auto`), why, and on
/// what.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct OperatorInfo {
    /// The Laplacian asked for (possibly `Auto`).
    pub requested: LaplacianKind,
    /// The Laplacian built.
    pub laplacian: LaplacianKind,
    /// The lumped mass (`Galerkin` is lumped by row sums: the barycentric
    /// areas).
    pub mass: MassKind,
    /// Zero-area faces of the mesh (`2 area <= 1e-12 longest edge^2`, the
    /// faces the cotangent Laplacian has to drop); when non-zero, `Auto`
    /// takes the intrinsic Delaunay Laplacian.
    pub degenerate_faces: usize,
    /// Vertices of the mesh the pencil was built on.
    pub vertices: usize,
    /// Faces of the mesh the pencil was built on.
    pub faces: usize,
    /// Seconds spent assembling `L` and `M` (edge flips included).
    pub assembly_seconds: f64,
}

impl OperatorInfo {
    /// One line for people: the Laplacian and why it was taken.
    pub fn describe(&self) -> String {
        let name = match self.laplacian {
            LaplacianKind::IntrinsicDelaunay => "intrinsic Delaunay Laplacian (mollified)",
            _ => "cotangent Laplacian",
        };
        let why = match (self.requested, self.degenerate_faces) {
            (LaplacianKind::Auto, 0) => " (automatic: no zero-area face)".to_owned(),
            (LaplacianKind::Auto, d) => format!(" (automatic: {d} zero-area faces)"),
            (LaplacianKind::Cotan, d) if d > 0 => format!(" ({d} zero-area faces dropped)"),
            _ => String::new(),
        };
        let mass = match self.mass {
            MassKind::MixedVoronoi => "mixed Voronoi",
            MassKind::Barycentric => "barycentric",
            MassKind::Galerkin => "row-summed Galerkin (barycentric)",
        };
        format!("{name}{why}, {mass} lumped mass")
    }
}

/// Stiffness, lumped mass and what was built.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct Pencil {
    /// `L`, symmetric positive semi-definite, CSR.
    pub laplacian: CsMat<f64>,
    /// Diagonal of `M`.
    pub mass: Vec<f64>,
    /// Which Laplacian and why.
    pub info: OperatorInfo,
}

/// The pencil `(L, M)` of `mesh`, with [`LaplacianKind::Auto`] resolved by
/// [`LaplacianKind::resolve`]. Isolated vertices get a zero row and zero
/// mass (the eigensolver excludes them). O(V + F), plus the edge flips for
/// the intrinsic Delaunay Laplacian.
///
/// # Errors
/// `SpectralError::Mesh` (`MeshError::Empty`) for a mesh without faces; the errors of the intrinsic Delaunay
/// triangulation (`LaplacianKind::IntrinsicDelaunay`).
pub fn pencil(mesh: &TriMesh, laplacian: LaplacianKind, mass: MassKind) -> Result<Pencil> {
    if mesh.face_count() == 0 {
        return Err(SpectralError::Mesh(mesh_kernel::MeshError::Empty));
    }
    let start = Instant::now();
    let (kind, degenerate_faces) = laplacian.resolve(mesh);
    // From the mesh's cache: shared with any other analysis of the same mesh.
    let l = mesh.geometry().laplacian(kind)?.clone();
    let m = mesh.geometry().lumped_mass(mass).to_vec();
    let info = OperatorInfo {
        requested: laplacian,
        laplacian: kind,
        mass,
        degenerate_faces,
        vertices: mesh.vertex_count(),
        faces: mesh.face_count(),
        assembly_seconds: start.elapsed().as_secs_f64(),
    };
    Ok(Pencil { laplacian: l, mass: m, info })
}

/// Stiffness and lumped mass of a mesh: `L` (symmetric positive
/// semi-definite, CSR) and the diagonal of `M`; [`pencil`] without the
/// report. O(V + F), plus the edge flips for the intrinsic Delaunay
/// Laplacian.
///
/// # Errors
/// As [`pencil`].
pub fn laplace_beltrami(mesh: &TriMesh, laplacian: LaplacianKind, mass: MassKind) -> Result<(CsMat<f64>, Vec<f64>)> {
    let p = pencil(mesh, laplacian, mass)?;
    Ok((p.laplacian, p.mass))
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::glam::DVec3;
    use mesh_kernel::shapes;

    #[test]
    fn auto_takes_intrinsic_only_with_zero_area_faces() {
        let sphere = shapes::icosphere(2).unwrap();
        let p = pencil(&sphere, LaplacianKind::Auto, MassKind::MixedVoronoi).unwrap();
        assert_eq!((p.info.laplacian, p.info.degenerate_faces), (LaplacianKind::Cotan, 0));
        // Two triangles over three collinear points, closed below by the
        // zero-area triangle (0, 2, 1).
        let q = |x: f64, y: f64| DVec3::new(x, y, 0.0);
        let pos = vec![q(0.0, 0.0), q(1.0, 0.0), q(2.0, 0.0), q(1.0, 1.0)];
        let mesh = TriMesh::new(pos, vec![[0, 1, 3], [1, 2, 3], [0, 2, 1]]).unwrap();
        let p = pencil(&mesh, LaplacianKind::Auto, MassKind::MixedVoronoi).unwrap();
        assert_eq!((p.info.laplacian, p.info.degenerate_faces), (LaplacianKind::IntrinsicDelaunay, 1));
        assert!(p.info.describe().contains("1 zero-area faces"), "{}", p.info.describe());
    }
}
