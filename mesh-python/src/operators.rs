//! Discrete operators, normals and curvature (mesh-kernel, mesh-curvature).

use mesh_curvature::{
    curvature_tensor, gaussian_curvature as gaussian, mean_curvature as mean, pointwise_curvature, GaussianOptions,
    MeanOptions, PointwiseOptions, TensorMethod, TensorOptions,
};
use mesh_kernel::geometry::{self, NormalWeighting};
use mesh_kernel::operators::{self, IntrinsicOptions, IntrinsicTriangulation, MassKind};
use numpy::{PyArray1, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;

use crate::convert::{csr, points, run, vec1, Arrays, Csr, Faces};
use crate::errors::{Failure, Fallible};

/// Parses a named choice (`"voronoi"`, `"mean-value"`, ...); `_` stands for `-`.
pub fn choice<T: std::str::FromStr>(what: &str, name: &str) -> Fallible<T>
where
    T::Err: std::fmt::Display,
{
    name.replace('_', "-").parse().map_err(|e: T::Err| Failure::option(format!("{what}: {e}")))
}

/// The cotangent Laplacian, positive semi-definite (`-igl.cotmatrix`), as CSR arrays.
#[pyfunction]
pub fn cotan_laplacian<'py>(py: Python<'py>, v: PyReadonlyArray2<'py, f64>, f: Faces<'py>) -> PyResult<Csr<'py>> {
    let arrays = Arrays::new(&v, &f)?;
    let l = run(py, move || Ok(operators::cotan_laplacian(&arrays.mesh()?)))?;
    Ok(csr(py, l))
}

/// The graph Laplacian `D - A` (eq. 2.12 unnormalized), as CSR arrays.
#[pyfunction]
pub fn uniform_laplacian<'py>(py: Python<'py>, v: PyReadonlyArray2<'py, f64>, f: Faces<'py>) -> PyResult<Csr<'py>> {
    let arrays = Arrays::new(&v, &f)?;
    let l = run(py, move || Ok(operators::uniform_laplacian(&arrays.mesh()?)))?;
    Ok(csr(py, l))
}

/// The vertex adjacency matrix (1 per edge), as CSR arrays.
#[pyfunction]
pub fn adjacency_matrix<'py>(py: Python<'py>, v: PyReadonlyArray2<'py, f64>, f: Faces<'py>) -> PyResult<Csr<'py>> {
    let arrays = Arrays::new(&v, &f)?;
    let a = run(py, move || Ok(operators::adjacency_matrix(&arrays.mesh()?)))?;
    Ok(csr(py, a))
}

/// The per-face gradient (3F x V), as CSR arrays.
#[pyfunction]
pub fn gradient<'py>(py: Python<'py>, v: PyReadonlyArray2<'py, f64>, f: Faces<'py>) -> PyResult<Csr<'py>> {
    let arrays = Arrays::new(&v, &f)?;
    let g = run(py, move || Ok(operators::gradient(&arrays.mesh()?)))?;
    Ok(csr(py, g))
}

/// The integrated divergence (V x 3F), as CSR arrays.
#[pyfunction]
pub fn divergence<'py>(py: Python<'py>, v: PyReadonlyArray2<'py, f64>, f: Faces<'py>) -> PyResult<Csr<'py>> {
    let arrays = Arrays::new(&v, &f)?;
    let d = run(py, move || Ok(operators::divergence(&arrays.mesh()?)))?;
    Ok(csr(py, d))
}

/// The mass matrix of `kind` (`voronoi`, `barycentric`, `galerkin`), as CSR arrays.
#[pyfunction]
#[pyo3(signature = (v, f, kind="voronoi"))]
pub fn mass_matrix<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    kind: &str,
) -> PyResult<Csr<'py>> {
    let kind: MassKind = choice("kind", kind)?;
    let arrays = Arrays::new(&v, &f)?;
    let m = run(py, move || Ok(operators::mass_matrix(&arrays.mesh()?, kind)))?;
    Ok(csr(py, m))
}

/// The lumped (diagonal) mass of `kind` as a vector.
#[pyfunction]
#[pyo3(signature = (v, f, kind="voronoi"))]
pub fn lumped_mass<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    kind: &str,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let kind: MassKind = choice("kind", kind)?;
    let arrays = Arrays::new(&v, &f)?;
    let m = run(py, move || Ok(operators::lumped_mass(&arrays.mesh()?, kind)))?;
    Ok(vec1(py, m))
}

