//! STL (stereolithography), ascii and binary.
//!
//! STL stores loose triangles, so the reader welds corners with identical
//! positions ([`mesh_kernel::clean::weld_vertices`], exact by default) and drops
//! (and counts) the faces that collapse. Binary files are recognised by their
//! size (`84 + 50 n` bytes for `n` triangles), even when their header starts
//! with `solid`; trailing bytes after the last triangle are ignored. Facet
//! normals and attribute bytes are not read; writers compute unit facet normals.
//! Binary STL stores `f32`: positions round to single precision.

use std::io::Write;

use glam::DVec3;

use crate::data::{tri_mesh, MeshData, MeshView, ReadReport};
use crate::error::{IoError, Location, Result};
use crate::format::Format;
use crate::text::{Scanner, TextWriter};

/// Ascii or binary STL.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum StlEncoding {
    /// `solid ... endsolid` text, full `f64` precision.
    Ascii,
    /// 50 bytes per triangle, `f32` coordinates.
    #[default]
    Binary,
}

const HEADER: usize = 84;
const RECORD: usize = 50;

/// `true` when the size of `bytes` is exactly that of a binary STL with the
/// triangle count in its header.
pub fn is_binary(bytes: &[u8]) -> bool {
    triangle_count(bytes).is_some_and(|n| (HEADER as u64 + RECORD as u64 * u64::from(n)) == bytes.len() as u64)
}

fn triangle_count(bytes: &[u8]) -> Option<u32> {
    Some(u32::from_le_bytes(bytes.get(80..84)?.try_into().ok()?))
}

/// Reads an ascii or binary STL from memory, welding corners within
/// `weld_tolerance` (`Some(0.0)`: identical positions; `None`: no welding,
/// three vertices per triangle). Cost O(n log n) for `n` triangles.
///
/// # Errors
/// `IoError::Truncated` for a binary STL shorter than its triangle count says, or an ascii STL without
/// `endfacet`/`endsolid`; `IoError::Syntax` for an ascii keyword or number that is not STL, or a facet
/// without 3 vertices; `IoError::NonFinite` for a NaN or infinite corner; `IoError::Mesh` for a negative
/// `weld_tolerance` (mesh-kernel's welding refuses it) or faces that do not make a valid `TriMesh`.
pub fn read(bytes: &[u8], weld_tolerance: Option<f64>) -> Result<MeshData> {
    let ascii =
        !is_binary(bytes) && bytes.trim_ascii_start().get(..5).is_some_and(|w| w.eq_ignore_ascii_case(b"solid"));
    let (corners, mut report) = if ascii { read_ascii(bytes)? } else { read_binary(bytes)? };
    let faces: Vec<[u32; 3]> = (0..corners.len() as u32 / 3).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    let at = Location::new(Format::Stl);
    let Some(tolerance) = weld_tolerance else {
        return Ok(MeshData { report, ..MeshData::new(tri_mesh(corners, faces, at)?) });
    };
    let (positions, welded, merged) = mesh_kernel::clean::weld_vertices(&corners, &faces, tolerance)
        .map_err(|source| IoError::Mesh { at: at.clone(), source })?;
    report.vertices_welded = merged;
    let mut faces = Vec::with_capacity(welded.len());
    for tri in &welded {
        report.triangulate(tri, |_, t| faces.push(t));
    }
    Ok(MeshData { report, ..MeshData::new(tri_mesh(positions, faces, at)?) })
}

