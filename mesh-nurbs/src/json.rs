//! A small JSON format for NURBS surfaces, read and written with serde.
//!
//! ```json
//! {
//!   "format": "mesh-nurbs-surface",
//!   "version": 1,
//!   "degree_u": 1,
//!   "degree_v": 1,
//!   "knots_u": [0, 0, 1, 1],
//!   "knots_v": [0, 0, 1, 1],
//!   "count_u": 2,
//!   "count_v": 2,
//!   "control_points": [
//!     [0, 0, 0],
//!     [0, 1, 0],
//!     [1, 0, 0],
//!     [1, 1, 1]
//!   ],
//!   "weights": [1, 1, 1, 1]
//! }
//! ```
//!
//! - `control_points` is row-major: point `(i, j)` (`i`-th along `u`) is entry
//!   `i * count_v + j`; Cartesian coordinates (not multiplied by the weight).
//! - `knots_u` holds `count_u + degree_u + 1` non-decreasing numbers (same in `v`).
//! - `weights` is optional (all 1 when absent); weights must be positive.
//! - `format` and `version` are optional on input and always written.
//! - Unknown fields are refused, so that typos do not pass silently.
//!
//! Malformed JSON and well-formed documents describing an invalid surface both
//! give typed errors ([`NurbsError::Json`] or the validation error of the
//! surface, e.g. [`NurbsError::DecreasingKnots`]). Numbers round-trip exactly.

use std::io::{Read, Write};

use glam::DVec3;
use serde::{Deserialize, Serialize};
use serde_json::ser::{Formatter, PrettyFormatter};

use crate::error::{NurbsError, Result};
use crate::knots::KnotVector;
use crate::surface::NurbsSurface;

/// Value of the `format` field.
pub const FORMAT: &str = "mesh-nurbs-surface";
/// Current `version`.
pub const VERSION: u32 = 1;

/// The JSON document of a surface, field for field (see the module
/// documentation). Convert with [`SurfaceDocument::from_surface`] and
/// [`SurfaceDocument::to_surface`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SurfaceDocument {
    /// Always `"mesh-nurbs-surface"`.
    #[serde(default = "default_format")]
    pub format: String,
    /// Format version, 1.
    #[serde(default = "default_version")]
    pub version: u32,
    /// Degree in `u`.
    pub degree_u: usize,
    /// Degree in `v`.
    pub degree_v: usize,
    /// Knots in `u`.
    pub knots_u: Vec<f64>,
    /// Knots in `v`.
    pub knots_v: Vec<f64>,
    /// Number of control points along `u`.
    pub count_u: usize,
    /// Number of control points along `v`.
    pub count_v: usize,
    /// Control points, row-major, `[x, y, z]`.
    pub control_points: Vec<[f64; 3]>,
    /// Weights, row-major; all 1 when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weights: Option<Vec<f64>>,
}

fn default_format() -> String {
    FORMAT.to_owned()
}

fn default_version() -> u32 {
    VERSION
}

impl SurfaceDocument {
    /// The document of a surface. Cost O(n).
    pub fn from_surface(surface: &NurbsSurface) -> Self {
        Self {
            format: FORMAT.to_owned(),
            version: VERSION,
            degree_u: surface.knots_u().degree(),
            degree_v: surface.knots_v().degree(),
            knots_u: surface.knots_u().knots().to_vec(),
            knots_v: surface.knots_v().knots().to_vec(),
            count_u: surface.count_u(),
            count_v: surface.count_v(),
            control_points: surface.control_points().iter().map(|p| p.to_array()).collect(),
            weights: Some(surface.weights().to_vec()),
        }
    }

