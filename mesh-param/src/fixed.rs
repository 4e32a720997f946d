//! The one solver behind every fixed-boundary method: assemble
//! `sum_j w_ij (q_i - q_j) = 0` (eq. 2.13) from any [`Weights`], fix the
//! constrained vertices, factor once, and solve for u and v.

use glam::DVec2;
use mesh_kernel::operators::EdgePattern;
use mesh_kernel::solver::Factorization;
use mesh_kernel::sprs::CsMat;
use mesh_kernel::{FaceId, HalfedgeId, MeshError, TriMesh, VertexId, VertexKind};

use crate::dirichlet::dirichlet_solver;
use crate::error::{ParamError, Result};
use crate::weights::{EdgeInfo, WeightContext, Weights};

/// What to do with zero-area faces, whose cotangents and half-angle tangents
/// are infinite.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum DegeneratePolicy {
    /// Weight each zero-area face as an equilateral triangle of its mean edge
    /// length (uniform weights on that face only); the faces are listed in
    /// the result. With positive weights elsewhere (Tutte, mean-value) the map
    /// onto a convex boundary stays bijective.
    #[default]
    Uniform,
    /// Refuse the mesh with [`ParamError::DegenerateFaces`].
    Error,
}

impl DegeneratePolicy {
    /// Both policies; their [`name`](Self::name)s are what
    /// [`FromStr`](std::str::FromStr) accepts and
    /// [`Display`](std::fmt::Display) writes.
    pub const ALL: [Self; 2] = [Self::Uniform, Self::Error];

    /// The name used on the command line: `uniform`, `error`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::Error => "error",
        }
    }
}

mesh_kernel::named_choice!(DegeneratePolicy, "degenerate", ParamError);

/// The matrix L of eq. 2.13 for `weights`: `(L q)_i = sum_j w_ij (q_i - q_j)`,
/// assembled on the edge pattern in O(V + F): each face is measured once and
/// adds its terms to the weights of its three edges in both directions.
pub fn weight_matrix<W: Weights + ?Sized>(ctx: &WeightContext<'_>, weights: &W) -> CsMat<f64> {
    let conn = ctx.connectivity();
    let edges = conn.edges();
    let mut lo_hi = vec![0.0; edges.len()];
    let mut hi_lo = vec![0.0; edges.len()];
    let mean_edge_length = ctx.mean_edge_length();
    for f in ctx.mesh().face_ids() {
        let mut t = ctx.face_triangle(f);
        for k in 0..3 {
            let h = HalfedgeId::of_corner(f, k);
            let e = conn.edge(h);
            let info = EdgeInfo { faces: conn.edge_halfedges(e).len(), mean_edge_length };
            let [ij, ji] = weights.face_terms(&t, &info);
            if conn.origin(h) == edges[e.idx()][0] {
                lo_hi[e.idx()] += ij;
                hi_lo[e.idx()] += ji;
            } else {
                lo_hi[e.idx()] += ji;
                hi_lo[e.idx()] += ij;
            }
            t = t.rotated();
        }
    }
    EdgePattern::new(ctx.mesh().vertex_count(), edges).directed(&lo_hi, &hi_lo)
}

/// A factored fixed-boundary system: build once for a mesh, weights and set
/// of constrained vertices, then [`FixedBoundarySolver::solve`] for any
/// positions of those vertices (e.g. circle and square boundaries) at the cost
/// of two triangular solves each.
///
/// Symmetric weights are factored by sparse Cholesky (falling back to LU if
/// the matrix is not positive definite), asymmetric ones by sparse LU, both
/// from `mesh_kernel::solver` (on the free block cut out in O(nnz)). Unreferenced
/// vertices are fixed at the centroid of the constraints. Cost: assembly
/// O(V + E) plus one sparse factorization of the free block.
#[derive(Debug, Clone)]
pub struct FixedBoundarySolver {
    solver: mesh_kernel::solver::DirichletSolver,
    /// For each slot of `solver.fixed()`: index into the caller's constraints,
    /// or `None` for an unreferenced vertex.
    slot_source: Vec<Option<usize>>,
    constrained: usize,
    degenerate: Vec<FaceId>,
}

