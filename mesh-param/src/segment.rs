//! Which faces form which chart, and each chart as a manifold mesh of its
//! own.
//!
//! By default a chart is a connected component. With a size limit, a larger
//! component is split into k = ceil(faces / limit) regions: k seeds by
//! farthest-point clustering (Gonzalez 1985) on the dual graph, each face
//! joined to its nearest seed (a geodesic Voronoi region, grown by Dijkstra
//! over centroid-to-centroid distances). Each region is connected through
//! edges, because a face's shortest-path predecessor belongs to its region.
//!
//! A set of faces of a manifold mesh may touch itself at a vertex only (two
//! fans of the region around one vertex); [`chart_pieces`] gives such a
//! vertex one copy per fan, so that every piece is a manifold.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use glam::DVec3;
use mesh_kernel::union_find::UnionFind;
use mesh_kernel::{Connectivity, FaceId, HalfedgeId, SubMesh, TriMesh, VertexId};

use crate::error::{ParamError, Result};

/// The chart of each face and the number of charts: connected components,
/// each split into ceil(faces / `max_faces`) Voronoi regions when
/// `max_faces` is given (see the module documentation). Needs a manifold
/// mesh. Cost: one Dijkstra per seed over the faces it takes (O(F log F)
/// per component when regions are even), a heap of the farthest faces, and
/// O(F) per pass of the border smoothing.
///
/// # Errors
/// `ParamError::Mesh` (`MeshError::NonManifold`) when the mesh is not an oriented manifold;
/// `ParamError::InvalidOption` (`max_chart_faces`) for `Some(0)`.
pub fn chart_labels(mesh: &TriMesh, max_faces: Option<usize>) -> Result<(Vec<u32>, usize)> {
    let conn = mesh.manifold_connectivity()?;
    let components = conn.components();
    let Some(limit) = max_faces else { return Ok((components.face_component.clone(), components.count)) };
    if limit == 0 {
        return Err(ParamError::InvalidOption { name: "max_chart_faces", reason: "must be at least 1".into() });
    }
    let dual = Dual::new(mesh, conn);
    let mut label = vec![u32::MAX; mesh.face_count()];
    let mut dist = vec![f64::INFINITY; mesh.face_count()];
    let mut count = 0u32;
    let mut members = vec![Vec::new(); components.count];
    for (f, &c) in components.face_component.iter().enumerate() {
        members[c as usize].push(f as u32);
    }
    let mut touched = Vec::new();
    for faces in &members {
        let regions = faces.len().div_ceil(limit).max(1);
        // The first seed: the face farthest from the component's first face.
        dual.grow(faces[0], u32::MAX, &mut dist, &mut label, &mut touched);
        let mut seed = faces.iter().copied().max_by(|&a, &b| dist[a as usize].total_cmp(&dist[b as usize]));
        faces.iter().for_each(|&f| dist[f as usize] = f64::INFINITY);
        // Local maxima of the distance, largest first. The farthest face is
        // one; a face becomes one only when it or a neighbour is reached
        // closer, so the faces reached and their neighbours are the only
        // ones to look at. Entries go stale as distances shrink and are
        // dropped when they come up.
        let mut far: BinaryHeap<(u64, u32)> = BinaryHeap::new();
        for _ in 0..regions {
            let Some(s) = seed else { break };
            touched.clear();
            dual.grow(s, count, &mut dist, &mut label, &mut touched);
            count += 1;
            for &f in &touched {
                for g in std::iter::once(f).chain(dual.neighbors(f)) {
                    if dual.neighbors(g).all(|h| dist[h as usize] <= dist[g as usize]) {
                        far.push((dist[g as usize].to_bits(), g));
                    }
                }
            }
            while far.peek().is_some_and(|&(d, f)| d != dist[f as usize].to_bits()) {
                far.pop();
            }
            seed = far.peek().filter(|&&(d, _)| f64::from_bits(d) > 0.0).map(|&(_, f)| f);
        }
    }
    smooth_borders(conn, &mut label, count as usize);
    Ok((label, count as usize))
}

