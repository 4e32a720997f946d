//! PLY (Stanford Polygon File Format), ascii and binary of both endians.
//!
//! Reading: the `vertex` element gives positions (`x y z`, any scalar type),
//! normals (`nx ny nz`), texture coordinates (`u v`, `s t`, `texture_u
//! texture_v`), colours (`red green blue [alpha]`; integer types are divided
//! by 255, `ushort` by 65535) and, for every other scalar property, a named
//! attribute ([`crate::attribute`]): a float triple named `NAMEx NAMEy NAMEz`
//! (or `NAME_x NAME_y NAME_z`) is a vector `NAME`, another float property a
//! scalar, an integer property (`char` to `uint`) a label. The `face`
//! element gives polygons (`vertex_indices` or `vertex_index`, a list of any
//! integer count and index type), fan-triangulated, per-corner texture
//! coordinates from a `texcoord` float list, and per-face attributes from its
//! scalar properties in the same way (each triangle of a polygon gets the
//! polygon's value). Other elements and list properties are skipped with a
//! note. Header counts are checked against the data size before anything is
//! allocated.
//!
//! Writing: positions, normals and texture coordinates as `double` (or
//! `float`, [`PlyOptions::double`]), colours as `uchar`, scalars and vectors
//! as `double` (vectors as `NAMEx NAMEy NAMEz`), labels as `int` (`uint`
//! when a value needs it), faces as `list uchar int vertex_indices` (plus
//! `list uchar double texcoord` for corner UVs) followed by the per-face
//! attributes.

use std::collections::{HashMap, HashSet};
use std::io::Write;

use glam::{DVec2, DVec3};

use crate::attribute::{AttributeElement, AttributeValues};
use crate::data::{tri_mesh, MeshData, MeshView, ReadReport};
use crate::error::{excerpt, IoError, Location, Result};
use crate::format::Format;
use crate::text::{vertex_index, Scanner, TextWriter};

/// How a PLY body is stored.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum PlyEncoding {
    /// Text.
    Ascii,
    /// Binary, little-endian (what most tools write).
    #[default]
    BinaryLittleEndian,
    /// Binary, big-endian.
    BinaryBigEndian,
}

/// Options of [`write()`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PlyOptions {
    /// Body encoding.
    pub encoding: PlyEncoding,
    /// Positions, normals and texture coordinates as `double` (exact) rather
    /// than `float`. Scalars are always `double`.
    pub double: bool,
    /// Property names of per-vertex texture coordinates.
    pub uv_names: PlyUvNames,
}

impl Default for PlyOptions {
    fn default() -> Self {
        Self { encoding: PlyEncoding::default(), double: true, uv_names: PlyUvNames::default() }
    }
}

/// Names of the per-vertex texture coordinate properties written; the
/// reader accepts both (and `s t`, `texture_s texture_t`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PlyUvNames {
    /// `texture_u texture_v` (MeshLab's names).
    #[default]
    TextureUv,
    /// `u v` (surface parameters, e.g. of a NURBS tessellation).
    Uv,
}

impl PlyUvNames {
    fn names(self) -> &'static [&'static str] {
        match self {
            Self::TextureUv => &["texture_u", "texture_v"],
            Self::Uv => &["u", "v"],
        }
    }
}

/// A PLY scalar type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &[u8]) -> Option<Self> {
        Some(match name {
            b"char" | b"int8" => Self::I8,
            b"uchar" | b"uint8" => Self::U8,
            b"short" | b"int16" => Self::I16,
            b"ushort" | b"uint16" => Self::U16,
            b"int" | b"int32" => Self::I32,
            b"uint" | b"uint32" => Self::U32,
            b"float" | b"float32" => Self::F32,
            b"double" | b"float64" => Self::F64,
            _ => return None,
        })
    }

    fn name(self) -> &'static str {
        ["char", "uchar", "short", "ushort", "int", "uint", "float", "double"][self as usize]
    }

    fn size(self) -> usize {
        [1, 1, 2, 2, 4, 4, 4, 8][self as usize]
    }

    fn is_float(self) -> bool {
        matches!(self, Self::F32 | Self::F64)
    }

    /// The factor that maps a colour of this type to `[0, 1]`.
    fn color_scale(self) -> f64 {
        match self {
            Self::F32 | Self::F64 => 1.0,
            Self::U16 => 1.0 / 65535.0,
            _ => 1.0 / 255.0,
        }
    }

    /// Decodes a value from exactly `self.size()` bytes.
    #[inline(always)]
    fn decode(self, b: &[u8], big: bool) -> f64 {
        fn arr<const N: usize>(b: &[u8], big: bool) -> [u8; N] {
            let mut a = [0u8; N];
            a.copy_from_slice(&b[..N]);
            if big {
                a.reverse();
            }
            a
        }
        match self {
            Self::I8 => f64::from(b[0] as i8),
            Self::U8 => f64::from(b[0]),
            Self::I16 => f64::from(i16::from_le_bytes(arr(b, big))),
            Self::U16 => f64::from(u16::from_le_bytes(arr(b, big))),
            Self::I32 => f64::from(i32::from_le_bytes(arr(b, big))),
            Self::U32 => f64::from(u32::from_le_bytes(arr(b, big))),
            Self::F32 => f64::from(f32::from_le_bytes(arr(b, big))),
            Self::F64 => f64::from_le_bytes(arr(b, big)),
        }
    }

    /// Decodes an integer from exactly `self.size()` bytes (`None` for a
    /// float with a fractional part or out of the `i64` range).
    #[inline(always)]
    fn decode_int(self, b: &[u8], big: bool) -> Option<i64> {
        let bytes = |n: usize| -> [u8; 4] {
            let mut a = [0u8; 4];
            a[..n].copy_from_slice(&b[..n]);
            if big {
                a[..n].reverse();
            }
            a
        };
        Some(match self {
            Self::I8 => i64::from(b[0] as i8),
            Self::U8 => i64::from(b[0]),
            Self::I16 => i64::from(i32::from_le_bytes(bytes(2)) as i16),
            Self::U16 => i64::from(u32::from_le_bytes(bytes(2)) as u16),
            Self::I32 => i64::from(i32::from_le_bytes(bytes(4))),
            Self::U32 => i64::from(u32::from_le_bytes(bytes(4))),
            Self::F32 | Self::F64 => {
                let x = self.decode(b, big);
                return (x.fract() == 0.0 && x.abs() < 9.2e18).then_some(x as i64);
            }
        })
    }

    /// Appends `x` converted to this type.
    #[inline]
    fn encode(self, x: f64, big: bool, out: &mut Vec<u8>) {
        let start = out.len();
        match self {
            Self::I8 => out.push(x as i8 as u8),
            Self::U8 => out.push(x as u8),
            Self::I16 => out.extend_from_slice(&(x as i16).to_le_bytes()),
            Self::U16 => out.extend_from_slice(&(x as u16).to_le_bytes()),
            Self::I32 => out.extend_from_slice(&(x as i32).to_le_bytes()),
            Self::U32 => out.extend_from_slice(&(x as u32).to_le_bytes()),
            Self::F32 => out.extend_from_slice(&(x as f32).to_le_bytes()),
            Self::F64 => out.extend_from_slice(&x.to_le_bytes()),
        }
        if big {
            out[start..].reverse();
        }
    }
}

