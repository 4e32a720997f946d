//! Connectivity derived from the triangles: edges, half-edges, vertex rings,
//! boundary loops, components, and a precise manifold report.
//!
//! Half-edge `3 f + k` runs from corner `k` of face `f` to corner `k + 1`, so
//! `next`, `prev` and `face` are arithmetic ([`HalfedgeId::next`]); only
//! `twin`, the edge of each half-edge and the vertex rings are stored. Boundary
//! edges have a single half-edge whose twin is `None`.
//!
//! Construction is O(V + F) and sort-based: half-edges are bucketed by their
//! smaller endpoint with a counting sort, then each (tiny) bucket is sorted by
//! the larger endpoint, so equal edges become adjacent runs. No hashing. The
//! passes that meet half-edges in an order other than their own carry what
//! they need with them (each sorted entry its direction, each ring slot the
//! next half-edge around the vertex), so that no pass looks up a half-edge
//! at random: on meshes whose faces do not follow their vertices those
//! lookups are cache misses.

use std::sync::OnceLock;

use crate::error::{MeshError, NonManifoldReport, Result};
use crate::ids::{EdgeId, FaceId, HalfedgeId, VertexId};
use crate::union_find::UnionFind;

/// What the neighbourhood of a vertex looks like.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VertexKind {
    /// Referenced by no face.
    Isolated,
    /// Its faces form one closed fan.
    Interior,
    /// Its faces form one open fan (two boundary edges meet at it).
    Boundary,
    /// More than one fan, or an endpoint of an edge with more than two faces.
    NonManifold,
}

/// One closed boundary curve: the boundary half-edges in order, each ending
/// where the next starts, with the faces on their left (so the loop of a
/// counter-clockwise disk runs counter-clockwise).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BoundaryLoop {
    /// The boundary half-edges in order.
    pub halfedges: Vec<HalfedgeId>,
    /// The origin vertex of each half-edge, in the same order.
    pub vertices: Vec<VertexId>,
}

/// Connected parts of the mesh (through shared vertices).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Components {
    /// Number of connected components (unreferenced vertices are not counted).
    pub count: usize,
    /// Component of each vertex; `u32::MAX` for unreferenced vertices.
    pub vertex_component: Vec<u32>,
    /// Component of each face.
    pub face_component: Vec<u32>,
}

/// Half-edge connectivity of a [`crate::TriMesh`], valid for any triangle soup.
/// Ordered ring queries are exact on vertices of kind `Interior`/`Boundary`
/// when the mesh is consistently oriented ([`Connectivity::require_manifold`]).
#[derive(Debug, Clone)]
pub struct Connectivity {
    corner_vertex: Vec<VertexId>,
    twin: Vec<HalfedgeId>,
    face_edges: Vec<[EdgeId; 3]>,
    edges: Vec<[VertexId; 2]>,
    edge_offsets: Vec<u32>,
    edge_halfedges: Vec<HalfedgeId>,
    vertex_offsets: Vec<u32>,
    vertex_out: Vec<HalfedgeId>,
    vertex_kind: Vec<VertexKind>,
    report: NonManifoldReport,
    components: OnceLock<Components>,
    boundary_loops: OnceLock<Vec<BoundaryLoop>>,
}

/// The half-edges `3 f + k` grouped into buckets by their smaller endpoint
/// (counting sort), each bucket sorted. An entry packs (larger endpoint,
/// half-edge, starts at the smaller) into one u64, so that a bucket's runs
/// of equal larger endpoint are its edges in order and the orientation of a
/// pair is known with no further lookup. Past 2^31 half-edges the direction
/// bit does not fit (`packed` is false): it is read from the corners instead.
struct HalfedgeSort {
    bucket_offsets: Vec<u32>,
    sorted: Vec<u64>,
    packed: bool,
}

impl HalfedgeSort {
    fn new(vertex_count: usize, faces: &[[u32; 3]]) -> Self {
        let nh = faces.len() * 3;
        // Each half-edge's endpoints as (smaller, larger) and whether it
        // starts at the smaller, read face by face (twice, rather than kept).
        let ends = |f: &[u32; 3], k: usize| {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            (a.min(b), a.max(b), a < b)
        };
        let packed = nh < 1 << 31;
        let mut bucket_offsets = vec![0u32; vertex_count + 1];
        for f in faces {
            for k in 0..3 {
                bucket_offsets[ends(f, k).0 as usize + 1] += 1;
            }
        }
        for v in 0..vertex_count {
            bucket_offsets[v + 1] += bucket_offsets[v];
        }
        let mut fill = bucket_offsets.clone();
        let mut sorted = vec![0u64; nh];
        for (f, tri) in faces.iter().enumerate() {
            for k in 0..3 {
                let (lo, hi, up) = ends(tri, k);
                let h = (3 * f + k) as u64;
                let low = if packed { (h << 1) | u64::from(up) } else { h };
                sorted[fill[lo as usize] as usize] = (u64::from(hi) << 32) | low;
                fill[lo as usize] += 1;
            }
        }
        for lo in 0..vertex_count {
            let bucket = &mut sorted[bucket_offsets[lo] as usize..bucket_offsets[lo + 1] as usize];
            if bucket.len() > 1 {
                bucket.sort_unstable();
            }
        }
        Self { bucket_offsets, sorted, packed }
    }
}

