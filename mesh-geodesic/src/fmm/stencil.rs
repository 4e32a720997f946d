//! Preprocessing of Fast Marching: the local stencils of every triangle
//! corner, with obtuse corners split into virtual acute triangles by
//! unfolding (Kimmel and Sethian 1998), and the per-vertex Gaussian
//! curvature that the curved-front update needs.

use mesh_core::glam::{DVec2, DVec3};
use mesh_core::{Connectivity, FaceId, HalfedgeId, TriMesh, VertexId, VertexKind};

/// Relative tolerance below which a corner counts as degenerate.
const DEGENERATE: f64 = 1e-12;

/// An accepted vertex may update its target along their (real or virtual)
/// common edge.
pub(crate) const EDGE: u8 = 1;
/// Triangle update once the other known vertex is accepted too.
pub(crate) const TRIANGLE: u8 = 2;

/// A local stencil seen from one of its two known vertices `v`: the target
/// `x`, the other known vertex `o`, and the Gram matrix of `e_v = v - x` and
/// `e_o = o - x` (in the unfolded plane for virtual triangles).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Entry {
    pub target: u32,
    pub other: u32,
    pub g_self: f64,
    pub g_other: f64,
    pub g_dot: f64,
    pub flags: u8,
}

/// Statistics of the preprocessing of a [`super::FastMarching`] object.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FmmStats {
    /// Triangle corners with an angle above 90 degrees.
    pub obtuse_corners: usize,
    /// Obtuse corners split into two virtual acute triangles.
    pub split_corners: usize,
    /// Corners of zero-area triangles (edge updates only).
    pub degenerate_corners: usize,
}

/// Per-vertex stencils in compressed rows: the stencils vertex `v` takes
/// part in as a known vertex are `entries[offsets[v]..offsets[v + 1]]`.
#[derive(Debug, Clone)]
pub(crate) struct Stencils {
    pub offsets: Vec<u32>,
    pub entries: Vec<Entry>,
    pub stats: FmmStats,
    /// Gaussian curvature per vertex (zeros unless asked for).
    pub curvature: Vec<f64>,
}

impl Stencils {
    /// Builds the stencils of every corner: its own triangle, and when the
    /// angle there is obtuse and `split` holds, two virtual acute triangles
    /// through the vertex found by unfolding. Two passes over the corners
    /// (count, then fill in place), O(F) plus the unfolding.
    pub fn new(mesh: &TriMesh, split: bool, max_unfold: usize, curvature: bool) -> Self {
        let conn = mesh.connectivity();
        let p = mesh.positions();
        let n = mesh.vertex_count();
        let mut stats = FmmStats::default();
        // Angle sums and barycentric areas for the curvature, from the same
        // Gram matrices.
        let (mut angle_sum, mut area) = if curvature { (vec![0.0; n], vec![0.0; n]) } else { (Vec::new(), Vec::new()) };
        // Pass 1: classify corners, unfold the obtuse ones, count entries.
        let mut offsets = vec![0u32; n + 1];
        let mut virtual_stencils: Vec<(u32, [u32; 2], [f64; 2], f64)> = Vec::new();
        for f in mesh.face_ids() {
            let tri = mesh.faces()[f.idx()];
            for k in 0..3 {
                let (x, x1, x2) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
                offsets[x1 as usize + 1] += 1;
                offsets[x2 as usize + 1] += 1;
                let [g11, g22, g12] = gram(p, x, x1, x2);
                let det = g11 * g22 - g12 * g12;
                if curvature {
                    let root = det.max(0.0).sqrt();
                    angle_sum[x as usize] += root.atan2(g12);
                    area[x as usize] += root / 6.0;
                }
                if !(det > DEGENERATE * g11 * g22) {
                    stats.degenerate_corners += 1;
                } else if g12 < 0.0 {
                    stats.obtuse_corners += 1;
                    let found = if split { split_obtuse(conn, p, f, k, max_unfold) } else { None };
                    if let Some((c, q)) = found {
                        stats.split_corners += 1;
                        let l1 = g11.sqrt();
                        let (q1, q2) = (DVec2::new(l1, 0.0), DVec2::new(g12 / l1, det.sqrt() / l1));
                        let gc = q.length_squared();
                        virtual_stencils.push((x, [x1, c.0], [g11, gc], q1.dot(q)));
                        virtual_stencils.push((x, [c.0, x2], [gc, g22], q.dot(q2)));
                        for v in [x1, c.0, c.0, x2] {
                            offsets[v as usize + 1] += 1;
                        }
                    }
                }
            }
        }
        for v in 0..n {
            offsets[v + 1] += offsets[v];
        }
        // Pass 2: fill each vertex's bucket.
        let mut fill: Vec<u32> = offsets[..n].to_vec();
        let blank = Entry { target: 0, other: 0, g_self: 0.0, g_other: 0.0, g_dot: 0.0, flags: 0 };
        let mut entries = vec![blank; offsets[n] as usize];
        let mut put = |x: u32, [v1, v2]: [u32; 2], [g1, g2]: [f64; 2], g12: f64, flags: u8| {
            for (v, other, g_self, g_other) in [(v1, v2, g1, g2), (v2, v1, g2, g1)] {
                entries[fill[v as usize] as usize] = Entry { target: x, other, g_self, g_other, g_dot: g12, flags };
                fill[v as usize] += 1;
            }
        };
        for tri in mesh.faces() {
            for k in 0..3 {
                let (x, x1, x2) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
                let [g11, g22, g12] = gram(p, x, x1, x2);
                let det = g11 * g22 - g12 * g12;
                let flags = if det > DEGENERATE * g11 * g22 { EDGE | TRIANGLE } else { EDGE };
                put(x, [x1, x2], [g11, g22], g12, flags);
            }
        }
        for (x, v, g, g12) in virtual_stencils {
            put(x, v, g, g12, EDGE | TRIANGLE);
        }
        let curvature = if curvature { smoothed_curvature(mesh, &angle_sum, &area) } else { vec![0.0; n] };
        Self { offsets, entries, stats, curvature }
    }

