//! Geodesic distances and paths (mesh-geodesic).

use mesh_geodesic::{
    dijkstra as graph_distance, exact_distance as exact, farthest_point_sampling as fps, trace_path as trace,
    DijkstraOptions, ExactOptions, FastMarching, FmmOptions, HeatBoundary, HeatFarField, HeatGeodesics, HeatOptions,
    HeatStatus, LaplacianKind, SamplingMetric, SamplingOptions, SurfacePoint, TraceOptions,
};
use mesh_kernel::{FaceId, TriMesh};
use numpy::{PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;

use crate::convert::{field, points, run, vec1, vertex_ids, Arrays, Faces, Indices};
use crate::errors::{Failure, Fallible};
use crate::operators::choice;

/// The heat method, prepared (Crane et al. 2013): factors once, then answers
/// any source set with a few sparse triangular solves.
#[pyclass(module = "meshkit._meshkit", frozen)]
pub struct HeatSolver {
    heat: HeatGeodesics,
    vertex_count: usize,
}

#[pymethods]
impl HeatSolver {
    /// Prepares the solver: time step `t = t_coef h^2` (h the mean edge
    /// length), Laplacian `intrinsic` (intrinsic Delaunay, robust) or
    /// `cotan`, boundary condition `mean`, `neumann` or `dirichlet`, far
    /// field `fmm`, `restart` or `none`.
    #[new]
    #[pyo3(signature = (v, f, t_coef=1.0, laplacian="intrinsic", boundary="mean", far_field="fmm"))]
    fn new(
        py: Python<'_>,
        v: PyReadonlyArray2<'_, f64>,
        f: Faces<'_>,
        t_coef: f64,
        laplacian: &str,
        boundary: &str,
        far_field: &str,
    ) -> PyResult<Self> {
        let laplacian: LaplacianKind = choice("laplacian", laplacian)?;
        let boundary: HeatBoundary = choice("boundary", boundary)?;
        let far_field: HeatFarField = choice("far_field", far_field)?;
        let options = HeatOptions { time_factor: t_coef, laplacian, boundary, far_field, ..Default::default() };
        let arrays = Arrays::new(&v, &f)?;
        let vertex_count = arrays.vertex_count();
        let mesh = run(py, move || arrays.mesh())?;
        let heat = run(py, move || Ok(HeatGeodesics::new(&mesh, &options)?))?;
        Ok(Self { heat, vertex_count })
    }

    /// Geodesic distance from the source vertices (0 there, +inf where no
    /// source reaches), one value per vertex.
    fn distance<'py>(&self, py: Python<'py>, sources: Indices<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let sources = vertex_ids(&sources, self.vertex_count)?;
        let d = run(py, || Ok(self.heat.distance(&sources)?))?;
        Ok(vec1(py, d))
    }

    /// The distance and, per vertex, 0 (resolved by the heat flow), 1 (far
    /// field: continued by `far_field`) or 2 (unresolved).
    fn distance_and_status<'py>(
        &self,
        py: Python<'py>,
        sources: Indices<'py>,
    ) -> PyResult<(Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<u8>>)> {
        let sources = vertex_ids(&sources, self.vertex_count)?;
        let d = run(py, || Ok(self.heat.solve(&sources)?))?;
        let status = d
            .status
            .iter()
            .map(|s| match s {
                HeatStatus::FarField => 1u8,
                HeatStatus::Unresolved => 2,
                _ => 0,
            })
            .collect();
        Ok((vec1(py, d.distance), vec1(py, status)))
    }

    /// The time step t of the heat flow.
    #[getter]
    fn time(&self) -> f64 {
        self.heat.time()
    }

    /// Number of vertices of the mesh the solver was built on.
    #[getter]
    fn vertex_count(&self) -> usize {
        self.vertex_count
    }
}

/// Fast Marching, prepared: the stencils of one mesh for any source set.
#[pyclass(module = "meshkit._meshkit", frozen)]
pub struct FastMarchingSolver {
    fmm: FastMarching,
    vertex_count: usize,
}

#[pymethods]
impl FastMarchingSolver {
    /// Prepares Fast Marching with the local `update` (`curved`, `point-source`, `plane-wave`).
    #[new]
    #[pyo3(signature = (v, f, update="curved"))]
    fn new(py: Python<'_>, v: PyReadonlyArray2<'_, f64>, f: Faces<'_>, update: &str) -> PyResult<Self> {
        let options = FmmOptions { update: choice("update", update)?, ..Default::default() };
        let arrays = Arrays::new(&v, &f)?;
        let vertex_count = arrays.vertex_count();
        let mesh = run(py, move || arrays.mesh())?;
        let fmm = run(py, move || Ok(FastMarching::new(&mesh, &options)?))?;
        Ok(Self { fmm, vertex_count })
    }

    /// Geodesic distance from the source vertices.
    fn distance<'py>(&self, py: Python<'py>, sources: Indices<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let sources = vertex_ids(&sources, self.vertex_count)?;
        let d = run(py, || Ok(self.fmm.distance(&sources)?))?;
        Ok(vec1(py, d))
    }
}

fn with_mesh<'py, T: Send>(
    py: Python<'py>,
    v: &PyReadonlyArray2<'py, f64>,
    f: &Faces<'py>,
    sources: &Indices<'py>,
    work: impl FnOnce(&TriMesh, &[mesh_kernel::VertexId]) -> Fallible<T> + Send,
) -> PyResult<T> {
    let arrays = Arrays::new(v, f)?;
    let sources = vertex_ids(sources, arrays.vertex_count())?;
    let mesh = run(py, move || arrays.mesh())?;
    run(py, move || work(&mesh, &sources))
}

