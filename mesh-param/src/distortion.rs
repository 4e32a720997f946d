//! Distortion of a parameterization, per face and in total (section 2.4.2
//! of the "Digital Shape Processing" thesis chapter, eq. 2.8-2.11).
//!
//! On each face the map f from the parameter plane to the surface is affine;
//! its Jacobian A = (f_u, f_v) (eq. 2.9) is a 3 x 2 matrix and, in an
//! orthonormal frame P of the face's plane, B = P A (eq. 2.8) is 2 x 2. Its
//! singular values sigma1 >= sigma2 give the angle distortion sigma1 /
//! sigma2 (1 iff conformal) and the area scale sigma1 sigma2 (the ratio of
//! surface to parameter area). Eq. 2.10-2.11: |f_u ^ f_v| <= |f_u||f_v| <=
//! (f_u^2 + f_v^2) / 2, so the Dirichlet energy is at least the surface area,
//! with equality iff the map is conformal.

use glam::{DVec2, DVec3};
use mesh_kernel::{MeshError, TriMesh};

use crate::bijectivity::boundary_is_simple;
use crate::error::Result;
use crate::weights::DEGENERATE_TOLERANCE;

/// Distortion of one face. When the face's parameter triangle has no area
/// the Jacobian is infinite and so are all fields but the areas; when its
/// surface triangle has no area, sigma2 = 0 and the angle distortion is
/// infinite. Never NaN.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct FaceDistortion {
    /// B = P A (eq. 2.8), row-major: the map from the parameter plane to the
    /// face's own orthonormal frame.
    pub jacobian: [[f64; 2]; 2],
    /// Singular values sigma1 >= sigma2 >= 0 of B.
    pub singular_values: [f64; 2],
    /// sigma1 / sigma2 >= 1 (1 iff the face is mapped conformally).
    pub angle_distortion: f64,
    /// sigma1 sigma2 = surface area / parameter area of the face.
    pub area_scale: f64,
    /// The chapter's torsion f_u . f_v (0 when the parameter directions stay
    /// orthogonal).
    pub torsion: f64,
    /// The chapter's non-uniform scaling |f_u|^2 - |f_v|^2.
    pub nonuniform_scaling: f64,
    /// Area of the surface triangle.
    pub surface_area: f64,
    /// Signed area of the parameter triangle (negative when flipped).
    pub uv_signed_area: f64,
    /// The surface triangle has (numerically) zero area.
    pub degenerate: bool,
    /// The parameter triangle has (numerically) zero area.
    pub collapsed: bool,
}

/// Totals over all faces.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct DistortionSummary {
    /// Number of faces.
    pub faces: usize,
    /// Faces whose parameter triangle is clockwise (negative area).
    pub flipped_faces: usize,
    /// Faces whose parameter triangle has (numerically) zero area.
    pub collapsed_faces: usize,
    /// Faces whose surface triangle has zero area (excluded from the means).
    pub degenerate_faces: usize,
    /// Surface-area-weighted mean of sigma1 / sigma2 over measurable faces
    /// (both triangles with area); 0 when no face is measurable.
    pub angle_distortion_mean: f64,
    /// Largest sigma1 / sigma2 over measurable faces.
    pub angle_distortion_max: f64,
    /// Area-weighted mean of max(r, 1 / r), r = (sigma1 sigma2) / (total
    /// surface area / total parameter area): 1 when every face keeps its share
    /// of the area.
    pub area_distortion_mean: f64,
    /// Largest max(r, 1 / r).
    pub area_distortion_max: f64,
    /// Dirichlet energy of f, sum of (|f_u|^2 + |f_v|^2) / 2 times the
    /// parameter area of each measurable face (eq. 2.11, last term).
    pub dirichlet_energy: f64,
    /// Surface area of the measurable faces (eq. 2.11, first term).
    pub surface_area: f64,
    /// Total absolute parameter area.
    pub uv_area: f64,
    /// dirichlet_energy / surface_area >= 1, equal iff conformal.
    pub dirichlet_area_ratio: f64,
    /// The boundary loops in the plane are simple and disjoint.
    pub boundary_simple: bool,
    /// No flipped or collapsed face and a simple boundary: the map of a disk
    /// is then one-to-one.
    pub bijective: bool,
}

/// Per-face measures and their summary.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct DistortionReport {
    /// One entry per face.
    pub faces: Vec<FaceDistortion>,
    /// Totals.
    pub summary: DistortionSummary,
}