/// Moves every face that borders another region along two of its edges
/// into that region, until none is left (at most 20 passes): a region's
/// border then has no face with all three corners on it where this can be
/// avoided, which a fixed convex boundary would flatten into a sliver. The
/// face moved has at most one neighbour in its old region, so that region
/// stays connected; a region never loses its last face. O(F) per pass.
fn smooth_borders(conn: &Connectivity, label: &mut [u32], count: usize) {
    let mut size = vec![0usize; count];
    label.iter().for_each(|&l| size[l as usize] += 1);
    for _ in 0..20 {
        let mut moved = 0;
        for f in 0..label.len() {
            let own = label[f];
            let others: Vec<u32> = conn
                .face_neighbors(FaceId::new(f))
                .into_iter()
                .flatten()
                .map(|g| label[g.idx()])
                .filter(|&l| l != own)
                .collect();
            let target = match others[..] {
                [a, b] | [a, b, _] if a == b => a,
                [_, b, c] if b == c => b,
                [a, _, c] if a == c => a,
                _ => continue,
            };
            if size[own as usize] > 1 {
                size[own as usize] -= 1;
                size[target as usize] += 1;
                label[f] = target;
                moved += 1;
            }
        }
        if moved == 0 {
            break;
        }
    }
}

/// The dual graph: for each face, the faces across its three edges
/// (`u32::MAX` for none) and the distances between centroids.
struct Dual {
    next: Vec<[u32; 3]>,
    length: Vec<[f64; 3]>,
}

impl Dual {
    fn new(mesh: &TriMesh, conn: &Connectivity) -> Self {
        let centroid = |f: usize| mesh.faces()[f].map(|v| mesh.positions()[v as usize]).iter().sum::<DVec3>() / 3.0;
        let centroids: Vec<DVec3> = (0..mesh.face_count()).map(centroid).collect();
        let next: Vec<[u32; 3]> = (0..mesh.face_count())
            .map(|f| conn.face_neighbors(FaceId::new(f)).map(|g| g.map_or(u32::MAX, |g| g.0)))
            .collect();
        let length = next
            .iter()
            .enumerate()
            .map(|(f, n)| n.map(|g| if g == u32::MAX { 0.0 } else { centroids[f].distance(centroids[g as usize]) }))
            .collect();
        Self { next, length }
    }

    /// The faces across the edges of `f`.
    fn neighbors(&self, f: u32) -> impl Iterator<Item = u32> + '_ {
        self.next[f as usize].into_iter().filter(|&g| g != u32::MAX)
    }

    /// Dijkstra from `seed`: every face reached closer than before takes
    /// `label` and the new distance, and is listed in `touched`. O(n log n)
    /// for the n faces it takes.
    fn grow(&self, seed: u32, label: u32, dist: &mut [f64], labels: &mut [u32], touched: &mut Vec<u32>) {
        let mut heap = BinaryHeap::new();
        dist[seed as usize] = 0.0;
        labels[seed as usize] = label;
        touched.push(seed);
        heap.push(Reverse((0u64, seed)));
        while let Some(Reverse((bits, f))) = heap.pop() {
            let d = f64::from_bits(bits);
            if d > dist[f as usize] {
                continue;
            }
            for (&g, &l) in self.next[f as usize].iter().zip(&self.length[f as usize]) {
                if g == u32::MAX {
                    continue;
                }
                let nd = d + l;
                if nd < dist[g as usize] {
                    dist[g as usize] = nd;
                    labels[g as usize] = label;
                    touched.push(g);
                    // Non-negative floats order like their bit patterns.
                    heap.push(Reverse((nd.to_bits(), g)));
                }
            }
        }
    }
}

