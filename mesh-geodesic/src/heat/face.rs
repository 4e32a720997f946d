//! One triangle laid out in the plane from its edge lengths, with the
//! area-weighted gradients of its hat functions: the gradient and the
//! divergence of the heat method (Crane, Weischedel and Wardetzky 2013,
//! section 3.2), intrinsic so that the same code serves the mesh and its
//! intrinsic Delaunay triangulation.

use mesh_kernel::glam::DVec2;
use mesh_kernel::{clean, operators, TriMesh};

/// Below this relative area a triangle carries no gradient.
const DEGENERATE: f64 = mesh_kernel::operators::laplacian::DEGENERATE_TOLERANCE;

/// One triangle laid out in the plane: its vertices and the area-weighted
/// gradients of its hat functions, `w_k = A grad(phi_k)` (half the edge
/// opposite corner k turned by 90 degrees), or `None` when it has no area.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FaceGradient {
    pub(crate) vertices: [u32; 3],
    pub(crate) w: Option<[DVec2; 3]>,
}

impl FaceGradient {
    /// Lays out the triangle with side lengths `l[k]` (from corner k to k+1).
    pub(crate) fn new(vertices: [u32; 3], l: [f64; 3]) -> Self {
        let area = operators::intrinsic::heron_area(l[0], l[1], l[2]);
        let longest = l[0].max(l[1]).max(l[2]);
        if !(l[0] > 0.0 && area > 0.5 * DEGENERATE * longest * longest) {
            return Self { vertices, w: None };
        }
        // Corner 0 at the origin, corner 1 on +x, corner 2 above.
        let p = [DVec2::ZERO, DVec2::new(l[0], 0.0), mesh_kernel::geometry::planar_apex(l[0], l[2], l[1])];
        let w = [0, 1, 2].map(|k| 0.5 * (p[(k + 2) % 3] - p[(k + 1) % 3]).perp());
        Self { vertices, w: Some(w) }
    }

    /// [`FaceGradient::descent`] where all three heat values are resolved
    /// (at least [`super::far::RESOLVED`]), `None` elsewhere.
    #[inline]
    pub(crate) fn resolved_descent(&self, u: &[f64]) -> Option<DVec2> {
        if self.vertices.iter().all(|&v| u[v as usize] >= super::far::RESOLVED) {
            self.descent(u)
        } else {
            None
        }
    }

    /// The unit vector -grad u / |grad u| (zero where grad u vanishes).
    #[inline]
    pub(crate) fn descent(&self, u: &[f64]) -> Option<DVec2> {
        let w = self.w?;
        let values = self.vertices.map(|v| u[v as usize]);
        // The direction does not depend on the scale of u: dividing by the
        // largest value first keeps |grad u|^2 away from underflow where u
        // itself is far below 1e-154.
        let scale = values.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if !(scale > 0.0 && scale.is_finite()) {
            return None;
        }
        let g: DVec2 = (0..3).map(|k| (values[k] / scale) * w[k]).sum();
        let len = g.length();
        (len > 0.0 && len.is_finite()).then(|| -g / len)
    }
}

/// The mesh's own triangles laid out from their 3D edge lengths; triangles
/// that [`mesh_kernel::clean::is_degenerate_triangle`] flags carry no gradient,
/// as they carry no cotangent weight.
pub(crate) fn extrinsic_faces(mesh: &TriMesh) -> Vec<FaceGradient> {
    mesh.face_ids()
        .map(|f| {
            let tri = mesh.triangle(f);
            let vertices = mesh.faces()[f.idx()];
            if clean::is_degenerate_triangle(tri, DEGENERATE) {
                return FaceGradient { vertices, w: None };
            }
            FaceGradient::new(vertices, [0, 1, 2].map(|k| tri[k].distance(tri[(k + 1) % 3])))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::operators;

    #[test]
    fn face_gradients_reproduce_linear_functions() {
        // A scalene triangle; u linear with gradient (2, -1) in the layout.
        let l = [3.0, 2.5, 2.0];
        let f = FaceGradient::new([0, 1, 2], l);
        let w = f.w.unwrap();
        let area = operators::intrinsic::heron_area(l[0], l[1], l[2]);
        let p = [DVec2::ZERO, DVec2::new(l[0], 0.0), mesh_kernel::geometry::planar_apex(l[0], l[2], l[1])];
        let g = DVec2::new(2.0, -1.0);
        let u: Vec<f64> = p.iter().map(|q| g.dot(*q) + 5.0).collect();
        let grad: DVec2 = (0..3).map(|k| u[k] * w[k]).sum::<DVec2>() / area;
        assert!((grad - g).length() < 1e-12);
        // Hat gradients sum to zero.
        assert!((w[0] + w[1] + w[2]).length() < 1e-12);
        assert_eq!(f.descent(&u).map(|d| (d + g.normalize()).length() < 1e-12), Some(true));
    }

    #[test]
    fn the_direction_does_not_depend_on_the_scale_of_u() {
        // Heat values 370 mean edge lengths from a unit source are about
        // 1e-154 and below: squaring their gradient underflowed there.
        let f = FaceGradient::new([0, 1, 2], [3.0, 2.5, 2.0]);
        let u = [1.0, 0.4, 0.15];
        let d = f.descent(&u).unwrap();
        for scale in [1e300, 1e-160, 1e-200, 1e-300] {
            let scaled = u.map(|x| x * scale);
            let e = f.descent(&scaled).unwrap_or_else(|| panic!("no direction at scale {scale}"));
            assert!((e - d).length() < 1e-14, "{scale}: {e} vs {d}");
        }
        assert!(f.descent(&[0.0; 3]).is_none());
        assert!(f.descent(&[f64::INFINITY, 1.0, 1.0]).is_none());
        // Below the resolved range no direction is claimed.
        assert!(f.resolved_descent(&u.map(|x| x * 1e-302)).is_none());
        assert!(f.resolved_descent(&[1.0, -1.0, 1.0]).is_none());
        assert_eq!(f.resolved_descent(&u), Some(d));
    }

    #[test]
    fn zero_area_faces_carry_no_gradient() {
        assert!(FaceGradient::new([0, 1, 2], [1.0, 1.0, 2.0]).w.is_none());
        assert!(FaceGradient::new([0, 1, 2], [0.0, 1.0, 1.0]).w.is_none());
    }
}
