//! Reading and writing by file name: the format comes from the extension
//! (or the options), the content is checked against it, writes are atomic.

use std::io::Write;
use std::path::Path;

use glam::DVec3;

use crate::atomic::write_atomic;
use crate::data::{MeshData, MeshView};
use crate::error::{IoError, Result};
use crate::format::Format;
#[cfg(feature = "gltf")]
use crate::gltf;
use crate::ply::PlyOptions;
use crate::precision::{self, Narrowed, WriteReport};
use crate::stl::StlEncoding;
use crate::{obj, off, ply, stl, support};

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
    /// Write values a 32-bit float format cannot hold (they become infinite
    /// or zero) instead of refusing with [`IoError::Precision`]; they are
    /// counted in [`WriteReport::values_lost`]. Default `false`.
    pub allow_precision_loss: bool,
}

/// Reads a mesh file with default options; the format comes from the
/// extension (case-insensitive). The whole file is read into memory first.
///
/// # Errors
/// As [`read_with`].
pub fn read(path: impl AsRef<Path>) -> Result<MeshData> {
    read_with(path, &ReadOptions::default())
}

/// Reads a mesh file. Errors name the file.
///
/// # Errors
/// [`IoError::UnknownFormat`] when the extension is not a mesh format and no
/// format is given; [`IoError::Io`] when the file cannot be read or is not a
/// regular file (folders, devices and pipes are refused before reading); any
/// error of the format's reader ([`read_from`]).
pub fn read_with(path: impl AsRef<Path>, options: &ReadOptions) -> Result<MeshData> {
    let path = path.as_ref();
    let format = match options.format {
        Some(f) => f,
        None => Format::from_path(path)?,
    };
    // A device or pipe named like a mesh file (`zero.ply -> /dev/zero`) would
    // be read without end: only regular files are read by name.
    let meta = std::fs::metadata(path).map_err(|e| IoError::io(path, e))?;
    if !meta.is_file() {
        let e = std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a regular file (a folder, device or pipe)");
        return Err(IoError::io(path, e));
    }
    let bytes = std::fs::read(path).map_err(|e| IoError::io(path, e))?;
    // glTF external buffers are looked up in the named file's folder only.
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    read_bytes(&bytes, format, options, Some(dir)).map_err(|e| e.with_path(path))
}

/// Reads a mesh of the given format from memory (glTF buffers in external
/// files cannot be resolved here).
///
/// # Errors
/// The errors of the format's reader: `IoError::WrongMagic`, `IoError::Syntax`, `IoError::Truncated`,
/// `IoError::Count` (a header count the data cannot hold), `IoError::Index` (a face naming a missing vertex),
/// `IoError::NonFinite`, `IoError::Unsupported`, `IoError::Mesh` (the faces do not make a valid `TriMesh`),
/// `IoError::Gltf` (invalid glTF JSON) and `IoError::ExternalBuffer` (a glTF buffer in an external file:
/// there is no folder to look in).
pub fn read_from(bytes: &[u8], format: Format, options: &ReadOptions) -> Result<MeshData> {
    read_bytes(bytes, format, options, None)
}

fn read_bytes(bytes: &[u8], format: Format, options: &ReadOptions, dir: Option<&Path>) -> Result<MeshData> {
    let data = match format {
        Format::Obj => obj::read(bytes),
        Format::Off => off::read(bytes),
        Format::Ply => ply::read(bytes),
        Format::Stl => stl::read(bytes, options.stl_weld_tolerance),
        #[cfg(feature = "gltf")]
        Format::Gltf => gltf::read(bytes, dir),
        #[cfg(feature = "gltf")]
        Format::Glb => gltf::check_glb_magic(bytes).and_then(|()| gltf::read(bytes, dir)),
        #[cfg(not(feature = "gltf"))]
        Format::Gltf | Format::Glb => {
            let _ = dir;
            Err(without_gltf(format))
        }
    }?;
    Ok(data.without_non_finite_attributes())
}

