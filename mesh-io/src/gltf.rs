//! glTF 2.0: `.gltf` (JSON) and `.glb` (binary).
//!
//! Reading takes every triangle primitive (`TRIANGLES`, `TRIANGLE_STRIP`,
//! `TRIANGLE_FAN`) of every mesh instanced by the nodes of the default scene
//! (the first scene when none is marked default; the root nodes when there is
//! no scene), with each node's world transform applied to positions and
//! normals (winding flipped under mirroring transforms). Primitives are
//! concatenated without welding. Attributes kept: `NORMAL`, `TEXCOORD_0` (v
//! flipped to the OBJ/PLY convention `v = 1 - v_gltf`), `COLOR_0`, and
//! application-specific attributes `_NAME` as named attributes `NAME`
//! ([`crate::attribute`]): a `SCALAR` of floats (or normalized integers) as
//! a scalar, of integers as a label, a `VEC3` as a vector (not transformed
//! by the nodes: its meaning is the application's); other shapes are
//! skipped with a note. An attribute is kept only when every primitive has
//! it with the same kind. A scene with no
//! triangle primitive reads its `POINTS` primitives as vertices without
//! faces (what the writer makes of a mesh without faces). Buffers come from the
//! GLB `BIN` chunk, `data:` URIs, or files next to the `.gltf` (given a base
//! directory). Points, lines, morph targets, skins, materials and textures
//! are not read; sparse accessors are refused.
//!
//! Writing produces one mesh with one triangle primitive (a `POINTS`
//! primitive when the mesh has no faces): `POSITION`,
//! `NORMAL`, `TEXCOORD_0`, `COLOR_0`, and per-vertex scalars and vectors as
//! `_NAME` `f32` `SCALAR`/`VEC3` accessors, `u32` indices. Labels are
//! `_NAME` `SCALAR` accessors of unsigned shorts when every value is in
//! `0..=65535`, else signed shorts when in `-32768..=32767` (padded to a
//! 4-byte stride, as the specification wants of vertex attributes), else
//! `f32` (exact up to 2^24; such a label reads back as a scalar): glTF
//! allows 32-bit integers for indices only. Per-face attributes have no
//! place in glTF ([`crate::WriteReport::dropped`] names them). glTF stores one texture coordinate per vertex, so vertices with
//! several corner UVs are split. JSON parsing and validation use the `gltf`
//! crate; binary containers and accessors are decoded here with every offset
//! checked.

use std::borrow::Cow;
use std::collections::{BTreeMap, HashMap};
use std::io::Write;
use std::path::Path;

use ::gltf::json::{self, accessor::ComponentType, mesh::Semantic, validation::Checked};
use glam::{DMat3, DMat4, DQuat, DVec2, DVec3, Vec3};

use crate::attribute::{AttributeElement, AttributeValues, LabelStorage};
use crate::data::{tri_mesh, MeshData, MeshView, ReadReport};
use crate::error::{excerpt, IoError, Location, Result};
use crate::format::Format;

fn loc() -> Location {
    Location::new(Format::Gltf)
}

const GLB_MAGIC: &[u8; 4] = b"glTF";
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

/// Checks that `bytes` start with the GLB magic `glTF`.
///
/// # Errors
/// `IoError::WrongMagic` when the bytes do not start with `glTF`.
pub fn check_glb_magic(bytes: &[u8]) -> Result<()> {
    if bytes.starts_with(GLB_MAGIC) {
        Ok(())
    } else {
        Err(IoError::WrongMagic { at: Location::new(Format::Glb), expected: "`glTF`", found: excerpt(bytes) })
    }
}

/// Reads glTF JSON or GLB from memory. External buffer files are looked up
/// in `base_dir` (the `.gltf` file's directory); without one they are an
/// [`IoError::Unsupported`]. Cost O(size).
///
/// # Errors
/// `IoError::Gltf` for JSON that is not glTF; `IoError::Truncated` for a GLB container, chunk, buffer or
/// accessor shorter than announced (GLB lengths are checked against the data, buffers against their
/// byteLength, accessors against their buffer views); `IoError::ExternalBuffer` for a buffer URI that is not
/// a data: URI or a relative path to a regular file inside `base_dir`, or a file shorter than byteLength (or
/// any external buffer when `base_dir` is None); `IoError::Syntax` for an index (mesh, node, accessor, buffer
/// view) out of range or a node hierarchy that is not a tree; `IoError::Unsupported` for sparse accessors,
/// GLB versions other than 2 or non-base64 data URIs; `IoError::Index`, `IoError::NonFinite` and
/// `IoError::Mesh` as for every reader.
pub fn read(bytes: &[u8], base_dir: Option<&Path>) -> Result<MeshData> {
    let (json, bin) = if bytes.starts_with(GLB_MAGIC) { split_glb(bytes)? } else { (bytes, None) };
    // Not `gltf::Document::from_json`: its validation indexes accessors
    // unchecked (it panics on an out-of-range POSITION index), and it refuses
    // files real exporters write (no POSITION min/max). Every index and
    // enumeration is checked here where it is used instead.
    let root = json::Root::from_slice(json).map_err(|e| gltf_error(::gltf::Error::Deserialize(e)))?;
    let buffers = load_buffers(&root, bin, base_dir)?;
    let instances = mesh_instances(&root)?;
    let mut parts = Parts { points: !has_triangles(&root, &instances), ..Parts::default() };
    for (mesh, transform) in instances {
        let mesh = root.meshes.get(mesh).ok_or_else(|| index_error("a mesh", mesh))?;
        for primitive in &mesh.primitives {
            parts.add(&root, &buffers, primitive, transform)?;
        }
    }
    parts.finish()
}

