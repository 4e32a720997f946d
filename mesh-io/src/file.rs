//! Reading and writing by file name: the format comes from the extension
//! (or the options), the content is checked against it, writes are atomic.

use std::io::Write;
use std::path::Path;

use glam::DVec3;

use crate::atomic::write_atomic;
use crate::data::{MeshData, MeshView};
use crate::error::{IoError, Result};
use crate::format::Format;
use crate::ply::PlyOptions;
use crate::stl::StlEncoding;
use crate::{gltf, obj, off, ply, stl};

/// Options of [`read_with`] and [`read_from`].
#[derive(Debug, Clone, PartialEq)]
pub struct ReadOptions {
    /// The format, instead of the one the file name's extension gives.
    pub format: Option<Format>,
    /// STL corners closer than this are welded into one vertex (`Some(0.0)`,
    /// the default: identical positions; `None`: three vertices per triangle).
    pub stl_weld_tolerance: Option<f64>,
}

impl Default for ReadOptions {
    fn default() -> Self {
        Self { format: None, stl_weld_tolerance: Some(0.0) }
    }
}

/// Options of [`write()`] and [`write_to`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct WriteOptions {
    /// The format, instead of the one the file name's extension gives.
    pub format: Option<Format>,
    /// PLY encoding and precision (default: binary little-endian, `double`).
    pub ply: PlyOptions,
    /// STL encoding (default: binary).
    pub stl: StlEncoding,
}

/// Reads a mesh file with default options; the format comes from the
/// extension (case-insensitive). The whole file is read into memory first.
pub fn read(path: impl AsRef<Path>) -> Result<MeshData> {
    read_with(path, &ReadOptions::default())
}

/// Reads a mesh file. Errors name the file.
pub fn read_with(path: impl AsRef<Path>, options: &ReadOptions) -> Result<MeshData> {
    let path = path.as_ref();
    let format = match options.format {
        Some(f) => f,
        None => Format::from_path(path)?,
    };
    let bytes = std::fs::read(path).map_err(|e| IoError::io(path, e))?;
    // glTF external buffers are looked up in the named file's folder only.
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    read_bytes(&bytes, format, options, Some(dir)).map_err(|e| e.with_path(path))
}

/// Reads a mesh of the given format from memory (glTF buffers in external
/// files cannot be resolved here).
pub fn read_from(bytes: &[u8], format: Format, options: &ReadOptions) -> Result<MeshData> {
    read_bytes(bytes, format, options, None)
}

fn read_bytes(bytes: &[u8], format: Format, options: &ReadOptions, dir: Option<&Path>) -> Result<MeshData> {
    match format {
        Format::Obj => obj::read(bytes),
        Format::Off => off::read(bytes),
        Format::Ply => ply::read(bytes),
        Format::Stl => stl::read(bytes, options.stl_weld_tolerance),
        Format::Gltf => gltf::read(bytes, dir),
        Format::Glb => gltf::check_glb_magic(bytes).and_then(|()| gltf::read(bytes, dir)),
    }
}

/// Writes a mesh, or a mesh with attributes, atomically (see
/// [`crate::write_atomic`]). `data` is a `&TriMesh`, a `&MeshData` or a
/// [`MeshView`]; what the format cannot hold is left out.
pub fn write<'a>(path: impl AsRef<Path>, data: impl Into<MeshView<'a>>, options: &WriteOptions) -> Result<()> {
    let path = path.as_ref();
    let format = match options.format {
        Some(f) => f,
        None => Format::from_path(path)?,
    };
    let view = data.into();
    write_atomic(path, |out| write_to(out, format, view, options)).map_err(|e| e.with_path(path))
}

/// Writes a mesh in the given format to any writer.
pub fn write_to<'a, W: Write>(
    out: W,
    format: Format,
    data: impl Into<MeshView<'a>>,
    options: &WriteOptions,
) -> Result<()> {
    let view = data.into();
    match format {
        Format::Obj => obj::write(out, &view),
        Format::Off => off::write(out, &view),
        Format::Ply => ply::write(out, &view, &options.ply),
        Format::Stl => stl::write(out, &view, options.stl),
        Format::Gltf => gltf::write_gltf(out, &view),
        Format::Glb => gltf::write_glb(out, &view),
    }
}

/// Writes polylines (for example geodesic paths) atomically as an OBJ file of
/// `l` elements ([`obj::write_polylines`]).
pub fn write_polylines<P: AsRef<[DVec3]>>(path: impl AsRef<Path>, polylines: &[P]) -> Result<()> {
    let path = path.as_ref();
    write_atomic(path, |out| obj::write_polylines(out, polylines)).map_err(|e| e.with_path(path))
}