/// A property: a scalar or a list (count type, item type).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Scalar(Scalar),
    List(Scalar, Scalar),
}

#[derive(Debug, Clone)]
struct Property {
    name: String,
    kind: Kind,
}

#[derive(Debug, Clone)]
struct Element {
    name: String,
    count: usize,
    props: Vec<Property>,
}

impl Element {
    fn find(&self, names: &[&str]) -> Option<usize> {
        self.props.iter().position(|p| names.contains(&p.name.as_str()))
    }

    /// Fewest bytes (binary) or words (ascii) one instance can take.
    fn min_size(&self, binary: bool) -> u64 {
        let each = |p: &Property| match (binary, p.kind) {
            (false, _) => 1,
            (true, Kind::Scalar(t) | Kind::List(t, _)) => t.size() as u64,
        };
        self.props.iter().map(each).sum()
    }
}

struct Header {
    encoding: PlyEncoding,
    elements: Vec<Element>,
    /// Byte offset of the body.
    body: usize,
    /// Line number of the body's first line.
    body_line: usize,
}

fn loc() -> Location {
    Location::new(Format::Ply)
}

/// Parses the header up to and including `end_header`.
fn header(bytes: &[u8]) -> Result<Header> {
    if !(bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n")) {
        let at = Location::at_line(Format::Ply, 1);
        return Err(IoError::WrongMagic { at, expected: "`ply` and a newline", found: excerpt(bytes) });
    }
    let mut s = Scanner::new(bytes, Format::Ply, None);
    s.next_line();
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        if s.is_eof() {
            return Err(IoError::truncated(s.at(), "`end_header`"));
        }
        match s.word().unwrap_or_default() {
            b"format" => encoding = Some(format_line(&mut s)?),
            b"element" => {
                let name = word_string(&mut s, "an element name")?;
                let count = s.int("an element count")?;
                let count = usize::try_from(count)
                    .map_err(|_| IoError::count(s.at(), &name, count.into(), "counts cannot be negative"))?;
                elements.push(Element { name, count, props: Vec::new() });
            }
            b"property" => {
                let at = s.at();
                let prop = property(&mut s)?;
                let element = elements
                    .last_mut()
                    .ok_or_else(|| IoError::syntax(at, "`element` before `property`", b"property"))?;
                element.props.push(prop);
            }
            b"end_header" => break,
            b"comment" | b"obj_info" | b"" => {}
            other => return Err(IoError::syntax(s.at(), "a PLY header keyword", other)),
        }
        s.next_line();
    }
    s.next_line();
    let encoding = encoding.ok_or_else(|| IoError::syntax(s.at(), "a `format` line in the header", b"end_header"))?;
    Ok(Header { encoding, elements, body: s.offset(), body_line: s.at().line.unwrap_or(1) })
}

fn format_line(s: &mut Scanner<'_>) -> Result<PlyEncoding> {
    let encoding = match s.word().unwrap_or_default() {
        b"ascii" => PlyEncoding::Ascii,
        b"binary_little_endian" => PlyEncoding::BinaryLittleEndian,
        b"binary_big_endian" => PlyEncoding::BinaryBigEndian,
        other => return Err(IoError::syntax(s.at(), "ascii, binary_little_endian or binary_big_endian", other)),
    };
    match s.word() {
        Some(b"1.0" | b"1") => Ok(encoding),
        other => Err(IoError::unsupported(s.at(), format!("PLY version {}", excerpt(other.unwrap_or_default())))),
    }
}

fn word_string(s: &mut Scanner<'_>, what: &str) -> Result<String> {
    let word = s.word().ok_or_else(|| s.error(what))?;
    String::from_utf8(word.to_vec()).map_err(|_| IoError::syntax(s.at(), what, word))
}

fn scalar_type(s: &Scanner<'_>, word: Option<&[u8]>) -> Result<Scalar> {
    let word = word.unwrap_or_default();
    Scalar::parse(word).ok_or_else(|| IoError::syntax(s.at(), "a PLY scalar type (uchar, int, float, ...)", word))
}

fn property(s: &mut Scanner<'_>) -> Result<Property> {
    let first = s.word();
    let kind = if first == Some(b"list") {
        let word = s.word();
        let count = scalar_type(s, word)?;
        if count.is_float() {
            return Err(IoError::syntax(s.at(), "an integer list count type", count.name().as_bytes()));
        }
        let word = s.word();
        Kind::List(count, scalar_type(s, word)?)
    } else {
        Kind::Scalar(scalar_type(s, first)?)
    };
    Ok(Property { name: word_string(s, "a property name")?, kind })
}

/// Refuses element counts the data cannot hold, before allocating.
fn check_counts(h: &Header, available: usize) -> Result<()> {
    let binary = h.encoding != PlyEncoding::Ascii;
    let mut need: u128 = 0;
    for e in &h.elements {
        // An ascii word takes at least two bytes with its separator.
        let each = if binary { e.min_size(true) } else { 2 * e.min_size(false) };
        need += e.count as u128 * u128::from(each);
        if need > available as u128 + 1 {
            let reason =
                format!("{} bytes of data cannot hold {} elements of {each} bytes or more", available, e.count);
            return Err(IoError::count(loc(), format!("`{}`", e.name), e.count as i128, reason));
        }
        if e.name == "vertex" && e.count >= u32::MAX as usize {
            return Err(IoError::count(loc(), "vertex", e.count as i128, "more than 32-bit indices can address"));
        }
    }
    Ok(())
}