/// The edges of a mesh, numbered as [`Connectivity::edges`] numbers them
/// (endpoint pairs, smaller first, sorted), and the edge of every half-edge
/// `3 f + k` (from corner `k` of face `f` to corner `k + 1`), without the
/// rest of the half-edge structure: for callers that only need the edge
/// numbering (midpoint subdivision), on any mesh, manifold or not. Cost
/// O(V + F).
pub fn number_edges(mesh: &crate::TriMesh) -> (Vec<[u32; 2]>, Vec<u32>) {
    let vertex_count = mesh.vertex_count();
    let HalfedgeSort { bucket_offsets, sorted, packed } = HalfedgeSort::new(vertex_count, mesh.faces());
    let mut edges: Vec<[u32; 2]> = Vec::with_capacity(sorted.len() / 2 + 1);
    let mut halfedge_edge = vec![0u32; sorted.len()];
    for lo in 0..vertex_count {
        let mut last = u32::MAX;
        for &x in &sorted[bucket_offsets[lo] as usize..bucket_offsets[lo + 1] as usize] {
            let hi = (x >> 32) as u32;
            if hi != last {
                edges.push([lo as u32, hi]);
                last = hi;
            }
            let h = if packed { (x as u32) >> 1 } else { x as u32 };
            halfedge_edge[h as usize] = (edges.len() - 1) as u32;
        }
    }
    (edges, halfedge_edge)
}

