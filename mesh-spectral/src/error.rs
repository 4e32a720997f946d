//! The error type of the crate.

use mesh_core::MeshError;
use thiserror::Error;

/// Everything that can go wrong in `mesh-spectral`.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SpectralError {
    /// An error from `mesh-core` (invalid mesh, factorization failure, ...).
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// An option or argument is out of its valid range.
    #[error("invalid option `{name}`: {reason}")]
    InvalidOption {
        /// Name of the option or argument.
        name: &'static str,
        /// Why it was refused.
        reason: String,
    },
    /// A matrix handed to the eigensolver does not have the required form
    /// (square, symmetric `L`, diagonal non-negative `M`, finite entries).
    #[error("invalid matrix `{name}`: {reason}")]
    InvalidMatrix {
        /// Which matrix (`L` or `M`).
        name: &'static str,
        /// What is wrong with it.
        reason: String,
    },
    /// Sizes of matrices, vectors or coefficient lists disagree.
    #[error("dimension mismatch: {0}")]
    Dimension(String),
    /// More eigenpairs were requested than the problem has.
    #[error("{requested} eigenpairs requested, but the problem has only {available} (vertices carrying mass)")]
    TooManyPairs {
        /// How many were asked for.
        requested: usize,
        /// How many finite eigenvalues exist.
        available: usize,
    },
    /// The iteration stopped before every wanted pair met the tolerance.
    #[error("eigensolver did not converge: {converged} of {wanted} pairs after {restarts} restarts (worst relative residual {worst:e})")]
    NotConverged {
        /// Pairs that met the tolerance.
        converged: usize,
        /// Pairs wanted.
        wanted: usize,
        /// Restarts performed.
        restarts: usize,
        /// Largest relative residual estimate among the wanted pairs.
        worst: f64,
    },
    /// A dense factorization or eigendecomposition failed.
    #[error("dense linear algebra failed: {0}")]
    Dense(String),
}

/// Shorthand for results in this crate.
pub type Result<T, E = SpectralError> = std::result::Result<T, E>;