/// Where property values come from: ascii words or binary bytes.
trait Source {
    /// The next value, converted to `f64`.
    fn scalar(&mut self, t: Scalar) -> Result<f64>;
    /// The next value, which must be a non-negative integer (list length).
    fn count(&mut self, t: Scalar) -> Result<usize>;
    /// The current location, for errors.
    fn at(&self) -> Location;

    /// A whole list (length, then items) into `out`, which is cleared first.
    fn list(&mut self, c: Scalar, t: Scalar, out: &mut Vec<f64>) -> Result<()> {
        out.clear();
        let n = self.count(c)?;
        for _ in 0..n {
            out.push(self.scalar(t)?);
        }
        Ok(())
    }

    /// A list of vertex indices, each checked to be in `0..nv`, into `out`.
    fn indices(&mut self, c: Scalar, t: Scalar, face: usize, nv: usize, out: &mut Vec<u32>) -> Result<()> {
        out.clear();
        let n = self.count(c)?;
        for _ in 0..n {
            let i = self.scalar(t)?;
            if i.fract() != 0.0 {
                return Err(IoError::syntax(self.at(), "an integer vertex index", i.to_string().as_bytes()));
            }
            out.push(vertex_index(|| self.at(), face, i as i64, nv)?);
        }
        Ok(())
    }

    /// Reads a `face` element made of the index list alone, straight into
    /// `faces`, when this source has a fast path for it (`Ok(false)` if not).
    fn index_lists(&mut self, _e: &Element, _nv: usize, _faces: &mut Faces, _report: &mut ReadReport) -> Result<bool> {
        Ok(false)
    }

    /// Calls `visit` with the values of each instance of `e`: `row[k]` holds
    /// property `k` (lists are skipped and leave their slot alone).
    fn rows(&mut self, e: &Element, row: &mut [f64], visit: impl FnMut(&[f64]) -> Result<()>) -> Result<()> {
        rows_one_by_one(self, e, row, visit)
    }
}

/// [`Source::rows`] one value at a time.
fn rows_one_by_one<S: Source + ?Sized>(
    src: &mut S,
    e: &Element,
    row: &mut [f64],
    mut visit: impl FnMut(&[f64]) -> Result<()>,
) -> Result<()> {
    let mut skipped = Vec::new();
    for _ in 0..e.count {
        for (slot, p) in row.iter_mut().zip(&e.props) {
            match p.kind {
                Kind::Scalar(t) => *slot = src.scalar(t)?,
                Kind::List(c, t) => src.list(c, t, &mut skipped)?,
            }
        }
        visit(row).map_err(|e| e.or_line(src.at().line))?;
    }
    Ok(())
}

struct Ascii<'a>(Scanner<'a>);

impl Source for Ascii<'_> {
    #[inline]
    fn scalar(&mut self, _: Scalar) -> Result<f64> {
        if !self.0.skip_to_content() {
            return Err(IoError::truncated(self.0.at(), "more property values"));
        }
        self.0.float("a number")
    }

    #[inline]
    fn count(&mut self, _: Scalar) -> Result<usize> {
        if !self.0.skip_to_content() {
            return Err(IoError::truncated(self.0.at(), "a list length"));
        }
        let n = self.0.int("a list length")?;
        usize::try_from(n).map_err(|_| IoError::syntax(self.0.at(), "a list length", n.to_string().as_bytes()))
    }

    fn at(&self) -> Location {
        self.0.at()
    }

    /// Indices parsed as integers, not floats.
    fn indices(&mut self, c: Scalar, _: Scalar, face: usize, nv: usize, out: &mut Vec<u32>) -> Result<()> {
        out.clear();
        let n = self.count(c)?;
        for _ in 0..n {
            if !self.0.skip_to_content() {
                return Err(IoError::truncated(self.0.at(), "more vertex indices"));
            }
            let i = self.0.int("an integer vertex index")?;
            out.push(vertex_index(|| self.0.at(), face, i, nv)?);
        }
        Ok(())
    }
}

struct Binary<'a> {
    bytes: &'a [u8],
    pos: usize,
    big: bool,
}

impl Binary<'_> {
    #[inline(always)]
    fn take(&mut self, len: usize) -> Result<&[u8]> {
        match self.bytes.get(self.pos..).and_then(|rest| rest.get(..len)) {
            Some(taken) => {
                self.pos += len;
                Ok(taken)
            }
            None => Err(truncated_at(self.pos, len)),
        }
    }
}

#[cold]
#[inline(never)]
fn truncated_at(pos: usize, len: usize) -> IoError {
    IoError::truncated(loc(), format!("{len} more bytes at byte {pos} of the body"))
}

