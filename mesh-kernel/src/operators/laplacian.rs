//! The cotangent Laplacian (eq. 2.14-2.15; Pinkall and Polthier 1993).

use sprs::CsMat;

use glam::DVec3;

use super::corner_batch::{cotans_batch, CORNER_BATCH};
use super::pattern::EdgePattern;
use crate::error::MeshError;
use crate::mesh::TriMesh;
use crate::par;

/// Relative area below which a triangle counts as degenerate for cotangents
/// (see [`crate::clean::is_degenerate_triangle`]).
pub const DEGENERATE_TOLERANCE: f64 = 1e-12;

/// Which Laplace-Beltrami discretization an algorithm works with.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum LaplacianKind {
    /// [`LaplacianKind::Cotan`] unless the mesh has zero-area faces, then
    /// [`LaplacianKind::IntrinsicDelaunay`]: a zero-area triangle has no
    /// cotangents, and its near-degenerate neighbours have huge ones.
    /// [`LaplacianKind::resolve`] says which one a mesh gets.
    #[default]
    Auto,
    /// The cotangent Laplacian of the mesh itself (eq. 2.15; `-igl::cotmatrix`);
    /// zero-area faces contribute nothing.
    Cotan,
    /// The cotangent Laplacian of the intrinsic Delaunay triangulation
    /// (Bobenko and Springborn 2007) of the mollified edge lengths (Sharp and
    /// Crane 2020): non-negative weights, well defined on zero-area
    /// triangles, equal to [`LaplacianKind::Cotan`] on Delaunay meshes.
    IntrinsicDelaunay,
}

crate::named_choice!(LaplacianKind, "laplacian", MeshError);

impl LaplacianKind {
    /// Every choice, in the order of the names `auto`, `cotan`, `intrinsic`.
    pub const ALL: [Self; 3] = [Self::Auto, Self::Cotan, Self::IntrinsicDelaunay];

    /// The name parsed and displayed.
    pub fn name(self) -> &'static str {
        match self {
            Self::Auto => "auto",
            Self::Cotan => "cotan",
            Self::IntrinsicDelaunay => "intrinsic",
        }
    }

    /// The Laplacian `self` stands for on `mesh` (never `Auto`) and the
    /// number of zero-area faces (relative area at most
    /// [`DEGENERATE_TOLERANCE`]) that decided it. O(F).
    pub fn resolve(self, mesh: &TriMesh) -> (Self, usize) {
        let degenerate = crate::clean::degenerate_faces(mesh, DEGENERATE_TOLERANCE).len();
        let kind = match self {
            Self::Auto if degenerate > 0 => Self::IntrinsicDelaunay,
            Self::Auto => Self::Cotan,
            other => other,
        };
        (kind, degenerate)
    }

    /// `self`, or what `Auto` stands for on `mesh` (see [`LaplacianKind::resolve`]).
    pub fn resolve_if_auto(self, mesh: &TriMesh) -> Self {
        match self {
            Self::Auto => self.resolve(mesh).0,
            other => other,
        }
    }
}

/// Cotangents of the three angles of a triangle, `[k]` at corner `k`, or zeros
/// when the triangle is degenerate (zero area): a zero-area triangle adds no
/// stiffness instead of an infinite one. Use
/// [`super::IntrinsicTriangulation`] for a Laplacian that stays well-defined
/// and non-negative on such input.
#[inline]
pub fn triangle_cotans(tri: [DVec3; 3]) -> [f64; 3] {
    // In the triangle's own unit (exact), where nothing over- or underflows;
    // the degeneracy test is that of `crate::clean::is_degenerate_triangle`, on the same
    // edges (both sides scale alike, so the unit does not change it).
    let [a, b, c] = crate::geometry::triangle_in_own_unit(tri).0;
    let (ab, ac, bc) = (b - a, c - a, c - b);
    let double_area = crate::geometry::norm(ab.cross(ac));
    let longest2 = ab.length_squared().max(ac.length_squared()).max(bc.length_squared());
    // False for NaN too (edges that overflowed).
    let proper = double_area > DEGENERATE_TOLERANCE * longest2;
    if !proper {
        return [0.0; 3];
    }
    [ab.dot(ac) / double_area, bc.dot(a - b) / double_area, (a - c).dot(-bc) / double_area]
}

/// For each half-edge `3 f + k`, the cotangent of the angle opposite to it in
/// its face (at corner `k + 2`). O(F).
pub fn halfedge_cotans(mesh: &TriMesh) -> Vec<f64> {
    face_cotans(mesh).into_iter().flatten().collect()
}

