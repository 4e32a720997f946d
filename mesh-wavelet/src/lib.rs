//! Subdivision and wavelets on triangle meshes: 4-to-1 refinement (midpoint,
//! Loop, modified butterfly), detection of subdivision connectivity, the
//! multiresolution analysis of Lounsbery, DeRose and Warren (section 2.8,
//! eq. 2.36-2.39 of the "Digital Shape Processing" thesis chapter) with lazy and lifted wavelets as fast in-place lifting
//! steps (and as sparse matrices), level of detail, multiresolution editing
//! and compression.
//!
//! | module | what it holds | chapter |
//! |---|---|---|
//! | [`subdivide`](mod@subdivide) | [`subdivide()`]: midpoint, Loop (1987), modified butterfly (Zorin et al. 1996) | fig. 2.13 |
//! | [`hierarchy`] | [`Hierarchy`]: K^0 ⊂ ... ⊂ K^J with hierarchical numbering and parent edges | 2.8 |
//! | [`detect`](mod@detect) | [`detect()`]: reverse 4-to-1 splitting (after Taubin 2002), base mesh and level count | |
//! | [`rules`] | the subdivision masks | |
//! | [`filter`] | [`FilterBank`]: analysis A, B and synthesis P, Q as lifting steps | eq. 2.38-2.39, fig. 2.12 |
//! | [`matrices`] | the same as `sprs` matrices; the Gram matrix of eq. 2.36 | eq. 2.36 |
//! | [`multires`] | [`Multiresolution`]: base + coefficients, LOD, editing, statistics | eq. 2.39 |
//! | [`compress`](mod@compress) | keep the largest coefficients, RMS / max error | |
//! | [`scheme`] | [`Scheme`] (midpoint, Loop, butterfly) and [`WaveletKind`] (lazy, lifted) | |
//! | [`error`] | [`WaveletError`] | |
//!
//! Private: `topology`, a lean half-edge structure numbered like
//! `mesh_kernel::Connectivity` (faster to build; see the README), and `update`,
//! the least-squares weights of the lifted wavelet.
//!
//! ```
//! use mesh_wavelet::{subdivide, CompressOptions, Multiresolution, MultiresOptions, Scheme, SubdivideOptions};
//! use mesh_kernel::shapes;
//!
//! // A semi-regular mesh: the icosahedron split 3 times, new vertices on the sphere.
//! let sphere = shapes::icosphere(3)?;
//! let mr = Multiresolution::analyze(&sphere, &MultiresOptions::default())?; // detects K^0..K^3
//! assert_eq!((mr.levels(), mr.level(0)?.vertex_count()), (3, 12));
//!
//! // Analysis then synthesis returns the input.
//! let back = mr.synthesize()?;
//! let err = back.positions().iter().zip(sphere.positions()).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
//! assert!(err < 1e-12);
//!
//! // Keep 20% of the coefficients.
//! let c = mr.compress(&CompressOptions { keep_fraction: 0.2 })?;
//! assert!(c.rms_error < 1e-2);
//!
//! // Loop subdivision of the icosahedron.
//! let smooth = subdivide(&shapes::icosphere(0)?, &SubdivideOptions { scheme: Scheme::Loop, levels: 2 })?;
//! assert_eq!(smooth.vertex_count(), 162);
//! # Ok::<(), mesh_wavelet::WaveletError>(())
//! ```
//!
//! Everything a user can feed in gives a [`WaveletError`] or a result:
//! empty, non-manifold or non-semi-regular meshes, bad levels and options.
#![deny(missing_docs)]

pub mod compress;
pub mod detect;
pub mod error;
pub mod filter;
pub mod hierarchy;
pub mod matrices;
pub mod multires;
pub mod rules;
pub mod scheme;
pub mod subdivide;
mod topology;
mod update;

pub use compress::{CompressOptions, WaveletCompression, WaveletCompressionPoint};
pub use detect::{detect, DetectOptions};
pub use error::WaveletError;
pub use filter::{Coefficient, FilterBank, LevelFilter};
pub use hierarchy::Hierarchy;
pub use matrices::{inner_product_matrix, FilterMatrices};
pub use multires::{decay_rate, LevelStatistics, MultiresOptions, Multiresolution};
pub use scheme::{Scheme, WaveletKind};
pub use subdivide::{subdivide, SubdivideOptions};

pub use glam;
/// The data model this crate works on, so that one dependency line is enough.
pub use mesh_kernel;

/// The README's example, compiled and run as a doc-test.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