impl Source for Binary<'_> {
    #[inline(always)]
    fn scalar(&mut self, t: Scalar) -> Result<f64> {
        let big = self.big;
        Ok(t.decode(self.take(t.size())?, big))
    }

    #[inline(always)]
    fn count(&mut self, t: Scalar) -> Result<usize> {
        let big = self.big;
        let n = t.decode_int(self.take(t.size())?, big);
        n.and_then(|n| usize::try_from(n).ok())
            .ok_or_else(|| IoError::syntax(loc(), "a list length", b"a negative number"))
    }

    /// One bounds check per list, integers decoded without going through `f64`.
    #[inline]
    fn indices(&mut self, c: Scalar, t: Scalar, face: usize, nv: usize, out: &mut Vec<u32>) -> Result<()> {
        out.clear();
        let n = self.count(c)?;
        let big = self.big;
        for b in self.take(n.saturating_mul(t.size()))?.chunks_exact(t.size()) {
            let i = t.decode_int(b, big).ok_or_else(|| IoError::syntax(loc(), "an integer vertex index", b))?;
            out.push(vertex_index(loc, face, i, nv)?);
        }
        Ok(())
    }

    fn at(&self) -> Location {
        loc()
    }

    /// One bounds check per list.
    #[inline]
    fn list(&mut self, c: Scalar, t: Scalar, out: &mut Vec<f64>) -> Result<()> {
        out.clear();
        let n = self.count(c)?;
        let big = self.big;
        let bytes = self.take(n.saturating_mul(t.size()))?;
        out.extend(bytes.chunks_exact(t.size()).map(|b| t.decode(b, big)));
        Ok(())
    }

    /// 32-bit index lists, triangles decoded without intermediate buffers.
    fn index_lists(&mut self, e: &Element, nv: usize, faces: &mut Faces, report: &mut ReadReport) -> Result<bool> {
        let [Property { kind: Kind::List(c, t @ (Scalar::I32 | Scalar::U32)), .. }] = e.props.as_slice() else {
            return Ok(false);
        };
        let (c, t, big) = (*c, *t, self.big);
        let mut polygon = Vec::new();
        for f in 0..e.count {
            let n = self.count(c)?;
            polygon.clear();
            for b in self.take(n.saturating_mul(4))?.chunks_exact(4) {
                polygon.push(vertex_index(loc, f, t.decode_int(b, big).unwrap_or(-1), nv)?);
            }
            faces.push(&polygon, &[], report);
        }
        Ok(true)
    }

    /// One bounds check per element when every property is a scalar.
    fn rows(&mut self, e: &Element, row: &mut [f64], mut visit: impl FnMut(&[f64]) -> Result<()>) -> Result<()> {
        let mut fields = Vec::new();
        for p in &e.props {
            let Kind::Scalar(t) = p.kind else { return rows_one_by_one(self, e, row, visit) };
            fields.push((t, fields.last().map_or(0, |&(t, at): &(Scalar, usize)| at + t.size())));
        }
        let size = e.min_size(true) as usize;
        let (big, count) = (self.big, e.count);
        let bytes = self.take(size.saturating_mul(count))?;
        for record in bytes.chunks_exact(size.max(1)).take(count) {
            for (slot, &(t, at)) in row.iter_mut().zip(&fields) {
                *slot = t.decode(&record[at..], big);
            }
            visit(row)?;
        }
        Ok(())
    }
}

/// Reads a PLY file (ascii or binary) from memory. Cost O(size).
///
/// # Errors
/// `IoError::WrongMagic` or `IoError::Syntax` for a malformed header; `IoError::Count` for element counts the
/// data cannot hold (checked before allocating) or a vertex count beyond 32-bit indices; `IoError::Truncated`
/// when a binary body or list ends early; `IoError::Syntax` for a face element without a vertex_indices list
/// or a non-integer index; `IoError::Index`, `IoError::NonFinite` and `IoError::Mesh` as for every reader.
pub fn read(bytes: &[u8]) -> Result<MeshData> {
    let h = header(bytes)?;
    let body = bytes.get(h.body..).unwrap_or_default();
    check_counts(&h, body.len())?;
    match h.encoding {
        PlyEncoding::Ascii => {
            read_body(&h, Ascii(Scanner::new(bytes, Format::Ply, None).starting_at(h.body, h.body_line)))
        }
        encoding => read_body(&h, Binary { bytes: body, pos: 0, big: encoding == PlyEncoding::BinaryBigEndian }),
    }
}

fn read_body(h: &Header, mut src: impl Source) -> Result<MeshData> {
    let nv = h.elements.iter().find(|e| e.name == "vertex").map_or(0, |e| e.count);
    let mut vertices = None;
    let mut faces = None;
    let mut report = ReadReport::default();
    for e in &h.elements {
        match e.name.as_str() {
            "vertex" if vertices.is_none() => vertices = Some(Vertices::read(e, &mut src)?),
            "face" if faces.is_none() => faces = Some(Faces::read(e, nv, &mut src, &mut report)?),
            _ => {
                if !e.props.is_empty() {
                    src.rows(e, &mut vec![0.0; e.props.len()], |_| Ok(()))?;
                }
                report.note(format!("element `{}` ({} items) ignored", e.name, e.count));
            }
        }
    }
    let v = vertices.unwrap_or_default();
    let f = faces.unwrap_or_default();
    let mut data = MeshData::new(tri_mesh(v.positions, f.faces, loc())?);
    data.normals = v.normals;
    data.uvs = v.uvs;
    data.colors = v.colors;
    (data.scalars, data.vectors, data.labels) = (v.fields.scalars, v.fields.vectors, v.fields.labels);
    (data.face_scalars, data.face_vectors, data.face_labels) = (f.fields.scalars, f.fields.vectors, f.fields.labels);
    data.corner_uvs = f.corner_uvs;
    data.report = report;
    Ok(data)
}

const NORMALS: [&[&str]; 3] = [&["nx", "normal_x"], &["ny", "normal_y"], &["nz", "normal_z"]];
const UVS: [&[&str]; 2] = [&["u", "s", "texture_u", "texture_s"], &["v", "t", "texture_v", "texture_t"]];
const COLORS: [&[&str]; 4] =
    [&["red", "diffuse_red"], &["green", "diffuse_green"], &["blue", "diffuse_blue"], &["alpha", "diffuse_alpha"]];

#[derive(Default)]
struct Vertices {
    positions: Vec<DVec3>,
    normals: Option<Vec<DVec3>>,
    uvs: Option<Vec<DVec2>>,
    colors: Option<Vec<[f32; 4]>>,
    fields: Fields,
}

/// The named attributes among an element's scalar properties that no
/// standard attribute claims: float triples `NAMEx NAMEy NAMEz` (or
/// `NAME_x ...`) as vectors, other floats as scalars, integers as labels.
#[derive(Default)]
struct FieldSlots {
    scalars: Vec<(String, usize)>,
    vectors: Vec<(String, [usize; 3])>,
    labels: Vec<(String, usize)>,
}

