//! The curvature tensor (second fundamental form, eq. 2.27-2.31) per vertex:
//! principal curvatures and directions, and the estimators that produce it.

use glam::DVec3;
use mesh_kernel::TriMesh;

use crate::error::{CurvatureError, Result};
use crate::fit::{self, Degree, FitOptions};
use crate::frame::{tangent_basis, Sym2};
use crate::neighborhood::Neighborhood;
use crate::normal_cycle;
use crate::rusinkiewicz;
use crate::status::VertexStatus;
use mesh_kernel::geometry::NormalWeighting;

/// How the curvature tensor is estimated. More estimators may come: matches
/// outside the crate need a wildcard arm.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum TensorMethod {
    /// Local polynomial fit of the surface as a height field over the tangent
    /// plane (see [`FitOptions`]): a cubic through the positions and normals
    /// of the neighbourhood (Goldfeather and Interrante 2004), or a quadric
    /// through the positions (libigl's `principal_curvature`). The default:
    /// the most accurate in the crate's validation (README).
    Fit(FitOptions),
    /// Per-face second fundamental form fitted to the normal differences
    /// along the face's edges, rotated into each vertex frame and averaged
    /// with mixed Voronoi weights (Rusinkiewicz 2004). The fastest.
    Rusinkiewicz,
    /// Normal-cycle tensor (Cohen-Steiner and Morvan 2003): sum over edges of
    /// dihedral angle x length x edge direction outer products, over the
    /// neighbourhood, divided by its area, projected on the tangent plane.
    NormalCycle(Neighborhood),
}

impl Default for TensorMethod {
    fn default() -> Self {
        Self::Fit(FitOptions::default())
    }
}

impl TensorMethod {
    /// Every estimator by name, with its default neighbourhood: `fit` (the
    /// default quartic over the 2-ring), `quadric` (a quadric through the
    /// 1-ring positions, libigl's `principal_curvature`), `rusinkiewicz`,
    /// `normal-cycle` (1-ring). Their [`name`](Self::name)s are what
    /// [`FromStr`](std::str::FromStr) accepts and [`Display`](std::fmt::Display) writes.
    pub const ALL: [Self; 4] = [
        Self::Fit(FitOptions {
            neighborhood: Neighborhood::Rings(2),
            degree: Degree::Quartic,
            use_normals: false,
            refine_normal: true,
        }),
        Self::Fit(FitOptions {
            neighborhood: Neighborhood::Rings(1),
            degree: Degree::Quadric,
            use_normals: false,
            refine_normal: false,
        }),
        Self::Rusinkiewicz,
        Self::NormalCycle(Neighborhood::Rings(1)),
    ];

    /// The command-line name: `quadric` for a quadric fit, `fit` for the
    /// other fits, `rusinkiewicz`, `normal-cycle`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Fit(fit) if fit.degree == Degree::Quadric => "quadric",
            Self::Fit(_) => "fit",
            Self::Rusinkiewicz => "rusinkiewicz",
            Self::NormalCycle(_) => "normal-cycle",
        }
    }

    /// The neighbourhood the estimator fits or sums over (`None` for
    /// Rusinkiewicz, whose stencil is the 1-ring of faces).
    pub fn neighborhood(self) -> Option<Neighborhood> {
        match self {
            Self::Fit(fit) => Some(fit.neighborhood),
            Self::NormalCycle(nbh) => Some(nbh),
            Self::Rusinkiewicz => None,
        }
    }

    /// The same estimator over `neighborhood`.
    ///
    /// # Errors
    /// `CurvatureError::InvalidOption` (`neighborhood`) for Rusinkiewicz, which has no neighbourhood to set.
    pub fn with_neighborhood(self, neighborhood: Neighborhood) -> Result<Self> {
        match self {
            Self::Fit(fit) => Ok(Self::Fit(FitOptions { neighborhood, ..fit })),
            Self::NormalCycle(_) => Ok(Self::NormalCycle(neighborhood)),
            Self::Rusinkiewicz => Err(CurvatureError::InvalidOption {
                name: "neighborhood",
                reason: "rusinkiewicz has no neighbourhood to set (its stencil is the 1-ring of faces)".into(),
            }),
        }
    }
}

mesh_kernel::named_choice!(TensorMethod, "method", CurvatureError);

/// Options of [`curvature_tensor`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TensorOptions {
    /// The estimator.
    pub method: TensorMethod,
    /// The vertex normals the estimator starts from. Default
    /// [`NormalWeighting::Max`] (Max 1999): exact when a vertex and its
    /// 1-ring lie on a sphere, and what Rusinkiewicz 2004 uses; the tensor
    /// estimators differentiate the normal field, so its accuracy matters.
    pub normals: NormalWeighting,
}

impl Default for TensorOptions {
    fn default() -> Self {
        Self { method: TensorMethod::default(), normals: NormalWeighting::Max }
    }
}