    /// The stencils in which `v` is a known vertex.
    #[inline]
    pub fn of(&self, v: u32) -> &[Entry] {
        &self.entries[self.offsets[v as usize] as usize..self.offsets[v as usize + 1] as usize]
    }
}

/// Gram matrix entries |e1|^2, |e2|^2, e1 . e2 of the corner x with edges
/// e1 = x1 - x, e2 = x2 - x.
#[inline]
fn gram(p: &[DVec3], x: u32, x1: u32, x2: u32) -> [f64; 3] {
    let (e1, e2) = (p[x1 as usize] - p[x as usize], p[x2 as usize] - p[x as usize]);
    [e1.length_squared(), e2.length_squared(), e1.dot(e2)]
}

/// Splits the obtuse corner `k` of face `f` (Kimmel and Sethian 1998): lays
/// the face out in the plane with its obtuse corner x at the origin and the
/// edge to x1 along +x, then unfolds the neighbouring triangles across the
/// edge that the acute section of x (the directions within 90 degrees of
/// both edges) passes through, until a vertex lands inside that section.
/// Returns the vertex and its unfolded position, or `None` at a boundary or
/// non-manifold edge, when the strip comes back to the corner's triangle, or
/// after `max_steps` unfoldings.
pub(crate) fn split_obtuse(
    conn: &Connectivity,
    p: &[DVec3],
    f: FaceId,
    k: usize,
    max_steps: usize,
) -> Option<(VertexId, DVec2)> {
    let h0 = HalfedgeId::of_corner(f, k);
    let (x, x1, x2) = (conn.origin(h0), conn.dest(h0), conn.opposite_vertex(h0));
    let (e1, e2) = (p[x1.idx()] - p[x.idx()], p[x2.idx()] - p[x.idx()]);
    let l1 = e1.length();
    let q1 = DVec2::new(l1, 0.0);
    let q2 = DVec2::new(e1.dot(e2) / l1, e1.cross(e2).length() / l1);
    // The edge being crossed runs from a (on the e1 side) to b (on the e2
    // side); `apex` is the vertex of the current triangle opposite to it.
    let mut h = h0.next();
    let (mut qa, mut qb, mut apex) = (q1, q2, DVec2::ZERO);
    for _ in 0..max_steps {
        let t = conn.twin(h)?; // runs b -> a in the next triangle
        let (a, b, c) = (conn.dest(t), conn.origin(t), conn.opposite_vertex(t));
        if c == x || c == x1 || c == x2 {
            return None;
        }
        let qc = unfold(qa, qb, p[a.idx()].distance(p[c.idx()]), p[b.idx()].distance(p[c.idx()]), apex)?;
        let (s1, s2) = (qc.dot(q1), qc.dot(q2));
        if s1 > 0.0 && s2 > 0.0 {
            return Some((c, qc));
        }
        if s1 <= 0.0 && s2 <= 0.0 {
            return None; // behind the corner
        }
        if s1 <= 0.0 {
            // c lies past the section on the e2 side: go on across (a, c).
            h = t.next();
            apex = qb;
            qb = qc;
        } else {
            // c lies before the section on the e1 side: go on across (c, b).
            h = t.prev();
            apex = qa;
            qa = qc;
        }
    }
    None
}