/// Writes a mesh, or a mesh with attributes, atomically (see
/// [`crate::write_atomic`]). `data` is a `&TriMesh`, a `&MeshData` or a
/// [`MeshView`]; what the format cannot hold is left out. Returns the
/// [`WriteReport`] of [`write_to`].
///
/// # Errors
/// [`IoError::UnknownFormat`] for an extension that is not a mesh format
/// (and no [`WriteOptions::format`]); [`IoError::Io`] when the file cannot be
/// written (a missing folder included: none is created); and the errors of
/// [`write_to`]. The file is left untouched on error.
pub fn write<'a>(path: impl AsRef<Path>, data: impl Into<MeshView<'a>>, options: &WriteOptions) -> Result<WriteReport> {
    let path = path.as_ref();
    let format = match options.format {
        Some(f) => f,
        None => Format::from_path(path)?,
    };
    let view = data.into();
    let mut report = WriteReport::default();
    write_atomic(path, |out| {
        report = write_to(out, format, view, options)?;
        Ok(())
    })
    .map_err(|e: IoError| e.with_path(path))?;
    Ok(report)
}

/// Writes a mesh in the given format to any writer. Values that STL (binary),
/// glTF/GLB and PLY with `float` properties store as 32-bit floats are
/// checked first ([`crate::precision`]); the [`WriteReport`] says how much
/// they were rounded, and names what the format cannot store
/// ([`WriteReport::dropped`]: per-face attributes in glTF, named attributes
/// in OBJ, OFF and STL, ...). (The per-format functions, [`stl::write`] and the
/// like, narrow without this check.)
///
/// # Errors
/// [`IoError::AttributeLength`] when an attribute of the view does not have
/// one entry per vertex (per face for corner UVs and face attributes);
/// [`IoError::AttributeName`] for an empty name or one given twice to the
/// same element; [`IoError::Precision`]
/// when a value would become infinite or zero in a 32-bit format, naming the
/// vertex (unless [`WriteOptions::allow_precision_loss`]);
/// [`IoError::Unsupported`] for what the format cannot hold at all (vertices
/// without faces in STL, PLY attribute names that are not words or clash
/// with other properties, PLY labels beyond 32-bit integers, more than 2^32
/// STL triangles); [`IoError::Io`] when the writer fails.
pub fn write_to<'a, W: Write>(
    out: W,
    format: Format,
    data: impl Into<MeshView<'a>>,
    options: &WriteOptions,
) -> Result<WriteReport> {
    let view = data.into();
    view.check()?;
    let mut report = precision::check(&view, narrowed(format, options), format, options.allow_precision_loss)?;
    report.dropped = support::dropped(format, &view);
    match format {
        Format::Obj => obj::write(out, &view),
        Format::Off => off::write(out, &view),
        Format::Ply => ply::write(out, &view, &options.ply),
        Format::Stl => stl::write(out, &view, options.stl),
        #[cfg(feature = "gltf")]
        Format::Gltf => gltf::write_gltf(out, &view),
        #[cfg(feature = "gltf")]
        Format::Glb => gltf::write_glb(out, &view),
        #[cfg(not(feature = "gltf"))]
        Format::Gltf | Format::Glb => {
            let _ = out;
            Err(without_gltf(format))
        }
    }?;
    Ok(report)
}

/// The error for glTF data when the `gltf` feature is off.
#[cfg(not(feature = "gltf"))]
fn without_gltf(format: Format) -> IoError {
    IoError::Unsupported {
        at: crate::Location::new(format),
        what: "glTF (mesh-io was built without its `gltf` feature)".into(),
    }
}

/// The parts of a view `format` stores as 32-bit floats.
fn narrowed(format: Format, options: &WriteOptions) -> Narrowed {
    let all = Narrowed { positions: true, normals: true, uvs: true, attributes: true };
    match format {
        Format::Gltf | Format::Glb => all,
        Format::Stl if options.stl == StlEncoding::Binary => Narrowed { positions: true, ..Narrowed::default() },
        Format::Ply if !options.ply.double => Narrowed { attributes: false, ..all },
        Format::Obj | Format::Off | Format::Stl | Format::Ply => Narrowed::default(),
    }
}

/// Writes polylines (for example geodesic paths) atomically as an OBJ file of
/// `l` elements ([`obj::write_polylines`]).
///
/// # Errors
/// `IoError::Io` when the file cannot be written (a missing folder included); the file is left untouched on
/// error.
pub fn write_polylines<P: AsRef<[DVec3]>>(path: impl AsRef<Path>, polylines: &[P]) -> Result<()> {
    let path = path.as_ref();
    write_atomic(path, |out| obj::write_polylines(out, polylines)).map_err(|e| e.with_path(path))
}
