//! Sparse Cholesky factorization, solved for single right-hand sides or
//! blocks of them.

use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::SymbolicSupernodalParams;
use faer::sparse::SparseColMat;
use faer::{Conj, MatMut, Side, Spec};
use glam::DVec3;
use sprs::CsMat;

use super::dissection::nested_dissection;
use super::supernodal::Supernodes;
use super::{check_rhs, check_square, memory, parallelism, to_faer, DISSECTION_FROM, SUPERNODAL_FROM};
use crate::error::{MeshError, Result};

/// How [`Cholesky`] orders the unknowns to keep its factor small.
#[derive(Debug, Clone, Default, PartialEq)]
pub enum FillOrdering {
    /// Approximate minimum degree (faer's): for any matrix.
    #[default]
    MinimumDegree,
    /// Geometric nested dissection (George 1973) of unknowns that sit at
    /// points in space, one point per row: a mesh's vertices. From
    /// [`DISSECTION_FROM`] unknowns (minimum degree below); on meshes of
    /// 3e4-5e5 vertices it made the factor 11-28% smaller
    /// (BENCHMARKS.md, "Nested dissection").
    Dissection(Arc<[DVec3]>),
}

impl FillOrdering {
    /// Geometric nested dissection of a mesh's vertices.
    pub fn of_points(points: &[DVec3]) -> Self {
        Self::Dissection(points.into())
    }

    /// The ordering of a sub-problem made of the unknowns `rows` (in that
    /// order) of this one, e.g. one connected component. A row without a
    /// point gives [`FillOrdering::MinimumDegree`] (only the speed depends
    /// on the ordering).
    pub fn restrict(&self, rows: &[usize]) -> Self {
        match self {
            Self::MinimumDegree => Self::MinimumDegree,
            Self::Dissection(points) => rows
                .iter()
                .map(|&r| points.get(r).copied())
                .collect::<Option<Arc<[DVec3]>>>()
                .map_or(Self::MinimumDegree, Self::Dissection),
        }
    }
}

/// Supernode amalgamation of faer's symbolic analysis: two supernodes of
/// `n` columns in all merge when the zeros this adds are a fraction below
/// `z` of the merged one. faer's default (`(16, 0.8)` second) padded
/// nested-dissection factors of meshes with a third more entries than the
/// exact factor; these thresholds bring the padding under a quarter and
/// take 10-20% off a single solve (BENCHMARKS.md, "Nested dissection").
const RELAX: &[(usize, f64)] = &[(4, 1.0), (16, 0.2), (48, 0.05), (usize::MAX, 0.02)];

/// Sparse Cholesky factorization `P A P^T = L L^T` of a symmetric positive
/// definite matrix (only its lower triangle is read), with a fill-reducing
/// ordering `P` ([`FillOrdering`], minimum degree unless told), the
/// supernodal variant from [`SUPERNODAL_FROM`] unknowns and one thread below
/// [`super::PARALLEL_FROM`].
///
/// Solves take one right-hand side, several stacked column after column
/// ([`Cholesky::solve_in_place`]), or blocks of `W` stored row by row
/// ([`Cholesky::solve_rows`], [`Cholesky::solve_ordered_rows`]): a block
/// reads the factor once for its `W` columns, which is what makes block
/// eigensolvers and multi-coordinate solves (u and v of a parameterization)
/// cheaper than one solve per column.
#[derive(Debug, Clone)]
pub struct Cholesky {
    symbolic: Arc<SymbolicCholesky<usize>>,
    values: Vec<f64>,
    /// The analysed sparsity pattern (column pointers, row indices), to
    /// check that [`Cholesky::refactor`] gets the same one.
    pattern: Arc<(Vec<usize>, Vec<usize>)>,
    /// The supernodes, when the factor is supernodal.
    supernodes: Option<Arc<Supernodes>>,
    /// `order[i]`: the original index of the factor's i-th unknown.
    order: Arc<Vec<usize>>,
}

impl Cholesky {
    /// Analyses and factors `a` with the minimum-degree ordering. Cost: one
    /// symbolic analysis plus one numeric factorization (for a 40k-vertex
    /// Laplacian about 0.1 s on a 2-core x86-64 machine). Fails when `a` is
    /// not positive definite.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] for a matrix that is not square; [`MeshError::Solver`] when it is
    /// not symmetric positive definite (naming the failing pivot), has a non-finite entry, or
    /// memory runs out.
    pub fn new(a: &CsMat<f64>) -> Result<Self> {
        Self::with_ordering(a, &FillOrdering::MinimumDegree)
    }

