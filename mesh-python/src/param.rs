//! Parameterization (mesh-param).

use glam::DVec2;
use mesh_param::{
    parameterize as flatten, parameterize_cut, BoundaryMap, DistortionSummary, ParamMethod, ParamOptions, Spacing,
};
use numpy::{PyArray1, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{mesh_arrays, points2, run, vec1, vertex_ids, Arrays, Faces, Indices, MeshArrays};
use crate::errors::Failure;
use crate::operators::choice;

fn summary_dict<'py>(py: Python<'py>, s: &DistortionSummary) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("faces", s.faces)?;
    d.set_item("flipped_faces", s.flipped_faces)?;
    d.set_item("collapsed_faces", s.collapsed_faces)?;
    d.set_item("degenerate_faces", s.degenerate_faces)?;
    d.set_item("angle_distortion_mean", s.angle_distortion_mean)?;
    d.set_item("angle_distortion_max", s.angle_distortion_max)?;
    d.set_item("area_distortion_mean", s.area_distortion_mean)?;
    d.set_item("area_distortion_max", s.area_distortion_max)?;
    d.set_item("dirichlet_energy", s.dirichlet_energy)?;
    d.set_item("surface_area", s.surface_area)?;
    d.set_item("uv_area", s.uv_area)?;
    d.set_item("dirichlet_area_ratio", s.dirichlet_area_ratio)?;
    d.set_item("boundary_simple", s.boundary_simple)?;
    d.set_item("bijective", s.bijective)?;
    Ok(d)
}

#[allow(clippy::too_many_arguments)]
fn options(
    method: &str,
    boundary: &str,
    spacing: &str,
    normalize: bool,
    lambda: f64,
    mu: f64,
    iterations: usize,
    fixed: Option<(Vec<mesh_kernel::VertexId>, Vec<DVec2>)>,
) -> Result<ParamOptions, Failure> {
    let method = match choice::<ParamMethod>("method", method)? {
        ParamMethod::Intrinsic { .. } => ParamMethod::Intrinsic { lambda, mu },
        ParamMethod::Arap { .. } => ParamMethod::Arap { iterations },
        other => other,
    };
    let boundary = match fixed {
        Some((ids, uv)) => BoundaryMap::Fixed(ids.into_iter().zip(uv).collect()),
        None => match choice::<BoundaryMap>("boundary", boundary)? {
            BoundaryMap::Circle(_) => BoundaryMap::Circle(choice::<Spacing>("spacing", spacing)?),
            other => other,
        },
    };
    Ok(ParamOptions { method, boundary, normalize, ..Default::default() })
}

fn fixed_points(
    n: usize,
    fixed: Option<(Indices<'_>, PyReadonlyArray2<'_, f64>)>,
) -> PyResult<Option<(Vec<mesh_kernel::VertexId>, Vec<DVec2>)>> {
    let Some((ids, uv)) = fixed else { return Ok(None) };
    let ids = vertex_ids(&ids, n)?;
    let uv = uv.as_array();
    if uv.shape() != [ids.len(), 2] {
        return Err(Failure::option(format!(
            "fixed positions must have shape ({}, 2), not {:?}",
            ids.len(),
            uv.shape()
        ))
        .into());
    }
    Ok(Some((ids, uv.rows().into_iter().map(|r| DVec2::new(r[0], r[1])).collect())))
}

/// Flattens a disk: `(UV (n, 2), distortion summary)`.
#[pyfunction]
#[pyo3(signature = (v, f, method="harmonic", boundary="circle", spacing="chord", normalize=false,
                    lambda_=0.5, mu=0.5, iterations=20, fixed=None))]
pub fn parameterize<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    method: &str,
    boundary: &str,
    spacing: &str,
    normalize: bool,
    lambda_: f64,
    mu: f64,
    iterations: usize,
    fixed: Option<(Indices<'py>, PyReadonlyArray2<'py, f64>)>,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyDict>)> {
    let arrays = Arrays::new(&v, &f)?;
    let fixed = fixed_points(arrays.vertex_count(), fixed)?;
    let options = options(method, boundary, spacing, normalize, lambda_, mu, iterations, fixed)?;
    let p = run(py, move || Ok(flatten(&arrays.mesh()?, &options)?))?;
    let summary = summary_dict(py, &p.report.summary)?;
    Ok((points2(py, p.uv)?, summary))
}

/// Cuts any manifold mesh into a disk along a seam and flattens it:
/// `(V_cut, F_cut, UV (n_cut, 2), vertex_origin, distortion summary)`.
#[pyfunction]
#[pyo3(signature = (v, f, method="harmonic", boundary="circle", spacing="chord", normalize=false,
                    lambda_=0.5, mu=0.5, iterations=20))]
pub fn parameterize_cut_mesh<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    method: &str,
    boundary: &str,
    spacing: &str,
    normalize: bool,
    lambda_: f64,
    mu: f64,
    iterations: usize,
) -> PyResult<(MeshArrays<'py>, Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<i64>>, Bound<'py, PyDict>)> {
    let arrays = Arrays::new(&v, &f)?;
    let options = options(method, boundary, spacing, normalize, lambda_, mu, iterations, None)?;
    let c = run(py, move || Ok(parameterize_cut(&arrays.mesh()?, &options)?))?;
    let summary = summary_dict(py, &c.param.report.summary)?;
    let origin = c.cut.vertex_origin.iter().map(|v| i64::from(v.0)).collect();
    Ok((mesh_arrays(py, c.cut.mesh)?, points2(py, c.param.uv)?, vec1(py, origin), summary))
}
