//! Remeshing through a parameterization (section 2.4 of the "Digital Shape
//! Processing" thesis chapter: "texture mapping, remeshing"): cut the
//! surface into low-distortion charts, sample the seams once in 3D,
//! triangulate each chart's parameter domain by constrained Delaunay
//! refinement sized by the map's local scale, and lift the new vertices
//! back onto the input; with a report of the quality, the distance to the
//! input and the topology.
//!
//! | module | what it holds | chapter / paper |
//! |---|---|---|
//! | [`remesh`](mod@remesh) | [`remesh()`] and its options: atlas, seams, per-chart refinement, lifting | 2.4; Floater 2003, Chew 1989, Ruppert 1995 |
//! | [`report`] | [`RemeshReport`]: angles, edge lengths against the target, topology of both meshes | 2.2 (eq. 2.6) |
//! | [`hausdorff`] | closest point on a triangle, a triangle grid, sampled Hausdorff distances | Ericson 2005 |
//! | [`locate`] | point location in a chart's parameter triangles (a uniform grid), barycentric coordinates | |
//! | [`error`] | [`RemeshError`] and the crate's `Result` | |
//!
//! Inside, in the order [`remesh()`] runs them: `seams` (the seam curves
//! and their samples), `chart` (a chart's polygon split at repeated
//! points, refined and lifted), `stitch` (no output edge with a third
//! face), `flips` and `collapse` (surface Delaunay flips, short edges),
//! `smooth` (tangential smoothing projected onto the input; Botsch and
//! Kobbelt 2004).
//!
//! ```
//! use mesh_remesh::{remesh, RemeshOptions};
//!
//! let sphere = mesh_remesh::mesh_kernel::shapes::icosphere(3)?;
//! let r = remesh(&sphere, &RemeshOptions { edge_length: 0.2, ..Default::default() })?;
//! let q = &r.report;
//! assert!(!q.topology_changed && q.output_topology.boundary_loops == Some(0));
//! assert!(q.edge_lengths.within_half > 0.9);
//! assert!(q.hausdorff.unwrap().symmetric_relative < 0.01);
//! # Ok::<(), mesh_remesh::RemeshError>(())
//! ```
//!
//! Conventions: positions in any unit (the edge length is in the same),
//! triangles counter-clockwise seen from outside as in the input. Nothing a
//! user can feed in panics: invalid input is a [`RemeshError`], and a chart
//! that cannot be remeshed is an error, never a silently wrong mesh.
#![deny(missing_docs)]

mod chart;
mod collapse;
pub mod error;
mod flips;
pub mod hausdorff;
pub mod locate;
pub mod remesh;
pub mod report;
mod seams;
mod smooth;
mod stitch;

pub use error::RemeshError;
pub use hausdorff::{closest_point_on_triangle, one_sided_hausdorff, TriangleGrid};
pub use remesh::{atlas_options, remesh, RemeshOptions, Remeshed, SIZE_FACTOR};
pub use report::{hausdorff_distance, EdgeLengthStats, HausdorffDistance, RemeshReport, TopologySummary};

pub use mesh_kernel;
