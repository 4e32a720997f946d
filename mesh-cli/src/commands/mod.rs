//! One module per subcommand, each with `Args` and `run`.

pub mod clean;
pub mod convert;
pub mod curvature;
pub mod generate;
pub mod geodesic;
pub mod info;
pub mod nurbs;
pub mod param;
pub mod render;
pub mod report;
pub mod spectral;
pub mod wavelet;
