//! As-rigid-as-possible parameterization (Liu, Zhang, Xu, Gotsman and
//! Gortler 2008): local/global alternation that brings every face as close
//! to an isometry of its surface triangle as possible, with a free boundary.
//!
//! Local step: for each face, the rotation R_t closest to the Jacobian of the
//! current map (closed form for 2 x 2: the angle of its conformal part).
//! Global step: the cotangent system `sum_j w_ij (u_i - u_j) = b_i`
//! (eq. 2.15 weights) with one vertex pinned, factored once.

use glam::{DMat2, DVec2};
use mesh_kernel::{TriMesh, VertexId, VertexKind};

use crate::dirichlet::dirichlet_solver;
use crate::error::{ParamError, Result};
use crate::fixed::{weight_matrix, DegeneratePolicy};
use crate::topology::require_disk;
use crate::weights::{Harmonic, LocalTriangle, WeightContext};

/// Options of [`Arap`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ArapOptions {
    /// Zero-area faces: weighted as equilateral triangles (default) or
    /// refused.
    pub degenerate: DegeneratePolicy,
    /// Local/global iterations of each [`Arap::solve`] (default 20, as
    /// [`crate::ParamMethod::Arap`] in [`crate::ParamMethod::ALL`]); at most
    /// 10,000.
    pub iterations: usize,
}

impl Default for ArapOptions {
    fn default() -> Self {
        Self { degenerate: DegeneratePolicy::Uniform, iterations: 20 }
    }
}

/// A factored ARAP problem on a disk: the global-step matrix and each face's
/// isometric flattening, ready for any number of solves from any start.
#[derive(Debug, Clone)]
pub struct Arap {
    solver: mesh_kernel::solver::DirichletSolver,
    iterations: usize,
    /// Per face: flattened corners (x_0 = 0) and the opposite cotangents of
    /// the half-edges 0 -> 1, 1 -> 2, 2 -> 0.
    flat: Vec<([DVec2; 3], [f64; 3])>,
    faces: Vec<[u32; 3]>,
    vertex_count: usize,
}

impl Arap {
    /// Flattens every face isometrically and factors the cotangent system
    /// with one vertex (and every unreferenced vertex) pinned. Cost O(V + F)
    /// plus one sparse Cholesky.
    ///
    /// # Errors
    /// `ParamError::InvalidOption` (`iterations`) above 10,000; `ParamError::NotADisk` unless the mesh is a
    /// topological disk; `ParamError::DegenerateFaces` for zero-area faces under `DegeneratePolicy::Error`;
    /// `ParamError::Mesh` (`MeshError::NonManifold`, or `MeshError::Solver` when the factorization fails).
    pub fn new(mesh: &TriMesh, options: &ArapOptions) -> Result<Self> {
        crate::ParamMethod::Arap { iterations: options.iterations }.validate()?;
        let degenerate = options.degenerate;
        require_disk(mesh)?;
        let ctx = WeightContext::new(mesh);
        if let (DegeneratePolicy::Error, Some(&first)) = (degenerate, ctx.degenerate_faces().first()) {
            return Err(ParamError::DegenerateFaces { count: ctx.degenerate_faces().len(), first });
        }
        let conn = ctx.connectivity();
        let flat = mesh
            .face_ids()
            .map(|f| {
                let t = ctx.triangle(mesh_kernel::HalfedgeId::of_corner(f, 0));
                (flatten(&t), [t.cot(2), t.cot(0), t.cot(1)])
            })
            .collect();
        let n = mesh.vertex_count();
        let first = (0..n).find(|&v| conn.vertex_kind(VertexId::new(v)) != VertexKind::Isolated).unwrap_or(0);
        let pinned: Vec<usize> = std::iter::once(first)
            .chain((0..n).filter(|&v| conn.vertex_kind(VertexId::new(v)) == VertexKind::Isolated))
            .collect();
        let l = weight_matrix(&ctx, &Harmonic);
        let mut is_fixed = vec![false; n];
        pinned.iter().for_each(|&v| is_fixed[v] = true);
        let solver = dirichlet_solver(&l, &is_fixed, true)?;
        Ok(Self { solver, iterations: options.iterations, flat, faces: mesh.faces().to_vec(), vertex_count: n })
    }

    /// The ARAP energy sum_t sum_(i,j) cot_ij |(u_i - u_j) - R_t (x_i - x_j)|^2
    /// with the best rotations for `uv`. O(F).
    pub fn energy(&self, uv: &[DVec2]) -> f64 {
        self.faces
            .iter()
            .zip(&self.flat)
            .map(|(f, (x, cot))| face_energy(f, x, cot, uv, best_rotation(f, x, cot, uv)))
            .sum()
    }