    /// Analyses and factors `a` with the given fill-reducing ordering.
    ///
    /// # Errors
    /// Those of [`Cholesky::new`]; [`MeshError::Dimension`] when a
    /// [`FillOrdering::Dissection`] does not have one point per row.
    pub fn with_ordering(a: &CsMat<f64>, ordering: &FillOrdering) -> Result<Self> {
        let n = check_square(a)?;
        let a = to_faer(a)?;
        let threshold =
            if n >= SUPERNODAL_FROM { SupernodalThreshold::FORCE_SUPERNODAL } else { SupernodalThreshold::AUTO };
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: threshold,
            supernodal_params: SymbolicSupernodalParams { relax: Some(RELAX) },
            ..Default::default()
        };
        let (forward, inverse);
        let ordering = match ordering {
            FillOrdering::MinimumDegree => SymmetricOrdering::Amd,
            FillOrdering::Dissection(points) if points.len() != n => {
                return Err(MeshError::Dimension(format!("{} points for {n} unknowns", points.len())));
            }
            // (The dissection's adjacency has 32-bit indices.)
            FillOrdering::Dissection(_) if !(DISSECTION_FROM..u32::MAX as usize).contains(&n) => SymmetricOrdering::Amd,
            FillOrdering::Dissection(points) => {
                forward = nested_dissection(a.symbolic().col_ptr(), a.symbolic().row_idx(), points);
                let mut inv = vec![0; n];
                for (i, &v) in forward.iter().enumerate() {
                    inv[v] = i;
                }
                inverse = inv;
                SymmetricOrdering::Custom(PermRef::new_checked(&forward, &inverse, n))
            }
        };
        let symbolic = factorize_symbolic_cholesky(a.symbolic(), Side::Lower, ordering, params)
            .map_err(|e| MeshError::Solver(format!("symbolic Cholesky failed: {e:?}")))?;
        let pattern = (a.symbolic().col_ptr().to_vec(), a.symbolic().row_idx().to_vec());
        let order = match symbolic.perm() {
            Some(p) => p.arrays().0.to_vec(),
            None => (0..a.nrows()).collect(),
        };
        let mut this = Self {
            supernodes: Supernodes::of(&symbolic).map(Arc::new),
            symbolic: Arc::new(symbolic),
            values: Vec::new(),
            pattern: Arc::new(pattern),
            order: Arc::new(order),
        };
        this.factor_numeric(&a)?;
        Ok(this)
    }

    fn factor_numeric(&mut self, a: &SparseColMat<usize, f64>) -> Result<()> {
        let par = parallelism(a.nrows());
        let mut values = vec![0.0; self.symbolic.len_val()];
        let mut mem =
            memory(MemBuffer::try_new(self.symbolic.factorize_numeric_llt_scratch::<f64>(par, Spec::default())))?;
        self.symbolic
            .factorize_numeric_llt(
                &mut values,
                a.as_ref(),
                Side::Lower,
                LltRegularization::default(),
                par,
                MemStack::new(&mut mem),
                Spec::default(),
            )
            .map_err(|e| {
                MeshError::Solver(format!("Cholesky factorization failed, the matrix is not positive definite ({e:?})"))
            })?;
        self.values = values;
        Ok(())
    }

    /// Refactors a matrix with the same sparsity pattern as the one given to
    /// [`Cholesky::new`] (e.g. `M + t L` for another `t`), reusing the analysis.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] for a matrix that is not square or whose pattern differs from the
    /// analysed one; [`MeshError::Solver`] when it is not positive definite.
    pub fn refactor(&mut self, a: &CsMat<f64>) -> Result<()> {
        let a = self.same_pattern(a)?;
        self.factor_numeric(&a)
    }

    /// How many eigenvalues of the symmetric `a` are negative, for `a` with
    /// the sparsity pattern of the analysed matrix (e.g. `L - mu M` where
    /// `L - sigma M` was factored): the negative pivots of `P a P^T = L D L^T`
    /// with this factor's ordering and analysis, by Sylvester's law of
    /// inertia. The factorization does not pivot, so a pivot below
    /// `64 eps` times the largest (or not finite) makes the count
    /// untrustworthy: `None` then. Cost: one numeric factorization.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] for a matrix that is not square or whose pattern differs from the
    /// analysed one; [`MeshError::Solver`] when the workspace cannot be allocated.
    pub fn negative_eigenvalues(&self, a: &CsMat<f64>) -> Result<Option<usize>> {
        let a = self.same_pattern(a)?;
        let par = parallelism(a.nrows());
        let mut values = vec![0.0; self.symbolic.len_val()];
        let mut mem =
            memory(MemBuffer::try_new(self.symbolic.factorize_numeric_ldlt_scratch::<f64>(par, Spec::default())))?;
        let factored = self.symbolic.factorize_numeric_ldlt(
            &mut values,
            a.as_ref(),
            Side::Lower,
            LdltRegularization::default(),
            par,
            MemStack::new(&mut mem),
            Spec::default(),
        );
        if factored.is_err() {
            return Ok(None);
        }
        let pivots: Vec<f64> = match (&self.supernodes, self.symbolic.raw()) {
            (Some(nodes), _) => nodes.diagonal(&values).collect(),
            (None, SymbolicCholeskyRaw::Simplicial(s)) => (0..a.nrows())
                .map(|j| {
                    let range = s.col_ptr()[j]..s.col_ptr()[j + 1];
                    range.clone().find(|&p| s.row_idx()[p] == j).map_or(0.0, |p| values[p])
                })
                .collect(),
            (None, SymbolicCholeskyRaw::Supernodal(_)) => return Ok(None),
        };
        let largest = pivots.iter().fold(0.0f64, |m, d| m.max(d.abs()));
        let trusted = largest.is_finite() && pivots.iter().all(|d| d.abs() > 64.0 * f64::EPSILON * largest);
        Ok(trusted.then(|| pivots.iter().filter(|d| **d < 0.0).count()))
    }

    /// `a` in faer form, checked to be square with the analysed pattern.
    fn same_pattern(&self, a: &CsMat<f64>) -> Result<SparseColMat<usize, f64>> {
        if check_square(a)? != self.dim() {
            return Err(MeshError::Dimension(format!("{} rows, expected {}", a.rows(), self.dim())));
        }
        let a = to_faer(a)?;
        if a.symbolic().col_ptr() != self.pattern.0 || a.symbolic().row_idx() != self.pattern.1 {
            return Err(MeshError::Dimension("a different sparsity pattern from the analysed one".into()));
        }
        Ok(a)
    }

    /// Number of unknowns.
    pub fn dim(&self) -> usize {
        self.symbolic.nrows()
    }

    /// Stored values of the factor (its memory in doubles).
    pub fn factor_nonzeros(&self) -> usize {
        self.values.len()
    }

    /// The factor's order of the unknowns: `order()[i]` is the original
    /// index of its i-th unknown (the row order of
    /// [`Cholesky::solve_ordered_rows`]).
    pub fn order(&self) -> &[usize] {
        &self.order
    }

    /// Solves `A x = b` in place; `b` may hold several right-hand sides one
    /// after the other (column-major, `b.len()` a multiple of the
    /// dimension), which are solved in blocks of up to 8.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] when `b.len()` is not a multiple of the dimension;
    /// [`MeshError::Solver`] when the workspace cannot be allocated.
    pub fn solve_in_place(&self, b: &mut [f64]) -> Result<()> {
        let n = self.dim();
        check_rhs(n, b.len())?;
        if n == 0 {
            return Ok(());
        }
        let Some(nodes) = &self.supernodes else {
            return self.solve_simplicial(MatMut::from_column_major_slice_mut(b, n, b.len() / n));
        };
        let k = b.len() / n;
        let mut c0 = 0;
        while c0 < k {
            c0 += match k - c0 {
                8.. => self.solve_columns::<8>(nodes, b, c0),
                4..=7 => self.solve_columns::<4>(nodes, b, c0),
                2 | 3 => self.solve_columns::<2>(nodes, b, c0),
                _ => self.solve_columns::<1>(nodes, b, c0),
            };
        }
        Ok(())
    }

    /// Solves `A x = b` for one or several stacked right-hand sides.
    ///
    /// # Errors
    /// Those of [`Cholesky::solve_in_place`].
    pub fn solve(&self, b: &[f64]) -> Result<Vec<f64>> {
        let mut x = b.to_vec();
        self.solve_in_place(&mut x)?;
        Ok(x)
    }

    /// Solves `A X = B` in place for `W` right-hand sides stored row by row
    /// in the original order: `x[i][j]` is unknown `i` of right-hand side `j`.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] when `x.len()` is not the dimension; [`MeshError::Solver`] when
    /// the workspace cannot be allocated.
    pub fn solve_rows<const W: usize>(&self, x: &mut [[f64; W]]) -> Result<()> {
        self.check_rows(x.len())?;
        let mut ordered: Vec<[f64; W]> = self.order.iter().map(|&i| x[i]).collect();
        self.solve_ordered_rows(&mut ordered)?;
        for (&i, row) in self.order.iter().zip(ordered) {
            x[i] = row;
        }
        Ok(())
    }

    /// Solves `A X = B` in place for `W` right-hand sides stored row by row
    /// in the factor's order ([`Cholesky::order`]): `x[i][j]` is unknown
    /// `order()[i]` of right-hand side `j`. Callers that keep their vectors
    /// in this order (block eigensolvers) skip two permutations per solve.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] when `x.len()` is not the dimension; [`MeshError::Solver`] when
    /// the workspace cannot be allocated.
    pub fn solve_ordered_rows<const W: usize>(&self, x: &mut [[f64; W]]) -> Result<()> {
        let n = self.check_rows(x.len())?;
        if let Some(nodes) = &self.supernodes {
            nodes.solve(&self.values, x);
            return Ok(());
        }
        // Simplicial factor (small systems): through faer, column by column.
        let mut b = vec![0.0; n * W];
        for (row, &i) in x.iter().zip(self.order.iter()) {
            for j in 0..W {
                b[j * n + i] = row[j];
            }
        }
        self.solve_simplicial(MatMut::from_column_major_slice_mut(&mut b, n, W))?;
        for (row, &i) in x.iter_mut().zip(self.order.iter()) {
            for j in 0..W {
                row[j] = b[j * n + i];
            }
        }
        Ok(())
    }

    /// Right-hand sides per row at which [`Cholesky::solve_ordered_rows`]
    /// costs least per right-hand side on this CPU (each block reads the
    /// factor twice, whatever its width, as long as its rows fit in
    /// registers): 32 on x86-64 with AVX-512, 16 elsewhere.
    pub fn widest_block() -> usize {
        super::supernodal::widest_block()
    }

    fn check_rows(&self, len: usize) -> Result<usize> {
        let n = self.dim();
        if len != n {
            return Err(MeshError::Dimension(format!("{len} rows for {n} unknowns")));
        }
        Ok(n)
    }

    /// Columns `c0..c0 + W` of the column-major `b` through the supernodal
    /// solve; returns `W`.
    fn solve_columns<const W: usize>(&self, nodes: &Supernodes, b: &mut [f64], c0: usize) -> usize {
        let n = self.dim();
        let mut x: Vec<[f64; W]> = self.order.iter().map(|&i| std::array::from_fn(|j| b[(c0 + j) * n + i])).collect();
        nodes.solve(&self.values, &mut x);
        for (row, &i) in x.iter().zip(self.order.iter()) {
            for j in 0..W {
                b[(c0 + j) * n + i] = row[j];
            }
        }
        W
    }

    /// faer's solve, for a simplicial factor.
    fn solve_simplicial(&self, b: MatMut<'_, f64>) -> Result<()> {
        let par = parallelism(self.dim());
        let mut mem = memory(MemBuffer::try_new(self.symbolic.solve_in_place_scratch::<f64>(b.ncols(), par)))?;
        LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(Conj::No, b, par, MemStack::new(&mut mem));
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The instruction sets compile the same operations in the same order:
    /// the vectorized block solves give the portable one's bits.
    #[test]
    fn every_instruction_set_solves_to_the_same_bits() {
        let c = Cholesky::new(&super::super::tests::grid(60, 50)).unwrap();
        let nodes = c.supernodes.as_ref().expect("a supernodal factor");
        let b: Vec<[f64; 32]> =
            (0..c.dim()).map(|i| std::array::from_fn(|j| ((i * 37 + j * 5) % 11) as f64 - 5.0)).collect();
        let mut portable = b.clone();
        nodes.solve_portable(&c.values, &mut portable);
        #[cfg(target_arch = "x86_64")]
        for (feature, supported) in [
            ("avx2", std::arch::is_x86_feature_detected!("avx2")),
            ("avx512f", std::arch::is_x86_feature_detected!("avx512f")),
        ] {
            if !supported {
                continue;
            }
            let mut x = b.clone();
            // SAFETY: the CPU supports the feature, checked just above.
            unsafe {
                if feature == "avx2" {
                    nodes.solve_avx2(&c.values, &mut x);
                } else {
                    nodes.solve_avx512(&c.values, &mut x);
                }
            }
            assert!(x == portable, "{feature}");
        }
        assert!(portable.iter().flatten().all(|v| v.is_finite()));
    }
}