impl FieldSlots {
    /// Slots of the properties of `e` not in `claimed`. O(properties).
    fn new(e: &Element, claimed: &[usize]) -> Self {
        let mut taken = vec![false; e.props.len()];
        for &i in claimed {
            if let Some(t) = taken.get_mut(i) {
                *t = true;
            }
        }
        let float = |i: usize| matches!(e.props[i].kind, Kind::Scalar(t) if t.is_float());
        let by_name: HashMap<&str, usize> = e.props.iter().enumerate().map(|(i, p)| (p.name.as_str(), i)).collect();
        let mut out = Self::default();
        let mut vector_names = HashSet::new();
        for x in 0..e.props.len() {
            let Some(prefix) = e.props[x].name.strip_suffix('x').filter(|p| !p.is_empty()) else { continue };
            let other = |axis: &str| by_name.get(format!("{prefix}{axis}").as_str()).copied();
            let (Some(y), Some(z)) = (other("y"), other("z")) else { continue };
            let name = prefix.strip_suffix('_').filter(|n| !n.is_empty()).unwrap_or(prefix);
            let free = [x, y, z].iter().all(|&i| !taken[i] && float(i));
            if free && !by_name.contains_key(name) && vector_names.insert(name.to_owned()) {
                [x, y, z].iter().for_each(|&i| taken[i] = true);
                out.vectors.push((name.to_owned(), [x, y, z]));
            }
        }
        for (i, p) in e.props.iter().enumerate().filter(|&(i, _)| !taken[i]) {
            match p.kind {
                Kind::Scalar(t) if t.is_float() => out.scalars.push((p.name.clone(), i)),
                Kind::Scalar(_) => out.labels.push((p.name.clone(), i)),
                Kind::List(..) => {}
            }
        }
        out
    }
}

/// Values of the named attributes of one element, as read.
#[derive(Default)]
struct Fields {
    scalars: Vec<(String, Vec<f64>)>,
    vectors: Vec<(String, Vec<DVec3>)>,
    labels: Vec<(String, Vec<i64>)>,
}

impl Fields {
    /// Empty lists for `slots`, with room for `n` values each (`n` bounded
    /// by the data size, see `check_counts`).
    fn new(slots: &FieldSlots, n: usize) -> Self {
        fn lists<T, S>(named: &[(String, S)], n: usize) -> Vec<(String, Vec<T>)> {
            named.iter().map(|(name, _)| (name.clone(), Vec::with_capacity(n))).collect()
        }
        Self { scalars: lists(&slots.scalars, n), vectors: lists(&slots.vectors, n), labels: lists(&slots.labels, n) }
    }

    /// Appends one instance's values (`row[k]` for property `k`) `times`
    /// times (once per triangle of a polygon).
    ///
    /// # Errors
    /// `IoError::Syntax` when a label's value is not an integer (an ascii
    /// `2.5`, `nan` or `1e300` in an integer property).
    #[inline]
    fn push(&mut self, slots: &FieldSlots, row: &[f64], times: usize) -> Result<()> {
        for ((_, list), (_, k)) in self.scalars.iter_mut().zip(&slots.scalars) {
            list.extend(std::iter::repeat_n(row[*k], times));
        }
        for ((_, list), (_, k)) in self.vectors.iter_mut().zip(&slots.vectors) {
            list.extend(std::iter::repeat_n(DVec3::new(row[k[0]], row[k[1]], row[k[2]]), times));
        }
        for ((name, list), (_, k)) in self.labels.iter_mut().zip(&slots.labels) {
            let x = row[*k];
            if x.fract() != 0.0 || x.abs() >= 9.2e18 {
                let expected = format!("an integer value of property `{name}`");
                return Err(IoError::syntax(loc(), expected, x.to_string().as_bytes()));
            }
            list.extend(std::iter::repeat_n(x as i64, times));
        }
        Ok(())
    }
}

/// Which property of the `vertex` element feeds which attribute.
struct VertexSlots {
    xyz: Vec<usize>,
    normal: Option<Vec<usize>>,
    uv: Option<Vec<usize>>,
    /// Red, green, blue, alpha (alpha may point at the constant 1 slot).
    color: Option<Vec<usize>>,
    color_scale: Vec<f64>,
    fields: FieldSlots,
}

impl VertexSlots {
    /// Slots into a row of one value per property plus a constant 1 at the end.
    fn new(e: &Element) -> Result<Self> {
        let all = |names: &[&[&str]]| names.iter().map(|n| e.find(n)).collect::<Option<Vec<usize>>>();
        let xyz = all(&[&["x"], &["y"], &["z"]]).ok_or_else(|| {
            let first = e.props.first().map_or(&b""[..], |p| p.name.as_bytes());
            IoError::syntax(loc(), "`x`, `y` and `z` properties in element `vertex`", first)
        })?;
        let one = e.props.len();
        let color = all(&COLORS[..3]).map(|mut c| {
            c.push(e.find(COLORS[3]).unwrap_or(one));
            c
        });
        let (normal, uv) = (all(&NORMALS), all(&UVS));
        let mut known = xyz.clone();
        known.extend(normal.iter().chain(&uv).chain(&color).flatten());
        let fields = FieldSlots::new(e, &known);
        let mut color_scale: Vec<f64> =
            e.props.iter().map(|p| if let Kind::Scalar(t) = p.kind { t.color_scale() } else { 1.0 }).collect();
        color_scale.push(1.0);
        Ok(Self { xyz, normal, uv, color, color_scale, fields })
    }
}

impl Vertices {
    fn read(e: &Element, src: &mut impl Source) -> Result<Self> {
        let slots = VertexSlots::new(e)?;
        let n = e.count;
        fn with<T>(on: bool, n: usize) -> Option<Vec<T>> {
            on.then(|| Vec::with_capacity(n))
        }
        let mut out = Vertices {
            positions: Vec::with_capacity(n),
            normals: with(slots.normal.is_some(), n),
            uvs: with(slots.uv.is_some(), n),
            colors: with(slots.color.is_some(), n),
            fields: Fields::new(&slots.fields, n),
        };
        let mut row = vec![1.0; e.props.len() + 1];
        src.rows(e, &mut row[..e.props.len()], |row| out.push(&slots, row))?;
        Ok(out)
    }

    #[inline]
    fn push(&mut self, s: &VertexSlots, row: &[f64]) -> Result<()> {
        let value = |k: usize| row.get(k).copied().unwrap_or(1.0);
        let p = DVec3::new(value(s.xyz[0]), value(s.xyz[1]), value(s.xyz[2]));
        if !p.is_finite() {
            return Err(IoError::NonFinite { at: loc(), vertex: self.positions.len() });
        }
        self.positions.push(p);
        if let (Some(k), Some(list)) = (&s.normal, &mut self.normals) {
            list.push(DVec3::new(value(k[0]), value(k[1]), value(k[2])));
        }
        if let (Some(k), Some(list)) = (&s.uv, &mut self.uvs) {
            list.push(DVec2::new(value(k[0]), value(k[1])));
        }
        if let (Some(k), Some(list)) = (&s.color, &mut self.colors) {
            list.push([0, 1, 2, 3].map(|c| (value(k[c]) * s.color_scale[k[c]]) as f32));
        }
        self.fields.push(&s.fields, row, 1)
    }
}

