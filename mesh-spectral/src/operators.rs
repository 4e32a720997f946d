//! The operator pair `(L, M)` of a mesh: which Laplacian and which lumped
//! mass the spectral tools use, and which one was actually taken.

use std::fmt;
use std::str::FromStr;
use std::time::Instant;

use mesh_kernel::clean::degenerate_faces;
use mesh_kernel::operators::laplacian::DEGENERATE_TOLERANCE;
use mesh_kernel::operators::{self, IntrinsicOptions, IntrinsicTriangulation, MassKind};
use mesh_kernel::TriMesh;
use sprs::CsMat;

use crate::error::{Result, SpectralError};

/// Which Laplace-Beltrami discretization.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum LaplacianKind {
    /// [`LaplacianKind::Cotan`] unless the mesh has zero-area faces, then
    /// [`LaplacianKind::IntrinsicDelaunay`]: a zero-area triangle has no
    /// cotangents, and its near-degenerate neighbours have huge ones that
    /// ruin the conditioning of `L - sigma M`. The choice is reported in
    /// [`OperatorInfo`].
    #[default]
    Auto,
    /// Cotangent Laplacian of the mesh itself (eq. 2.15; `-igl::cotmatrix`);
    /// zero-area faces contribute nothing.
    Cotan,
    /// Cotangent Laplacian of the intrinsic Delaunay triangulation (Bobenko
    /// and Springborn 2007) of the mollified edge lengths (Sharp and Crane
    /// 2020): non-negative weights, symmetric positive semi-definite, well
    /// defined on zero-area triangles.
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

/// The names of [`LaplacianKind`], as parsed and displayed.
pub const LAPLACIAN_NAMES: [&str; 3] = ["auto", "cotan", "intrinsic"];
/// The names of [`LumpedMass`], as parsed and displayed.
pub const MASS_NAMES: [&str; 2] = ["voronoi", "barycentric"];

impl LaplacianKind {
    /// Every kind, in the order of [`LAPLACIAN_NAMES`].
    pub const ALL: [Self; 3] = [Self::Auto, Self::Cotan, Self::IntrinsicDelaunay];

    /// The kind [`laplace_beltrami`] builds for `mesh` (never `Auto`) and the
    /// number of zero-area faces that decided it. O(F).
    pub fn resolve(self, mesh: &TriMesh) -> (Self, usize) {
        let degenerate = degenerate_faces(mesh, DEGENERATE_TOLERANCE).len();
        let kind = match self {
            Self::Auto if degenerate > 0 => Self::IntrinsicDelaunay,
            Self::Auto => Self::Cotan,
            other => other,
        };
        (kind, degenerate)
    }
}

impl LumpedMass {
    /// Every kind, in the order of [`MASS_NAMES`].
    pub const ALL: [Self; 2] = [Self::MixedVoronoi, Self::Barycentric];
}

fn parse_name<T: Copy>(s: &str, names: &[&str], all: &[T], what: &'static str) -> Result<T> {
    names.iter().position(|n| n.eq_ignore_ascii_case(s.trim())).map(|i| all[i]).ok_or_else(|| {
        SpectralError::InvalidOption { name: what, reason: format!("unknown `{s}`; known: {}", names.join(", ")) }
    })
}

impl FromStr for LaplacianKind {
    type Err = SpectralError;
    fn from_str(s: &str) -> Result<Self> {
        parse_name(s, &LAPLACIAN_NAMES, &Self::ALL, "laplacian")
    }
}

impl fmt::Display for LaplacianKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let i = Self::ALL.iter().position(|k| k == self).unwrap_or(0);
        f.write_str(LAPLACIAN_NAMES[i])
    }
}

impl FromStr for LumpedMass {
    type Err = SpectralError;
    fn from_str(s: &str) -> Result<Self> {
        parse_name(s, &MASS_NAMES, &Self::ALL, "mass")
    }
}

impl fmt::Display for LumpedMass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let i = Self::ALL.iter().position(|k| k == self).unwrap_or(0);
        f.write_str(MASS_NAMES[i])
    }
}

/// What [`pencil`] built: the Laplacian taken (never `Auto`), why, and on
/// what.
#[derive(Debug, Clone, PartialEq)]
pub struct OperatorInfo {
    /// The Laplacian asked for (possibly `Auto`).
    pub requested: LaplacianKind,
    /// The Laplacian built.
    pub laplacian: LaplacianKind,
    /// The lumped mass.
    pub mass: LumpedMass,
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
            LumpedMass::MixedVoronoi => "mixed Voronoi",
            LumpedMass::Barycentric => "barycentric",
        };
        format!("{name}{why}, {mass} lumped mass")
    }
}

/// Stiffness, lumped mass and what was built.
#[derive(Debug, Clone)]
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
pub fn pencil(mesh: &TriMesh, laplacian: LaplacianKind, mass: LumpedMass) -> Result<Pencil> {
    if mesh.face_count() == 0 {
        return Err(SpectralError::Mesh(mesh_kernel::MeshError::Empty));
    }
    let start = Instant::now();
    let (kind, degenerate_faces) = laplacian.resolve(mesh);
    let l = match kind {
        LaplacianKind::IntrinsicDelaunay => {
            IntrinsicTriangulation::delaunay(mesh, &IntrinsicOptions::default())?.cotan_laplacian()
        }
        _ => operators::cotan_laplacian(mesh),
    };
    let kind_m = match mass {
        LumpedMass::MixedVoronoi => MassKind::MixedVoronoi,
        LumpedMass::Barycentric => MassKind::Barycentric,
    };
    let m = operators::lumped_mass(mesh, kind_m);
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
pub fn laplace_beltrami(mesh: &TriMesh, laplacian: LaplacianKind, mass: LumpedMass) -> Result<(CsMat<f64>, Vec<f64>)> {
    let p = pencil(mesh, laplacian, mass)?;
    Ok((p.laplacian, p.mass))
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::glam::DVec3;
    use mesh_kernel::shapes;

    #[test]
    fn names_round_trip() {
        for k in LaplacianKind::ALL {
            assert_eq!(k.to_string().parse::<LaplacianKind>().unwrap(), k);
        }
        for k in LumpedMass::ALL {
            assert_eq!(k.to_string().parse::<LumpedMass>().unwrap(), k);
        }
        assert!("nope".parse::<LaplacianKind>().is_err());
    }

    #[test]
    fn auto_takes_intrinsic_only_with_zero_area_faces() {
        let sphere = shapes::icosphere(2).unwrap();
        let p = pencil(&sphere, LaplacianKind::Auto, LumpedMass::MixedVoronoi).unwrap();
        assert_eq!((p.info.laplacian, p.info.degenerate_faces), (LaplacianKind::Cotan, 0));
        // Two triangles over three collinear points, closed below by the
        // zero-area triangle (0, 2, 1).
        let q = |x: f64, y: f64| DVec3::new(x, y, 0.0);
        let pos = vec![q(0.0, 0.0), q(1.0, 0.0), q(2.0, 0.0), q(1.0, 1.0)];
        let mesh = TriMesh::new(pos, vec![[0, 1, 3], [1, 2, 3], [0, 2, 1]]).unwrap();
        let p = pencil(&mesh, LaplacianKind::Auto, LumpedMass::MixedVoronoi).unwrap();
        assert_eq!((p.info.laplacian, p.info.degenerate_faces), (LaplacianKind::IntrinsicDelaunay, 1));
        assert!(p.info.describe().contains("1 zero-area faces"), "{}", p.info.describe());
    }
}