/// Whether any instanced mesh has a triangle primitive.
fn has_triangles(root: &json::Root, instances: &[(usize, DMat4)]) -> bool {
    use json::mesh::Mode;
    instances
        .iter()
        .filter_map(|&(m, _)| root.meshes.get(m))
        .flat_map(|m| &m.primitives)
        .any(|p| matches!(p.mode, Checked::Valid(Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan)))
}

fn index_error(expected: &str, index: usize) -> IoError {
    IoError::syntax(loc(), format!("{expected} index"), index.to_string().as_bytes())
}

fn gltf_error(source: ::gltf::Error) -> IoError {
    IoError::Gltf { at: loc(), source }
}

/// A little-endian `u32` at `offset`, if there are four bytes.
fn le_u32(bytes: &[u8], offset: usize) -> Option<u32> {
    Some(u32::from_le_bytes(bytes.get(offset..offset.checked_add(4)?)?.try_into().ok()?))
}

/// Splits a GLB container into its JSON chunk and optional BIN chunk.
fn split_glb(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>)> {
    let at = Location::new(Format::Glb);
    let (Some(version), Some(length)) = (le_u32(bytes, 4), le_u32(bytes, 8)) else {
        return Err(IoError::truncated(at, "a 12-byte GLB header"));
    };
    if version != 2 {
        return Err(IoError::unsupported(at, format!("GLB version {version}")));
    }
    let data = bytes.get(..length as usize).ok_or_else(|| {
        IoError::truncated(at.clone(), format!("{length} bytes as the GLB header says, found {}", bytes.len()))
    })?;
    let chunk = |offset: usize| -> Result<Option<(u32, &[u8])>> {
        if offset >= data.len() {
            return Ok(None);
        }
        let (Some(len), Some(kind)) = (le_u32(data, offset), le_u32(data, offset + 4)) else {
            return Err(IoError::truncated(at.clone(), "an 8-byte GLB chunk header"));
        };
        let body = data.get(offset + 8..).and_then(|rest| rest.get(..len as usize));
        let body = body.ok_or_else(|| IoError::truncated(at.clone(), format!("a GLB chunk of {len} bytes")))?;
        Ok(Some((kind, body)))
    };
    let json = match chunk(12)? {
        Some((CHUNK_JSON, json)) => json,
        _ => return Err(IoError::syntax(at, "a JSON chunk first", data.get(16..20).unwrap_or_default())),
    };
    let bin = match chunk(20 + json.len())? {
        Some((CHUNK_BIN, bin)) => Some(bin),
        _ => None,
    };
    Ok((json, bin))
}

/// The data of every buffer, cut to its declared `byteLength` and refused
/// when shorter: the GLB `BIN` chunk, a base64 `data:` URI, or a file inside
/// `base_dir` ([`external_buffer`]).
fn load_buffers<'a>(root: &json::Root, bin: Option<&'a [u8]>, base_dir: Option<&Path>) -> Result<Vec<Cow<'a, [u8]>>> {
    let mut out = Vec::with_capacity(root.buffers.len());
    for (i, buffer) in root.buffers.iter().enumerate() {
        let length = buffer.byte_length.0;
        let mut data: Cow<'a, [u8]> =
            match buffer.uri.as_deref() {
                None => Cow::Borrowed(
                    bin.ok_or_else(|| IoError::truncated(loc(), format!("the GLB BIN chunk of buffer {i}")))?,
                ),
                Some(uri) if uri.starts_with("data:") => {
                    let (_, payload) = uri.split_once(";base64,").ok_or_else(|| {
                        IoError::unsupported(loc(), format!("buffer {i}: a data URI that is not base64"))
                    })?;
                    Cow::Owned(base64_decode(payload.as_bytes()).ok_or_else(|| {
                        IoError::syntax(loc(), format!("base64 data in buffer {i}"), payload.as_bytes())
                    })?)
                }
                Some(uri) => {
                    let dir = base_dir.ok_or_else(|| IoError::ExternalBuffer {
                        at: loc(),
                        uri: uri.to_owned(),
                        reason: "external buffer files cannot be resolved when reading from memory (no folder)".into(),
                    })?;
                    Cow::Owned(external_buffer(dir, uri, length)?)
                }
            };
        if (data.len() as u64) < length {
            let e = format!("buffer {i} of {length} bytes (its byteLength), found {}", data.len());
            return Err(IoError::truncated(loc(), e));
        }
        // Only the declared bytes: views beyond `byteLength` are refused.
        match &mut data {
            Cow::Borrowed(b) => *b = &b[..length as usize],
            Cow::Owned(v) => v.truncate(length as usize),
        }
        out.push(data);
    }
    Ok(out)
}

/// Reads the external buffer file `uri` of `byte_length` bytes, which must be
/// a relative URI naming a regular file inside `dir` (the `.gltf` file's
/// folder) once both are canonicalized (symbolic links resolved). Absolute
/// paths, `..` components, other URI schemes, escapes out of the folder and
/// devices, pipes or folders are refused with [`IoError::ExternalBuffer`]
/// before anything is opened; the file's size is checked against
/// `byte_length` first and at most `byte_length` bytes are read. Cost
/// O(`byte_length`).
fn external_buffer(dir: &Path, uri: &str, byte_length: u64) -> Result<Vec<u8>> {
    let refuse = |path: Option<&Path>, reason: String| IoError::ExternalBuffer {
        at: loc(),
        uri: uri.to_owned(),
        reason: match path {
            Some(p) => format!("{}: {reason}", p.display()),
            None => reason,
        },
    };
    let relative = relative_uri_path(uri).map_err(|reason| refuse(None, reason.into()))?;
    let folder = dir.canonicalize().map_err(|e| refuse(Some(dir), format!("the folder cannot be resolved: {e}")))?;
    let named = folder.join(&relative);
    let path = named.canonicalize().map_err(|e| refuse(Some(&named), format!("cannot be resolved: {e}")))?;
    if !path.starts_with(&folder) {
        let reason = format!("it resolves to {}, outside the folder {}", path.display(), folder.display());
        return Err(refuse(Some(&path), reason));
    }
    let meta = std::fs::metadata(&path).map_err(|e| refuse(Some(&path), e.to_string()))?;
    if !meta.is_file() {
        return Err(refuse(Some(&path), "not a regular file (a folder, device or pipe)".into()));
    }
    if meta.len() < byte_length {
        let reason = format!("the file has {} bytes, the buffer's byteLength is {byte_length}", meta.len());
        return Err(refuse(Some(&path), reason));
    }
    let file = std::fs::File::open(&path).map_err(|e| IoError::io(&path, e))?;
    // Capacity bounded by the file's real size, checked above.
    let mut data = Vec::with_capacity(byte_length as usize);
    std::io::Read::read_to_end(&mut std::io::Read::take(file, byte_length), &mut data)
        .map_err(|e| IoError::io(&path, e))?;
    if (data.len() as u64) < byte_length {
        let reason = format!("only {} of the buffer's {byte_length} bytes could be read", data.len());
        return Err(refuse(Some(&path), reason));
    }
    Ok(data)
}