#[derive(Default)]
struct Faces {
    faces: Vec<[u32; 3]>,
    corner_uvs: Option<Vec<[DVec2; 3]>>,
    fields: Fields,
}

impl Faces {
    fn read(e: &Element, nv: usize, src: &mut impl Source, report: &mut ReadReport) -> Result<Self> {
        let list = |names: &[&str]| e.find(names).filter(|&i| matches!(e.props[i].kind, Kind::List(..)));
        let Some(indices) = list(&["vertex_indices", "vertex_index"]) else {
            return Err(IoError::syntax(loc(), "a `vertex_indices` list in element `face`", b""));
        };
        let texcoord = list(&["texcoord"]);
        let slots = FieldSlots::new(e, &[indices]);
        // `check_counts` bounds e.count by the data size.
        let mut out = Faces {
            faces: Vec::with_capacity(e.count),
            corner_uvs: texcoord.map(|_| Vec::new()),
            fields: Fields::new(&slots, e.count),
        };
        if src.index_lists(e, nv, &mut out, report)? {
            return Ok(out);
        }
        for (k, p) in e.props.iter().enumerate() {
            if matches!(p.kind, Kind::List(..)) && k != indices && Some(k) != texcoord {
                report.note(format!("face list property `{}` ignored", p.name));
            }
        }
        let (mut polygon, mut uv, mut skipped) = (Vec::new(), Vec::new(), Vec::new());
        let mut row = vec![0.0; e.props.len()];
        for f in 0..e.count {
            for (k, p) in e.props.iter().enumerate() {
                match p.kind {
                    Kind::List(c, t) if k == indices => src.indices(c, t, f, nv, &mut polygon)?,
                    Kind::List(c, t) if Some(k) == texcoord => src.list(c, t, &mut uv)?,
                    Kind::List(c, t) => src.list(c, t, &mut skipped)?,
                    Kind::Scalar(t) => row[k] = src.scalar(t)?,
                }
            }
            let before = out.faces.len();
            out.push(&polygon, &uv, report);
            let triangles = out.faces.len() - before;
            out.fields.push(&slots, &row, triangles).map_err(|e| e.or_line(src.at().line))?;
        }
        Ok(out)
    }

    #[inline]
    fn push(&mut self, polygon: &[u32], uv: &[f64], report: &mut ReadReport) {
        if self.corner_uvs.is_some() && uv.len() != 2 * polygon.len() && self.corner_uvs.take().is_some() {
            report.note("texture coordinates dropped: a face's `texcoord` list does not match its vertices");
        }
        let Faces { faces, corner_uvs, .. } = self;
        report.triangulate(polygon, |corners, tri| {
            faces.push(tri);
            if let Some(list) = corner_uvs {
                list.push(corners.map(|c| DVec2::new(uv[2 * c], uv[2 * c + 1])));
            }
        });
    }
}

/// Writes a PLY file. Cost O(size).
///
/// Attribute names must be single words of printable ascii, and the
/// properties they make (`NAME`, or `NAMEx NAMEy NAMEz` for a vector) must
/// not collide with each other or with the properties this crate reads as
/// standard attributes (`x`, `nx`, `red`, `texture_u`, ... on vertices,
/// `vertex_indices`, `texcoord` on faces), else [`IoError::Unsupported`].
/// Labels are written as `int`, or `uint` when a value needs it.
///
/// # Errors
/// `IoError::AttributeLength` and `IoError::AttributeName` from `MeshView::check`; `IoError::Unsupported` for
/// an attribute name that is not a single printable word or makes a property name used twice or by a standard
/// attribute, or a label with values beyond both `int` and `uint`; `IoError::Io` when `out` fails. Float
/// properties are narrowed without the check of [`crate::write_to`].
pub fn write<W: Write>(out: W, view: &MeshView<'_>, options: &PlyOptions) -> Result<()> {
    view.check()?;
    let layout = Layout::new(view, options)?;
    let mut out = out;
    let mut head = TextWriter::new(&mut out);
    layout.header(view, options.encoding, &mut head)?;
    head.finish()?;
    match options.encoding {
        PlyEncoding::Ascii => layout.body(view, AsciiSink { w: TextWriter::new(out), first: true }),
        encoding => layout.body(
            view,
            BinarySink { out, buf: Vec::with_capacity(1 << 16), big: encoding == PlyEncoding::BinaryBigEndian },
        ),
    }
}

/// The properties written for a view.
struct Layout {
    real: Scalar,
    index: Scalar,
    /// Named properties of the `vertex` element, standard ones first.
    vertex: Vec<(String, Scalar)>,
    /// Named scalar properties of the `face` element, after its lists.
    face: Vec<(String, Scalar)>,
    /// The type of each of the view's attributes, in order.
    types: Vec<Scalar>,
}

/// Vertex property names the reader takes as standard attributes.
const RESERVED: [&str; 24] = [
    "x",
    "y",
    "z",
    "nx",
    "ny",
    "nz",
    "normal_x",
    "normal_y",
    "normal_z",
    "u",
    "v",
    "s",
    "t",
    "texture_u",
    "texture_v",
    "texture_s",
    "texture_t",
    "red",
    "green",
    "blue",
    "alpha",
    "diffuse_red",
    "diffuse_green",
    "diffuse_blue",
];

/// Face property names the reader takes as standard attributes.
const RESERVED_FACE: [&str; 3] = ["vertex_indices", "vertex_index", "texcoord"];

