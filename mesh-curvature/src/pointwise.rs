//! Pointwise curvature of a scan, with a flag wherever a value is not an
//! estimate of the surface's curvature.
//!
//! The pointwise Gaussian and mean curvature are those of the curvature
//! tensor, `K = k1 k2` and `H = (k1 + k2) / 2` (eq. 2.19-2.20): they converge
//! on irregular meshes. The discrete values, the angle defect (eq. 2.25) and
//! the cotangent formula (eq. 2.26) divided by the vertex area, do not: on a
//! torus whose grid parameters are jittered by 40% of a step they are off by
//! up to several hundred (README). They are kept beside the tensor's, with
//! their integrated values, the ones for which Gauss-Bonnet holds exactly.
//!
//! A scan also has vertices where no value can be trusted: near-duplicate
//! vertices, zero-area faces, folds and noise below the sampling length.
//! There a value is replaced by 0 and the vertex flagged with the reason
//! ([`CurvatureFlag`]), so a huge number is never presented as a curvature.

use std::fmt;
use std::str::FromStr;

use mesh_kernel::clean::is_degenerate_triangle;
use mesh_kernel::operators::laplacian::DEGENERATE_TOLERANCE;
use mesh_kernel::TriMesh;

use crate::error::{CurvatureError, Result};
use crate::gaussian::{gaussian_curvature, GaussianOptions};
use crate::mean::mean_curvature_with_normals;
use crate::neighborhood::{Adjacency, Gatherer, Neighborhood};
use crate::status::VertexStatus;
use crate::tensor::{curvature_tensor, CurvatureTensor, TensorOptions};
use mesh_kernel::operators::MassKind;
use mesh_kernel::par;

/// Options of [`pointwise_curvature`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointwiseOptions {
    /// The curvature tensor's estimator.
    pub tensor: TensorOptions,
    /// The area dividing the integrated discrete curvature.
    pub area: MassKind,
    /// Resolution limit: a curvature `k` at a vertex of sampling length `h`
    /// ([`sampling_length`]) is flagged [`CurvatureFlag::Unresolved`] when
    /// `|k| h > resolution` (for the Gaussian curvature, `|K| h^2 >
    /// resolution^2`). The default 2 is the largest curvature samples `h`
    /// apart can carry: a circle through the vertex and a sample at distance
    /// `d` has a radius of at least `d / 2` (a chord is at most a diameter).
    /// `f64::INFINITY` turns the test off.
    pub resolution: f64,
}

impl Default for PointwiseOptions {
    fn default() -> Self {
        Self { tensor: TensorOptions::default(), area: MassKind::default(), resolution: 2.0 }
    }
}

/// Why a pointwise value at a vertex is not an estimate of the surface's
/// curvature. Each flagged vertex carries the first reason that applies, in
/// the order of the variants.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum CurvatureFlag {
    /// Referenced by no face.
    Isolated,
    /// Its faces form several fans or share an edge with more than two
    /// faces: no surface to measure.
    NonManifold,
    /// No normal, no area, or no fit (too few or collinear neighbours).
    Degenerate,
    /// The tensor's fit was ill-conditioned on every neighbourhood and degree
    /// tried ([`VertexStatus::IllConditioned`]).
    IllConditioned,
    /// Discrete values only: a face of the 1-ring has zero area (twice its
    /// area at most 1e-12 of its longest edge squared), so its angles and
    /// cotangent weights are undefined (the cotangent Laplacian drops it).
    ZeroAreaFace,
    /// Discrete values only: on the boundary, where the angle defect is the
    /// boundary's geodesic curvature and the Gaussian curvature is 0 by
    /// convention (the tensor gives one-sided estimates there, unflagged).
    Boundary,
    /// The value exceeds the resolution limit of
    /// [`PointwiseOptions::resolution`]: a curvature radius below half the
    /// distance to the samples, which the samples cannot determine (noise,
    /// folds and tiny triangles of a scan, sharp creases).
    Unresolved,
}

