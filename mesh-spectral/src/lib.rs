//! Spectral geometry processing on triangle meshes ("Digital Shape
//! Processing" thesis chapter, sec. 2.7): the
//! smallest eigenpairs of the Laplace-Beltrami operator, the manifold
//! harmonic transform built on them, spectral filtering and compression of
//! geometry, and the heat kernel signature.
//!
//! | module | what it holds | reference |
//! |---|---|---|
//! | [`eigen`] | [`eigenpairs`]: the k smallest pairs of `L x = lambda M x` by block Krylov-Schur shift-invert (dense for small pieces), one exact zero per component, M-orthonormal, every residual within the tolerance or [`SpectralError::NotConverged`] | Stewart 2001; chapter sec. 2.7 |
//! | [`operators`] | the pair `(L, M)` of a mesh: cotangent or intrinsic Delaunay Laplacian, mixed Voronoi or barycentric lumped mass | eq. 2.15; Meyer et al. 2003 |
//! | [`harmonics`] | [`ManifoldHarmonics`]: basis, forward `Phi^T M f` and inverse transforms of fields and geometry | Vallet and Levy 2008 |
//! | [`filter`](mod@filter) | [`filter()`]: transfer functions over frequencies (low-pass, band exaggeration) | Vallet and Levy 2008 |
//! | [`compress`](mod@compress) | [`compress()`], [`compression_curve`]: keep k coefficients, error vs k | Karni and Gotsman 2000 |
//! | [`hks`] | [`heat_kernel_signature`], [`heat_trace`] (its area-weighted sum, a global descriptor) | Sun, Ovsjanikov and Guibas 2009 |
//!
//! ```
//! use mesh_kernel::{operators, shapes};
//! use mesh_spectral::{eigenpairs, EigenOptions};
//!
//! // Unit sphere: eigenvalues l (l + 1), each repeated 2 l + 1 times.
//! let mesh = shapes::icosphere(3)?;
//! let l = operators::cotan_laplacian(&mesh);
//! let mass = operators::lumped_mass(&mesh, operators::MassKind::MixedVoronoi);
//! let pairs = eigenpairs(&l, &mass, 9, &EigenOptions::default())?;
//! assert!(pairs.values[0].abs() < 1e-9);
//! assert!(pairs.values[1..4].iter().all(|v| (v - 2.0).abs() < 0.02));
//! assert!(pairs.values[4..9].iter().all(|v| (v - 6.0).abs() < 0.1));
//! assert!(pairs.residuals.iter().all(|r| *r < 1e-8));
//! # Ok::<(), mesh_spectral::SpectralError>(())
//! ```
//!
//! Conventions: `L` is positive semi-definite (`-igl::cotmatrix`), `M`
//! diagonal; eigenvalues ascend; eigenvectors are M-orthonormal
//! (`x_i^T M x_j = delta_ij`); frequencies are `sqrt(lambda)`. Nothing a
//! user can feed in panics: invalid input is a [`SpectralError`].
#![deny(missing_docs)]

pub mod compress;
pub mod eigen;
pub mod error;
pub mod filter;
pub mod harmonics;
pub mod hks;
pub mod operators;

pub use compress::{compress, compression_curve, SpectralCompressionPoint};
pub use eigen::{eigenpairs, ComponentSelection, EigenOptions, EigenSolver, EigenStats, Eigenpairs};
pub use error::SpectralError;
pub use filter::{filter, filter_mesh, filter_with, Transfer};
pub use harmonics::{HarmonicsOptions, ManifoldHarmonics};
pub use hks::{heat_kernel_signature, heat_trace, hks_times};
/// The choices of Laplacian and mass, shared with every crate of the workspace.
pub use mesh_kernel::operators::{LaplacianKind, MassKind};
pub use mesh_kernel::solver::FillOrdering;
pub use operators::{laplace_beltrami, pencil, OperatorInfo, Pencil};

/// The data model this crate works on, so that one dependency line is enough.
pub use mesh_kernel;
