//! NURBS curves and surfaces for the mesh workspace: the B-spline basis of
//! eq. 2.1-2.2 of the "Digital Shape Processing" thesis chapter (section 2.2.1),
//! NURBS surfaces (eq. 2.3-2.4) with exact derivatives, fundamental forms and
//! curvatures (section 2.5, eq. 2.19-2.24), exact shapes, and tessellation to
//! a watertight [`mesh_kernel::TriMesh`] carrying the exact curvature of every
//! vertex.
//!
//! - [`knots`]: validated knot vectors, clamped and uniform constructors, span search.
//! - [`basis`]: `N_{i,k}(u)` by Cox-de Boor, all non-zero functions of a span and
//!   their derivatives, without allocation.
//! - [`curve`]: [`NurbsCurve`]: points, derivatives, curvature, knot insertion,
//!   degree elevation.
//! - [`surface`]: [`NurbsSurface`]: points, first and second partial derivatives,
//!   normals, knot insertion, degree elevation.
//! - [`frame`]: [`SurfaceFrame`], the differential geometry at a point: `E, F, G`,
//!   `L, M, N`, `K`, `H`, `k1 >= k2` and principal directions (sign conventions
//!   are documented there: a sphere with outward normals has `H = +1/r`).
//! - [`shapes`]: exact circles, arcs, spheres, tori, cylinders, cones, surfaces
//!   of revolution and bilinear patches.
//! - [`tessellate`](mod@tessellate): uniform and adaptive (chordal tolerance) tessellation into a
//!   [`Tessellation`]: the mesh plus per-vertex `(u, v)`, normal, `K`, `H`,
//!   `k1`, `k2` and principal directions. Seams are welded, poles are fans.
//! - [`json`]: a small JSON format for surfaces.
//! - [`error`]: the one error type, [`NurbsError`], of every fallible function.
//!
//! ```
//! use mesh_nurbs::{shapes, tessellate, GridOptions, SurfaceFrame, glam::DVec3};
//!
//! let sphere = shapes::sphere(DVec3::ZERO, 2.0)?;
//! let frame = SurfaceFrame::new(&sphere, 0.3, 0.4)?;
//! assert!((frame.gaussian - 0.25).abs() < 1e-12); // K = 1/r^2
//! assert!((frame.mean - 0.5).abs() < 1e-12); // H = 1/r, outward normal
//!
//! let t = tessellate(&sphere, &GridOptions { segments_u: 32, segments_v: 16, ..Default::default() })?;
//! assert_eq!(t.mesh.connectivity().euler_characteristic(), 2); // watertight
//! assert!(t.mean.iter().all(|&h| (h - 0.5).abs() < 1e-6));
//! # Ok::<(), mesh_nurbs::NurbsError>(())
//! ```
#![deny(missing_docs)]

pub mod basis;
pub mod curve;
pub mod error;
pub mod frame;
pub mod json;
pub mod knots;
pub mod shapes;
pub mod surface;
pub mod tessellate;

pub use curve::NurbsCurve;
pub use error::NurbsError;
pub use frame::SurfaceFrame;
pub use knots::KnotVector;
pub use surface::{NurbsSurface, SurfaceDerivatives};
pub use tessellate::{
    tessellate, tessellate_adaptive, tessellate_parameters, AdaptiveOptions, GridOptions, Tessellation,
};

pub use glam;
/// The data model this crate works on, so that one dependency line is enough.
pub use mesh_kernel;

/// The code blocks of README.md, run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