    /// Runs [`ArapOptions::iterations`] local/global steps from `start` (one
    /// UV per vertex),
    /// keeping the first pinned vertex where `start` has it. Fails rather
    /// than return non-finite coordinates.
    ///
    /// # Errors
    /// `ParamError::Mesh` (`MeshError::Dimension`) when `start` does not have one entry per vertex,
    /// (`MeshError::Solver`) when a solve fails; `ParamError::NonFinite` naming the first vertex whose
    /// coordinates become non-finite.
    pub fn solve(&self, start: &[DVec2]) -> Result<Vec<DVec2>> {
        let n = start.len();
        if n != self.vertex_count {
            return Err(mesh_kernel::MeshError::Dimension(format!(
                "{n} start positions for {} vertices",
                self.vertex_count
            ))
            .into());
        }
        if let Some(vertex) = start.iter().position(|q| !q.is_finite()) {
            return Err(ParamError::NonFinite { vertex });
        }
        let mut uv = start.to_vec();
        let fixed_u: Vec<f64> = self.solver.fixed().iter().map(|&v| uv[v].x).collect();
        let fixed_v: Vec<f64> = self.solver.fixed().iter().map(|&v| uv[v].y).collect();
        for _ in 0..self.iterations {
            let mut bu = vec![0.0; n];
            let mut bv = vec![0.0; n];
            for (f, (x, cot)) in self.faces.iter().zip(&self.flat) {
                let r = best_rotation(f, x, cot, &uv);
                for k in 0..3 {
                    let (i, j) = (f[k] as usize, f[(k + 1) % 3] as usize);
                    let d = cot[k] * (r * (x[k] - x[(k + 1) % 3]));
                    bu[i] += d.x;
                    bv[i] += d.y;
                    bu[j] -= d.x;
                    bv[j] -= d.y;
                }
            }
            let x = self.solver.solve_many(&[&fixed_u, &fixed_v], Some(&[&bu, &bv]))?;
            uv = x[0].iter().zip(&x[1]).map(|(u, v)| DVec2::new(*u, *v)).collect();
        }
        Ok(uv)
    }
}

/// A face laid flat with its first corner at the origin and first edge on
/// the x axis, from its (possibly equilateral stand-in) side lengths.
fn flatten(t: &LocalTriangle) -> [DVec2; 3] {
    let l01 = t.len[0];
    let l20 = t.len[2];
    // Angle at corner 0 from cot and the double area.
    let (c, s) = (t.dot[0], t.double_area);
    let dir = DVec2::new(c, s).normalize_or_zero();
    [DVec2::ZERO, DVec2::new(l01, 0.0), dir * l20]
}

/// The rotation closest to the cotangent-weighted covariance of the face's
/// current map (the angle of its conformal part).
fn best_rotation(f: &[u32; 3], x: &[DVec2; 3], cot: &[f64; 3], uv: &[DVec2]) -> DMat2 {
    let mut s = DMat2::ZERO;
    for k in 0..3 {
        let (i, j) = (f[k] as usize, f[(k + 1) % 3] as usize);
        let du = uv[i] - uv[j];
        let dx = x[k] - x[(k + 1) % 3];
        // s += cot * du dx^T
        s += cot[k] * DMat2::from_cols(du * dx.x, du * dx.y);
    }
    let angle = (s.x_axis.y - s.y_axis.x).atan2(s.x_axis.x + s.y_axis.y);
    DMat2::from_angle(angle)
}

fn face_energy(f: &[u32; 3], x: &[DVec2; 3], cot: &[f64; 3], uv: &[DVec2], r: DMat2) -> f64 {
    (0..3)
        .map(|k| {
            let (i, j) = (f[k] as usize, f[(k + 1) % 3] as usize);
            cot[k] * ((uv[i] - uv[j]) - r * (x[k] - x[(k + 1) % 3])).length_squared()
        })
        .sum()
}

/// Isometric flattening of a 3D triangle, for tests.
#[cfg(test)]
fn flat_of(p: [glam::DVec3; 3]) -> [DVec2; 3] {
    flatten(&LocalTriangle::new(p[0], p[1], p[2]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use mesh_kernel::shapes;

    #[test]
    fn flattening_is_isometric() {
        let p = [DVec3::new(0.1, 0.2, 0.3), DVec3::new(1.0, -0.5, 0.7), DVec3::new(-0.4, 0.9, 1.2)];
        let x = flat_of(p);
        for (a, b) in [(0, 1), (1, 2), (2, 0)] {
            assert!((x[a].distance(x[b]) - p[a].distance(p[b])).abs() < 1e-14);
        }
        assert!((x[1] - x[0]).perp_dot(x[2] - x[0]) > 0.0);
    }

    #[test]
    fn rotation_of_a_rotated_face_is_found() {
        let x = [DVec2::ZERO, DVec2::X, DVec2::new(0.3, 0.8)];
        let r = DMat2::from_angle(0.7);
        let uv: Vec<DVec2> = x.iter().map(|p| r * *p + DVec2::new(2.0, -1.0)).collect();
        let got = best_rotation(&[0, 1, 2], &x, &[1.0, 0.5, 0.8], &uv);
        assert!((got - r).to_cols_array().iter().all(|d| d.abs() < 1e-14));
        assert!(face_energy(&[0, 1, 2], &x, &[1.0, 0.5, 0.8], &uv, got) < 1e-28);
    }

    #[test]
    fn iterations_decrease_the_energy() {
        let mut m = shapes::disk(6, 3).unwrap();
        for p in m.positions_mut() {
            p.z = 0.5 * (p.x * p.x - p.y * p.y);
        }
        let arap = Arap::new(&m, &ArapOptions { iterations: 1, ..Default::default() }).unwrap();
        let start: Vec<DVec2> = m.positions().iter().map(|p| DVec2::new(p.x, p.y)).collect();
        let mut uv = start;
        let mut e = arap.energy(&uv);
        for _ in 0..5 {
            uv = arap.solve(&uv).unwrap();
            let e1 = arap.energy(&uv);
            assert!(e1 <= e * (1.0 + 1e-12), "{e1} > {e}");
            e = e1;
        }
    }
}