/// [`halfedge_cotans`] grouped by face.
fn face_cotans(mesh: &TriMesh) -> Vec<[f64; 3]> {
    par::map(mesh.face_count(), |f| face_halfedge_cotans(mesh, f))
}

/// The cotangents opposite the half-edges `3 f + k` of face `f`, `[k]`
/// for half-edge k.
#[inline]
fn face_halfedge_cotans(mesh: &TriMesh, f: usize) -> [f64; 3] {
    let [c0, c1, c2] = triangle_cotans(mesh.triangle(crate::FaceId::new(f)));
    // Half-edge k runs from corner k to k+1; its opposite corner is k+2.
    [c2, c0, c1]
}

/// Cotangent weight of every edge, w_ij = (cot alpha_ij + cot beta_ij) / 2
/// (eq. 2.15 up to the factor 1/2 that makes it the FEM stiffness), summed
/// over however many faces the edge has (one on the boundary). Negative for
/// edges opposite obtuse angles (chapter section 2.2.2). O(F), in one pass
/// over the faces, adding into the edges with [`par::scatter`] (several
/// threads, each edge's sum in face order on any number of them), the
/// corner positions of the face [`par::READ_AHEAD`] faces on asked for
/// ahead (the cotan Laplacian at 470,274 vertices in Loop subdivision's
/// order, on one thread: 71-79 ms instead of 82-87 in one set of
/// alternated rounds, 91-93 instead of 92-99 in another, 2026-12-06).
pub fn cotan_weights(mesh: &TriMesh) -> Vec<f64> {
    let conn = mesh.connectivity();
    let (faces, p) = (mesh.faces(), mesh.positions());
    par::scatter(
        conn.edge_count(),
        conn.edges_by_face(),
        0.0,
        |f| {
            if let Some(ahead) = faces.get(f + par::READ_AHEAD) {
                ahead.iter().for_each(|&v| crate::hint::prefetch(&p[v as usize]));
            }
            face_halfedge_cotans(mesh, f).map(|c| 0.5 * c)
        },
        |w, c| *w += c,
    )
}

/// `L v` for one vector per vertex, without assembling `L`
/// ([`cotan_laplacian`]): `(L v)_i = sum_j w_ij (v_i - v_j)` over the
/// edges `ij` (weights of [`cotan_weights`]), each face adding its three
/// sides' terms to their ends. Built from differences `v_i - v_j`, it
/// keeps its relative accuracy when the values lie far from the origin,
/// where the assembled product, `L_ii v_i` minus the neighbours' `w_ij
/// v_j`, cancels: the mean curvature of a unit sphere 10^7 radii from the
/// origin differed by 6e-6 from that of the same positions moved back,
/// and does not differ at all from differences (each `v_i - v_j` of
/// such positions is exact). One pass over the faces, eight at a time (the cotangents of the
/// corner batches), sums in face order on any thread count
/// ([`par::scatter_batched`]). O(V + F).
///
/// # Errors
/// `MeshError::Dimension` when `values` does not hold one vector per vertex.
pub fn cotan_laplacian_apply(mesh: &TriMesh, values: &[DVec3]) -> Result<Vec<DVec3>, MeshError> {
    if values.len() != mesh.vertex_count() {
        let counts = format!("{} values for {} vertices", values.len(), mesh.vertex_count());
        return Err(MeshError::Dimension(counts));
    }
    let faces = mesh.faces();
    Ok(par::scatter_batched(
        mesh.vertex_count(),
        faces,
        mesh.positions(),
        DVec3::ZERO,
        |first| {
            let mut cotans = [[0.0; 3]; CORNER_BATCH];
            let count = cotans_batch(mesh, first, &mut cotans);
            let mut terms = [[DVec3::ZERO; 3]; CORNER_BATCH];
            for (f, (cot, terms)) in cotans.iter().zip(&mut terms).enumerate().take(count) {
                // Corner k's cotangent weighs the side opposite it.
                let w = cot.map(|c| 0.5 * c);
                let [a, b, c] = faces[first + f].map(|v| values[v as usize]);
                let (ab, bc, ca) = (w[2] * (a - b), w[0] * (b - c), w[1] * (c - a));
                *terms = [ab - ca, bc - ab, ca - bc];
            }
            terms
        },
        #[inline(always)]
        |sum, x| *sum += x,
    ))
}