/// The relative path a buffer URI names, after `%XX` decoding; refused
/// (with the reason) when it has a scheme, is absolute, climbs out with
/// `..`, or decodes to something that is not a plain relative path.
fn relative_uri_path(uri: &str) -> std::result::Result<std::path::PathBuf, &'static str> {
    use std::path::Component;
    if uri.is_empty() {
        return Err("an empty URI");
    }
    let scheme = uri
        .split_once(':')
        .is_some_and(|(s, _)| !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c)));
    if scheme {
        return Err("only data: URIs and relative paths are allowed");
    }
    let decoded = percent_decode(uri).ok_or("a %-escape that does not decode to UTF-8 text")?;
    if decoded.contains(['\\', '\0']) || decoded.contains(':') {
        return Err("a backslash, colon or NUL character in the path");
    }
    let path = Path::new(&decoded);
    if path.is_absolute() || decoded.starts_with('/') {
        return Err("an absolute path (only paths relative to the glTF file's folder are allowed)");
    }
    for component in path.components() {
        match component {
            Component::Normal(_) | Component::CurDir => {}
            Component::ParentDir => {
                return Err("a `..` component (the buffer must stay inside the glTF file's folder)")
            }
            Component::RootDir | Component::Prefix(_) => return Err("an absolute path"),
        }
    }
    Ok(path.to_path_buf())
}

/// Decodes the `%XX` escapes of a relative URI; `None` when the result is
/// not UTF-8.
fn percent_decode(uri: &str) -> Option<String> {
    let b = uri.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex =
            b.get(i + 1..i + 3).and_then(|h| std::str::from_utf8(h).ok()).and_then(|h| u8::from_str_radix(h, 16).ok());
        match (b[i], hex) {
            (b'%', Some(byte)) => {
                out.push(byte);
                i += 3;
            }
            (byte, _) => {
                out.push(byte);
                i += 1;
            }
        }
    }
    String::from_utf8(out).ok()
}

const BASE64: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// Standard base64 with padding.
fn base64_encode(data: &[u8]) -> String {
    let mut out = Vec::with_capacity(data.len().div_ceil(3) * 4);
    for chunk in data.chunks(3) {
        let n = chunk.iter().enumerate().fold(0u32, |n, (k, &b)| n | u32::from(b) << (16 - 8 * k));
        for k in 0..4 {
            out.push(if k <= chunk.len() { BASE64[(n >> (18 - 6 * k) & 63) as usize] } else { b'=' });
        }
    }
    // Only characters of the base64 alphabet were pushed.
    String::from_utf8(out).unwrap_or_default()
}

/// Standard base64, padding optional; `None` on any other character.
fn base64_decode(text: &[u8]) -> Option<Vec<u8>> {
    const INVALID: u8 = 0xff;
    let mut value = [INVALID; 256];
    for (i, &c) in BASE64.iter().enumerate() {
        value[c as usize] = i as u8;
    }
    let text = text.strip_suffix(b"==").or_else(|| text.strip_suffix(b"=")).unwrap_or(text);
    let mut out = Vec::with_capacity(text.len() / 4 * 3 + 2);
    let (mut acc, mut bits) = (0u32, 0);
    for &c in text {
        let v = value[c as usize];
        if v == INVALID {
            return None;
        }
        acc = (acc << 6 | u32::from(v)) & 0xff_ffff;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
        }
    }
    Some(out)
}

/// Every mesh instance of the default scene with its world transform.
fn mesh_instances(root: &json::Root) -> Result<Vec<(usize, DMat4)>> {
    let scene = root.scene.map(|s| s.value()).or((!root.scenes.is_empty()).then_some(0));
    let roots: Vec<usize> = match scene.and_then(|s| root.scenes.get(s)) {
        Some(scene) => scene.nodes.iter().map(|n| n.value()).collect(),
        None if root.nodes.is_empty() => return Ok((0..root.meshes.len()).map(|m| (m, DMat4::IDENTITY)).collect()),
        None => {
            let mut is_child = vec![false; root.nodes.len()];
            for child in root.nodes.iter().flat_map(|n| n.children.iter().flatten()) {
                if let Some(c) = is_child.get_mut(child.value()) {
                    *c = true;
                }
            }
            (0..root.nodes.len()).filter(|&n| !is_child[n]).collect()
        }
    };
    let mut visited = vec![false; root.nodes.len()];
    let mut stack: Vec<(usize, DMat4)> = roots.into_iter().rev().map(|n| (n, DMat4::IDENTITY)).collect();
    let mut instances = Vec::new();
    while let Some((n, parent)) = stack.pop() {
        let node = root.nodes.get(n).ok_or_else(|| index_error("a node", n))?;
        if std::mem::replace(&mut visited[n], true) {
            return Err(IoError::syntax(
                loc(),
                "a node hierarchy that is a tree",
                format!("node {n} twice").as_bytes(),
            ));
        }
        let world = parent * local_transform(node);
        if let Some(mesh) = node.mesh {
            instances.push((mesh.value(), world));
        }
        stack.extend(node.children.iter().flatten().rev().map(|c| (c.value(), world)));
    }
    Ok(instances)
}

