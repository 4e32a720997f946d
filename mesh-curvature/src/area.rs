//! The area a vertex stands for, which turns integrated curvature into
//! pointwise curvature.

use glam::DVec3;
use mesh_core::operators::{lumped_mass, MassKind};
use mesh_core::TriMesh;

/// Which vertex area divides integrated curvature.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum AreaKind {
    /// Mixed Voronoi area of Meyer, Desbrun, Schroeder and Barr 2003 (the
    /// area for which the angle defect and the cotangent formula are the
    /// integrals of K and H).
    #[default]
    MixedVoronoi,
    /// One third of the area of each incident face.
    Barycentric,
}

impl AreaKind {
    /// The mesh-core mass kind behind it.
    pub fn mass_kind(self) -> MassKind {
        match self {
            Self::MixedVoronoi => MassKind::MixedVoronoi,
            Self::Barycentric => MassKind::Barycentric,
        }
    }
}

/// Per-vertex area of the given kind ([`mesh_core::operators::lumped_mass`]). O(F).
pub fn vertex_areas(mesh: &TriMesh, kind: AreaKind) -> Vec<f64> {
    lumped_mass(mesh, kind.mass_kind())
}

/// The mixed Voronoi share of each corner of a triangle (Meyer et al. 2003,
/// figure 4): the Voronoi region when no angle is obtuse, otherwise half of
/// the area at the obtuse corner and a quarter at the others. Zero-area
/// triangles give zeros. Shares sum to the triangle's area.
///
/// The same rule as mesh-core's `lumped_mass`, per corner (mesh-core keeps
/// its per-corner function private).
pub(crate) fn mixed_voronoi_corners([a, b, c]: [DVec3; 3]) -> [f64; 3] {
    let area = 0.5 * (b - a).cross(c - a).length();
    if area.is_nan() || area <= 0.0 {
        return [0.0; 3];
    }
    let (da, db, dc) = ((b - a).dot(c - a), (c - b).dot(a - b), (a - c).dot(b - c));
    if da < 0.0 {
        return [area / 2.0, area / 4.0, area / 4.0];
    }
    if db < 0.0 {
        return [area / 4.0, area / 2.0, area / 4.0];
    }
    if dc < 0.0 {
        return [area / 4.0, area / 4.0, area / 2.0];
    }
    // cot at each corner = dot / (2 area); Voronoi area at a is
    // (|ab|^2 cot C + |ac|^2 cot B) / 8.
    let inv = 1.0 / (2.0 * area);
    let (ca, cb, cc) = (da * inv, db * inv, dc * inv);
    let (lab, lbc, lca) = ((b - a).length_squared(), (c - b).length_squared(), (a - c).length_squared());
    [(lab * cc + lca * cb) / 8.0, (lbc * ca + lab * cc) / 8.0, (lca * cb + lbc * ca) / 8.0]
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_core::shapes;

    #[test]
    fn corner_shares_match_lumped_mass() {
        let m = shapes::disk(6, 3).unwrap();
        let mut sum = vec![0.0; m.vertex_count()];
        for f in m.face_ids() {
            let s = mixed_voronoi_corners(m.triangle(f));
            for (k, v) in m.faces()[f.idx()].iter().enumerate() {
                sum[*v as usize] += s[k];
            }
        }
        let core = vertex_areas(&m, AreaKind::MixedVoronoi);
        for (a, b) in sum.iter().zip(&core) {
            assert!((a - b).abs() < 1e-14, "{a} vs {b}");
        }
    }
}