/// Each chart (faces with the same label, `labels[f] < count`) as a mesh of
/// its own, in label order, with its faces in input order and its vertices
/// in order of first use. A vertex gets one copy per fan of the chart's
/// faces around it (corners joined across edges inside the chart, union-find),
/// so every piece is a manifold when the input is. O(F α(F)).
///
/// # Errors
/// `ParamError::Mesh` (`MeshError::NonManifold`) when the mesh is not an oriented manifold,
/// (`MeshError::Dimension`) when `labels` does not have one entry per face or a label is not below `count`.
pub fn chart_pieces(mesh: &TriMesh, labels: &[u32], count: usize) -> Result<Vec<SubMesh>> {
    let conn = mesh.manifold_connectivity()?;
    if labels.len() != mesh.face_count() || labels.iter().any(|&l| l as usize >= count) {
        return Err(mesh_kernel::MeshError::Dimension(format!(
            "{} labels below {count} for {} faces",
            labels.len(),
            mesh.face_count()
        ))
        .into());
    }
    let mut corners = UnionFind::new(3 * mesh.face_count());
    for f in 0..mesh.face_count() {
        for k in 0..3 {
            let Some(twin) = conn.twin(HalfedgeId::of_corner(FaceId::new(f), k)) else { continue };
            let g = twin.face().idx();
            if g < f || labels[g] != labels[f] {
                continue;
            }
            // h runs corner k -> k + 1 of f; its twin corner j -> j + 1 of g.
            let j = twin.corner();
            corners.union((3 * f + k) as u32, (3 * g + (j + 1) % 3) as u32);
            corners.union((3 * f + (k + 1) % 3) as u32, (3 * g + j) as u32);
        }
    }
    let mut pieces: Vec<Piece> = vec![Default::default(); count];
    let mut local = vec![u32::MAX; 3 * mesh.face_count()];
    for (f, tri) in mesh.faces().iter().enumerate() {
        let (faces, vertices, tris) = &mut pieces[labels[f] as usize];
        let corners = [0, 1, 2].map(|k| {
            let root = corners.find((3 * f + k) as u32) as usize;
            if local[root] == u32::MAX {
                local[root] = vertices.len() as u32;
                vertices.push(VertexId(tri[k]));
            }
            local[root]
        });
        faces.push(FaceId::new(f));
        tris.push(corners);
    }
    pieces
        .into_iter()
        .map(|(faces, vertices, tris)| {
            let positions = vertices.iter().map(|&v| mesh.position(v)).collect();
            Ok(SubMesh { mesh: TriMesh::new(positions, tris)?, vertices, faces })
        })
        .collect()
}

/// A piece being built: its input faces, input vertex of each new vertex,
/// triangles over the new vertices.
type Piece = (Vec<FaceId>, Vec<VertexId>, Vec<[u32; 3]>);

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::shapes;

    #[test]
    fn components_are_the_default_charts() {
        let m = shapes::torus(2.0, 0.5, 12, 6).unwrap();
        let (labels, count) = chart_labels(&m, None).unwrap();
        assert_eq!(count, 1);
        let pieces = chart_pieces(&m, &labels, count).unwrap();
        assert_eq!(pieces[0].mesh.vertex_count(), m.vertex_count());
        assert_eq!(pieces[0].mesh.face_count(), m.face_count());
    }

    #[test]
    fn regions_are_connected_manifold_and_bounded() {
        let m = shapes::icosphere(4).unwrap();
        let limit = 500;
        let (labels, count) = chart_labels(&m, Some(limit)).unwrap();
        assert_eq!(count, m.face_count().div_ceil(limit));
        let pieces = chart_pieces(&m, &labels, count).unwrap();
        let mut sizes: Vec<usize> = pieces.iter().map(|p| p.mesh.face_count()).collect();
        sizes.sort_unstable();
        assert_eq!(sizes.iter().sum::<usize>(), m.face_count());
        // Farthest-point regions are of similar size on an even mesh.
        assert!(sizes[count - 1] < 3 * sizes[0], "{sizes:?}");
        for p in &pieces {
            let conn = p.mesh.manifold_connectivity().unwrap();
            assert_eq!(conn.components().count, 1);
            for (v, &parent) in p.vertices.iter().enumerate() {
                assert_eq!(p.mesh.positions()[v], m.position(parent));
            }
        }
    }

    #[test]
    fn a_region_touching_itself_at_a_vertex_gets_two_copies() {
        // A fan of 6 triangles around vertex 0; faces 0 and 3 (opposite) form
        // one chart that meets only at the centre.
        let mut p = vec![DVec3::ZERO];
        p.extend((0..6).map(|k| DVec3::from((glam::DVec2::from_angle(k as f64), 0.0))));
        let f: Vec<[u32; 3]> = (0..6).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
        let m = TriMesh::new(p, f).unwrap();
        let labels = [0, 1, 1, 0, 2, 2];
        let pieces = chart_pieces(&m, &labels, 3).unwrap();
        assert_eq!(pieces[0].mesh.vertex_count(), 6);
        assert!(pieces[0].mesh.manifold_connectivity().is_ok());
        assert_eq!(pieces[1].mesh.vertex_count(), 4);
        assert!(chart_pieces(&m, &[0, 1], 3).is_err());
        assert!(chart_labels(&m, Some(0)).is_err());
    }
}
