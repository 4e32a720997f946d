//! Cutting a closed or multiply-bounded surface into a topological disk, so
//! that it can be parameterized (with UVs per corner along the seam).
//!
//! The cut graph is built the tree-cotree way with the greedy choice of
//! Erickson and Whittlesey 2005 (shortest-path tree T from a root; dual
//! spanning tree D of maximum loop length across the edges not in T), then
//! every interior edge not crossed by D is cut and dangling seam edges are
//! pruned. Cutting along all edges not crossed by a dual spanning tree leaves
//! a tree of triangles (a disk), and re-gluing a dangling seam edge keeps it
//! a disk, so the result is a disk whose seam joins all boundary loops and
//! cuts every handle through short loops. A closed genus-0 surface is cut
//! along a shortest path between two far-apart vertices instead.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use mesh_kernel::union_find::UnionFind;
use mesh_kernel::{Connectivity, EdgeId, HalfedgeId, TriMesh, VertexId, VertexKind};

use crate::error::{ParamError, Result};
use crate::topology::{require_disk, Topology};

/// A mesh cut open into a disk: the same faces in the same order, with the
/// vertices along the seam duplicated (one copy per side).
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct CutMesh {
    /// The disk. Vertex `v < n` is the original vertex `v` (one of its
    /// copies if it lies on the seam); copies are appended after them.
    pub mesh: TriMesh,
    /// Original vertex of each vertex of [`CutMesh::mesh`].
    pub vertex_origin: Vec<VertexId>,
    /// Interior edges of the original mesh that were cut open (empty when the
    /// mesh already was a disk).
    pub seam: Vec<EdgeId>,
}

impl CutMesh {
    /// Values per corner (`[f][k]` for corner k of face f) from values per
    /// vertex of the cut mesh, e.g. UVs to write per corner in an OBJ file.
    pub fn per_corner<T: Copy>(&self, values: &[T]) -> Vec<[T; 3]> {
        self.mesh.faces().iter().map(|f| f.map(|v| values[v as usize])).collect()
    }
}

/// Cuts `mesh` into a topological disk (see the module documentation).
/// Needs a manifold mesh with one connected component; a disk is returned
/// unchanged with an empty seam. Cost O((V + F) log V) (Dijkstra and a sort).
///
/// # Errors
/// `ParamError::Mesh` (`MeshError::NonManifold`) when the mesh is not an oriented manifold;
/// `ParamError::NotADisk` for a mesh of several components, or one that is still not a disk after cutting.
pub fn cut_to_disk(mesh: &TriMesh) -> Result<CutMesh> {
    let topology = Topology::of(mesh)?;
    if topology.components != 1 {
        return Err(ParamError::NotADisk { found: format!("{}; cut each component separately", topology.describe()) });
    }
    let n = mesh.vertex_count();
    if topology.is_disk() {
        let vertex_origin = (0..n).map(VertexId::new).collect();
        return Ok(CutMesh { mesh: mesh.clone(), vertex_origin, seam: Vec::new() });
    }
    let conn = mesh.connectivity();
    let graph = Graph::new(mesh);
    let root = (0..n).find(|&v| conn.vertex_kind(VertexId::new(v)) != VertexKind::Isolated).unwrap_or(0);
    let mut cut = vec![false; conn.edge_count()];
    if topology.boundary_loops == 0 && topology.genus == 0 {
        for e in graph.far_path(root) {
            cut[e] = true;
        }
    } else {
        tree_cotree(conn, &graph, root, &mut cut);
        prune(conn, &graph, &mut cut);
    }
    let seam: Vec<EdgeId> = (0..cut.len()).filter(|&e| cut[e]).map(EdgeId::new).collect();
    let (positions, faces, vertex_origin) = split_along(mesh, conn, &cut);
    let disk = TriMesh::new(positions, faces)?;
    require_disk(&disk).map_err(|e| ParamError::NotADisk { found: format!("after cutting: {e}") })?;
    Ok(CutMesh { mesh: disk, vertex_origin, seam })
}

/// Vertex adjacency with edge ids and lengths, in CSR form.
struct Graph {
    offsets: Vec<usize>,
    /// (neighbour, edge, length)
    adj: Vec<(u32, u32, f64)>,
}

