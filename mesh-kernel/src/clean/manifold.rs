//! Turning any triangle soup into an oriented 2-manifold, the repair a scan
//! needs before parameterization or any algorithm that walks half-edges.
//!
//! Three defects are resolved, each by cutting, never by moving a vertex:
//!
//! 1. **Fins**: an edge with three or more faces keeps the pair of faces
//!    that continue each other best (opposite directions along the edge,
//!    most aligned normals) and the other faces are detached from it.
//! 2. **Unorientable gluing**: faces are oriented breadth-first across the
//!    kept pairs; a pair whose orientations cannot agree (a Moebius-like
//!    cycle) is cut open.
//! 3. **Non-manifold vertices**: the corners around each vertex are grouped
//!    into fans (corners joined across kept edges) and every fan but the first
//!    gets its own copy of the vertex.
//!
//! Each pass is O(F). A cut through the interior of a surface splits no
//! vertex and so leaves its edge shared; the faces of such leftovers are
//! isolated (three vertices of their own) in the next pass, which can then
//! only leave vertices with several fans, split by the pass after it.

use glam::DVec3;

use crate::connectivity::Connectivity;
use crate::error::{MeshError, Result};
use crate::ids::{EdgeId, FaceId, HalfedgeId};
use crate::mesh::TriMesh;
use crate::union_find::UnionFind;

/// Passes of glue, orient and split. The first resolves every defect but
/// cuts that split no vertex; the second isolates the faces of those (after
/// which nothing is glued inconsistently), so the third always ends manifold.
const MAX_PASSES: usize = 4;

/// At most this many faces of one fin edge are compared pairwise (bounds the
/// cost on hostile input where thousands of faces share one edge).
const PAIR_CANDIDATES: usize = 16;

/// What [`make_manifold`] changed.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub(crate) struct ManifoldCounts {
    /// Edges that had three or more faces.
    pub fin_edges: usize,
    /// Faces detached from a fin edge whose best pair they were not, or
    /// isolated because a cut could not be made otherwise.
    pub detached_faces: usize,
    /// Edges cut open so that every component can be oriented.
    pub cut_edges: usize,
    /// Vertex copies added so that every vertex has a single fan (including
    /// the three of each isolated face).
    pub split_vertices: usize,
    /// Which faces were flipped to agree with their neighbours.
    pub flipped: Vec<bool>,
}

/// The half-edge glued across each half-edge (`INVALID`: boundary or cut).
type Gluing = Vec<HalfedgeId>;

/// Makes `(positions, faces)` an oriented manifold (see the module docs).
/// The faces must not repeat a vertex and indices must be in range.
pub(crate) fn make_manifold(
    positions: Vec<DVec3>,
    faces: Vec<[u32; 3]>,
) -> Result<(Vec<DVec3>, Vec<[u32; 3]>, ManifoldCounts)> {
    let mut counts = ManifoldCounts { flipped: vec![false; faces.len()], ..ManifoldCounts::default() };
    let mut mesh = TriMesh::new(positions, faces)?;
    for pass in 0..MAX_PASSES {
        if mesh.connectivity().is_manifold() {
            let (p, f) = mesh.into_parts();
            return Ok((p, f, counts));
        }
        if pass > 0 {
            mesh = isolate_faces_on_bad_edges(mesh, &mut counts)?;
        }
        let conn = mesh.connectivity();
        let mut across = glue(&mesh, conn, &mut counts);
        let flip = orient_cutting(conn, &mut across, &mut counts);
        let (p, mut f) = split_fans(&mesh, &across, &mut counts);
        for ((tri, &flip), flipped) in f.iter_mut().zip(&flip).zip(&mut counts.flipped) {
            if flip {
                tri.swap(1, 2);
                *flipped = !*flipped;
            }
        }
        mesh = TriMesh::new(p, f)?;
    }
    Err(MeshError::Degenerate(format!(
        "manifold repair left defects after {MAX_PASSES} passes: {}",
        mesh.connectivity().non_manifold_report()
    )))
}

/// Gives every face on an edge that is still shared by more than two faces,
/// or by two faces running the same way, three vertices of its own (the
/// first pair, respectively the first face, stays).
fn isolate_faces_on_bad_edges(mesh: TriMesh, counts: &mut ManifoldCounts) -> Result<TriMesh> {
    let conn = mesh.connectivity();
    let report = conn.non_manifold_report();
    let mut isolate: Vec<FaceId> = report.edges.iter().flat_map(|&e| conn.edge_faces(e).skip(2)).collect();
    isolate.extend(report.inconsistent_edges.iter().flat_map(|&e| conn.edge_faces(e).skip(1)));
    isolate.sort_unstable();
    isolate.dedup();
    counts.detached_faces += isolate.len();
    counts.split_vertices += 3 * isolate.len();
    let (mut p, mut f) = mesh.into_parts();
    for face in isolate {
        for k in 0..3 {
            p.push(p[f[face.idx()][k] as usize]);
            f[face.idx()][k] = (p.len() - 1) as u32;
        }
    }
    TriMesh::new(p, f)
}

