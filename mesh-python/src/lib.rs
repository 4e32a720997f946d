//! `meshkit._meshkit`: the native half of the `meshkit` Python package.
//!
//! Every function wraps one public function of the workspace's crates on
//! numpy arrays; the Python half (`python/meshkit/__init__.py`) checks and
//! converts the arguments, wraps sparse matrices in `scipy.sparse` and
//! documents the API. Conventions of the binding:
//!
//! - `V` is float64 (n, 3), `F` int32 or int64 (m, 3); both are copied once
//!   into the mesh, under the GIL; results are handed to numpy without a
//!   copy where the layout allows (module `convert`).
//! - The GIL is released while Rust computes; signals (Ctrl-C) are checked
//!   between the stages of a call (`convert::run`).
//! - Every error is a typed Python exception carrying the Rust error's text
//!   (module `errors`); a panic is caught and raised as `MeshkitError`, never
//!   unwound into the interpreter.

// Python functions return tuples of arrays, spelled out in the signatures.
#![allow(clippy::type_complexity)]

mod convert;
mod errors;
mod geodesic;
mod info;
mod io;
mod operators;
mod param;
mod remesh;
mod spectral;
mod topology;
mod wavelet;

use pyo3::prelude::*;

/// Freed large arrays kept for the next call instead of faulted in again
/// (see `mesh_kernel::alloc`); results handed to numpy without a copy are
/// released through this allocator too.
#[global_allocator]
static ALLOCATOR: mesh_kernel::alloc::BlockCache = mesh_kernel::alloc::BlockCache;

/// The native module.
#[pymodule]
fn _meshkit(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(info::info, m)?)?;
    m.add_function(wrap_pyfunction!(info::info_file, m)?)?;
    m.add_function(wrap_pyfunction!(io::read, m)?)?;
    m.add_function(wrap_pyfunction!(io::read_attributes, m)?)?;
    m.add_function(wrap_pyfunction!(io::write, m)?)?;
    m.add_function(wrap_pyfunction!(io::shape, m)?)?;
    m.add_function(wrap_pyfunction!(operators::cotan_laplacian, m)?)?;
    m.add_function(wrap_pyfunction!(operators::uniform_laplacian, m)?)?;
    m.add_function(wrap_pyfunction!(operators::adjacency_matrix, m)?)?;
    m.add_function(wrap_pyfunction!(operators::gradient, m)?)?;
    m.add_function(wrap_pyfunction!(operators::divergence, m)?)?;
    m.add_function(wrap_pyfunction!(operators::mass_matrix, m)?)?;
    m.add_function(wrap_pyfunction!(operators::lumped_mass, m)?)?;
    m.add_function(wrap_pyfunction!(operators::intrinsic_delaunay_laplacian, m)?)?;
    m.add_function(wrap_pyfunction!(operators::vertex_normals, m)?)?;
    m.add_function(wrap_pyfunction!(operators::face_normals, m)?)?;
    m.add_function(wrap_pyfunction!(operators::face_areas, m)?)?;
    m.add_function(wrap_pyfunction!(operators::gaussian_curvature, m)?)?;
    m.add_function(wrap_pyfunction!(operators::mean_curvature, m)?)?;
    m.add_function(wrap_pyfunction!(operators::principal_curvature, m)?)?;
    m.add_function(wrap_pyfunction!(operators::shape_index_histogram, m)?)?;
    m.add_function(wrap_pyfunction!(topology::clean_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(topology::edges, m)?)?;
    m.add_function(wrap_pyfunction!(topology::boundary_loops, m)?)?;
    m.add_function(wrap_pyfunction!(topology::connected_components, m)?)?;
    m.add_class::<geodesic::HeatSolver>()?;
    m.add_class::<geodesic::FastMarchingSolver>()?;
    m.add_function(wrap_pyfunction!(geodesic::fmm_distance, m)?)?;
    m.add_function(wrap_pyfunction!(geodesic::exact_distance, m)?)?;
    m.add_function(wrap_pyfunction!(geodesic::dijkstra, m)?)?;
    m.add_function(wrap_pyfunction!(geodesic::trace_path, m)?)?;
    m.add_function(wrap_pyfunction!(geodesic::farthest_point_sampling, m)?)?;
    m.add_function(wrap_pyfunction!(param::parameterize, m)?)?;
    m.add_function(wrap_pyfunction!(param::parameterize_cut_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(remesh::remesh, m)?)?;
    m.add_function(wrap_pyfunction!(spectral::eigenpairs, m)?)?;
    m.add_function(wrap_pyfunction!(spectral::heat_kernel_signature, m)?)?;
    m.add_class::<spectral::Harmonics>()?;
    m.add_function(wrap_pyfunction!(wavelet::subdivide, m)?)?;
    m.add_function(wrap_pyfunction!(wavelet::loop_subdivide_timed, m)?)?;
    m.add_class::<wavelet::Multiresolution>()?;
    Ok(())
}
