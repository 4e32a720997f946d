//! Preprocessing of Fast Marching: the local stencils of every triangle
//! corner, with obtuse corners split into virtual acute triangles by
//! unfolding (Kimmel and Sethian 1998), and the per-vertex Gaussian
//! curvature that the curved-front update needs.

use mesh_kernel::glam::{DVec2, DVec3};
use mesh_kernel::{Connectivity, FaceId, HalfedgeId, TriMesh, VertexId, VertexKind};

/// Relative tolerance below which a corner counts as degenerate.
const DEGENERATE: f64 = 1e-12;

/// A local stencil seen from one of its two known vertices `v`: the target
/// `x`, the other known vertex `o`, and the Gram matrix of `e_v = v - x` and
/// `e_o = o - x` (in the unfolded plane for virtual triangles). Once `v` is
/// accepted it updates `x` along their (real or virtual) edge, and through
/// the triangle once `o` is accepted too (the local solvers refuse
/// degenerate triangles). 32 bytes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Entry {
    pub target: u32,
    pub other: u32,
    pub g_self: f64,
    pub g_other: f64,
    pub g_dot: f64,
}

/// Statistics of the preprocessing of a [`super::FastMarching`] object.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[non_exhaustive]
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
    /// The vertices in breadth-first order (internal index -> vertex): fronts
    /// then sweep memory mostly in order.
    pub order: Vec<u32>,
    /// Internal index of each vertex (the inverse of `order`).
    pub rank: Vec<u32>,
    pub offsets: Vec<usize>,
    pub entries: Vec<Entry>,
    pub stats: FmmStats,
    /// Gaussian curvature per internal index (zeros unless asked for).
    pub curvature: Vec<f64>,
}

impl Stencils {
    /// Builds the stencils of every corner: its own triangle, and when the
    /// angle there is obtuse and `split` holds, two virtual acute triangles
    /// through the vertex found by unfolding. One pass over the corners
    /// (curvature, obtuse splits), then the stencils written vertex by vertex
    /// in breadth-first order from each vertex's faces, with vertices
    /// renumbered in that order. O(F) plus the unfolding.
    pub fn new(mesh: &TriMesh, split: bool, max_unfold: usize, curvature: bool) -> Self {
        let conn = mesh.connectivity();
        let p = mesh.positions();
        let n = mesh.vertex_count();
        let mut stats = FmmStats::default();
        // Angle sums and barycentric areas for the curvature.
        let (mut angles, mut area) =
            if curvature { (vec![AngleSum::default(); n], vec![0.0; n]) } else { (Vec::new(), Vec::new()) };
        // Virtual stencils, keyed by the vertex they are registered under.
        let mut virtual_stencils: Vec<(u32, Entry)> = Vec::new();
        for f in mesh.face_ids() {
            let tri = mesh.faces()[f.idx()];
            for k in 0..3 {
                let (x, x1, x2) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
                let [g11, g22, g12] = gram(p, x, x1, x2);
                let det = g11 * g22 - g12 * g12;
                if curvature {
                    let root = det.max(0.0).sqrt();
                    angles[x as usize].add(g12, root);
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
                        for (v, other, g_self, g_other, g_dot) in [
                            (x1, c.0, g11, gc, q1.dot(q)),
                            (c.0, x1, gc, g11, q1.dot(q)),
                            (c.0, x2, gc, g22, q.dot(q2)),
                            (x2, c.0, g22, gc, q.dot(q2)),
                        ] {
                            virtual_stencils.push((v, Entry { target: x, other, g_self, g_other, g_dot }));
                        }
                    }
                }
            }
        }
        let (order, rank) = crate::support::breadth_first_order(mesh);
        for (v, e) in &mut virtual_stencils {
            *v = rank[*v as usize];
            e.target = rank[e.target as usize];
            e.other = rank[e.other as usize];
        }
        virtual_stencils.sort_unstable_by_key(|(v, e)| (*v, e.target, e.other));
        // Each vertex's stencils: in every face around it, those of the two
        // other corners, then its virtual ones.
        let mut offsets = Vec::with_capacity(n + 1);
        let mut entries = Vec::with_capacity(6 * mesh.face_count() + virtual_stencils.len());
        let mut next_virtual = virtual_stencils.iter().peekable();
        offsets.push(0usize);
        for (i, &v) in order.iter().enumerate() {
            for &h in conn.outgoing(VertexId(v)) {
                let tri = mesh.faces()[h.face().idx()];
                let c = h.corner();
                // v is x2 of corner c + 1 and x1 of corner c + 2.
                let (a, b) = (tri[(c + 1) % 3], tri[(c + 2) % 3]);
                let (ra, rb) = (rank[a as usize], rank[b as usize]);
                let [ga_b, ga_v, gdot] = gram(p, a, b, v);
                entries.push(Entry { target: ra, other: rb, g_self: ga_v, g_other: ga_b, g_dot: gdot });
                let [gb_v, gb_a, gdot] = gram(p, b, v, a);
                entries.push(Entry { target: rb, other: ra, g_self: gb_v, g_other: gb_a, g_dot: gdot });
            }
            while let Some((_, e)) = next_virtual.next_if(|(w, _)| *w as usize == i) {
                entries.push(*e);
            }
            offsets.push(entries.len());
        }
        let curvature = if curvature {
            let angle_sum: Vec<f64> = angles.iter().map(AngleSum::total).collect();
            let k = smoothed_curvature(mesh, &angle_sum, &area);
            order.iter().map(|&v| k[v as usize]).collect()
        } else {
            vec![0.0; n]
        };
        Self { order, rank, offsets, entries, stats, curvature }
    }

    /// The stencils in which `v` is a known vertex.
    #[inline]
    pub fn of(&self, v: u32) -> &[Entry] {
        &self.entries[self.offsets[v as usize]..self.offsets[v as usize + 1]]
    }
}