    /// Validates the document into a surface (format, version, knots, counts,
    /// points, weights). Cost O(n).
    ///
    /// # Errors
    /// `NurbsError::Json` for another format name or version; the errors of
    /// [`crate::KnotVector::for_control_points`] and [`crate::NurbsSurface::new`] for knots, counts, control
    /// points and weights that do not make a surface.
    pub fn to_surface(&self) -> Result<NurbsSurface> {
        if self.format != FORMAT {
            return Err(NurbsError::Json(format!("format is {:?}, expected {FORMAT:?}", self.format)));
        }
        if self.version != VERSION {
            return Err(NurbsError::Json(format!("version {} is not supported (expected {VERSION})", self.version)));
        }
        let knots_u = KnotVector::for_control_points(self.degree_u, self.knots_u.clone(), self.count_u)?;
        let knots_v = KnotVector::for_control_points(self.degree_v, self.knots_v.clone(), self.count_v)?;
        let points: Vec<DVec3> = self.control_points.iter().map(|&p| DVec3::from_array(p)).collect();
        let weights = self.weights.clone().unwrap_or_else(|| vec![1.0; points.len()]);
        NurbsSurface::new(knots_u, knots_v, points, weights)
    }
}

/// Reads a surface from JSON text. Cost O(n).
///
/// # Errors
/// `NurbsError::Json` for text that is not a surface document; the errors of [`SurfaceDocument::to_surface`].
pub fn from_json_str(text: &str) -> Result<NurbsSurface> {
    serde_json::from_str::<SurfaceDocument>(text)?.to_surface()
}

/// Reads a surface from a reader of JSON. Cost O(n).
///
/// # Errors
/// `NurbsError::Json` when reading fails or the text is not a surface document; the errors of
/// [`SurfaceDocument::to_surface`].
pub fn read_json(reader: impl Read) -> Result<NurbsSurface> {
    serde_json::from_reader::<_, SurfaceDocument>(reader)?.to_surface()
}

/// Writes a surface as JSON text laid out like the module example (one field
/// per line, one control point per line). Cost O(n).
///
/// # Errors
/// `NurbsError::Json` if serialization fails (a non-finite number cannot be written).
pub fn to_json_string(surface: &NurbsSurface) -> Result<String> {
    let mut out = Vec::new();
    write_json(surface, &mut out)?;
    String::from_utf8(out).map_err(|e| NurbsError::Json(e.to_string()))
}

/// Writes a surface as JSON to a writer, laid out like [`to_json_string`].
/// Cost O(n).
///
/// # Errors
/// `NurbsError::Json` when serialization or the writer fails.
pub fn write_json(surface: &NurbsSurface, writer: impl Write) -> Result<()> {
    let mut serializer = serde_json::Serializer::with_formatter(writer, Layout::default());
    SurfaceDocument::from_surface(surface).serialize(&mut serializer)?;
    Ok(())
}

/// Pretty objects, compact arrays, and a line break before each inner array
/// of an array of arrays (one control point per line).
#[derive(Default)]
struct Layout {
    object: PrettyFormatter<'static>,
    depth: usize,
    nested: bool,
}

impl Formatter for Layout {
    fn begin_array<W: ?Sized + Write>(&mut self, w: &mut W) -> std::io::Result<()> {
        self.depth += 1;
        if self.depth == 2 {
            self.nested = true;
            w.write_all(b"\n    ")?;
        }
        w.write_all(b"[")
    }

    fn end_array<W: ?Sized + Write>(&mut self, w: &mut W) -> std::io::Result<()> {
        self.depth -= 1;
        if self.depth == 0 && std::mem::take(&mut self.nested) {
            w.write_all(b"\n  ")?;
        }
        w.write_all(b"]")
    }

    fn begin_array_value<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> std::io::Result<()> {
        match (first, self.depth) {
            (true, _) => Ok(()),
            (false, 1) if self.nested => w.write_all(b","),
            (false, _) => w.write_all(b", "),
        }
    }

    fn end_array_value<W: ?Sized + Write>(&mut self, _w: &mut W) -> std::io::Result<()> {
        Ok(())
    }

    fn begin_object<W: ?Sized + Write>(&mut self, w: &mut W) -> std::io::Result<()> {
        self.object.begin_object(w)
    }

    fn end_object<W: ?Sized + Write>(&mut self, w: &mut W) -> std::io::Result<()> {
        self.object.end_object(w)
    }

