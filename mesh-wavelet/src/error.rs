//! The one error type of the crate.

use mesh_kernel::MeshError;
use thiserror::Error;

/// Everything that can go wrong in `mesh-wavelet`.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum WaveletError {
    /// An error of the mesh data model: invalid, empty or non-manifold input
    /// ([`MeshError::NonManifold`] lists every defect).
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// The mesh is not the result of recursive 4-to-1 splitting of a coarser
    /// mesh (not even once), so it has no multiresolution representation.
    #[error("the mesh has no subdivision connectivity: {reason}")]
    NoSubdivisionConnectivity {
        /// Why the reverse 4-to-1 splitting failed.
        reason: String,
    },
    /// A level index beyond the hierarchy.
    #[error("level {level} is out of range: the hierarchy has levels 0..={levels}")]
    LevelOutOfRange {
        /// The requested level.
        level: usize,
        /// The finest level J.
        levels: usize,
    },
    /// An option or argument is out of its valid range.
    #[error("invalid option `{name}`: {reason}")]
    InvalidOption {
        /// Name of the option.
        name: &'static str,
        /// Why it was refused.
        reason: String,
    },
    /// Sizes disagree (positions, coefficients, levels).
    #[error("dimension mismatch: {0}")]
    Dimension(String),
}

/// Shorthand for results in this crate.
pub type Result<T, E = WaveletError> = std::result::Result<T, E>;
