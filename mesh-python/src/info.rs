//! `info(V, F)` and `info_file(path)`: the measures of `mesh info --json`.
//!
//! Both this and the `mesh` command report `mesh_kernel::summary::MeshSummary`
//! (the tests compare the two on the shared meshes).

use mesh_kernel::summary::MeshSummary;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::convert::{run, Arrays, Faces};
use numpy::PyReadonlyArray2;

/// The summary as a dict, with the keys of `mesh info --json` in its order.
fn summary_dict(info: MeshSummary, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("vertices", info.vertices)?;
    d.set_item("faces", info.faces)?;
    d.set_item("edges", info.edges)?;
    d.set_item("euler_characteristic", info.euler_characteristic)?;
    d.set_item("genus", info.genus)?;
    d.set_item("components", info.components)?;
    d.set_item("boundary_loops", info.boundary_loops)?;
    d.set_item("manifold", info.manifold)?;
    d.set_item("non_manifold_edges", info.non_manifold_edges)?;
    d.set_item("non_manifold_vertices", info.non_manifold_vertices)?;
    d.set_item("inconsistent_edges", info.inconsistent_edges)?;
    d.set_item("degenerate_faces", info.degenerate_faces)?;
    d.set_item("duplicate_faces", info.duplicate_faces)?;
    d.set_item("unreferenced_vertices", info.unreferenced_vertices)?;
    d.set_item("coincident_vertices", info.coincident_vertices)?;
    d.set_item("area", info.area)?;
    d.set_item("volume", info.volume)?;
    d.set_item("out_of_range", info.out_of_range)?;
    d.set_item("mean_edge_length", info.mean_edge_length)?;
    d.set_item("bbox_min", info.bbox_min.map(|b| b.to_vec()))?;
    d.set_item("bbox_max", info.bbox_max.map(|b| b.to_vec()))?;
    Ok(d)
}

/// The measures of `mesh info --json` for arrays; `attributes` is an empty
/// list and `read` is None (nothing was read from a file).
#[pyfunction]
pub fn info<'py>(py: Python<'py>, v: PyReadonlyArray2<'py, f64>, f: Faces<'py>) -> PyResult<Bound<'py, PyDict>> {
    let arrays = Arrays::new(&v, &f)?;
    let info = run(py, move || Ok(MeshSummary::of(&arrays.mesh()?)))?;
    let d = summary_dict(info, py)?;
    d.set_item("attributes", PyList::empty(py))?;
    d.set_item("read", py.None())?;
    Ok(d)
}

/// `mesh info FILE --json` as a dict: the measures, the file's attributes and what reading changed.
#[pyfunction]
pub fn info_file<'py>(py: Python<'py>, path: std::path::PathBuf) -> PyResult<Bound<'py, PyDict>> {
    let (info, attributes, read) = run(py, move || {
        let data = mesh_io::read(&path)?;
        let info = MeshSummary::of(&data.mesh);
        Ok((info, crate::io::attribute_list(&data), data.report))
    })?;
    let d = summary_dict(info, py)?;
    let list = PyList::empty(py);
    for (name, element, kind, arity) in attributes {
        let a = PyDict::new(py);
        a.set_item("name", name)?;
        a.set_item("element", element)?;
        a.set_item("kind", kind)?;
        a.set_item("arity", arity)?;
        list.append(a)?;
    }
    d.set_item("attributes", list)?;
    let r = PyDict::new(py);
    r.set_item("faces_dropped", read.faces_dropped)?;
    r.set_item("polygons_triangulated", read.polygons_triangulated)?;
    r.set_item("vertices_welded", read.vertices_welded)?;
    r.set_item("notes", read.notes)?;
    d.set_item("read", r)?;
    Ok(d)
}