/// Per-vertex curvature tensor, as principal curvatures and directions.
///
/// Conventions: curvatures are positive where the surface bends away from
/// its normal (a sphere with outward normals has `k1 = k2 = 1 / r`), and the
/// normal is on the side the faces' orientation gives: on the side of the
/// area-weighted vertex normal, which a flipped sliver in a fold of the mesh
/// cannot turn over (Max's weights, which the estimators start from, can);
/// `k1 >= k2`; `d1`, `d2` are unit tangent vectors, orthogonal, with
/// `d1 x d2 = normal`; `d1` is the direction of `k1`. Vertices without an
/// estimate (isolated, degenerate) have zero curvatures; their directions
/// are any tangent basis of the normal, or zero when there is no normal.
#[derive(Debug, Clone, PartialEq, Default)]
#[non_exhaustive]
pub struct CurvatureTensor {
    /// Maximum principal curvature.
    pub k1: Vec<f64>,
    /// Minimum principal curvature.
    pub k2: Vec<f64>,
    /// Unit direction of `k1`.
    pub d1: Vec<DVec3>,
    /// Unit direction of `k2`.
    pub d2: Vec<DVec3>,
    /// The unit normal the tensor lives in the tangent plane of.
    pub normal: Vec<DVec3>,
    /// What each value means (see [`VertexStatus`]).
    pub status: Vec<VertexStatus>,
}

impl CurvatureTensor {
    /// Number of vertices.
    pub fn len(&self) -> usize {
        self.k1.len()
    }

    /// `true` for a mesh without vertices.
    pub fn is_empty(&self) -> bool {
        self.k1.is_empty()
    }

    /// Gaussian curvature `K = k1 k2`, the determinant of the tensor (eq. 2.19). O(V).
    pub fn gaussian(&self) -> Vec<f64> {
        self.k1.iter().zip(&self.k2).map(|(a, b)| a * b).collect()
    }

    /// Mean curvature `H = (k1 + k2) / 2`, half its trace (eq. 2.20). O(V).
    pub fn mean(&self) -> Vec<f64> {
        self.k1.iter().zip(&self.k2).map(|(a, b)| 0.5 * (a + b)).collect()
    }

    /// Shape index `S = (2 / pi) atan2(k1 + k2, k1 - k2)` in [-1, 1]
    /// (Koenderink and van Doorn 1992, oriented so that a convex cap is +1,
    /// a ridge (cylinder) 0.5, a symmetric saddle 0, a valley -0.5 and a cup
    /// -1); 0 at planar points, where it is undefined. O(V).
    pub fn shape_index(&self) -> Vec<f64> {
        self.k1.iter().zip(&self.k2).map(|(&a, &b)| shape_index(a, b)).collect()
    }

    /// Curvedness `C = sqrt((k1^2 + k2^2) / 2)` (Koenderink and van Doorn
    /// 1992): how strongly curved, whatever the shape. O(V).
    pub fn curvedness(&self) -> Vec<f64> {
        self.k1.iter().zip(&self.k2).map(|(&a, &b)| curvedness(a, b)).collect()
    }

    /// The tensor at vertex `v` as a 3x3 symmetric matrix (rows), the shape
    /// operator `k1 d1 d1^T + k2 d2 d2^T` (eq. 2.29-2.31 in ambient
    /// coordinates): `t^T S t` is the normal curvature along a unit tangent
    /// `t` (eq. 2.18). O(1); `None` when `v` is out of range.
    pub fn matrix(&self, v: usize) -> Option<[[f64; 3]; 3]> {
        let (k1, k2, d1, d2) = (*self.k1.get(v)?, self.k2[v], self.d1[v], self.d2[v]);
        let mut m = [[0.0; 3]; 3];
        for (r, row) in m.iter_mut().enumerate() {
            for (c, x) in row.iter_mut().enumerate() {
                *x = k1 * d1[r] * d1[c] + k2 * d2[r] * d2[c];
            }
        }
        Some(m)
    }
}

/// Shape index of one pair of principal curvatures (see
/// [`CurvatureTensor::shape_index`]).
#[inline]
pub fn shape_index(k1: f64, k2: f64) -> f64 {
    let (hi, lo) = if k1 >= k2 { (k1, k2) } else { (k2, k1) };
    if hi == 0.0 && lo == 0.0 {
        return 0.0;
    }
    std::f64::consts::FRAC_2_PI * (hi + lo).atan2(hi - lo)
}

/// Curvedness of one pair of principal curvatures (see
/// [`CurvatureTensor::curvedness`]).
#[inline]
pub fn curvedness(k1: f64, k2: f64) -> f64 {
    (0.5 * (k1 * k1 + k2 * k2)).sqrt()
}