/// The corners of a binary STL, three per triangle.
fn read_binary(bytes: &[u8]) -> Result<(Vec<DVec3>, ReadReport)> {
    let at = Location::new(Format::Stl);
    let n = triangle_count(bytes).ok_or_else(|| IoError::truncated(at.clone(), "an 84-byte binary STL header"))?;
    let need = HEADER as u64 + RECORD as u64 * u64::from(n);
    if need > bytes.len() as u64 {
        let e =
            format!("a binary STL (no `solid` keyword) of {n} triangles ({need} bytes), found {} bytes", bytes.len());
        return Err(IoError::truncated(at, e));
    }
    let mut report = ReadReport::default();
    if need < bytes.len() as u64 {
        report.note(format!("{} bytes after the last triangle ignored", bytes.len() as u64 - need));
    }
    let records = bytes.get(HEADER..need as usize).unwrap_or_default();
    let mut corners = Vec::with_capacity(3 * n as usize);
    for record in records.chunks_exact(RECORD) {
        for k in 0..3 {
            let xyz = [0, 1, 2].map(|c| f64::from(le_f32(record, 12 * (k + 1) + 4 * c)));
            corners.push(finite(DVec3::from_array(xyz), corners.len(), &at)?);
        }
    }
    Ok((corners, report))
}

/// A little-endian `f32` at `offset` (zero past the end; callers check sizes).
#[inline]
fn le_f32(bytes: &[u8], offset: usize) -> f32 {
    bytes.get(offset..offset + 4).and_then(|b| b.try_into().ok()).map_or(0.0, f32::from_le_bytes)
}

fn finite(p: DVec3, vertex: usize, at: &Location) -> Result<DVec3> {
    if p.is_finite() {
        Ok(p)
    } else {
        Err(IoError::NonFinite { at: at.clone(), vertex })
    }
}

/// The corners of an ascii STL: every `vertex x y z` line, grouped by facet.
/// Every other line (`solid`, `facet normal`, `outer loop`, ...) is skipped.
fn read_ascii(bytes: &[u8]) -> Result<(Vec<DVec3>, ReadReport)> {
    let mut s = Scanner::new(bytes, Format::Stl, None);
    let mut corners = Vec::new();
    let mut in_facet = 0usize;
    let mut ended = false;
    while s.skip_to_content() {
        let word = s.word().unwrap_or_default();
        let is = |keyword: &str| word.eq_ignore_ascii_case(keyword.as_bytes());
        if is("vertex") {
            let at = s.at();
            let p = DVec3::new(s.float("coordinate x")?, s.float("coordinate y")?, s.float("coordinate z")?);
            corners.push(finite(p, corners.len(), &at)?);
            in_facet += 1;
        } else if is("endfacet") {
            if in_facet != 3 {
                return Err(IoError::syntax(s.at(), "3 vertices per facet", in_facet.to_string().as_bytes()));
            }
            in_facet = 0;
        } else if is("solid") || is("endsolid") {
            ended = is("endsolid");
        } else if !(is("facet") || is("outer") || is("endloop")) {
            return Err(IoError::syntax(s.at(), "an ascii STL keyword", word));
        }
        s.next_line();
    }
    if in_facet != 0 || !ended {
        return Err(IoError::truncated(s.at(), "`endfacet` and `endsolid`"));
    }
    Ok((corners, ReadReport::default()))
}

/// Writes an STL. Only positions are stored, as the corners of each
/// triangle (vertices no face uses are left out). Cost O(F).
///
/// # Errors
/// [`IoError::Unsupported`] for a mesh with vertices but no faces (STL
/// cannot hold vertices without triangles) or more than 2^32 triangles;
/// [`IoError::AttributeLength`] from [`MeshView::check`]; [`IoError::Io`].
pub fn write<W: Write>(out: W, view: &MeshView<'_>, encoding: StlEncoding) -> Result<()> {
    view.check()?;
    if view.mesh.face_count() == 0 && view.mesh.vertex_count() > 0 {
        let what = format!(
            "{} vertices without faces: STL stores triangles only (write PLY, OBJ, OFF or glTF instead)",
            view.mesh.vertex_count()
        );
        return Err(IoError::unsupported(Location::new(Format::Stl), what));
    }
    match encoding {
        StlEncoding::Ascii => write_ascii(out, view),
        StlEncoding::Binary => write_binary(out, view),
    }
}

fn unit_normal(tri: [DVec3; 3]) -> DVec3 {
    mesh_kernel::geometry::triangle_normal(tri)
}