impl CurvatureFlag {
    /// Every flag, in order.
    pub const ALL: [Self; 7] = [
        Self::Isolated,
        Self::NonManifold,
        Self::Degenerate,
        Self::IllConditioned,
        Self::ZeroAreaFace,
        Self::Boundary,
        Self::Unresolved,
    ];

    /// Short lowercase name, for reports.
    pub fn name(self) -> &'static str {
        match self {
            Self::Isolated => "isolated",
            Self::NonManifold => "non-manifold",
            Self::Degenerate => "degenerate",
            Self::IllConditioned => "ill-conditioned",
            Self::ZeroAreaFace => "zero-area-face",
            Self::Boundary => "boundary",
            Self::Unresolved => "unresolved",
        }
    }

    /// Numeric code for per-vertex files: 1 + the position in
    /// [`CurvatureFlag::ALL`] (0 stands for "not flagged", see
    /// [`flag_code`]).
    pub fn code(self) -> u8 {
        Self::ALL.iter().position(|f| *f == self).map_or(0, |i| i as u8 + 1)
    }
}

impl fmt::Display for CurvatureFlag {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for CurvatureFlag {
    type Err = CurvatureError;

    fn from_str(s: &str) -> Result<Self> {
        Self::ALL.into_iter().find(|f| f.name() == s).ok_or_else(|| CurvatureError::InvalidOption {
            name: "flag",
            reason: format!("unknown flag `{s}`; known: {}", Self::ALL.map(Self::name).join(", ")),
        })
    }
}

/// The code of an optional flag: 0 when not flagged, else
/// [`CurvatureFlag::code`].
pub fn flag_code(flag: Option<CurvatureFlag>) -> u8 {
    flag.map_or(0, CurvatureFlag::code)
}

/// Number of vertices per flag.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct FlagCounts {
    /// Per flag, in the order of [`CurvatureFlag::ALL`].
    pub by_flag: [usize; 7],
}

impl FlagCounts {
    /// Counts the flags of a slice. O(V).
    pub fn of(flags: &[Option<CurvatureFlag>]) -> Self {
        let mut by_flag = [0; 7];
        for f in flags.iter().flatten() {
            by_flag[f.code() as usize - 1] += 1;
        }
        Self { by_flag }
    }

    /// Vertices with `flag`.
    pub fn get(&self, flag: CurvatureFlag) -> usize {
        self.by_flag[flag.code() as usize - 1]
    }

    /// Flagged vertices.
    pub fn total(&self) -> usize {
        self.by_flag.iter().sum()
    }

    /// `(flag, count)` for every flag with a nonzero count.
    pub fn nonzero(&self) -> impl Iterator<Item = (CurvatureFlag, usize)> + '_ {
        CurvatureFlag::ALL.into_iter().zip(self.by_flag).filter(|(_, c)| *c > 0)
    }
}

