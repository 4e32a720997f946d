//! The error type shared by the whole workspace.

use crate::ids::{EdgeId, FaceId, VertexId};
use thiserror::Error;

/// Everything that can go wrong in `mesh-kernel`. Algorithm crates wrap it in their
/// own error enums.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum MeshError {
    /// A face refers to a vertex that does not exist.
    #[error("face {face} refers to vertex {vertex}, but the mesh has only {vertex_count} vertices")]
    IndexOutOfRange {
        /// The offending face.
        face: FaceId,
        /// The index it holds.
        vertex: u32,
        /// Number of vertices of the mesh.
        vertex_count: usize,
    },
    /// A vertex has a NaN or infinite coordinate.
    #[error("vertex {vertex} has a non-finite coordinate ({x}, {y}, {z})")]
    NonFinitePosition {
        /// The offending vertex.
        vertex: VertexId,
        /// Its x coordinate.
        x: f64,
        /// Its y coordinate.
        y: f64,
        /// Its z coordinate.
        z: f64,
    },
    /// A face uses the same vertex twice.
    #[error("face {face} uses vertex {vertex} more than once")]
    RepeatedVertex {
        /// The offending face.
        face: FaceId,
        /// The repeated vertex.
        vertex: VertexId,
    },
    /// More elements than 32-bit indices can address.
    #[error("{what} count {count} exceeds the 32-bit index range")]
    TooLarge {
        /// Which kind of element.
        what: &'static str,
        /// How many were given.
        count: usize,
    },
    /// The operation needs at least one face.
    #[error("the mesh has no faces")]
    Empty,
    /// The operation needs an oriented 2-manifold (with or without boundary).
    #[error("the mesh is not an oriented manifold: {0}")]
    NonManifold(Box<NonManifoldReport>),
    /// The operation needs a different topology (for example a disk).
    #[error("wrong topology: expected {expected}, found {found}")]
    Topology {
        /// What the operation needs.
        expected: String,
        /// What the mesh is.
        found: String,
    },
    /// An option or argument is out of its valid range.
    #[error("invalid option `{name}`: {reason}")]
    InvalidOption {
        /// Name of the option.
        name: &'static str,
        /// Why it was refused.
        reason: String,
    },
    /// Geometry too degenerate for the operation (zero area, collinear, ...).
    #[error("degenerate geometry: {0}")]
    Degenerate(String),
    /// A sparse factorization or solve failed.
    #[error("solver failed: {0}")]
    Solver(String),
    /// Matrix or vector sizes disagree.
    #[error("dimension mismatch: {0}")]
    Dimension(String),
}

/// Where a mesh fails to be an oriented 2-manifold. Each list is complete and
/// sorted; [`NonManifoldReport::is_empty`] means the mesh is manifold.
/// `Debug` and `Display` show the first few entries of each list and its
/// length (a scan can have thousands); the fields hold them all.
#[derive(Clone, Default, PartialEq, Eq)]
pub struct NonManifoldReport {
    /// Edges shared by more than two faces.
    pub edges: Vec<EdgeId>,
    /// Vertices whose incident faces form more than one fan (bow-ties, pinched
    /// sheets), excluding the endpoints of non-manifold edges.
    pub vertices: Vec<VertexId>,
    /// Edges shared by exactly two faces that traverse it in the same direction
    /// (neighbours with inconsistent orientation).
    pub inconsistent_edges: Vec<EdgeId>,
}

impl NonManifoldReport {
    /// `true` when there is nothing to report.
    pub fn is_empty(&self) -> bool {
        self.edges.is_empty() && self.vertices.is_empty() && self.inconsistent_edges.is_empty()
    }
}

/// The first entries of `items` and, when some are left out, their count. O(1).
fn abridged<T: std::fmt::Debug>(items: &[T]) -> String {
    const SHOWN: usize = 8;
    let mut s: Vec<String> = items.iter().take(SHOWN).map(|i| format!("{i:?}")).collect();
    if items.len() > SHOWN {
        s.push(format!("... ({} in all)", items.len()));
    }
    s.join(", ")
}

impl std::fmt::Debug for NonManifoldReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "NonManifoldReport {{ edges: [{}], vertices: [{}], inconsistent_edges: [{}] }}",
            abridged(&self.edges),
            abridged(&self.vertices),
            abridged(&self.inconsistent_edges)
        )
    }
}

impl std::fmt::Display for NonManifoldReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut parts = Vec::new();
        if !self.edges.is_empty() {
            parts.push(format!("{} edges with more than two faces [{}]", self.edges.len(), abridged(&self.edges)));
        }
        if !self.vertices.is_empty() {
            parts.push(format!(
                "{} vertices with more than one fan [{}]",
                self.vertices.len(),
                abridged(&self.vertices)
            ));
        }
        if !self.inconsistent_edges.is_empty() {
            parts.push(format!(
                "{} edges between inconsistently oriented faces [{}]",
                self.inconsistent_edges.len(),
                abridged(&self.inconsistent_edges)
            ));
        }
        if parts.is_empty() {
            f.write_str("no defect")
        } else {
            f.write_str(&parts.join("; "))
        }
    }
}

/// Shorthand for results in this crate.
pub type Result<T, E = MeshError> = std::result::Result<T, E>;

#[cfg(test)]
mod report_tests {
    use super::*;

    #[test]
    fn long_reports_are_abridged_in_debug_and_display() {
        let report = NonManifoldReport { edges: (0..1000).map(EdgeId::new).collect(), ..Default::default() };
        for text in [format!("{report:?}"), report.to_string()] {
            assert!(text.contains("e0, e1") && text.contains("(1000 in all)") && text.len() < 200, "{text}");
        }
        assert_eq!(
            format!("{:?}", NonManifoldReport::default()),
            "NonManifoldReport { edges: [], vertices: [], inconsistent_edges: [] }"
        );
    }
}
