//! Geodesic distances and paths on triangle meshes (section 2.6 of the
//! "Digital Shape Processing" thesis chapter):
//! graph distances, Fast Marching, the heat method, gradient-flow path
//! tracing and geodesic sampling, on any [`mesh_kernel::TriMesh`].
//!
//! | module | what it holds | chapter / paper |
//! |---|---|---|
//! | [`dijkstra`](mod@dijkstra) | multi-source Dijkstra on the edge graph (CSR graph, indexed 4-ary heap), shortest-path tree, edge paths; [`DijkstraGraph`] prepared for repeated queries | 2.6 (upper bound); Dijkstra 1959 |
//! | [`exact`] | exact polyhedral distances by window propagation in vertex-oriented triangle order: per-edge window lists, pairwise trimming, the vertex-distance filter, one split per angle | Mitchell, Mount and Papadimitriou 1987; Surazhsky et al. 2005; Xin and Wang 2009; Qin et al. 2016 |
//! | [`fmm`] | Fast Marching ([`FastMarching`]): eq. 2.33-2.34 plane-wave update, point-source and curved-front updates, obtuse triangles split by unfolding, per-vertex weights P | eq. 2.32-2.34, Kimmel and Sethian 1998 |
//! | [`heat`] | the heat method ([`HeatGeodesics`]), prefactored, cotangent or intrinsic Delaunay Laplacian, boundary conditions; the whole exponent range of the heat flow, and a far field ([`HeatFarField`]) with per-vertex status ([`HeatStatus`]) beyond it | Crane, Weischedel and Wardetzky 2013 |
//! | [`trace`] | paths along dC/dt = -grad U from any surface point back to the sources | eq. 2.35 |
//! | [`sampling`] | farthest-point sampling and geodesic Voronoi regions | 2.6 |
//!
//! Every function takes the sources as [`mesh_kernel::VertexId`]s and returns
//! one distance per vertex: 0 at the sources, `+infinity` on vertices no
//! source reaches (other components, isolated vertices), never NaN. Input
//! that cannot be handled is a [`GeodesicError`]; nothing panics.
//!
#![cfg_attr(feature = "heat", doc = "```")]
#![cfg_attr(not(feature = "heat"), doc = "```ignore")]
//! use mesh_kernel::{shapes, VertexId};
//! use mesh_geodesic::{FastMarching, FmmOptions, HeatGeodesics, HeatOptions, SurfacePoint, TraceOptions};
//!
//! let sphere = shapes::icosphere(4)?; // unit sphere, 2562 vertices
//! let source = VertexId(0);
//! let p0 = sphere.position(source);
//!
//! // Fast Marching: one sweep; the object keeps the stencils for more sources.
//! let fmm = FastMarching::new(&sphere, &FmmOptions::default())?;
//! let d = fmm.distance(&[source])?;
//!
//! // The heat method: factor once, then two sparse solves per source set.
//! let heat = HeatGeodesics::new(&sphere, &HeatOptions::default())?;
//! let h = heat.distance(&[source])?;
//!
//! for (i, p) in sphere.positions().iter().enumerate() {
//!     let great_circle = p.dot(p0).clamp(-1.0, 1.0).acos();
//!     assert!((d[i] - great_circle).abs() < 2e-3);
//!     assert!((h[i] - great_circle).abs() < 0.05);
//! }
//!
//! // The path back to the source along -grad U (eq. 2.35).
//! let start = SurfacePoint::at_vertex(&sphere, VertexId(1000)).unwrap();
//! let path = mesh_geodesic::trace_path(&sphere, &d, &[source], start, &TraceOptions::default())?;
//! let great_circle = sphere.position(VertexId(1000)).dot(p0).acos();
//! assert!((path.length - great_circle).abs() < 0.01 * great_circle);
//! # Ok::<(), mesh_geodesic::GeodesicError>(())
//! ```
#![deny(missing_docs)]
// `!(x > 0.0)` is the NaN-rejecting test used throughout on purpose.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod bucket_queue;
pub mod dijkstra;
mod edge_graph;
pub mod error;
pub mod exact;
pub mod fmm;
#[cfg(feature = "heat")]
pub mod heat;
mod indexed_heap;
pub mod sampling;
mod support;
pub mod trace;

pub use dijkstra::{dijkstra, DijkstraGraph, DijkstraOptions, ShortestPaths};
pub use error::GeodesicError;
pub use exact::{exact_distance, ExactOptions};
pub use fmm::{fmm_distance, FastMarching, FmmOptions, FmmStats, FmmUpdate};
#[cfg(feature = "heat")]
pub use heat::{heat_distance, HeatBoundary, HeatDistance, HeatFarField, HeatGeodesics, HeatOptions, HeatStatus};
/// The choice of Laplacian of the heat method, shared with every crate of the workspace.
#[cfg(feature = "heat")]
pub use mesh_kernel::operators::LaplacianKind;
pub use sampling::{farthest_point_sampling, geodesic_voronoi, GeodesicVoronoi, SamplingMetric, SamplingOptions};
pub use trace::{trace_path, GeodesicPath, SurfacePoint, TraceOptions};

/// The data model this crate works on, so that one dependency line is enough.
pub use mesh_kernel;

/// The README's example, compiled and run as a doc-test.
#[cfg(all(doctest, feature = "heat"))]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