/// Everything [`pointwise_curvature`] computes, per vertex.
///
/// Sign convention: curvatures are positive where the surface bends away
/// from its normal, and the normal is the one the faces' orientation gives
/// (counter-clockwise seen from the side it points to). With outward faces
/// (mesh-kernel's shapes, most scans) a sphere of radius `r` has `k1 = k2 = H
/// = 1 / r`, convex regions have `H > 0`, and `mean`, `mean_discrete` and
/// `mean_integrated` share this sign at every vertex: the discrete mean
/// curvature is signed by the tensor's fitted normal. Gaussian curvature
/// does not depend on the orientation.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct PointwiseCurvature {
    /// The curvature tensor (principal curvatures and directions), with
    /// `k1 = k2 = 0` at vertices flagged in [`Self::flag`]; the directions,
    /// normals and estimator status are kept.
    pub tensor: CurvatureTensor,
    /// Gaussian curvature `k1 k2` from the tensor (eq. 2.19); 0 where flagged.
    pub gaussian: Vec<f64>,
    /// Mean curvature `(k1 + k2) / 2` from the tensor (eq. 2.20); 0 where
    /// flagged.
    pub mean: Vec<f64>,
    /// Why the tensor's values of a vertex are not trusted (`None`: they
    /// are). Reasons: isolated, non-manifold, degenerate, ill-conditioned,
    /// unresolved.
    pub flag: Vec<Option<CurvatureFlag>>,
    /// Angle defect divided by the vertex area (eq. 2.25); 0 where
    /// [`Self::flag_discrete`] is set.
    pub gaussian_discrete: Vec<f64>,
    /// Cotangent-formula mean curvature divided by the vertex area
    /// (eq. 2.26); 0 where [`Self::flag_discrete`] is set.
    pub mean_discrete: Vec<f64>,
    /// Why the discrete values of a vertex are not trusted: the tensor's
    /// reasons (isolated, non-manifold, degenerate), a zero-area face in the
    /// 1-ring, the boundary, or a value past the resolution limit (checked
    /// on the discrete values themselves).
    pub flag_discrete: Vec<Option<CurvatureFlag>>,
    /// Integrated Gaussian curvature, the angle defect `2 pi - sum of
    /// angles` (eq. 2.25) at interior vertices, 0 on the boundary and at
    /// non-manifold or isolated vertices; never zeroed by a flag.
    pub gaussian_integrated: Vec<f64>,
    /// Integrated geodesic curvature of the boundary, `pi - sum of angles`
    /// at boundary vertices, 0 elsewhere.
    pub geodesic_integrated: Vec<f64>,
    /// Integrated mean curvature `|(L x)_i| / 2` (eq. 2.26), signed like
    /// `mean`; never zeroed by a flag.
    pub mean_integrated: Vec<f64>,
    /// The vertex areas dividing the discrete values.
    pub area: Vec<f64>,
    /// The sampling length of each vertex ([`sampling_length`]), the length
    /// the resolution limit refers to.
    pub length: Vec<f64>,
    /// How far the rounding of the stored coordinates may have moved a
    /// vertex: the largest [`mesh_kernel::precision::position_noise`] of the
    /// mesh (half a step of single precision, or of the decimal grid of a
    /// text file, at the largest coordinates; 0 for coordinates on no such
    /// grid). The largest, because a vertex's estimate reads its whole
    /// neighbourhood. Curvature estimates carry errors of order `noise /
    /// length^2` from it.
    pub position_noise: f64,
}

impl PointwiseCurvature {
    /// `sum gaussian_integrated + sum geodesic_integrated`, which is `2 pi
    /// chi` to rounding on every manifold mesh (discrete Gauss-Bonnet; see
    /// [`crate::GaussianCurvature::total`]). O(V).
    pub fn gauss_bonnet_total(&self) -> f64 {
        crate::gaussian::compensated_sum(self.gaussian_integrated.iter().chain(&self.geodesic_integrated).copied())
    }

    /// Area-weighted histogram of the [`crate::shape_index`] over `bins`
    /// equal bins of [-1, 1] (first bin: cups, middle: saddles, last: caps),
    /// over the vertices that are not flagged and not planar, each weighted
    /// by its [`Self::area`]. A vertex is planar when its curvedness `c`
    /// times its sampling [`Self::length`] `h` is below
    /// [`PLANAR_CURVEDNESS`], or when `c h^2` is below [`NOISE_CURVEDNESS`]
    /// times its [`Self::position_noise`] (the curvature the rounding of a
    /// single-precision or text file's coordinates can fake): there the
    /// shape index is undefined, and the principal curvatures of a flat
    /// region are rounding noise whose shape index is anything (a grid or
    /// the flat faces of a CAD part would otherwise fill random bins, and
    /// differently after a rotation). The fractions sum to 1 (all 0 when no
    /// vertex counts). It does not depend on the unit of length or on rigid
    /// motions, so it compares meshes of any scale: a global shape
    /// descriptor for datasets. O(V).
    pub fn shape_index_histogram(&self, bins: usize) -> Vec<f64> {
        let mut out = vec![0.0; bins];
        if bins == 0 {
            return out;
        }
        let (k1, k2) = (&self.tensor.k1, &self.tensor.k2);
        for i in 0..self.flag.len() {
            let usable = self.flag[i].is_none() && k1[i].is_finite() && k2[i].is_finite() && self.area[i] > 0.0;
            let (c, h) = (crate::curvedness(k1[i], k2[i]), self.length[i]);
            if !usable || c * h < PLANAR_CURVEDNESS || c * h * h < NOISE_CURVEDNESS * self.position_noise {
                continue;
            }
            let s = crate::shape_index(k1[i], k2[i]);
            let bin = ((s + 1.0) * 0.5 * bins as f64).floor().clamp(0.0, (bins - 1) as f64);
            out[bin as usize] += self.area[i];
        }
        let total: f64 = out.iter().sum();
        if total > 0.0 {
            out.iter_mut().for_each(|b| *b /= total);
        }
        out
    }

