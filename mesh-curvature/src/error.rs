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

/// The entry of `all` named `s` (by `name`), or
/// [`CurvatureError::InvalidOption`] on `option` listing the names: the one
/// `FromStr` of the crate's selectable enums. O(all).
pub(crate) fn by_name<T: Clone>(
    all: &[T],
    name: impl Fn(&T) -> &'static str,
    s: &str,
    option: &'static str,
) -> Result<T> {
    all.iter().find(|x| name(x) == s).cloned().ok_or_else(|| CurvatureError::InvalidOption {
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
            type Err = $crate::error::CurvatureError;

            fn from_str(s: &str) -> $crate::error::Result<Self> {
                $crate::error::by_name(&Self::ALL, |x| x.name(), s, $option)
            }
        }
    };
}
pub(crate) use named_enum;
