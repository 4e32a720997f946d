//! A lean half-edge structure for the inner loops of subdivision and of the
//! filter-bank setup: twins, edges in sorted order, counter-clockwise
//! outgoing half-edges, vertex kinds.
//!
//! It holds a subset of [`mesh_kernel::Connectivity`] and numbers edges and
//! half-edges the same way (half-edge `3f + k` leaves corner k of face f;
//! edges sorted by (smaller, larger) endpoint), but is built about three
//! times faster, because it keeps only what subdivision needs and finds twins
//! by scanning the (small) outgoing lists instead of sorting all half-edges.
//! One level of Loop subdivision must beat libigl by 5x, and building
//! `Connectivity` alone takes more than that budget. On any manifold defect
//! it gives up, and callers ask `mesh_kernel` for the precise report.

use std::borrow::Cow;

use mesh_kernel::{Connectivity, MeshError};

use crate::error::{Result, WaveletError};

/// Builds the topology, or the precise [`MeshError::NonManifold`] report of
/// `mesh_kernel` when the mesh is not an oriented 2-manifold. Cost O(V + F).
pub(crate) fn manifold_topology(n: usize, faces: &[[u32; 3]]) -> Result<Topology<'_>> {
    Topology::new(n, faces).map_err(|NotManifold| match Connectivity::new(n, faces).require_manifold() {
        Err(e) => WaveletError::Mesh(e),
        Ok(()) => WaveletError::Mesh(MeshError::Topology {
            expected: "an oriented 2-manifold".into(),
            found: "a vertex or edge the half-edge build rejected".into(),
        }),
    })
}

/// Marks "no half-edge" (the twin of a boundary half-edge).
pub(crate) const NONE: u32 = u32::MAX;

/// What a vertex's neighbourhood looks like (manifold meshes only).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// Referenced by no face.
    Isolated,
    /// One closed fan.
    Interior,
    /// One open fan.
    Boundary,
}

/// Half-edge topology of an oriented 2-manifold triangle mesh; the corner
/// array is the face list itself (borrowed) or a copy.
#[derive(Debug, Clone)]
pub(crate) struct Topology<'a> {
    corner: Cow<'a, [u32]>,
    twin: Vec<u32>,
    edge_of: Vec<u32>,
    edges: Vec<[u32; 2]>,
    edge_he: Vec<u32>,
    out_start: Vec<u32>,
    out: Vec<u32>,
    kind: Vec<Kind>,
}

/// The mesh is not an oriented 2-manifold (details from `mesh_kernel`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct NotManifold;

#[inline]
fn next(h: u32) -> u32 {
    if h % 3 == 2 {
        h - 2
    } else {
        h + 1
    }
}

#[inline]
fn prev(h: u32) -> u32 {
    if h.is_multiple_of(3) {
        h + 2
    } else {
        h - 1
    }
}

