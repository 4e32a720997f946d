//! Topology and repair (mesh-kernel's connectivity and `clean`).

use mesh_kernel::clean::{self, CleanOptions};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{mesh_arrays, run, vec1, Arrays, Faces, MeshArrays};
use crate::errors::Fallible;

/// Repairs a mesh: welds coincident vertices (within `weld_tolerance`; None
/// turns welding off), drops collapsed, zero-area and duplicate faces and
/// unreferenced vertices, optionally cuts it into an oriented manifold, and
/// orients the faces consistently: `((V, F), report)`. Accepts triangles
/// that repeat a vertex (they are dropped).
#[pyfunction]
#[pyo3(signature = (v, f, weld_tolerance=Some(0.0), drop_degenerate=true, drop_duplicates=true,
                    drop_unreferenced=true, manifold=false, orient=true))]
pub fn clean_mesh<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    weld_tolerance: Option<f64>,
    drop_degenerate: bool,
    drop_duplicates: bool,
    drop_unreferenced: bool,
    manifold: bool,
    orient: bool,
) -> PyResult<(MeshArrays<'py>, Bound<'py, PyDict>)> {
    let options = CleanOptions {
        weld_tolerance,
        drop_degenerate,
        drop_duplicates,
        drop_unreferenced,
        manifold,
        orient,
        ..Default::default()
    };
    let (positions, faces) = Arrays::new(&v, &f)?.into_parts();
    let (mesh, report) = run(py, move || Ok(clean::clean(positions, faces, &options)?))?;
    let d = PyDict::new(py);
    d.set_item("welded_vertices", report.welded_vertices)?;
    d.set_item("collapsed_faces", report.collapsed_faces)?;
    d.set_item("degenerate_faces", report.degenerate_faces)?;
    d.set_item("duplicate_faces", report.duplicate_faces)?;
    d.set_item("unreferenced_vertices", report.unreferenced_vertices)?;
    d.set_item("fin_edges", report.fin_edges)?;
    d.set_item("detached_faces", report.detached_faces)?;
    d.set_item("cut_edges", report.cut_edges)?;
    d.set_item("split_vertices", report.split_vertices)?;
    d.set_item("flipped_faces", report.flipped_faces)?;
    d.set_item("unorientable_components", report.unorientable_components)?;
    Ok((mesh_arrays(py, mesh)?, d))
}

/// The undirected edges as an (E, 2) int64 array (smaller index first), in
/// the order of the connectivity's edge ids.
#[pyfunction]
pub fn edges<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
) -> PyResult<Bound<'py, PyArray2<i64>>> {
    let arrays = Arrays::new(&v, &f)?;
    let flat = run(py, move || -> Fallible<Vec<i64>> {
        let mesh = arrays.mesh()?;
        Ok(mesh.connectivity().edges().iter().flat_map(|e| e.map(|v| i64::from(v.0))).collect())
    })?;
    let m = flat.len() / 2;
    flat.into_pyarray(py).reshape([m, 2])
}

/// The boundary loops of an oriented manifold, each a vertex-index array in
/// order (an empty list for a closed mesh).
#[pyfunction]
pub fn boundary_loops<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
) -> PyResult<Vec<Bound<'py, PyArray1<i64>>>> {
    let arrays = Arrays::new(&v, &f)?;
    let loops = run(py, move || -> Fallible<Vec<Vec<i64>>> {
        let mesh = arrays.mesh()?;
        let loops = mesh.connectivity().boundary_loops()?;
        Ok(loops.iter().map(|l| l.vertices.iter().map(|v| i64::from(v.0)).collect()).collect())
    })?;
    Ok(loops.into_iter().map(|l| vec1(py, l)).collect())
}

/// Connected components of the faces: one label per vertex, numbered from
/// 0 (-1 for vertices no face uses).
#[pyfunction]
pub fn connected_components<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
) -> PyResult<Bound<'py, PyArray1<i64>>> {
    let arrays = Arrays::new(&v, &f)?;
    let labels = run(py, move || -> Fallible<Vec<i64>> {
        let mesh = arrays.mesh()?;
        let c = mesh.connectivity().components();
        Ok(c.vertex_component.iter().map(|&c| if c == u32::MAX { -1 } else { i64::from(c) }).collect())
    })?;
    Ok(vec1(py, labels))
}
