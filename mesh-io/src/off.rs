//! OFF (Geomview Object File Format), text.
//!
//! Header keyword `[ST][C][N]OFF` (optional, as in Geomview), then
//! `vertex_count face_count edge_count` (on the same line or the next), one
//! vertex per line (`x y z`, then `nx ny nz` with `N`, `r g b [a]` with `C`,
//! `s t` with `ST`), one face per line (`n i0 .. i(n-1)`, any colour after the
//! indices ignored). Blank lines, `#` comments and repeated spaces are
//! accepted. A colour written with integers only is in `0..=255`, else in `[0, 1]`.
//! Polygons are fan-triangulated. The 4D (`4OFF`) and n-D (`nOFF`) variants
//! are refused with [`IoError::Unsupported`].

use std::io::Write;

use glam::{DVec2, DVec3};

use crate::data::{tri_mesh, MeshData, MeshView, ReadReport};
use crate::error::{excerpt, IoError, Location, Result};
use crate::format::Format;
use crate::text::{check_count, parse_int, vertex_index, Scanner, TextWriter};

/// Which optional per-vertex fields a header keyword announces.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
struct Fields {
    normals: bool,
    colors: bool,
    uvs: bool,
}

/// Reads an OFF file from memory. Cost O(size).
///
/// # Errors
/// `IoError::WrongMagic` or `IoError::Syntax` for a malformed header; `IoError::Count` for a negative count,
/// one beyond 32-bit indices, or more elements than the remaining bytes could hold (checked before
/// allocating); `IoError::Truncated` when the data ends early; `IoError::Index`, `IoError::NonFinite` and
/// `IoError::Mesh` as for every reader.
pub fn read(bytes: &[u8]) -> Result<MeshData> {
    let mut s = Scanner::new(bytes, Format::Off, Some(b'#'));
    if !s.skip_to_content() {
        return Err(IoError::truncated(s.at(), "the `OFF` header"));
    }
    let fields = header(&mut s)?;
    if s.at_line_end() && !s.skip_to_content() {
        return Err(IoError::truncated(s.at(), "the vertex and face counts"));
    }
    let at = s.at();
    let nv = s.int("the vertex count")?;
    let nf = s.int("the face count")?;
    s.next_line();
    // A vertex takes at least 6 bytes ("0 0 0\n"), a face at least 8 ("3 0 1 2\n").
    let nv = check_count(&at, "vertex", nv, 6, s.rest().len())?;
    let nf = check_count(&at, "face", nf, 8, s.rest().len().saturating_sub(nv * 6))?;

    let mut vertices = Vertices::with_capacity(nv, fields);
    for i in 0..nv {
        if !s.skip_to_content() {
            return Err(IoError::truncated(s.at(), format!("vertex {i} of {nv}")));
        }
        vertices.read(&mut s, i)?;
        s.next_line();
    }
    let mut faces = Vec::with_capacity(nf);
    let mut report = ReadReport::default();
    let mut polygon = Vec::new();
    for f in 0..nf {
        if !s.skip_to_content() {
            return Err(IoError::truncated(s.at(), format!("face {f} of {nf}")));
        }
        read_polygon(&mut s, f, nv, &mut polygon)?;
        report.triangulate(&polygon, |_, tri| faces.push(tri));
        s.next_line();
    }
    vertices.finish(faces, report)
}

/// Parses the optional header keyword `[ST][C][N]OFF`.
fn header(s: &mut Scanner<'_>) -> Result<Fields> {
    let next = s.rest().split(|b| b.is_ascii_whitespace()).next().unwrap_or_default();
    if parse_int(next).is_some_and(|(_, len)| len == next.len()) {
        return Ok(Fields::default());
    }
    let at = s.at();
    let word = s.word().unwrap_or_default();
    let wrong =
        || IoError::WrongMagic { at: at.clone(), expected: "`OFF`, `COFF`, `NOFF` or `STOFF`", found: excerpt(word) };
    let mut prefix = word.strip_suffix(b"OFF").ok_or_else(wrong)?;
    let mut fields = Fields::default();
    while !prefix.is_empty() {
        let rest;
        (rest, fields) = match prefix {
            [b'S', b'T', rest @ ..] => (rest, Fields { uvs: true, ..fields }),
            [b'C', rest @ ..] => (rest, Fields { colors: true, ..fields }),
            [b'N', rest @ ..] => (rest, Fields { normals: true, ..fields }),
            [b'4' | b'n', ..] => return Err(IoError::unsupported(at, "4D and n-dimensional OFF")),
            _ => return Err(wrong()),
        };
        prefix = rest;
    }
    Ok(fields)
}

