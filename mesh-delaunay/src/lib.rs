//! Planar Delaunay triangulations, Voronoi diagrams, Lawson's edge flips and
//! constrained Delaunay refinement for the mesh workspace, after section
//! 2.2.2 and Figure 2.2 ("arbitrary -> Delaunay by edge flips") of the
//! "Digital Shape Processing" thesis chapter, on
//! [spade](https://docs.rs/spade) (exact predicates, Shewchuk 1997).
//!
//! | module | what it holds | chapter section |
//! |---|---|---|
//! | [`triangulate`] | [`delaunay`]: the Delaunay triangulation of points, duplicates mapped to their first occurrence | 2.2.2, Fig. 2.2 |
//! | [`voronoi`](mod@voronoi) | [`voronoi()`]: the dual cells clipped to a box, the circumcentres | 2.2.2, Fig. 2.2 |
//! | [`lawson`] | [`sweep_triangulation`] (an arbitrary one) and [`lawson_flips`] to Delaunay (Lawson 1977), with mesh-kernel's edge test | 2.2.2, Fig. 2.2 |
//! | [`check`] | [`check_empty_circumcircles`]: the empty-circumcircle property with a relative tolerance | 2.2.2 |
//! | [`refine`] | [`refine_polygon`] and [`refine_polygon_sized`]: constrained Delaunay of a polygon with holes, refined to an angle, an area and a varying size (Chew 1989, Ruppert 1995, Shewchuk 2002) | 2.2.2, 2.4 |
//! | [`error`] | [`DelaunayError`] and the crate's `Result` | |
//!
//! ```
//! use glam::DVec2;
//! use mesh_delaunay::{check_empty_circumcircles, delaunay, lawson_flips, sweep_triangulation, LawsonOptions};
//!
//! let mut rng = mesh_delaunay::mesh_kernel::random::SplitMix64::new(7);
//! let points: Vec<DVec2> = (0..200).map(|_| DVec2::new(rng.signed(), rng.signed())).collect();
//! let d = delaunay(&points)?;
//! assert!(check_empty_circumcircles(&points, &d.triangles, 1e-9)?.is_delaunay());
//!
//! // Figure 2.2: an arbitrary triangulation of the same points, flipped to Delaunay.
//! let sweep = sweep_triangulation(&points)?;
//! let flipped = lawson_flips(&points, &sweep, &LawsonOptions::default())?;
//! assert!(flipped.flips > 0);
//! assert_eq!(flipped.triangles.len(), d.triangles.len());
//! # Ok::<(), mesh_delaunay::DelaunayError>(())
//! ```
//!
//! Conventions: points are `glam::DVec2` in any unit (the points are
//! divided by a power of two near their largest coordinate before spade
//! sees them, which is exact), triangles are `[u32; 3]` counter-clockwise
//! into the points. Nothing a user can feed in panics: invalid input is a
//! [`DelaunayError`].
#![deny(missing_docs)]

pub mod check;
pub mod error;
mod frame;
pub mod lawson;
pub mod refine;
pub mod triangulate;
pub mod voronoi;

pub use check::{check_empty_circumcircles, CircumcircleCheck};
pub use error::DelaunayError;
pub use lawson::{lawson_flips, sweep_triangulation, LawsonFlips, LawsonOptions};
pub use refine::{refine_polygon, refine_polygon_sized, PolygonDomain, RefineOptions, RefinedMesh};
pub use triangulate::{delaunay, Delaunay};
pub use voronoi::{voronoi, Voronoi, VoronoiOptions};

pub use glam;
pub use mesh_kernel;
