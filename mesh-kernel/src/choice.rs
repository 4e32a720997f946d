//! Named choices: every enum that selects a method or a quantity, in every
//! crate and in the command line, has one list of names, written once as an
//! inherent `pub const ALL: [Self; N]` and `pub fn name(&self) -> &'static str`.
//! [`named_choice!`](crate::named_choice) derives `Display` and `FromStr`
//! from them: exactly the names are accepted (no aliases, no case folding),
//! and an unknown one is refused with the crate's
//! `InvalidOption { name, reason }` error listing the valid names. See
//! [`conventions`](crate::conventions), section 3.
//!
//! ```
//! use mesh_kernel::operators::{LaplacianKind, MassKind};
//!
//! let mass: MassKind = "voronoi".parse()?;
//! assert!("Voronoi".parse::<MassKind>().is_err());
//! assert_eq!(mass, MassKind::MixedVoronoi);
//! assert_eq!(LaplacianKind::IntrinsicDelaunay.to_string(), "intrinsic");
//! assert_eq!(MassKind::ALL.map(|m| m.name()), ["barycentric", "voronoi", "galerkin"]);
//! let refused = "cotangent".parse::<LaplacianKind>().unwrap_err();
//! assert!(refused.to_string().contains("auto, cotan, intrinsic"));
//! # Ok::<(), mesh_kernel::MeshError>(())
//! ```

/// The entry of `all` whose `name` is exactly `s`, or the reason it is refused, listing the names. The one
/// parse behind [`named_choice!`](crate::named_choice). O(all).
///
/// # Errors
/// The reason text for the caller's `InvalidOption` error.
pub fn find<T: Clone>(all: &[T], name: impl Fn(&T) -> &'static str, s: &str) -> Result<T, String> {
    all.iter().find(|x| name(x) == s).cloned().ok_or_else(|| {
        let known: Vec<&str> = all.iter().map(&name).collect();
        format!("unknown `{s}`; known: {}", known.join(", "))
    })
}

/// `Display` and `FromStr` of a selectable enum from its inherent `ALL` and
/// `name()`: `named_choice!(Type, "what is chosen", ErrorType)`, where
/// `ErrorType` (in scope) has a variant
/// `InvalidOption { name: &'static str, reason: String }`.
#[macro_export]
macro_rules! named_choice {
    ($t:ty, $what:literal, $err:ident) => {
        impl ::std::fmt::Display for $t {
            fn fmt(&self, f: &mut ::std::fmt::Formatter<'_>) -> ::std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl ::std::str::FromStr for $t {
            type Err = $err;
            fn from_str(s: &str) -> ::std::result::Result<Self, $err> {
                $crate::choice::find(&<$t>::ALL, |x: &$t| x.name(), s)
                    .map_err(|reason| $err::InvalidOption { name: $what, reason })
            }
        }
    };
}
