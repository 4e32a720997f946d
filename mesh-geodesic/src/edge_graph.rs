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
use mesh_kernel::{Connectivity, TriMesh, VertexId, VertexKind};

/// How many faces ahead of the one being written [`EdgeGraph::new`] asks
/// for the ring slots it will write (and twice as far, for the corners'
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
    /// vertex `order[i]` and `rank` the inverse permutation. Interior
    /// vertices of a consistently oriented fan list the destinations of
    /// their outgoing half-edges; every other vertex (open, non-manifold or
    /// inconsistently oriented fans) also the vertex before each of them, so
    /// that no neighbour is lost (some appear twice, which a search does not
    /// mind). Lengths `|p_w - p_v|` go through the overflow-safe
    /// [`mesh_kernel::geometry::norm`] when `robust`
    /// (from [`crate::dijkstra::robust_lengths`]). O(V + F).
    ///
    /// One pass over the faces in their order: each face's three sides are
    /// measured once and written into the rings of their starts, in the
    /// faces' order within a ring (not counter-clockwise, which no search
    /// needs). The slots written [`AHEAD`] faces on are asked for ahead, as
    /// are the positions and ring cursors `2 AHEAD` faces on. At 470,274
    /// vertices in file order this took 17.5-18.4 ms on one core where a
    /// pass over the vertices that looked up their half-edges' ends and
    /// then the ends' positions took 29; a fused version of that vertex
    /// pass, asking for the faces and positions ahead, 24-29 ms. The rings
    /// are written into memory that was not zeroed first
    /// ([`RowFill`]); the vertices before, on the full rings only, in a
    /// second pass over those rings' half-edges (a test of each corner in
    /// the face pass cost about 2 ms at 470,274 vertices).
    pub(crate) fn new(mesh: &TriMesh, robust: bool, numbering: Option<(&[u32], &[u32])>) -> Self {
        let internal = |v: u32| numbering.map_or(v, |(_, rank)| rank[v as usize]);
        let conn = mesh.connectivity();
        let full = full_rings(conn);
        let mut rings = RowFill::with_lengths(Self::ring_lengths(conn, &full, numbering.map(|(order, _)| order)));
        let p = mesh.positions();
        let length = |a: DVec3, b: DVec3| if robust { mesh_kernel::geometry::norm(b - a) } else { (b - a).length() };
        let faces = mesh.faces();
        let (mut shortest, mut longest) = (f64::INFINITY, 0f64);
        for (f, face) in faces.iter().enumerate() {
            if let Some(ahead) = faces.get(f + 2 * AHEAD) {
                for &v in ahead {
                    rings.prefetch_cursor(internal(v) as usize);
                    mesh_kernel::hint::prefetch(p.as_ptr().wrapping_add(v as usize));
                }
            }
            if let Some(ahead) = faces.get(f + AHEAD) {
                for &v in ahead {
                    rings.prefetch_slot(internal(v) as usize);
                }
            }
            let ids = face.map(internal);
            let [pa, pb, pc] = face.map(|v| p[v as usize]);
            let sides = [length(pa, pb), length(pb, pc), length(pc, pa)];
            for s in sides {
                if s > longest {
                    longest = s;
                }
                if s < shortest {
                    shortest = s;
                }
            }
            // Corner k: to the next corner along side k.
            for k in 0..3 {
                rings.push(ids[k] as usize, Edge { to: ids[(k + 1) % 3], length: sides[k] });
            }
        }
        // Then on the full rings, from each outgoing half-edge's corner to
        // the corner before it.
        for v in (0..full.len()).filter(|&v| full[v]) {
            for &h in conn.outgoing(VertexId::new(v)) {
                let face = faces[h.idx() / 3];
                let before = face[(h.idx() + 2) % 3];
                let edge = Edge { to: internal(before), length: length(p[before as usize], p[v]) };
                rings.push(internal(v as u32) as usize, edge);
            }
        }
        let (offsets, edges) = rings.finish();
        Self { offsets, edges, shortest, longest }
    }

    /// The rings' lengths in the internal numbering (`order[i]` the mesh
    /// vertex of internal vertex `i`, the identity without it): a ring
    /// holds a vertex's outgoing half-edges, twice over on the `full`
    /// ones. O(V).
    fn ring_lengths<'a>(
        conn: &'a Connectivity,
        full: &'a [bool],
        order: Option<&'a [u32]>,
    ) -> impl ExactSizeIterator<Item = u32> + 'a {
        (0..full.len()).map(move |i| {
            let v = order.map_or(i, |order| order[i] as usize);
            let out = conn.outgoing(VertexId::new(v)).len() as u32;
            if full[v] {
                2 * out
            } else {
                out
            }
        })
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

/// `true` for the vertices whose neighbours are not all destinations of
/// their outgoing half-edges: every vertex but the interior ones, and the
/// interior ones on an edge whose two faces disagree on orientation (their
/// fan is closed, yet a neighbour may only be reached by an incoming
/// half-edge). O(V).
fn full_rings(conn: &Connectivity) -> Vec<bool> {
    let mut full: Vec<bool> = conn.vertex_kinds().iter().map(|k| *k != VertexKind::Interior).collect();
    for &e in &conn.non_manifold_report().inconsistent_edges {
        for v in conn.edge_vertices(e) {
            full[v.idx()] = true;
        }
    }
    full
}

#[cfg(test)]
mod tests {
    use super::EdgeGraph;
    use mesh_kernel::{shapes, TriMesh, VertexId};

    /// Every ring holds what the documentation of [`EdgeGraph::new`] says,
    /// with lengths to the bit, on a mesh with boundary, a flipped face, a
    /// fin on an edge of two faces, a separate triangle and an isolated
    /// vertex, in the mesh's numbering and in a shuffled one, with plain
    /// and overflow-safe lengths.
    #[test]
    fn rings_list_the_ends_of_the_outgoing_half_edges_and_on_open_fans_the_vertices_before() {
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
        let mesh = TriMesh::new(positions, faces).unwrap();
        let count = mesh.vertex_count();
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
                let out = conn.outgoing(VertexId(v));
                let full = conn.vertex_kinds()[v as usize] != mesh_kernel::VertexKind::Interior
                    || conn
                        .non_manifold_report()
                        .inconsistent_edges
                        .iter()
                        .any(|&e| conn.edge_vertices(e).contains(&VertexId(v)));
                let mut expected: Vec<u32> = out.iter().map(|&h| conn.dest(h).0).collect();
                if full {
                    expected.extend(out.iter().map(|&h| conn.opposite_vertex(h).0));
                }
                let mut expected: Vec<(u32, u64)> = expected
                    .into_iter()
                    .map(|w| {
                        let edge = mesh.position(VertexId(w)) - mesh.position(VertexId(v));
                        let length = if robust { mesh_kernel::geometry::norm(edge) } else { edge.length() };
                        assert!(length.is_finite() && length > 0.0);
                        (rank[w as usize], length.to_bits())
                    })
                    .collect();
                let mut ring: Vec<(u32, u64)> = graph.ring(i).iter().map(|e| (e.to, { e.length }.to_bits())).collect();
                expected.sort_unstable();
                ring.sort_unstable();
                assert_eq!(ring, expected, "mesh vertex {v}");
            }
        }
    }
}