impl Graph {
    fn new(mesh: &TriMesh) -> Self {
        let conn = mesh.connectivity();
        let p = mesh.positions();
        let n = mesh.vertex_count();
        let mut offsets = vec![0usize; n + 1];
        for [a, b] in conn.edges() {
            offsets[a.idx() + 1] += 1;
            offsets[b.idx() + 1] += 1;
        }
        for v in 0..n {
            offsets[v + 1] += offsets[v];
        }
        let mut fill = offsets.clone();
        let mut adj = vec![(0, 0, 0.0); offsets[n]];
        for (e, [a, b]) in conn.edges().iter().enumerate() {
            let l = p[a.idx()].distance(p[b.idx()]);
            adj[fill[a.idx()]] = (b.0, e as u32, l);
            fill[a.idx()] += 1;
            adj[fill[b.idx()]] = (a.0, e as u32, l);
            fill[b.idx()] += 1;
        }
        Self { offsets, adj }
    }

    fn neighbors(&self, v: usize) -> &[(u32, u32, f64)] {
        &self.adj[self.offsets[v]..self.offsets[v + 1]]
    }

    /// Shortest-path distances and parent edges from `root` (Dijkstra).
    fn dijkstra(&self, root: usize) -> (Vec<f64>, Vec<u32>) {
        let n = self.offsets.len() - 1;
        let mut dist = vec![f64::INFINITY; n];
        let mut parent = vec![u32::MAX; n];
        let mut heap = BinaryHeap::new();
        dist[root] = 0.0;
        heap.push(Reverse((0u64, root as u32)));
        while let Some(Reverse((bits, v))) = heap.pop() {
            let v = v as usize;
            if f64::from_bits(bits) > dist[v] {
                continue;
            }
            for &(w, e, l) in self.neighbors(v) {
                let d = dist[v] + l;
                if d < dist[w as usize] {
                    dist[w as usize] = d;
                    parent[w as usize] = e;
                    // Non-negative floats order like their bit patterns.
                    heap.push(Reverse((d.to_bits(), w)));
                }
            }
        }
        (dist, parent)
    }

    fn other(&self, e: u32, v: usize) -> usize {
        self.neighbors(v).iter().find(|x| x.1 == e).map_or(v, |x| x.0 as usize)
    }

    /// Edges of a shortest path between two far-apart vertices (double
    /// sweep), at least two edges long so that cutting along it opens a hole.
    fn far_path(&self, root: usize) -> Vec<usize> {
        let farthest = |d: &[f64]| {
            (0..d.len()).filter(|&v| d[v].is_finite()).max_by(|&a, &b| d[a].total_cmp(&d[b])).unwrap_or(root)
        };
        let a = farthest(&self.dijkstra(root).0);
        let (dist, parent) = self.dijkstra(a);
        let b = farthest(&dist);
        let mut path = Vec::new();
        let mut v = b;
        while v != a && parent[v] != u32::MAX && path.len() < dist.len() {
            path.push(parent[v] as usize);
            v = self.other(parent[v], v);
        }
        if path.len() < 2 {
            // A second edge at b, away from the first.
            let avoid = path.first().map(|&e| e as u32);
            if let Some(&(_, e, _)) = self.neighbors(b).iter().find(|x| Some(x.1) != avoid) {
                path.push(e as usize);
            }
        }
        path
    }
}

/// Marks as cut every interior edge that the dual spanning tree does not
/// cross (Erickson-Whittlesey greedy choice: the dual tree prefers edges
/// outside the shortest-path tree, longest loop first).
fn tree_cotree(conn: &Connectivity, graph: &Graph, root: usize, cut: &mut [bool]) {
    let (dist, parent) = graph.dijkstra(root);
    let mut in_tree = vec![false; conn.edge_count()];
    for &e in parent.iter().filter(|&&e| e != u32::MAX) {
        in_tree[e as usize] = true;
    }
    let interior = |e: usize| conn.edge_halfedges(EdgeId::new(e)).len() == 2;
    let loop_length = |e: usize| {
        let [a, b] = conn.edge_vertices(EdgeId::new(e));
        let l = graph.neighbors(a.idx()).iter().find(|x| x.1 == e as u32).map_or(0.0, |x| x.2);
        dist[a.idx()] + dist[b.idx()] + l
    };
    let mut candidates: Vec<(f64, usize)> =
        (0..conn.edge_count()).filter(|&e| interior(e) && !in_tree[e]).map(|e| (loop_length(e), e)).collect();
    candidates.sort_unstable_by(|x, y| y.0.total_cmp(&x.0).then(x.1.cmp(&y.1)));
    // Tree edges come last, only where needed to connect the dual tree.
    candidates.extend((0..conn.edge_count()).filter(|&e| interior(e) && in_tree[e]).map(|e| (0.0, e)));
    let mut faces = UnionFind::new(conn.face_count());
    for e in 0..conn.edge_count() {
        cut[e] = interior(e);
    }
    for (_, e) in candidates {
        let hs = conn.edge_halfedges(EdgeId::new(e));
        let (f, g) = (hs[0].face().0, hs[1].face().0);
        if faces.union(f, g) {
            cut[e] = false;
        }
    }
}