fn local_transform(node: &json::Node) -> DMat4 {
    if let Some(m) = node.matrix {
        return DMat4::from_cols_array(&m.map(f64::from));
    }
    let t = node.translation.map_or(DVec3::ZERO, |t| DVec3::from_array(t.map(f64::from)));
    let r = node.rotation.map_or(DQuat::IDENTITY, |q| DQuat::from_array(q.0.map(f64::from)).normalize());
    let s = node.scale.map_or(DVec3::ONE, |s| DVec3::from_array(s.map(f64::from)));
    DMat4::from_scale_rotation_translation(s, r, t)
}

/// The elements of an accessor, bounds-checked once: `get(i, k)` is
/// component `k` of element `i` as `f64` (normalized integers mapped to
/// `[0, 1]` or `[-1, 1]`).
struct Elements<'b> {
    data: &'b [u8],
    component: ComponentType,
    normalized: bool,
    dims: usize,
    count: usize,
    offset: usize,
    stride: usize,
}

impl Elements<'_> {
    #[inline]
    fn get(&self, i: usize, k: usize) -> f64 {
        let size = self.component.size();
        let at = self.offset + i * self.stride + k * size;
        decode(self.component, &self.data[at..at + size], self.normalized)
    }

    /// Every element as `[f64; N]` (`N <= dims`).
    fn rows<const N: usize>(&self) -> impl Iterator<Item = [f64; N]> + '_ {
        (0..self.count).map(|i| std::array::from_fn(|k| self.get(i, k)))
    }
}

/// Accessor `index`, which must have one of `dims` components per element
/// and lie within its buffer view and buffer.
fn accessor<'b>(root: &json::Root, buffers: &'b [Cow<'_, [u8]>], index: usize, dims: &[usize]) -> Result<Elements<'b>> {
    let bad = |what: String| IoError::syntax(loc(), what, format!("accessor {index}").as_bytes());
    let acc = root.accessors.get(index).ok_or_else(|| bad("an accessor".into()))?;
    if acc.sparse.is_some() {
        return Err(IoError::unsupported(loc(), format!("sparse accessor {index}")));
    }
    let (Checked::Valid(component), Checked::Valid(kind)) = (&acc.component_type, &acc.type_) else {
        return Err(bad("a valid component type".into()));
    };
    let (component, n) = (component.0, kind.multiplicity());
    if !dims.contains(&n) {
        return Err(bad(format!("{dims:?} components per element")));
    }
    let view =
        acc.buffer_view.and_then(|v| root.buffer_views.get(v.value())).ok_or_else(|| bad("a buffer view".into()))?;
    let data = view_data(view, buffers).ok_or_else(|| bad("a buffer view within its buffer".into()))?;
    let elem = component.size() * n;
    let stride = view.byte_stride.map_or(elem, |s| s.0).max(elem);
    let (count, offset) = (acc.count.0, acc.byte_offset.map_or(0, |o| o.0));
    let need = count
        .checked_sub(1)
        .map_or(Some(0), |last| last.checked_mul(stride as u64)?.checked_add(offset)?.checked_add(elem as u64));
    if need.is_none_or(|need| need > data.len() as u64) {
        return Err(IoError::truncated(loc(), format!("accessor {index}: {count} elements within its buffer view")));
    }
    let (count, offset) = (count as usize, offset as usize);
    Ok(Elements { data, component, normalized: acc.normalized, dims: n, count, offset, stride })
}

/// The bytes of a buffer view, if they lie within its buffer.
fn view_data<'b>(view: &json::buffer::View, buffers: &'b [Cow<'_, [u8]>]) -> Option<&'b [u8]> {
    let buffer = buffers.get(view.buffer.value())?;
    let start = view.byte_offset.map_or(0, |o| o.0);
    let end = start.checked_add(view.byte_length.0)?;
    buffer.get(usize::try_from(start).ok()?..usize::try_from(end).ok()?)
}

#[inline]
fn decode(component: ComponentType, b: &[u8], normalized: bool) -> f64 {
    let (x, scale) = match component {
        ComponentType::I8 => (f64::from(b[0] as i8), 127.0),
        ComponentType::U8 => (f64::from(b[0]), 255.0),
        ComponentType::I16 => (f64::from(i16::from_le_bytes([b[0], b[1]])), 32767.0),
        ComponentType::U16 => (f64::from(u16::from_le_bytes([b[0], b[1]])), 65535.0),
        ComponentType::U32 => (f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])), 1.0),
        ComponentType::F32 => (f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])), 1.0),
    };
    if normalized && scale != 1.0 {
        (x / scale).max(-1.0)
    } else {
        x
    }
}

/// Reads a primitive's attribute, if present.
type AttributeReader<'a, 'b> = dyn Fn(&Semantic, &[usize]) -> Result<Option<Elements<'b>>> + 'a;

/// Primitives gathered into one mesh; an attribute list becomes `None` as
/// soon as a primitive lacks it.
#[derive(Default)]
struct Parts {
    positions: Vec<DVec3>,
    faces: Vec<[u32; 3]>,
    normals: Option<Vec<DVec3>>,
    uvs: Option<Vec<DVec2>>,
    colors: Option<Vec<[f32; 4]>>,
    named: Vec<(String, Named)>,
    primitives: usize,
    /// Read `POINTS` primitives as vertices without faces (when the scene
    /// has no triangle primitive: a point set, as [`write_glb`] writes a mesh
    /// without faces).
    points: bool,
    report: ReadReport,
}

