//! Manifold harmonics (Vallet and Levy 2008, "Spectral geometry processing
//! with manifold harmonics"): the M-orthonormal eigenvectors `phi_i` of
//! `L phi = lambda M phi` are the surface analogue of Fourier modes, with
//! frequency `omega_i = sqrt(lambda_i)`.
//!
//! - forward transform (analysis): `c_i = <f, phi_i>_M = sum_v phi_i(v) m_v f(v)`,
//!   i.e. `c = Phi^T M f`;
//! - inverse transform (synthesis): `f = sum_i c_i phi_i = Phi c`.
//!
//! With all n pairs the two are inverse to each other; with the k smallest,
//! synthesis after analysis is the M-orthogonal projection onto the k
//! smoothest modes (the best approximation in the area-weighted L2 norm).

use faer::{Accum, Mat, MatRef};
use glam::DVec3;
use mesh_kernel::solver::FillOrdering;
use mesh_kernel::TriMesh;
use sprs::CsMat;

use crate::eigen::{eigenpairs, tall, ComponentSelection, EigenOptions, Eigenpairs};
use crate::error::{Result, SpectralError};
use mesh_kernel::operators::{LaplacianKind, MassKind};

use crate::operators::{laplace_beltrami, pencil, OperatorInfo};

/// Options of [`ManifoldHarmonics::new`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct HarmonicsOptions {
    /// Laplacian discretization (`Auto`: intrinsic Delaunay when the mesh
    /// has zero-area faces).
    pub laplacian: LaplacianKind,
    /// Lumped mass.
    pub mass: MassKind,
    /// Eigensolver options; with `component: Largest` the basis lives on
    /// the mesh's largest connected component (most faces) and is zero on
    /// the other vertices.
    pub eigen: EigenOptions,
}

/// The manifold-harmonic basis of a mesh: `k` eigenpairs and the mass they
/// are orthonormal for, with the transforms.
#[derive(Debug, Clone)]
pub struct ManifoldHarmonics {
    pairs: Eigenpairs,
    mass: Vec<f64>,
    info: Option<OperatorInfo>,
}

impl ManifoldHarmonics {
    /// The `k` smoothest harmonics of `mesh` (see [`crate::eigenpairs`] for
    /// the cost), on the whole mesh or, with
    /// [`ComponentSelection::Largest`], on its largest connected component
    /// (cut out with `TriMesh::largest_component`, so the operator is only
    /// assembled there; the harmonics are zero elsewhere). Errors: empty
    /// mesh, `k` above the number of vertices with mass, solver failures.
    ///
    /// # Errors
    /// `SpectralError::Mesh` (`MeshError::Empty`) for a mesh without faces; the errors of
    /// [`crate::laplace_beltrami`] and [`crate::eigenpairs`] (`SpectralError::TooManyPairs`,
    /// `SpectralError::NotConverged`, ...); `SpectralError::InvalidOption` (`component`) for an invalid
    /// component choice.
    pub fn new(mesh: &TriMesh, k: usize, options: &HarmonicsOptions) -> Result<Self> {
        let largest = options.eigen.component == ComponentSelection::Largest;
        if largest && mesh.connectivity().components().count > 1 {
            let piece = mesh.largest_component()?;
            let inner = Self::solve(&piece.mesh, k, options)?;
            let rows: Vec<usize> = piece.vertices.iter().map(|v| v.idx()).collect();
            let n = mesh.vertex_count();
            let mass = piece.scatter(&inner.mass, n, 0.0)?;
            let pairs = inner.pairs.scatter(&rows, n)?;
            return Ok(Self { pairs, mass, info: inner.info });
        }
        Self::solve(mesh, k, options)
    }

    fn solve(mesh: &TriMesh, k: usize, options: &HarmonicsOptions) -> Result<Self> {
        // Assembled in a unit where no area over- or underflows; the masses
        // carry the unit squared back (and the eigenpairs follow them).
        let (mesh, unit) = mesh_kernel::units::normalized(mesh);
        let p = pencil(&mesh, options.laplacian, options.mass)?;
        let mass: Vec<f64> = p.mass.iter().map(|m| m * unit * unit).collect();
        if mass.iter().zip(&p.mass).any(|(m, inner)| !m.is_finite() || (*m == 0.0 && *inner > 0.0)) {
            return Err(SpectralError::InvalidMatrix {
                name: "M",
                reason: format!(
                    "the vertex areas of a mesh of size about {unit:.1e} are outside the range of double precision; \
                     rescale the mesh"
                ),
            });
        }
        let ordering =
            Some(options.eigen.ordering.clone().unwrap_or_else(|| FillOrdering::of_points(mesh.positions())));
        let eigen = EigenOptions { ordering, ..options.eigen.clone() };
        let pairs = eigenpairs(&p.laplacian, &mass, k, &eigen)?;
        Ok(Self { pairs, mass, info: Some(p.info) })
    }