fn write_binary<W: Write>(mut out: W, view: &MeshView<'_>) -> Result<()> {
    let mesh = view.mesh;
    let count = u32::try_from(mesh.face_count())
        .map_err(|_| IoError::unsupported(Location::new(Format::Stl), "more than 2^32 triangles"))?;
    let mut header = [b' '; HEADER];
    let title = b"binary STL written by mesh-io";
    header[..title.len()].copy_from_slice(title);
    header[80..].copy_from_slice(&count.to_le_bytes());
    out.write_all(&header)?;
    let mut buf = Vec::with_capacity(1 << 16);
    for f in mesh.face_ids() {
        let tri = mesh.triangle(f);
        for p in [unit_normal(tri)].iter().chain(&tri) {
            for c in p.to_array() {
                buf.extend_from_slice(&(c as f32).to_le_bytes());
            }
        }
        buf.extend_from_slice(&[0, 0]);
        if buf.len() >= 1 << 16 {
            out.write_all(&buf)?;
            buf.clear();
        }
    }
    out.write_all(&buf)?;
    out.flush()?;
    Ok(())
}

fn write_ascii<W: Write>(out: W, view: &MeshView<'_>) -> Result<()> {
    let mesh = view.mesh;
    let mut w = TextWriter::new(out);
    w.str("solid mesh").line()?;
    for f in mesh.face_ids() {
        let tri = mesh.triangle(f);
        w.str("facet normal").floats(&unit_normal(tri).to_array()).line()?;
        w.str("outer loop").line()?;
        for p in tri {
            w.str("vertex").floats(&p.to_array()).line()?;
        }
        w.str("endloop").line()?;
        w.str("endfacet").line()?;
    }
    w.str("endsolid mesh").line()?;
    w.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    const TETRA: &[u8] = b"solid t
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 0 1 0
  vertex 1 0 0
 endloop
endfacet
facet normal 0 0 0
 outer loop
  vertex 0 0 0
  vertex 1 0 0
  vertex 0 0 1
 endloop
endfacet
facet normal 0 0 0
 outer loop
  vertex 0 0 0
  vertex 0 0 0
  vertex 0 0 1
 endloop
endfacet
endsolid t
";

    #[test]
    fn ascii_is_welded_and_collapsed_faces_dropped() {
        let d = read(TETRA, Some(0.0)).unwrap();
        assert_eq!((d.mesh.vertex_count(), d.mesh.face_count()), (4, 2));
        assert_eq!((d.report.vertices_welded, d.report.faces_dropped), (5, 1));
        let loose = read(TETRA, None).unwrap();
        assert_eq!((loose.mesh.vertex_count(), loose.mesh.face_count()), (9, 3));
    }

    #[test]
    fn ascii_keywords_in_any_case() {
        let upper = String::from_utf8_lossy(TETRA).to_uppercase();
        assert_eq!(read(upper.as_bytes(), Some(0.0)).unwrap().mesh.face_count(), 2);
    }

    #[test]
    fn binary_round_trip_and_truncation() {
        let d = read(TETRA, Some(0.0)).unwrap();
        let mut bin = Vec::new();
        write(&mut bin, &d.view(), StlEncoding::Binary).unwrap();
        assert_eq!(bin.len(), 84 + 2 * 50);
        assert!(is_binary(&bin));
        let back = read(&bin, Some(0.0)).unwrap();
        assert_eq!(back.mesh, d.mesh);
        assert!(matches!(read(&bin[..120], Some(0.0)), Err(IoError::Truncated { .. })));
        assert!(matches!(read(&bin[..50], Some(0.0)), Err(IoError::Truncated { .. })));
    }

    #[test]
    fn ascii_errors() {
        let cut = &TETRA[..TETRA.len() - 30];
        assert!(matches!(read(cut, Some(0.0)), Err(IoError::Truncated { .. })));
        let nan = String::from_utf8_lossy(TETRA).replace("vertex 1 0 0", "vertex 1 NaN 0");
        assert!(matches!(read(nan.as_bytes(), None), Err(IoError::NonFinite { vertex: 2, .. })));
        assert!(matches!(read(b"solid x\nfacet\nvertex 0 0 0\nendfacet\nendsolid", None), Err(IoError::Syntax { .. })));
    }
}
