//! The error type of the crate.

use mesh_kernel::MeshError;
use thiserror::Error;

/// Everything that can go wrong in `mesh-nurbs`: invalid knot vectors, control
/// nets, parameters, options and JSON documents. No function of the crate
/// panics on user input; it returns one of these instead.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum NurbsError {
    /// A knot is NaN or infinite.
    #[error("knot {index} is not finite ({value})")]
    NonFiniteKnot {
        /// Position in the knot vector.
        index: usize,
        /// The value found.
        value: f64,
    },
    /// Knots must be non-decreasing (`t_i <= t_{i+1}`, eq. 2.1).
    #[error("knot {index} ({value}) is smaller than the knot before it ({previous})")]
    DecreasingKnots {
        /// Position of the offending knot.
        index: usize,
        /// Its value.
        value: f64,
        /// The value of the knot before it.
        previous: f64,
    },
    /// A knot appears more than `degree + 1` times.
    #[error("knot {value} appears {multiplicity} times, more than degree + 1 = {max}")]
    KnotMultiplicity {
        /// The repeated value.
        value: f64,
        /// How many times it appears.
        multiplicity: usize,
        /// The largest multiplicity allowed.
        max: usize,
    },
    /// The knot count does not match `control points + degree + 1`, or is too small.
    #[error("{knots} knots for degree {degree} and {control_points} control points (need control points + degree + 1 knots and at least degree + 1 control points)")]
    KnotCount {
        /// Number of knots given.
        knots: usize,
        /// Degree of the basis.
        degree: usize,
        /// Number of control points the knots are meant for.
        control_points: usize,
    },
    /// The degree is 0 or beyond [`crate::basis::MAX_DEGREE`].
    #[error("degree {degree} is outside 1..={max}")]
    Degree {
        /// Degree requested.
        degree: usize,
        /// Largest supported degree.
        max: usize,
    },
    /// The parameter domain `[t_p, t_{n+1}]` has zero length.
    #[error("the parameter domain [{start}, {end}] is empty")]
    EmptyDomain {
        /// First knot of the domain.
        start: f64,
        /// Last knot of the domain.
        end: f64,
    },
    /// The number of control points (or weights) is not what the knots ask for.
    #[error("{what}: expected {expected}, found {found}")]
    Count {
        /// What was counted.
        what: &'static str,
        /// The number needed.
        expected: usize,
        /// The number given.
        found: usize,
    },
    /// A control point has a NaN or infinite coordinate.
    #[error("control point {index} is not finite")]
    NonFiniteControlPoint {
        /// Position in the control net (row-major, `i * count_v + j` for surfaces).
        index: usize,
    },
    /// Weights must be finite and strictly positive.
    #[error("weight {index} is {value}; weights must be finite and > 0")]
    Weight {
        /// Position in the control net.
        index: usize,
        /// The value found.
        value: f64,
    },
    /// An evaluation parameter is NaN or infinite.
    #[error("parameter {name} = {value} is not finite")]
    NonFiniteParameter {
        /// `"u"` or `"v"`.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// Knot insertion outside the open domain or beyond full multiplicity.
    #[error("cannot insert knot {value} {times} time(s): {reason}")]
    KnotInsertion {
        /// The knot to insert.
        value: f64,
        /// How many times it was to be inserted.
        times: usize,
        /// Why it was refused.
        reason: String,
    },
    /// The operation needs clamped knots (first and last knots of multiplicity
    /// `degree + 1`).
    #[error("{operation} needs clamped knots (end knots repeated degree + 1 times)")]
    NotClamped {
        /// What was attempted.
        operation: &'static str,
    },
    /// A shape constructor got a non-finite or out-of-range dimension.
    #[error("invalid shape: {0}")]
    Shape(String),
    /// An option is out of its valid range (tessellation resolution, tolerance, ...).
    #[error("invalid option `{name}`: {reason}")]
    InvalidOption {
        /// Name of the option.
        name: &'static str,
        /// Why it was refused.
        reason: String,
    },
    /// The adaptive tessellation would need more segments than allowed.
    #[error("chordal tolerance {tolerance:e} needs more than {max_segments} segments along {direction}")]
    ToleranceUnreachable {
        /// The tolerance asked for.
        tolerance: f64,
        /// The limit that was hit.
        max_segments: usize,
        /// `"u"` or `"v"`.
        direction: &'static str,
    },
    /// A JSON document is malformed, or well-formed but describes no valid surface.
    #[error("JSON: {0}")]
    Json(String),
    /// Building the output mesh failed.
    #[error(transparent)]
    Mesh(#[from] MeshError),
}

impl From<serde_json::Error> for NurbsError {
    fn from(e: serde_json::Error) -> Self {
        NurbsError::Json(e.to_string())
    }
}

/// Shorthand for results in this crate.
pub type Result<T, E = NurbsError> = std::result::Result<T, E>;

/// Checks that a parameter is finite (the evaluators clamp finite values into
/// the domain but refuse NaN and infinities).
pub(crate) fn check_param(name: &'static str, value: f64) -> Result<()> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(NurbsError::NonFiniteParameter { name, value })
    }
}
