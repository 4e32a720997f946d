//! numpy arrays in and out, and the one way every function runs its work.
//!
//! In: `V` float64 (n, 3) and `F` int32 or int64 (m, 3) are read in place
//! (no numpy-side conversion; a C-contiguous array is read as one slice) and
//! copied once into the [`TriMesh`] that owns them, with the GIL held, so
//! that no Python thread can change them under the computation.
//!
//! Out: vectors are handed to numpy without a copy (`Vec<f64>` and, by
//! [`bytemuck::cast_vec`], `Vec<DVec3>` become the array's buffer);
//! triangles are widened to int64; sparse matrices go out as their CSR
//! arrays, which the Python side wraps in `scipy.sparse.csr_matrix`.

use std::panic::{catch_unwind, AssertUnwindSafe};

use glam::{DVec2, DVec3};
use mesh_kernel::sprs::CsMat;
use mesh_kernel::{TriMesh, VertexId};
use numpy::ndarray::ArrayView2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;

use crate::errors::{Failure, Fallible};

/// Triangles as numpy holds them: int32 or int64.
#[derive(FromPyObject)]
pub enum Faces<'py> {
    /// int64 (numpy's default integer, libigl's `F`).
    I64(PyReadonlyArray2<'py, i64>),
    /// int32.
    I32(PyReadonlyArray2<'py, i32>),
}

impl Faces<'_> {
    /// Number of triangles (rows of `F`).
    pub fn rows(&self) -> usize {
        match self {
            Faces::I64(a) => a.as_array().nrows(),
            Faces::I32(a) => a.as_array().nrows(),
        }
    }
}

/// Vertex indices as numpy holds them (sources of a geodesic query).
#[derive(FromPyObject)]
pub enum Indices<'py> {
    /// int64.
    I64(PyReadonlyArray1<'py, i64>),
    /// int32.
    I32(PyReadonlyArray1<'py, i32>),
}

/// Runs one stage of a call without the GIL, catching panics (a bug, raised
/// as `MeshkitError`, never unwound into the interpreter), then lets Python
/// handle a pending signal: Ctrl-C during a stage raises `KeyboardInterrupt`
/// when the stage ends (the Rust crates have no cancellation points inside
/// a stage).
pub fn run<T: Send>(py: Python<'_>, work: impl FnOnce() -> Fallible<T> + Send) -> PyResult<T> {
    let out = py.detach(|| catch_unwind(AssertUnwindSafe(work)));
    py.check_signals()?;
    match out {
        Ok(result) => result.map_err(PyErr::from),
        Err(payload) => Err(Failure::panic(payload).into()),
    }
}

fn rows3<T: Copy>(a: ArrayView2<'_, T>, what: &str) -> Fallible<Vec<[T; 3]>> {
    if a.ncols() != 3 {
        return Err(Failure::mesh(format!("{what} must have shape (n, 3), not {:?}", a.shape())));
    }
    Ok(match a.as_slice() {
        Some(flat) => flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
        None => a.rows().into_iter().map(|r| [r[0], r[1], r[2]]).collect(),
    })
}

/// Copies `V` into positions (shape checked; finiteness is checked by [`TriMesh::new`]).
pub fn positions(v: &PyReadonlyArray2<'_, f64>) -> Fallible<Vec<DVec3>> {
    Ok(rows3(v.as_array(), "V")?.into_iter().map(DVec3::from_array).collect())
}

/// Copies `F` into triangles, refusing negative indices and indices past `u32`.
pub fn faces(f: &Faces<'_>) -> Fallible<Vec<[u32; 3]>> {
    fn narrow<T: Copy + Into<i64>>(rows: Vec<[T; 3]>) -> Fallible<Vec<[u32; 3]>> {
        rows.into_iter()
            .enumerate()
            .map(|(i, t)| {
                let mut out = [0u32; 3];
                for k in 0..3 {
                    let x: i64 = t[k].into();
                    out[k] = u32::try_from(x).map_err(|_| {
                        Failure::mesh(format!("face {i} refers to vertex {x}, which is not a valid vertex index"))
                    })?;
                }
                Ok(out)
            })
            .collect()
    }
    match f {
        Faces::I64(a) => narrow(rows3(a.as_array(), "F")?),
        Faces::I32(a) => narrow(rows3(a.as_array(), "F")?),
    }
}

/// Vertex ids from an index array, each checked against `n`.
pub fn vertex_ids(s: &Indices<'_>, n: usize) -> Fallible<Vec<VertexId>> {
    let values: Vec<i64> = match s {
        Indices::I64(a) => a.as_array().iter().copied().collect(),
        Indices::I32(a) => a.as_array().iter().map(|&x| i64::from(x)).collect(),
    };
    values
        .into_iter()
        .map(|x| match usize::try_from(x) {
            Ok(i) if i < n => Ok(VertexId::new(i)),
            _ => Err(Failure::option(format!("vertex {x} is out of range: the mesh has {n} vertices"))),
        })
        .collect()
}

/// The arrays read under the GIL; [`Arrays::mesh`] validates them without it.
pub struct Arrays {
    positions: Vec<DVec3>,
    faces: Vec<[u32; 3]>,
}

impl Arrays {
    /// Copies `V` and `F` (shapes checked).
    pub fn new(v: &PyReadonlyArray2<'_, f64>, f: &Faces<'_>) -> PyResult<Self> {
        Ok(Self { positions: positions(v)?, faces: faces(f)? })
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// The positions and triangles, unchecked (for `clean`, which accepts
    /// triangles with a repeated corner).
    pub fn into_parts(self) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        (self.positions, self.faces)
    }

    /// The mesh: indices in range, coordinates finite, no repeated corner.
    pub fn mesh(self) -> Fallible<TriMesh> {
        Ok(TriMesh::new(self.positions, self.faces)?)
    }
}

/// A vector as a 1-D array, without a copy.
pub fn vec1<'py, T: numpy::Element>(py: Python<'py>, v: Vec<T>) -> Bound<'py, PyArray1<T>> {
    v.into_pyarray(py)
}

