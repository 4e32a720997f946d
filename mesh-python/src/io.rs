//! `read`, `read_attributes`, `write`: every format of mesh-io with its
//! per-vertex (and per-face) attributes.

use glam::{DVec2, DVec3};
use mesh_io::{MeshData, MeshView, WriteOptions};
use numpy::{IntoPyArray, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{mesh_arrays, points, points2, run, Arrays, Faces, MeshArrays};
use crate::errors::{Failure, Fallible};

/// Every attribute of `data` as `(name, element, kind, arity)`, as `mesh info` lists them.
pub fn attribute_list(data: &MeshData) -> Vec<(String, String, String, usize)> {
    let entry = |name: &str, element: &str, kind: &str, arity: usize| {
        (name.to_owned(), element.to_owned(), kind.to_owned(), arity)
    };
    let mut out = Vec::new();
    if data.normals.is_some() {
        out.push(entry("normals", "vertex", "vector", 3));
    }
    if data.uvs.is_some() {
        out.push(entry("uvs", "vertex", "uv", 2));
    }
    if data.corner_uvs.is_some() {
        out.push(entry("uvs", "corner", "uv", 2));
    }
    if data.colors.is_some() {
        out.push(entry("colors", "vertex", "color", 4));
    }
    out.extend(
        data.attributes().iter().map(|a| entry(a.name, &a.element.to_string(), &a.kind().to_string(), a.arity())),
    );
    out
}

/// Reads a mesh file (OBJ, OFF, PLY, STL, glTF/GLB; format from the extension) as `(V, F)`.
#[pyfunction]
pub fn read(py: Python<'_>, path: std::path::PathBuf) -> PyResult<MeshArrays<'_>> {
    let data = run(py, move || Ok(mesh_io::read(&path)?))?;
    mesh_arrays(py, data.mesh)
}

fn colors_array(py: Python<'_>, c: Vec<[f32; 4]>) -> PyResult<Bound<'_, PyAny>> {
    let n = c.len();
    let flat: Vec<f32> = c.into_iter().flatten().collect();
    Ok(flat.into_pyarray(py).reshape([n, 4])?.into_any())
}

/// Reads a mesh file with its attributes: `(V, F, vertex_attributes, face_attributes, report)`.
#[pyfunction]
pub fn read_attributes(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Bound<'_, pyo3::types::PyTuple>> {
    let data = run(py, move || Ok(mesh_io::read(&path)?))?;
    let vertex = PyDict::new(py);
    let face = PyDict::new(py);
    let report = PyDict::new(py);
    report.set_item("faces_dropped", data.report.faces_dropped)?;
    report.set_item("polygons_triangulated", data.report.polygons_triangulated)?;
    report.set_item("vertices_welded", data.report.vertices_welded)?;
    report.set_item("notes", data.report.notes.clone())?;
    let MeshData {
        mesh,
        normals,
        uvs,
        corner_uvs,
        colors,
        scalars,
        vectors,
        labels,
        face_scalars,
        face_vectors,
        face_labels,
        ..
    } = data;
    if let Some(n) = normals {
        vertex.set_item("normals", points(py, n)?)?;
    }
    if let Some(uv) = uvs {
        vertex.set_item("uvs", points2(py, uv)?)?;
    }
    if let Some(c) = colors {
        vertex.set_item("colors", colors_array(py, c)?)?;
    }
    if let Some(cuv) = corner_uvs {
        let m = cuv.len();
        let flat: Vec<f64> = cuv.into_iter().flat_map(|t| t.into_iter().flat_map(|uv| uv.to_array())).collect();
        face.set_item("uvs", flat.into_pyarray(py).reshape([m, 3, 2])?)?;
    }
    for (name, s) in scalars {
        vertex.set_item(name, s.into_pyarray(py))?;
    }
    for (name, v) in vectors {
        vertex.set_item(name, points(py, v)?)?;
    }
    for (name, l) in labels {
        vertex.set_item(name, l.into_pyarray(py))?;
    }
    for (name, s) in face_scalars {
        face.set_item(name, s.into_pyarray(py))?;
    }
    for (name, v) in face_vectors {
        face.set_item(name, points(py, v)?)?;
    }
    for (name, l) in face_labels {
        face.set_item(name, l.into_pyarray(py))?;
    }
    let (v, f) = mesh_arrays(py, mesh)?;
    pyo3::types::PyTuple::new(py, [v.into_any(), f.into_any(), vertex.into_any(), face.into_any(), report.into_any()])
}

/// Attributes of one element (vertices or faces), owned, ready for a [`MeshView`].
#[derive(Default)]
struct Owned {
    scalars: Vec<(String, Vec<f64>)>,
    vectors: Vec<(String, Vec<DVec3>)>,
    labels: Vec<(String, Vec<i64>)>,
    normals: Option<Vec<DVec3>>,
    uvs: Option<Vec<DVec2>>,
    colors: Option<Vec<[f32; 4]>>,
}

/// Sorts the arrays of `dict` (float64 1-D: scalar, int64 1-D: label,
/// float64 (n, 3): vector; for vertices `normals` (n, 3), `uvs` (n, 2) and
/// `colors` (n, 3 or 4, in [0, 1]) are the formats' own attributes).
fn collect(dict: Option<&Bound<'_, PyDict>>, count: usize, element: &str, vertex: bool) -> PyResult<Owned> {
    let mut out = Owned::default();
    let Some(dict) = dict else { return Ok(out) };
    for (key, value) in dict.iter() {
        let name: String = key.extract()?;
        let bad_len = |found: usize| {
            Failure::option(format!("{element} attribute `{name}` has {found} rows for {count} {element}s"))
        };
        if let Ok(a) = value.extract::<PyReadonlyArray1<'_, f64>>() {
            let a = a.as_array();
            if a.len() != count {
                return Err(bad_len(a.len()).into());
            }
            out.scalars.push((name, a.to_vec()));
        } else if let Ok(a) = value.extract::<PyReadonlyArray1<'_, i64>>() {
            let a = a.as_array();
            if a.len() != count {
                return Err(bad_len(a.len()).into());
            }
            out.labels.push((name, a.to_vec()));
        } else if let Ok(a) = value.extract::<PyReadonlyArray2<'_, f64>>() {
            let a = a.as_array();
            if a.nrows() != count {
                return Err(bad_len(a.nrows()).into());
            }
            let cols = a.ncols();
            match (vertex, name.as_str(), cols) {
                (true, "uvs", 2) => out.uvs = Some(a.rows().into_iter().map(|r| DVec2::new(r[0], r[1])).collect()),
                (true, "colors", 3 | 4) => {
                    out.colors = Some(
                        a.rows()
                            .into_iter()
                            .map(|r| [r[0] as f32, r[1] as f32, r[2] as f32, if cols == 4 { r[3] as f32 } else { 1.0 }])
                            .collect(),
                    )
                }
                (_, _, 3) => {
                    let v: Vec<DVec3> = a.rows().into_iter().map(|r| DVec3::new(r[0], r[1], r[2])).collect();
                    if vertex && name == "normals" {
                        out.normals = Some(v);
                    } else {
                        out.vectors.push((name, v));
                    }
                }
                _ => {
                    return Err(Failure::option(format!(
                        "{element} attribute `{name}` has {cols} columns: expected 1 (scalar or label), 3 (vector){}",
                        if vertex { ", 2 (`uvs`) or 3-4 (`colors`)" } else { "" }
                    ))
                    .into())
                }
            }
        } else {
            return Err(Failure::option(format!(
                "{element} attribute `{name}` is not a float64 or int64 array of 1 or 2 dimensions"
            ))
            .into());
        }
    }
    Ok(out)
}

