//! Dijkstra's algorithm on the edge graph: the chapter's upper-bound estimate
//! of geodesic distance (section 2.6, figure 2.10), with the shortest-path
//! tree and edge-path extraction.
//!
//! Edge weights are the Euclidean edge lengths, stored with the neighbours
//! in compressed sparse rows (built from the cached connectivity in
//! O(V + F)); the priority queue is a ring of buckets of distances (Dial
//! 1969), and each vertex's distance, predecessor and queue flag sit in
//! one 16-byte record, so that relaxing an edge touches one cache line. A
//! vertex's ring is asked for when it enters the queue, its neighbours'
//! records (and where their rings start) when it comes next.
//! [`DijkstraGraph`] keeps the graph, in a breadth-first vertex numbering
//! that keeps the front's memory together, for repeated queries. Cost
//! O(V + E) per query when the edges' lengths lie within a factor of 2048
//! of one another (no heap at all), else O((V + E) log V) (the logarithm
//! of a bucket's size), plus the number of buckets the distances span;
//! O(V + E) memory.

use mesh_kernel::{TriMesh, VertexId};

use crate::bucket_queue::BucketQueue;
use crate::edge_graph::EdgeGraph;
use crate::error::{GeodesicError, Result};
use crate::support::{breadth_first_order, validate_source_indices};

/// Options of [`dijkstra`].
#[derive(Debug, Clone, PartialEq)]
pub struct DijkstraOptions {
    /// Stop the search at this distance: vertices farther away are left at
    /// `+infinity`, unreached. Default `+infinity` (the whole mesh).
    pub max_distance: f64,
}

impl Default for DijkstraOptions {
    fn default() -> Self {
        Self { max_distance: f64::INFINITY }
    }
}

/// The result of [`dijkstra`]: graph distances and the shortest-path tree.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct ShortestPaths {
    /// Graph distance of every vertex to the nearest source; `+infinity`
    /// where no source is reachable (other components, isolated vertices,
    /// beyond [`DijkstraOptions::max_distance`]).
    pub distance: Vec<f64>,
    /// The previous vertex on a shortest edge path from the nearest source;
    /// [`VertexId::INVALID`] at sources and unreached vertices.
    pub predecessor: Vec<VertexId>,
    /// Position in the source list of the nearest source (a graph Voronoi
    /// labelling); `u32::MAX` where unreached.
    pub source_index: Vec<u32>,
}

impl ShortestPaths {
    /// The shortest edge path from the nearest source to `to`, source first;
    /// `None` when `to` is out of range or unreached. O(path length).
    pub fn edge_path(&self, to: VertexId) -> Option<Vec<VertexId>> {
        if to.idx() >= self.distance.len() || !self.distance[to.idx()].is_finite() {
            return None;
        }
        let mut path = vec![to];
        let mut v = to;
        // The tree is acyclic; the bound only guards against a corrupted tree.
        for _ in 0..self.distance.len() {
            let p = self.predecessor[v.idx()];
            if !p.is_valid() {
                path.reverse();
                return Some(path);
            }
            path.push(p);
            v = p;
        }
        None
    }
}