/// The Laplacian of the intrinsic Delaunay triangulation of the mollified
/// mesh and its lumped barycentric mass: `(L, M)` as CSR arrays and a vector.
#[pyfunction]
#[pyo3(signature = (v, f, mollify=1e-6))]
pub fn intrinsic_delaunay_laplacian<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    mollify: f64,
) -> PyResult<(Csr<'py>, Bound<'py, PyArray1<f64>>)> {
    let arrays = Arrays::new(&v, &f)?;
    let (l, m) = run(py, move || {
        let mesh = arrays.mesh()?;
        let t = IntrinsicTriangulation::delaunay(&mesh, &IntrinsicOptions { mollify, ..Default::default() })?;
        Ok((t.cotan_laplacian(), t.barycentric_mass()))
    })?;
    Ok((csr(py, l), vec1(py, m)))
}

/// Unit vertex normals, averaged with `weighting` (`area`, `angle`, `uniform`, `max`).
#[pyfunction]
#[pyo3(signature = (v, f, weighting="area"))]
pub fn vertex_normals<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    weighting: &str,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let weighting: NormalWeighting = choice("weighting", weighting)?;
    let arrays = Arrays::new(&v, &f)?;
    let n = run(py, move || Ok(geometry::vertex_normals(&arrays.mesh()?, weighting)))?;
    points(py, n)
}

/// Unit face normals (zero for zero-area faces).
#[pyfunction]
pub fn face_normals<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let arrays = Arrays::new(&v, &f)?;
    let n = run(py, move || Ok(geometry::face_normals(&arrays.mesh()?)))?;
    points(py, n)
}

/// Face areas.
#[pyfunction]
pub fn face_areas<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let arrays = Arrays::new(&v, &f)?;
    let a = run(py, move || Ok(geometry::face_areas(&arrays.mesh()?)))?;
    Ok(vec1(py, a))
}

/// Gaussian curvature by angle defect: pointwise (divided by the `area`
/// of `kind`) or integrated; 0 off the interior.
#[pyfunction]
#[pyo3(signature = (v, f, area="voronoi", integrated=false))]
pub fn gaussian_curvature<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    area: &str,
    integrated: bool,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let area: MassKind = choice("area", area)?;
    let arrays = Arrays::new(&v, &f)?;
    let k = run(py, move || -> Fallible<_> {
        let k = gaussian(&arrays.mesh()?, &GaussianOptions { area })?;
        Ok(if integrated { k.integrated } else { k.pointwise })
    })?;
    Ok(vec1(py, k))
}

/// Mean curvature `H = (k1 + k2) / 2` from the cotangent Laplacian, signed
/// by the vertex normal (positive on a sphere); pointwise or integrated.
#[pyfunction]
#[pyo3(signature = (v, f, area="voronoi", normals="area", integrated=false))]
pub fn mean_curvature<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    area: &str,
    normals: &str,
    integrated: bool,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let options = MeanOptions { area: choice("area", area)?, normals: choice("normals", normals)? };
    let arrays = Arrays::new(&v, &f)?;
    let h = run(py, move || -> Fallible<_> {
        let h = mean(&arrays.mesh()?, &options)?;
        Ok(if integrated { h.integrated } else { h.pointwise })
    })?;
    Ok(vec1(py, h))
}

/// `(k1, k2, d1, d2)`: principal curvatures `k1 >= k2` and unit directions
/// by the estimator `method` (`fit`, `quadric`, `rusinkiewicz`, `normal-cycle`).
#[pyfunction]
#[pyo3(signature = (v, f, method="fit"))]
pub fn principal_curvature<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    method: &str,
) -> PyResult<(
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<f64>>,
)> {
    let method: TensorMethod = choice("method", method)?;
    let arrays = Arrays::new(&v, &f)?;
    let t = run(py, move || -> Fallible<_> {
        Ok(curvature_tensor(&arrays.mesh()?, &TensorOptions { method, ..Default::default() })?)
    })?;
    Ok((vec1(py, t.k1), vec1(py, t.k2), points(py, t.d1)?, points(py, t.d2)?))
}

/// Most bins of [`shape_index_histogram`] (a bound on the allocation).
const MAX_BINS: usize = 1 << 20;

/// Area-weighted histogram of the shape index over `bins` bins of [-1, 1],
/// from the pointwise curvature (quartic fit), flagged and planar vertices
/// left out: `PointwiseCurvature::shape_index_histogram`, as `mesh batch`.
#[pyfunction]
#[pyo3(signature = (v, f, bins=16))]
pub fn shape_index_histogram<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    bins: usize,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    if !(1..=MAX_BINS).contains(&bins) {
        return Err(Failure::option(format!("bins must be in 1..={MAX_BINS}, got {bins}")).into());
    }
    let arrays = Arrays::new(&v, &f)?;
    let h = run(py, move || -> Fallible<_> {
        Ok(pointwise_curvature(&arrays.mesh()?, &PointwiseOptions::default())?.shape_index_histogram(bins))
    })?;
    Ok(vec1(py, h))
}
