//! What writing to a 32-bit float format does to the values: the check that
//! refuses values `f32` cannot hold, and the [`WriteReport`] of the rounding.
//!
//! STL (binary), glTF/GLB and PLY with `float` properties store positions
//! (and normals, texture coordinates, glTF scalars and vectors, glTF labels
//! beyond 16 bits) as IEEE 754 single precision. A value is *lost* when it is finite in `f64` but becomes
//! infinite in `f32` (|x| > 3.4e38), or when it is non-zero and becomes zero
//! or subnormal with a relative change above [`PRECISION_WARNING`] (the whole
//! mesh is tiny, e.g. at a scale of 1e-300). Rounding is measured relative to
//! the field's scale `s`: `|f32(x) - x| / s`, with `s` the largest side of the
//! bounding box for positions (so that a small mesh far from the origin,
//! whose details `f32` cannot resolve, is reported) and the largest
//! magnitude of the attribute otherwise (`|x|` when `s` is zero).

use glam::{DVec2, DVec3};

use crate::attribute::{AttributeElement, AttributeValues, LabelStorage, F32_EXACT_INTEGER};
use crate::data::MeshView;
use crate::error::{IoError, Location, Result};
use crate::format::Format;

/// Relative rounding above which [`WriteReport::is_clean`] is `false` (the
/// writer warns): `1e-6`, about eight units in the last place of an `f32`.
pub const PRECISION_WARNING: f64 = 1e-6;

/// What a writer changed in the values it stored, returned by
/// [`crate::write()`] and [`crate::write_to`] (the counterpart of
/// [`crate::ReadReport`]).
#[derive(Debug, Clone, Default, PartialEq)]
#[non_exhaustive]
pub struct WriteReport {
    /// Largest relative change of a value stored as `f32`, `|f32(x) - x| /
    /// scale` (see the module documentation); `0` when nothing is narrowed.
    pub max_relative_rounding: f64,
    /// Values lost (infinite or flushed to zero in `f32`, labels beyond
    /// 2^24 rounded), written anyway because
    /// [`crate::WriteOptions::allow_precision_loss`] was set.
    pub values_lost: usize,
    /// What the view held that the format cannot store, left out of the
    /// file, one short phrase each (`face scalar `distortion``, `normals`).
    pub dropped: Vec<String>,
}

impl WriteReport {
    /// `true` when every value was stored within [`PRECISION_WARNING`], none
    /// lost and nothing dropped.
    pub fn is_clean(&self) -> bool {
        self.values_lost == 0 && self.max_relative_rounding <= PRECISION_WARNING && self.dropped.is_empty()
    }
}

impl std::fmt::Display for WriteReport {
    /// One line, e.g. `values rounded to 32-bit floats by up to 3.1e-5 relative`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let rounded = self.values_lost > 0 || self.max_relative_rounding > PRECISION_WARNING;
        if rounded {
            write!(f, "values rounded to 32-bit floats by up to {:.1e} relative", self.max_relative_rounding)?;
        } else if self.dropped.is_empty() {
            f.write_str("values stored within 1e-6 relative")?;
        }
        if self.values_lost > 0 {
            write!(f, "; {} values lost (infinite or zero in 32-bit floats)", self.values_lost)?;
        }
        if !self.dropped.is_empty() {
            let separator = if rounded { "; " } else { "" };
            write!(f, "{separator}not stored by this format: {}", self.dropped.join(", "))?;
        }
        Ok(())
    }
}

/// Which parts of a view a format stores as `f32`.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Narrowed {
    pub positions: bool,
    pub normals: bool,
    pub uvs: bool,
    /// Per-vertex scalars and vectors, and labels wider than 16 bits.
    pub attributes: bool,
}

