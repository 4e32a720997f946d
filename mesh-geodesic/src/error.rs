//! The error type of the crate.

use mesh_kernel::{FaceId, MeshError, VertexId};
use thiserror::Error;

/// Everything that can go wrong in `mesh-geodesic`.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum GeodesicError {
    /// An error of the underlying mesh machinery (connectivity, solver, ...).
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// The source set is empty.
    #[error("no source vertex given")]
    NoSources,
    /// A source vertex index is not a vertex of the mesh.
    #[error("source vertex {vertex} out of range: the mesh has {vertex_count} vertices")]
    SourceOutOfRange {
        /// The offending source.
        vertex: VertexId,
        /// Number of vertices of the mesh.
        vertex_count: usize,
    },
    /// An option or argument is out of its valid range.
    #[error("invalid option `{name}`: {reason}")]
    InvalidOption {
        /// Name of the option.
        name: &'static str,
        /// Why it was refused.
        reason: String,
    },
    /// A surface point does not lie on the mesh (face out of range, or
    /// barycentric coordinates not finite, negative or not summing to one).
    #[error("invalid surface point on face {face}: {reason}")]
    InvalidSurfacePoint {
        /// The face of the point.
        face: FaceId,
        /// What is wrong with it.
        reason: String,
    },
    /// A per-vertex field has the wrong length.
    #[error("per-vertex field `{name}` has {found} values for {expected} vertices")]
    FieldLength {
        /// Which field.
        name: &'static str,
        /// Number of vertices of the mesh.
        expected: usize,
        /// Number of values given.
        found: usize,
    },
    /// The start of a path is not connected to any source.
    #[error("the start point is not reachable from any source (other component)")]
    Unreachable,
    /// An algorithm reached its work bound before finishing (see the
    /// option that sets it, e.g. [`crate::ExactOptions::max_windows`]).
    #[error("work limit reached: more than {limit} {what}")]
    WorkLimit {
        /// What was counted.
        what: &'static str,
        /// The bound.
        limit: usize,
    },
    /// Geometry too degenerate for the chosen method, with what to use instead.
    #[error("degenerate geometry: {0}")]
    Degenerate(String),
}

/// Shorthand for results in this crate.
pub type Result<T, E = GeodesicError> = std::result::Result<T, E>;