    /// A basis from eigenpairs computed elsewhere (for instance with
    /// [`crate::eigenpairs`] on custom matrices) and the diagonal of the mass
    /// matrix they are orthonormal for.
    ///
    /// # Errors
    /// `SpectralError::Dimension` when `mass` does not have one entry per row of the eigenvectors;
    /// `SpectralError::InvalidMatrix` (`M`) for a mass that is negative or not finite.
    pub fn from_eigenpairs(pairs: Eigenpairs, mass: Vec<f64>) -> Result<Self> {
        if mass.len() != pairs.vertex_count() {
            return Err(SpectralError::Dimension(format!(
                "{} masses for eigenvectors of length {}",
                mass.len(),
                pairs.vertex_count()
            )));
        }
        if let Some(bad) = mass.iter().find(|m| !(m.is_finite() && **m >= 0.0)) {
            return Err(SpectralError::InvalidMatrix { name: "M", reason: format!("mass {bad}") });
        }
        Ok(Self { pairs, mass, info: None })
    }

    /// Which Laplacian was built, why, and on how many vertices (`None` for
    /// [`ManifoldHarmonics::from_eigenpairs`]).
    pub fn operator_info(&self) -> Option<&OperatorInfo> {
        self.info.as_ref()
    }

    /// The mass diagonal and the Laplacian of `mesh` for the given options,
    /// as used by [`ManifoldHarmonics::new`] (to compute pairs yourself).
    ///
    /// # Errors
    /// `SpectralError::Mesh` (`MeshError::Empty`) for a mesh without faces; the errors of the intrinsic
    /// Delaunay triangulation when it is chosen; `SpectralError::InvalidMatrix` for masses that are not
    /// positive and finite.
    pub fn operators(mesh: &TriMesh, options: &HarmonicsOptions) -> Result<(CsMat<f64>, Vec<f64>)> {
        laplace_beltrami(mesh, options.laplacian, options.mass)
    }

    /// Number of harmonics k.
    pub fn len(&self) -> usize {
        self.pairs.len()
    }