impl Connectivity {
    /// Builds the connectivity of `faces` over `vertex_count` vertices. Indices
    /// must be in range (as [`crate::TriMesh::new`] guarantees). Cost O(V + F).
    pub fn new(vertex_count: usize, faces: &[[u32; 3]]) -> Self {
        let nh = faces.len() * 3;
        let corner_vertex: Vec<VertexId> = faces.iter().flat_map(|f| f.map(VertexId)).collect();
        let HalfedgeSort { bucket_offsets, sorted, packed } = HalfedgeSort::new(vertex_count, faces);
        let hi_of = |x: u64| (x >> 32) as u32;
        let h_of = |x: u64| HalfedgeId(if packed { (x as u32) >> 1 } else { x as u32 });
        let starts_low = |x: u64, lo: usize| if packed { x & 1 == 1 } else { corner_vertex[h_of(x).idx()].idx() == lo };

        // Runs of equal larger endpoint in a sorted bucket are edges.
        let mut twin = vec![HalfedgeId::INVALID; nh];
        let mut face_edges = vec![[EdgeId::INVALID; 3]; faces.len()];
        let halfedge_edge = face_edges.as_flattened_mut();
        let mut edges = Vec::with_capacity(nh / 2 + 1);
        let mut edge_offsets = Vec::with_capacity(nh / 2 + 2);
        let mut report = NonManifoldReport::default();
        for lo in 0..vertex_count {
            let bucket_end = bucket_offsets[lo + 1] as usize;
            let mut start = bucket_offsets[lo] as usize;
            while start < bucket_end {
                let hi = hi_of(sorted[start]);
                let mut end = start + 1;
                while end < bucket_end && hi_of(sorted[end]) == hi {
                    end += 1;
                }
                let e = EdgeId::new(edges.len());
                edges.push([VertexId::new(lo), VertexId(hi)]);
                edge_offsets.push(start as u32);
                for &x in &sorted[start..end] {
                    halfedge_edge[h_of(x).idx()] = e;
                }
                match end - start {
                    1 => {}
                    2 => {
                        let (x0, x1) = (sorted[start], sorted[start + 1]);
                        if starts_low(x0, lo) != starts_low(x1, lo) {
                            let (h0, h1) = (h_of(x0), h_of(x1));
                            twin[h0.idx()] = h1;
                            twin[h1.idx()] = h0;
                        } else {
                            report.inconsistent_edges.push(e);
                        }
                    }
                    _ => report.edges.push(e),
                }
                start = end;
            }
        }
        drop(bucket_offsets);
        edge_offsets.push(nh as u32);
        let edge_halfedges: Vec<HalfedgeId> = sorted.into_iter().map(h_of).collect();

        // Outgoing half-edges per vertex (CSR), each with the half-edge
        // after it counter-clockwise, twin(prev(h)): read here in face
        // order (prev(h) is in h's face), so that walking a fan below reads
        // only its vertex's own slots.
        let mut vertex_offsets = vec![0u32; vertex_count + 1];
        for v in &corner_vertex {
            vertex_offsets[v.idx() + 1] += 1;
        }
        for v in 0..vertex_count {
            vertex_offsets[v + 1] += vertex_offsets[v];
        }
        let mut fill = vertex_offsets.clone();
        let mut rings = vec![(HalfedgeId::INVALID, HalfedgeId::INVALID); nh];
        for (f, tri) in faces.iter().enumerate() {
            let face_twins = &twin[3 * f..3 * f + 3];
            for k in 0..3 {
                let v = tri[k] as usize;
                rings[fill[v] as usize] = (HalfedgeId((3 * f + k) as u32), face_twins[(k + 2) % 3]);
                fill[v] += 1;
            }
        }
        drop(fill);

        let edge_size = |e: EdgeId| edge_offsets[e.idx() + 1] - edge_offsets[e.idx()];
        let mut nonmanifold_edge_vertex = vec![false; vertex_count];
        for &e in &report.edges {
            for v in edges[e.idx()] {
                nonmanifold_edge_vertex[v.idx()] = true;
            }
        }
        let mut unoriented_vertex = vec![false; vertex_count];
        for &e in &report.inconsistent_edges {
            for v in edges[e.idx()] {
                unoriented_vertex[v.idx()] = true;
            }
        }

        // Classify each vertex by its fans and order manifold rings counter-clockwise.
        let mut vertex_out = vec![HalfedgeId::INVALID; nh];
        let mut vertex_kind = vec![VertexKind::Isolated; vertex_count];
        let mut fans_of = UnionFind::new(0);
        let mut ordered: Vec<HalfedgeId> = Vec::new();
        let mut index = RingIndex::default();
        for v in 0..vertex_count {
            let range = vertex_offsets[v] as usize..vertex_offsets[v + 1] as usize;
            let ring = &rings[range.clone()];
            let d = ring.len();
            if d == 0 {
                continue;
            }
            index.build(ring);
            // Fast path, almost every vertex: a consistently oriented single
            // fan, walked counter-clockwise by h -> twin(prev(h)) from its
            // boundary half-edge (no twin) if it has one.
            if !nonmanifold_edge_vertex[v] && !unoriented_vertex[v] {
                if let Some(kind) = walk_fan(ring, &index, &mut ordered) {
                    vertex_kind[v] = kind;
                    vertex_out[range].copy_from_slice(&ordered);
                    continue;
                }
            }
            for (slot, &(h, _)) in vertex_out[range].iter_mut().zip(ring) {
                *slot = h;
            }
            // Otherwise union the incident faces across edges at v that have
            // exactly two faces, and count the fans.
            fans_of.reset(d);
            let mut on_boundary = false;
            for (i, &(h, _)) in ring.iter().enumerate() {
                for g in [h, h.prev()] {
                    let e = halfedge_edge[g.idx()];
                    match edge_size(e) {
                        1 => on_boundary = true,
                        2 => {
                            let pair = &edge_halfedges[edge_offsets[e.idx()] as usize..][..2];
                            let other = if pair[0] == g { pair[1] } else { pair[0] };
                            // The other face's half-edge leaving v.
                            let out = if corner_vertex[other.idx()].idx() == v { other } else { other.next() };
                            if let Some(j) = index.position(ring, out) {
                                fans_of.union(i as u32, j as u32);
                            }
                        }
                        _ => {}
                    }
                }
            }
            let fans = (0..d as u32).filter(|&i| fans_of.find(i) == i).count();
            vertex_kind[v] = if fans > 1 || nonmanifold_edge_vertex[v] {
                if fans > 1 && !nonmanifold_edge_vertex[v] {
                    report.vertices.push(VertexId::new(v));
                }
                VertexKind::NonManifold
            } else if on_boundary {
                VertexKind::Boundary
            } else {
                VertexKind::Interior
            };
        }
        drop(rings);

        Self {
            corner_vertex,
            twin,
            face_edges,
            edges,
            edge_offsets,
            edge_halfedges,
            vertex_offsets,
            vertex_out,
            vertex_kind,
            report,
            components: OnceLock::new(),
            boundary_loops: OnceLock::new(),
        }
    }

    /// Number of vertices (referenced or not).
    #[inline]
    pub fn vertex_count(&self) -> usize {
        self.vertex_kind.len()
    }

    /// Number of faces.
    #[inline]
    pub fn face_count(&self) -> usize {
        self.corner_vertex.len() / 3
    }

