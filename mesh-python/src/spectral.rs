//! Eigenpairs, manifold harmonics, spectral filtering and compression, heat
//! kernel signature (mesh-spectral).

use glam::DVec3;
use mesh_kernel::TriMesh;
use mesh_spectral::{
    compress, filter, heat_kernel_signature as hks, heat_trace, hks_times, ComponentSelection, EigenOptions,
    Eigenpairs, HarmonicsOptions, ManifoldHarmonics, SpectralCompressionPoint, Transfer,
};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{field, mesh_arrays, points, run, vec1, vectors, Arrays, Faces, MeshArrays};
use crate::errors::{Failure, Fallible};
use crate::operators::choice;

fn harmonics_options(laplacian: &str, mass: &str, component: &str, tolerance: f64) -> Fallible<HarmonicsOptions> {
    let eigen = EigenOptions {
        tolerance,
        component: choice::<ComponentSelection>("component", component)?,
        ..EigenOptions::default()
    };
    Ok(HarmonicsOptions { laplacian: choice("laplacian", laplacian)?, mass: choice("mass", mass)?, eigen })
}

/// The eigenvectors as an (n, k) array (Fortran order: one column per pair, copied once).
fn basis<'py>(py: Python<'py>, pairs: &Eigenpairs) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let (n, k) = (pairs.vertex_count(), pairs.len());
    let mut flat = Vec::with_capacity(n * k);
    for j in 0..k {
        flat.extend_from_slice(pairs.vector(j));
    }
    // Columns are contiguous: a (k, n) C array, transposed without a copy.
    let a = flat.into_pyarray(py).reshape([k, n])?;
    Ok(a.transpose()?.cast_into::<PyArray2<f64>>()?)
}

fn mesh_and_harmonics(
    py: Python<'_>,
    arrays: Arrays,
    k: usize,
    options: HarmonicsOptions,
) -> PyResult<(TriMesh, ManifoldHarmonics)> {
    let mesh = run(py, move || arrays.mesh())?;
    let (mesh, mh) = run(py, move || {
        let mh = ManifoldHarmonics::new(&mesh, k, &options)?;
        Ok((mesh, mh))
    })?;
    // Copies of a repeated eigenvalue may be missing: a Python warning.
    if let Some(caveat) = mh.eigenpairs().stats.caveat() {
        PyErr::warn(py, &py.get_type::<pyo3::exceptions::PyUserWarning>(), &std::ffi::CString::new(caveat)?, 1)?;
    }
    Ok((mesh, mh))
}

/// The `k` smallest eigenpairs of `L x = lambda M x`: `(evals (k,), evecs (n, k))`, M-orthonormal.
#[pyfunction]
#[pyo3(signature = (v, f, k, laplacian="auto", mass="voronoi", component="all", tolerance=1e-11))]
pub fn eigenpairs<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    k: usize,
    laplacian: &str,
    mass: &str,
    component: &str,
    tolerance: f64,
) -> PyResult<(Bound<'py, PyArray1<f64>>, Bound<'py, PyArray2<f64>>)> {
    let options = harmonics_options(laplacian, mass, component, tolerance)?;
    let arrays = Arrays::new(&v, &f)?;
    let (_, mh) = mesh_and_harmonics(py, arrays, k, options)?;
    let pairs = mh.eigenpairs();
    Ok((vec1(py, pairs.values.clone()), basis(py, pairs)?))
}

fn point_dict<'py>(py: Python<'py>, p: &SpectralCompressionPoint) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("keep", p.keep)?;
    d.set_item("rms", p.rms)?;
    d.set_item("vertex_rms", p.vertex_rms)?;
    d.set_item("max", p.max)?;
    Ok(d)
}