impl Layout {
    fn new(view: &MeshView<'_>, options: &PlyOptions) -> Result<Self> {
        let real = if options.double { Scalar::F64 } else { Scalar::F32 };
        let index = if view.mesh.vertex_count() <= i32::MAX as usize { Scalar::I32 } else { Scalar::U32 };
        let mut vertex: Vec<(String, Scalar)> = ["x", "y", "z"].map(|n| (n.to_owned(), real)).to_vec();
        let mut add = |on: bool, names: &[&str], t: Scalar| {
            if on {
                vertex.extend(names.iter().map(|n| (n.to_string(), t)));
            }
        };
        add(view.normals.is_some(), &["nx", "ny", "nz"], real);
        add(view.uvs.is_some() && view.corner_uvs.is_none(), options.uv_names.names(), real);
        add(view.colors.is_some(), &["red", "green", "blue", "alpha"], Scalar::U8);
        let standard = vertex.len();
        let (mut face, mut types) = (Vec::new(), Vec::with_capacity(view.attributes.len()));
        for a in &view.attributes {
            let valid = !a.name.is_empty() && a.name.bytes().all(|b| b.is_ascii_graphic());
            if !valid {
                return Err(IoError::unsupported(loc(), format!("{a} as a PLY property (the name is not a word)")));
            }
            let t = match a.values {
                AttributeValues::Scalar(_) | AttributeValues::Vector(_) => Scalar::F64,
                AttributeValues::Label(v) => label_type(v).ok_or_else(|| {
                    IoError::unsupported(loc(), format!("{a}: values beyond the 32-bit integers PLY stores"))
                })?,
            };
            types.push(t);
            let names: Vec<String> = match a.values {
                AttributeValues::Vector(_) => ["x", "y", "z"].iter().map(|axis| format!("{}{axis}", a.name)).collect(),
                _ => vec![a.name.to_owned()],
            };
            let list = if a.element == AttributeElement::Vertex { &mut vertex } else { &mut face };
            list.extend(names.into_iter().map(|n| (n, t)));
        }
        check_names(&vertex[standard..], &RESERVED, "vertex")?;
        check_names(&face, &RESERVED_FACE, "face")?;
        Ok(Self { real, index, vertex, face, types })
    }

    fn header<W: Write>(&self, view: &MeshView<'_>, encoding: PlyEncoding, w: &mut TextWriter<W>) -> Result<()> {
        let format = ["ascii", "binary_little_endian", "binary_big_endian"][encoding as usize];
        w.str("ply").line()?;
        w.str("format ").str(format).str(" 1.0").line()?;
        w.str("comment written by mesh-io").line()?;
        w.str("element vertex ").uint(view.mesh.vertex_count() as u64).line()?;
        for (name, t) in &self.vertex {
            w.str("property ").str(t.name()).str(" ").str(name).line()?;
        }
        w.str("element face ").uint(view.mesh.face_count() as u64).line()?;
        w.str("property list uchar ").str(self.index.name()).str(" vertex_indices").line()?;
        if view.corner_uvs.is_some() {
            w.str("property list uchar ").str(self.real.name()).str(" texcoord").line()?;
        }
        for (name, t) in &self.face {
            w.str("property ").str(t.name()).str(" ").str(name).line()?;
        }
        w.str("end_header").line()
    }

    fn body(&self, view: &MeshView<'_>, mut sink: impl Sink) -> Result<()> {
        let mesh = view.mesh;
        let uvs = view.uvs.filter(|_| view.corner_uvs.is_none());
        for (i, p) in mesh.positions().iter().enumerate() {
            let real = self.real;
            sink.values(real, &p.to_array());
            if let Some(n) = view.normals {
                sink.values(real, &n[i].to_array());
            }
            if let Some(uv) = uvs {
                sink.values(real, &uv[i].to_array());
            }
            if let Some(c) = view.colors {
                sink.values(Scalar::U8, &c[i].map(|x| f64::from(crate::off::color_byte(x))));
            }
            self.attributes(view, AttributeElement::Vertex, i, &mut sink);
            sink.end()?;
        }
        for (f, tri) in mesh.faces().iter().enumerate() {
            sink.values(Scalar::U8, &[3.0]);
            sink.values(self.index, &tri.map(f64::from));
            if let Some(corner) = view.corner_uvs {
                sink.values(Scalar::U8, &[6.0]);
                sink.values(self.real, &corner[f].map(|uv| uv.to_array()).concat());
            }
            self.attributes(view, AttributeElement::Face, f, &mut sink);
            sink.end()?;
        }
        sink.finish()
    }

    /// The values of element `i` of every attribute of `element`.
    #[inline]
    fn attributes(&self, view: &MeshView<'_>, element: AttributeElement, i: usize, sink: &mut impl Sink) {
        for (a, &t) in view.attributes.iter().zip(&self.types).filter(|(a, _)| a.element == element) {
            match a.values {
                AttributeValues::Scalar(v) => sink.values(t, &[v[i]]),
                AttributeValues::Vector(v) => sink.values(t, &v[i].to_array()),
                // Exact: `label_type` keeps values within 32 bits.
                AttributeValues::Label(v) => sink.values(t, &[v[i] as f64]),
            }
        }
    }
}

/// `int` when every value fits, else `uint` when every value fits, else `None`. O(n).
fn label_type(values: &[i64]) -> Option<Scalar> {
    let (lo, hi) = values.iter().fold((0, 0), |(lo, hi), &x| (x.min(lo), x.max(hi)));
    if lo >= i64::from(i32::MIN) && hi <= i64::from(i32::MAX) {
        Some(Scalar::I32)
    } else if lo >= 0 && hi <= i64::from(u32::MAX) {
        Some(Scalar::U32)
    } else {
        None
    }
}

/// Refuses named properties of `element` that repeat each other or a
/// standard property. O(n).
fn check_names(named: &[(String, Scalar)], reserved: &[&str], element: &str) -> Result<()> {
    let mut seen = HashSet::with_capacity(named.len());
    for (name, _) in named {
        if reserved.contains(&name.as_str()) || !seen.insert(name.as_str()) {
            let what = format!(
                "a property `{name}` in element `{element}` from a named attribute (a standard property, or \
                 one made twice: a vector `NAME` makes `NAMEx NAMEy NAMEz`)"
            );
            return Err(IoError::unsupported(loc(), what));
        }
    }
    Ok(())
}

/// Where the writer puts values: ascii words or binary bytes.
trait Sink {
    /// Appends values of type `t`.
    fn values(&mut self, t: Scalar, xs: &[f64]);
    /// Ends an element instance.
    fn end(&mut self) -> Result<()>;
    /// Writes out what is left.
    fn finish(self) -> Result<()>;
}