/// Multi-source Dijkstra on the edge graph of `mesh` (chapter section 2.6): exact
/// shortest edge-path lengths, an upper bound of the geodesic distance.
/// Works on any triangle soup (non-manifold, disconnected, degenerate).
/// Duplicate sources are allowed (the first one labels the vertex).
///
/// Builds the edge graph for this one call (O(V + E), from the cached
/// connectivity's edges, about half as long as the search itself on a mesh
/// larger than the cache); for several queries on one mesh,
/// [`DijkstraGraph`] builds it once. Cost O((V + E) log V).
///
/// ```
/// use mesh_kernel::{shapes, VertexId};
/// use mesh_geodesic::{dijkstra, DijkstraOptions};
///
/// let mesh = shapes::icosphere(3)?;
/// let tree = dijkstra(&mesh, &[VertexId(0)], &DijkstraOptions::default())?;
/// let path = tree.edge_path(VertexId(100)).unwrap();
/// assert_eq!(path[0], VertexId(0));
/// assert!(tree.distance[100] >= mesh.position(VertexId(0)).distance(mesh.position(VertexId(100))));
/// # Ok::<(), mesh_geodesic::GeodesicError>(())
/// ```
///
/// # Errors
/// `GeodesicError::NoSources` for an empty `sources`; `GeodesicError::SourceOutOfRange` for a source that is
/// not a vertex; `GeodesicError::InvalidOption` (`max_distance`) for a NaN or negative `max_distance`.
pub fn dijkstra(mesh: &TriMesh, sources: &[VertexId], options: &DijkstraOptions) -> Result<ShortestPaths> {
    let seeds = validate(mesh.vertex_count(), sources, options)?;
    let graph = EdgeGraph::new(mesh, robust_lengths(mesh), None);
    let mut search = Search::unreached(mesh.vertex_count(), sources.len());
    search.propagate(&graph, &seeds, options.max_distance, |_| {});
    Ok(search.into_paths(None))
}

/// A mesh's edge graph prepared for repeated [`dijkstra`] queries: the
/// neighbours and edge lengths of every vertex in compressed sparse rows,
/// over a breadth-first renumbering of the vertices (neighbours get nearby
/// numbers, so the front of a search touches little memory even when the
/// mesh's own vertex order is scattered, as after subdivision). Building it
/// costs O(V + F); each query O((V + E) log V) and an O(V) translation back
/// to the mesh's numbering.
///
/// ```
/// use mesh_kernel::{shapes, VertexId};
/// use mesh_geodesic::{dijkstra, DijkstraGraph, DijkstraOptions};
///
/// let mesh = shapes::icosphere(3)?;
/// let graph = DijkstraGraph::new(&mesh);
/// let opts = DijkstraOptions::default();
/// for source in [VertexId(0), VertexId(7)] {
///     assert_eq!(graph.shortest_paths(&[source], &opts)?.distance, dijkstra(&mesh, &[source], &opts)?.distance);
/// }
/// # Ok::<(), mesh_geodesic::GeodesicError>(())
/// ```
#[derive(Debug, Clone)]
pub struct DijkstraGraph {
    graph: EdgeGraph,
    /// Mesh vertex of each internal index (breadth-first order).
    order: Vec<u32>,
    /// Internal index of each mesh vertex.
    rank: Vec<u32>,
}

impl DijkstraGraph {
    /// Builds the graph of `mesh` (robust edge lengths for extreme units, as
    /// [`dijkstra`]). O(V + F).
    pub fn new(mesh: &TriMesh) -> Self {
        let (order, rank) = breadth_first_order(mesh);
        let graph = EdgeGraph::new(mesh, robust_lengths(mesh), Some((&order, &rank)));
        Self { graph, order, rank }
    }

    /// Number of vertices of the mesh.
    pub fn vertex_count(&self) -> usize {
        self.order.len()
    }

    /// The shortest edge paths from `sources`: the same distances, bit for
    /// bit, as [`dijkstra`] on the mesh (ties between equally short paths
    /// may pick another predecessor). O((V + E) log V).
    ///
    /// # Errors
    /// As [`dijkstra`].
    pub fn shortest_paths(&self, sources: &[VertexId], options: &DijkstraOptions) -> Result<ShortestPaths> {
        let seeds = validate(self.vertex_count(), sources, options)?;
        let seeds: Vec<(VertexId, u32)> = seeds.iter().map(|&(s, l)| (VertexId(self.rank[s.idx()]), l)).collect();
        let mut search = Search::unreached(self.vertex_count(), sources.len());
        search.propagate(&self.graph, &seeds, options.max_distance, |_| {});
        Ok(search.into_paths(Some((&self.order, &self.rank))))
    }
}