/// Distortion of one face from its surface corners `p` and parameter corners
/// `q` (eq. 2.8-2.9), for finite input (as a `TriMesh` guarantees; see
/// [`distortion`], which also checks the UVs). O(1).
pub fn face_distortion(p: [DVec3; 3], q: [DVec2; 3]) -> FaceDistortion {
    let (a, b) = (p[1] - p[0], p[2] - p[0]);
    let (d1, d2) = (q[1] - q[0], q[2] - q[0]);
    let cross = a.cross(b);
    let surface_area = 0.5 * mesh_kernel::geometry::norm(cross);
    let det_q = d1.perp_dot(d2);
    let uv_signed_area = 0.5 * det_q;
    let degenerate = mesh_kernel::clean::is_degenerate_triangle(p, DEGENERATE_TOLERANCE);
    if uv_is_collapsed(q, det_q) {
        let inf = f64::INFINITY;
        return FaceDistortion {
            jacobian: [[inf; 2]; 2],
            singular_values: [inf; 2],
            angle_distortion: inf,
            area_scale: inf,
            torsion: inf,
            nonuniform_scaling: inf,
            surface_area,
            uv_signed_area,
            degenerate,
            collapsed: true,
        };
    }
    // Q^{-1} for Q = [d1 d2] (columns).
    let inv = [[d2.y / det_q, -d2.x / det_q], [-d1.y / det_q, d1.x / det_q]];
    let f_u = a * inv[0][0] + b * inv[1][0];
    let f_v = a * inv[0][1] + b * inv[1][1];
    // Orthonormal frame P of the face plane: e1 along a, e2 = n x e1.
    let (e1, e2) = frame(a, cross);
    let jacobian = [[e1.dot(f_u), e1.dot(f_v)], [e2.dot(f_u), e2.dot(f_v)]];
    let [s1, s2] = singular_values_2x2(jacobian);
    FaceDistortion {
        jacobian,
        singular_values: [s1, s2],
        angle_distortion: if s2 > 0.0 && !degenerate { s1 / s2 } else { f64::INFINITY },
        area_scale: s1 * s2,
        torsion: f_u.dot(f_v),
        nonuniform_scaling: f_u.length_squared() - f_v.length_squared(),
        surface_area,
        uv_signed_area,
        degenerate,
        collapsed: false,
    }
}

/// A parameter triangle counts as collapsed when twice its area is at most
/// [`DEGENERATE_TOLERANCE`] times its longest edge squared.
fn uv_is_collapsed(q: [DVec2; 3], det_q: f64) -> bool {
    let longest2 = q[0].distance_squared(q[1]).max(q[1].distance_squared(q[2])).max(q[2].distance_squared(q[0]));
    det_q.abs() <= DEGENERATE_TOLERANCE * longest2
}

/// An orthonormal basis of the plane of a face with edge `a` and normal
/// `cross`; any basis of the plane containing `a` for degenerate faces.
fn frame(a: DVec3, cross: DVec3) -> (DVec3, DVec3) {
    let e1 = mesh_kernel::geometry::unit_vector(a);
    let n = mesh_kernel::geometry::unit_vector(cross);
    if e1 == DVec3::ZERO {
        return (DVec3::X, DVec3::Y);
    }
    if n == DVec3::ZERO {
        return (e1, e1.any_orthonormal_vector());
    }
    (e1, n.cross(e1))
}

/// Singular values of a 2 x 2 matrix, sigma1 >= sigma2 >= 0, from the
/// conformal / anticonformal split (stable, no cancellation in sigma1).
pub fn singular_values_2x2(m: [[f64; 2]; 2]) -> [f64; 2] {
    let e = 0.5 * (m[0][0] + m[1][1]);
    let f = 0.5 * (m[0][0] - m[1][1]);
    let g = 0.5 * (m[1][0] + m[0][1]);
    let h = 0.5 * (m[1][0] - m[0][1]);
    let (q, r) = (e.hypot(h), f.hypot(g));
    [q + r, (q - r).abs()]
}