impl Parts {
    fn add(&mut self, root: &json::Root, buffers: &[Cow<'_, [u8]>], p: &json::mesh::Primitive, m: DMat4) -> Result<()> {
        use json::mesh::Mode;
        let mode = match p.mode {
            Checked::Valid(mode) => mode,
            Checked::Invalid => return Err(IoError::syntax(loc(), "a primitive mode", b"")),
        };
        let get = |s: &Semantic, dims: &[usize]| {
            p.attributes.get(&Checked::Valid(s.clone())).map(|a| accessor(root, buffers, a.value(), dims)).transpose()
        };
        let triangles = matches!(mode, Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan);
        let points = mode == Mode::Points && self.points;
        let (Some(xyz), true) = (get(&Semantic::Positions, &[3])?, triangles || points) else {
            self.report.note("primitives that are not triangles, or have no positions, skipped");
            return Ok(());
        };
        let (nv, base) = (xyz.count, self.positions.len());
        for c in xyz.rows::<3>() {
            let p = m.transform_point3(DVec3::from_array(c));
            if !p.is_finite() {
                return Err(IoError::NonFinite { at: loc(), vertex: self.positions.len() });
            }
            self.positions.push(p);
        }
        if triangles {
            let indices = p.indices.map(|i| accessor(root, buffers, i.value(), &[1])).transpose()?;
            self.triangles(mode, indices.as_ref(), nv, base, m.determinant() < 0.0)?;
        }
        self.attributes(p, &get, nv, m)?;
        self.primitives += 1;
        Ok(())
    }

    /// Appends the triangles of a primitive whose `nv` vertices start at
    /// `base`, reversed when `flip` (mirroring transform).
    fn triangles(
        &mut self,
        mode: json::mesh::Mode,
        indices: Option<&Elements<'_>>,
        nv: usize,
        base: usize,
        flip: bool,
    ) -> Result<()> {
        let corner = |c: usize| indices.map_or(c as f64, |e| e.get(c, 0));
        for (t, corners) in corner_triples(mode, indices.map_or(nv, |e| e.count)).enumerate() {
            let mut tri = [0u32; 3];
            for (v, &c) in tri.iter_mut().zip(&corners) {
                let i = corner(c);
                if !(0.0..nv as f64).contains(&i) {
                    let face = self.faces.len() + t;
                    return Err(IoError::Index { at: loc(), face, what: "vertex", index: i as i64, count: nv });
                }
                *v = (base + i as usize) as u32;
            }
            if flip {
                tri.swap(1, 2);
            }
            let Self { report, faces, .. } = self;
            report.triangulate(&tri, |_, t| faces.push(t));
        }
        Ok(())
    }

    fn attributes(
        &mut self,
        p: &json::mesh::Primitive,
        get: &AttributeReader<'_, '_>,
        nv: usize,
        m: DMat4,
    ) -> Result<()> {
        let first = self.primitives == 0;
        let normal_matrix = DMat3::from_mat4(m).inverse().transpose();
        let normals = get(&Semantic::Normals, &[3])?
            .map(|e| e.rows::<3>().map(|c| (normal_matrix * DVec3::from_array(c)).normalize_or_zero()).collect());
        merge(&mut self.normals, normals, first, nv);
        let uvs =
            get(&Semantic::TexCoords(0), &[2])?.map(|e| e.rows::<2>().map(|[u, v]| DVec2::new(u, 1.0 - v)).collect());
        merge(&mut self.uvs, uvs, first, nv);
        let colors = get(&Semantic::Colors(0), &[3, 4])?.map(|e| {
            let alpha = |i: usize| if e.dims == 4 { e.get(i, 3) } else { 1.0 };
            (0..e.count).map(|i| [e.get(i, 0), e.get(i, 1), e.get(i, 2), alpha(i)].map(|x| x as f32)).collect()
        });
        merge(&mut self.colors, colors, first, nv);
        if first {
            self.named = self.first_named(p, get)?;
        }
        let mut named = Vec::with_capacity(self.named.len());
        for (name, mut values) in std::mem::take(&mut self.named) {
            let part = get(&Semantic::Extras(name.clone()), ANY_SHAPE)?.filter(|e| e.count == nv);
            if part.and_then(|e| Named::read(&e)).is_some_and(|part| values.append(part)) {
                named.push((name, values));
            } else {
                self.report.note(format!("attribute `_{name}` dropped: not every primitive has it, of the same kind"));
            }
        }
        self.named = named;
        Ok(())
    }

    /// The application-specific attributes of the first primitive, empty;
    /// those of a shape other than `SCALAR` or `VEC3` are skipped with a note.
    fn first_named(
        &mut self,
        p: &json::mesh::Primitive,
        get: &AttributeReader<'_, '_>,
    ) -> Result<Vec<(String, Named)>> {
        let mut named = Vec::new();
        for key in p.attributes.keys() {
            let Checked::Valid(semantic @ Semantic::Extras(name)) = key else { continue };
            match get(semantic, ANY_SHAPE)?.and_then(|e| Named::read(&e)) {
                Some(values) => named.push((name.clone(), values.emptied())),
                None => self.report.note(format!("attribute `_{name}` skipped: neither SCALAR nor VEC3")),
            }
        }
        Ok(named)
    }

    fn finish(self) -> Result<MeshData> {
        let mut data = MeshData::new(tri_mesh(self.positions, self.faces, loc())?);
        data.normals = self.normals;
        data.uvs = self.uvs;
        data.colors = self.colors;
        for (name, values) in self.named {
            match values {
                Named::Scalar(v) => data.scalars.push((name, v)),
                Named::Vector(v) => data.vectors.push((name, v)),
                Named::Label(v) => data.labels.push((name, v)),
            }
        }
        data.report = self.report;
        Ok(data)
    }
}

/// Every accessor shape (`SCALAR` to `MAT4`), for attributes whose shape decides their kind.
const ANY_SHAPE: &[usize] = &[1, 2, 3, 4, 9, 16];

/// The values of an application-specific attribute as read.
enum Named {
    Scalar(Vec<f64>),
    Vector(Vec<DVec3>),
    Label(Vec<i64>),
}

impl Named {
    /// A `SCALAR` of floats or normalized integers as a scalar, of integers
    /// as a label (decoded exactly), a `VEC3` as a vector; `None` for other
    /// shapes. O(count).
    fn read(e: &Elements<'_>) -> Option<Self> {
        Some(match e.dims {
            1 if e.component == ComponentType::F32 || e.normalized => {
                Self::Scalar(e.rows::<1>().map(|[x]| x).collect())
            }
            1 => Self::Label(e.rows::<1>().map(|[x]| x as i64).collect()),
            3 => Self::Vector(e.rows::<3>().map(DVec3::from_array).collect()),
            _ => return None,
        })
    }

