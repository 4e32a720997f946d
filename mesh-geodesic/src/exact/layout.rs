//! The planar layout of every face, per half-edge, and the vertices a
//! geodesic may bend around.

use std::f64::consts::PI;

use mesh_kernel::glam::DVec2;
use mesh_kernel::{TriMesh, VertexId, VertexKind};

use crate::error::{GeodesicError, Result};

/// Relative height below which a triangle is treated as having no area.
const DEGENERATE: f64 = 1e-12;

/// Per half-edge layout: half-edge `h` runs from A = (0, 0) to B = (len, 0)
/// and its face's third corner C lies at `apex`, above the axis.
pub(super) struct Layout {
    pub len: Vec<f64>,
    pub apex: Vec<DVec2>,
    /// Vertices a geodesic may bend around: total angle above 2 pi (beyond
    /// rounding) or on the boundary. Geodesics also pass straight through
    /// flat vertices; the windows on both sides of such a vertex cover that
    /// line, so flat vertices need not emit windows.
    pub pseudo_source: Vec<bool>,
}

impl Layout {
    /// Lays out every face from its edge lengths (`planar_apex`); O(F).
    ///
    /// # Errors
    /// [`GeodesicError::Degenerate`] for a face of (relatively) zero height.
    pub fn new(mesh: &TriMesh) -> Result<Self> {
        let p = mesh.positions();
        let conn = mesh.connectivity();
        let nh = 3 * mesh.face_count();
        let mut len = vec![0.0; nh];
        let mut apex = vec![DVec2::ZERO; nh];
        let mut angle = vec![0.0; mesh.vertex_count()];
        for (f, face) in mesh.faces().iter().enumerate() {
            for k in 0..3 {
                let (a, b, c) = (p[face[k] as usize], p[face[(k + 1) % 3] as usize], p[face[(k + 2) % 3] as usize]);
                let (l, ac, bc) = (a.distance(b), a.distance(c), b.distance(c));
                let DVec2 { x, y } = mesh_kernel::geometry::planar_apex(l, ac, bc);
                if !(y > DEGENERATE * l.max(ac).max(bc)) || !x.is_finite() {
                    return Err(GeodesicError::Degenerate(format!(
                        "face {f} has no area; exact geodesics need proper triangles \
                         (the heat method with the intrinsic Delaunay Laplacian handles them)"
                    )));
                }
                len[3 * f + k] = l;
                apex[3 * f + k] = DVec2::new(x, y);
                angle[face[k] as usize] += y.atan2(x);
            }
        }
        let pseudo_source = (0..mesh.vertex_count())
            .map(|v| match conn.vertex_kind(VertexId::new(v)) {
                VertexKind::Interior => angle[v] > 2.0 * PI * (1.0 + 1e-12),
                _ => true,
            })
            .collect();
        Ok(Self { len, apex, pseudo_source })
    }
}
