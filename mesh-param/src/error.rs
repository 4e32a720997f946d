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

/// The entry of `all` named `s` (by `name`), or [`ParamError::InvalidOption`]
/// on `option` listing the names: the one `FromStr` of the crate's
/// selectable enums. O(all).
pub(crate) fn by_name<T: Clone>(
    all: &[T],
    name: impl Fn(&T) -> &'static str,
    s: &str,
    option: &'static str,
) -> Result<T> {
    all.iter().find(|x| name(x) == s).cloned().ok_or_else(|| ParamError::InvalidOption {
        name: option,
        reason: format!("unknown `{s}`; known: {}", all.iter().map(&name).collect::<Vec<_>>().join(", ")),
    })
}

/// `Display` and `FromStr` of a selectable enum from its `ALL` and `name()`.
macro_rules! named_enum {
    ($t:ty, $option:literal) => {
        impl std::fmt::Display for $t {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl std::str::FromStr for $t {
            type Err = $crate::error::ParamError;

            fn from_str(s: &str) -> $crate::error::Result<Self> {
                $crate::error::by_name(&Self::ALL, |x| x.name(), s, $option)
            }
        }
    };
}
pub(crate) use named_enum;
