//! Dijkstra's algorithm on the edge graph: the chapter's upper-bound estimate
//! of geodesic distance (section 2.6, figure 2.10), with the shortest-path
//! tree and edge-path extraction.
//!
//! Edge weights are the Euclidean edge lengths, stored with the neighbours
//! in compressed sparse rows (built from the cached connectivity in
//! O(V + F)); the priority queue is a radix heap on the distances' bits
//! (Ahuja, Mehlhorn, Orlin and Tarjan 1990) with lazy deletion, and settled
//! vertices are marked in a bitset. [`DijkstraGraph`] keeps the graph, in a
//! breadth-first vertex numbering that keeps the front's memory together,
//! for repeated queries. Cost O(V + E) per query plus the heap's
//! redistributions (at most 64 per entry), O(V + E) memory.

use mesh_kernel::{TriMesh, VertexId};

use crate::edge_graph::EdgeGraph;
use crate::error::{GeodesicError, Result};
use crate::radix_heap::RadixHeap;
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
    /// Every vertex unreached. O(V).
    pub(crate) fn unreached(vertex_count: usize) -> Self {
        Self {
            distance: vec![f64::INFINITY; vertex_count],
            predecessor: vec![VertexId::INVALID; vertex_count],
            source_index: vec![u32::MAX; vertex_count],
        }
    }

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
/// Builds the edge graph for this one call (O(V + F), about as long as the
/// search itself on a mesh larger than the cache); for several queries on
/// one mesh, [`DijkstraGraph`] builds it once. Cost O(V + E) plus the radix
/// heap's redistributions.
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
    let mut paths = ShortestPaths::unreached(mesh.vertex_count());
    propagate(&graph, &seeds, options.max_distance, &mut paths);
    Ok(paths)
}

/// A mesh's edge graph prepared for repeated [`dijkstra`] queries: the
/// neighbours and edge lengths of every vertex in compressed sparse rows,
/// over a breadth-first renumbering of the vertices (neighbours get nearby
/// numbers, so the front of a search touches little memory even when the
/// mesh's own vertex order is scattered, as after subdivision). Building it
/// costs O(V + F); each query O(V + E) plus the radix heap's
/// redistributions and an O(V) translation back to the mesh's numbering.
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
    /// may pick another predecessor). O(V + E).
    ///
    /// # Errors
    /// As [`dijkstra`].
    pub fn shortest_paths(&self, sources: &[VertexId], options: &DijkstraOptions) -> Result<ShortestPaths> {
        let seeds = validate(self.vertex_count(), sources, options)?;
        let seeds: Vec<(VertexId, u32)> = seeds.iter().map(|&(s, l)| (VertexId(self.rank[s.idx()]), l)).collect();
        let mut internal = ShortestPaths::unreached(self.vertex_count());
        propagate(&self.graph, &seeds, options.max_distance, &mut internal);
        let at = |v: usize| self.rank[v] as usize;
        Ok(ShortestPaths {
            distance: (0..self.vertex_count()).map(|v| internal.distance[at(v)]).collect(),
            predecessor: (0..self.vertex_count())
                .map(|v| match internal.predecessor[at(v)] {
                    p if p.is_valid() => VertexId(self.order[p.idx()]),
                    p => p,
                })
                .collect(),
            source_index: (0..self.vertex_count()).map(|v| internal.source_index[at(v)]).collect(),
        })
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

/// Dijkstra from `seeds` (vertex, label) over `graph` into an existing
/// labelling, all in the graph's numbering: a vertex is updated only where
/// the new distance is strictly smaller than the one already stored, which
/// makes repeated calls an exact incremental multi-source search
/// (farthest-point sampling). Seeds must be in range. A vertex's distance is
/// the smallest `d(u) + |uw|` over its neighbours, each sum rounded once,
/// whatever the heap's order among equal keys.
pub(crate) fn propagate(graph: &EdgeGraph, seeds: &[(VertexId, u32)], max_distance: f64, paths: &mut ShortestPaths) {
    let mut heap = RadixHeap::new();
    for &(s, label) in seeds {
        if paths.distance[s.idx()] > 0.0 || paths.source_index[s.idx()] == u32::MAX {
            paths.distance[s.idx()] = 0.0;
            paths.predecessor[s.idx()] = VertexId::INVALID;
            paths.source_index[s.idx()] = label;
            heap.push(0.0, s.0);
        }
    }
    let ShortestPaths { distance, predecessor, source_index } = paths;
    let mut settled = vec![0u64; graph.vertex_count().div_ceil(64)];
    while let Some((d, v)) = heap.pop() {
        let (word, bit) = (v as usize / 64, 1u64 << (v % 64));
        if settled[word] & bit != 0 {
            continue; // stale entry: settled at a smaller distance
        }
        if d > max_distance {
            break;
        }
        settled[word] |= bit;
        let label = source_index[v as usize];
        let (ring, lengths) = graph.ring(v as usize);
        for (&w, &l) in ring.iter().zip(lengths) {
            let nd = d + l;
            if nd < distance[w as usize] {
                distance[w as usize] = nd;
                predecessor[w as usize] = VertexId(v);
                source_index[w as usize] = label;
                graph.prefetch_ring(w as usize);
                heap.push(nd, w);
            }
        }
    }
    if max_distance.is_finite() {
        for v in 0..distance.len() {
            if distance[v] > max_distance {
                distance[v] = f64::INFINITY;
                predecessor[v] = VertexId::INVALID;
                source_index[v] = u32::MAX;
            }
        }
    }
}
