//! Surface parameterization (section 2.4 of the "Digital Shape Processing"
//! thesis chapter): flatten a disk-like triangle mesh onto the plane, and
//! measure how much the map distorts; cut any surface into a disk; build a
//! texture atlas of any oriented manifold mesh ([`atlas()`]: charts packed
//! into the unit square, one UV per face corner).
//!
//! | module | what it holds | chapter / paper |
//! |---|---|---|
//! | [`weights`] | one trait, five weight sets: Tutte, mean-value, harmonic, authalic, intrinsic | eq. 2.12-2.16 |
//! | [`fixed`] | the one fixed-boundary solver for `sum_j w_ij (q_i - q_j) = 0` | eq. 2.13 |
//! | [`boundary`] | circle (uniform / chord length), square, user-given boundary maps | |
//! | [`mod@lscm`] | least-squares conformal maps, free boundary | Levy et al. 2002 |
//! | [`arap`] | as-rigid-as-possible local/global refinement | Liu et al. 2008 |
//! | [`mod@distortion`] | Jacobian B = P A, singular values, angle / area distortion, Dirichlet energy vs area, torsion, scaling | eq. 2.8-2.11 |
//! | [`bijectivity`] | boundary self-intersection test (sparse grid) | |
//! | [`topology`] | disk check with a typed error saying what the mesh is | eq. 2.6-2.7 |
//! | [`cut`] | cut a closed or multiply-bounded mesh into a disk, with its seam | Erickson-Whittlesey 2005 |
//! | [`param`] | [`parameterize`] and [`parameterize_cut`], the entry points | |
//! | [`mod@atlas`] | [`atlas()`]: any manifold mesh, one chart per component, packed into the unit square | |
//! | [`pack`] | smallest bounding box of a chart, skyline packing of boxes | Freeman-Shapira 1975, Jylanki 2010 |
//! | [`segment`] | charts: components, optionally split into farthest-point Voronoi regions; one manifold piece each | Gonzalez 1985 |
//!
//! ```
//! use mesh_param::{parameterize, BoundaryMap, ParamMethod, ParamOptions, Spacing};
//!
//! let mut mesh = mesh_kernel::shapes::disk(10, 7)?;      // 331 vertices, unit disk
//! for p in mesh.positions_mut() {
//!     p.z = 0.5 * (p.x * p.x - p.y * p.y);             // bend it into a saddle
//! }
//! let options = ParamOptions {
//!     method: ParamMethod::Harmonic,
//!     boundary: BoundaryMap::Circle(Spacing::ChordLength),
//!     ..Default::default()
//! };
//! let p = parameterize(&mesh, &options)?;
//! assert_eq!(p.uv.len(), mesh.vertex_count());
//! let s = &p.report.summary;
//! assert!(s.bijective && s.flipped_faces == 0);
//! // Eq. 2.11: the Dirichlet energy is at least the area, equal iff conformal.
//! assert!(s.dirichlet_area_ratio > 1.0 && s.dirichlet_area_ratio < 1.1);
//! # Ok::<(), mesh_param::ParamError>(())
//! ```
//!
//! Zero-area faces never produce NaN: by default each is weighted as an
//! equilateral triangle of its mean edge length (uniform weights on that face
//! only, see [`DegeneratePolicy`]), or refused with
//! [`ParamError::DegenerateFaces`]. Nothing a user can feed in panics.
#![deny(missing_docs)]

pub mod arap;
pub mod atlas;
pub mod bijectivity;
pub mod boundary;
pub mod cut;
mod dirichlet;
pub mod distortion;
pub mod error;
pub mod fixed;
pub mod lscm;
pub mod pack;
pub mod param;
pub mod segment;
pub mod topology;
pub mod weights;

pub use arap::{Arap, ArapOptions};
pub use atlas::{atlas, Atlas, AtlasOptions, AtlasSummary, Chart, ChartLayout};
pub use boundary::{BoundaryMap, Spacing};
pub use cut::{cut_to_disk, CutMesh};
pub use distortion::{distortion, DistortionReport, DistortionSummary, FaceDistortion};
pub use error::ParamError;
pub use fixed::{DegeneratePolicy, FixedBoundarySolver};
pub use lscm::{lscm, LscmOptions};
pub use pack::{pack_rectangles, Packing, UvRect};
pub use param::{parameterize, parameterize_cut, CutParameterization, ParamMethod, ParamOptions, Parameterization};
pub use topology::{require_disk, Topology};
pub use weights::{Authalic, Harmonic, Intrinsic, MeanValue, Uniform, Weights};

/// The data model this crate works on, so that one dependency line is enough.
pub use mesh_kernel;
