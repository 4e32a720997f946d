//! The error type of the crate.

use mesh_kernel::{FaceId, MeshError};
use thiserror::Error;

/// Everything that can go wrong while parameterizing.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum ParamError {
    /// An error of the underlying mesh library (non-manifold input, solver
    /// failure, dimension mismatch, ...).
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// The method needs a topological disk (one component, one boundary loop,
    /// Euler characteristic 1) and the mesh is something else. `found` says
    /// what it is, e.g. "a closed surface of genus 3" or "genus 0 with 7
    /// boundary loops"; [`crate::cut_to_disk`] turns such a mesh into a disk.
    #[error("parameterization needs a topological disk (one boundary loop, chi = 1), found {found}")]
    NotADisk {
        /// What the mesh is.
        found: String,
    },
    /// An option is out of range.
    #[error("invalid option `{name}`: {reason}")]
    InvalidOption {
        /// Name of the option.
        name: &'static str,
        /// Why it was refused.
        reason: String,
    },
    /// Zero-area faces were found and [`crate::DegeneratePolicy::Error`] asked
    /// to refuse them.
    #[error("{count} zero-area faces (first: {first}); use DegeneratePolicy::Uniform to parameterize anyway")]
    DegenerateFaces {
        /// How many faces are degenerate.
        count: usize,
        /// The first of them.
        first: FaceId,
    },
    /// The linear solve produced a non-finite coordinate (the system is too
    /// ill-conditioned for the chosen weights); no NaN is handed out.
    #[error("the solve produced a non-finite coordinate at vertex {vertex}; try Tutte or mean-value weights")]
    NonFinite {
        /// The first vertex with a non-finite coordinate.
        vertex: usize,
    },
}

/// Shorthand for results of this crate.
pub type Result<T, E = ParamError> = std::result::Result<T, E>;
