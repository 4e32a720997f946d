//! Dijkstra's algorithm on the edge graph: the chapter's upper-bound estimate
//! of geodesic distance (section 2.6, figure 2.10), with the shortest-path
//! tree and edge-path extraction.
//!
//! Edge weights are the Euclidean edge lengths. The graph is walked through
//! the [`mesh_kernel::Connectivity`] vertex rings (no adjacency matrix is
//! built); the priority queue is a binary heap with lazy deletion. Cost
//! O((V + E) log V) time, O(V) memory.

use std::collections::BinaryHeap;

use mesh_kernel::{TriMesh, VertexId};

use crate::error::{GeodesicError, Result};
use crate::support::{for_each_neighbor, validate_sources, HeapEntry};

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
/// Duplicate sources are allowed. Cost O((V + E) log V).
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
    validate_sources(mesh, sources)?;
    if options.max_distance.is_nan() || options.max_distance < 0.0 {
        return Err(GeodesicError::InvalidOption {
            name: "max_distance",
            reason: format!("{} is not a non-negative number", options.max_distance),
        });
    }
    let n = mesh.vertex_count();
    let mut paths = ShortestPaths {
        distance: vec![f64::INFINITY; n],
        predecessor: vec![VertexId::INVALID; n],
        source_index: vec![u32::MAX; n],
    };
    let seeds: Vec<(VertexId, u32)> = sources.iter().enumerate().map(|(i, &s)| (s, i as u32)).collect();
    propagate(mesh, &seeds, options.max_distance, robust_lengths(mesh), &mut paths);
    Ok(paths)
}

/// `true` when the mesh's size lies outside `[2^-100, 2^100]`, where squared
/// edge lengths could over- or underflow: edge lengths then go through
/// [`mesh_kernel::geometry::norm`] (about 20% slower than a plain length,
/// so only there). O(V).
pub(crate) fn robust_lengths(mesh: &TriMesh) -> bool {
    !(2f64.powi(-100)..=2f64.powi(100)).contains(&mesh_kernel::units::length_unit(mesh))
}

/// Dijkstra from `seeds` (vertex, label) into an existing labelling: a vertex
/// is updated only where the new distance is strictly smaller than the one
/// already stored, which makes repeated calls an exact incremental
/// multi-source search (farthest-point sampling). Seeds must be in range;
/// `robust` comes from [`robust_lengths`].
pub(crate) fn propagate(
    mesh: &TriMesh,
    seeds: &[(VertexId, u32)],
    max_distance: f64,
    robust: bool,
    paths: &mut ShortestPaths,
) {
    let conn = mesh.connectivity();
    let p = mesh.positions();
    let mut heap = BinaryHeap::with_capacity(seeds.len() + 64);
    for &(s, label) in seeds {
        if paths.distance[s.idx()] > 0.0 || paths.source_index[s.idx()] == u32::MAX {
            paths.distance[s.idx()] = 0.0;
            paths.predecessor[s.idx()] = VertexId::INVALID;
            paths.source_index[s.idx()] = label;
            heap.push(HeapEntry { distance: 0.0, vertex: s.0 });
        }
    }
    let ShortestPaths { distance, predecessor, source_index } = paths;
    while let Some(HeapEntry { distance: d, vertex }) = heap.pop() {
        let v = VertexId(vertex);
        if d > distance[v.idx()] {
            continue; // stale entry
        }
        if d > max_distance {
            break;
        }
        let (pv, label) = (p[v.idx()], source_index[v.idx()]);
        for_each_neighbor(conn, v, |w| {
            if distance[w.idx()] <= d {
                return; // settled (or about to be): no shorter path through v
            }
            let edge = p[w.idx()] - pv;
            let nd = d + if robust { mesh_kernel::geometry::norm(edge) } else { edge.length() };
            if nd < distance[w.idx()] {
                distance[w.idx()] = nd;
                predecessor[w.idx()] = v;
                source_index[w.idx()] = label;
                heap.push(HeapEntry { distance: nd, vertex: w.0 });
            }
        });
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