/// Checks every value the format narrows to `f32`: a lost value is an
/// [`IoError::Precision`] naming the vertex unless `allow`; the rounding is
/// reported. Cost O(V).
pub(crate) fn check(view: &MeshView<'_>, which: Narrowed, format: Format, allow: bool) -> Result<WriteReport> {
    let mut c = Checker { format, allow, report: WriteReport::default() };
    if which.positions {
        c.field("position", view.mesh.positions(), DVec3::to_array, Scale::Extent)?;
    }
    if let (true, Some(normals)) = (which.normals, view.normals) {
        c.field("normal", normals, DVec3::to_array, Scale::Magnitude)?;
    }
    if let (true, Some(uvs), None) = (which.uvs, view.uvs, view.corner_uvs) {
        c.field("texture coordinate", uvs, DVec2::to_array, Scale::Magnitude)?;
    }
    if which.attributes {
        for a in view.attributes.iter().filter(|a| a.element == AttributeElement::Vertex) {
            match a.values {
                AttributeValues::Scalar(v) => c.field(&a.to_string(), v, |&x| [x], Scale::Magnitude)?,
                AttributeValues::Vector(v) => c.field(&a.to_string(), v, DVec3::to_array, Scale::Magnitude)?,
                AttributeValues::Label(v) if LabelStorage::of(v) == LabelStorage::F32 => c.labels(&a.to_string(), v)?,
                AttributeValues::Label(_) => {}
            }
        }
    }
    Ok(c.report)
}

struct Checker {
    format: Format,
    allow: bool,
    report: WriteReport,
}

impl Checker {
    fn field<T, const N: usize>(
        &mut self,
        what: &str,
        values: &[T],
        get: impl Fn(&T) -> [f64; N],
        kind: Scale,
    ) -> Result<()> {
        let scale = scale(values.iter().map(&get), kind);
        for (vertex, v) in values.iter().enumerate() {
            for x in get(v) {
                self.value(what, vertex, x, scale)?;
            }
        }
        Ok(())
    }

    /// Labels stored as `f32`: exact up to 2^24 in magnitude, rounded
    /// (lost) beyond.
    fn labels(&mut self, what: &str, values: &[i64]) -> Result<()> {
        for (vertex, &x) in values.iter().enumerate() {
            if x.abs() > F32_EXACT_INTEGER {
                self.lose(what, vertex, x as f64, "is an integer beyond 2^24, which a 32-bit float rounds")?;
            }
        }
        Ok(())
    }

    #[inline]
    fn value(&mut self, what: &str, vertex: usize, x: f64, scale: f64) -> Result<()> {
        let narrowed = x as f32;
        let relative =
            if x == 0.0 { 0.0 } else { (f64::from(narrowed) - x).abs() / if scale > 0.0 { scale } else { x.abs() } };
        let problem = if !x.is_finite() {
            None // non-finite input is the mesh's problem, not the format's
        } else if narrowed.is_infinite() {
            Some("is beyond the 32-bit float range (it would become infinity)")
        } else if x != 0.0 && !narrowed.is_normal() && relative > PRECISION_WARNING {
            Some("is too small for a 32-bit float (it would become zero or lose its digits)")
        } else {
            if relative.is_finite() {
                self.report.max_relative_rounding = self.report.max_relative_rounding.max(relative);
            }
            return Ok(());
        };
        match problem {
            Some(problem) => self.lose(what, vertex, x, problem),
            None => Ok(()),
        }
    }

    /// A value the format cannot hold: counted when allowed, else refused.
    fn lose(&mut self, what: &str, vertex: usize, x: f64, problem: &'static str) -> Result<()> {
        if self.allow {
            self.report.values_lost += 1;
            self.report.max_relative_rounding = self.report.max_relative_rounding.max(1.0);
            return Ok(());
        }
        Err(IoError::Precision {
            at: Location::new(self.format),
            what: format!("{what} of vertex {vertex}"),
            value: x,
            problem,
        })
    }
}

/// What the rounding of a field is compared to.
#[derive(Clone, Copy)]
enum Scale {
    /// The largest side of the bounding box (positions).
    Extent,
    /// The largest magnitude (attributes).
    Magnitude,
}