    /// Counts of [`Self::flag`]. O(V).
    pub fn flag_counts(&self) -> FlagCounts {
        FlagCounts::of(&self.flag)
    }

    /// Counts of [`Self::flag_discrete`]. O(V).
    pub fn discrete_flag_counts(&self) -> FlagCounts {
        FlagCounts::of(&self.flag_discrete)
    }
}

/// Curvedness times sampling length below which a vertex counts as planar
/// in [`PointwiseCurvature::shape_index_histogram`]: a radius of curvature a
/// million sampling lengths long. Fits on flat regions give curvatures of
/// order 1e-13 / length from rounding in double precision; the least
/// curvature a mesh can resolve is many orders above this. Coordinates
/// stored rounded (single precision, text) carry far more noise; that floor
/// is [`NOISE_CURVEDNESS`].
pub const PLANAR_CURVEDNESS: f64 = 1e-6;

/// Below `NOISE_CURVEDNESS` times the mesh's position noise `d`
/// ([`PointwiseCurvature::position_noise`]), a vertex's curvedness times its
/// sampling length squared (`c h^2`, a height over the neighbourhood)
/// counts as planar in [`PointwiseCurvature::shape_index_histogram`]: the
/// noise of rounded coordinates fakes curvatures of order `d / h^2`.
/// Measured on flat grids (40 and 100 a side) and the flat faces of cubes
/// (10 and 30), rotated, moved up to 500 sizes from the origin or scaled by
/// 1e3 and 1e-3, then rounded to single precision, to `%.6f` or to `%.6e`:
/// the largest `c h^2 / d` of a flat vertex was 3.1. A curvature below 8
/// times the noise is within a factor 3 of what the noise alone gives, so
/// it is not resolved either; spheres and cylinders of 40 segments keep
/// their histograms in every one of those cases but one (a cylinder of
/// radius 1e-3 rounded to 6 decimal places, whose noise is 2% of its edge
/// length: it counts as planar).
pub const NOISE_CURVEDNESS: f64 = 8.0;

/// Pointwise Gaussian and mean curvature of every vertex from the curvature
/// tensor (eq. 2.19-2.20), the discrete values (eq. 2.25, 2.26) beside them,
/// their integrated values, and per-vertex flags where a value is not an
/// estimate of the surface's curvature (see [`CurvatureFlag`]).
///
/// Works on any mesh (scans with zero-area faces, non-manifold edges,
/// several components): every value is finite, flagged values are 0.
/// Cost: that of [`curvature_tensor`] plus O(V + F) for the discrete values
/// and O(sum of 2-ring sizes) for [`sampling_length`]; parallel with the
/// `rayon` feature.
///
/// Errors with [`CurvatureError::InvalidOption`] when `resolution` is not
/// positive (or NaN), and as [`curvature_tensor`] does.
///
/// # Errors
/// `CurvatureError::InvalidOption` (`resolution`) when `resolution` is not positive or is NaN; the errors of
/// [`curvature_tensor`] and [`crate::mean_curvature_with_normals`].
pub fn pointwise_curvature(mesh: &TriMesh, options: &PointwiseOptions) -> Result<PointwiseCurvature> {
    if options.resolution.is_nan() || options.resolution <= 0.0 {
        return Err(CurvatureError::InvalidOption {
            name: "resolution",
            reason: format!("must be positive, got {}", options.resolution),
        });
    }
    let noise = mesh_kernel::precision::position_noise(mesh).into_iter().fold(0.0, f64::max);
    let (mesh, unit) = mesh_kernel::units::normalized(mesh);
    Ok(PointwiseCurvature { position_noise: noise, ..estimate(&mesh, options)?.in_unit(unit) })
}

