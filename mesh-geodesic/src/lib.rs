//! Geodesic distances on triangle meshes (work in progress).
#![deny(missing_docs)]
// `!(x > 0.0)` is the NaN-rejecting test used throughout on purpose.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod dijkstra;
pub mod error;
pub mod fmm;
pub mod heat;
pub mod sampling;
mod support;
pub mod trace;

pub use dijkstra::{dijkstra, DijkstraOptions, ShortestPaths};
pub use error::{GeodesicError, Result};
pub use fmm::{fmm_distance, FastMarching, FmmOptions, FmmStats, FmmUpdate};
pub use heat::{heat_distance, HeatBoundary, HeatGeodesics, HeatLaplacian, HeatOptions};
pub use sampling::{farthest_point_sampling, geodesic_voronoi, GeodesicVoronoi, SamplingMetric, SamplingOptions};
pub use trace::{trace_path, GeodesicPath, SurfacePoint, TraceOptions};