impl<'a> Topology<'a> {
    /// Builds the topology of `faces` over `n` vertices (indices in range).
    /// Cost O(V + F).
    pub(crate) fn new(n: usize, faces: &'a [[u32; 3]]) -> std::result::Result<Self, NotManifold> {
        let corner = faces.as_flattened();
        let nh = corner.len();
        // Outgoing half-edges by origin (counting sort), with their
        // destinations alongside so that the scans below stay sequential.
        let mut out_start = vec![0u32; n + 1];
        for &v in corner {
            out_start[v as usize + 1] += 1;
        }
        for v in 0..n {
            out_start[v + 1] += out_start[v];
        }
        // Scatter with out_start[v] as the fill pointer of v, then shift back.
        let mut out = vec![0u32; nh];
        let mut out_dest = vec![0u32; nh];
        for h in 0..nh {
            let v = corner[h] as usize;
            let p = out_start[v] as usize;
            out[p] = h as u32;
            out_dest[p] = corner[next(h as u32) as usize];
            out_start[v] += 1;
        }
        for v in (1..=n).rev() {
            out_start[v] = out_start[v - 1];
        }
        out_start[0] = 0;
        let range = |v: u32| out_start[v as usize] as usize..out_start[v as usize + 1] as usize;
        // One pass over the vertices u in order. Twins are searched from the
        // smaller endpoint: u -> v (v > u) among the outgoing half-edges of v.
        // The edges (u, w) with w > u are those of the half-edges u -> w and
        // of the incoming w -> u (prev of an outgoing one), deduplicated, so
        // boundary edges entering u are found too. Two half-edges u -> v, or
        // two v -> u, mean a non-manifold edge or inconsistent orientation:
        // they show up as a repeated bucket entry at the smaller endpoint.
        let mut twin = vec![NONE; nh];
        let mut edge_of = vec![NONE; nh];
        let mut edges = Vec::with_capacity(nh / 2 + 1);
        let mut edge_he = Vec::with_capacity(nh / 2 + 1);
        let mut bucket: Vec<(u32, u32, u32)> = Vec::new();
        for u in 0..n as u32 {
            let ru = range(u);
            bucket.clear();
            for p in ru.clone() {
                let (h, v) = (out[p], out_dest[p]);
                if v > u {
                    let mut found = NONE;
                    for q in range(v) {
                        if out_dest[q] == u {
                            if found != NONE {
                                return Err(NotManifold);
                            }
                            found = out[q];
                        }
                    }
                    twin[h as usize] = found;
                    if found != NONE {
                        twin[found as usize] = h;
                    }
                    bucket.push((v, 0, h));
                }
                let g = prev(h);
                let w = corner[g as usize];
                if w > u {
                    bucket.push((w, 1, g));
                }
            }
            if bucket.len() > 1 {
                bucket.sort_unstable();
            }
            let mut last = (NONE, 0);
            for &(hi, kind, h) in &bucket {
                if (hi, kind) == last {
                    // Two half-edges u -> hi, or two hi -> u.
                    return Err(NotManifold);
                }
                let repeat = hi == last.0;
                last = (hi, kind);
                if repeat {
                    continue;
                }
                let e = edges.len() as u32;
                edges.push([u, hi]);
                edge_he.push(h);
                edge_of[h as usize] = e;
                if twin[h as usize] != NONE {
                    edge_of[twin[h as usize] as usize] = e;
                }
            }
        }
        if edge_of.contains(&NONE) {
            return Err(NotManifold);
        }
        drop(out_dest);
        let corner = Cow::Borrowed(corner);
        let mut topo = Self { corner, twin, edge_of, edges, edge_he, out_start, out, kind: vec![Kind::Isolated; n] };
        topo.order_fans()?;
        Ok(topo)
    }