/// [`pointwise_curvature`] in the mesh's own unit.
fn estimate(mesh: &TriMesh, options: &PointwiseOptions) -> Result<PointwiseCurvature> {
    // Every branch below asks for the connectivity: built here once, not
    // by each branch that finds it missing (`par::init_once`).
    mesh.connectivity();
    let (tensor, (k, (radius, zero_area))) = par::join(
        || curvature_tensor(mesh, &options.tensor),
        || {
            par::join(
                || gaussian_curvature(mesh, &GaussianOptions { area: options.area }),
                || (sampling_length(mesh), touches_zero_area_face(mesh)),
            )
        },
    );
    let (mut tensor, k) = (tensor?, k?);
    let h = mean_curvature_with_normals(mesh, options.area, &tensor.normal)?;
    let limit = options.resolution;
    let n = mesh.vertex_count();

    let flag: Vec<Option<CurvatureFlag>> = (0..n)
        .map(|i| {
            status_flag(tensor.status[i]).or_else(|| {
                let k = tensor.k1[i].abs().max(tensor.k2[i].abs());
                (k * radius[i] > limit).then_some(CurvatureFlag::Unresolved)
            })
        })
        .collect();
    for i in (0..n).filter(|&i| flag[i].is_some()) {
        (tensor.k1[i], tensor.k2[i]) = (0.0, 0.0);
    }
    let (gaussian, mean) = (tensor.gaussian(), tensor.mean());

    let flag_discrete: Vec<Option<CurvatureFlag>> = (0..n)
        .map(|i| {
            let structural = [k.status[i], h.status[i]].into_iter().find_map(status_flag);
            structural
                .or_else(|| zero_area[i].then_some(CurvatureFlag::ZeroAreaFace))
                .or_else(|| (k.status[i] == VertexStatus::Boundary).then_some(CurvatureFlag::Boundary))
                .or_else(|| {
                    let r = radius[i];
                    let past = k.pointwise[i].abs() * r * r > limit * limit || h.pointwise[i].abs() * r > limit;
                    past.then_some(CurvatureFlag::Unresolved)
                })
        })
        .collect();
    let zero_flagged = |values: Vec<f64>| -> Vec<f64> {
        values.into_iter().zip(&flag_discrete).map(|(v, f)| if f.is_some() { 0.0 } else { v }).collect()
    };
    let gaussian_discrete = zero_flagged(k.pointwise);
    let mean_discrete = zero_flagged(h.pointwise);
    Ok(PointwiseCurvature {
        tensor,
        gaussian,
        mean,
        flag,
        gaussian_discrete,
        mean_discrete,
        flag_discrete,
        gaussian_integrated: k.integrated,
        geodesic_integrated: k.geodesic,
        mean_integrated: h.integrated,
        area: k.area,
        length: radius,
        position_noise: 0.0,
    })
}

impl PointwiseCurvature {
    /// The values of a mesh divided by `unit`, for the mesh itself.
    fn in_unit(mut self, unit: f64) -> Self {
        // One factor at a time: 0 times an overflowed square would be NaN.
        let per_length = self.tensor.k1.iter_mut().chain(&mut self.tensor.k2).chain(&mut self.mean);
        per_length.chain(&mut self.mean_discrete).for_each(|x| *x /= unit);
        self.gaussian.iter_mut().chain(&mut self.gaussian_discrete).for_each(|x| *x = *x / unit / unit);
        self.mean_integrated.iter_mut().chain(&mut self.length).for_each(|x| *x *= unit);
        self.area.iter_mut().for_each(|x| *x = *x * unit * unit);
        self
    }
}