/// The scale of a field (finite; `f64::MAX` when it overflows).
fn scale<const N: usize>(values: impl Iterator<Item = [f64; N]>, kind: Scale) -> f64 {
    let (mut lo, mut hi, mut magnitude) = ([f64::INFINITY; N], [f64::NEG_INFINITY; N], 0.0f64);
    for v in values {
        for k in 0..N {
            if v[k].is_finite() {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
                magnitude = magnitude.max(v[k].abs());
            }
        }
    }
    let side = (0..N).map(|k| (hi[k] - lo[k]).max(0.0)).fold(0.0, f64::max);
    let s = match kind {
        Scale::Extent => side,
        Scale::Magnitude => magnitude,
    };
    if s.is_finite() {
        s
    } else {
        f64::MAX
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::TriMesh;

    fn triangle(scale: f64) -> TriMesh {
        TriMesh::new(vec![DVec3::ZERO, DVec3::X * scale, DVec3::Y * scale], vec![[0, 1, 2]]).unwrap()
    }

    fn positions() -> Narrowed {
        Narrowed { positions: true, ..Narrowed::default() }
    }

    #[test]
    fn overflow_and_underflow_are_refused_unless_allowed() {
        for s in [1e300, 1e-300, 1e39, 1e-45] {
            let mesh = triangle(s);
            let e = check(&MeshView::new(&mesh), positions(), Format::Stl, false).unwrap_err();
            assert!(matches!(e, IoError::Precision { .. }) && e.to_string().contains("vertex 1"), "{e}");
            let r = check(&MeshView::new(&mesh), positions(), Format::Stl, true).unwrap();
            assert_eq!(r.values_lost, 2, "{s}");
            assert!(!r.is_clean());
        }
    }

    #[test]
    fn rounding_is_reported_relative_to_the_scale() {
        let exact = triangle(1.0);
        assert_eq!(check(&MeshView::new(&exact), positions(), Format::Glb, false).unwrap(), WriteReport::default());
        let mesh = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::new(0.1, 1e-40, 0.0)], vec![[0, 1, 2]]).unwrap();
        let r = check(&MeshView::new(&mesh), positions(), Format::Glb, false).unwrap();
        assert!(r.max_relative_rounding > 0.0 && r.is_clean(), "{r:?}: 0.1 rounds by 1.5e-8, 1e-40 is negligible");
        let far = TriMesh::new(
            vec![DVec3::splat(1e6), DVec3::splat(1e6) + DVec3::X * 1e-3, DVec3::splat(1e6) + DVec3::Y * 1e-3],
            vec![[0, 1, 2]],
        )
        .unwrap();
        let r = check(&MeshView::new(&far), positions(), Format::Glb, false).unwrap();
        assert!(!r.is_clean(), "{r:?}: 1e6 + 1e-3 rounds by 3e-2 of the mesh's size 1e-3");
        let mean = [0.1, 1e39, 0.0];
        let e = check(
            &MeshView::new(&exact).with_scalar("mean", &mean),
            Narrowed { attributes: true, ..Narrowed::default() },
            Format::Glb,
            false,
        )
        .unwrap_err();
        assert!(e.to_string().contains("scalar `mean` of vertex 1"), "{e}");
    }

    #[test]
    fn the_line_names_what_was_dropped() {
        let dropped = WriteReport { dropped: vec!["face label `chart`".into()], ..WriteReport::default() };
        assert_eq!(dropped.to_string(), "not stored by this format: face label `chart`");
        let both = WriteReport { max_relative_rounding: 1e-3, ..dropped };
        assert!(
            both.to_string().starts_with("values rounded")
                && both.to_string().ends_with("; not stored by this format: face label `chart`")
        );
    }

    #[test]
    fn vectors_and_wide_labels_are_checked() {
        let mesh = triangle(1.0);
        let attributes = Narrowed { attributes: true, ..Narrowed::default() };
        let d = [DVec3::X, DVec3::new(0.0, 1e39, 0.0), DVec3::Z];
        let e = check(&MeshView::new(&mesh).with_vector("d1", &d), attributes, Format::Glb, false).unwrap_err();
        assert!(e.to_string().contains("vertex vector `d1` of vertex 1"), "{e}");
        let narrow = [0, 1, 65535];
        let r = check(&MeshView::new(&mesh).with_label("chart", &narrow), attributes, Format::Glb, false).unwrap();
        assert!(r.is_clean());
        let exact = [-1, 1 << 24, 7];
        assert!(check(&MeshView::new(&mesh).with_label("c", &exact), attributes, Format::Glb, false)
            .unwrap()
            .is_clean());
        let wide = [0, (1 << 24) + 1, 2];
        let e = check(&MeshView::new(&mesh).with_label("c", &wide), attributes, Format::Glb, false).unwrap_err();
        assert!(e.to_string().contains("label `c` of vertex 1"), "{e}");
        let r = check(&MeshView::new(&mesh).with_label("c", &wide), attributes, Format::Glb, true).unwrap();
        assert_eq!(r.values_lost, 1);
    }
}
