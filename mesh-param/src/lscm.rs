//! Least-squares conformal maps (Levy, Petitjean, Ray and Maillot 2002), a
//! free-boundary parameterization: minimize the conformal energy
//! E_C = E_D - A (Dirichlet energy minus the signed parameter area; Desbrun,
//! Meyer and Alliez 2002 show this equals the LSCM energy), which is zero
//! exactly for conformal maps (eq. 2.10-2.11 with equality).

use glam::DVec2;
use mesh_kernel::sprs::CsMat;
use mesh_kernel::{FaceId, TriMesh, VertexId, VertexKind};

use crate::dirichlet::dirichlet_solver;
use crate::error::{ParamError, Result};
use crate::fixed::{weight_matrix, DegeneratePolicy};
use crate::topology::require_disk;
use crate::weights::{Harmonic, WeightContext};

/// Options of [`lscm`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LscmOptions {
    /// The two pinned vertices and their positions; `None` pins the two
    /// boundary vertices farthest apart (double sweep, O(n)) at distance
    /// equal to their 3D distance.
    pub pins: Option<[(VertexId, DVec2); 2]>,
    /// Scale and translate the result into the unit square [0, 1]^2
    /// (uniformly, keeping the aspect ratio). Default false, as in
    /// [`crate::ParamOptions::normalize`]: the map keeps the surface's unit of
    /// length and the pins stay where given; set it for texture coordinates.
    pub normalize: bool,
    /// What to do with zero-area faces (weighted as equilateral, or refused).
    pub degenerate: DegeneratePolicy,
}

/// The LSCM result: one UV per vertex and the faces weighted uniformly.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct LscmMap {
    /// Parameter coordinates, one per vertex.
    pub uv: Vec<DVec2>,
    /// The pinned vertices.
    pub pins: [VertexId; 2],
    /// Zero-area faces weighted as equilateral triangles.
    pub degenerate_faces: Vec<FaceId>,
}

/// The 2n x 2n matrix Q of E_C = x^T Q x / 2 for x = (u, v):
/// [[L, -S], [S, L]] with L the cotangent Laplacian (FEM stiffness, eq. 2.15)
/// and S the antisymmetric boundary matrix of the signed area
/// A = u^T S v = 1/2 sum over boundary edges i -> j of (u_i v_j - u_j v_i).
/// Symmetric positive semi-definite; its kernel holds the similarities.
/// O(V + E).
///
/// # Errors
/// `ParamError::Mesh` (`MeshError::NonManifold`) when the boundary loops of a non-manifold mesh cannot be
/// traced.
pub fn conformal_energy_matrix(ctx: &WeightContext<'_>) -> Result<CsMat<f64>> {
    let n = ctx.mesh().vertex_count();
    let conn = ctx.connectivity();
    // weight_matrix uses cot alpha + cot beta: half of it is the stiffness.
    let l = weight_matrix(ctx, &Harmonic);
    // Boundary neighbours (previous, next) of each boundary vertex.
    let mut around: Vec<Option<(usize, usize)>> = vec![None; n];
    for lp in conn.boundary_loops()? {
        let m = lp.vertices.len();
        for k in 0..m {
            around[lp.vertices[k].idx()] = Some((lp.vertices[(k + m - 1) % m].idx(), lp.vertices[(k + 1) % m].idx()));
        }
    }
    // For boundary edge i -> j: Q(u_i, v_j) = Q(v_j, u_i) = -1/2 and
    // Q(u_j, v_i) = Q(v_i, u_j) = +1/2. So row u_i holds +1/2 at v_prev and
    // -1/2 at v_next; row v_i holds -1/2 at u_prev and +1/2 at u_next.
    let extra = |i: usize, sign: f64| -> Vec<(usize, f64)> {
        let Some((prev, next)) = around[i] else { return Vec::new() };
        let mut e = vec![(prev, 0.5 * sign), (next, -0.5 * sign)];
        e.sort_unstable_by_key(|x| x.0);
        if e[0].0 == e[1].0 {
            e = vec![(e[0].0, e[0].1 + e[1].1)];
        }
        e
    };
    let mut indptr = Vec::with_capacity(2 * n + 1);
    let mut indices = Vec::with_capacity(2 * l.nnz() + 4 * n);
    let mut data = Vec::with_capacity(2 * l.nnz() + 4 * n);
    indptr.push(0);
    for (i, row) in l.outer_iterator().enumerate() {
        for (j, &w) in row.iter() {
            indices.push(j);
            data.push(0.5 * w);
        }
        for (j, w) in extra(i, 1.0) {
            indices.push(n + j);
            data.push(w);
        }
        indptr.push(indices.len());
    }
    for (i, row) in l.outer_iterator().enumerate() {
        for (j, w) in extra(i, -1.0) {
            indices.push(j);
            data.push(w);
        }
        for (j, &w) in row.iter() {
            indices.push(n + j);
            data.push(0.5 * w);
        }
        indptr.push(indices.len());
    }
    Ok(CsMat::new((2 * n, 2 * n), indptr, indices, data))
}