    fn begin_object_key<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> std::io::Result<()> {
        self.object.begin_object_key(w, first)
    }

    fn begin_object_value<W: ?Sized + Write>(&mut self, w: &mut W) -> std::io::Result<()> {
        self.object.begin_object_value(w)
    }

    fn end_object_value<W: ?Sized + Write>(&mut self, w: &mut W) -> std::io::Result<()> {
        self.object.end_object_value(w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    #[test]
    fn round_trip_is_exact() {
        let s = shapes::torus(DVec3::new(0.1, 0.2, 0.3), 3.0, 1.0).unwrap();
        let text = to_json_string(&s).unwrap();
        assert!(from_json_str(&text).unwrap() == s, "text round trip");
        let mut buf = Vec::new();
        write_json(&s, &mut buf).unwrap();
        assert!(read_json(buf.as_slice()).unwrap() == s, "reader round trip");
    }

    #[test]
    fn layout_matches_the_documented_example() {
        let s = shapes::bilinear(DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE).unwrap();
        let text = to_json_string(&s).unwrap();
        let expected = r#"{
  "format": "mesh-nurbs-surface",
  "version": 1,
  "degree_u": 1,
  "degree_v": 1,
  "knots_u": [0.0, 0.0, 1.0, 1.0],
  "knots_v": [0.0, 0.0, 1.0, 1.0],
  "count_u": 2,
  "count_v": 2,
  "control_points": [
    [0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 1.0]
  ],
  "weights": [1.0, 1.0, 1.0, 1.0]
}"#;
        assert_eq!(text, expected);
    }

    #[test]
    fn documented_example_parses() {
        let text = r#"{ "format": "mesh-nurbs-surface", "version": 1, "degree_u": 1, "degree_v": 1,
            "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1], "count_u": 2, "count_v": 2,
            "control_points": [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 1]], "weights": [1, 1, 1, 1] }"#;
        let s = from_json_str(text).unwrap();
        assert!((s.point(1.0, 1.0).unwrap() - DVec3::ONE).length() < 1e-15);
    }

    #[test]
    fn invalid_documents_give_typed_errors() {
        let ok = r#""degree_u": 1, "degree_v": 1, "knots_u": [0, 0, 1, 1], "count_u": 2, "count_v": 2,
            "control_points": [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 1]]"#;
        let doc = |extra: &str| format!("{{ {ok}, {extra} }}");
        assert!(from_json_str(&doc(r#""knots_v": [0, 0, 1, 1]"#)).is_ok());
        assert!(matches!(from_json_str("{"), Err(NurbsError::Json(_))));
        assert!(matches!(from_json_str("[]"), Err(NurbsError::Json(_))));
        assert!(matches!(from_json_str(&doc(r#""knots_v": [0, 1, 0, 1]"#)), Err(NurbsError::DecreasingKnots { .. })));
        assert!(matches!(from_json_str(&doc(r#""knots_v": [0, 0, 1]"#)), Err(NurbsError::KnotCount { .. })));
        assert!(matches!(
            from_json_str(&doc(r#""knots_v": [0, 0, 1, 1], "weights": [1, -1, 1, 1]"#)),
            Err(NurbsError::Weight { index: 1, .. })
        ));
        assert!(matches!(
            from_json_str(&doc(r#""knots_v": [0, 0, 1, 1], "weights": [1, 1]"#)),
            Err(NurbsError::Count { .. })
        ));
        assert!(matches!(from_json_str(&doc(r#""knots_v": [0, 0, 1, 1], "colour": 3"#)), Err(NurbsError::Json(_))));
        assert!(matches!(from_json_str(&doc(r#""knots_v": [0, 0, 1, 1], "version": 2"#)), Err(NurbsError::Json(_))));
        assert!(matches!(from_json_str(&doc(r#""knots_v": [0, 0, 1, 1], "degree_v": 40"#)), Err(NurbsError::Json(_))));
    }
}
