//! Building a [`Connectivity`] from the faces, in O(V + F), sort-based, on
//! [`crate::par`]'s threads where that pays; the result does not depend
//! on the thread count.
//!
//! 1. The half-edges are bucketed by their smaller endpoint (a counting
//!    sort, [`par::group_by_key`]) and each small bucket is sorted by the
//!    larger endpoint (rows side by side, by rank where the processor has
//!    AVX2: [`bucket_sort`]), so equal edges become adjacent runs. No
//!    hashing.
//! 2. One loop numbers the runs as edges and pairs the twins.
//! 3. The outgoing half-edges of every vertex are gathered (a second
//!    counting sort), and each vertex's fan is walked and classified, rows
//!    of vertices side by side.
//!
//! The passes that meet half-edges in an order other than their own carry
//! what they need with them (each sorted entry its direction, each ring
//! slot the next half-edge around the vertex), so that no pass looks up a
//! half-edge at random: on meshes whose faces do not follow their vertices
//! those lookups are cache misses.

use std::sync::OnceLock;

use super::{bucket_sort, Connectivity, VertexKind};
use crate::error::NonManifoldReport;
use crate::ids::{EdgeId, HalfedgeId, VertexId};
use crate::par;
use crate::union_find::UnionFind;

/// Entries between the one being numbered and the one whose slots are
/// asked for ahead.
const AHEAD: usize = par::READ_AHEAD;

/// The half-edges `3 f + k` grouped into buckets by their smaller endpoint,
/// each bucket sorted. An entry packs (larger endpoint, half-edge, starts
/// at the smaller) into one u64, so that a bucket's runs of equal larger
/// endpoint are its edges in order and the orientation of a pair is known
/// with no further lookup. Past 2^31 half-edges the direction bit does not
/// fit (`packed` is false): it is read from the corners instead.
struct HalfedgeSort<'a> {
    corner: &'a [u32],
    bucket_offsets: Vec<usize>,
    sorted: Vec<u64>,
    packed: bool,
}

/// The edge numbering of a whole mesh.
struct Numbering {
    edges: Vec<[VertexId; 2]>,
    /// The first sorted entry of each edge, and the entry count at the end.
    edge_offsets: Vec<u32>,
    halfedge_edge: Vec<EdgeId>,
    report: NonManifoldReport,
}

impl<'a> HalfedgeSort<'a> {
    fn new(vertex_count: usize, faces: &'a [[u32; 3]]) -> Self {
        let corner = faces.as_flattened();
        let packed = corner.len() < 1 << 31;
        // Each half-edge's endpoints as (smaller, larger) and whether it
        // starts at the smaller, read twice rather than kept.
        let ends = |f: usize, k: usize| {
            let (a, b) = (faces[f][k], faces[f][(k + 1) % 3]);
            (a.min(b), a.max(b), a < b)
        };
        let (bucket_offsets, mut sorted) = par::group_by_key(
            vertex_count,
            faces.len(),
            |f| [ends(f, 0).0 as usize, ends(f, 1).0 as usize, ends(f, 2).0 as usize],
            |f| {
                let entry = |k: usize| {
                    let (_, hi, up) = ends(f, k);
                    let h = (3 * f + k) as u64;
                    let low = if packed { (h << 1) | u64::from(up) } else { h };
                    (u64::from(hi) << 32) | low
                };
                [entry(0), entry(1), entry(2)]
            },
        );
        bucket_sort::sort_buckets(&mut sorted, &bucket_offsets);
        Self { corner, bucket_offsets, sorted, packed }
    }

    /// The half-edge of a sorted entry.
    #[inline]
    fn halfedge(&self, x: u64) -> HalfedgeId {
        HalfedgeId(if self.packed { (x as u32) >> 1 } else { x as u32 })
    }

    /// Whether the half-edge of entry `x`, in the bucket of `lo`, starts at `lo`.
    #[inline]
    fn starts_low(&self, x: u64, lo: usize) -> bool {
        if self.packed {
            x & 1 == 1
        } else {
            self.corner[self.halfedge(x).idx()] as usize == lo
        }
    }

