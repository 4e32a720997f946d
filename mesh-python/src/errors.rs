//! Rust errors as typed Python exceptions.
//!
//! Every error of the workspace becomes a [`Failure`]: a kind (which
//! exception class of `meshkit._errors` it raises) and the Rust error's text.
//! The classes live in Python (`python/meshkit/_errors.py`) so that they can
//! also derive from `ValueError`, `OSError` or `FileNotFoundError`; a
//! [`Failure`] looks its class up when it becomes a `PyErr`.

use std::any::Any;

use mesh_curvature::CurvatureError;
use mesh_geodesic::GeodesicError;
use mesh_io::IoError;
use mesh_kernel::MeshError;
use mesh_param::ParamError;
use mesh_remesh::RemeshError;
use mesh_spectral::SpectralError;
use mesh_wavelet::WaveletError;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::PyType;

/// Which exception class of `meshkit._errors` a failure raises.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Arrays that do not make a mesh: shapes, dtypes, indices, NaN.
    InvalidMesh,
    /// An option or argument out of its range (unknown name, k = 0, a source out of range).
    InvalidOption,
    /// The operation needs another topology (manifold, disk, semi-regular).
    Topology,
    /// Geometry too degenerate for the operation.
    Degenerate,
    /// A sparse or dense solver failed.
    Solver,
    /// An iterative solver missed its tolerance.
    NotConverged,
    /// Reading or writing a file.
    Io,
    /// The file does not exist.
    FileNotFound,
    /// Anything else (including a panic, which is a bug).
    Other,
}

impl Kind {
    fn class_name(self) -> &'static str {
        match self {
            Kind::InvalidMesh => "InvalidMeshError",
            Kind::InvalidOption => "InvalidOptionError",
            Kind::Topology => "TopologyError",
            Kind::Degenerate => "DegenerateError",
            Kind::Solver => "SolverError",
            Kind::NotConverged => "NotConvergedError",
            Kind::Io => "MeshIOError",
            Kind::FileNotFound => "MeshFileNotFoundError",
            Kind::Other => "MeshkitError",
        }
    }
}

/// An error on its way to Python: the exception class and the message.
#[derive(Debug, Clone)]
pub struct Failure {
    kind: Kind,
    message: String,
}

/// Results of the binding's Rust side.
pub type Fallible<T> = Result<T, Failure>;

impl Failure {
    /// A failure of `kind` with `message`.
    pub fn new(kind: Kind, message: impl Into<String>) -> Self {
        Self { kind, message: message.into() }
    }

    /// An invalid argument.
    pub fn option(message: impl Into<String>) -> Self {
        Self::new(Kind::InvalidOption, message)
    }

    /// Arrays that do not make a mesh.
    pub fn mesh(message: impl Into<String>) -> Self {
        Self::new(Kind::InvalidMesh, message)
    }

    /// A panic caught at the boundary: a bug, reported instead of unwinding into Python.
    pub fn panic(payload: Box<dyn Any + Send>) -> Self {
        let text = payload
            .downcast_ref::<&str>()
            .map(|s| (*s).to_owned())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".to_owned());
        Self::new(Kind::Other, format!("internal error (a bug in meshkit, please report it): {text}"))
    }
}

impl From<Failure> for PyErr {
    fn from(f: Failure) -> PyErr {
        Python::attach(|py| {
            let class = py
                .import("meshkit._errors")
                .and_then(|m| m.getattr(f.kind.class_name()))
                .and_then(|c| c.cast_into::<PyType>().map_err(PyErr::from));
            match class {
                Ok(class) => PyErr::from_type(class, f.message),
                // Only when the native module is imported without its package.
                Err(_) => PyRuntimeError::new_err(format!("{}: {}", f.kind.class_name(), f.message)),
            }
        })
    }
}

fn mesh_kind(e: &MeshError) -> Kind {
    match e {
        MeshError::IndexOutOfRange { .. }
        | MeshError::NonFinitePosition { .. }
        | MeshError::RepeatedVertex { .. }
        | MeshError::TooLarge { .. }
        | MeshError::Empty
        | MeshError::Dimension(_) => Kind::InvalidMesh,
        MeshError::NonManifold(_) | MeshError::Topology { .. } => Kind::Topology,
        MeshError::InvalidOption { .. } => Kind::InvalidOption,
        MeshError::Degenerate(_) => Kind::Degenerate,
        MeshError::Solver(_) => Kind::Solver,
        _ => Kind::Other,
    }
}