/// Least-squares conformal map of a disk (Levy et al. 2002) with two pinned
/// vertices, solved as one sparse 2n x 2n Cholesky (LU if that fails) of the
/// free block of [`conformal_energy_matrix`] (the pins and unreferenced
/// vertices are fixed). A planar mesh is reproduced up
/// to a similarity. Cost: O(V + F) assembly plus one sparse factorization.
///
/// # Errors
/// `ParamError::NotADisk` unless the mesh is a topological disk; `ParamError::DegenerateFaces` for zero-area
/// faces under `DegeneratePolicy::Error`; `ParamError::InvalidOption` (`pins`) for pins on the same vertex,
/// at the same or non-finite positions, or out of range; `ParamError::Mesh` (`MeshError::Solver`) when the
/// solve fails.
pub fn lscm(mesh: &TriMesh, options: &LscmOptions) -> Result<LscmMap> {
    let boundary = require_disk(mesh)?;
    let ctx = WeightContext::new(mesh);
    if let (DegeneratePolicy::Error, Some(&first)) = (options.degenerate, ctx.degenerate_faces().first()) {
        return Err(ParamError::DegenerateFaces { count: ctx.degenerate_faces().len(), first });
    }
    let n = mesh.vertex_count();
    let pins = match options.pins {
        Some(p) => p,
        None => far_apart_pins(mesh, &boundary.vertices),
    };
    validate_pins(&pins, n)?;
    let q = conformal_energy_matrix(&ctx)?;

    // Fixed unknowns: both coordinates of the pins and of unreferenced vertices.
    let conn = ctx.connectivity();
    let mut fixed_value = vec![None; 2 * n];
    for (v, p) in pins {
        fixed_value[v.idx()] = Some(p.x);
        fixed_value[n + v.idx()] = Some(p.y);
    }
    for v in 0..n {
        if conn.vertex_kind(VertexId::new(v)) == VertexKind::Isolated {
            fixed_value[v] = Some(pins[0].1.x);
            fixed_value[n + v] = Some(pins[0].1.y);
        }
    }
    let is_fixed: Vec<bool> = fixed_value.iter().map(Option::is_some).collect();
    let solver = dirichlet_solver(&q, &is_fixed, true)?;
    let values: Vec<f64> = solver.fixed().iter().map(|&k| fixed_value[k].unwrap_or(0.0)).collect();
    let x = solver.solve(&values, None)?;
    let mut uv: Vec<DVec2> = (0..n).map(|v| DVec2::new(x[v], x[n + v])).collect();
    if options.normalize {
        normalize_to_unit_box(&mut uv);
    }
    Ok(LscmMap { uv, pins: [pins[0].0, pins[1].0], degenerate_faces: ctx.degenerate_faces().to_vec() })
}