fn transfer(
    kind: &str,
    keep: Option<usize>,
    cutoff: Option<f64>,
    order: u32,
    band: Option<(f64, f64, f64)>,
) -> Fallible<Transfer> {
    match (kind, keep, cutoff, band) {
        ("keep", Some(keep), None, None) => Ok(Transfer::KeepFirst(keep)),
        ("low-pass" | "low_pass" | "lowpass", None, Some(cutoff), None) => Ok(Transfer::LowPass { cutoff, order }),
        ("band", None, None, Some((low, high, gain))) => Ok(Transfer::Band { low, high, gain }),
        _ => Err(Failure::option(
            "transfer: give kind=\"keep\" with keep=K, kind=\"low-pass\" with cutoff=OMEGA (and order), \
             or kind=\"band\" with band=(low, high, gain)",
        )),
    }
}

/// The manifold-harmonic basis of a mesh (Vallet and Levy 2008), prepared:
/// `k` eigenpairs with the forward and inverse transforms, filtering and
/// compression of the geometry.
#[pyclass(module = "meshkit._meshkit", frozen)]
pub struct Harmonics {
    mesh: TriMesh,
    mh: ManifoldHarmonics,
}

#[pymethods]
impl Harmonics {
    /// Computes the `k` smoothest harmonics of the mesh.
    #[new]
    #[pyo3(signature = (v, f, k, laplacian="auto", mass="voronoi", component="all", tolerance=1e-11))]
    fn new(
        py: Python<'_>,
        v: PyReadonlyArray2<'_, f64>,
        f: Faces<'_>,
        k: usize,
        laplacian: &str,
        mass: &str,
        component: &str,
        tolerance: f64,
    ) -> PyResult<Self> {
        let options = harmonics_options(laplacian, mass, component, tolerance)?;
        let arrays = Arrays::new(&v, &f)?;
        let (mesh, mh) = mesh_and_harmonics(py, arrays, k, options)?;
        Ok(Self { mesh, mh })
    }

    /// Eigenvalues, ascending.
    #[getter]
    fn eigenvalues<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, self.mh.eigenvalues().to_vec())
    }

    /// Frequencies `sqrt(lambda)`.
    #[getter]
    fn frequencies<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, self.mh.frequencies())
    }

    /// The basis, (n, k), M-orthonormal.
    #[getter]
    fn basis<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        basis(py, self.mh.eigenpairs())
    }

    /// The lumped mass the basis is orthonormal for.
    #[getter]
    fn mass<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec1(py, self.mh.mass().to_vec())
    }

    /// Number of harmonics k.
    fn __len__(&self) -> usize {
        self.mh.len()
    }

    /// Coefficients `Phi^T M f` of a per-vertex function.
    fn forward<'py>(&self, py: Python<'py>, values: PyReadonlyArray1<'py, f64>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let values = field(&values, self.mh.vertex_count(), "values")?;
        let c = run(py, || Ok(self.mh.forward(&values)?))?;
        Ok(vec1(py, c))
    }

    /// The function `Phi c` of k coefficients.
    fn inverse<'py>(
        &self,
        py: Python<'py>,
        coefficients: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let c: Vec<f64> = coefficients.as_array().to_vec();
        let f = run(py, || Ok(self.mh.inverse(&c)?))?;
        Ok(vec1(py, f))
    }

    /// Filters the vertex positions (or the (n, 3) `positions` given) with a
    /// transfer function: `kind="keep"` and `keep`, `kind="low-pass"` and
    /// `cutoff` (and `order`), or `kind="band"` and `band=(low, high, gain)`.
    #[pyo3(signature = (kind="low-pass", keep=None, cutoff=None, order=2, band=None, positions=None))]
    fn filter<'py>(
        &self,
        py: Python<'py>,
        kind: &str,
        keep: Option<usize>,
        cutoff: Option<f64>,
        order: u32,
        band: Option<(f64, f64, f64)>,
        positions: Option<PyReadonlyArray2<'py, f64>>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let transfer = transfer(kind, keep, cutoff, order, band)?;
        let input: Vec<DVec3> = match positions {
            Some(p) => vectors(&p, self.mh.vertex_count(), "points")?,
            None => self.mesh.positions().to_vec(),
        };
        let out = run(py, || Ok(filter(&self.mh, &input, &transfer)?))?;
        points(py, out)
    }

    /// Reconstructs the mesh from its first `keep` coefficients: `((V, F), error dict)`.
    fn compress<'py>(&self, py: Python<'py>, keep: usize) -> PyResult<(MeshArrays<'py>, Bound<'py, PyDict>)> {
        let (mesh, point) = run(py, || Ok(compress(&self.mesh, &self.mh, keep)?))?;
        Ok((mesh_arrays(py, mesh)?, point_dict(py, &point)?))
    }

    /// Heat kernel signature at `times` (or `count` log-spaced times over the
    /// range the basis resolves): `(hks (n, T), times (T,))`.
    #[pyo3(signature = (times=None, count=5))]
    fn heat_kernel_signature<'py>(
        &self,
        py: Python<'py>,
        times: Option<Vec<f64>>,
        count: usize,
    ) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<f64>>)> {
        hks_of(py, self.mh.eigenpairs(), times, count)
    }

    /// Heat trace `sum_i exp(-lambda_i t)` (the area-weighted sum of the
    /// signature) at `times` or at the `count` times of the signature:
    /// `(trace (T,), times (T,))`.
    #[pyo3(signature = (times=None, count=5))]
    fn heat_trace<'py>(
        &self,
        py: Python<'py>,
        times: Option<Vec<f64>>,
        count: usize,
    ) -> PyResult<(Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>)> {
        let pairs = self.mh.eigenpairs();
        let (trace, times) = run(py, || {
            let times = times_for(pairs, times, count)?;
            Ok((heat_trace(pairs, &times)?, times))
        })?;
        Ok((vec1(py, trace), vec1(py, times)))
    }
}