/// Reads one face line's vertex indices into `polygon`.
fn read_polygon(s: &mut Scanner<'_>, face: usize, nv: usize, polygon: &mut Vec<u32>) -> Result<()> {
    let n = s.int("the number of vertices of a face")?;
    if n < 0 {
        return Err(s.error("a non-negative number of vertices"));
    }
    polygon.clear();
    for _ in 0..n {
        let i = s.int("a vertex index")?;
        polygon.push(vertex_index(|| s.at(), face, i, nv)?);
    }
    Ok(())
}

/// Vertex data collected while reading.
struct Vertices {
    fields: Fields,
    positions: Vec<DVec3>,
    normals: Vec<DVec3>,
    colors: Vec<[f32; 4]>,
    uvs: Vec<DVec2>,
}

impl Vertices {
    fn with_capacity(n: usize, fields: Fields) -> Self {
        let cap = |on: bool| if on { n } else { 0 };
        Self {
            fields,
            positions: Vec::with_capacity(n),
            normals: Vec::with_capacity(cap(fields.normals)),
            colors: Vec::with_capacity(cap(fields.colors)),
            uvs: Vec::with_capacity(cap(fields.uvs)),
        }
    }

    /// Reads vertex `i` from the current line.
    #[inline]
    fn read(&mut self, s: &mut Scanner<'_>, i: usize) -> Result<()> {
        let at = s.at();
        let p = DVec3::new(s.float("coordinate x")?, s.float("coordinate y")?, s.float("coordinate z")?);
        if !p.is_finite() {
            return Err(IoError::NonFinite { at, vertex: i });
        }
        self.positions.push(p);
        if self.fields == Fields::default() {
            return Ok(());
        }
        if self.fields.normals {
            self.normals.push(DVec3::new(s.float("normal x")?, s.float("normal y")?, s.float("normal z")?));
        }
        let mut words = Vec::new();
        while let Some(w) = s.word() {
            words.push(w);
        }
        let n_color = words.len().saturating_sub(if self.fields.uvs { 2 } else { 0 });
        if self.fields.colors {
            self.colors.push(color(&at, &words[..n_color])?);
        }
        if self.fields.uvs {
            let uv = words.get(n_color..n_color + 2).unwrap_or_default();
            let [u, v] = [0, 1].map(|k| uv.get(k).and_then(|w| fast_float2::parse::<f64, _>(w).ok()));
            match (u, v) {
                (Some(u), Some(v)) => self.uvs.push(DVec2::new(u, v)),
                _ => return Err(IoError::syntax(at, "texture coordinates `s t`", uv.first().unwrap_or(&&b""[..]))),
            }
        }
        Ok(())
    }

    fn finish(self, faces: Vec<[u32; 3]>, report: ReadReport) -> Result<MeshData> {
        let fields = self.fields;
        let mut data = MeshData::new(tri_mesh(self.positions, faces, Location::new(Format::Off))?);
        data.normals = fields.normals.then_some(self.normals);
        data.colors = fields.colors.then_some(self.colors);
        data.uvs = fields.uvs.then_some(self.uvs);
        data.report = report;
        Ok(data)
    }
}

/// An RGB or RGBA colour: integers in `0..=255`, or floats in `[0, 1]`.
fn color(at: &Location, words: &[&[u8]]) -> Result<[f32; 4]> {
    let bad = |w: &[u8]| IoError::syntax(at.clone(), "3 or 4 colour components", w);
    if !(3..=4).contains(&words.len()) {
        return Err(bad(words.first().copied().unwrap_or_default()));
    }
    let integral = !words.iter().flat_map(|w| w.iter()).any(|b| matches!(b, b'.' | b'e' | b'E'));
    let mut rgba = [1.0f32; 4];
    for (c, w) in rgba.iter_mut().zip(words) {
        let x = fast_float2::parse::<f32, _>(w).map_err(|_| bad(w))?;
        *c = if integral { x / 255.0 } else { x };
    }
    Ok(rgba)
}