    /// The same kind, without values.
    fn emptied(self) -> Self {
        match self {
            Self::Scalar(_) => Self::Scalar(Vec::new()),
            Self::Vector(_) => Self::Vector(Vec::new()),
            Self::Label(_) => Self::Label(Vec::new()),
        }
    }

    /// Appends `part` when it is of the same kind (`false` otherwise).
    fn append(&mut self, part: Self) -> bool {
        match (self, part) {
            (Self::Scalar(all), Self::Scalar(p)) => all.extend(p),
            (Self::Vector(all), Self::Vector(p)) => all.extend(p),
            (Self::Label(all), Self::Label(p)) => all.extend(p),
            _ => return false,
        }
        true
    }
}

/// Appends a primitive's attribute, or drops the attribute when it lacks it.
fn merge<T>(all: &mut Option<Vec<T>>, part: Option<Vec<T>>, first: bool, nv: usize) {
    match (all.as_mut(), part) {
        (Some(list), Some(part)) if part.len() == nv => list.extend(part),
        (None, Some(part)) if first && part.len() == nv => *all = Some(part),
        _ => *all = None,
    }
}

/// Corner numbers of the triangles of a primitive with `n` indices.
fn corner_triples(mode: json::mesh::Mode, n: usize) -> Box<dyn Iterator<Item = [usize; 3]>> {
    use json::mesh::Mode;
    match mode {
        Mode::TriangleStrip => {
            Box::new((0..n.saturating_sub(2)).map(|i| if i % 2 == 0 { [i, i + 1, i + 2] } else { [i + 1, i, i + 2] }))
        }
        Mode::TriangleFan => Box::new((1..n.saturating_sub(1)).map(|i| [0, i, i + 1])),
        _ => Box::new((0..n / 3).map(|t| [3 * t, 3 * t + 1, 3 * t + 2])),
    }
}

/// Writes a binary glTF (`.glb`): one mesh, one triangle primitive, `f32`
/// attributes and `u32` indices in the `BIN` chunk. Cost O(size).
///
/// # Errors
/// `IoError::AttributeLength` from `MeshView::check`; `IoError::Gltf` when the JSON cannot be serialized or
/// written; values are narrowed to f32 without the check of [`crate::write_to`].
pub fn write_glb<W: Write>(out: W, view: &MeshView<'_>) -> Result<()> {
    let (root, bin) = document(view, false)?;
    let json = json::serialize::to_vec(&root).map_err(|e| gltf_error(::gltf::Error::Deserialize(e)))?;
    let header = ::gltf::binary::Header { magic: *GLB_MAGIC, version: 2, length: 0 };
    let glb = ::gltf::binary::Glb { header, json: Cow::Owned(json), bin: Some(Cow::Owned(bin)) };
    glb.to_writer(out).map_err(gltf_error)
}

/// Writes glTF JSON (`.gltf`) with the buffer embedded as a base64 `data:`
/// URI, so the file stands alone. Cost O(size).
///
/// # Errors
/// `IoError::AttributeLength` from `MeshView::check`; `IoError::Gltf` when the JSON cannot be serialized;
/// `IoError::Io` when `out` fails. Values are narrowed to f32 without the check of [`crate::write_to`].
pub fn write_gltf<W: Write>(mut out: W, view: &MeshView<'_>) -> Result<()> {
    let (root, _) = document(view, true)?;
    let json = json::serialize::to_vec(&root).map_err(|e| gltf_error(::gltf::Error::Deserialize(e)))?;
    out.write_all(&json)?;
    out.flush()?;
    Ok(())
}

/// Vertices as glTF needs them: split where a vertex has several corner UVs.
struct Split {
    /// The original vertex of each written vertex.
    source: Vec<u32>,
    faces: Vec<[u32; 3]>,
    uvs: Option<Vec<DVec2>>,
}

impl Split {
    fn new(view: &MeshView<'_>) -> Self {
        let mesh = view.mesh;
        let Some(corner_uvs) = view.corner_uvs else {
            let source = (0..mesh.vertex_count() as u32).collect();
            return Self { source, faces: mesh.faces().to_vec(), uvs: view.uvs.map(<[_]>::to_vec) };
        };
        let mut ids: HashMap<(u32, [u64; 2]), u32> = HashMap::with_capacity(mesh.vertex_count());
        let (mut source, mut uvs) = (Vec::new(), Vec::new());
        let faces = mesh
            .faces()
            .iter()
            .zip(corner_uvs)
            .map(|(tri, uv)| {
                [0, 1, 2].map(|k| {
                    *ids.entry((tri[k], uv[k].to_array().map(f64::to_bits))).or_insert_with(|| {
                        source.push(tri[k]);
                        uvs.push(uv[k]);
                        source.len() as u32 - 1
                    })
                })
            })
            .collect();
        Self { source, faces, uvs: Some(uvs) }
    }