/// Most times of a signature or a heat trace (a bound on the allocation).
const MAX_TIMES: usize = 10_000;

/// The given times, or `count` times log-spaced over the range the pairs
/// resolve ([`hks_times`]); at most [`MAX_TIMES`] either way.
fn times_for(pairs: &Eigenpairs, times: Option<Vec<f64>>, count: usize) -> Fallible<Vec<f64>> {
    let n = times.as_ref().map_or(count, Vec::len);
    if n > MAX_TIMES {
        return Err(Failure::option(format!("at most {MAX_TIMES} times, got {n}")));
    }
    Ok(match times {
        Some(t) => t,
        None => hks_times(pairs, count)?,
    })
}

fn hks_of<'py>(
    py: Python<'py>,
    pairs: &Eigenpairs,
    times: Option<Vec<f64>>,
    count: usize,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<f64>>)> {
    let (h, times) = run(py, || {
        let times = times_for(pairs, times, count)?;
        Ok((hks(pairs, &times)?, times))
    })?;
    let (n, t) = (pairs.vertex_count(), times.len());
    let flat: Vec<f64> = h.into_iter().flatten().collect();
    let a = flat.into_pyarray(py).reshape([t, n])?.transpose()?.cast_into::<PyArray2<f64>>()?;
    Ok((a, vec1(py, times)))
}

/// Heat kernel signature from `k` eigenpairs: `(hks (n, T), times (T,))`.
#[pyfunction]
#[pyo3(signature = (v, f, k=100, times=None, count=5, laplacian="auto", mass="voronoi"))]
pub fn heat_kernel_signature<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    k: usize,
    times: Option<Vec<f64>>,
    count: usize,
    laplacian: &str,
    mass: &str,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<f64>>)> {
    let options = harmonics_options(laplacian, mass, "all", EigenOptions::default().tolerance)?;
    let arrays = Arrays::new(&v, &f)?;
    let k = k.min(arrays.vertex_count());
    let (_, mh) = mesh_and_harmonics(py, arrays, k, options)?;
    hks_of(py, mh.eigenpairs(), times, count)
}