/// Writes an OFF file: `[ST][C][N]OFF` as the attributes require, colours as
/// integers `0..=255`, floats in shortest round-trip form. Corner UVs and
/// scalars are not stored. Cost O(size).
///
/// # Errors
/// `IoError::AttributeLength` from `MeshView::check`; `IoError::Io` when `out` fails.
pub fn write<W: Write>(out: W, view: &MeshView<'_>) -> Result<()> {
    view.check()?;
    let mesh = view.mesh;
    let mut w = TextWriter::new(out);
    let keyword = [(view.uvs.is_some(), "ST"), (view.colors.is_some(), "C"), (view.normals.is_some(), "N")];
    for (on, prefix) in keyword {
        if on {
            w.str(prefix);
        }
    }
    w.str("OFF");
    w.line()?;
    w.uint(mesh.vertex_count() as u64).str(" ").uint(mesh.face_count() as u64).str(" 0");
    w.line()?;
    for (i, p) in mesh.positions().iter().enumerate() {
        w.float(p.x).floats(&[p.y, p.z]);
        if let Some(n) = view.normals {
            w.floats(&n[i].to_array());
        }
        if let Some(c) = view.colors {
            for x in c[i] {
                w.str(" ").uint(color_byte(x).into());
            }
        }
        if let Some(uv) = view.uvs {
            w.floats(&uv[i].to_array());
        }
        w.line()?;
    }
    for f in mesh.faces() {
        w.str("3");
        for &v in f {
            w.str(" ").uint(v.into());
        }
        w.line()?;
    }
    w.finish()
}

/// A colour component in `[0, 1]` as a byte (clamped, rounded).
pub(crate) fn color_byte(x: f32) -> u8 {
    (x.clamp(0.0, 1.0) * 255.0).round() as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_blank_lines_comments_and_polygons() {
        let src = b"OFF\n# comment\n\n4  2 0\n0 0 0\n1 0 0\n\n1  1 0 # tail\n0 1 0\n4 0 1 2 3\n3 0 2 2\n";
        let d = read(src).unwrap();
        assert_eq!((d.mesh.vertex_count(), d.mesh.face_count()), (4, 2));
        assert_eq!((d.report.polygons_triangulated, d.report.faces_dropped), (1, 1));
    }

    #[test]
    fn reads_counts_on_header_line_and_headerless() {
        assert_eq!(read(b"OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap().mesh.face_count(), 1);
        assert_eq!(read(b"3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap().mesh.face_count(), 1);
    }

    #[test]
    fn reads_colors_normals_and_uvs() {
        let src = b"STCNOFF\n3 1 0\n0 0 0 0 0 1 255 0 0 0.5 0.25\n1 0 0 0 0 1 0.5 0.5 0.5 1 0 1\n0 1 0 0 0 1 0 0 255 255 1 1\n3 0 1 2 255 0 0\n";
        let d = read(src).unwrap();
        assert_eq!(d.colors.as_ref().unwrap()[0], [1.0, 0.0, 0.0, 1.0]);
        assert_eq!(d.colors.as_ref().unwrap()[1], [0.5, 0.5, 0.5, 1.0]);
        assert_eq!(d.uvs.as_ref().unwrap()[0], DVec2::new(0.5, 0.25));
        assert_eq!(d.normals.as_ref().unwrap()[2], DVec3::Z);
    }

    #[test]
    fn typed_errors() {
        let e = |src: &[u8]| read(src).unwrap_err();
        assert!(matches!(e(b"PLY\n"), IoError::WrongMagic { .. }));
        assert!(matches!(e(b"4OFF\n"), IoError::Unsupported { .. }));
        assert!(matches!(e(b"OFF\n-1 0 0\n"), IoError::Count { .. }));
        assert!(matches!(e(b"OFF\n4000000000 1 0\n"), IoError::Count { .. }));
        assert!(matches!(e(b"OFF\n3 1 0\n0 0 0\n1 0 0\n"), IoError::Count { .. }), "too short for its counts");
        assert!(matches!(e(b"OFF\n3 1 0\n0.0 0.0 0.0\n1.0 0.0 0.0\n0.0 1.0 0.0\n"), IoError::Truncated { .. }));
        assert!(matches!(e(b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 nan\n3 0 1 2\n"), IoError::NonFinite { vertex: 2, .. }));
        let bad_index = e(b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
        assert!(matches!(bad_index, IoError::Index { index: 3, .. }), "{bad_index}");
        assert_eq!(bad_index.location().and_then(|l| l.line), Some(6));
        assert!(matches!(e(b"OFF\n3 1 0\n0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n"), IoError::Syntax { .. }));
    }
}
