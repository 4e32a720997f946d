//! The error type of the crate.

use thiserror::Error;

/// Everything that can go wrong in `mesh-curvature`.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum CurvatureError {
    /// An error of the underlying mesh (invalid input, non-manifold, ...).
    #[error(transparent)]
    Mesh(#[from] mesh_kernel::MeshError),
    /// An option is out of its valid range.
    #[error("invalid option `{name}`: {reason}")]
    InvalidOption {
        /// Name of the option.
        name: &'static str,
        /// Why it was refused.
        reason: String,
    },
}

/// Shorthand for results of this crate.
pub type Result<T, E = CurvatureError> = std::result::Result<T, E>;