/// Checks the sources and options of a query; the seeds labelled by their
/// position in `sources`.
fn validate(vertex_count: usize, sources: &[VertexId], options: &DijkstraOptions) -> Result<Vec<(VertexId, u32)>> {
    validate_source_indices(vertex_count, sources)?;
    if options.max_distance.is_nan() || options.max_distance < 0.0 {
        return Err(GeodesicError::InvalidOption {
            name: "max_distance",
            reason: format!("{} is not a non-negative number", options.max_distance),
        });
    }
    Ok(sources.iter().enumerate().map(|(i, &s)| (s, i as u32)).collect())
}

/// `true` when the mesh's size lies outside `[2^-100, 2^100]`, where squared
/// edge lengths could over- or underflow: edge lengths then go through
/// [`mesh_kernel::geometry::norm`] (about 20% slower than a plain length,
/// so only there). O(V).
pub(crate) fn robust_lengths(mesh: &TriMesh) -> bool {
    !(2f64.powi(-100)..=2f64.powi(100)).contains(&mesh_kernel::units::length_unit(mesh))
}

/// A vertex's state in a search: 16 bytes, aligned so that what an edge
/// relaxation reads or writes shares one cache line.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(16))]
struct VertexState {
    distance: f64,
    /// The previous vertex on a shortest path (graph numbering), or
    /// `u32::MAX`.
    predecessor: u32,
    /// In the queue of the running search ([`BucketQueue::push`]).
    queued: bool,
}

/// The state of a (possibly incremental) multi-source search, in the
/// graph's numbering.
#[derive(Debug, Clone)]
pub(crate) struct Search {
    state: Vec<VertexState>,
    /// Position in the source list of the nearest source, `u32::MAX` where
    /// unreached; set when a vertex is popped, from its predecessor's.
    /// Empty in a search from one source, where it would be 0 wherever a
    /// distance is finite ([`Search::label`]): keeping it cost 6% of a
    /// query at 470,274 vertices.
    label: Vec<u32>,
    /// The queue, kept between the calls of an incremental search on one
    /// graph (its lists keep their memory).
    queue: Option<BucketQueue>,
}

impl Search {
    /// Every one of `vertex_count` vertices unreached, for seeds labelled
    /// by their position in a list of `source_count` sources. O(V).
    pub(crate) fn unreached(vertex_count: usize, source_count: usize) -> Self {
        let state = VertexState { distance: f64::INFINITY, predecessor: u32::MAX, queued: false };
        let label = if source_count > 1 { vec![u32::MAX; vertex_count] } else { Vec::new() };
        Self { state: vec![state; vertex_count], label, queue: None }
    }

    /// Distance of graph vertex `i` to its nearest source so far.
    #[inline]
    pub(crate) fn distance(&self, i: usize) -> f64 {
        self.state[i].distance
    }

    /// Label (source position) of graph vertex `i`'s nearest source so far.
    #[inline]
    pub(crate) fn label(&self, i: usize) -> u32 {
        match self.label.get(i) {
            Some(&label) => label,
            None if self.state[i].distance.is_finite() => 0,
            None => u32::MAX,
        }
    }

    /// The paths in the mesh's numbering, given the graph's numbering as
    /// `(order, rank)` (graph vertex `i` is mesh vertex `order[i]`, mesh
    /// vertex `v` is graph vertex `rank[v]`; the identity without it).
    /// Each array is written once, in mesh order, gathering from the
    /// search's state (queries at 470,274 vertices in file order measured
    /// level with, or 1-2 ms faster than, filling unreached arrays and
    /// scattering into them). O(V).
    fn into_paths(self, numbering: Option<(&[u32], &[u32])>) -> ShortestPaths {
        let n = self.state.len();
        let graph_vertex = |v: usize| numbering.map_or(v, |(_, rank)| rank[v] as usize);
        let mesh_vertex = |i: u32| numbering.map_or(i, |(order, _)| order[i as usize]);
        let mut paths = ShortestPaths {
            distance: Vec::with_capacity(n),
            predecessor: Vec::with_capacity(n),
            source_index: Vec::with_capacity(n),
        };
        for v in 0..n {
            let i = graph_vertex(v);
            let s = self.state[i];
            paths.distance.push(s.distance);
            paths.predecessor.push(match s.predecessor {
                u32::MAX => VertexId::INVALID,
                p => VertexId(mesh_vertex(p)),
            });
            paths.source_index.push(self.label(i));
        }
        paths
    }

