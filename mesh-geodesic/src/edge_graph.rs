//! The weighted edge graph of a mesh in compressed sparse rows: for every
//! vertex, its neighbours and the Euclidean lengths of the edges to them,
//! side by side in one flat array, so that a graph search reads one
//! contiguous run per settled vertex (two or three cache lines) instead of
//! walking half-edges and positions. Interleaving the neighbours with the
//! lengths, rather than two arrays, took 12-15% off Dijkstra's search at
//! 470,274 vertices.
//!
//! Measured against building no graph (2026-12-06, one core, 470,274
//! vertices in file order): a search that walked each settled vertex's
//! half-edges, their ends and the ends' positions took 95-97 ms, against
//! 21-23 ms for this graph (zeroed before it was written, as it then was)
//! and 35-37 ms for the search on it. Keeping in
//! each edge where its neighbour's ring starts (16 bytes an edge, so that
//! a search asks for that ring without reading the offsets first) left
//! prepared queries level and made a one-off `dijkstra` 10% slower, the
//! larger graph costing more to build than the offsets' reads it saves.

use mesh_kernel::glam::DVec3;
use mesh_kernel::rows::RowFill;
use mesh_kernel::{TriMesh, VertexId};

/// How many edges ahead of the one being written [`EdgeGraph::new`] asks
/// for the ring slots it will write (and twice as far, for the ends'
/// positions and ring cursors).
const AHEAD: usize = mesh_kernel::par::READ_AHEAD;

/// One directed edge of a ring: 12 bytes, so that six of them (a typical
/// ring) span 72 bytes.
#[derive(Debug, Clone, Copy)]
#[repr(C, packed(4))]
pub(crate) struct Edge {
    /// The neighbour, in the graph's internal numbering.
    pub(crate) to: u32,
    /// The edge's Euclidean length.
    pub(crate) length: f64,
}

/// Neighbours and edge lengths of every vertex, in compressed sparse rows,
/// over an internal vertex numbering (the mesh's own, or a renumbering for
/// locality). 12 bytes per directed edge plus 4 per vertex.
#[derive(Debug, Clone)]
pub(crate) struct EdgeGraph {
    /// `offsets[i]..offsets[i + 1]` is the range of internal vertex `i`'s ring.
    offsets: Vec<u32>,
    edges: Vec<Edge>,
    /// The shortest edge length (`+infinity` without edges).
    shortest: f64,
    /// The longest edge length (0 without edges).
    longest: f64,
}

impl EdgeGraph {
    /// The edge graph of `mesh` in the mesh's vertex numbering, or, with
    /// `numbering = Some((order, rank))`, with internal vertex `i` being mesh
    /// vertex `order[i]` and `rank` the inverse permutation: every vertex's
    /// ring lists each of its neighbours once, whatever the fan (closed,
    /// open, non-manifold or inconsistently oriented). In the mesh's
    /// numbering a ring is sorted by neighbour. Lengths `|p_w - p_v|` go
    /// through the overflow-safe [`mesh_kernel::geometry::norm`] when
    /// `robust` (from [`crate::dijkstra::robust_lengths`]). O(V + E).
    ///
    /// One pass over the connectivity's edges, which are sorted by their
    /// smaller end: each edge is measured once and written into the rings
    /// of both ends, so that in the mesh's numbering the smaller ends'
    /// rings fill in memory order and only the larger ends' writes
    /// scatter. The slots written [`AHEAD`] edges on are asked for ahead,
    /// as are the positions and ring cursors `2 AHEAD` edges on. The rings'
    /// lengths are the valences ([`mesh_kernel::Connectivity::valence`]),
    /// and the rings are written into memory that was not zeroed first
    /// ([`RowFill`]).
    ///
    /// Measured against a pass over the faces (each side measured and
    /// written into its start's ring, then the vertex before each outgoing
    /// half-edge added on open and non-manifold fans), 2026-12-08, one
    /// core, 470,274 vertices in file order: the graph in 18.4-19.6 ms
    /// against 28.3-31.3 with the rings' lengths counted over the edges
    /// (3.1-4.7 ms of it; 2.1-2.8 ms from the valences), and in a
    /// breadth-first numbering in 37 ms against 49-54. A one-off
    /// `dijkstra`, graph and search, in 53.2-54.9 ms against 64.5-73.8
    /// (three alternated rounds), where scipy's takes 121-125.
    pub(crate) fn new(mesh: &TriMesh, robust: bool, numbering: Option<(&[u32], &[u32])>) -> Self {
        let conn = mesh.connectivity();
        let valence = |v: u32| conn.valence(VertexId(v)) as u32;
        match numbering {
            None => Self::build(mesh, robust, (0..mesh.vertex_count() as u32).map(valence), |v| v),
            Some((order, rank)) => Self::build(mesh, robust, order.iter().map(|&v| valence(v)), |v| rank[v as usize]),
        }
    }

