//! The error type of the crate.

use mesh_kernel::MeshError;
use thiserror::Error;

/// Everything that can go wrong while triangulating, flipping or refining.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum DelaunayError {
    /// An error of the underlying mesh library.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// Fewer than three distinct points: no triangle can be made.
    #[error("a triangulation needs at least 3 distinct points, found {distinct}")]
    TooFewPoints {
        /// How many distinct points there are.
        distinct: usize,
    },
    /// Every point lies on one line: the triangulation has no triangle.
    #[error("all {distinct} distinct points are collinear: the triangulation has no triangle")]
    Collinear {
        /// How many distinct points there are.
        distinct: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("point {index} has a non-finite coordinate")]
    NonFinite {
        /// The first such point.
        index: usize,
    },
    /// A coordinate is outside the range of spade's exact predicates
    /// (`spade::MIN_ALLOWED_VALUE` to `spade::MAX_ALLOWED_VALUE`) even after
    /// the points are divided by a power of two near their largest
    /// coordinate: a non-zero coordinate smaller than 2^-142 times the
    /// largest one.
    #[error("point {index} has a coordinate outside the range of the exact predicates ({reason})")]
    OutOfRange {
        /// The first such point.
        index: usize,
        /// Why spade refused it.
        reason: String,
    },
    /// A triangulation handed in is not a valid triangulation of its points.
    #[error("invalid triangulation: {reason}")]
    InvalidTriangulation {
        /// What is wrong with it.
        reason: String,
    },
    /// The Lawson flips did not finish within their bound.
    #[error("Lawson flips stopped after {flips} flips (the bound) with non-Delaunay edges left")]
    FlipLimit {
        /// Flips done before stopping.
        flips: usize,
    },
    /// A loop of a polygon is degenerate: fewer than three distinct
    /// vertices, two consecutive equal vertices, zero area, or a vertex shared
    /// with another loop.
    #[error("polygon loop {loop_index} is degenerate: {reason}")]
    DegenerateLoop {
        /// The loop (0 is the outer loop, then the holes in order).
        loop_index: usize,
        /// What is degenerate.
        reason: String,
    },
    /// An edge of a polygon loop crosses or touches another edge, or passes
    /// through a vertex.
    #[error("polygon loop {loop_index}: edge {edge} crosses or touches another edge of the polygon")]
    SelfIntersecting {
        /// The loop (0 is the outer loop, then the holes in order).
        loop_index: usize,
        /// The edge, from vertex `edge` to vertex `edge + 1` of the loop.
        edge: usize,
    },
    /// A hole is not inside the outer loop, or lies inside another hole.
    #[error("hole {hole} is {reason}")]
    MisplacedHole {
        /// The hole (0 is the first hole).
        hole: usize,
        /// Where it is.
        reason: String,
    },
    /// An option is out of range.
    #[error("invalid option `{name}`: {reason}")]
    InvalidOption {
        /// Name of the option.
        name: &'static str,
        /// Why it was refused.
        reason: String,
    },
    /// The underlying triangulation library failed on this input (a guard:
    /// it is not expected to happen).
    #[error("the triangulation library failed: {reason}")]
    Backend {
        /// What failed.
        reason: String,
    },
}

/// Shorthand for results of this crate.
pub type Result<T, E = DelaunayError> = std::result::Result<T, E>;