    /// Number of undirected edges.
    #[inline]
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }

    /// Number of half-edges (three per face).
    #[inline]
    pub fn halfedge_count(&self) -> usize {
        self.corner_vertex.len()
    }

    /// Number of vertices referenced by at least one face.
    pub fn referenced_vertex_count(&self) -> usize {
        self.vertex_kind.iter().filter(|k| **k != VertexKind::Isolated).count()
    }

    /// Where the half-edge starts.
    #[inline]
    pub fn origin(&self, h: HalfedgeId) -> VertexId {
        self.corner_vertex[h.idx()]
    }

    /// Where the half-edge ends.
    #[inline]
    pub fn dest(&self, h: HalfedgeId) -> VertexId {
        self.corner_vertex[h.next().idx()]
    }

    /// The vertex of the half-edge's face opposite to it.
    #[inline]
    pub fn opposite_vertex(&self, h: HalfedgeId) -> VertexId {
        self.corner_vertex[h.prev().idx()]
    }

    /// The oppositely oriented half-edge of the neighbouring face, if the edge
    /// is interior and manifold.
    #[inline]
    pub fn twin(&self, h: HalfedgeId) -> Option<HalfedgeId> {
        let t = self.twin[h.idx()];
        t.is_valid().then_some(t)
    }

    /// The undirected edge of a half-edge.
    #[inline]
    pub fn edge(&self, h: HalfedgeId) -> EdgeId {
        self.face_edges.as_flattened()[h.idx()]
    }

    /// Endpoints of an edge, smaller index first.
    #[inline]
    pub fn edge_vertices(&self, e: EdgeId) -> [VertexId; 2] {
        self.edges[e.idx()]
    }

    /// All edges, as endpoint pairs with the smaller index first, sorted.
    #[inline]
    pub fn edges(&self) -> &[[VertexId; 2]] {
        &self.edges
    }

    /// The half-edges of an edge: one on the boundary, two inside a manifold,
    /// more on a non-manifold edge.
    #[inline]
    pub fn edge_halfedges(&self, e: EdgeId) -> &[HalfedgeId] {
        &self.edge_halfedges[self.edge_offsets[e.idx()] as usize..self.edge_offsets[e.idx() + 1] as usize]
    }

    /// The faces incident to an edge.
    pub fn edge_faces(&self, e: EdgeId) -> impl ExactSizeIterator<Item = FaceId> + '_ {
        self.edge_halfedges(e).iter().map(|h| h.face())
    }

    /// `true` when exactly one face has this edge.
    #[inline]
    pub fn is_boundary_edge(&self, e: EdgeId) -> bool {
        self.edge_offsets[e.idx() + 1] - self.edge_offsets[e.idx()] == 1
    }

    /// The three edges of a face, edge `k` running from corner `k` to `k + 1`.
    #[inline]
    pub fn face_edges(&self, f: FaceId) -> [EdgeId; 3] {
        self.face_edges[f.idx()]
    }

    /// [`Connectivity::face_edges`] of every face, indexed by face.
    #[inline]
    pub fn edges_by_face(&self) -> &[[EdgeId; 3]] {
        &self.face_edges
    }

    /// The faces across the three edges of `f` (`None` on the boundary or
    /// across a non-manifold or inconsistently oriented edge).
    pub fn face_neighbors(&self, f: FaceId) -> [Option<FaceId>; 3] {
        [0, 1, 2].map(|k| self.twin(HalfedgeId::of_corner(f, k)).map(|t| t.face()))
    }

    /// Half-edges leaving `v`: counter-clockwise for manifold vertices of an
    /// oriented mesh, starting at the boundary edge on the boundary.
    #[inline]
    pub fn outgoing(&self, v: VertexId) -> &[HalfedgeId] {
        &self.vertex_out[self.vertex_offsets[v.idx()] as usize..self.vertex_offsets[v.idx() + 1] as usize]
    }

    /// Faces around `v`, in the order of [`Connectivity::outgoing`].
    pub fn vertex_faces(&self, v: VertexId) -> impl ExactSizeIterator<Item = FaceId> + '_ {
        self.outgoing(v).iter().map(|h| h.face())
    }

    /// The 1-ring of `v`: its neighbours, ordered counter-clockwise on manifold
    /// vertices (on the boundary, from one boundary neighbour to the other).
    /// On non-manifold vertices every neighbour appears, some possibly twice.
    pub fn neighbors(&self, v: VertexId) -> impl Iterator<Item = VertexId> + '_ {
        let out = self.outgoing(v);
        let closing = match (self.vertex_kind[v.idx()], out.last()) {
            (VertexKind::Boundary, Some(&h)) => Some(self.opposite_vertex(h)),
            _ => None,
        };
        let extra: Vec<VertexId> = if self.vertex_kind[v.idx()] == VertexKind::NonManifold {
            // Every neighbour reached only by an incoming half-edge.
            out.iter().map(|h| self.opposite_vertex(*h)).filter(|w| !out.iter().any(|g| self.dest(*g) == *w)).collect()
        } else {
            Vec::new()
        };
        out.iter().map(|&h| self.dest(h)).chain(closing).chain(extra)
    }

    /// Number of neighbours of `v` (the chapter's valence |N(p_i)|).
    pub fn valence(&self, v: VertexId) -> usize {
        match self.vertex_kind[v.idx()] {
            VertexKind::Isolated => 0,
            VertexKind::Interior => self.outgoing(v).len(),
            VertexKind::Boundary => self.outgoing(v).len() + 1,
            VertexKind::NonManifold => self.neighbors(v).count(),
        }
    }

    /// How the neighbourhood of `v` looks.
    #[inline]
    pub fn vertex_kind(&self, v: VertexId) -> VertexKind {
        self.vertex_kind[v.idx()]
    }

    /// `true` for vertices on a boundary edge.
    #[inline]
    pub fn is_boundary_vertex(&self, v: VertexId) -> bool {
        match self.vertex_kind[v.idx()] {
            VertexKind::Boundary => true,
            VertexKind::NonManifold => self
                .outgoing(v)
                .iter()
                .any(|&h| self.is_boundary_edge(self.edge(h)) || self.is_boundary_edge(self.edge(h.prev()))),
            _ => false,
        }
    }

    /// Kinds of all vertices.
    #[inline]
    pub fn vertex_kinds(&self) -> &[VertexKind] {
        &self.vertex_kind
    }

    /// Every manifold defect found while building.
    #[inline]
    pub fn non_manifold_report(&self) -> &NonManifoldReport {
        &self.report
    }

    /// `true` when the mesh is an oriented 2-manifold, possibly with boundary.
    #[inline]
    pub fn is_manifold(&self) -> bool {
        self.report.is_empty()
    }

    /// `Ok` for an oriented 2-manifold, otherwise [`MeshError::NonManifold`]
    /// listing every defect.
    ///
    /// # Errors
    /// [`MeshError::NonManifold`] with the full report when an edge has more than two faces, a
    /// vertex more than one fan, or two faces disagree on orientation.
    pub fn require_manifold(&self) -> Result<()> {
        if self.report.is_empty() {
            Ok(())
        } else {
            Err(MeshError::NonManifold(Box::new(self.report.clone())))
        }
    }

    /// Euler-Poincare characteristic chi = n - n_e + n_f (eq. 2.6), over
    /// referenced vertices.
    pub fn euler_characteristic(&self) -> i64 {
        self.referenced_vertex_count() as i64 - self.edge_count() as i64 + self.face_count() as i64
    }

    /// Connected components through shared vertices (union-find, cached).
    pub fn components(&self) -> &Components {
        self.components.get_or_init(|| {
            let n = self.vertex_count();
            let mut sets = UnionFind::new(n);
            for f in self.corner_vertex.chunks_exact(3) {
                sets.union(f[0].0, f[1].0);
                sets.union(f[0].0, f[2].0);
            }
            let mut label = vec![u32::MAX; n];
            let mut count = 0u32;
            let mut vertex_component = vec![u32::MAX; n];
            for v in 0..n {
                if self.vertex_kind[v] == VertexKind::Isolated {
                    continue;
                }
                let r = sets.find(v as u32) as usize;
                if label[r] == u32::MAX {
                    label[r] = count;
                    count += 1;
                }
                vertex_component[v] = label[r];
            }
            let face_component = self.corner_vertex.chunks_exact(3).map(|f| vertex_component[f[0].idx()]).collect();
            Components { count: count as usize, vertex_component, face_component }
        })
    }

    /// Boundary loops of a manifold mesh, in order of their first half-edge
    /// (cached). Fails with [`MeshError::NonManifold`] otherwise.
    ///
    /// # Errors
    /// [`MeshError::NonManifold`] on a non-manifold mesh (see [`Connectivity::require_manifold`]).
    pub fn boundary_loops(&self) -> Result<&[BoundaryLoop]> {
        self.require_manifold()?;
        Ok(self.boundary_loops.get_or_init(|| {
            let nh = self.halfedge_count();
            let mut visited = vec![false; nh];
            let mut loops = Vec::new();
            for start in 0..nh {
                let h0 = HalfedgeId(start as u32);
                if visited[start] || self.twin[start].is_valid() {
                    continue;
                }
                let mut lp = BoundaryLoop { halfedges: Vec::new(), vertices: Vec::new() };
                let mut h = h0;
                // Each boundary vertex of a manifold has exactly one outgoing
                // boundary half-edge, first in its counter-clockwise ring.
                while !visited[h.idx()] {
                    visited[h.idx()] = true;
                    lp.halfedges.push(h);
                    lp.vertices.push(self.origin(h));
                    h = self.outgoing(self.dest(h))[0];
                }
                loops.push(lp);
            }
            loops
        }))
    }

    /// Number of boundary loops, or `None` when the mesh is not manifold.
    pub fn boundary_loop_count(&self) -> Option<usize> {
        self.boundary_loops().ok().map(|l| l.len())
    }

    /// Genus from chi = 2 (c - g) - b (eq. 2.7), or `None` when the mesh is not
    /// an oriented manifold.
    pub fn genus(&self) -> Option<u64> {
        let b = self.boundary_loop_count()? as i64;
        let c = self.components().count as i64;
        let twice = 2 * c - b - self.euler_characteristic();
        (twice >= 0 && twice % 2 == 0).then_some((twice / 2) as u64)
    }
}

