//! Typed element indices.
//!
//! Vertices, faces, edges and half-edges are all numbered from zero, but mixing
//! them up is a classic source of bugs. Each kind gets its own newtype over
//! `u32` so that the compiler keeps them apart. Per-element data stays a plain
//! `Vec<T>` or slice, indexed with [`VertexId::idx`] and friends.

use std::fmt;

macro_rules! typed_id {
    ($(#[$doc:meta])* $name:ident, $prefix:literal) => {
        $(#[$doc])*
        #[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
        pub struct $name(pub u32);

        impl $name {
            /// The sentinel for "no such element" (`u32::MAX`).
            pub const INVALID: Self = Self(u32::MAX);

            /// Wraps a `usize` index. Indices above `u32::MAX` are a logic error
            /// of the caller; mesh construction rejects meshes that large.
            #[inline]
            pub const fn new(index: usize) -> Self {
                Self(index as u32)
            }

            /// The index as `usize`, for indexing slices.
            #[inline]
            pub const fn idx(self) -> usize {
                self.0 as usize
            }

            /// `true` unless this is [`Self::INVALID`].
            #[inline]
            pub const fn is_valid(self) -> bool {
                self.0 != u32::MAX
            }
        }

        impl fmt::Debug for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                if self.is_valid() {
                    write!(f, concat!($prefix, "{}"), self.0)
                } else {
                    f.write_str(concat!($prefix, "-"))
                }
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                fmt::Debug::fmt(self, f)
            }
        }

        impl From<$name> for usize {
            #[inline]
            fn from(id: $name) -> usize {
                id.idx()
            }
        }

        impl From<$name> for u32 {
            #[inline]
            fn from(id: $name) -> u32 {
                id.0
            }
        }
    };
}

typed_id!(
    /// Index of a vertex (a position in [`crate::TriMesh::positions`]).
    VertexId,
    "v"
);
typed_id!(
    /// Index of a triangle (an entry of [`crate::TriMesh::faces`]).
    FaceId,
    "f"
);
typed_id!(
    /// Index of an undirected edge of [`crate::Connectivity`].
    EdgeId,
    "e"
);
typed_id!(
    /// Index of a half-edge: half-edge `3 f + k` runs from corner `k` of face `f`
    /// to corner `k + 1 (mod 3)`, so face, next and origin are implicit.
    HalfedgeId,
    "h"
);

impl HalfedgeId {
    /// The face this half-edge belongs to.
    #[inline]
    pub const fn face(self) -> FaceId {
        FaceId(self.0 / 3)
    }

    /// Position of the half-edge's origin among its face's corners (0, 1 or 2).
    #[inline]
    pub const fn corner(self) -> usize {
        (self.0 % 3) as usize
    }

    /// The next half-edge around the same face (counter-clockwise).
    #[inline]
    pub const fn next(self) -> Self {
        let base = self.0 - self.0 % 3;
        Self(base + (self.0 + 1) % 3)
    }

    /// The previous half-edge around the same face.
    #[inline]
    pub const fn prev(self) -> Self {
        let base = self.0 - self.0 % 3;
        Self(base + (self.0 + 2) % 3)
    }

    /// The half-edge leaving corner `corner` of face `face`.
    #[inline]
    pub const fn of_corner(face: FaceId, corner: usize) -> Self {
        Self(face.0 * 3 + corner as u32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halfedge_cycle_is_three() {
        for h in 0..12u32 {
            let h = HalfedgeId(h);
            assert_eq!(h.next().next().next(), h);
            assert_eq!(h.next().prev(), h);
            assert_eq!(h.next().face(), h.face());
        }
    }

    #[test]
    fn debug_names_the_kind() {
        assert_eq!(format!("{:?}", VertexId(3)), "v3");
        assert_eq!(format!("{}", FaceId::INVALID), "f-");
    }
}
