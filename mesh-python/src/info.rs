//! `info(V, F)` and `info_file(path)`: the measures of `mesh info --json`.
//!
//! The `mesh` command keeps its `Info` in the binary crate, so the same
//! composition of mesh-kernel calls is written here once more (the list of
//! keys, their order and their meaning are those of `mesh info --json`; the
//! tests compare both on the shared meshes).

use mesh_kernel::{clean, geometry, TriMesh};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::convert::{run, Arrays, Faces};
use numpy::PyReadonlyArray2;

/// Everything `mesh info` measures, in the order it prints the keys.
struct Info {
    vertices: usize,
    faces: usize,
    edges: usize,
    euler_characteristic: i64,
    genus: Option<u64>,
    components: usize,
    boundary_loops: Option<usize>,
    manifold: bool,
    non_manifold_edges: usize,
    non_manifold_vertices: usize,
    inconsistent_edges: usize,
    degenerate_faces: usize,
    duplicate_faces: usize,
    unreferenced_vertices: usize,
    coincident_vertices: usize,
    area: Option<f64>,
    volume: Option<f64>,
    out_of_range: Vec<String>,
    mean_edge_length: f64,
    bbox_min: Option<[f64; 3]>,
    bbox_max: Option<[f64; 3]>,
}

/// A quantity of degree `degree` in lengths measured as `inner` on the mesh
/// divided by `unit`: its value, or its order of magnitude when it has no
/// double-precision representation.
fn rescaled(inner: f64, unit: f64, degree: i32) -> Result<f64, String> {
    let value = (0..degree).fold(inner, |v, _| v * unit);
    if inner != 0.0 && inner.is_finite() && !(value.is_finite() && value.abs() >= f64::MIN_POSITIVE) {
        let exponent = (inner.abs().log10() + f64::from(degree) * unit.log10()).floor();
        Err(format!("about {}1e{exponent}", if inner < 0.0 { "-" } else { "" }))
    } else {
        Ok(value)
    }
}

impl Info {
    fn of(mesh: &TriMesh) -> Self {
        let c = mesh.connectivity();
        let report = c.non_manifold_report();
        let bbox = geometry::bounding_box(mesh);
        let closed = c.boundary_loop_count() == Some(0);
        let (normalized, unit) = mesh_kernel::units::normalized(mesh);
        let mut out_of_range = Vec::new();
        let mut carry = |name: &str, inner: f64, degree: i32| match rescaled(inner, unit, degree) {
            Ok(v) => Some(v),
            Err(magnitude) => {
                out_of_range.push(format!("{name} {magnitude}"));
                None
            }
        };
        let area = carry("area", geometry::surface_area(&normalized), 2);
        let volume = if closed { carry("volume", geometry::enclosed_volume(&normalized), 3) } else { None };
        Info {
            vertices: mesh.vertex_count(),
            faces: mesh.face_count(),
            edges: c.edge_count(),
            euler_characteristic: c.euler_characteristic(),
            genus: c.genus(),
            components: c.components().count,
            boundary_loops: c.boundary_loop_count(),
            manifold: c.is_manifold(),
            non_manifold_edges: report.edges.len(),
            non_manifold_vertices: report.vertices.len(),
            inconsistent_edges: report.inconsistent_edges.len(),
            degenerate_faces: clean::degenerate_faces(mesh, clean::CleanOptions::default().degenerate_tolerance).len(),
            duplicate_faces: clean::duplicate_faces(mesh.faces()).len(),
            unreferenced_vertices: clean::unreferenced_vertices(mesh.vertex_count(), mesh.faces()).len(),
            coincident_vertices: clean::weld_vertices(mesh.positions(), &[], 0.0).map_or(0, |(_, _, merged)| merged),
            area,
            volume,
            out_of_range,
            mean_edge_length: geometry::mean_edge_length(mesh),
            bbox_min: bbox.map(|b| b.min.to_array()),
            bbox_max: bbox.map(|b| b.max.to_array()),
        }
    }

    fn into_dict(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("vertices", self.vertices)?;
        d.set_item("faces", self.faces)?;
        d.set_item("edges", self.edges)?;
        d.set_item("euler_characteristic", self.euler_characteristic)?;
        d.set_item("genus", self.genus)?;
        d.set_item("components", self.components)?;
        d.set_item("boundary_loops", self.boundary_loops)?;
        d.set_item("manifold", self.manifold)?;
        d.set_item("non_manifold_edges", self.non_manifold_edges)?;
        d.set_item("non_manifold_vertices", self.non_manifold_vertices)?;
        d.set_item("inconsistent_edges", self.inconsistent_edges)?;
        d.set_item("degenerate_faces", self.degenerate_faces)?;
        d.set_item("duplicate_faces", self.duplicate_faces)?;
        d.set_item("unreferenced_vertices", self.unreferenced_vertices)?;
        d.set_item("coincident_vertices", self.coincident_vertices)?;
        d.set_item("area", self.area)?;
        d.set_item("volume", self.volume)?;
        d.set_item("out_of_range", self.out_of_range)?;
        d.set_item("mean_edge_length", self.mean_edge_length)?;
        d.set_item("bbox_min", self.bbox_min.map(|b| b.to_vec()))?;
        d.set_item("bbox_max", self.bbox_max.map(|b| b.to_vec()))?;
        Ok(d)
    }
}

/// The measures of `mesh info --json` for arrays; `attributes` is an empty
/// list and `read` is None (nothing was read from a file).
#[pyfunction]
pub fn info<'py>(py: Python<'py>, v: PyReadonlyArray2<'py, f64>, f: Faces<'py>) -> PyResult<Bound<'py, PyDict>> {
    let arrays = Arrays::new(&v, &f)?;
    let info = run(py, move || Ok(Info::of(&arrays.mesh()?)))?;
    let d = info.into_dict(py)?;
    d.set_item("attributes", PyList::empty(py))?;
    d.set_item("read", py.None())?;
    Ok(d)
}

/// `mesh info FILE --json` as a dict: the measures, the file's attributes and what reading changed.
#[pyfunction]
pub fn info_file<'py>(py: Python<'py>, path: std::path::PathBuf) -> PyResult<Bound<'py, PyDict>> {
    let (info, attributes, read) = run(py, move || {
        let data = mesh_io::read(&path)?;
        let info = Info::of(&data.mesh);
        Ok((info, crate::io::attribute_list(&data), data.report))
    })?;
    let d = info.into_dict(py)?;
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
