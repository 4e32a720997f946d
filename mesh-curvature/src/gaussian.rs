//! Gaussian curvature by angle defect (eq. 2.25) and the geodesic curvature
//! of the boundary, which together satisfy the discrete Gauss-Bonnet theorem.

use std::f64::consts::{PI, TAU};

use mesh_kernel::{TriMesh, VertexKind};

use crate::error::Result;
use crate::status::{status_of_kind, VertexStatus};
use mesh_kernel::operators::{corner_angles_and_masses_batch, CornerBatch, MassKind, CORNER_BATCH};
use mesh_kernel::par;

/// Options of [`gaussian_curvature`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct GaussianOptions {
    /// The area that turns the integrated curvature into a pointwise one.
    pub area: MassKind,
}

/// Per-vertex Gaussian curvature by angle defect.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct GaussianCurvature {
    /// Integrated Gaussian curvature `2 pi - sum of corner angles` (eq. 2.25
    /// with the sign of a defect: positive on a sphere) at interior vertices;
    /// 0 at boundary, non-manifold and isolated vertices.
    pub integrated: Vec<f64>,
    /// Integrated geodesic curvature of the boundary `pi - sum of corner
    /// angles` (the turning angle of the boundary polygon) at boundary
    /// vertices; 0 elsewhere.
    pub geodesic: Vec<f64>,
    /// `integrated / area`: the Gaussian curvature at the vertex; 0 where the
    /// area is 0 (flagged [`VertexStatus::Degenerate`]) and off the interior.
    pub pointwise: Vec<f64>,
    /// The vertex areas used.
    pub area: Vec<f64>,
    /// What each value means (see [`VertexStatus`]).
    pub status: Vec<VertexStatus>,
}

impl GaussianCurvature {
    /// `sum integrated + sum geodesic`, which equals `2 pi chi` (discrete
    /// Gauss-Bonnet) to rounding on every manifold mesh, closed or not,
    /// whatever its geometry: every triangle's angles sum to pi. Summed with
    /// Neumaier's compensation. O(V).
    pub fn total(&self) -> f64 {
        compensated_sum(self.integrated.iter().chain(&self.geodesic).copied())
    }
}

/// Gaussian curvature of every vertex by angle defect (eq. 2.25), integrated
/// and pointwise, with the boundary's geodesic curvature reported apart so
/// that [`GaussianCurvature::total`] is `2 pi chi`.
///
/// Works on any mesh (non-manifold, degenerate, disconnected): values are
/// finite everywhere and [`GaussianCurvature::status`] says which are
/// estimates. Cost O(V + F): two `atan2` per face (the third angle is
/// `pi` minus the others, so each face's angles sum to pi exactly),
/// eight faces at a time
/// ([`mesh_kernel::operators::corner_angles_and_masses_batch`], 4-wide
/// where the processor has AVX2), in parallel over faces with the `rayon`
/// feature.
///
/// # Errors
/// None in practice for a valid `TriMesh` (the result type leaves room for `CurvatureError::Mesh` from
/// mesh-kernel's geometry); unreliable vertices are flagged in the output, not refused.
pub fn gaussian_curvature(mesh: &TriMesh, options: &GaussianOptions) -> Result<GaussianCurvature> {
    let (mesh, unit) = mesh_kernel::units::normalized(mesh);
    let mut k = angle_defect(&mesh, options)?;
    if unit != 1.0 {
        k.pointwise.iter_mut().for_each(|x| *x = *x / unit / unit);
        k.area.iter_mut().for_each(|x| *x = *x * unit * unit);
    }
    Ok(k)
}

/// [`gaussian_curvature`] in the mesh's own unit.
fn angle_defect(mesh: &TriMesh, options: &GaussianOptions) -> Result<GaussianCurvature> {
    let conn = mesh.connectivity();
    // One pass over the faces, eight at a time: each corner's angle and
    // area, added at its vertex (the angles with Neumaier's compensation).
    let sums = par::scatter_batched(
        mesh.vertex_count(),
        mesh.faces(),
        mesh.positions(),
        VertexSums::default(),
        |first| {
            let mut corners: CornerBatch = [[(0.0, 0.0); 3]; CORNER_BATCH];
            corner_angles_and_masses_batch(mesh, first, options.area, &mut corners);
            corners
        },
        VertexSums::add,
    );
    // Then each vertex's values and status in one pass, each array written
    // once, on several threads. One loop writing into zeroed arrays took
    // 3.3-4.0 ms at 470,274 vertices on any thread count; with this pass
    // the whole Gaussian curvature there (Hilbert order) took 29.4-30.5
    // ms on one thread against 30.1-31.0, and 17.1-18.5 ms on two against
    // 22.1-24.1 (2026-12-05).
    let kinds = conn.vertex_kinds();
    let ([integrated, geodesic, pointwise, area], status) = par::map_columns(mesh.vertex_count(), |i| {
        let (sum, area) = (sums[i].angle + sums[i].compensation, sums[i].area);
        let status = status_of_kind(kinds[i]);
        match kinds[i] {
            VertexKind::Isolated | VertexKind::NonManifold => ([0.0, 0.0, 0.0, area], status),
            VertexKind::Boundary => ([0.0, PI - sum, 0.0, area], status),
            VertexKind::Interior if area > 0.0 => ([TAU - sum, 0.0, (TAU - sum) / area, area], status),
            VertexKind::Interior => ([TAU - sum, 0.0, 0.0, area], VertexStatus::Degenerate),
        }
    });
    Ok(GaussianCurvature { integrated, geodesic, pointwise, area, status })
}

/// The corner angles at a vertex, summed with Neumaier's compensation, and
/// its area.
#[derive(Debug, Clone, Copy, Default)]
struct VertexSums {
    angle: f64,
    compensation: f64,
    area: f64,
}

impl VertexSums {
    fn add(&mut self, (angle, area): (f64, f64)) {
        let t = self.angle + angle;
        self.compensation +=
            if self.angle.abs() >= angle.abs() { (self.angle - t) + angle } else { (angle - t) + self.angle };
        self.angle = t;
        self.area += area;
    }
}

/// Neumaier's compensated sum.
pub(crate) fn compensated_sum(values: impl Iterator<Item = f64>) -> f64 {
    let (mut sum, mut comp) = (0.0f64, 0.0f64);
    for x in values {
        let t = sum + x;
        comp += if sum.abs() >= x.abs() { (sum - t) + x } else { (x - t) + sum };
        sum = t;
    }
    sum + comp
}