    /// `true` when there is no harmonic.
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.mass.len()
    }

    /// The eigenpairs (values ascending, vectors M-orthonormal).
    pub fn eigenpairs(&self) -> &Eigenpairs {
        &self.pairs
    }

    /// Eigenvalues `lambda_i`, ascending.
    pub fn eigenvalues(&self) -> &[f64] {
        &self.pairs.values
    }

    /// Frequencies `omega_i = sqrt(max(lambda_i, 0))`.
    pub fn frequencies(&self) -> Vec<f64> {
        self.pairs.values.iter().map(|l| l.max(0.0).sqrt()).collect()
    }

    /// Lumped mass of each vertex.
    pub fn mass(&self) -> &[f64] {
        &self.mass
    }

    /// Harmonic `i` as a per-vertex field.
    ///
    /// # Panics
    /// If `i >= self.len()`.
    pub fn harmonic(&self, i: usize) -> &[f64] {
        self.pairs.vector(i)
    }

    /// Forward transform of a scalar field: `c = Phi^T M f` (k values).
    /// O(n k).
    ///
    /// # Errors
    /// `SpectralError::Dimension` when `f` does not have one value per vertex; `SpectralError::InvalidOption`
    /// (`field`) for a non-finite value.
    pub fn forward(&self, f: &[f64]) -> Result<Vec<f64>> {
        let c = self.forward_columns(self.field(f)?.as_ref())?;
        Ok(c.col_as_slice(0).to_vec())
    }

    /// Inverse transform: `f = sum_i c_i phi_i` for the first
    /// `coefficients.len() <= k` harmonics. O(n k).
    ///
    /// # Errors
    /// `SpectralError::Dimension` when there are more coefficients than harmonics;
    /// `SpectralError::InvalidOption` (`coefficients`) for a non-finite value.
    pub fn inverse(&self, coefficients: &[f64]) -> Result<Vec<f64>> {
        let c = MatRef::from_column_major_slice(coefficients, coefficients.len(), 1);
        let f = self.inverse_columns(c)?;
        Ok(f.col_as_slice(0).to_vec())
    }

    /// Forward transform of the geometry (or any vector field): one
    /// coefficient vector per harmonic, `c_i = sum_v phi_i(v) m_v p_v`.
    ///
    /// # Errors
    /// `SpectralError::Dimension` when `points` does not have one entry per vertex;
    /// `SpectralError::InvalidOption` (`points`) for a non-finite point.
    pub fn forward_points(&self, points: &[DVec3]) -> Result<Vec<DVec3>> {
        let c = self.forward_columns(self.points(points)?.as_ref())?;
        Ok((0..c.nrows()).map(|i| DVec3::new(c[(i, 0)], c[(i, 1)], c[(i, 2)])).collect())
    }

    /// Inverse transform of vector coefficients: `p = sum_i c_i phi_i` over
    /// the first `coefficients.len() <= k` harmonics.
    ///
    /// # Errors
    /// `SpectralError::Dimension` when there are more coefficients than harmonics;
    /// `SpectralError::InvalidOption` (`coefficients`) for a non-finite value.
    pub fn inverse_points(&self, coefficients: &[DVec3]) -> Result<Vec<DVec3>> {
        let c = Mat::from_fn(coefficients.len(), 3, |i, j| coefficients[i][j]);
        let p = self.inverse_columns(c.as_ref())?;
        Ok((0..p.nrows()).map(|v| DVec3::new(p[(v, 0)], p[(v, 1)], p[(v, 2)])).collect())
    }

    fn field(&self, f: &[f64]) -> Result<Mat<f64>> {
        self.check_len(f.len())?;
        if let Some(bad) = f.iter().find(|x| !x.is_finite()) {
            return Err(SpectralError::InvalidOption { name: "field", reason: format!("non-finite value {bad}") });
        }
        Ok(Mat::from_fn(f.len(), 1, |i, _| f[i]))
    }

    fn points(&self, p: &[DVec3]) -> Result<Mat<f64>> {
        self.check_len(p.len())?;
        if let Some(bad) = p.iter().find(|x| !x.is_finite()) {
            return Err(SpectralError::InvalidOption { name: "points", reason: format!("non-finite point {bad}") });
        }
        Ok(Mat::from_fn(p.len(), 3, |i, j| p[i][j]))
    }

    fn check_len(&self, len: usize) -> Result<()> {
        if len != self.vertex_count() {
            return Err(SpectralError::Dimension(format!("{len} values for {} vertices", self.vertex_count())));
        }
        Ok(())
    }

    /// `Phi^T M F` for the columns of `f` (n x c).
    pub(crate) fn forward_columns(&self, f: MatRef<'_, f64>) -> Result<Mat<f64>> {
        self.check_len(f.nrows())?;
        // M f carries the unit of length cubed for positions: form it from
        // the mass and values divided by powers of two near their sizes, and
        // bring the factors back one at a time.
        let mass_unit = mesh_kernel::units::unit_of(self.mass.iter().copied());
        let value_unit = mesh_kernel::units::unit_of((0..f.ncols()).flat_map(|j| f.col(j).iter().copied()));
        let mf = Mat::from_fn(f.nrows(), f.ncols(), |i, j| (self.mass[i] / mass_unit) * (f[(i, j)] / value_unit));
        let mut c = Mat::zeros(self.len(), f.ncols());
        tall::gram(c.as_mut(), self.pairs.vectors(), mf.as_ref());
        for j in 0..c.ncols() {
            c.col_mut(j).iter_mut().for_each(|x| *x = *x * mass_unit * value_unit);
        }
        Ok(c)
    }

    /// `Phi_[:, ..r] C` for the rows of `c` (r x c, r <= k).
    pub(crate) fn inverse_columns(&self, c: MatRef<'_, f64>) -> Result<Mat<f64>> {
        let r = c.nrows();
        if r > self.len() {
            return Err(SpectralError::Dimension(format!("{r} coefficients for {} harmonics", self.len())));
        }
        if (0..c.ncols()).any(|j| c.col(j).iter().any(|x| !x.is_finite())) {
            return Err(SpectralError::InvalidOption { name: "coefficients", reason: "non-finite value".into() });
        }
        let mut f = Mat::zeros(self.vertex_count(), c.ncols());
        tall::mul(f.as_mut(), Accum::Replace, self.pairs.vectors().subcols(0, r), c, 1.0);
        Ok(f)
    }
}