    /// The values of the written vertices.
    fn each<'v, T>(&'v self, values: &'v [T]) -> impl Iterator<Item = &'v T> + 'v {
        self.source.iter().map(move |&v| &values[v as usize])
    }
}

/// The glTF document and binary buffer for a view; `embed` puts the buffer
/// in a `data:` URI.
fn document(view: &MeshView<'_>, embed: bool) -> Result<(json::Root, Vec<u8>)> {
    view.check()?;
    let split = Split::new(view);
    let mut doc = Doc::default();
    let floats_per_vertex =
        [(true, 3), (view.normals.is_some(), 3), (split.uvs.is_some(), 2), (view.colors.is_some(), 4)]
            .iter()
            .map(|&(on, n)| usize::from(on) * n)
            .sum::<usize>()
            + view.attributes.iter().map(|a| a.arity()).sum::<usize>();
    doc.bin.reserve(4 * (split.source.len() * floats_per_vertex + split.faces.len() * 3));
    let mut attributes = BTreeMap::new();
    if !split.source.is_empty() {
        let positions = || split.each(view.mesh.positions()).map(|p| p.as_vec3());
        let min = positions().fold(Vec3::INFINITY, Vec3::min).to_array();
        let max = positions().fold(Vec3::NEG_INFINITY, Vec3::max).to_array();
        let bounds = Some((json::Value::from(&min[..]), json::Value::from(&max[..])));
        attributes.insert(Semantic::Positions, doc.floats(positions().flat_map(|p| p.to_array()), 3, bounds));
    }
    if let Some(n) = view.normals {
        attributes.insert(Semantic::Normals, doc.floats(split.each(n).flat_map(|n| n.as_vec3().to_array()), 3, None));
    }
    if let Some(uvs) = &split.uvs {
        let uv = uvs.iter().flat_map(|uv| [uv.x as f32, (1.0 - uv.y) as f32]);
        attributes.insert(Semantic::TexCoords(0), doc.floats(uv, 2, None));
    }
    if let Some(c) = view.colors {
        attributes.insert(Semantic::Colors(0), doc.floats(split.each(c).flatten().copied(), 4, None));
    }
    for a in view.attributes.iter().filter(|a| a.element == AttributeElement::Vertex) {
        let accessor = match a.values {
            AttributeValues::Scalar(v) => doc.floats(split.each(v).map(|&x| x as f32), 1, None),
            AttributeValues::Vector(v) => doc.floats(split.each(v).flat_map(|d| d.as_vec3().to_array()), 3, None),
            AttributeValues::Label(v) => doc.labels(split.each(v).copied(), LabelStorage::of(v)),
        };
        attributes.insert(Semantic::Extras(a.name.to_owned()), accessor);
    }
    let has_faces = !split.faces.is_empty();
    let indices = has_faces.then(|| {
        let words = split.faces.as_flattened().iter().map(|i| i.to_le_bytes());
        doc.accessor(words, 1, ComponentType::U32, json::buffer::Target::ElementArrayBuffer, None)
    });
    let mode = if has_faces { json::mesh::Mode::Triangles } else { json::mesh::Mode::Points };
    Ok(doc.finish(attributes, indices, mode, embed))
}

/// A glTF document under construction, with its binary buffer.
#[derive(Default)]
struct Doc {
    root: json::Root,
    bin: Vec<u8>,
}

impl Doc {
    /// Adds `f32` data with `n` components per element.
    fn floats(
        &mut self,
        values: impl Iterator<Item = f32>,
        n: usize,
        bounds: Option<(json::Value, json::Value)>,
    ) -> json::Index<json::Accessor> {
        self.accessor(values.map(f32::to_le_bytes), n, ComponentType::F32, json::buffer::Target::ArrayBuffer, bounds)
    }

    /// Adds integer labels as `storage` says: shorts padded to 4 bytes (a
    /// vertex attribute's elements must start at multiples of 4), or `f32`.
    fn labels(&mut self, values: impl Iterator<Item = i64>, storage: LabelStorage) -> json::Index<json::Accessor> {
        let target = json::buffer::Target::ArrayBuffer;
        let short = |b: [u8; 2]| [b[0], b[1], 0, 0];
        match storage {
            LabelStorage::U16 => {
                self.accessor(values.map(|x| short((x as u16).to_le_bytes())), 1, ComponentType::U16, target, None)
            }
            LabelStorage::I16 => {
                self.accessor(values.map(|x| short((x as i16).to_le_bytes())), 1, ComponentType::I16, target, None)
            }
            LabelStorage::F32 => self.floats(values.map(|x| x as f32), 1, None),
        }
    }