    /// Dijkstra from `seeds` (graph vertex, label) over `graph`, on top of
    /// what earlier calls found: a vertex is updated only where the new
    /// distance is strictly smaller than the one already stored, which
    /// makes repeated calls an exact incremental multi-source search
    /// (farthest-point sampling). Seeds must be in range. A vertex's
    /// distance is the smallest `d(u) + |uw|` over its neighbours, each sum
    /// rounded once, whatever the queue's order among equal keys. Vertices
    /// farther than `max_distance` are left (or put back) unreached.
    /// `on_settle` sees every vertex settled, once: with an infinite
    /// `max_distance`, the vertices whose distance this call lowers. One
    /// `Search` runs on one graph (its queue is kept between calls).
    ///
    /// A vertex's ring is asked for when it enters the queue, and its
    /// neighbours' states and ring starts when it comes next, one pop before
    /// they are read.
    pub(crate) fn propagate(
        &mut self,
        graph: &EdgeGraph,
        seeds: &[(VertexId, u32)],
        max_distance: f64,
        mut on_settle: impl FnMut(u32),
    ) {
        let (shortest, longest) = graph.length_range();
        let mut queue = self.queue.take().unwrap_or_else(|| BucketQueue::new(shortest, longest));
        debug_assert!(!self.label.is_empty() || seeds.iter().all(|&(_, label)| label == 0));
        for &(s, label) in seeds {
            let st = &mut self.state[s.idx()];
            let unlabelled = self.label.get(s.idx()) == Some(&u32::MAX);
            if st.distance > 0.0 || unlabelled {
                (st.distance, st.predecessor, st.queued) = (0.0, u32::MAX, true);
                if let Some(l) = self.label.get_mut(s.idx()) {
                    *l = label;
                }
                queue.push(0.0, s.0);
            }
        }
        while let Some((d, v)) = queue.pop(|v| self.state[v as usize].distance) {
            self.state[v as usize].queued = false;
            if d > max_distance {
                if queue.beyond(max_distance) {
                    for v in queue.drain() {
                        self.state[v as usize].queued = false;
                    }
                    break;
                }
                continue;
            }
            let p = self.state[v as usize].predecessor;
            if p != u32::MAX && !self.label.is_empty() {
                self.label[v as usize] = self.label[p as usize];
            }
            on_settle(v);
            if let Some(next) = queue.peek() {
                for e in graph.ring(next as usize) {
                    mesh_kernel::hint::prefetch(self.state.as_ptr().wrapping_add(e.to as usize));
                    graph.prefetch_offset(e.to as usize);
                }
            }
            for e in graph.ring(v as usize) {
                let (w, nd) = (e.to, d + e.length);
                let st = &mut self.state[w as usize];
                // A settled vertex is never improved: the queue settles a
                // vertex only once no other can lower it.
                if nd < st.distance {
                    if !st.queued {
                        graph.prefetch_ring(w as usize);
                    }
                    (st.distance, st.predecessor, st.queued) = (nd, v, true);
                    queue.push(nd, w);
                }
            }
        }
        queue.restart();
        self.queue = Some(queue);
        if max_distance.is_finite() {
            for (i, s) in self.state.iter_mut().enumerate() {
                if s.distance > max_distance {
                    s.distance = f64::INFINITY;
                    s.predecessor = u32::MAX;
                    if let Some(label) = self.label.get_mut(i) {
                        *label = u32::MAX;
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{EdgeGraph, Search};
    use mesh_kernel::{shapes, TriMesh, VertexId};
    use std::cmp::Reverse;
    use std::collections::BinaryHeap;

    /// A plain Dijkstra on `graph` over the distances `start`, from
    /// `source` labelled `label`: the distances and labels it lowers.
    fn reference(graph: &EdgeGraph, start: &[f64], labels: &[u32], source: u32, label: u32) -> (Vec<f64>, Vec<u32>) {
        let (mut distance, mut labels) = (start.to_vec(), labels.to_vec());
        let mut heap = BinaryHeap::from([Reverse((0f64.to_bits(), source))]);
        (distance[source as usize], labels[source as usize]) = (0.0, label);
        while let Some(Reverse((bits, v))) = heap.pop() {
            let d = f64::from_bits(bits);
            if d > distance[v as usize] {
                continue;
            }
            for e in graph.ring(v as usize) {
                let nd = d + e.length;
                if nd < distance[e.to as usize] {
                    (distance[e.to as usize], labels[e.to as usize]) = (nd, label);
                    heap.push(Reverse((nd.to_bits(), e.to)));
                }
            }
        }
        (distance, labels)
    }

    /// A search cut off at a distance gives the plain search's distances up
    /// to it and leaves nothing queued, and a second search on top of it
    /// lowers exactly what a plain Dijkstra started from the first one's
    /// field lowers (a vertex is passed on only where the new distance is
    /// strictly smaller). On edges of similar lengths (a queue of buckets
    /// taken in any order), with one edge 10^5 times shorter than the
    /// others, with an edge of length zero (buckets kept as heaps), and on
    /// a sphere of radius 2^-1050 (one bucket).
    #[test]
    fn searches_cut_off_and_resumed_match_a_plain_dijkstra() {
        let sphere = shapes::icosphere(3).unwrap();
        let [a, b, _] = sphere.faces()[0];
        let (pa, pb) = (sphere.position(VertexId(a)), sphere.position(VertexId(b)));
        let moved = |to| {
            let mut positions = sphere.positions().to_vec();
            positions[b as usize] = to;
            TriMesh::new(positions, sphere.faces().to_vec()).unwrap()
        };
        // So small that one over half its shortest edge overflows: one heap.
        let tiny: Vec<_> = sphere.positions().iter().map(|&p| p * 2f64.powi(-1050)).collect();
        let tiny = TriMesh::new(tiny, sphere.faces().to_vec()).unwrap();
        for (mesh, scale, ordered) in [
            (sphere.clone(), 1.0, false),
            (moved(pa + (pb - pa) * 1e-5), 1.0, true),
            (moved(pa), 1.0, true),
            (tiny, 2f64.powi(-1050), true),
        ] {
            let (n, graph) = (mesh.vertex_count(), EdgeGraph::new(&mesh, scale != 1.0, None));
            let mut search = Search::unreached(n, 2);
            search.propagate(&graph, &[(VertexId(0), 0)], 0.3 * scale, |_| {});
            assert_eq!(search.queue.as_ref().map(|q| q.is_ordered()), Some(ordered));
            assert!(search.state.iter().all(|s| !s.queued));
            let first: Vec<f64> = (0..n).map(|v| search.distance(v)).collect();
            let (plain, _) = reference(&graph, &vec![f64::INFINITY; n], &vec![u32::MAX; n], 0, 0);
            let cut: Vec<f64> = plain.iter().map(|&d| if d > 0.3 * scale { f64::INFINITY } else { d }).collect();
            assert_eq!(first, cut);
            assert!(first.iter().any(|d| d.is_infinite()) && first.iter().filter(|d| d.is_finite()).count() > 10);
            let labels: Vec<u32> = (0..n).map(|v| search.label(v)).collect();
            let mut settled = Vec::new();
            search.propagate(&graph, &[(VertexId(5), 1)], f64::INFINITY, |v| settled.push(v));
            let (expected, label) = reference(&graph, &first, &labels, 5, 1);
            for v in 0..n {
                assert_eq!((search.distance(v), search.label(v)), (expected[v], label[v]), "vertex {v}");
            }
            // Each vertex the second search lowered is settled once.
            settled.sort_unstable();
            let lowered: Vec<u32> = (0..n as u32).filter(|&v| expected[v as usize] != first[v as usize]).collect();
            assert_eq!(settled, lowered);
        }
    }
}