impl From<MeshError> for Failure {
    fn from(e: MeshError) -> Self {
        Self::new(mesh_kind(&e), e.to_string())
    }
}

impl From<GeodesicError> for Failure {
    fn from(e: GeodesicError) -> Self {
        let kind = match &e {
            GeodesicError::Mesh(m) => mesh_kind(m),
            GeodesicError::NoSources
            | GeodesicError::SourceOutOfRange { .. }
            | GeodesicError::InvalidOption { .. }
            | GeodesicError::InvalidSurfacePoint { .. }
            | GeodesicError::FieldLength { .. } => Kind::InvalidOption,
            GeodesicError::Unreachable => Kind::Topology,
            GeodesicError::WorkLimit { .. } => Kind::NotConverged,
            GeodesicError::Degenerate(_) => Kind::Degenerate,
            _ => Kind::Other,
        };
        Self::new(kind, e.to_string())
    }
}

impl From<CurvatureError> for Failure {
    fn from(e: CurvatureError) -> Self {
        let kind = match &e {
            CurvatureError::Mesh(m) => mesh_kind(m),
            CurvatureError::InvalidOption { .. } => Kind::InvalidOption,
            _ => Kind::Other,
        };
        Self::new(kind, e.to_string())
    }
}

impl From<ParamError> for Failure {
    fn from(e: ParamError) -> Self {
        let kind = match &e {
            ParamError::Mesh(m) => mesh_kind(m),
            ParamError::NotADisk { .. } => Kind::Topology,
            ParamError::InvalidOption { .. } => Kind::InvalidOption,
            ParamError::DegenerateFaces { .. } | ParamError::NonFinite { .. } => Kind::Degenerate,
            _ => Kind::Other,
        };
        Self::new(kind, e.to_string())
    }
}

impl From<RemeshError> for Failure {
    fn from(e: RemeshError) -> Self {
        let kind = match &e {
            RemeshError::Mesh(m) => mesh_kind(m),
            RemeshError::Param(p) => Failure::from(p.clone()).kind,
            RemeshError::InvalidOption { .. } | RemeshError::TooManyVertices { .. } => Kind::InvalidOption,
            RemeshError::Delaunay { .. } | RemeshError::ChartFailed { .. } => Kind::Degenerate,
            _ => Kind::Other,
        };
        Self::new(kind, e.to_string())
    }
}

impl From<SpectralError> for Failure {
    fn from(e: SpectralError) -> Self {
        let kind = match &e {
            SpectralError::Mesh(m) => mesh_kind(m),
            SpectralError::InvalidOption { .. }
            | SpectralError::InvalidMatrix { .. }
            | SpectralError::Dimension(_)
            | SpectralError::TooManyPairs { .. } => Kind::InvalidOption,
            SpectralError::NotConverged { .. } => Kind::NotConverged,
            SpectralError::Dense(_) => Kind::Solver,
            _ => Kind::Other,
        };
        Self::new(kind, e.to_string())
    }
}

impl From<WaveletError> for Failure {
    fn from(e: WaveletError) -> Self {
        let kind = match &e {
            WaveletError::Mesh(m) => mesh_kind(m),
            WaveletError::NoSubdivisionConnectivity { .. } => Kind::Topology,
            WaveletError::LevelOutOfRange { .. } | WaveletError::InvalidOption { .. } | WaveletError::Dimension(_) => {
                Kind::InvalidOption
            }
            _ => Kind::Other,
        };
        Self::new(kind, e.to_string())
    }
}

impl From<IoError> for Failure {
    fn from(e: IoError) -> Self {
        let kind = match &e {
            IoError::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound => Kind::FileNotFound,
            IoError::AttributeLength { .. } | IoError::AttributeName { .. } => Kind::InvalidOption,
            _ => Kind::Io,
        };
        Self::new(kind, e.to_string())
    }
}