/// Removes dangling seam edges: an interior cut edge with an endpoint that
/// no other cut or boundary edge reaches. O(E).
fn prune(conn: &Connectivity, graph: &Graph, cut: &mut [bool]) {
    let n = conn.vertex_count();
    let counted = |e: usize, cut: &[bool]| cut[e] || conn.is_boundary_edge(EdgeId::new(e));
    let mut degree: Vec<u32> =
        (0..n).map(|v| graph.neighbors(v).iter().filter(|x| counted(x.1 as usize, cut)).count() as u32).collect();
    let mut stack: Vec<usize> = (0..n).filter(|&v| degree[v] == 1).collect();
    while let Some(v) = stack.pop() {
        if degree[v] != 1 {
            continue;
        }
        let Some(&(w, e, _)) = graph.neighbors(v).iter().find(|x| cut[x.1 as usize]) else { continue };
        cut[e as usize] = false;
        degree[v] -= 1;
        degree[w as usize] -= 1;
        if degree[w as usize] == 1 {
            stack.push(w as usize);
        }
    }
}

/// Duplicates every vertex once per wedge (run of faces between cut edges
/// around it). Returns positions, faces and the origin of each new vertex.
fn split_along(mesh: &TriMesh, conn: &Connectivity, cut: &[bool]) -> (Vec<glam::DVec3>, Vec<[u32; 3]>, Vec<VertexId>) {
    let n = mesh.vertex_count();
    let mut faces = mesh.faces().to_vec();
    let mut origin: Vec<VertexId> = (0..n).map(VertexId::new).collect();
    for v in 0..n {
        let vid = VertexId::new(v);
        let ring: &[HalfedgeId] = conn.outgoing(vid);
        let boundary = conn.vertex_kind(vid) == VertexKind::Boundary;
        let starts = |k: usize| (boundary && k == 0) || cut[conn.edge(ring[k]).idx()];
        let Some(first) = (0..ring.len()).find(|&k| starts(k)) else { continue };
        let mut id = v as u32;
        for step in 0..ring.len() {
            let k = (first + step) % ring.len();
            if step > 0 && starts(k) {
                id = origin.len() as u32;
                origin.push(vid);
            }
            let h = ring[k];
            faces[h.face().idx()][h.corner()] = id;
        }
    }
    let p = mesh.positions();
    let positions = origin.iter().map(|v| p[v.idx()]).collect();
    (positions, faces, origin)
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::shapes;

    fn check(mesh: &TriMesh) -> CutMesh {
        let c = cut_to_disk(mesh).unwrap();
        assert!(Topology::of(&c.mesh).unwrap().is_disk());
        assert_eq!(c.mesh.face_count(), mesh.face_count());
        for (f, (a, b)) in c.mesh.faces().iter().zip(mesh.faces()).enumerate() {
            for k in 0..3 {
                assert_eq!(c.vertex_origin[a[k] as usize].0, b[k], "face {f}");
            }
        }
        c
    }

    #[test]
    fn closed_and_bounded_surfaces_become_disks() {
        let sphere = check(&shapes::icosphere(2).unwrap());
        assert!(sphere.seam.len() >= 2);
        let torus = check(&shapes::torus(2.0, 0.5, 16, 8).unwrap());
        // Two generator loops of the torus: the seam has at least 8 + 16 / 2 edges.
        assert!(torus.seam.len() >= 8);
        let cyl = check(&shapes::cylinder(1.0, 2.0, 12, 5).unwrap());
        // One path joining the two rims: at least `along` edges, not a loop.
        assert!(cyl.seam.len() >= 5 && cyl.seam.len() < 12);
        let tet = TriMesh::new(
            vec![glam::DVec3::ZERO, glam::DVec3::X, glam::DVec3::Y, glam::DVec3::Z],
            vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
        )
        .unwrap();
        check(&tet);
        check(&shapes::cube(3).unwrap());
    }

    #[test]
    fn disks_are_unchanged_and_pieces_refused() {
        let d = shapes::disk(3, 1).unwrap();
        let c = cut_to_disk(&d).unwrap();
        assert!(c.seam.is_empty());
        assert_eq!(c.mesh, d);
        let p = (0..6).map(|i| glam::DVec3::new(i as f64, (i % 3 == 2) as u8 as f64, 0.0)).collect();
        let two = TriMesh::new(p, vec![[0, 1, 2], [3, 4, 5]]).unwrap();
        assert!(matches!(cut_to_disk(&two), Err(ParamError::NotADisk { .. })));
    }
}
