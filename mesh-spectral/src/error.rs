//! The error type of the crate.

use mesh_kernel::MeshError;
use thiserror::Error;

/// Everything that can go wrong in `mesh-spectral`.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SpectralError {
    /// An error from `mesh-kernel` (invalid mesh, factorization failure, ...).
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
    /// Some wanted pair missed the tolerance after every attempt (more
    /// restarts, a larger block, another shift): no pair is returned.
    #[error(
        "eigensolver did not converge: {converged} of {wanted} pairs met the tolerance {tolerance:e} after {attempts} attempt(s) and {restarts} restarts; relative residuals of the wanted pairs: {}",
        list(.residuals)
    )]
    NotConverged {
        /// Pairs that met the tolerance.
        converged: usize,
        /// Pairs wanted.
        wanted: usize,
        /// Attempts made (each with more restarts, a larger block or another shift).
        attempts: usize,
        /// Thick restarts, summed over the attempts.
        restarts: usize,
        /// The tolerance the residuals were held to.
        tolerance: f64,
        /// Relative residual (or, when the iteration itself stopped, its
        /// residual estimate) of each wanted pair in the last attempt.
        residuals: Vec<f64>,
    },
    /// A dense factorization or eigendecomposition failed.
    #[error("dense linear algebra failed: {0}")]
    Dense(String),
}

/// Residuals in scientific notation, the worst first when there are many.
fn list(residuals: &[f64]) -> String {
    const SHOWN: usize = 8;
    let mut sorted: Vec<f64> = residuals.to_vec();
    if sorted.len() > SHOWN {
        sorted.sort_by(|a, b| b.total_cmp(a));
        sorted.truncate(SHOWN);
        let shown: Vec<String> = sorted.iter().map(|r| format!("{r:.1e}")).collect();
        return format!("[{}, ...] (the {SHOWN} largest of {})", shown.join(", "), residuals.len());
    }
    let shown: Vec<String> = sorted.iter().map(|r| format!("{r:.1e}")).collect();
    format!("[{}]", shown.join(", "))
}

/// Shorthand for results in this crate.
pub type Result<T, E = SpectralError> = std::result::Result<T, E>;