/// Chooses which faces are glued across every edge: both faces of a
/// two-face edge; the best pair of a fin edge ([`pair_score`]).
fn glue(mesh: &TriMesh, conn: &Connectivity, counts: &mut ManifoldCounts) -> Gluing {
    let mut across = vec![HalfedgeId::INVALID; conn.halfedge_count()];
    let normals: Vec<DVec3> = mesh
        .face_ids()
        .map(|f| {
            let [a, b, c] = mesh.triangle(f);
            crate::geometry::unit_vector((b - a).cross(c - a))
        })
        .collect();
    for e in 0..conn.edge_count() {
        let hs = conn.edge_halfedges(EdgeId::new(e));
        let pair = match hs.len() {
            0 | 1 => continue,
            2 => (hs[0], hs[1]),
            k => {
                counts.fin_edges += 1;
                counts.detached_faces += k - 2;
                let candidates = &hs[..k.min(PAIR_CANDIDATES)];
                let mut best = (f64::NEG_INFINITY, candidates[0], candidates[1]);
                for (i, &h) in candidates.iter().enumerate() {
                    for &g in &candidates[i + 1..] {
                        let s = pair_score(conn, &normals, h, g);
                        if s > best.0 {
                            best = (s, h, g);
                        }
                    }
                }
                (best.1, best.2)
            }
        };
        across[pair.0.idx()] = pair.1;
        across[pair.1.idx()] = pair.0;
    }
    across
}

/// How well two faces sharing an edge continue each other: the cosine
/// between their normals as they would be once consistently oriented, less
/// 2 when they run the same way along the edge (one would have to flip).
fn pair_score(conn: &Connectivity, normals: &[DVec3], h: HalfedgeId, g: HalfedgeId) -> f64 {
    let (nh, ng) = (normals[h.face().idx()], normals[g.face().idx()]);
    if conn.origin(h) == conn.origin(g) {
        -nh.dot(ng) - 2.0
    } else {
        nh.dot(ng)
    }
}

/// Orients faces breadth-first across glued pairs; a glued pair whose
/// orientations disagree with what the search already fixed is cut.
/// Returns which faces to flip.
fn orient_cutting(conn: &Connectivity, across: &mut Gluing, counts: &mut ManifoldCounts) -> Vec<bool> {
    let nf = conn.face_count();
    let mut flip = vec![false; nf];
    let mut seen = vec![false; nf];
    let mut queue = Vec::new();
    for seed in 0..nf {
        if std::mem::replace(&mut seen[seed], true) {
            continue;
        }
        queue.push(seed);
        while let Some(f) = queue.pop() {
            for k in 0..3 {
                let h = HalfedgeId::of_corner(FaceId::new(f), k);
                let g = across[h.idx()];
                if !g.is_valid() {
                    continue;
                }
                let nb = g.face().idx();
                let want = flip[f] ^ (conn.origin(g) == conn.origin(h));
                if !std::mem::replace(&mut seen[nb], true) {
                    flip[nb] = want;
                    queue.push(nb);
                } else if flip[nb] != want {
                    across[h.idx()] = HalfedgeId::INVALID;
                    across[g.idx()] = HalfedgeId::INVALID;
                    counts.cut_edges += 1;
                }
            }
        }
    }
    flip
}

/// Gives every fan of corners around a vertex its own vertex: corners of two
/// glued faces at a shared endpoint are one fan (union-find over the 3 F
/// corners). The first fan of a vertex keeps its index, the others are
/// appended. Cost O(F alpha(F)).
fn split_fans(mesh: &TriMesh, across: &Gluing, counts: &mut ManifoldCounts) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let faces = mesh.faces();
    let mut corners = UnionFind::new(3 * faces.len());
    let corner_of = |f: usize, v: u32| faces[f].iter().position(|&x| x == v).map(|k| (3 * f + k) as u32);
    for (h, &g) in across.iter().enumerate() {
        if !g.is_valid() || g.idx() < h {
            continue;
        }
        let (fh, fg) = (h / 3, g.face().idx());
        let tri = faces[fh];
        for v in [tri[h % 3], tri[(h + 1) % 3]] {
            if let (Some(a), Some(b)) = (corner_of(fh, v), corner_of(fg, v)) {
                corners.union(a, b);
            }
        }
    }
    let mut positions = mesh.positions().to_vec();
    let mut first_root = vec![u32::MAX; positions.len()];
    let mut new_vertex = vec![u32::MAX; corners.len()];
    let mut out = faces.to_vec();
    for c in 0..corners.len() {
        let root = corners.find(c as u32) as usize;
        let v = faces[c / 3][c % 3];
        if new_vertex[root] == u32::MAX {
            new_vertex[root] = if first_root[v as usize] == u32::MAX {
                first_root[v as usize] = root as u32;
                v
            } else {
                counts.split_vertices += 1;
                positions.push(positions[v as usize]);
                (positions.len() - 1) as u32
            };
        }
        out[c / 3][c % 3] = new_vertex[root];
    }
    (positions, out)
}
