//! Triangle meshes for geometry processing: the data model shared by every
//! crate of the mesh workspace, with the connectivity, topology, geometry,
//! discrete operators and sparse solvers that the algorithm crates build on.
//! Section and equation numbers (eq. 2.x) refer to the "Digital Shape
//! Processing" thesis chapter.
//!
//! | module | what it holds | chapter section |
//! |---|---|---|
//! | `alloc` | `BlockCache`, a global allocator that keeps freed large blocks for reuse (feature `block-cache`, for binaries) | |
//! | [`mesh`] | [`TriMesh`]: validated `f64` positions and triangles | 2.2.2 |
//! | [`ids`] | typed indices [`VertexId`], [`FaceId`], [`EdgeId`], [`HalfedgeId`] | |
//! | [`connectivity`] | half-edges, edges, ordered 1-rings, boundary loops, components, manifold report, Euler characteristic and genus (eq. 2.6-2.7) | 2.2.2, 2.3 |
//! | [`cache`] | [`Geometry`]: derived quantities (bounding box, areas, angles, normals, masses, Laplacians, gradient, divergence) computed once per mesh on first use, shared by every crate | |
//! | [`choice`] | named choices: one list of names per selectable enum, parsed and displayed alike | |
//! | [`clean`] | welding, degenerate / duplicate / unreferenced removal, orientation, with a report | |
//! | [`geometry`] | areas, normals, angles, edge lengths, dihedral angles, feature edges, bounding box, volume | 2.2.2 |
//! | [`operators`] | adjacency (eq. 2.5), uniform (eq. 2.12) and cotangent (eq. 2.15) Laplacians, mass matrices, intrinsic Delaunay | 2.2.2, 2.4 |
//! | `solver` | sparse Cholesky / LU on faer, Dirichlet-constrained solves (feature `solver`, default) | |
//! | [`precision`] | how precisely the coordinates were stored (single precision, decimal places or digits) and the position noise that left | |
//! | [`par`] | parallel maps over index ranges: one threshold and task size for every crate (feature `rayon`) | |
//! | [`hint`] | the processor's prefetch, for memory a loop will read a little later | |
//! | [`random`] | `SplitMix64`, the one seeded generator (jitter, start blocks, tests) | |
//! | [`reorder`] | cache-friendly vertex and face orders (a Hilbert curve through the bounding box), with the maps back | |
//! | [`rows`] | [`rows::RowFill`] and [`rows::fill_rows`]: the rows of a compressed sparse layout filled through cursors (pushes in any order, or whole rows in parallel), without zeroing them first | |
//! | [`shapes`] | procedural shapes with exact ground truth | |
//! | [`summary`] | [`summary::MeshSummary`]: counts, topology, defects, area, volume and extent in one struct (what `mesh info` prints) | 2.2.2, 2.3 |
//! | [`submesh`] | a subset of faces, one component or the largest as a mesh of its own, with maps back | |
//! | [`union_find`] | disjoint sets (components, welding, fan splitting) | |
//! | [`units`] | the unit of length: a mesh rescaled by a power of two so that no algorithm over- or underflows | |
//! | [`conventions`] | documentation only: the API convention every crate of the workspace follows | |
//!
//! ```
//! use mesh_kernel::{shapes, operators, solver::Cholesky};
//!
//! let mesh = shapes::icosphere(3)?;                 // 642 vertices on the unit sphere
//! let c = mesh.connectivity();                      // built once, cached
//! assert_eq!((c.euler_characteristic(), c.genus()), (2, Some(0)));
//!
//! // Backward Euler heat step (M + t L) u = M u0 with the cotangent Laplacian.
//! let l = operators::cotan_laplacian(&mesh);
//! let m = operators::mass_matrix(&mesh, operators::MassKind::MixedVoronoi);
//! let a = &m + &l.map(|x| 1e-2 * x);
//! let mut u = vec![0.0; mesh.vertex_count()];
//! u[0] = m.get(0, 0).copied().unwrap_or(0.0);
//! let u = Cholesky::new(&a)?.solve(&u)?;
//! assert!(u.iter().all(|x| x.is_finite() && *x >= -1e-12));
//! # Ok::<(), mesh_kernel::MeshError>(())
//! ```
//!
//! Features: `solver` (default) builds the faer solvers; `rayon` (default)
//! runs per-face loops of large meshes in parallel; `block-cache` provides
//! the `alloc::BlockCache` global allocator. Crates that need only the
//! data model turn both off.
//!
//! Conventions: geometry is `f64`, points are `glam::DVec3`, triangles are
//! counter-clockwise seen from outside, Laplacians are positive
//! semi-definite, sparse matrices are `sprs::CsMat<f64>` in CSR. Nothing a
//! user can feed in panics: invalid input is a [`MeshError`].
#![deny(missing_docs)]

#[cfg(feature = "block-cache")]
pub mod alloc;
pub mod cache;
pub mod choice;
pub mod clean;
pub mod connectivity;
#[doc = include_str!("conventions.md")]
pub mod conventions {}
pub mod error;
pub mod geometry;
pub mod hint;
pub mod ids;
pub mod mesh;
pub mod operators;
pub mod par;
pub mod precision;
pub mod random;
pub mod reorder;
pub mod rows;
pub mod shapes;
#[cfg(feature = "solver")]
pub mod solver;
pub mod submesh;
pub mod summary;
pub mod union_find;
pub mod units;

pub use cache::Geometry;
pub use connectivity::{BoundaryLoop, Components, Connectivity, VertexKind};
pub use error::{MeshError, NonManifoldReport, Result};
pub use ids::{EdgeId, FaceId, HalfedgeId, VertexId};
pub use mesh::TriMesh;
pub use reorder::Reordering;
pub use submesh::SubMesh;

#[cfg(feature = "solver")]
pub use faer;
pub use glam;
pub use sprs;

/// The README's example, compiled and run as a doc-test.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