/// The curvature tensor of every vertex (eq. 2.27-2.31) with the chosen
/// estimator: principal curvatures `k1 >= k2` and directions.
///
/// Works on any mesh: boundary vertices get one-sided estimates, non-manifold
/// vertices estimates from all incident faces, and vertices where the
/// estimator has no data (isolated, zero area, too few neighbours for a fit)
/// zeros, each flagged in [`CurvatureTensor::status`]; no value is NaN.
/// Cost O(V + F) for [`TensorMethod::Rusinkiewicz`], O(sum of neighbourhood sizes)
/// for the others; parallel over vertices with the `rayon` feature.
///
/// # Errors
/// `CurvatureError::InvalidOption` (`rings` or `radius`) for an invalid neighbourhood of the normal-cycle
/// method; the errors of the fitting method (`CurvatureError::Mesh` for geometry mesh-kernel refuses).
pub fn curvature_tensor(mesh: &TriMesh, options: &TensorOptions) -> Result<CurvatureTensor> {
    // Fits square and multiply coordinates: estimate in a unit where nothing
    // over- or underflows, then bring the curvatures (1 / length) back.
    let (mesh, unit) = mesh_kernel::units::normalized(mesh);
    let method = match options.method {
        TensorMethod::Fit(fit) => TensorMethod::Fit(FitOptions { neighborhood: fit.neighborhood.in_unit(unit), ..fit }),
        TensorMethod::NormalCycle(nbh) => TensorMethod::NormalCycle(nbh.in_unit(unit)),
        TensorMethod::Rusinkiewicz => TensorMethod::Rusinkiewicz,
    };
    let mut tensor = estimate(&mesh, &TensorOptions { method, ..*options })?;
    for k in tensor.k1.iter_mut().chain(&mut tensor.k2) {
        *k /= unit;
    }
    Ok(tensor)
}

/// [`curvature_tensor`] in the mesh's own unit.
fn estimate(mesh: &TriMesh, options: &TensorOptions) -> Result<CurvatureTensor> {
    let local = match options.method {
        TensorMethod::Fit(fit) => fit::estimate(mesh, options.normals, &fit)?,
        TensorMethod::Rusinkiewicz => rusinkiewicz::estimate(mesh, options.normals),
        TensorMethod::NormalCycle(nbh) => normal_cycle::estimate(mesh, options.normals, nbh.validate()?),
    };
    Ok(assemble(local, mesh.geometry().vertex_normals(NormalWeighting::Area)))
}

/// A tensor in a local frame, as the estimators produce it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LocalTensor {
    /// Unit normal (zero when there is none).
    pub normal: DVec3,
    /// Tangent basis with `t1 x t2 = normal`.
    pub t1: DVec3,
    /// Second tangent.
    pub t2: DVec3,
    /// The second fundamental form in `(t1, t2)`.
    pub form: Sym2,
    /// Status of the vertex.
    pub status: VertexStatus,
}

impl LocalTensor {
    /// A vertex without an estimate: zero form, status `status`, tangent
    /// basis of `normal` (zero when `normal` is zero).
    pub fn empty(normal: DVec3, status: VertexStatus) -> Self {
        let (t1, t2) = if normal == DVec3::ZERO { (DVec3::ZERO, DVec3::ZERO) } else { tangent_basis(normal) };
        Self { normal, t1, t2, form: Sym2::default(), status }
    }

    /// The same tensor seen from the other side: normal reversed, tangents
    /// swapped (so that `t1 x t2` is still the normal), curvatures negated.
    pub fn flipped(self) -> Self {
        let Sym2 { a, b, c } = self.form;
        Self { normal: -self.normal, t1: self.t2, t2: self.t1, form: Sym2::new(-c, -b, -a), status: self.status }
    }

    /// The tensor `form` in the tangent basis of `normal`.
    pub fn new(normal: DVec3, form: Sym2, status: VertexStatus) -> Self {
        let (t1, t2) = tangent_basis(normal);
        Self { normal, t1, t2, form, status }
    }
}

/// Principal curvatures and directions from local tensors, each oriented
/// so that its normal is on the side of `orient` (the area-weighted vertex
/// normals). O(V).
fn assemble(local: Vec<LocalTensor>, orient: &[DVec3]) -> CurvatureTensor {
    let n = local.len();
    let mut out = CurvatureTensor {
        k1: Vec::with_capacity(n),
        k2: Vec::with_capacity(n),
        d1: Vec::with_capacity(n),
        d2: Vec::with_capacity(n),
        normal: Vec::with_capacity(n),
        status: Vec::with_capacity(n),
    };
    for (t, side) in local.into_iter().zip(orient) {
        let t = if t.normal.dot(*side) < 0.0 { t.flipped() } else { t };
        let (mut form, mut status) = (t.form, t.status);
        if !form.is_finite() {
            form = Sym2::default();
            status = VertexStatus::Degenerate;
        }
        let (k1, k2, [c, s]) = form.eigen();
        let d1 = c * t.t1 + s * t.t2;
        out.k1.push(k1);
        out.k2.push(k2);
        out.d1.push(d1);
        out.d2.push(t.normal.cross(d1));
        out.normal.push(t.normal);
        out.status.push(status);
    }
    out
}
