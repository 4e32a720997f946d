//! Named choices: every enum that selects a method or a quantity has one list
//! of names, parsed (case-insensitively, surrounding spaces ignored) and
//! displayed the same way by every crate and by the command line.
//!
//! ```
//! use mesh_kernel::operators::{LaplacianKind, MassKind};
//! use mesh_kernel::choice::Choice;
//!
//! let mass: MassKind = "voronoi".parse()?;
//! assert_eq!(mass, MassKind::MixedVoronoi);
//! assert_eq!(LaplacianKind::IntrinsicDelaunay.to_string(), "intrinsic");
//! assert_eq!(MassKind::NAMES, ["barycentric", "voronoi", "galerkin"]);
//! assert!("cotangent".parse::<LaplacianKind>().is_err()); // names the valid ones
//! # Ok::<(), mesh_kernel::MeshError>(())
//! ```

use crate::error::{MeshError, Result};

/// A selectable enum with one name per variant.
pub trait Choice: Sized + Copy + PartialEq + 'static {
    /// Every variant, in the order of [`Choice::NAMES`].
    const ALL: &'static [Self];
    /// The name of each variant of [`Choice::ALL`], as parsed and displayed.
    const NAMES: &'static [&'static str];
    /// What is being chosen, for messages ("laplacian", "mass").
    const WHAT: &'static str;

    /// The name of this variant.
    fn name(self) -> &'static str {
        Self::ALL.iter().position(|v| *v == self).and_then(|i| Self::NAMES.get(i)).copied().unwrap_or("?")
    }

    /// The variant called `s` (case-insensitive, surrounding spaces ignored).
    ///
    /// # Errors
    /// [`MeshError::InvalidOption`] naming [`Choice::WHAT`] and listing the valid names.
    fn from_name(s: &str) -> Result<Self> {
        Self::NAMES
            .iter()
            .position(|n| n.eq_ignore_ascii_case(s.trim()))
            .and_then(|i| Self::ALL.get(i))
            .copied()
            .ok_or_else(|| MeshError::InvalidOption {
                name: Self::WHAT,
                reason: format!("unknown `{s}`; known: {}", Self::NAMES.join(", ")),
            })
    }
}

/// Implements `FromStr` (with [`MeshError`]) and `Display` for a [`Choice`].
#[macro_export]
macro_rules! choice_str {
    ($t:ty) => {
        impl ::std::str::FromStr for $t {
            type Err = $crate::MeshError;
            fn from_str(s: &str) -> ::std::result::Result<Self, $crate::MeshError> {
                <$t as $crate::choice::Choice>::from_name(s)
            }
        }
        impl ::std::fmt::Display for $t {
            fn fmt(&self, f: &mut ::std::fmt::Formatter<'_>) -> ::std::fmt::Result {
                f.write_str($crate::choice::Choice::name(*self))
            }
        }
    };
}
