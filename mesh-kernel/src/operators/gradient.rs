//! Gradient and divergence of piecewise-linear functions: the per-face
//! operators behind the cotangent Laplacian, `L = D G`.

use sprs::{CsMat, TriMat};

use crate::clean::is_degenerate_triangle;
use crate::geometry::{norm, triangle_in_own_unit};
use crate::mesh::TriMesh;
use crate::par;

use super::laplacian::DEGENERATE_TOLERANCE;

/// The gradient of a piecewise-linear function, face by face: a `3F x V`
/// matrix whose rows `3 f .. 3 f + 3` give the x, y, z components of the
/// gradient in face `f`. The hat function of corner `k` has the gradient
/// `N x e_k / (2 A)`, with `e_k` the edge opposite the corner (from corner
/// `k + 1` to `k + 2`), `N` the unit normal and `A` the area. Zero-area
/// faces have zero rows, as they have zero cotangents. O(F).
pub fn gradient(mesh: &TriMesh) -> CsMat<f64> {
    let per_face = par::map(mesh.face_count(), |f| {
        let tri = mesh.triangle(crate::FaceId::new(f));
        if is_degenerate_triangle(tri, DEGENERATE_TOLERANCE) {
            return None;
        }
        // In the triangle's own unit: N x e / (2A) scales as 1 / length.
        let ([a, b, c], unit) = triangle_in_own_unit(tri);
        let cross = (b - a).cross(c - a);
        let double_area = norm(cross);
        let n = cross / double_area;
        let edges = [c - b, a - c, b - a];
        Some(edges.map(|e| n.cross(e) / (double_area * unit)))
    });
    let mut t = TriMat::with_capacity((3 * mesh.face_count(), mesh.vertex_count()), 9 * mesh.face_count());
    for (f, grads) in per_face.iter().enumerate() {
        let Some(grads) = grads else { continue };
        for (k, g) in grads.iter().enumerate() {
            let v = mesh.faces()[f][k] as usize;
            for (axis, value) in g.to_array().into_iter().enumerate() {
                t.add_triplet(3 * f + axis, v, value);
            }
        }
    }
    t.to_csr()
}

/// The integrated divergence of a face-wise constant vector field: the
/// `V x 3F` matrix `D = G^T A`, `A` the face areas repeated for x, y, z, so
/// that `(D X)_i = sum_f A_f grad(phi_i) . X_f` and `D G` is the cotangent
/// Laplacian ([`super::cotan_laplacian`], positive semi-definite). O(F).
pub fn divergence(mesh: &TriMesh) -> CsMat<f64> {
    let areas = crate::geometry::face_areas(mesh);
    let g = gradient(mesh);
    let mut t = TriMat::with_capacity((mesh.vertex_count(), 3 * mesh.face_count()), g.nnz());
    for (row, vec) in g.outer_iterator().enumerate() {
        for (v, &value) in vec.iter() {
            t.add_triplet(v, row, value * areas[row / 3]);
        }
    }
    t.to_csr()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::operators::cotan_laplacian;
    use crate::shapes;

    #[test]
    fn gradients_of_linear_functions_are_exact_and_d_g_is_the_cotan_laplacian() {
        let m = shapes::irregular_torus(2.0, 0.7, 24, 16, 0.3, 7).unwrap();
        let g = gradient(&m);
        // The gradient of x restricted to a face is the projection of e_x.
        let x: Vec<f64> = m.positions().iter().map(|p| p.x).collect();
        let gx = &g * &sprs::CsVec::new(x.len(), (0..x.len()).collect(), x.clone());
        let normals = crate::geometry::face_normals(&m);
        for (f, n) in normals.iter().enumerate() {
            let expected = glam::DVec3::X - *n * n.x;
            let got = glam::DVec3::new(
                gx.get(3 * f).copied().unwrap_or(0.0),
                gx.get(3 * f + 1).copied().unwrap_or(0.0),
                gx.get(3 * f + 2).copied().unwrap_or(0.0),
            );
            assert!((got - expected).length() < 1e-12, "face {f}: {got} vs {expected}");
        }
        let dg = &divergence(&m) * &g;
        let l = cotan_laplacian(&m);
        let scale = l.data().iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for (a, b) in [(&l, &dg), (&dg, &l)] {
            for (i, row) in a.outer_iterator().enumerate() {
                for (j, v) in row.iter() {
                    let w = b.get(i, j).copied().unwrap_or(0.0);
                    assert!((v - w).abs() <= 1e-12 * scale, "({i}, {j}): {v} vs {w}");
                }
            }
        }
    }

    #[test]
    fn zero_area_faces_have_no_gradient() {
        let p = vec![glam::DVec3::ZERO, glam::DVec3::X, 2.0 * glam::DVec3::X, glam::DVec3::Y];
        let m = TriMesh::new(p, vec![[0, 1, 2], [0, 1, 3]]).unwrap();
        let g = gradient(&m);
        assert!((0..3).all(|r| g.outer_view(r).is_none_or(|row| row.nnz() == 0)));
        assert!(g.data().iter().all(|v| v.is_finite()));
    }
}
