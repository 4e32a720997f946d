//! Small shared pieces: input validation and the min-heap entry used by the
//! front-propagation algorithms.

use std::cmp::Ordering;

use mesh_kernel::{Connectivity, TriMesh, VertexId, VertexKind};

use crate::error::{GeodesicError, Result};

/// Checks that `sources` is non-empty and every source is a vertex of `mesh`.
pub(crate) fn validate_sources(mesh: &TriMesh, sources: &[VertexId]) -> Result<()> {
    if sources.is_empty() {
        return Err(GeodesicError::NoSources);
    }
    let n = mesh.vertex_count();
    match sources.iter().find(|s| s.idx() >= n) {
        Some(&vertex) => Err(GeodesicError::SourceOutOfRange { vertex, vertex_count: n }),
        None => Ok(()),
    }
}

/// Checks that a per-vertex field has one value per vertex.
pub(crate) fn validate_length(name: &'static str, expected: usize, found: usize) -> Result<()> {
    if expected == found {
        Ok(())
    } else {
        Err(GeodesicError::FieldLength { name, expected, found })
    }
}

/// Calls `f` on every neighbour of `v` (on boundary and non-manifold vertices
/// some neighbours twice), without allocating: the destination of every
/// outgoing half-edge, plus, where the ring is open, the vertex before it.
#[inline]
pub(crate) fn for_each_neighbor(conn: &Connectivity, v: VertexId, mut f: impl FnMut(VertexId)) {
    let closed = conn.vertex_kind(v) == VertexKind::Interior;
    for &h in conn.outgoing(v) {
        f(conn.dest(h));
        if !closed {
            f(conn.opposite_vertex(h));
        }
    }
}

/// An entry of a binary min-heap keyed by distance (lazy deletion: stale
/// entries are skipped when popped).
#[derive(Debug, Clone, Copy)]
pub(crate) struct HeapEntry {
    pub distance: f64,
    pub vertex: u32,
}

impl PartialEq for HeapEntry {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for HeapEntry {}

impl PartialOrd for HeapEntry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for HeapEntry {
    /// Reversed, so that `std::collections::BinaryHeap` pops the smallest.
    fn cmp(&self, other: &Self) -> Ordering {
        other.distance.total_cmp(&self.distance).then_with(|| other.vertex.cmp(&self.vertex))
    }
}