/// The flag of an estimator status (`None` for valid and boundary
/// vertices, whose values are estimates).
fn status_flag(status: VertexStatus) -> Option<CurvatureFlag> {
    match status {
        VertexStatus::Valid | VertexStatus::Boundary => None,
        VertexStatus::Isolated => Some(CurvatureFlag::Isolated),
        VertexStatus::NonManifold => Some(CurvatureFlag::NonManifold),
        VertexStatus::Degenerate => Some(CurvatureFlag::Degenerate),
        VertexStatus::IllConditioned => Some(CurvatureFlag::IllConditioned),
    }
}

/// A neighbour closer to a vertex than this fraction of the root-mean-square
/// distance to its 2-ring is a near-duplicate of it at the scale of the
/// neighbourhood (see [`sampling_length`]). On a well-shaped mesh the
/// nearest 2-ring vertex lies at about 0.55 of that distance (icosphere),
/// at least 0.098 on a torus whose grid is jittered by 40% of a step; a
/// marching-cubes scan puts 17% of its vertices (full Stanford dragon)
/// within 0.05 of a neighbour. A near-duplicate only makes the resolution
/// limit less strict, never stricter: a fifth keeps the limit meaningful
/// where a scan packs vertices a few hundredths of an edge apart (with 0.05
/// or 0.1, 16 and 8 of the dragon's vertices keep values beyond what the
/// edges around them, measured against the scan's median edge, support).
pub const NEAR_DUPLICATE: f64 = 0.2;

/// The sampling length of every vertex: the distance to the nearest vertex
/// of its 2-ring that is not a near-duplicate, i.e. not closer than
/// [`NEAR_DUPLICATE`] times the root-mean-square distance to the 2-ring
/// (0 for isolated vertices). About one edge length on a regular mesh; on a
/// scan, where marching cubes leaves vertices a hundredth of an edge apart,
/// those do not count: two samples that close say nothing about curvature
/// at the scale of the neighbourhood, only about the scan's noise.
/// O(sum of 2-ring sizes), parallel over vertices.
pub fn sampling_length(mesh: &TriMesh) -> Vec<f64> {
    let (mesh, unit) = mesh_kernel::units::normalized(mesh);
    let mut length = sampling_length_in_unit(&mesh);
    length.iter_mut().for_each(|x| *x *= unit);
    length
}

/// [`sampling_length`] in the mesh's own unit.
fn sampling_length_in_unit(mesh: &TriMesh) -> Vec<f64> {
    let adj = Adjacency::new(mesh);
    let p = mesh.positions();
    par::map_with(mesh.vertex_count(), Gatherer::default, |g, i| {
        g.gather(&adj, p, i, Neighborhood::Rings(2));
        let ring = g.vertices.get(1..).unwrap_or(&[]);
        if ring.is_empty() {
            return 0.0;
        }
        let d2 = |q: &u32| p[*q as usize].distance_squared(p[i]);
        let mean2 = ring.iter().map(d2).sum::<f64>() / ring.len() as f64;
        let near2 = NEAR_DUPLICATE * NEAR_DUPLICATE * mean2;
        ring.iter().map(d2).filter(|x| *x >= near2).fold(f64::INFINITY, f64::min).sqrt()
    })
}

/// `true` for the vertices of a zero-area face (the cotangent Laplacian's
/// test, `mesh_kernel::operators::laplacian::DEGENERATE_TOLERANCE`). O(F).
fn touches_zero_area_face(mesh: &TriMesh) -> Vec<bool> {
    let p = mesh.positions();
    let mut out = vec![false; mesh.vertex_count()];
    for face in mesh.faces() {
        let tri = face.map(|v| p[v as usize]);
        if is_degenerate_triangle(tri, DEGENERATE_TOLERANCE) {
            for v in face {
                out[*v as usize] = true;
            }
        }
    }
    out
}