/// Finds a half-edge's slot in a vertex's ring: by a linear scan in small
/// rings, by binary search in a sorted copy in large ones (so that a vertex
/// of valence `d` costs O(d log d), not O(d^2)).
#[derive(Default)]
struct RingIndex {
    /// `(half-edge, slot)` sorted, for rings above [`RingIndex::SCAN`].
    sorted: Vec<(HalfedgeId, u32)>,
    /// Every `twin(prev(h))` of the ring sorted, likewise.
    targets: Vec<HalfedgeId>,
}

impl RingIndex {
    /// Rings up to this size are scanned.
    const SCAN: usize = 16;

    fn build(&mut self, ring: &[(HalfedgeId, HalfedgeId)]) {
        if ring.len() > Self::SCAN {
            self.sorted.clear();
            self.sorted.extend(ring.iter().enumerate().map(|(i, &(h, _))| (h, i as u32)));
            self.sorted.sort_unstable();
            self.targets.clear();
            self.targets.extend(ring.iter().map(|&(_, t)| t));
            self.targets.sort_unstable();
        }
    }

    /// Whether some `twin(prev(g))` of `ring` is `h`.
    #[inline]
    fn is_target(&self, ring: &[(HalfedgeId, HalfedgeId)], h: HalfedgeId) -> bool {
        if ring.len() <= Self::SCAN {
            ring.iter().any(|&(_, t)| t == h)
        } else {
            self.targets.binary_search(&h).is_ok()
        }
    }