/// Fast Marching distance from the sources (one call; see `FastMarchingSolver`).
#[pyfunction]
#[pyo3(signature = (v, f, sources, update="curved"))]
pub fn fmm_distance<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    sources: Indices<'py>,
    update: &str,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let options = FmmOptions { update: choice("update", update)?, ..Default::default() };
    let d = with_mesh(py, &v, &f, &sources, |mesh, s| Ok(mesh_geodesic::fmm_distance(mesh, s, &options)?))?;
    Ok(vec1(py, d))
}

/// Exact polyhedral geodesic distance (window propagation).
#[pyfunction]
#[pyo3(signature = (v, f, sources, max_windows=20_000_000))]
pub fn exact_distance<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    sources: Indices<'py>,
    max_windows: usize,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let options = ExactOptions { max_windows };
    let d = with_mesh(py, &v, &f, &sources, |mesh, s| Ok(exact(mesh, s, &options)?))?;
    Ok(vec1(py, d))
}

/// Shortest paths along the edges: `(distance, predecessor)`; the
/// predecessor of a source or unreached vertex is -1.
#[pyfunction]
#[pyo3(signature = (v, f, sources, max_distance=f64::INFINITY))]
pub fn dijkstra<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    sources: Indices<'py>,
    max_distance: f64,
) -> PyResult<(Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<i64>>)> {
    let options = DijkstraOptions { max_distance };
    let sp = with_mesh(py, &v, &f, &sources, |mesh, s| Ok(graph_distance(mesh, s, &options)?))?;
    let n = sp.distance.len();
    let pred = sp.predecessor.iter().map(|p| if p.idx() < n { p.idx() as i64 } else { -1 }).collect();
    Ok((vec1(py, sp.distance), vec1(py, pred)))
}

/// The path from vertex `start` (or from the point `bary` of face `face`)
/// down the distance field to the nearest source: `(points (k, 3), length,
/// source)`.
#[pyfunction]
#[pyo3(signature = (v, f, distance, sources, start=None, face=None, bary=None))]
pub fn trace_path<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    distance: PyReadonlyArray1<'py, f64>,
    sources: Indices<'py>,
    start: Option<i64>,
    face: Option<i64>,
    bary: Option<[f64; 3]>,
) -> PyResult<(Bound<'py, PyArray2<f64>>, f64, i64)> {
    let arrays = Arrays::new(&v, &f)?;
    let d = field(&distance, arrays.vertex_count(), "distance")?;
    let n = arrays.vertex_count();
    let (start, face) = match (start, face, bary) {
        (Some(s), None, None) => {
            let s = usize::try_from(s).ok().filter(|&s| s < n).ok_or_else(|| {
                Failure::option(format!("start vertex {s} is out of range: the mesh has {n} vertices"))
            })?;
            (Some(s), None)
        }
        (None, Some(face), Some(bary)) => {
            let face =
                usize::try_from(face).map_err(|_| Failure::option(format!("face {face} is not a face index")))?;
            (None, Some((face, bary)))
        }
        _ => return Err(Failure::option("give either start (a vertex) or both face and bary").into()),
    };
    let path = with_mesh(py, &v, &f, &sources, move |mesh, s| {
        let from = match (start, face) {
            (Some(v), _) => SurfacePoint::at_vertex(mesh, mesh_kernel::VertexId::new(v))
                .ok_or_else(|| Failure::option(format!("start vertex {v} is not a vertex of any face")))?,
            (None, Some((face, bary))) => {
                if face >= mesh.face_count() {
                    return Err(Failure::option(format!(
                        "face {face} is out of range: the mesh has {} faces",
                        mesh.face_count()
                    )));
                }
                SurfacePoint::new(mesh, FaceId::new(face), bary)?
            }
            (None, None) => return Err(Failure::option("no start point")),
        };
        Ok(trace(mesh, &d, s, from, &TraceOptions::default())?)
    })?;
    Ok((points(py, path.positions)?, path.length, i64::from(path.source.0)))
}

/// `count` vertices by farthest-point sampling, with their geodesic Voronoi
/// regions: `(samples, region, distance)`.
#[pyfunction]
#[pyo3(signature = (v, f, count, metric="fmm", start=None))]
pub fn farthest_point_sampling<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    count: usize,
    metric: &str,
    start: Option<i64>,
) -> PyResult<(Bound<'py, PyArray1<i64>>, Bound<'py, PyArray1<i64>>, Bound<'py, PyArray1<f64>>)> {
    let metric: SamplingMetric = choice("metric", metric)?;
    let arrays = Arrays::new(&v, &f)?;
    let n = arrays.vertex_count();
    let start = match start {
        Some(s) => {
            Some(usize::try_from(s).ok().filter(|&s| s < n).map(mesh_kernel::VertexId::new).ok_or_else(|| {
                Failure::option(format!("start vertex {s} is out of range: the mesh has {n} vertices"))
            })?)
        }
        None => None,
    };
    let options = SamplingOptions { metric, start, ..Default::default() };
    let mesh = run(py, move || arrays.mesh())?;
    let vor = run(py, move || Ok(fps(&mesh, count, &options)?))?;
    let seeds = vor.seeds.iter().map(|s| i64::from(s.0)).collect();
    let region = vor.region.iter().map(|&r| if r == u32::MAX { -1 } else { i64::from(r) }).collect();
    Ok((vec1(py, seeds), vec1(py, region), vec1(py, vor.distance)))
}