/// Position of the vertex at distance `la` from `qa` and `lb` from `qb`, on
/// the side of the line (qa, qb) away from `apex`.
fn unfold(qa: DVec2, qb: DVec2, la: f64, lb: f64, apex: DVec2) -> Option<DVec2> {
    let d = qa.distance(qb);
    if !(d > 0.0) {
        return None;
    }
    let u = (qb - qa) / d;
    let along = (la * la - lb * lb + d * d) / (2.0 * d);
    let height = (la * la - along * along).max(0.0).sqrt();
    let mut n = u.perp();
    if n.dot(apex - qa) > 0.0 {
        n = -n;
    }
    Some(qa + along * u + height * n)
}

/// Gaussian curvature at each vertex from the angle sums and barycentric
/// areas: the angle defect (2 pi - sum of corner angles) over the area (the
/// discrete Gauss-Bonnet estimate), averaged over the vertex's star (its own
/// and its neighbours' defects over their areas) because a single vertex's
/// defect is noisy; 0 on boundary, non-manifold and isolated vertices. O(V + E).
fn smoothed_curvature(mesh: &TriMesh, angle_sum: &[f64], area: &[f64]) -> Vec<f64> {
    let conn = mesh.connectivity();
    let n = mesh.vertex_count();
    let interior: Vec<bool> = (0..n).map(|v| conn.vertex_kind(VertexId::new(v)) == VertexKind::Interior).collect();
    let defect = |v: usize| std::f64::consts::TAU - angle_sum[v];
    (0..n)
        .map(|v| {
            if !interior[v] {
                return 0.0;
            }
            let (mut sum_defect, mut sum_area) = (defect(v), area[v]);
            crate::support::for_each_neighbor(conn, VertexId::new(v), |w| {
                if interior[w.idx()] {
                    sum_defect += defect(w.idx());
                    sum_area += area[w.idx()];
                }
            });
            if sum_area > 0.0 {
                sum_defect / sum_area
            } else {
                0.0
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn obtuse_corner_is_split_through_its_neighbour() {
        // Obtuse triangle (0, 1, 2) at vertex 0; the neighbour across 1-2 has
        // its far vertex straight ahead of 0 (and is obtuse at 3 likewise).
        let p = vec![DVec3::ZERO, DVec3::new(1.0, -1.5, 0.0), DVec3::new(1.0, 1.5, 0.0), DVec3::new(2.0, 0.0, 0.0)];
        let mesh = TriMesh::new(p, vec![[0, 1, 2], [2, 1, 3]]).unwrap();
        let (c, q) = split_obtuse(mesh.connectivity(), mesh.positions(), FaceId(0), 0, 20).unwrap();
        assert_eq!(c, VertexId(3));
        assert!((q.length() - 2.0).abs() < 1e-12);
        let s = Stencils::new(&mesh, true, 20, false);
        assert_eq!(s.stats, FmmStats { obtuse_corners: 2, split_corners: 2, degenerate_corners: 0 });
    }

    #[test]
    fn unfolding_matches_the_flat_layout() {
        // On a flat sheared grid the unfolded position of the split vertex is
        // its true position relative to the corner.
        let mut m = mesh_core::shapes::grid(1.0, 1.0, 4, 4).unwrap();
        m.positions_mut().iter_mut().for_each(|p| p.x += 0.05 * p.y);
        let (conn, p) = (m.connectivity(), m.positions());
        let mut split = 0;
        for f in m.face_ids() {
            for k in 0..3 {
                let h = HalfedgeId::of_corner(f, k);
                let (x, x1, x2) = (conn.origin(h), conn.dest(h), conn.opposite_vertex(h));
                let (e1, e2) = (p[x1.idx()] - p[x.idx()], p[x2.idx()] - p[x.idx()]);
                if e1.dot(e2) >= 0.0 {
                    continue;
                }
                if let Some((c, q)) = split_obtuse(conn, p, f, k, 20) {
                    split += 1;
                    let d = p[c.idx()] - p[x.idx()];
                    assert!((q.length() - d.length()).abs() < 1e-12);
                    assert!((q.x * e1.length() - d.dot(e1)).abs() < 1e-12);
                    assert!(d.dot(e1) > 0.0 && d.dot(e2) > 0.0);
                }
            }
        }
        assert!(split > 10, "{split}");
    }

    #[test]
    fn curvature_of_a_sphere_is_one() {
        let m = mesh_core::shapes::icosphere(4).unwrap();
        let k = Stencils::new(&m, true, 20, true).curvature;
        let mean = k.iter().sum::<f64>() / k.len() as f64;
        assert!((mean - 1.0).abs() < 0.02, "{mean}");
        assert!(k.iter().all(|k| (k - 1.0).abs() < 0.1));
        let flat = Stencils::new(&mesh_core::shapes::disk(5, 1).unwrap(), true, 20, true).curvature;
        assert!(flat.iter().all(|k| k.abs() < 1e-9));
    }
}
