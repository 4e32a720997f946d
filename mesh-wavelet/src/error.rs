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

/// The entry of `all` named `s` (by `name`), or [`WaveletError::InvalidOption`]
/// on `option` listing the names: the one `FromStr` of the crate's
/// selectable enums. O(all).
pub(crate) fn by_name<T: Clone>(
    all: &[T],
    name: impl Fn(&T) -> &'static str,
    s: &str,
    option: &'static str,
) -> Result<T> {
    all.iter().find(|x| name(x) == s).cloned().ok_or_else(|| WaveletError::InvalidOption {
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
            type Err = $crate::error::WaveletError;

            fn from_str(s: &str) -> $crate::error::Result<Self> {
                $crate::error::by_name(&Self::ALL, |x| x.name(), s, $option)
            }
        }
    };
}
pub(crate) use named_enum;
