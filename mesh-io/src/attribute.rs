//! Named attributes beyond positions, normals, texture coordinates and
//! colours: per-vertex or per-face scalars (`f64`), 3-vectors (`DVec3`) and
//! integer labels (`i64`), as [`crate::MeshData`] holds them and
//! [`crate::MeshView`] hands them to the writers.
//!
//! What each format keeps: PLY all of them (vectors as `NAMEx NAMEy NAMEz`
//! property triples, labels as `int`, face attributes as properties of the
//! `face` element); glTF the per-vertex ones (`_NAME` accessors: `SCALAR`
//! or `VEC3` floats, labels as unsigned or signed shorts); OBJ, OFF and STL
//! none. What a format cannot hold is named in
//! [`crate::WriteReport::dropped`], never left out silently.

use std::fmt;

use glam::DVec3;

/// The elements an attribute gives one value each.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum AttributeElement {
    /// One value per vertex of the mesh.
    Vertex,
    /// One value per triangle of the mesh.
    Face,
}

impl fmt::Display for AttributeElement {
    /// `vertex` or `face`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Vertex => "vertex",
            Self::Face => "face",
        })
    }
}

/// What one value of a named attribute is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum AttributeKind {
    /// A real number (`f64`): a curvature, a distance, a distortion.
    Scalar,
    /// Three real numbers (`DVec3`): a direction, a gradient.
    Vector,
    /// An integer (`i64`): a component, chart or segment number, a flag.
    Label,
}

impl AttributeKind {
    /// Numbers per value: 1, 3 or 1.
    pub fn arity(self) -> usize {
        match self {
            Self::Scalar | Self::Label => 1,
            Self::Vector => 3,
        }
    }
}

impl fmt::Display for AttributeKind {
    /// `scalar`, `vector` or `label`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Scalar => "scalar",
            Self::Vector => "vector",
            Self::Label => "label",
        })
    }
}

/// The borrowed values of a named attribute.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AttributeValues<'a> {
    /// One real number per element.
    Scalar(&'a [f64]),
    /// One 3-vector per element.
    Vector(&'a [DVec3]),
    /// One integer per element.
    Label(&'a [i64]),
}

impl AttributeValues<'_> {
    /// The kind of value.
    pub fn kind(&self) -> AttributeKind {
        match self {
            Self::Scalar(_) => AttributeKind::Scalar,
            Self::Vector(_) => AttributeKind::Vector,
            Self::Label(_) => AttributeKind::Label,
        }
    }

    /// The number of elements given a value.
    pub fn len(&self) -> usize {
        match self {
            Self::Scalar(v) => v.len(),
            Self::Vector(v) => v.len(),
            Self::Label(v) => v.len(),
        }
    }

    /// `true` when no element has a value.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// A named attribute: its name, the elements it covers and its values.
/// Listed by [`crate::MeshData::attributes`] and held by
/// [`crate::MeshView::attributes`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attribute<'a> {
    /// The name (a PLY property name, a glTF `_NAME` semantic without the underscore).
    pub name: &'a str,
    /// Vertices or faces.
    pub element: AttributeElement,
    /// The values, one per element.
    pub values: AttributeValues<'a>,
}

impl Attribute<'_> {
    /// The kind of value.
    pub fn kind(&self) -> AttributeKind {
        self.values.kind()
    }

    /// Numbers per value (1 for scalars and labels, 3 for vectors).
    pub fn arity(&self) -> usize {
        self.kind().arity()
    }
}

impl fmt::Display for Attribute<'_> {
    /// E.g. `face scalar `distortion`` or `vertex vector `d1``.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {} `{}`", self.element, self.kind(), self.name)
    }
}

/// The largest magnitude up to which every integer is exact in an `f32`
/// (2^24), for labels a format stores as floats.
pub(crate) const F32_EXACT_INTEGER: i64 = 1 << 24;

/// How a format without 32-bit integer attributes (glTF allows 32-bit
/// integers for indices only) stores a label.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum LabelStorage {
    /// Every value in `0..=65535`.
    U16,
    /// Every value in `-32768..=32767`, some negative.
    I16,
    /// Wider: as `f32`, exact up to [`F32_EXACT_INTEGER`].
    F32,
}

impl LabelStorage {
    /// The narrowest exact storage of `values`. O(n).
    pub(crate) fn of(values: &[i64]) -> Self {
        let (lo, hi) = values.iter().fold((0, 0), |(lo, hi), &x| (x.min(lo), x.max(hi)));
        if lo >= 0 && hi <= i64::from(u16::MAX) {
            Self::U16
        } else if lo >= i64::from(i16::MIN) && hi <= i64::from(i16::MAX) {
            Self::I16
        } else {
            Self::F32
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds_arities_and_names() {
        let v = [DVec3::X; 2];
        let a = Attribute { name: "d1", element: AttributeElement::Vertex, values: AttributeValues::Vector(&v) };
        assert_eq!((a.kind(), a.arity(), a.values.len()), (AttributeKind::Vector, 3, 2));
        assert_eq!(a.to_string(), "vertex vector `d1`");
        let l = [1i64, 2, 3];
        let b = Attribute { name: "chart", element: AttributeElement::Face, values: AttributeValues::Label(&l) };
        assert_eq!((b.arity(), b.to_string()), (1, "face label `chart`".to_owned()));
        assert!(AttributeValues::Scalar(&[]).is_empty());
    }

    #[test]
    fn label_storage_is_the_narrowest_exact_one() {
        assert_eq!(LabelStorage::of(&[]), LabelStorage::U16);
        assert_eq!(LabelStorage::of(&[0, 65535]), LabelStorage::U16);
        assert_eq!(LabelStorage::of(&[-1, 32767]), LabelStorage::I16);
        assert_eq!(LabelStorage::of(&[-1, 32768]), LabelStorage::F32);
        assert_eq!(LabelStorage::of(&[65536]), LabelStorage::F32);
    }
}