fn validate_pins(pins: &[(VertexId, DVec2); 2], n: usize) -> Result<()> {
    let bad = |reason: String| Err(ParamError::InvalidOption { name: "pins", reason });
    if pins[0].0 == pins[1].0 {
        return bad(format!("both pins are vertex {}", pins[0].0));
    }
    if pins[0].1 == pins[1].1 || !pins[0].1.is_finite() || !pins[1].1.is_finite() {
        return bad("pin positions must be finite and distinct".into());
    }
    if let Some((v, _)) = pins.iter().find(|(v, _)| v.idx() >= n) {
        return bad(format!("vertex {v} out of range 0..{n}"));
    }
    Ok(())
}

/// Two boundary vertices far apart (double sweep on 3D distance: exact for a
/// convex planar boundary, within a factor of two in general), pinned at
/// (0, 0) and (d, 0) with d their distance. O(n).
fn far_apart_pins(mesh: &TriMesh, boundary: &[VertexId]) -> [(VertexId, DVec2); 2] {
    let farthest = |from: VertexId| {
        let p = mesh.position(from);
        boundary
            .iter()
            .copied()
            .max_by(|a, b| p.distance_squared(mesh.position(*a)).total_cmp(&p.distance_squared(mesh.position(*b))))
    };
    let start = boundary[0];
    let a = farthest(start).unwrap_or(start);
    let b = farthest(a).unwrap_or(start);
    let b = if b == a { boundary[boundary.len() / 2] } else { b };
    let d = mesh.position(a).distance(mesh.position(b));
    [(a, DVec2::ZERO), (b, DVec2::new(if d > 0.0 { d } else { 1.0 }, 0.0))]
}

/// Scales and translates `uv` uniformly into [0, 1]^2 (the longer side of the
/// bounding box becomes 1). Leaves a single point unchanged. O(n).
pub fn normalize_to_unit_box(uv: &mut [DVec2]) {
    let Some(first) = uv.first().copied() else { return };
    let (lo, hi) = uv.iter().fold((first, first), |(lo, hi), q| (lo.min(*q), hi.max(*q)));
    let size = (hi - lo).max_element();
    if size > 0.0 && size.is_finite() {
        uv.iter_mut().for_each(|q| *q = (*q - lo) / size);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::shapes;

    #[test]
    fn energy_matrix_is_symmetric_with_similarities_in_its_kernel() {
        let mut m = shapes::disk(4, 5).unwrap();
        for p in m.positions_mut() {
            p.z = 0.3 * p.x * p.y;
        }
        let ctx = WeightContext::new(&m);
        let q = conformal_energy_matrix(&ctx).unwrap();
        let t = q.transpose_view().to_csc();
        let d = &q - &t;
        assert!(d.data().iter().all(|x| x.abs() < 1e-14));
        // Translations (1, 0), (0, 1) are in the kernel.
        let n = m.vertex_count();
        for (du, dv) in [(1.0, 0.0), (0.0, 1.0)] {
            let x: Vec<f64> = (0..2 * n).map(|k| if k < n { du } else { dv }).collect();
            let qx = &q * &mesh_kernel::sprs::CsVec::new(2 * n, (0..2 * n).collect(), x);
            assert!(qx.data().iter().all(|y| y.abs() < 1e-12));
        }
    }

    #[test]
    fn pins_are_validated() {
        let m = shapes::disk(2, 1).unwrap();
        let same =
            LscmOptions { pins: Some([(VertexId(1), DVec2::ZERO), (VertexId(1), DVec2::X)]), ..Default::default() };
        assert!(lscm(&m, &same).is_err());
        let out =
            LscmOptions { pins: Some([(VertexId(1), DVec2::ZERO), (VertexId(99), DVec2::X)]), ..Default::default() };
        assert!(lscm(&m, &out).is_err());
        let coincident =
            LscmOptions { pins: Some([(VertexId(1), DVec2::X), (VertexId(2), DVec2::X)]), ..Default::default() };
        assert!(lscm(&m, &coincident).is_err());
    }

    #[test]
    fn normalization_fits_the_unit_box() {
        let mut uv = vec![DVec2::new(-2.0, 1.0), DVec2::new(2.0, 3.0), DVec2::new(0.0, 2.0)];
        normalize_to_unit_box(&mut uv);
        assert_eq!(uv, vec![DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.5), DVec2::new(0.5, 0.25)]);
    }
}
