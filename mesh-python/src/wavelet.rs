//! Subdivision and wavelets (mesh-wavelet).

use mesh_wavelet::{
    subdivide as refine, CompressOptions, LevelStatistics, MultiresOptions, Multiresolution as Mr, Scheme,
    SubdivideOptions, WaveletKind,
};
use numpy::{PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{mesh_arrays, points, run, vectors, Arrays, Faces, MeshArrays};
use crate::errors::Fallible;
use crate::operators::choice;

/// `levels` rounds of 4-to-1 subdivision with `scheme` (`loop`, `midpoint`, `butterfly`).
#[pyfunction]
#[pyo3(signature = (v, f, levels=1, scheme="loop"))]
pub fn subdivide<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    levels: usize,
    scheme: &str,
) -> PyResult<MeshArrays<'py>> {
    let scheme: Scheme = choice("scheme", scheme)?;
    let arrays = Arrays::new(&v, &f)?;
    let mesh = run(py, move || arrays.mesh())?;
    let out = run(py, move || Ok(refine(&mesh, &SubdivideOptions { scheme, levels })?))?;
    mesh_arrays(py, out)
}

/// `loop_subdivide(V, F, levels)`: Loop subdivision (Loop 1987), timed on the
/// Rust side: `((V, F), seconds)`, the seconds covering the subdivision
/// alone (mesh validation excluded), so that the binding's overhead can be
/// measured.
#[pyfunction]
pub fn loop_subdivide_timed<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    levels: usize,
) -> PyResult<(MeshArrays<'py>, f64)> {
    let arrays = Arrays::new(&v, &f)?;
    let mesh = run(py, move || arrays.mesh())?;
    let (out, seconds) = run(py, move || {
        let start = std::time::Instant::now();
        let out = refine(&mesh, &SubdivideOptions { scheme: Scheme::Loop, levels })?;
        Ok((out, start.elapsed().as_secs_f64()))
    })?;
    Ok((mesh_arrays(py, out)?, seconds))
}

fn stats_dict<'py>(py: Python<'py>, s: &LevelStatistics) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("level", s.level)?;
    d.set_item("count", s.count)?;
    d.set_item("mean", s.mean)?;
    d.set_item("rms", s.rms)?;
    d.set_item("max", s.max)?;
    Ok(d)
}

/// The wavelet decomposition of a semi-regular mesh (Lounsbery, DeRose and
/// Warren): a base mesh and one level of coefficients per subdivision.
/// Vertices are numbered hierarchically (the base mesh's first), so the
/// meshes it returns may number the input's vertices differently.
#[pyclass(module = "meshkit._meshkit")]
pub struct Multiresolution {
    mr: Mr,
}

#[pymethods]
impl Multiresolution {
    /// Analyzes a mesh with subdivision connectivity (detected): `scheme`
    /// (`midpoint`, `loop`, `butterfly`) and `wavelet` (`lifted`, `lazy`).
    #[new]
    #[pyo3(signature = (v, f, scheme="midpoint", wavelet="lifted", max_levels=None))]
    fn new(
        py: Python<'_>,
        v: PyReadonlyArray2<'_, f64>,
        f: Faces<'_>,
        scheme: &str,
        wavelet: &str,
        max_levels: Option<usize>,
    ) -> PyResult<Self> {
        let mut options = MultiresOptions {
            scheme: choice::<Scheme>("scheme", scheme)?,
            wavelet: choice::<WaveletKind>("wavelet", wavelet)?,
            ..Default::default()
        };
        if let Some(m) = max_levels {
            options.max_levels = m;
        }
        let arrays = Arrays::new(&v, &f)?;
        let mesh = run(py, move || arrays.mesh())?;
        let mr = run(py, move || Ok(Mr::analyze(&mesh, &options)?))?;
        Ok(Self { mr })
    }

    /// Number of levels J (the finest mesh is level J, the base level 0).
    #[getter]
    fn levels(&self) -> usize {
        self.mr.levels()
    }

    /// The mesh of `level` (0 = base, `levels` = the full mesh) as `(V, F)`.
    fn level<'py>(&self, py: Python<'py>, level: usize) -> PyResult<MeshArrays<'py>> {
        let mesh = run(py, || Ok(self.mr.level(level)?))?;
        mesh_arrays(py, mesh)
    }

    /// Synthesis: the full mesh from the base and the coefficients, `(V, F)`.
    fn synthesize<'py>(&self, py: Python<'py>) -> PyResult<MeshArrays<'py>> {
        let mesh = run(py, || Ok(self.mr.synthesize()?))?;
        mesh_arrays(py, mesh)
    }

    /// The base positions (n0, 3).
    #[getter]
    fn base_positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        points(py, self.mr.base_positions().to_vec())
    }

    /// Replaces the base positions (multiresolution editing).
    #[setter]
    fn set_base_positions(&mut self, positions: PyReadonlyArray2<'_, f64>) -> PyResult<()> {
        let n = self.mr.base_positions().len();
        let p = vectors(&positions, n, "base_positions")?;
        self.mr.set_base_positions(&p).map_err(|e| crate::errors::Failure::from(e).into())
    }

    /// The wavelet coefficients of `level` (0 <= level < levels), one 3-vector per new vertex.
    fn coefficients<'py>(&self, py: Python<'py>, level: usize) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let c = self.mr.coefficients(level).map_err(crate::errors::Failure::from)?;
        points(py, c.to_vec())
    }

    /// Replaces the coefficients of `level`.
    fn set_coefficients(&mut self, level: usize, values: PyReadonlyArray2<'_, f64>) -> PyResult<()> {
        let target = self.mr.coefficients_mut(level).map_err(crate::errors::Failure::from)?;
        let v = vectors(&values, target.len(), "coefficients")?;
        target.copy_from_slice(&v);
        Ok(())
    }

    /// Magnitudes of the coefficients per level: a list of dicts (level, count, mean, rms, max).
    fn statistics<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        self.mr.statistics().iter().map(|s| stats_dict(py, s)).collect()
    }

    /// Keeps the largest `keep_fraction` of the coefficients: `((V, F), error dict)`.
    fn compress<'py>(&self, py: Python<'py>, keep_fraction: f64) -> PyResult<(MeshArrays<'py>, Bound<'py, PyDict>)> {
        let (mesh, total, kept, rms, max) = run(py, || -> Fallible<_> {
            let c = self.mr.compress(&CompressOptions { keep_fraction })?;
            Ok((c.multiresolution.synthesize()?, c.total_coefficients, c.kept_coefficients, c.rms_error, c.max_error))
        })?;
        let d = PyDict::new(py);
        d.set_item("total_coefficients", total)?;
        d.set_item("kept_coefficients", kept)?;
        d.set_item("rms_error", rms)?;
        d.set_item("max_error", max)?;
        Ok((mesh_arrays(py, mesh)?, d))
    }
}
