//! Spectral geometry processing on triangle meshes (work in progress).
#![deny(missing_docs)]

pub mod eigen;
pub mod error;

pub use eigen::{eigenpairs, Eigenpairs, Method, Options, Stats};
pub use error::{Result, SpectralError};