fn view<'a>(mesh: &'a mesh_kernel::TriMesh, v: &'a Owned, f: &'a Owned) -> MeshView<'a> {
    let mut view = MeshView::new(mesh);
    if let Some(n) = &v.normals {
        view = view.with_normals(n);
    }
    if let Some(uv) = &v.uvs {
        view = view.with_uvs(uv);
    }
    if let Some(c) = &v.colors {
        view = view.with_colors(c);
    }
    for (name, s) in &v.scalars {
        view = view.with_scalar(name, s);
    }
    for (name, s) in &v.vectors {
        view = view.with_vector(name, s);
    }
    for (name, s) in &v.labels {
        view = view.with_label(name, s);
    }
    for (name, s) in &f.scalars {
        view = view.with_face_scalar(name, s);
    }
    for (name, s) in &f.vectors {
        view = view.with_face_vector(name, s);
    }
    for (name, s) in &f.labels {
        view = view.with_face_label(name, s);
    }
    view
}

/// Writes a mesh file with attributes (see the Python `write`); returns
/// what the format could not store and how much 32-bit values were rounded.
#[pyfunction]
#[pyo3(signature = (path, v, f, vertex_attributes=None, face_attributes=None, ply_binary=None, allow_precision_loss=false))]
pub fn write<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
    v: PyReadonlyArray2<'py, f64>,
    f: Faces<'py>,
    vertex_attributes: Option<Bound<'py, PyDict>>,
    face_attributes: Option<Bound<'py, PyDict>>,
    ply_binary: Option<bool>,
    allow_precision_loss: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let arrays = Arrays::new(&v, &f)?;
    let m = f.rows();
    let vattr = collect(vertex_attributes.as_ref(), arrays.vertex_count(), "vertex", true)?;
    let fattr = collect(face_attributes.as_ref(), m, "face", false)?;
    let report = run(py, move || -> Fallible<_> {
        let mesh = arrays.mesh()?;
        let mut options = WriteOptions { allow_precision_loss, ..Default::default() };
        if let Some(binary) = ply_binary {
            options.ply.encoding =
                if binary { mesh_io::PlyEncoding::BinaryLittleEndian } else { mesh_io::PlyEncoding::Ascii };
        }
        Ok(mesh_io::write(&path, view(&mesh, &vattr, &fattr), &options)?)
    })?;
    let d = PyDict::new(py);
    d.set_item("max_relative_rounding", report.max_relative_rounding)?;
    d.set_item("values_lost", report.values_lost)?;
    d.set_item("dropped", report.dropped)?;
    Ok(d)
}

/// A built-in shape of mesh-kernel by name (`icosphere`, `uv-sphere`,
/// `torus`, `cylinder`, `grid`, `disk`, `cube`) at resolution `n`, as `(V, F)`.
#[pyfunction]
pub fn shape(py: Python<'_>, name: String, n: usize) -> PyResult<MeshArrays<'_>> {
    let mesh = run(py, move || Ok(mesh_kernel::shapes::by_name(&name, n)?))?;
    mesh_arrays(py, mesh)
}
