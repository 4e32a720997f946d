//! Reading and writing triangle meshes: OBJ, OFF, PLY (ascii and binary),
//! STL (ascii and binary) and glTF 2.0 (`.gltf`, `.glb`), with the normals,
//! texture coordinates, colours and named per-vertex scalars each format can
//! carry, into the [`mesh_kernel::TriMesh`] of the mesh workspace.
//!
//! - [`read`] / [`write()`]: by file name (format from the extension, content
//!   checked against it, writes atomic); [`read_from`] / [`write_to`] for
//!   memory and streams. Writers return a [`WriteReport`] of how much values
//!   stored as 32-bit floats were rounded, and refuse values `f32` cannot
//!   hold ([`IoError::Precision`]) unless
//!   [`WriteOptions::allow_precision_loss`] is set ([`precision`]).
//! - [`MeshData`]: the mesh and its attributes as read, with a [`ReadReport`]
//!   of what the reader changed (polygons triangulated, faces dropped,
//!   vertices welded); [`MeshView`]: what the writers take.
//! - One module per format with small free functions: [`obj`], [`off`],
//!   [`ply`], [`stl`], `gltf` (default feature `gltf`; without it glTF
//!   files are an [`IoError::Unsupported`] and the gltf crate is not built).
//! - [`IoError`]: one error type naming the file, the line and what was
//!   expected. No input makes a reader panic; header counts are checked
//!   against the data size before anything is allocated.
//! - [`write_atomic`]: the temporary-file-and-rename helper the writers use.
//! - [`Format`]: extensions and content sniffing.
//!
//! ```
//! use mesh_kernel::{TriMesh, glam::DVec3};
//! use mesh_io::{MeshView, WriteOptions};
//!
//! let mesh = TriMesh::new(
//!     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
//!     vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
//! )?;
//! let curvature = vec![1.0, 2.0, 3.0, 4.0];
//! let dir = tempfile::tempdir()?;
//! let path = dir.path().join("tetra.ply");
//!
//! // Binary PLY, positions as double, with a named per-vertex property.
//! let view = MeshView::new(&mesh).with_scalar("mean", &curvature);
//! mesh_io::write(&path, view, &WriteOptions::default())?;
//!
//! let data = mesh_io::read(&path)?;
//! assert_eq!(data.mesh, mesh);
//! assert_eq!(data.scalar("mean"), Some(&curvature[..]));
//! assert!(data.report.is_clean());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![deny(missing_docs)]

pub mod atomic;
pub mod data;
pub mod error;
pub mod file;
pub mod format;
#[cfg(feature = "gltf")]
pub mod gltf;
pub mod obj;
pub mod off;
pub mod ply;
pub mod precision;
pub mod stl;
mod text;

pub use atomic::write_atomic;
pub use data::{MeshData, MeshView, ReadReport};
pub use error::{IoError, Location, Result};
pub use file::{read, read_from, read_with, write, write_polylines, write_to, ReadOptions, WriteOptions};
pub use format::Format;
pub use ply::{PlyEncoding, PlyOptions, PlyUvNames};
pub use precision::WriteReport;
pub use stl::StlEncoding;