/// Distortion of the map `uv` (one point per vertex) of `mesh`: per-face
/// measures, their area-weighted means and maxima, Dirichlet energy against
/// area, flipped and collapsed faces, and the bijectivity check (boundary
/// loops simple, see [`crate::bijectivity`]). Needs a manifold mesh (for the
/// boundary loops). O(V + F) plus the boundary check.
///
/// # Errors
/// `ParamError::Mesh` (`MeshError::Dimension`) when `uv` does not have one entry per vertex,
/// (`MeshError::NonManifold`) when the mesh is not an oriented manifold; `ParamError::NonFinite` naming a
/// vertex with non-finite coordinates.
pub fn distortion(mesh: &TriMesh, uv: &[DVec2]) -> Result<DistortionReport> {
    if uv.len() != mesh.vertex_count() {
        return Err(MeshError::Dimension(format!("{} UVs for {} vertices", uv.len(), mesh.vertex_count())).into());
    }
    if let Some(v) = uv.iter().position(|q| !q.is_finite()) {
        return Err(crate::ParamError::NonFinite { vertex: v });
    }
    let conn = mesh.manifold_connectivity()?;
    // Measured on the mesh in a unit where no area over- or underflows; the
    // ratios do not depend on it, lengths and areas carry it back.
    let (mesh, unit) = mesh_kernel::units::normalized(mesh);
    let mut faces: Vec<FaceDistortion> = mesh
        .faces()
        .iter()
        .enumerate()
        .map(|(f, t)| face_distortion(mesh.triangle(mesh_kernel::FaceId::new(f)), t.map(|v| uv[v as usize])))
        .collect();
    let loops: Vec<Vec<DVec2>> =
        conn.boundary_loops()?.iter().map(|l| l.vertices.iter().map(|v| uv[v.idx()]).collect()).collect();
    let mut summary = summarize(&faces, boundary_is_simple(&loops));
    if unit != 1.0 {
        let square = unit * unit;
        for d in &mut faces {
            d.jacobian = d.jacobian.map(|row| row.map(|x| x * unit));
            d.singular_values = d.singular_values.map(|x| x * unit);
            d.area_scale *= square;
            d.torsion *= square;
            d.nonuniform_scaling *= square;
            d.surface_area *= square;
        }
        summary.dirichlet_energy *= square;
        summary.surface_area *= square;
    }
    Ok(DistortionReport { summary, faces })
}