    /// Adds a buffer view holding 4-byte words, `n` per element, and an
    /// accessor over it (with a 4-byte stride when a word holds a
    /// narrower component).
    fn accessor(
        &mut self,
        words: impl Iterator<Item = [u8; 4]>,
        n: usize,
        component: ComponentType,
        target: json::buffer::Target,
        bounds: Option<(json::Value, json::Value)>,
    ) -> json::Index<json::Accessor> {
        use json::accessor::Type;
        let offset = self.bin.len();
        words.for_each(|w| self.bin.extend_from_slice(&w));
        let length = self.bin.len() - offset;
        let (count, kind) = (length / 4 / n, [Type::Scalar, Type::Vec2, Type::Vec3, Type::Vec4][n - 1]);
        let view = self.root.push(json::buffer::View {
            buffer: json::Index::new(0),
            byte_length: length.into(),
            byte_offset: Some(offset.into()),
            byte_stride: (component.size() < 4).then_some(json::buffer::Stride(4)),
            target: Some(Checked::Valid(target)),
            extensions: None,
            extras: Default::default(),
        });
        let (min, max) = bounds.unzip();
        self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: count.into(),
            component_type: Checked::Valid(json::accessor::GenericComponentType(component)),
            extensions: None,
            extras: Default::default(),
            type_: Checked::Valid(kind),
            min,
            max,
            normalized: false,
            sparse: None,
        })
    }

    fn finish(
        mut self,
        attributes: BTreeMap<Semantic, json::Index<json::Accessor>>,
        indices: Option<json::Index<json::Accessor>>,
        mode: json::mesh::Mode,
        embed: bool,
    ) -> (json::Root, Vec<u8>) {
        if !attributes.is_empty() {
            let primitive = json::mesh::Primitive {
                attributes: attributes.into_iter().map(|(k, v)| (Checked::Valid(k), v)).collect(),
                extensions: None,
                extras: Default::default(),
                indices,
                material: None,
                mode: Checked::Valid(mode),
                targets: None,
            };
            let mesh = self.root.push(json::Mesh {
                extensions: None,
                extras: Default::default(),
                primitives: vec![primitive],
                weights: None,
            });
            let nodes = vec![self.root.push(json::Node { mesh: Some(mesh), ..Default::default() })];
            // gltf-json cannot read back a scene with no nodes: an empty mesh has no scene.
            let scene = self.root.push(json::Scene { extensions: None, extras: Default::default(), nodes });
            self.root.scene = Some(scene);
        }
        self.root.asset.generator = Some("mesh-io".to_owned());
        if !self.bin.is_empty() {
            let uri = embed.then(|| format!("data:application/octet-stream;base64,{}", base64_encode(&self.bin)));
            self.root.push(json::Buffer {
                byte_length: self.bin.len().into(),
                uri,
                extensions: None,
                extras: Default::default(),
            });
        }
        (self.root, self.bin)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::TriMesh;

    fn quad() -> MeshData {
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
        let mut d = MeshData::new(TriMesh::new(p, vec![[0, 1, 2], [0, 2, 3]]).unwrap());
        d.normals = Some(vec![DVec3::Z; 4]);
        d.uvs = Some(vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y]);
        d.colors = Some(vec![[1.0, 0.5, 0.25, 1.0]; 4]);
        d.scalars = vec![("mean".into(), vec![0.5, 1.5, 2.5, 3.5])];
        d
    }

    #[test]
    fn strips_and_fans() {
        use json::mesh::Mode;
        let strip: Vec<_> = corner_triples(Mode::TriangleStrip, 5).collect();
        assert_eq!(strip, [[0, 1, 2], [2, 1, 3], [2, 3, 4]]);
        let fan: Vec<_> = corner_triples(Mode::TriangleFan, 5).collect();
        assert_eq!(fan, [[0, 1, 2], [0, 2, 3], [0, 3, 4]]);
        assert_eq!(corner_triples(Mode::Triangles, 7).count(), 2);
    }

    #[test]
    fn base64_round_trip() {
        for n in 0..8 {
            let data: Vec<u8> = (0..n).map(|i| (i * 77 + 3) as u8).collect();
            assert_eq!(base64_decode(base64_encode(&data).as_bytes()).unwrap(), data);
        }
        assert_eq!(base64_encode(b"Man"), "TWFu");
        assert!(base64_decode(b"a*b").is_none());
        assert_eq!(percent_decode("my%20mesh.bin").as_deref(), Some("my mesh.bin"));
    }

    #[test]
    fn glb_and_gltf_round_trip() {
        let d = quad();
        let mut glb = Vec::new();
        write_glb(&mut glb, &d.view()).unwrap();
        let mut text = Vec::new();
        write_gltf(&mut text, &d.view()).unwrap();
        for bytes in [glb, text] {
            let back = read(&bytes, None).unwrap();
            assert_eq!(back.mesh, d.mesh);
            assert_eq!(back.normals, d.normals);
            assert_eq!(back.uvs, d.uvs);
            assert_eq!(back.colors, d.colors);
            assert_eq!(back.scalars, d.scalars);
        }
    }

    #[test]
    fn corner_uvs_split_vertices() {
        let mut d = quad();
        d.uvs = None;
        d.corner_uvs = Some(vec![[DVec2::ZERO, DVec2::X, DVec2::ONE], [DVec2::ZERO, DVec2::splat(0.5), DVec2::Y]]);
        let mut glb = Vec::new();
        write_glb(&mut glb, &d.view()).unwrap();
        let back = read(&glb, None).unwrap();
        assert_eq!(back.mesh.vertex_count(), 5);
        let uv = back.uvs.unwrap();
        let corner = |f: usize, k: usize| uv[back.mesh.faces()[f][k] as usize];
        assert_eq!(corner(1, 1), DVec2::splat(0.5));
    }

    #[test]
    fn node_transforms_and_truncation() {
        let d = quad();
        let mut text = Vec::new();
        write_gltf(&mut text, &d.view()).unwrap();
        let text = String::from_utf8(text)
            .unwrap()
            .replace(r#""mesh":0"#, r#""mesh":0,"translation":[0,0,2],"scale":[-1,1,1]"#);
        let back = read(text.as_bytes(), None).unwrap();
        assert_eq!(back.mesh.positions()[1], DVec3::new(-1.0, 0.0, 2.0));
        assert_eq!(back.mesh.faces()[0], [0, 2, 1], "mirroring flips the winding");
        let mut glb = Vec::new();
        write_glb(&mut glb, &d.view()).unwrap();
        for cut in [3, 11, 19, 40, glb.len() - 8] {
            assert!(read(&glb[..cut], None).is_err(), "cut at {cut}");
        }
        assert!(matches!(check_glb_magic(b"{}"), Err(IoError::WrongMagic { .. })));
    }
}
