//! Mean curvature from the cotangent formula (eq. 2.26): the mean-curvature
//! normal of Meyer, Desbrun, Schroeder and Barr 2003.

use glam::DVec3;
use mesh_kernel::TriMesh;

use crate::error::{CurvatureError, Result};
use crate::status::{topological_status, VertexStatus};
use mesh_kernel::geometry::NormalWeighting;
use mesh_kernel::operators::MassKind;
use mesh_kernel::par;

/// Options of [`mean_curvature`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MeanOptions {
    /// The area that turns the integrated curvature into a pointwise one.
    pub area: MassKind,
    /// The vertex normal that gives the sign (and, off the interior, the
    /// direction the mean-curvature normal is projected on).
    pub normals: NormalWeighting,
}

impl Default for MeanOptions {
    fn default() -> Self {
        Self { area: MassKind::MixedVoronoi, normals: NormalWeighting::Area }
    }
}

/// Per-vertex mean curvature.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct MeanCurvature {
    /// Integrated mean curvature `H A`: half the length of `(L x)_i`, the
    /// cotangent Laplacian of the positions (eq. 2.26 halved), signed by the
    /// vertex normal (positive on a sphere with outward normals). At
    /// boundary and non-manifold vertices, where `(L x)_i` has a tangential
    /// part, its component along the normal.
    pub integrated: Vec<f64>,
    /// `integrated / area`: the mean curvature `H = (k1 + k2) / 2`; 0 where
    /// the area or the normal vanishes ([`VertexStatus::Degenerate`]).
    pub pointwise: Vec<f64>,
    /// The mean-curvature normal `H n = (L x)_i / (2 A_i)` (Meyer et al. 2003:
    /// `K(x) = 2 H n`); zero where the area vanishes.
    pub normal: Vec<DVec3>,
    /// The vertex areas used.
    pub area: Vec<f64>,
    /// What each value means (see [`VertexStatus`]).
    pub status: Vec<VertexStatus>,
}

/// Mean curvature of every vertex from the cotangent Laplacian
/// ([`mesh_kernel::operators::cotan_laplacian`]): `H n = (L x)_i / (2 A_i)`
/// (eq. 2.26, Meyer et al. 2003), integrated and pointwise.
///
/// Works on any mesh: zero-area faces add no stiffness, values are finite
/// everywhere and [`MeanCurvature::status`] says which are estimates.
/// Cost O(V + F): one pass over the faces for `L x`
/// ([`mesh_kernel::operators::cotan_laplacian_apply`], from differences of
/// positions, so that a mesh far from the origin loses no accuracy; the
/// Laplacian is not assembled), beside the vertex areas and normals of the
/// mesh's geometry cache (on several threads with the `rayon` feature).
///
/// # Errors
/// None in practice for a valid `TriMesh` (the result type leaves room for `CurvatureError::Mesh`); vertices
/// where the estimate cannot be trusted are flagged in [`MeanCurvature::status`].
pub fn mean_curvature(mesh: &TriMesh, options: &MeanOptions) -> Result<MeanCurvature> {
    let (mesh, unit) = mesh_kernel::units::normalized(mesh);
    let (normals, lx_and_area) =
        par::join(|| mesh.geometry().vertex_normals(options.normals), || laplacian_and_area(&mesh, options.area));
    let (lx, area) = lx_and_area?;
    Ok(assemble(&mesh, lx, area, normals).in_unit(unit))
}

/// [`mean_curvature`] signed by the given vertex normals instead of a
/// weighting of face normals: `normals[i]` (unit, or zero where there is
/// none) orients vertex `i`. With the normals of a [`crate::CurvatureTensor`]
/// the discrete and the tensor's mean curvature share one sign convention
/// at every vertex, folds of a scan included. Cost O(V + F).
///
/// Errors with [`CurvatureError::InvalidOption`] when `normals` does not
/// hold one vector per vertex.
///
/// # Errors
/// `CurvatureError::InvalidOption` (`normals`) when `normals` does not have one entry per vertex.
pub fn mean_curvature_with_normals(mesh: &TriMesh, area: MassKind, normals: &[DVec3]) -> Result<MeanCurvature> {
    if normals.len() != mesh.vertex_count() {
        return Err(CurvatureError::InvalidOption {
            name: "normals",
            reason: format!("{} normals for {} vertices", normals.len(), mesh.vertex_count()),
        });
    }
    let (mesh, unit) = mesh_kernel::units::normalized(mesh);
    let (lx, area) = laplacian_and_area(&mesh, area)?;
    Ok(assemble(&mesh, lx, area, normals).in_unit(unit))
}

impl MeanCurvature {
    /// The values of a mesh divided by `unit`, for the mesh itself.
    fn in_unit(mut self, unit: f64) -> Self {
        self.integrated.iter_mut().for_each(|x| *x *= unit);
        self.pointwise.iter_mut().for_each(|x| *x /= unit);
        self.area.iter_mut().for_each(|x| *x = *x * unit * unit);
        self
    }
}

/// `(L x)_i` for every vertex, and the vertex areas. O(V + F).
fn laplacian_and_area(mesh: &TriMesh, kind: MassKind) -> Result<(Vec<DVec3>, Vec<f64>)> {
    let (lx, area) = par::join(
        || mesh_kernel::operators::cotan_laplacian_apply(mesh, mesh.positions()),
        || mesh.geometry().lumped_mass(kind).to_vec(),
    );
    Ok((lx?, area))
}

/// Integrated and pointwise mean curvature from `(L x)_i`, the areas and
/// the orienting normals. O(V).
fn assemble(mesh: &TriMesh, lx: Vec<DVec3>, area: Vec<f64>, normals: &[DVec3]) -> MeanCurvature {
    let mut status = topological_status(mesh);
    let n = mesh.vertex_count();
    let (mut integrated, mut pointwise, mut normal) = (vec![0.0; n], vec![0.0; n], vec![DVec3::ZERO; n]);
    for i in 0..n {
        if status[i] == VertexStatus::Isolated {
            continue;
        }
        let (hn2, nv) = (lx[i], normals[i]);
        if area[i].is_nan() || area[i] <= 0.0 || nv == DVec3::ZERO || !nv.is_finite() {
            status[i] = VertexStatus::Degenerate;
            continue;
        }
        integrated[i] =
            if status[i] == VertexStatus::Valid { 0.5 * hn2.length().copysign(hn2.dot(nv)) } else { 0.5 * hn2.dot(nv) };
        pointwise[i] = integrated[i] / area[i];
        normal[i] = hn2 / (2.0 * area[i]);
        if !(pointwise[i].is_finite() && normal[i].is_finite()) {
            (integrated[i], pointwise[i], normal[i]) = (0.0, 0.0, DVec3::ZERO);
            status[i] = VertexStatus::Degenerate;
        }
    }
    MeanCurvature { integrated, pointwise, normal, area, status }
}
