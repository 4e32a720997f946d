//! Connectivity derived from the triangles: edges, half-edges, vertex rings,
//! boundary loops, components, and a precise manifold report.
//!
//! Half-edge `3 f + k` runs from corner `k` of face `f` to corner `k + 1`, so
//! `next`, `prev` and `face` are arithmetic ([`HalfedgeId::next`]); only
//! `twin`, the edge of each half-edge and the vertex rings are stored. Boundary
//! edges have a single half-edge whose twin is `None`.
//!
//! Construction is O(V + F) and sort-based: half-edges are bucketed by their
//! smaller endpoint with a counting sort ([`crate::par::group_by_key`]),
//! then each (tiny) bucket is sorted by the larger endpoint, so equal edges
//! become adjacent runs; no hashing. The counting sorts, the bucket sorts
//! and the walk around every vertex run on [`crate::par`]'s threads, with
//! a result that does not depend on their number.

use std::sync::OnceLock;

mod bucket_sort;
mod build;

pub use build::number_edges;

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
    halfedge_edge: Vec<EdgeId>,
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

impl Connectivity {
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
        self.halfedge_edge[h.idx()]
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
        self.edges_by_face()[f.idx()]
    }

    /// [`Connectivity::face_edges`] of every face, indexed by face.
    #[inline]
    pub fn edges_by_face(&self) -> &[[EdgeId; 3]] {
        self.halfedge_edge.as_chunks::<3>().0
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

    /// Number of distinct neighbours of `v` (the chapter's valence
    /// |N(p_i)|), the number of edges at `v`. O(1), but O(d log d) on a
    /// non-manifold vertex of `d` outgoing half-edges.
    ///
    /// A single fan (through edges of two faces) whose edges have one or
    /// two faces is a cycle or a path of faces, each with two edges at `v`:
    /// a cycle of `d` faces has `d` edges at `v`, a path `d + 1` (its two
    /// ends on boundary edges).
    pub fn valence(&self, v: VertexId) -> usize {
        match self.vertex_kind[v.idx()] {
            VertexKind::Isolated => 0,
            VertexKind::Interior => self.outgoing(v).len(),
            VertexKind::Boundary => self.outgoing(v).len() + 1,
            VertexKind::NonManifold => {
                let out = self.outgoing(v);
                let mut ring: Vec<VertexId> =
                    out.iter().flat_map(|&h| [self.dest(h), self.opposite_vertex(h)]).collect();
                ring.sort_unstable();
                ring.dedup();
                ring.len()
            }
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
        crate::par::init_once(&self.components, || {
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
        Ok(crate::par::init_once(&self.boundary_loops, || {
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
        })
        .as_slice())
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
        // Vertex 1 twice among the ends of 0's outgoing half-edges.
        assert_eq!((c.valence(VertexId(0)), c.valence(VertexId(1)), c.valence(VertexId(2))), (4, 4, 2));
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

    /// Everything a connectivity answers, for comparing two builds.
    #[cfg(feature = "rayon")]
    fn snapshot(c: &Connectivity) -> impl PartialEq + std::fmt::Debug {
        let halfedges = (0..c.halfedge_count() as u32).map(HalfedgeId);
        let vertices = (0..c.vertex_count()).map(VertexId::new);
        (
            c.edges().to_vec(),
            (0..c.edge_count()).map(|e| c.edge_halfedges(EdgeId::new(e)).to_vec()).collect::<Vec<_>>(),
            halfedges.map(|h| (c.twin(h), c.edge(h))).collect::<Vec<_>>(),
            vertices.map(|v| (c.outgoing(v).to_vec(), c.vertex_kind(v))).collect::<Vec<_>>(),
            c.non_manifold_report().clone(),
        )
    }

    /// The build is the same on 1, 2, 3 and 8 threads, past the sizes
    /// where its counting sorts run in several runs and its fan walks in
    /// several tasks: a 40,962-vertex sphere renumbered at random (so that
    /// runs and rows meet every part of the arrays), with faces flipped,
    /// repeated and glued at a vertex.
    #[cfg(feature = "rayon")]
    #[test]
    fn the_build_does_not_depend_on_the_thread_count() {
        let m = crate::shapes::icosphere(6).unwrap();
        let n = m.vertex_count();
        let mut rng = crate::random::SplitMix64::new(17);
        let mut order: Vec<u32> = (0..n as u32).collect();
        for i in (1..n).rev() {
            order.swap(i, rng.below(i + 1));
        }
        let mut faces: Vec<[u32; 3]> = m.faces().iter().map(|f| f.map(|v| order[v as usize])).collect();
        for _ in 0..50 {
            let f = rng.below(faces.len());
            match rng.below(3) {
                0 => faces[f].swap(1, 2),
                1 => faces.push(faces[f]),
                _ => faces.push([faces[f][0], n as u32, n as u32 + 1]),
            }
        }
        let build = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            snapshot(&pool.install(|| Connectivity::new(n + 2, &faces)))
        };
        let one = build(1);
        for threads in [2, 3, 8] {
            assert!(build(threads) == one, "{threads} threads");
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
