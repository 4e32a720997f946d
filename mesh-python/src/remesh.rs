//! Remeshing through a parameterization (mesh-remesh).

use mesh_kernel::geometry;
use mesh_remesh::{remesh as remesh_mesh, RemeshOptions, RemeshReport, TopologySummary};
use numpy::PyReadonlyArray2;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{mesh_arrays, run, Arrays, Faces, MeshArrays};

fn topology_dict<'py>(py: Python<'py>, t: &TopologySummary) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("euler_characteristic", t.euler_characteristic)?;
    d.set_item("components", t.components)?;
    d.set_item("boundary_loops", t.boundary_loops)?;
    d.set_item("manifold", t.manifold)?;
    Ok(d)
}

fn report_dict<'py>(py: Python<'py>, r: &RemeshReport) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("edge_length", r.edge_length)?;
    d.set_item("vertices", r.vertices)?;
    d.set_item("faces", r.faces)?;
    d.set_item("charts", r.charts)?;
    d.set_item("min_angle_degrees", r.min_angle_degrees)?;
    d.set_item("mean_min_angle_degrees", r.mean_min_angle_degrees)?;
    d.set_item("below_20_degrees", r.below_20_degrees)?;
    let e = &r.edge_lengths;
    d.set_item("mean_edge_over_target", e.mean_over_target)?;
    d.set_item("edges_within_half", e.within_half)?;
    d.set_item("edges_within_quarter", e.within_quarter)?;
    if let Some(h) = &r.hausdorff {
        d.set_item("hausdorff_relative", h.symmetric_relative)?;
        d.set_item("hausdorff", h.symmetric)?;
    }
    d.set_item("normal_disagreements", r.normal_disagreements)?;
    d.set_item("flips", r.flips)?;
    d.set_item("collapses", r.collapses)?;
    d.set_item("stitch_splits", r.stitch_splits)?;
    d.set_item("smoothing_moves", r.smoothing_moves)?;
    d.set_item("input_topology", topology_dict(py, &r.input_topology)?)?;
    d.set_item("output_topology", topology_dict(py, &r.output_topology)?)?;
    d.set_item("topology_changed", r.topology_changed)?;
    Ok(d)
}

/// Remeshes to edges near `edge_length` (default: the input's mean edge
/// length) through a parameterization: `((V, F), report)`.
#[pyfunction]
#[pyo3(signature = (v, f, edge_length=None, min_angle=28.0, max_vertices=4_000_000, smoothing_rounds=3,
                    hausdorff=true))]
#[allow(clippy::too_many_arguments)]
pub fn remesh<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    edge_length: Option<f64>,
    min_angle: f64,
    max_vertices: usize,
    smoothing_rounds: usize,
    hausdorff: bool,
) -> PyResult<(MeshArrays<'py>, Bound<'py, PyDict>)> {
    let arrays = Arrays::new(&v, &f)?;
    let r = run(py, move || {
        let mesh = arrays.mesh()?;
        let edge_length = edge_length.unwrap_or_else(|| geometry::mean_edge_length(&mesh));
        let options =
            RemeshOptions { edge_length, min_angle, max_vertices, smoothing_rounds, hausdorff, ..Default::default() };
        Ok(remesh_mesh(&mesh, &options)?)
    })?;
    let report = report_dict(py, &r.report)?;
    Ok((mesh_arrays(py, r.mesh)?, report))
}