impl FixedBoundarySolver {
    /// Assembles eq. 2.13 with `weights`, fixes the `constrained` vertices
    /// (which must include every boundary vertex for a well-posed system) and
    /// factors the rest.
    ///
    /// # Errors
    /// `ParamError::InvalidOption` (`constrained`) when no vertex is fixed or a fixed vertex is listed twice;
    /// `ParamError::Mesh` (`MeshError::Dimension`) for a fixed vertex out of range,
    /// (`MeshError::NonManifold`), or (`MeshError::Solver`) when the factorization fails;
    /// `ParamError::DegenerateFaces` for zero-area faces under `DegeneratePolicy::Error`.
    pub fn new<W: Weights + ?Sized>(
        mesh: &TriMesh,
        weights: &W,
        constrained: &[VertexId],
        policy: DegeneratePolicy,
    ) -> Result<Self> {
        let n = mesh.vertex_count();
        let conn = mesh.manifold_connectivity()?;
        if constrained.is_empty() {
            return Err(ParamError::InvalidOption { name: "constrained", reason: "no vertex is fixed".into() });
        }
        let mut slot_of = vec![None; n];
        for (k, v) in constrained.iter().enumerate() {
            if v.idx() >= n {
                return Err(MeshError::Dimension(format!("constrained vertex {v} out of range 0..{n}")).into());
            }
            if slot_of[v.idx()].replace(k).is_some() {
                return Err(ParamError::InvalidOption {
                    name: "constrained",
                    reason: format!("vertex {v} given twice"),
                });
            }
        }
        let ctx = WeightContext::new(mesh);
        if let (DegeneratePolicy::Error, Some(&first)) = (policy, ctx.degenerate_faces().first()) {
            return Err(ParamError::DegenerateFaces { count: ctx.degenerate_faces().len(), first });
        }
        let is_fixed: Vec<bool> = (0..n)
            .map(|v| slot_of[v].is_some() || conn.vertex_kind(VertexId::new(v)) == VertexKind::Isolated)
            .collect();
        let a = weight_matrix(&ctx, weights);
        let solver = dirichlet_solver(&a, &is_fixed, weights.is_symmetric())?;
        let slot_source = solver.fixed().iter().map(|&v| slot_of[v]).collect();
        Ok(Self { solver, slot_source, constrained: constrained.len(), degenerate: ctx.degenerate_faces().to_vec() })
    }

    /// Faces that were weighted uniformly because they have zero area.
    pub fn degenerate_faces(&self) -> &[FaceId] {
        &self.degenerate
    }

    /// The factorization used (Cholesky for symmetric weights, else LU).
    pub fn factorization(&self) -> Factorization {
        self.solver.factorization()
    }

