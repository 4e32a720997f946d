//! Discrete curvature of triangle meshes ("Digital Shape Processing" thesis
//! chapter, section 2.5): Gaussian curvature by angle defect, mean
//! curvature by the cotangent formula, the curvature tensor with principal
//! curvatures and directions, pointwise curvature of scans with per-vertex
//! flags, integral curvature over neighbourhoods, shape index and
//! curvedness.
//!
//! | function | what it computes | chapter |
//! |---|---|---|
//! | [`gaussian_curvature`] | angle defect, integrated and pointwise, boundary geodesic curvature (Gauss-Bonnet exact) | eq. 2.25 |
//! | [`mean_curvature`] | Meyer et al. 2003 mean-curvature normal from [`mesh_kernel::operators::cotan_laplacian`] | eq. 2.26 |
//! | [`curvature_tensor`] | [`CurvatureTensor`]: `k1 >= k2`, directions `d1`, `d2`, by a [`TensorMethod`]: quartic (default), cubic or quadric [jet fit](FitOptions), Rusinkiewicz 2004, normal cycle (Cohen-Steiner and Morvan 2003) | eq. 2.27-2.31, 2.18-2.20 |
//! | [`pointwise_curvature`] | [`PointwiseCurvature`]: pointwise `K = k1 k2` and `H = (k1 + k2) / 2` from the tensor (accurate on irregular meshes), the discrete values (angle defect, cotangent formula) and their integrals, with a [`CurvatureFlag`] wherever a value is not an estimate (zero-area faces, ill-conditioned fits, curvature past the sampling's resolution) | eq. 2.19-2.20, 2.25-2.26 |
//! | [`integral_curvature`] | Gaussian and mean curvature integrated over a k-ring or ball | 2.5 |
//! | [`shape_index`], [`curvedness`] | Koenderink's shape descriptors from `k1`, `k2` | |
//!
//! Every function takes any [`TriMesh`] (non-manifold, degenerate,
//! disconnected) and returns finite values with a per-vertex
//! [`VertexStatus`] saying which are estimates; nothing panics or returns
//! NaN. Curvatures are positive where the surface bends away from its normal:
//! a sphere of radius `r` with outward normals has `k1 = k2 = H = 1 / r` and
//! `K = 1 / r^2`. The `rayon` feature (default) parallelizes every estimator.
//!
//! ```
//! use mesh_curvature::{curvature_tensor, gaussian_curvature, mean_curvature, TensorOptions};
//! use mesh_kernel::shapes;
//!
//! let sphere = shapes::icosphere(4)?;
//! let k = gaussian_curvature(&sphere, &Default::default())?;
//! assert!((k.total() - 4.0 * std::f64::consts::PI).abs() < 1e-10); // Gauss-Bonnet, chi = 2
//! let h = mean_curvature(&sphere, &Default::default())?;
//! assert!(h.pointwise.iter().all(|h| (h - 1.0).abs() < 1e-2));
//!
//! let t = curvature_tensor(&sphere, &TensorOptions::default())?;
//! assert!(t.k1.iter().chain(&t.k2).all(|k| (k - 1.0).abs() < 1e-3));
//! # Ok::<(), mesh_curvature::CurvatureError>(())
//! ```
#![deny(missing_docs)]

pub mod error;
pub mod fit;
mod frame;
pub mod gaussian;
pub mod integral;
pub mod mean;
pub mod neighborhood;
mod normal_cycle;
pub mod pointwise;
mod rusinkiewicz;
pub mod status;
pub mod tensor;

pub use error::CurvatureError;
pub use fit::{Degree, FitOptions};
pub use gaussian::{gaussian_curvature, GaussianCurvature, GaussianOptions};
pub use integral::{integral_curvature, IntegralCurvature, IntegralOptions};
pub use mean::{mean_curvature, mean_curvature_with_normals, MeanCurvature, MeanOptions};
/// The choices of vertex area and vertex normal, shared with every crate of the workspace.
pub use mesh_kernel::{geometry::NormalWeighting, operators::MassKind};
pub use neighborhood::Neighborhood;
pub use pointwise::{
    flag_code, pointwise_curvature, sampling_length, CurvatureFlag, FlagCounts, PointwiseCurvature, PointwiseOptions,
    NOISE_CURVEDNESS, PLANAR_CURVEDNESS,
};
pub use status::{StatusCounts, VertexStatus};
pub use tensor::{curvature_tensor, curvedness, shape_index, CurvatureTensor, TensorMethod, TensorOptions};

/// The data model this crate works on, so that one dependency line is enough.
pub use mesh_kernel;
pub use mesh_kernel::TriMesh;

/// The code blocks of README.md, run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