/// A sum of angles in [0, pi] kept as the product of unit complex numbers
/// e^{i theta} and a count of its turns, so that one `atan2` per vertex
/// replaces one per corner: multiplying by e^{i theta}, theta in [0, pi],
/// passes the argument pi exactly when the imaginary part goes from >= 0 to
/// < 0.
#[derive(Debug, Clone, Copy)]
struct AngleSum {
    re: f64,
    im: f64,
    turns: u32,
}

impl Default for AngleSum {
    fn default() -> Self {
        Self { re: 1.0, im: 0.0, turns: 0 }
    }
}

impl AngleSum {
    /// Adds the angle of the vector (cos-like, sin-like) = (`c`, `s`), s >= 0.
    #[inline]
    fn add(&mut self, c: f64, s: f64) {
        let (re, im) = (self.re * c - self.im * s, self.re * s + self.im * c);
        let scale = re.abs().max(im.abs());
        if !(scale > 0.0 && scale.is_finite()) {
            return; // a zero-length edge: no angle
        }
        if self.im >= 0.0 && im < 0.0 {
            self.turns += 1;
        }
        (self.re, self.im) = (re / scale, im / scale);
    }

    fn total(&self) -> f64 {
        self.im.atan2(self.re) + std::f64::consts::TAU * f64::from(self.turns)
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
    let q2 = DVec2::new(e1.dot(e2) / l1, mesh_kernel::geometry::norm(e1.cross(e2)) / l1);
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
        let mut m = mesh_kernel::shapes::grid(1.0, 1.0, 4, 4).unwrap();
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
    fn angle_sums_count_turns() {
        let mut a = AngleSum::default();
        let angles = [3.0, 2.5, 1.0, 3.1, 0.2, 2.9, 0.0, std::f64::consts::PI];
        for t in angles {
            a.add(7.0 * t.cos(), 7.0 * t.sin());
        }
        assert!((a.total() - angles.iter().sum::<f64>()).abs() < 1e-12);
        let mut b = AngleSum::default();
        b.add(0.0, 0.0);
        b.add(0.5f64.cos(), 0.5f64.sin());
        assert!((b.total() - 0.5).abs() < 1e-15);
    }

    #[test]
    fn curvature_of_a_sphere_is_one() {
        let m = mesh_kernel::shapes::icosphere(4).unwrap();
        let k = Stencils::new(&m, true, 20, true).curvature;
        let mean = k.iter().sum::<f64>() / k.len() as f64;
        assert!((mean - 1.0).abs() < 0.02, "{mean}");
        assert!(k.iter().all(|k| (k - 1.0).abs() < 0.1));
        let flat = Stencils::new(&mesh_kernel::shapes::disk(5, 1).unwrap(), true, 20, true).curvature;
        assert!(flat.iter().all(|k| k.abs() < 1e-9));
    }
}