    /// Solves for all vertices given the positions of the constrained ones
    /// (in the order given to [`FixedBoundarySolver::new`]): u and v are two
    /// right-hand sides of the one factorization. Fails rather than return a
    /// non-finite coordinate. Cost: one pair of sparse triangular solves
    /// with two columns, O(nnz of the factor).
    ///
    /// # Errors
    /// `ParamError::Mesh` (`MeshError::Dimension`) when `positions` does not have one entry per fixed vertex,
    /// (`MeshError::Solver`) when the solve fails; `ParamError::InvalidOption` (`boundary`) for a non-finite
    /// fixed position.
    pub fn solve(&self, positions: &[DVec2]) -> Result<Vec<DVec2>> {
        if positions.len() != self.constrained {
            return Err(MeshError::Dimension(format!(
                "{} positions for {} constrained vertices",
                positions.len(),
                self.constrained
            ))
            .into());
        }
        if positions.iter().any(|p| !p.is_finite()) {
            return Err(ParamError::InvalidOption { name: "boundary", reason: "non-finite position".into() });
        }
        let centroid = positions.iter().sum::<DVec2>() / positions.len() as f64;
        let value = |s: &Option<usize>| s.map_or(centroid, |k| positions[k]);
        let fu: Vec<f64> = self.slot_source.iter().map(|s| value(s).x).collect();
        let fv: Vec<f64> = self.slot_source.iter().map(|s| value(s).y).collect();
        let [u, v]: [Vec<f64>; 2] = self
            .solver
            .solve_many(&[&fu, &fv], None)?
            .try_into()
            .map_err(|_| MeshError::Solver("expected two solutions".into()))?;
        Ok(u.into_iter().zip(v).map(|(u, v)| DVec2::new(u, v)).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::weights::{Authalic, Harmonic, MeanValue, Uniform};
    use mesh_kernel::shapes;

    fn boundary(m: &TriMesh) -> Vec<VertexId> {
        m.connectivity().boundary_loops().unwrap()[0].vertices.clone()
    }

    #[test]
    fn weight_matrix_rows_sum_to_zero() {
        let m = shapes::disk(4, 3).unwrap();
        let ctx = WeightContext::new(&m);
        for w in [&Uniform as &dyn Weights, &MeanValue, &Harmonic, &Authalic] {
            let a = weight_matrix(&ctx, w);
            for row in a.outer_iterator() {
                let s: f64 = row.iter().map(|(_, v)| v).sum();
                assert!(s.abs() < 1e-9, "{s}");
            }
        }
        // Harmonic equals twice mesh-kernel's cotangent Laplacian.
        let a = weight_matrix(&ctx, &Harmonic);
        let l = mesh_kernel::operators::cotan_laplacian(&m);
        let d = &a - &l.map(|x| 2.0 * x);
        assert!(d.data().iter().all(|x| x.abs() < 1e-12));
    }

    #[test]
    fn tutte_solves_eq_2_13_with_inverse_valence_weights() {
        // The solver scales each row by |N(i)|; the solution must satisfy the
        // unscaled equations q_i = mean of the neighbours.
        let mut m = shapes::disk(6, 9).unwrap();
        for p in m.positions_mut() {
            p.z = p.x * p.y;
        }
        let b = boundary(&m);
        let pos = crate::boundary::circle(&m, &b, crate::Spacing::Uniform);
        let uv = FixedBoundarySolver::new(&m, &Uniform, &b, DegeneratePolicy::Uniform).unwrap().solve(&pos).unwrap();
        let conn = m.connectivity();
        for v in m.vertex_ids() {
            if conn.is_boundary_vertex(v) {
                continue;
            }
            let ring: Vec<VertexId> = conn.neighbors(v).collect();
            let mean = ring.iter().map(|w| uv[w.idx()]).sum::<DVec2>() / ring.len() as f64;
            assert!(uv[v.idx()].distance(mean) < 1e-14, "{v}");
        }
    }

    #[test]
    fn one_factorization_serves_several_boundaries() {
        let m = shapes::disk(5, 4).unwrap();
        let b = boundary(&m);
        let solver = FixedBoundarySolver::new(&m, &MeanValue, &b, DegeneratePolicy::Uniform).unwrap();
        for pos in
            [crate::boundary::circle(&m, &b, crate::Spacing::ChordLength), crate::boundary::square(&m, &b).unwrap()]
        {
            let again = FixedBoundarySolver::new(&m, &MeanValue, &b, DegeneratePolicy::Uniform).unwrap();
            let (x, y) = (solver.solve(&pos).unwrap(), again.solve(&pos).unwrap());
            assert!(x.iter().zip(&y).all(|(p, q)| p == q));
            // The constrained vertices sit exactly where they were put.
            assert!(b.iter().zip(&pos).all(|(v, p)| x[v.idx()] == *p));
        }
    }

    #[test]
    fn solver_checks_its_input() {
        let m = shapes::disk(2, 1).unwrap();
        let b = boundary(&m);
        let s = FixedBoundarySolver::new(&m, &Uniform, &b, DegeneratePolicy::Uniform).unwrap();
        assert_eq!(s.factorization(), Factorization::Cholesky);
        assert!(s.solve(&[DVec2::ZERO]).is_err());
        let mut pos = vec![DVec2::ZERO; b.len()];
        pos[0].x = f64::NAN;
        assert!(s.solve(&pos).is_err());
        assert!(FixedBoundarySolver::new(&m, &Uniform, &[], DegeneratePolicy::Uniform).is_err());
        assert!(FixedBoundarySolver::new(&m, &Uniform, &[VertexId(99)], DegeneratePolicy::Uniform).is_err());
        assert!(FixedBoundarySolver::new(&m, &Uniform, &[VertexId(1), VertexId(1)], DegeneratePolicy::Uniform).is_err());
        let s = FixedBoundarySolver::new(&m, &MeanValue, &b, DegeneratePolicy::Uniform).unwrap();
        assert_eq!(s.factorization(), Factorization::Lu);
    }
}
