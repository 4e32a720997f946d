//! Reading and writing triangle meshes: OBJ, OFF, PLY (ascii and binary),
//! STL (ascii and binary) and glTF 2.0 (`.gltf`, `.glb`), with the normals,
//! texture coordinates, colours and named attributes (per-vertex or per-face
//! scalars, 3-vectors and integer labels, [`attribute`]) each format can
//! carry, into the [`mesh_kernel::TriMesh`] of the mesh workspace.
//!
//! - [`read`] / [`write()`]: by file name (format from the extension, content
//!   checked against it, writes atomic); [`read_from`] / [`write_to`] for
//!   memory and streams. Writers return a [`WriteReport`] of how much values
//!   stored as 32-bit floats were rounded, and refuse values `f32` cannot
//!   hold ([`IoError::Precision`]) unless
//!   [`WriteOptions::allow_precision_loss`] is set ([`precision`]); what a
//!   format cannot store at all is named in [`WriteReport::dropped`].
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
//! let direction = vec![DVec3::X; 4];
//! let chart = vec![0, 0, 1, 1];
//! // Binary PLY, positions as double, with a named per-vertex property,
//! // a vector (`d1x d1y d1z`) and a per-face integer label.
//! let view = MeshView::new(&mesh)
//!     .with_scalar("mean", &curvature)
//!     .with_vector("d1", &direction)
//!     .with_face_label("chart", &chart);
//! mesh_io::write(&path, view.clone(), &WriteOptions::default())?;
//!
//! let data = mesh_io::read(&path)?;
//! assert_eq!(data.mesh, mesh);
//! assert_eq!(data.scalar("mean"), Some(&curvature[..]));
//! assert_eq!(data.vector("d1"), Some(&direction[..]));
//! assert_eq!(data.face_label("chart"), Some(&chart[..]));
//! assert!(data.report.is_clean());
//!
//! // OBJ has no named attributes: the report says what was left out.
//! let report = mesh_io::write(dir.path().join("tetra.obj"), view, &WriteOptions::default())?;
//! assert_eq!(report.dropped.len(), 3);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![deny(missing_docs)]

pub mod atomic;
pub mod attribute;
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
mod support;
mod text;

pub use atomic::write_atomic;
pub use attribute::{Attribute, AttributeElement, AttributeKind, AttributeValues};
pub use data::{MeshData, MeshView, ReadReport};
pub use error::{IoError, Location};
pub use file::{read, read_from, read_with, write, write_polylines, write_to, ReadOptions, WriteOptions};
pub use format::Format;
pub use ply::{PlyEncoding, PlyOptions, PlyUvNames};
pub use precision::WriteReport;
pub use stl::StlEncoding;

/// The data model this crate works on, so that one dependency line is enough.
pub use mesh_kernel;
