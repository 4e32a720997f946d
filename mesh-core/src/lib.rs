//! Triangle meshes for geometry processing: the data model shared by every
//! crate of the mesh workspace.
//!
//! - [`TriMesh`]: `f64` positions and triangles, validated at construction.
//! - [`Connectivity`]: half-edges, edges, ordered 1-rings, boundary loops,
//!   components and a precise manifold report, built once in O(F) and cached.
//!
//! ```
//! use mesh_core::{TriMesh, glam::DVec3};
//!
//! let mesh = TriMesh::new(
//!     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
//!     vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
//! )?;
//! let c = mesh.connectivity();
//! assert_eq!(c.euler_characteristic(), 2); // a sphere
//! assert_eq!(c.genus(), Some(0));
//! # Ok::<(), mesh_core::MeshError>(())
//! ```
#![deny(missing_docs)]

pub mod clean;
pub mod connectivity;
pub mod error;
pub mod ids;
pub mod mesh;

pub use connectivity::{BoundaryLoop, Components, Connectivity, VertexKind};
pub use error::{MeshError, NonManifoldReport, Result};
pub use ids::{EdgeId, FaceId, HalfedgeId, VertexId};
pub use mesh::TriMesh;

pub use glam;
pub use sprs;