    /// The same topology owning its corner array.
    pub(crate) fn into_owned(self) -> Topology<'static> {
        Topology {
            corner: Cow::Owned(self.corner.into_owned()),
            twin: self.twin,
            edge_of: self.edge_of,
            edges: self.edges,
            edge_he: self.edge_he,
            out_start: self.out_start,
            out: self.out,
            kind: self.kind,
        }
    }

    /// Orders each vertex's outgoing half-edges counter-clockwise (from the
    /// boundary one on the boundary) and checks that they form one fan.
    fn order_fans(&mut self) -> std::result::Result<(), NotManifold> {
        let mut ordered = Vec::new();
        for v in 0..self.kind.len() {
            let range = self.out_start[v] as usize..self.out_start[v + 1] as usize;
            let ring = &self.out[range.clone()];
            let d = ring.len();
            if d == 0 {
                continue;
            }
            let mut boundary = ring.iter().filter(|&&h| self.twin[h as usize] == NONE);
            let start = match (boundary.next(), boundary.next()) {
                (Some(&h), None) => {
                    self.kind[v] = Kind::Boundary;
                    h
                }
                (None, _) => {
                    self.kind[v] = Kind::Interior;
                    ring[0]
                }
                _ => return Err(NotManifold),
            };
            ordered.clear();
            let mut h = start;
            loop {
                ordered.push(h);
                let t = self.twin[prev(h) as usize];
                if t == NONE || t == start || ordered.len() > d {
                    break;
                }
                h = t;
            }
            if ordered.len() != d {
                return Err(NotManifold);
            }
            self.out[range].copy_from_slice(&ordered);
        }
        Ok(())
    }

    /// Number of vertices.
    #[inline]
    pub(crate) fn vertex_count(&self) -> usize {
        self.kind.len()
    }

    /// Number of faces.
    #[inline]
    pub(crate) fn face_count(&self) -> usize {
        self.corner.len() / 3
    }

    /// Where half-edge `h` starts.
    #[inline]
    pub(crate) fn origin(&self, h: u32) -> u32 {
        self.corner[h as usize]
    }

    /// Where half-edge `h` ends.
    #[inline]
    pub(crate) fn dest(&self, h: u32) -> u32 {
        self.corner[next(h) as usize]
    }

    /// The vertex of `h`'s face opposite to it.
    #[inline]
    pub(crate) fn opposite(&self, h: u32) -> u32 {
        self.corner[prev(h) as usize]
    }

    /// The twin half-edge, `None` on the boundary.
    #[inline]
    pub(crate) fn twin(&self, h: u32) -> Option<u32> {
        let t = self.twin[h as usize];
        (t != NONE).then_some(t)
    }

    /// Next half-edge around the face.
    #[inline]
    pub(crate) fn next(h: u32) -> u32 {
        next(h)
    }

    /// Previous half-edge around the face.
    #[inline]
    pub(crate) fn prev(h: u32) -> u32 {
        prev(h)
    }

    /// Outgoing half-edges of `v`, counter-clockwise, starting at the
    /// boundary one on the boundary.
    #[inline]
    pub(crate) fn out(&self, v: u32) -> &[u32] {
        &self.out[self.out_start[v as usize] as usize..self.out_start[v as usize + 1] as usize]
    }

    /// Kind of vertex `v`.
    #[inline]
    pub(crate) fn kind(&self, v: u32) -> Kind {
        self.kind[v as usize]
    }

    /// Number of neighbours of `v`.
    #[inline]
    pub(crate) fn valence(&self, v: u32) -> usize {
        let d = self.out(v).len();
        if self.kind(v) == Kind::Boundary {
            d + 1
        } else {
            d
        }
    }

    /// Neighbours of `v` counter-clockwise (boundary: from one boundary
    /// neighbour to the other), appended to `ring` after clearing it.
    pub(crate) fn ring_into(&self, v: u32, ring: &mut Vec<u32>) {
        ring.clear();
        let out = self.out(v);
        ring.extend(out.iter().map(|&h| self.dest(h)));
        if self.kind(v) == Kind::Boundary {
            if let Some(&h) = out.last() {
                ring.push(self.opposite(h));
            }
        }
    }

    /// Edges as (smaller, larger) endpoints, sorted.
    #[inline]
    pub(crate) fn edges(&self) -> &[[u32; 2]] {
        &self.edges
    }

    /// Number of edges.
    #[inline]
    pub(crate) fn edge_count(&self) -> usize {
        self.edges.len()
    }

    /// The edge of half-edge `h`.
    #[inline]
    pub(crate) fn edge(&self, h: u32) -> u32 {
        self.edge_of[h as usize]
    }

    /// The vertices opposite edge `e` (one on the boundary, else two).
    pub(crate) fn edge_opposites(&self, e: u32, out: &mut Vec<u32>) {
        out.clear();
        let h = self.edge_he[e as usize];
        out.push(self.opposite(h));
        if let Some(t) = self.twin(h) {
            out.push(self.opposite(t));
        }
    }

    /// The three edges of face `f`, edge k from corner k to corner k + 1.
    #[inline]
    pub(crate) fn face_edges(&self, f: usize) -> [u32; 3] {
        [self.edge_of[3 * f], self.edge_of[3 * f + 1], self.edge_of[3 * f + 2]]
    }

    /// The edge between `a` and `b`, if any. Cost O(valence).
    pub(crate) fn find_edge(&self, a: u32, b: u32) -> Option<u32> {
        let through = |from: u32, to: u32| self.out(from).iter().find(|&&h| self.dest(h) == to).copied();
        through(a, b).or_else(|| through(b, a)).map(|h| self.edge(h))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::{shapes, VertexId, VertexKind};

    fn same_as_connectivity(mesh: &mesh_kernel::TriMesh) {
        let t = Topology::new(mesh.vertex_count(), mesh.faces()).unwrap();
        let c = mesh.connectivity();
        let edges: Vec<[u32; 2]> = c.edges().iter().map(|e| [e[0].0, e[1].0]).collect();
        assert_eq!(t.edges(), &edges[..]);
        for f in 0..mesh.face_count() {
            assert_eq!(t.face_edges(f), c.face_edges(mesh_kernel::FaceId::new(f)).map(|e| e.0));
        }
        let mut ring = Vec::new();
        for v in 0..mesh.vertex_count() as u32 {
            let kind = match c.vertex_kind(VertexId(v)) {
                VertexKind::Interior => Kind::Interior,
                VertexKind::Boundary => Kind::Boundary,
                _ => Kind::Isolated,
            };
            assert_eq!(t.kind(v), kind);
            assert_eq!(t.valence(v), c.valence(VertexId(v)));
            t.ring_into(v, &mut ring);
            let theirs: Vec<u32> = c.neighbors(VertexId(v)).map(|w| w.0).collect();
            // Same cyclic order (interior rings may start elsewhere).
            if let Some(p) = theirs.iter().position(|&w| Some(&w) == ring.first()) {
                let mut rotated = theirs.clone();
                rotated.rotate_left(p);
                assert_eq!(ring, rotated, "ring of v{v}");
            } else {
                assert!(ring.is_empty() && theirs.is_empty());
            }
        }
    }

    #[test]
    fn agrees_with_mesh_kernel() {
        same_as_connectivity(&shapes::icosphere(2).unwrap());
        same_as_connectivity(&shapes::disk(4, 3).unwrap());
        same_as_connectivity(&shapes::cylinder(1.0, 1.0, 7, 3).unwrap());
        same_as_connectivity(&shapes::grid(1.0, 1.0, 3, 2).unwrap());
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(400))]

        /// On random triangle soups (mostly non-manifold) the lean build
        /// accepts exactly what mesh-kernel calls an oriented manifold, and then
        /// agrees with it.
        #[test]
        fn agrees_with_mesh_kernel_on_random_soups(
            n in 3usize..9,
            raw in proptest::collection::vec((0u32..9, 0u32..9, 0u32..9), 1..14),
        ) {
            let faces: Vec<[u32; 3]> = raw
                .into_iter()
                .map(|(a, b, c)| [a % n as u32, b % n as u32, c % n as u32])
                .filter(|&[a, b, c]| a != b && b != c && a != c)
                .collect();
            proptest::prop_assume!(!faces.is_empty());
            let mesh = mesh_kernel::TriMesh::new(vec![mesh_kernel::glam::DVec3::ZERO; n], faces.clone()).unwrap();
            let manifold = mesh.connectivity().is_manifold();
            let ours = Topology::new(n, &faces);
            proptest::prop_assert_eq!(ours.is_ok(), manifold, "{:?}", faces);
            if manifold {
                same_as_connectivity(&mesh);
            }
        }
    }

    #[test]
    fn rejects_non_manifold() {
        // Three faces on one edge.
        assert!(Topology::new(5, &[[0, 1, 2], [1, 0, 3], [0, 1, 4]]).is_err());
        // Bow-tie.
        assert!(Topology::new(5, &[[0, 1, 2], [0, 3, 4]]).is_err());
        // Inconsistent orientation.
        assert!(Topology::new(4, &[[0, 1, 2], [0, 3, 2]]).is_err());
        // Two closed fans at vertex 0 (two tetrahedra sharing a vertex).
        let two = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2], [0, 5, 4], [0, 4, 6], [4, 5, 6], [0, 6, 5]];
        assert!(Topology::new(7, &two).is_err());
    }
}