    /// [`EdgeGraph::new`] with mesh vertex `v` numbered `internal(v)` and
    /// the rings' lengths in the internal numbering.
    fn build(
        mesh: &TriMesh,
        robust: bool,
        lengths: impl ExactSizeIterator<Item = u32>,
        internal: impl Fn(u32) -> u32,
    ) -> Self {
        let edges = mesh.connectivity().edges();
        let mut rings = RowFill::with_lengths(lengths);
        let p = mesh.positions();
        let length = |a: DVec3, b: DVec3| if robust { mesh_kernel::geometry::norm(b - a) } else { (b - a).length() };
        let (mut shortest, mut longest) = (f64::INFINITY, 0f64);
        for (e, &[a, b]) in edges.iter().enumerate() {
            if let Some(&ahead) = edges.get(e + 2 * AHEAD) {
                for v in ahead {
                    rings.prefetch_cursor(internal(v.0) as usize);
                    mesh_kernel::hint::prefetch(p.as_ptr().wrapping_add(v.idx()));
                }
            }
            if let Some(&ahead) = edges.get(e + AHEAD) {
                for v in ahead {
                    rings.prefetch_slot(internal(v.0) as usize);
                }
            }
            let s = length(p[a.idx()], p[b.idx()]);
            longest = longest.max(s);
            shortest = shortest.min(s);
            let (a, b) = (internal(a.0), internal(b.0));
            rings.push(a as usize, Edge { to: b, length: s });
            rings.push(b as usize, Edge { to: a, length: s });
        }
        let (offsets, edges) = rings.finish();
        Self { offsets, edges, shortest, longest }
    }

    /// The shortest and the longest edge length (`+infinity` and 0 without
    /// edges). O(1).
    pub(crate) fn length_range(&self) -> (f64, f64) {
        (self.shortest, self.longest)
    }

    /// The edges from internal vertex `i` to its neighbours. O(1).
    #[inline]
    pub(crate) fn ring(&self, i: usize) -> &[Edge] {
        &self.edges[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }

    /// Asks the processor to bring where `i`'s ring starts into cache. A
    /// hint only.
    #[inline]
    pub(crate) fn prefetch_offset(&self, i: usize) {
        mesh_kernel::hint::prefetch(self.offsets.as_ptr().wrapping_add(i));
    }

    /// Asks the processor to bring `i`'s ring into cache (the lines of its
    /// first and sixth edges: a ring of six spans two or three), so that it
    /// is there when `i` is settled. A hint only.
    #[inline]
    pub(crate) fn prefetch_ring(&self, i: usize) {
        let start = self.offsets[i] as usize;
        mesh_kernel::hint::prefetch(self.edges[start..].as_ptr());
        mesh_kernel::hint::prefetch(self.edges[(start + 5).min(self.offsets[i + 1] as usize)..].as_ptr());
    }
}

#[cfg(test)]
mod tests {
    use super::EdgeGraph;
    use mesh_kernel::{shapes, TriMesh, VertexId};

    /// Every ring lists each neighbour once (the other corners of the
    /// vertex's faces), with lengths to the bit, on a mesh with boundary, a
    /// flipped face, a fin on an edge of two faces, a separate triangle and
    /// an isolated vertex, in the mesh's numbering (rings sorted) and in a
    /// shuffled one, with plain and overflow-safe lengths.
    #[test]
    fn rings_list_every_neighbour_once() {
        let sphere = shapes::icosphere(2).unwrap();
        let mut positions = sphere.positions().to_vec();
        let mut faces: Vec<[u32; 3]> = sphere.faces()[..sphere.faces().len() - 7].to_vec();
        faces[3] = [faces[3][0], faces[3][2], faces[3][1]];
        let n = positions.len() as u32;
        let [a, b, _] = faces[10];
        positions.extend([
            positions[0] * 1.5,
            positions[1] * 0.5,
            positions[2] * 0.5,
            positions[3] * 0.5,
            positions[4] * 2.0,
        ]);
        faces.extend([[b, a, n], [n + 1, n + 2, n + 3]]);
        // The same mesh 2^700 times larger, where squared lengths overflow.
        let huge: Vec<_> = positions.iter().map(|&p| p * 2f64.powi(700)).collect();
        let huge = TriMesh::new(huge, faces.clone()).unwrap();
        let mesh = TriMesh::new(positions, faces.clone()).unwrap();
        let count = mesh.vertex_count();
        let mut neighbours = vec![std::collections::BTreeSet::new(); count];
        for face in &faces {
            for k in 0..3 {
                neighbours[face[k] as usize].extend([face[(k + 1) % 3], face[(k + 2) % 3]]);
            }
        }
        assert!(neighbours[count - 1].is_empty() && neighbours[b as usize].contains(&n));
        let shuffled: Vec<u32> = (0..count as u32).map(|i| (i * 37 + 11) % count as u32).collect();
        let mut rank = vec![0u32; count];
        for (i, &v) in shuffled.iter().enumerate() {
            rank[v as usize] = i as u32;
        }
        let identity: Vec<u32> = (0..count as u32).collect();
        for (mesh, order, rank, robust) in
            [(&mesh, &identity, &identity, false), (&mesh, &shuffled, &rank, false), (&huge, &shuffled, &rank, true)]
        {
            let conn = mesh.connectivity();
            assert!(!conn.is_manifold() && !conn.non_manifold_report().inconsistent_edges.is_empty());
            let graph = EdgeGraph::new(mesh, robust, Some((order, rank)));
            for (i, &v) in order.iter().enumerate() {
                let mut expected: Vec<(u32, u64)> = neighbours[v as usize]
                    .iter()
                    .map(|&w| {
                        let edge = mesh.position(VertexId(w)) - mesh.position(VertexId(v));
                        let length = if robust { mesh_kernel::geometry::norm(edge) } else { edge.length() };
                        assert!(length.is_finite() && length > 0.0);
                        (rank[w as usize], length.to_bits())
                    })
                    .collect();
                let mut ring: Vec<(u32, u64)> = graph.ring(i).iter().map(|e| (e.to, { e.length }.to_bits())).collect();
                if order == &identity {
                    assert!(ring.windows(2).all(|w| w[0].0 < w[1].0), "mesh vertex {v}: {ring:?}");
                }
                expected.sort_unstable();
                ring.sort_unstable();
                assert_eq!(ring, expected, "mesh vertex {v}");
            }
        }
    }
}