    /// The slot of `h` in `ring` (the ring [`RingIndex::build`] saw last).
    #[inline]
    fn position(&self, ring: &[(HalfedgeId, HalfedgeId)], h: HalfedgeId) -> Option<usize> {
        if ring.len() <= Self::SCAN {
            ring.iter().position(|&(g, _)| g == h)
        } else {
            let i = self.sorted.binary_search_by_key(&h, |&(g, _)| g).ok()?;
            Some(self.sorted[i].1 as usize)
        }
    }
}

/// The ring of a vertex none of whose edges is non-manifold or inconsistently
/// oriented, each outgoing half-edge `h` with `twin(prev(h))`, in
/// counter-clockwise order into `ordered`, when its faces form one fan:
/// from the first outgoing half-edge without twin (an open fan; on such a
/// vertex, the one no `twin(prev(g))` of the ring names) or from `ring[0]`
/// (a closed fan), rotating h -> twin(prev(h)). The vertex's kind, or `None`
/// when the walk does not visit the whole ring (several fans).
fn walk_fan(ring: &[(HalfedgeId, HalfedgeId)], index: &RingIndex, ordered: &mut Vec<HalfedgeId>) -> Option<VertexKind> {
    let open = ring.iter().position(|&(h, _)| !index.is_target(ring, h));
    let first = open.unwrap_or(0);
    ordered.clear();
    let mut i = first;
    loop {
        ordered.push(ring[i].0);
        let t = ring[i].1;
        let whole = ordered.len() == ring.len();
        if !t.is_valid() {
            return (open.is_some() && whole).then_some(VertexKind::Boundary);
        }
        if t == ring[first].0 {
            return (open.is_none() && whole).then_some(VertexKind::Interior);
        }
        if whole {
            return None;
        }
        i = index.position(ring, t)?;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn conn(n: usize, faces: &[[u32; 3]]) -> Connectivity {
        Connectivity::new(n, faces)
    }

    /// Two triangles sharing edge 1-2, a unit square.
    const SQUARE: [[u32; 3]; 2] = [[0, 1, 2], [0, 2, 3]];
    /// Tetrahedron, outward orientation.
    const TET: [[u32; 3]; 4] = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];

    #[test]
    fn square_has_five_edges_one_loop() {
        let c = conn(4, &SQUARE);
        assert_eq!(c.edge_count(), 5);
        assert!(c.is_manifold());
        assert_eq!(c.euler_characteristic(), 1);
        let loops = c.boundary_loops().unwrap();
        assert_eq!(loops.len(), 1);
        assert_eq!(loops[0].vertices.len(), 4);
        assert_eq!(c.genus(), Some(0));
        assert_eq!(c.valence(VertexId(0)), 3);
        assert_eq!(c.valence(VertexId(1)), 2);
        let ring: Vec<_> = c.neighbors(VertexId(0)).collect();
        assert_eq!(ring, vec![VertexId(1), VertexId(2), VertexId(3)]);
    }

    #[test]
    fn tetrahedron_is_closed_sphere() {
        let c = conn(4, &TET);
        assert!(c.is_manifold());
        assert_eq!(c.edge_count(), 6);
        assert_eq!(c.euler_characteristic(), 2);
        assert_eq!(c.boundary_loop_count(), Some(0));
        assert_eq!(c.genus(), Some(0));
        for h in 0..12 {
            let h = HalfedgeId(h);
            let t = c.twin(h).unwrap();
            assert_eq!(c.twin(t), Some(h));
            assert_eq!(c.origin(t), c.dest(h));
        }
        for v in 0..4 {
            assert_eq!(c.vertex_kind(VertexId(v)), VertexKind::Interior);
            assert_eq!(c.valence(VertexId(v)), 3);
        }
    }

    #[test]
    fn finds_nonmanifold_edge() {
        // Three triangles on edge 0-1.
        let c = conn(5, &[[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
        assert_eq!(c.non_manifold_report().edges, vec![EdgeId(0)]);
        assert!(c.boundary_loops().is_err());
        assert_eq!(c.genus(), None);
    }

    #[test]
    fn finds_bowtie_vertex() {
        let c = conn(5, &[[0, 1, 2], [0, 3, 4]]);
        assert_eq!(c.non_manifold_report().vertices, vec![VertexId(0)]);
        assert_eq!(c.vertex_kind(VertexId(0)), VertexKind::NonManifold);
        assert_eq!(c.components().count, 1);
        assert_eq!(c.valence(VertexId(0)), 4);
    }

    #[test]
    fn finds_inconsistent_orientation() {
        assert!(conn(4, &SQUARE).is_manifold());
        // Both faces traverse 2 -> 0.
        let c = conn(4, &[[0, 1, 2], [0, 3, 2]]);
        assert_eq!(c.non_manifold_report().inconsistent_edges, vec![EdgeId(1)]);
        assert!(c.non_manifold_report().vertices.is_empty());
        assert!(c.non_manifold_report().edges.is_empty());
    }

    /// Everything `Connectivity::new` derives, from a plain reading of the
    /// definitions (a map from edges to half-edges, fans by union-find over
    /// all faces at a vertex), on manifold shapes, on the same with faces
    /// removed, flipped or repeated, with fans of more faces than
    /// `RingIndex::SCAN`, and on random soups.
    #[test]
    fn agrees_with_the_definitions() {
        use std::collections::BTreeMap;
        let mut rng = crate::random::SplitMix64::new(11);
        let mut cases: Vec<(usize, Vec<[u32; 3]>)> = Vec::new();
        for m in [crate::shapes::icosphere(2).unwrap(), crate::shapes::disk(4, 1).unwrap()] {
            cases.push((m.vertex_count(), m.faces().to_vec()));
            for _ in 0..6 {
                let mut faces = m.faces().to_vec();
                for _ in 0..1 + rng.below(8) {
                    let f = rng.below(faces.len());
                    match rng.below(4) {
                        0 => drop(faces.swap_remove(f)),
                        1 => faces[f].swap(0, 1),
                        2 => faces.push(faces[f]),
                        _ => faces.push([faces[f][0], faces[f][1], rng.below(m.vertex_count()) as u32]),
                    }
                }
                faces.retain(|f| f[0] != f[1] && f[1] != f[2] && f[0] != f[2]);
                cases.push((m.vertex_count(), faces));
            }
        }
        // A closed cone of 40 faces, an open one, both glued at the apex, and
        // the closed one with a face flipped.
        let cone = |apex: u32, base: u32, n: u32, open: bool| -> Vec<[u32; 3]> {
            (0..n - u32::from(open)).map(|i| [apex, base + i, base + (i + 1) % n]).collect()
        };
        cases.push((41, cone(0, 1, 40, false)));
        cases.push((41, cone(0, 1, 40, true)));
        cases.push((81, [cone(0, 1, 40, false), cone(0, 41, 40, true)].concat()));
        let mut flipped = cone(0, 1, 40, false);
        flipped[7].swap(1, 2);
        cases.push((41, flipped));
        for _ in 0..40 {
            let n = 4 + rng.below(12);
            let faces = (0..1 + rng.below(3 * n))
                .map(|_| {
                    let a = rng.below(n) as u32;
                    let b = (a + 1 + rng.below(n - 1) as u32) % n as u32;
                    let mut c = rng.below(n) as u32;
                    while c == a || c == b {
                        c = (c + 1) % n as u32;
                    }
                    [a, b, c]
                })
                .collect();
            cases.push((n + rng.below(2), faces));
        }
        for (n, faces) in &cases {
            let c = conn(*n, faces);
            let mut by_edge: BTreeMap<(u32, u32), Vec<u32>> = BTreeMap::new();
            for (h, f) in faces.iter().flat_map(|f| [0, 1, 2].map(|k| [f[k], f[(k + 1) % 3]])).enumerate() {
                by_edge.entry((f[0].min(f[1]), f[0].max(f[1]))).or_default().push(h as u32);
            }
            let origin = |h: u32| faces[h as usize / 3][h as usize % 3];
            let mut report = NonManifoldReport::default();
            assert_eq!(c.edge_count(), by_edge.len());
            for (e, (&(a, b), hs)) in by_edge.iter().enumerate() {
                let e = EdgeId::new(e);
                assert_eq!(c.edge_vertices(e), [VertexId(a), VertexId(b)]);
                assert_eq!(c.edge_halfedges(e), &hs.iter().map(|&h| HalfedgeId(h)).collect::<Vec<_>>()[..]);
                let twins = hs.len() == 2 && origin(hs[0]) != origin(hs[1]);
                for (i, &h) in hs.iter().enumerate() {
                    assert_eq!(c.edge(HalfedgeId(h)), e);
                    assert_eq!(c.twin(HalfedgeId(h)), twins.then(|| HalfedgeId(hs[1 - i])));
                }
                match hs.len() {
                    1 => {}
                    2 if twins => {}
                    2 => report.inconsistent_edges.push(e),
                    _ => report.edges.push(e),
                }
            }
            for v in 0..*n as u32 {
                let out: Vec<u32> = (0..3 * faces.len() as u32).filter(|&h| origin(h) == v).collect();
                let mut got: Vec<u32> = c.outgoing(VertexId(v)).iter().map(|h| h.0).collect();
                let kind = c.vertex_kind(VertexId(v));
                if matches!(kind, VertexKind::Interior | VertexKind::Boundary) && c.is_manifold() {
                    // Counter-clockwise: each next one is twin(prev(h)).
                    for w in got.windows(2) {
                        assert_eq!(c.twin(HalfedgeId(w[0]).prev()), Some(HalfedgeId(w[1])), "vertex {v}");
                    }
                }
                got.sort_unstable();
                assert_eq!(got, out, "vertex {v}");
                // Fans: faces at v joined across their edges at v with two faces.
                let mut fans = UnionFind::new(out.len());
                let (mut boundary, mut bad_edge) = (false, false);
                for (i, &h) in out.iter().enumerate() {
                    for g in [h, HalfedgeId(h).prev().0] {
                        let (a, b) = (origin(g), origin(HalfedgeId(g).next().0));
                        let hs = &by_edge[&(a.min(b), a.max(b))];
                        boundary |= hs.len() == 1;
                        bad_edge |= hs.len() > 2;
                        if hs.len() == 2 {
                            let other = if hs[0] == g { hs[1] } else { hs[0] };
                            let other_out = if origin(other) == v { other } else { HalfedgeId(other).next().0 };
                            fans.union(i as u32, out.iter().position(|&x| x == other_out).unwrap() as u32);
                        }
                    }
                }
                let count = (0..out.len() as u32).filter(|&i| fans.find(i) == i).count();
                let expect = match (out.len(), count > 1 || bad_edge, boundary) {
                    (0, _, _) => VertexKind::Isolated,
                    (_, true, _) => VertexKind::NonManifold,
                    (_, false, true) => VertexKind::Boundary,
                    _ => VertexKind::Interior,
                };
                assert_eq!(kind, expect, "vertex {v} of {faces:?}");
                if count > 1 && !bad_edge {
                    report.vertices.push(VertexId(v));
                }
            }
            assert_eq!(c.non_manifold_report(), &report);
        }
    }

    #[test]
    fn isolated_vertices_do_not_count() {
        let c = conn(6, &SQUARE);
        assert_eq!(c.referenced_vertex_count(), 4);
        assert_eq!(c.euler_characteristic(), 1);
        assert_eq!(c.components().count, 1);
        assert_eq!(c.components().vertex_component[5], u32::MAX);
    }
}