/// The cotangent Laplacian L (eq. 2.15): L_ij = -(cot alpha_ij + cot beta_ij)/2,
/// L_ii = -sum_j L_ij. Symmetric positive semi-definite on meshes whose
/// weights are non-negative, rows sum to zero, `L x = 0` for linear `x` on a
/// planar mesh (interior rows). Equal to `-igl::cotmatrix`. Works on
/// non-manifold input; zero-area faces contribute nothing. O(V + F); the
/// weights and the pattern are built side by side on two threads.
pub fn cotan_laplacian(mesh: &TriMesh) -> CsMat<f64> {
    let conn = mesh.connectivity();
    let (pattern, weights) = par::join(|| EdgePattern::new(mesh.vertex_count(), conn.edges()), || cotan_weights(mesh));
    pattern.laplacian(&weights)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    fn assert_laplacian_invariants(l: &CsMat<f64>) {
        let t = l.transpose_view().to_csr();
        for (i, row) in l.outer_iterator().enumerate() {
            assert!(row.iter().map(|(_, v)| v).sum::<f64>().abs() < 1e-12, "row {i}");
            for (j, v) in row.iter() {
                assert!((t.get(i, j).copied().unwrap_or(0.0) - v).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn linear_precision_on_a_plane() {
        let m = shapes::disk(6, 2).unwrap();
        let l = cotan_laplacian(&m);
        assert_laplacian_invariants(&l);
        let conn = m.connectivity();
        let x: Vec<f64> = m.positions().iter().map(|p| 2.0 * p.x - 3.0 * p.y + 1.0).collect();
        for (i, row) in l.outer_iterator().enumerate() {
            if conn.is_boundary_vertex(crate::VertexId::new(i)) {
                continue;
            }
            let lx: f64 = row.iter().map(|(j, v)| v * x[j]).sum();
            assert!(lx.abs() < 1e-12, "vertex {i}: {lx}");
        }
    }

    #[test]
    fn sphere_laplacian_of_coordinates_is_mean_curvature_normal() {
        // L x = 2 H n A on a sphere of radius 1 (H = 1, n = x): L x ~ 2 A x.
        let m = shapes::icosphere(4).unwrap();
        let l = cotan_laplacian(&m);
        assert_laplacian_invariants(&l);
        let mass = super::super::lumped_mass(&m, super::super::MassKind::MixedVoronoi);
        let p = m.positions();
        let mut worst: f64 = 0.0;
        for (i, row) in l.outer_iterator().enumerate() {
            let lx: DVec3 = row.iter().map(|(j, v)| *v * p[j]).sum();
            let h = lx.dot(p[i]) / (2.0 * mass[i]);
            worst = worst.max((h - 1.0).abs());
        }
        assert!(worst < 1e-2, "{worst}");
    }

    /// The matrix-free product equals the assembled one on a mesh with a
    /// boundary, a fin (an edge of three faces), a flipped face, a
    /// zero-area face and an isolated vertex, for arbitrary values.
    #[test]
    fn applying_equals_the_assembled_product() {
        let sphere = shapes::icosphere(2).unwrap();
        let mut positions = sphere.positions().to_vec();
        let mut faces: Vec<[u32; 3]> = sphere.faces()[..sphere.faces().len() - 5].to_vec();
        faces[2] = [faces[2][0], faces[2][2], faces[2][1]];
        let n = positions.len() as u32;
        let [a, b, _] = faces[7];
        positions.extend([positions[0] * 1.5, (positions[a as usize] + positions[b as usize]) * 0.5, DVec3::ONE]);
        faces.extend([[b, a, n], [a, b, n + 1]]);
        let mesh = TriMesh::new(positions, faces).unwrap();
        assert!(!mesh.connectivity().is_manifold());
        let values: Vec<DVec3> = (0..mesh.vertex_count())
            .map(|i| DVec3::new((i as f64).sin(), (i * i % 7) as f64, 1.0 / (1.0 + i as f64)))
            .collect();
        let l = cotan_laplacian(&mesh);
        let applied = cotan_laplacian_apply(&mesh, &values).unwrap();
        assert!(cotan_laplacian_apply(&mesh, &values[1..]).is_err());
        for (i, row) in l.outer_iterator().enumerate() {
            let product: DVec3 = row.iter().map(|(j, w)| *w * values[j]).sum();
            assert!((product - applied[i]).length() < 1e-12, "vertex {i}: {product} against {}", applied[i]);
        }
        assert_eq!(applied[mesh.vertex_count() - 1], DVec3::ZERO);
    }

    #[test]
    fn degenerate_faces_stay_finite() {
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0), DVec3::new(1.0, 1.0, 0.0)];
        let m = TriMesh::new(p, vec![[0, 1, 2], [0, 2, 3]]).unwrap();
        let l = cotan_laplacian(&m);
        assert!(l.data().iter().all(|v| v.is_finite()));
    }
}
