//! Small shared pieces: input validation, the breadth-first vertex order
//! and the min-heap entry of the exact algorithm's vertex queue.

use std::cmp::Ordering;

use mesh_kernel::{Connectivity, TriMesh, VertexId, VertexKind};

use crate::error::{GeodesicError, Result};

/// Checks that `sources` is non-empty and every source is a vertex of `mesh`.
pub(crate) fn validate_sources(mesh: &TriMesh, sources: &[VertexId]) -> Result<()> {
    validate_source_indices(mesh.vertex_count(), sources)
}

/// Checks that `sources` is non-empty and every source is below `n`.
pub(crate) fn validate_source_indices(n: usize, sources: &[VertexId]) -> Result<()> {
    if sources.is_empty() {
        return Err(GeodesicError::NoSources);
    }
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

/// Vertices in breadth-first order over the edges, one component after
/// the other (isolated vertices last, in index order), and the inverse
/// permutation. O(V + E).
pub(crate) fn breadth_first_order(mesh: &TriMesh) -> (Vec<u32>, Vec<u32>) {
    let conn = mesh.connectivity();
    let n = mesh.vertex_count();
    let mut rank = vec![u32::MAX; n];
    let mut order = Vec::with_capacity(n);
    for root in 0..n {
        if rank[root] != u32::MAX {
            continue;
        }
        rank[root] = order.len() as u32;
        order.push(root as u32);
        let mut head = order.len() - 1;
        while head < order.len() {
            let v = VertexId(order[head]);
            head += 1;
            for_each_neighbor(conn, v, |w| {
                if rank[w.idx()] == u32::MAX {
                    rank[w.idx()] = order.len() as u32;
                    order.push(w.0);
                }
            });
        }
    }
    (order, rank)
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