struct AsciiSink<W: Write> {
    w: TextWriter<W>,
    first: bool,
}

impl<W: Write> Sink for AsciiSink<W> {
    #[inline]
    fn values(&mut self, t: Scalar, xs: &[f64]) {
        for &x in xs {
            if !self.first {
                self.w.str(" ");
            }
            self.first = false;
            match t {
                Scalar::F64 => self.w.float(x),
                Scalar::F32 => self.w.float32(x as f32),
                Scalar::I8 | Scalar::I16 | Scalar::I32 => self.w.int(x as i64),
                Scalar::U8 | Scalar::U16 | Scalar::U32 => self.w.uint(x as u64),
            };
        }
    }

    #[inline]
    fn end(&mut self) -> Result<()> {
        self.first = true;
        self.w.line()
    }

    fn finish(self) -> Result<()> {
        self.w.finish()
    }
}

struct BinarySink<W: Write> {
    out: W,
    buf: Vec<u8>,
    big: bool,
}

impl<W: Write> Sink for BinarySink<W> {
    #[inline]
    fn values(&mut self, t: Scalar, xs: &[f64]) {
        for &x in xs {
            t.encode(x, self.big, &mut self.buf);
        }
    }

    #[inline]
    fn end(&mut self) -> Result<()> {
        if self.buf.len() >= 1 << 16 {
            self.out.write_all(&self.buf)?;
            self.buf.clear();
        }
        Ok(())
    }

    fn finish(mut self) -> Result<()> {
        self.out.write_all(&self.buf)?;
        self.out.flush()?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ASCII: &[u8] = b"ply\nformat ascii 1.0\ncomment hi\nelement vertex 4\nproperty float x\nproperty float y\n\
property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nproperty double quality\n\
element face 2\nproperty list uchar int vertex_indices\nproperty uchar flags\nelement edge 1\n\
property int vertex1\nproperty int vertex2\nend_header\n0 0 0 255 0 0 0.5\n1 0 0 0 255 0 1.5\n1 1 0 0 0 255 2.5\n\
0 1 0 0 0 0 3.5\n4 0 1 2 3 7\n3 0 2 2 7\n0 1\n";

    #[test]
    fn reads_ascii_with_colors_scalars_and_other_elements() {
        let d = read(ASCII).unwrap();
        assert_eq!((d.mesh.vertex_count(), d.mesh.face_count()), (4, 2));
        assert_eq!((d.report.polygons_triangulated, d.report.faces_dropped), (1, 1));
        assert_eq!(d.colors.as_ref().unwrap()[1], [0.0, 1.0, 0.0, 1.0]);
        assert_eq!(d.scalar("quality"), Some(&[0.5, 1.5, 2.5, 3.5][..]));
        assert_eq!(d.report.notes.len(), 1);
    }

    #[test]
    fn typed_errors() {
        let e = |src: &[u8]| read(src).unwrap_err();
        assert!(matches!(e(b"OFF\n"), IoError::WrongMagic { .. }));
        assert!(matches!(e(b"ply\nformat ascii 1.0\n"), IoError::Truncated { .. }));
        let hostile = b"ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n\
property float y\nproperty float z\nend_header\n";
        assert!(matches!(e(hostile), IoError::Count { .. }), "{}", e(hostile));
        let negative = b"ply\nformat ascii 1.0\nelement vertex -3\nend_header\n";
        assert!(matches!(e(negative), IoError::Count { .. }));
        let text = String::from_utf8_lossy(ASCII);
        let bad_index = text.replace("4 0 1 2 3 7", "4 0 1 2 9 7");
        let err = e(bad_index.as_bytes());
        assert!(matches!(err, IoError::Index { index: 9, .. }), "{err}");
        assert_eq!(err.location().and_then(|l| l.line), Some(23));
        let nan = e(text.replace("1 1 0 0 0 255", "1 nan 0 0 0 255").as_bytes());
        assert!(matches!(nan, IoError::NonFinite { vertex: 2, .. }));
        assert_eq!(nan.location().and_then(|l| l.line), Some(21));
        assert!(matches!(e(&ASCII[..ASCII.len() - 8]), IoError::Truncated { .. }));
        assert!(matches!(
            e(text.replace("uchar int", "uchar float").replace("3 0 2 2", "3 0 2 2.5").as_bytes()),
            IoError::Syntax { .. }
        ));
    }

    #[test]
    fn binary_polygons_and_16_bit_indices() {
        let head = "ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
property float z\nelement face 2\nproperty list uchar uint vertex_indices\nend_header\n";
        let mut bytes = head.as_bytes().to_vec();
        for p in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]] {
            p.iter().for_each(|c| bytes.extend_from_slice(&c.to_be_bytes()));
        }
        for face in [&[0u32, 1, 2, 3][..], &[0, 2, 3]] {
            bytes.push(face.len() as u8);
            face.iter().for_each(|i| bytes.extend_from_slice(&i.to_be_bytes()));
        }
        let d = read(&bytes).unwrap();
        assert_eq!(d.mesh.faces(), &[[0, 1, 2], [0, 2, 3], [0, 2, 3]]);
        assert_eq!(d.report.polygons_triangulated, 1);
        let head16 = head.replace("uchar uint", "uchar ushort").replace("face 2", "face 1");
        let mut bytes16 = head16.into_bytes();
        bytes16.extend_from_slice(&bytes[head.len()..head.len() + 48]);
        bytes16.extend_from_slice(&[3, 0, 0, 0, 1, 0, 2]);
        assert_eq!(read(&bytes16).unwrap().mesh.faces(), &[[0, 1, 2]]);
    }

    #[test]
    fn binary_both_endians_round_trip() {
        let d = read(ASCII).unwrap();
        for encoding in [PlyEncoding::BinaryLittleEndian, PlyEncoding::BinaryBigEndian, PlyEncoding::Ascii] {
            let mut out = Vec::new();
            write(&mut out, &d.view(), &PlyOptions { encoding, double: true, ..Default::default() }).unwrap();
            let back = read(&out).unwrap();
            assert_eq!(back.mesh, d.mesh);
            assert_eq!(back.colors, d.colors);
            assert_eq!(back.scalars, d.scalars);
            assert!(matches!(read(&out[..out.len() - 3]), Err(IoError::Truncated { .. })));
        }
    }
}
