//! The error type of the crate.

use mesh_delaunay::DelaunayError;
use mesh_kernel::MeshError;
use mesh_param::ParamError;
use thiserror::Error;

/// Everything that can go wrong while remeshing.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum RemeshError {
    /// An error of the underlying mesh library (a non-manifold input, an
    /// invalid output mesh).
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// The atlas could not be built.
    #[error("the atlas failed: {0}")]
    Param(#[from] ParamError),
    /// An option is out of range.
    #[error("invalid option `{name}`: {reason}")]
    InvalidOption {
        /// Name of the option.
        name: &'static str,
        /// Why it was refused.
        reason: String,
    },
    /// The edge length asks for more vertices than the bound allows.
    #[error(
        "an edge length of {edge_length} needs about {estimated} vertices, more than the bound of {limit} \
         (max_vertices): choose a longer edge length"
    )]
    TooManyVertices {
        /// The edge length asked for.
        edge_length: f64,
        /// The estimated vertex count (or the count reached).
        estimated: usize,
        /// The bound.
        limit: usize,
    },
    /// The triangulation of one chart's parameter domain failed.
    #[error("chart {chart}: the triangulation of its parameter domain failed: {source}")]
    Delaunay {
        /// The chart (index into the atlas's charts).
        chart: usize,
        /// What failed.
        source: DelaunayError,
    },
    /// One chart could not be remeshed (see the reason): a chart not
    /// flattened to a disk, an incomplete refinement, a parameter point
    /// outside the chart, a collapsed output triangle.
    #[error("chart {chart}: {reason}")]
    ChartFailed {
        /// The chart (index into the atlas's charts).
        chart: usize,
        /// What failed.
        reason: String,
    },
}

/// Shorthand for results of this crate.
pub type Result<T, E = RemeshError> = std::result::Result<T, E>;