/// Totals of per-face measures (see [`DistortionSummary`]). O(F).
pub fn summarize(faces: &[FaceDistortion], boundary_simple: bool) -> DistortionSummary {
    let collapsed = faces.iter().filter(|d| d.collapsed).count();
    let flipped = faces.iter().filter(|d| !d.collapsed && d.uv_signed_area < 0.0).count();
    let degenerate = faces.iter().filter(|d| d.degenerate).count();
    let measurable: Vec<&FaceDistortion> = faces.iter().filter(|d| !d.collapsed && !d.degenerate).collect();
    let surface_area: f64 = measurable.iter().map(|d| d.surface_area).sum();
    let uv_area: f64 = faces.iter().map(|d| d.uv_signed_area.abs()).sum();
    let measurable_uv: f64 = measurable.iter().map(|d| d.uv_signed_area.abs()).sum();
    let global = if measurable_uv > 0.0 { surface_area / measurable_uv } else { 1.0 };
    let (mut angle_mean, mut angle_max, mut area_mean, mut area_max, mut dirichlet) = (0.0, 0.0f64, 0.0, 0.0f64, 0.0);
    for d in &measurable {
        let r = d.area_scale / global;
        let area = r.max(1.0 / r);
        angle_mean += d.surface_area * d.angle_distortion;
        area_mean += d.surface_area * area;
        angle_max = angle_max.max(d.angle_distortion);
        area_max = area_max.max(area);
        let [s1, s2] = d.singular_values;
        dirichlet += 0.5 * (s1 * s1 + s2 * s2) * d.uv_signed_area.abs();
    }
    if surface_area > 0.0 {
        angle_mean /= surface_area;
        area_mean /= surface_area;
    }
    DistortionSummary {
        faces: faces.len(),
        flipped_faces: flipped,
        collapsed_faces: collapsed,
        degenerate_faces: degenerate,
        angle_distortion_mean: angle_mean,
        angle_distortion_max: angle_max,
        area_distortion_mean: area_mean,
        area_distortion_max: area_max,
        dirichlet_energy: dirichlet,
        surface_area,
        uv_area,
        dirichlet_area_ratio: if surface_area > 0.0 { dirichlet / surface_area } else { 0.0 },
        boundary_simple,
        bijective: flipped == 0 && collapsed == 0 && boundary_simple,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn tri3(q: [DVec2; 3], z: [f64; 3]) -> [DVec3; 3] {
        [0, 1, 2].map(|k| q[k].extend(z[k]))
    }

    #[test]
    fn identity_has_no_distortion() {
        let q = [DVec2::ZERO, DVec2::new(2.0, 0.1), DVec2::new(0.4, 1.3)];
        let d = face_distortion(tri3(q, [0.0; 3]), q);
        assert!((d.singular_values[0] - 1.0).abs() < 1e-14 && (d.singular_values[1] - 1.0).abs() < 1e-14);
        assert!((d.angle_distortion - 1.0).abs() < 1e-14);
        assert!(d.torsion.abs() < 1e-14 && d.nonuniform_scaling.abs() < 1e-14);
        assert!((d.uv_signed_area - d.surface_area).abs() < 1e-14);
    }

    #[test]
    fn stretch_is_measured() {
        // Surface = parameter triangle stretched by 3 in x: sigma = (3, 1).
        let q = [DVec2::ZERO, DVec2::X, DVec2::Y];
        let p = [DVec3::ZERO, DVec3::new(3.0, 0.0, 0.0), DVec3::Y];
        let d = face_distortion(p, q);
        assert!((d.singular_values[0] - 3.0).abs() < 1e-14 && (d.singular_values[1] - 1.0).abs() < 1e-14);
        assert!((d.angle_distortion - 3.0).abs() < 1e-14);
        assert!((d.area_scale - 3.0).abs() < 1e-14);
        assert!((d.nonuniform_scaling - 8.0).abs() < 1e-14);
        assert!(d.torsion.abs() < 1e-14);
    }

    #[test]
    fn flipped_collapsed_and_degenerate_never_nan() {
        let q = [DVec2::ZERO, DVec2::Y, DVec2::X];
        let p = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let d = face_distortion(p, q);
        assert!(d.uv_signed_area < 0.0 && (d.angle_distortion - 1.0).abs() < 1e-14);
        let line = [DVec2::ZERO, DVec2::X, DVec2::new(2.0, 0.0)];
        let c = face_distortion(p, line);
        assert!(c.angle_distortion.is_infinite());
        let flat = [DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0)];
        let g = face_distortion(flat, [DVec2::ZERO, DVec2::X, DVec2::Y]);
        assert!(g.degenerate && g.angle_distortion.is_infinite() && g.area_scale == 0.0);
        let s = summarize(&[d, c, g], true);
        assert_eq!((s.flipped_faces, s.collapsed_faces, s.degenerate_faces), (1, 1, 1));
        assert!(!s.bijective);
        for x in [s.angle_distortion_mean, s.area_distortion_mean, s.dirichlet_area_ratio] {
            assert!(x.is_finite());
        }
    }

    proptest! {
        #[test]
        fn invariants_of_eq_2_10(coords in prop::array::uniform12(-1.0f64..1.0)) {
            let c = coords;
            let p = [DVec3::new(c[0], c[1], c[2]), DVec3::new(c[3], c[4], c[5]), DVec3::new(c[6], c[7], c[8])];
            let q = [DVec2::ZERO, DVec2::new(c[9], c[10]), DVec2::new(c[11], 0.7)];
            let d = face_distortion(p, q);
            prop_assume!(d.area_scale.is_finite() && d.surface_area > 1e-6);
            // sigma1 sigma2 = area ratio; sum of squares = Frobenius norm.
            let ratio = d.surface_area / d.uv_signed_area.abs();
            prop_assert!((d.area_scale - ratio).abs() <= 1e-9 * ratio.max(1.0));
            let b = d.jacobian;
            let frob = b[0][0].powi(2) + b[0][1].powi(2) + b[1][0].powi(2) + b[1][1].powi(2);
            let [s1, s2] = d.singular_values;
            prop_assert!((s1 * s1 + s2 * s2 - frob).abs() <= 1e-9 * frob.max(1.0));
            // Eq. 2.10: |f_u ^ f_v| <= |f_u| |f_v| <= (f_u^2 + f_v^2) / 2.
            prop_assert!(s1 * s2 <= 0.5 * (s1 * s1 + s2 * s2) * (1.0 + 1e-12));
            prop_assert!(d.angle_distortion >= 1.0 - 1e-12);
        }
    }
}