/// `n` points as an (n, 3) float64 array, without a copy.
pub fn points<'py>(py: Python<'py>, p: Vec<DVec3>) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let n = p.len();
    let flat: Vec<f64> =
        bytemuck::try_cast_vec(p).unwrap_or_else(|(_, p)| p.iter().flat_map(|x| x.to_array()).collect());
    flat.into_pyarray(py).reshape([n, 3])
}

/// `n` 2-D points as an (n, 2) float64 array, without a copy.
pub fn points2<'py>(py: Python<'py>, p: Vec<DVec2>) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let n = p.len();
    let flat: Vec<f64> =
        bytemuck::try_cast_vec(p).unwrap_or_else(|(_, p)| p.iter().flat_map(|x| x.to_array()).collect());
    flat.into_pyarray(py).reshape([n, 2])
}

/// Triangles as an (m, 3) int64 array.
pub fn triangles<'py>(py: Python<'py>, f: &[[u32; 3]]) -> PyResult<Bound<'py, PyArray2<i64>>> {
    let flat: Vec<i64> = f.iter().flat_map(|t| t.map(i64::from)).collect();
    flat.into_pyarray(py).reshape([f.len(), 3])
}

/// A mesh as `(V, F)`.
pub fn mesh_arrays<'py>(py: Python<'py>, mesh: TriMesh) -> PyResult<MeshArrays<'py>> {
    let (p, f) = mesh.into_parts();
    Ok((points(py, p)?, triangles(py, &f)?))
}

/// `(V, F)` as returned to Python.
pub type MeshArrays<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<i64>>);

/// A sparse matrix as `(data, indices, indptr, (rows, cols))` of CSR, the
/// arguments of `scipy.sparse.csr_matrix`.
pub type Csr<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<i64>>, Bound<'py, PyArray1<i64>>, (usize, usize));

/// Hands a sparse matrix to Python as its CSR arrays (converted to CSR first if needed).
pub fn csr(py: Python<'_>, m: CsMat<f64>) -> Csr<'_> {
    let m = if m.is_csr() { m } else { m.to_csr() };
    let shape = m.shape();
    let (indptr, indices, data) = m.into_raw_storage();
    let widen = |v: Vec<usize>| -> Vec<i64> {
        bytemuck::try_cast_vec(v).unwrap_or_else(|(_, v)| v.iter().map(|&x| x as i64).collect())
    };
    (data.into_pyarray(py), widen(indices).into_pyarray(py), widen(indptr).into_pyarray(py), shape)
}

/// Reads a per-vertex float field, which must have `n` values.
pub fn field(values: &PyReadonlyArray1<'_, f64>, n: usize, what: &str) -> Fallible<Vec<f64>> {
    let a = values.as_array();
    if a.len() != n {
        return Err(Failure::option(format!("{what} has {} values for {n} vertices", a.len())));
    }
    Ok(a.iter().copied().collect())
}

/// Reads an (n, 3) float array of per-vertex vectors.
pub fn vectors(values: &PyReadonlyArray2<'_, f64>, n: usize, what: &str) -> Fallible<Vec<DVec3>> {
    let rows = rows3(values.as_array(), what)?;
    if rows.len() != n {
        return Err(Failure::option(format!("{what} has {} rows for {n} vertices", rows.len())));
    }
    Ok(rows.into_iter().map(DVec3::from_array).collect())
}