    /// Numbers every edge in order of (smaller, larger) endpoint: the runs
    /// of equal larger endpoint in each bucket. It sets the twins too if
    /// `twin` is given, and then reports inconsistently oriented pairs.
    ///
    /// Its writes to the edge and twin of each half-edge land at random:
    /// they are asked for [`AHEAD`] entries before their turn
    /// ([`crate::hint::prefetch`]), which the processor does not do for
    /// stores on its own. At 470,274 vertices on two threads the numbering
    /// with the twins (beside the connectivity's two maps) took 17.4-17.5
    /// ms instead of 27.3-29.4 (2026-12-06).
    ///
    /// One loop: numbering chunks of buckets on two threads (each chunk
    /// from 0, made global afterwards) took longer on two threads than this
    /// loop on one (18 against 10 ms at 470k vertices), the extra passes
    /// costing more than the second thread gained; so did chunks numbered
    /// from a count of their edges (27.5 ms of chunks against 14 for the
    /// loop, 2026-12-06): the three half-edges of a face fall in three
    /// chunks, whose threads then write the same cache lines. Gathering
    /// instead (each bucket's entries given their edge and twin bucket by
    /// bucket, then each face finding its half-edges' entries by rank in
    /// their buckets, writing in face order) wrote no line from two
    /// threads, but read three at random per half-edge: the edge numbering
    /// alone took 104-109 ms against 33.5-35 on one thread and 53.5-56
    /// against 24-25.5 on two, at 437,645 and 470,274 vertices (2026-12-07).
    fn number(&self, mut twin: Option<&mut [HalfedgeId]>) -> Numbering {
        let hi_of = |x: u64| (x >> 32) as u32;
        let nh = self.corner.len();
        let mut numbering = Numbering {
            edges: Vec::with_capacity(nh / 2 + 1),
            edge_offsets: Vec::with_capacity(nh / 2 + 2),
            halfedge_edge: vec![EdgeId::INVALID; nh],
            report: NonManifoldReport::default(),
        };
        let Numbering { edges, edge_offsets, halfedge_edge, report } = &mut numbering;
        for (lo, bucket) in self.bucket_offsets.windows(2).enumerate() {
            let mut start = bucket[0];
            while start < bucket[1] {
                let hi = hi_of(self.sorted[start]);
                let mut end = start + 1;
                while end < bucket[1] && hi_of(self.sorted[end]) == hi {
                    end += 1;
                }
                let e = EdgeId::new(edges.len());
                edges.push([VertexId::new(lo), VertexId(hi)]);
                edge_offsets.push(start as u32);
                for (i, &x) in self.sorted[start..end].iter().enumerate() {
                    if let Some(&ahead) = self.sorted.get(start + i + AHEAD) {
                        let h = self.halfedge(ahead).idx();
                        crate::hint::prefetch(halfedge_edge.as_ptr().wrapping_add(h));
                        if let Some(twin) = twin.as_deref() {
                            crate::hint::prefetch(twin.as_ptr().wrapping_add(h));
                        }
                    }
                    halfedge_edge[self.halfedge(x).idx()] = e;
                }
                match (end - start, twin.as_deref_mut()) {
                    (1, _) | (2, None) => {}
                    (2, Some(twin)) => {
                        let (x0, x1) = (self.sorted[start], self.sorted[start + 1]);
                        if self.starts_low(x0, lo) != self.starts_low(x1, lo) {
                            let (h0, h1) = (self.halfedge(x0), self.halfedge(x1));
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
        edge_offsets.push(nh as u32);
        numbering
    }
}

/// The edges of a mesh, numbered as [`Connectivity::edges`] numbers them
/// (endpoint pairs, smaller first, sorted), and the edge of every half-edge
/// `3 f + k` (from corner `k` of face `f` to corner `k + 1`), without the
/// rest of the half-edge structure: for callers that only need the edge
/// numbering (midpoint subdivision), on any mesh, manifold or not. Cost
/// O(V + F).
pub fn number_edges(mesh: &crate::TriMesh) -> (Vec<[u32; 2]>, Vec<u32>) {
    let numbering = HalfedgeSort::new(mesh.vertex_count(), mesh.faces()).number(None);
    let edges = numbering.edges.into_iter().map(|[a, b]| [a.0, b.0]).collect();
    (edges, numbering.halfedge_edge.into_iter().map(|e| e.0).collect())
}

/// An outgoing half-edge of a vertex with the half-edge after it
/// counter-clockwise, `twin(prev(h))` (invalid without a twin), packed into
/// a u64 for [`par::group_by_key`].
#[derive(Clone, Copy)]
struct Spoke(u64);

impl Spoke {
    fn new(out: HalfedgeId, next: HalfedgeId) -> Self {
        Self(u64::from(out.0) | (u64::from(next.0) << 32))
    }

    #[inline]
    fn out(self) -> HalfedgeId {
        HalfedgeId(self.0 as u32)
    }

    #[inline]
    fn next(self) -> HalfedgeId {
        HalfedgeId((self.0 >> 32) as u32)
    }
}

impl From<u64> for Spoke {
    fn from(x: u64) -> Self {
        Self(x)
    }
}

impl From<Spoke> for u64 {
    fn from(s: Spoke) -> u64 {
        s.0
    }
}

/// What the fan walk of one vertex reads besides its ring.
struct Fans<'a> {
    corner_vertex: &'a [VertexId],
    halfedge_edge: &'a [EdgeId],
    edge_offsets: &'a [u32],
    edge_halfedges: &'a [HalfedgeId],
    /// Endpoints of edges with more than two faces.
    nonmanifold_edge_vertex: Vec<bool>,
    /// Endpoints of edges whose two faces disagree on their direction.
    unoriented_vertex: Vec<bool>,
}

/// Per-task buffers of [`Fans::classify`].
#[derive(Default)]
struct Scratch {
    fans_of: UnionFind,
    index: RingIndex,
}

impl Fans<'_> {
    /// The kind of vertex `v` with outgoing half-edges `ring` (with the
    /// next of each), and whether it joins several fans at none of its
    /// edges being non-manifold (a vertex of the report); its outgoing
    /// half-edges into `out`, counter-clockwise on a single fan.
    fn classify(&self, s: &mut Scratch, v: usize, ring: &[Spoke], out: &mut [HalfedgeId]) -> (VertexKind, bool) {
        let d = ring.len();
        if d == 0 {
            return (VertexKind::Isolated, false);
        }
        s.index.build(ring);
        // Fast path, almost every vertex: a consistently oriented single
        // fan, walked counter-clockwise by h -> twin(prev(h)) from its
        // boundary half-edge (no twin) if it has one.
        if !self.nonmanifold_edge_vertex[v] && !self.unoriented_vertex[v] {
            if let Some(kind) = walk_fan(ring, &s.index, out) {
                return (kind, false);
            }
        }
        for (slot, spoke) in out.iter_mut().zip(ring) {
            *slot = spoke.out();
        }
        // Otherwise union the incident faces across edges at v that have
        // exactly two faces, and count the fans.
        s.fans_of.reset(d);
        let mut on_boundary = false;
        for (i, spoke) in ring.iter().enumerate() {
            let h = spoke.out();
            for g in [h, h.prev()] {
                let e = self.halfedge_edge[g.idx()].idx();
                match self.edge_offsets[e + 1] - self.edge_offsets[e] {
                    1 => on_boundary = true,
                    2 => {
                        let pair = &self.edge_halfedges[self.edge_offsets[e] as usize..][..2];
                        let other = if pair[0] == g { pair[1] } else { pair[0] };
                        // The other face's half-edge leaving v.
                        let out = if self.corner_vertex[other.idx()].idx() == v { other } else { other.next() };
                        if let Some(j) = s.index.position(ring, out) {
                            s.fans_of.union(i as u32, j as u32);
                        }
                    }
                    _ => {}
                }
            }
        }
        let fans = (0..d as u32).filter(|&i| s.fans_of.find(i) == i).count();
        if fans > 1 || self.nonmanifold_edge_vertex[v] {
            (VertexKind::NonManifold, fans > 1 && !self.nonmanifold_edge_vertex[v])
        } else if on_boundary {
            (VertexKind::Boundary, false)
        } else {
            (VertexKind::Interior, false)
        }
    }
}

/// Whether one of `vertices` is an endpoint of one of `edges`, per vertex.
fn endpoints(vertex_count: usize, edges: &[[VertexId; 2]], of: &[EdgeId]) -> Vec<bool> {
    let mut mark = vec![false; vertex_count];
    for &e in of {
        for v in edges[e.idx()] {
            mark[v.idx()] = true;
        }
    }
    mark
}

impl Connectivity {
    /// Builds the connectivity of `faces` over `vertex_count` vertices. Indices
    /// must be in range (as [`crate::TriMesh::new`] guarantees). Cost O(V + F),
    /// on [`par`]'s threads; the result does not depend on their number.
    pub fn new(vertex_count: usize, faces: &[[u32; 3]]) -> Self {
        let corner = faces.as_flattened();
        let nh = corner.len();
        let sort = HalfedgeSort::new(vertex_count, faces);
        let mut twin = vec![HalfedgeId::INVALID; nh];
        // The numbering is one loop (see `HalfedgeSort::number`); the two
        // maps that do not need it run beside it: at 470,274 vertices on
        // two threads, the whole build with boundary loops took 67.9-70.0
        // ms against 73.6-81.4 ms with the maps after it (2026-12-05).
        let (Numbering { edges, edge_offsets, halfedge_edge, mut report }, (corner_vertex, edge_halfedges)) = par::join(
            || sort.number(Some(&mut twin)),
            || {
                let corner_vertex: Vec<VertexId> = par::map(nh, |h| VertexId(corner[h]));
                let edge_halfedges: Vec<HalfedgeId> = par::map(nh, |i| sort.halfedge(sort.sorted[i]));
                (corner_vertex, edge_halfedges)
            },
        );
        drop(sort);

        // Outgoing half-edges per vertex, each with the half-edge after it
        // counter-clockwise, twin(prev(h)): read here in face order (prev(h)
        // is in h's face), so that walking a fan reads only its own slots.
        let (vertex_offsets, rings) = par::group_by_key(
            vertex_count,
            faces.len(),
            |f| {
                let [a, b, c] = faces[f];
                [a as usize, b as usize, c as usize]
            },
            |f| {
                // Half-edge k follows half-edge k + 2 in its face.
                let (h, t) = (HalfedgeId::new(3 * f), &twin[3 * f..3 * f + 3]);
                [Spoke::new(h, t[2]), Spoke::new(h.next(), t[0]), Spoke::new(h.prev(), t[1])]
            },
        );
        let fans = Fans {
            corner_vertex: &corner_vertex,
            halfedge_edge: &halfedge_edge,
            edge_offsets: &edge_offsets,
            edge_halfedges: &edge_halfedges,
            nonmanifold_edge_vertex: endpoints(vertex_count, &edges, &report.edges),
            unoriented_vertex: endpoints(vertex_count, &edges, &report.inconsistent_edges),
        };
        // Classify each vertex by its fans and order manifold rings counter-clockwise.
        let mut vertex_out = vec![HalfedgeId::INVALID; nh];
        let kinds = par::rows_with(&mut vertex_out, &vertex_offsets, Scratch::default, |s, v, out| {
            fans.classify(s, v, &rings[vertex_offsets[v]..vertex_offsets[v + 1]], out)
        });
        drop(fans);
        drop(rings);
        report.vertices = (0..vertex_count).filter(|&v| kinds[v].1).map(VertexId::new).collect();
        let vertex_kind = kinds.into_iter().map(|(kind, _)| kind).collect();
        Self {
            corner_vertex,
            twin,
            halfedge_edge,
            edges,
            edge_offsets,
            edge_halfedges,
            vertex_offsets: vertex_offsets.into_iter().map(|o| o as u32).collect(),
            vertex_out,
            vertex_kind,
            report,
            components: OnceLock::new(),
            boundary_loops: OnceLock::new(),
        }
    }
}

/// Finds a half-edge's slot in a vertex's ring: by a linear scan in small
/// rings, by binary search in a sorted copy in large ones (so that a vertex
/// of valence `d` costs O(d log d), not O(d^2)). Comparing every slot of a
/// small ring at once instead, with no exit that depends on where the
/// half-edge is, built the dragon's full scan 8-11% faster but a mesh in
/// Loop subdivision's order 10-18% slower, whose slots the scan's exits
/// learn (one core, 2026-12-07): left out.
#[derive(Default)]
pub(super) struct RingIndex {
    /// `(half-edge, slot)` sorted, for rings above [`RingIndex::SCAN`].
    sorted: Vec<(HalfedgeId, u32)>,
}

impl RingIndex {
    /// Rings up to this size are scanned.
    pub(super) const SCAN: usize = 16;

    fn build(&mut self, ring: &[Spoke]) {
        if ring.len() > Self::SCAN {
            self.sorted.clear();
            self.sorted.extend(ring.iter().enumerate().map(|(i, s)| (s.out(), i as u32)));
            self.sorted.sort_unstable();
        }
    }

    /// The slot of `h` in `ring` (the ring [`RingIndex::build`] saw last).
    #[inline]
    fn position(&self, ring: &[Spoke], h: HalfedgeId) -> Option<usize> {
        if ring.len() <= Self::SCAN {
            ring.iter().position(|s| s.out() == h)
        } else {
            let i = self.sorted.binary_search_by_key(&h, |&(g, _)| g).ok()?;
            Some(self.sorted[i].1 as usize)
        }
    }
}

/// The ring of a vertex none of whose edges is non-manifold or inconsistently
/// oriented, each outgoing half-edge `h` with `twin(prev(h))`, in
/// counter-clockwise order into `ordered` (as long as the ring), when its
/// faces form one fan: from its boundary half-edge, the one that no
/// `twin(prev(g))` of the ring names (an open fan), or from `ring[0]` (a
/// closed fan), rotating h -> twin(prev(h)). The vertex's kind, or `None`
/// when the walk does not visit the whole ring (several fans; `ordered`
/// then holds part of a walk).
///
/// One open fan has exactly one spoke without a next, and its boundary
/// half-edge is the sum of the outgoing half-edges less the sum of the
/// nexts: found in O(d) without a branch on the ring's order, where a
/// search of the nexts for every spoke took O(d^2) and most of the walk's
/// time on meshes in a scan's or a spatial order. A wrong candidate (the
/// ring is not one fan) cannot pass the walk: a walk that visits every
/// spoke and ends without a next started at the one spoke no other names.
fn walk_fan(ring: &[Spoke], index: &RingIndex, ordered: &mut [HalfedgeId]) -> Option<VertexKind> {
    let (mut outs, mut nexts, mut ends) = (0u64, 0u64, 0usize);
    for s in ring {
        let has_next = s.next().is_valid();
        outs = outs.wrapping_add(u64::from(s.out().0));
        nexts = nexts.wrapping_add(if has_next { u64::from(s.next().0) } else { 0 });
        ends += usize::from(!has_next);
    }
    let open = match ends {
        0 => false,
        1 => true,
        _ => return None,
    };
    let first =
        if open { index.position(ring, HalfedgeId(u32::try_from(outs.wrapping_sub(nexts)).ok()?))? } else { 0 };
    let mut i = first;
    for (walked, slot) in ordered.iter_mut().enumerate() {
        *slot = ring[i].out();
        let t = ring[i].next();
        let whole = walked + 1 == ring.len();
        if !t.is_valid() {
            return (open && whole).then_some(VertexKind::Boundary);
        }
        if t == ring[first].out() {
            return (!open && whole).then_some(VertexKind::Interior);
        }
        if whole {
            return None;
        }
        i = index.position(ring, t)?;
    }
    None
}
