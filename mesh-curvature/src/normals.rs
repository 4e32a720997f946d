//! Vertex normals for the curvature estimators.
//!
//! The tensor estimators differentiate the normal field, so its accuracy
//! matters: [`Normals::Max`] (Max 1999, "Weights for computing vertex normals
//! from facet normals") weights each incident face by the cross product of
//! its two edges at the vertex divided by both squared edge lengths. It is
//! exact whenever the vertex and its 1-ring lie on a sphere, and is what
//! Rusinkiewicz 2004 uses. All weightings come from
//! [`mesh_kernel::geometry::vertex_normals`].

use glam::DVec3;
use mesh_kernel::geometry::{vertex_normals as core_normals, NormalWeighting};
use mesh_kernel::TriMesh;

/// Which vertex normal the estimators use.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Normals {
    /// Max 1999: sum over incident faces of `(e1 x e2) / (|e1|^2 |e2|^2)` with
    /// `e1`, `e2` the face's edges at the vertex. Exact on spheres.
    #[default]
    Max,
    /// Area-weighted face normals (libigl's default).
    Area,
    /// Angle-weighted face normals (Thurmer and Wuthrich 1998).
    Angle,
    /// Plain average of unit face normals.
    Uniform,
}

/// Unit vertex normals with the chosen weighting. Where a weighting gives a
/// zero vector (only zero-area or zero-length-edge faces around a vertex), the
/// area-weighted normal is used; isolated vertices and vertices with no area
/// at all get the zero vector. O(F).
pub fn vertex_normals(mesh: &TriMesh, normals: Normals) -> Vec<DVec3> {
    let weighting = match normals {
        Normals::Max => NormalWeighting::Max,
        Normals::Area => NormalWeighting::Area,
        Normals::Angle => NormalWeighting::Angle,
        Normals::Uniform => NormalWeighting::Uniform,
    };
    core_normals(mesh, weighting)
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::shapes;

    #[test]
    fn max_normals_are_exact_on_spheres() {
        let m = shapes::icosphere(3).unwrap();
        for (n, p) in vertex_normals(&m, Normals::Max).iter().zip(m.positions()) {
            assert!((*n - *p).length() < 1e-13, "{n} vs {p}");
        }
        let area = vertex_normals(&m, Normals::Area);
        let worst = area.iter().zip(m.positions()).map(|(n, p)| (*n - *p).length()).fold(0.0, f64::max);
        assert!(worst > 1e-6, "area normals are not exact: the test above means something");
    }

    #[test]
    fn degenerate_fans_fall_back() {
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::X, DVec3::Y];
        let m = TriMesh::new(p, vec![[0, 1, 2], [0, 1, 3]]).unwrap();
        for n in vertex_normals(&m, Normals::Max) {
            assert!(n.is_finite());
        }
    }
}
