//! Sparse linear solvers on faer, shared by every crate of the workspace.
//!
//! - [`Cholesky`]: a sparse (supernodal or simplicial, chosen by faer)
//!   Cholesky factorization of a symmetric positive definite matrix, reused
//!   across any number of right-hand sides and refactorable with the same
//!   pattern (heat method, shift-invert eigensolvers).
//! - [`Lu`]: sparse LU with partial pivoting for non-symmetric systems (the
//!   asymmetric parameterization weights).
//! - [`DirichletSolver`]: fix some unknowns, factor the rest once, solve for
//!   any boundary values and right-hand sides.
//!
//! Matrices come in as `sprs::CsMat<f64>` (CSR or CSC); conversion to faer is
//! a copy of the raw arrays. Factorization errors (not positive definite,
//! singular) are [`MeshError::Solver`]; NaN or infinite entries are refused
//! before factoring.

use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::linalg::solvers::Lu as FaerLu;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par, Side, Spec};
use sprs::CsMat;

use crate::error::{MeshError, Result};

/// Copies a sprs matrix into faer's compressed-column format.
///
/// # Errors
/// [`MeshError::Solver`] when faer cannot hold the matrix (out of memory or index overflow).
pub fn to_faer(a: &CsMat<f64>) -> Result<SparseColMat<usize, f64>> {
    let csc;
    let a = if a.is_csc() {
        a
    } else {
        csc = a.to_csc();
        &csc
    };
    if let Some(bad) = a.data().iter().find(|v| !v.is_finite()) {
        return Err(MeshError::Solver(format!("matrix has a non-finite entry ({bad})")));
    }
    let (nrows, ncols) = a.shape();
    let symbolic = SymbolicSparseColMat::new_checked(
        nrows,
        ncols,
        a.indptr().to_proper().into_owned(),
        None,
        a.indices().to_vec(),
    );
    Ok(SparseColMat::new(symbolic, a.data().to_vec()))
}

fn check_square(a: &CsMat<f64>) -> Result<usize> {
    let (r, c) = a.shape();
    if r != c {
        return Err(MeshError::Dimension(format!("matrix is {r} x {c}, not square")));
    }
    Ok(r)
}

fn check_rhs(n: usize, len: usize) -> Result<()> {
    if !len.is_multiple_of(n.max(1)) || (n == 0 && len != 0) {
        return Err(MeshError::Dimension(format!("right-hand side of length {len} for {n} unknowns")));
    }
    Ok(())
}

/// Unknowns from which the supernodal Cholesky is forced: faer's automatic
/// choice keeps the simplicial one on 2D meshes up to ~50k unknowns, where
/// the supernodal one factors up to 1.7x faster (crossover measured at
/// 2.5k-3.5k unknowns on disks).
const SUPERNODAL_FROM: usize = 2000;

/// Unknowns below which factorizations and solves run on one thread: on the
/// 2-core machines measured, threads made 8k-unknown factorizations 1.5x
/// slower.
const PARALLEL_FROM: usize = 100_000;

/// faer's global parallelism for large systems, one thread for small ones.
fn parallelism(n: usize) -> Par {
    if n >= PARALLEL_FROM {
        faer::get_global_parallelism()
    } else {
        Par::Seq
    }
}

fn memory<T>(req: Result<MemBuffer, T>) -> Result<MemBuffer> {
    req.map_err(|_| MeshError::Solver("out of memory for the sparse factorization".into()))
}

/// Sparse Cholesky factorization `A = L L^T` of a symmetric positive definite
/// matrix (only its lower triangle is read), with AMD fill-reducing ordering,
/// the supernodal variant from 2000 unknowns and one thread below 100k.
#[derive(Debug, Clone)]
pub struct Cholesky {
    symbolic: Arc<SymbolicCholesky<usize>>,
    values: Vec<f64>,
    /// The analysed sparsity pattern (column pointers, row indices), to
    /// check that [`Cholesky::refactor`] gets the same one.
    pattern: Arc<(Vec<usize>, Vec<usize>)>,
}

impl Cholesky {
    /// Analyses and factors `a`. Cost: one symbolic analysis plus one numeric
    /// factorization (for a 40k-vertex Laplacian about 0.1 s on this machine
    /// class). Fails when `a` is not positive definite.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] for a matrix that is not square; [`MeshError::Solver`] when it is
    /// not symmetric positive definite (naming the failing pivot) or memory runs out.
    pub fn new(a: &CsMat<f64>) -> Result<Self> {
        check_square(a)?;
        let a = to_faer(a)?;
        let threshold = if a.nrows() >= SUPERNODAL_FROM {
            SupernodalThreshold::FORCE_SUPERNODAL
        } else {
            SupernodalThreshold::AUTO
        };
        let params = CholeskySymbolicParams { supernodal_flop_ratio_threshold: threshold, ..Default::default() };
        let symbolic = factorize_symbolic_cholesky(a.symbolic(), Side::Lower, SymmetricOrdering::Amd, params)
            .map_err(|e| MeshError::Solver(format!("symbolic Cholesky failed: {e:?}")))?;
        let pattern = (a.symbolic().col_ptr().to_vec(), a.symbolic().row_idx().to_vec());
        let mut this = Self { symbolic: Arc::new(symbolic), values: Vec::new(), pattern: Arc::new(pattern) };
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
        if check_square(a)? != self.dim() {
            return Err(MeshError::Dimension(format!("refactor with {} rows, expected {}", a.rows(), self.dim())));
        }
        let a = to_faer(a)?;
        if a.symbolic().col_ptr() != self.pattern.0 || a.symbolic().row_idx() != self.pattern.1 {
            return Err(MeshError::Dimension("refactor with a different sparsity pattern".into()));
        }
        self.factor_numeric(&a)
    }

    /// Number of unknowns.
    pub fn dim(&self) -> usize {
        self.symbolic.nrows()
    }

    /// Solves `A x = b` in place; `b` may hold several right-hand sides one
    /// after the other (column-major, `b.len()` a multiple of the dimension).
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
        self.solve_mat_in_place(MatMut::from_column_major_slice_mut(b, n, b.len() / n))
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

    /// Solves in place for the columns of a faer matrix.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] for a row count other than the dimension; [`MeshError::Solver`]
    /// when the workspace cannot be allocated.
    pub fn solve_mat_in_place(&self, b: MatMut<'_, f64>) -> Result<()> {
        let n = self.dim();
        if b.nrows() != n {
            return Err(MeshError::Dimension(format!("{} rows for {n} unknowns", b.nrows())));
        }
        let par = parallelism(n);
        let mut mem = memory(MemBuffer::try_new(self.symbolic.solve_in_place_scratch::<f64>(b.ncols(), par)))?;
        LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(Conj::No, b, par, MemStack::new(&mut mem));
        Ok(())
    }
}

/// Sparse LU factorization with partial pivoting, for square non-symmetric
/// systems.
#[derive(Debug, Clone)]
pub struct Lu {
    n: usize,
    factor: FaerLu<usize, f64>,
}

impl Lu {
    /// Factors `a`. Fails on structurally or numerically singular matrices
    /// (faer reports these) and checks the factors on a probe solve.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] for a matrix that is not square; [`MeshError::Solver`] when it is
    /// singular.
    pub fn new(a: &CsMat<f64>) -> Result<Self> {
        let n = check_square(a)?;
        let fa = to_faer(a)?;
        let factor = fa.sp_lu().map_err(|e| MeshError::Solver(format!("LU factorization failed: {e:?}")))?;
        let lu = Self { n, factor };
        // faer does not report numerical singularity: detect it by solving.
        let probe = lu.solve(&vec![1.0; n])?;
        if probe.iter().any(|x| !x.is_finite()) {
            return Err(MeshError::Solver("LU factorization failed: the matrix is singular".into()));
        }
        Ok(lu)
    }

    /// Number of unknowns.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Solves `A x = b` in place for one or several stacked right-hand sides.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] when `b.len()` is not a multiple of the dimension.
    pub fn solve_in_place(&self, b: &mut [f64]) -> Result<()> {
        check_rhs(self.n, b.len())?;
        if self.n == 0 {
            return Ok(());
        }
        let k = b.len() / self.n;
        self.factor.solve_in_place(MatMut::from_column_major_slice_mut(b, self.n, k));
        Ok(())
    }

    /// Solves `A x = b` for one or several stacked right-hand sides.
    ///
    /// # Errors
    /// Those of [`Lu::solve_in_place`].
    pub fn solve(&self, b: &[f64]) -> Result<Vec<f64>> {
        let mut x = b.to_vec();
        self.solve_in_place(&mut x)?;
        Ok(x)
    }
}

/// Which factorization a [`DirichletSolver`] uses for the free block.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Factorization {
    /// Cholesky: the free block must be symmetric positive definite.
    #[default]
    Cholesky,
    /// LU: any non-singular free block.
    Lu,
    /// Cholesky, falling back to LU when the free block is not positive
    /// definite (for symmetric systems of unknown sign).
    CholeskyOrLu,
}

#[derive(Debug, Clone)]
enum Factor {
    Cholesky(Cholesky),
    Lu(Box<Lu>),
}

/// Solves `A x = b` with some unknowns fixed (Dirichlet conditions): the free
/// unknowns satisfy `A_ff x_f = b_f - A_fc x_c`. The free and coupling
/// blocks are cut out of the CSR rows in O(nnz) (renumbering is monotone, so
/// rows stay sorted), the free block is factored once, and
/// [`DirichletSolver::solve_many`] takes any number of systems (fixed values
/// and right-hand sides) through the factorization together.
#[derive(Debug, Clone)]
pub struct DirichletSolver {
    n: usize,
    free: Vec<usize>,
    fixed: Vec<usize>,
    /// The coupling block A_fc in CSR (rows: free, columns: fixed).
    coupling: CsMat<f64>,
    factor: Factor,
}

impl DirichletSolver {
    /// Splits `a` into free and `fixed` unknowns (indices, any order,
    /// duplicates ignored) and factors the free block.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] for a matrix that is not square or a fixed index out of range; the
    /// errors of the chosen factorization of the free block.
    pub fn new(a: &CsMat<f64>, fixed: &[usize], factorization: Factorization) -> Result<Self> {
        let n = check_square(a)?;
        let mut is_fixed = vec![false; n];
        for &i in fixed {
            if i >= n {
                return Err(MeshError::Dimension(format!("fixed unknown {i} out of range 0..{n}")));
            }
            is_fixed[i] = true;
        }
        let fixed: Vec<usize> = (0..n).filter(|&i| is_fixed[i]).collect();
        let free: Vec<usize> = (0..n).filter(|&i| !is_fixed[i]).collect();
        let mut free_index = vec![usize::MAX; n];
        let mut fixed_index = vec![usize::MAX; n];
        for (k, &i) in free.iter().enumerate() {
            free_index[i] = k;
        }
        for (k, &i) in fixed.iter().enumerate() {
            fixed_index[i] = k;
        }
        let csr_copy;
        let csr = if a.is_csr() {
            a
        } else {
            csr_copy = a.to_csr();
            &csr_copy
        };
        let nf = free.len();
        let (mut ff_ptr, mut ff_idx, mut ff_val) = (vec![0], Vec::new(), Vec::new());
        let (mut fc_ptr, mut fc_idx, mut fc_val) = (vec![0], Vec::new(), Vec::new());
        for &i in &free {
            if let Some(row) = csr.outer_view(i) {
                for (j, &v) in row.iter() {
                    if is_fixed[j] {
                        fc_idx.push(fixed_index[j]);
                        fc_val.push(v);
                    } else {
                        ff_idx.push(free_index[j]);
                        ff_val.push(v);
                    }
                }
            }
            ff_ptr.push(ff_idx.len());
            fc_ptr.push(fc_idx.len());
        }
        let coupling = CsMat::new((nf, fixed.len()), fc_ptr, fc_idx, fc_val);
        let ff = CsMat::new((nf, nf), ff_ptr, ff_idx, ff_val);
        let factor = match factorization {
            Factorization::Cholesky => Factor::Cholesky(Cholesky::new(&ff)?),
            Factorization::Lu => Factor::Lu(Box::new(Lu::new(&ff)?)),
            Factorization::CholeskyOrLu => match Cholesky::new(&ff) {
                Ok(c) => Factor::Cholesky(c),
                Err(_) => Factor::Lu(Box::new(Lu::new(&ff)?)),
            },
        };
        Ok(Self { n, free, fixed, coupling, factor })
    }

    /// The fixed unknowns, sorted.
    pub fn fixed(&self) -> &[usize] {
        &self.fixed
    }

    /// The free unknowns, sorted.
    pub fn free(&self) -> &[usize] {
        &self.free
    }

    /// The factorization used for the free block (Cholesky or Lu).
    pub fn factorization(&self) -> Factorization {
        match self.factor {
            Factor::Cholesky(_) => Factorization::Cholesky,
            Factor::Lu(_) => Factorization::Lu,
        }
    }

    /// Solves for all `n` unknowns given the values of the fixed ones (in the
    /// order of [`DirichletSolver::fixed`]) and the right-hand side `b` (length
    /// n; `None` for zero). Fixed entries of the result equal the given values.
    ///
    /// # Errors
    /// Those of [`DirichletSolver::solve_many`].
    pub fn solve(&self, fixed_values: &[f64], b: Option<&[f64]>) -> Result<Vec<f64>> {
        let rhs = b.map(|b| [b]);
        let mut x = self.solve_many(&[fixed_values], rhs.as_ref().map(|r| &r[..]))?;
        Ok(x.pop().unwrap_or_default())
    }

    /// Solves `k = fixed_values.len()` systems at once (one pass through the
    /// factorization): system `c` has fixed values `fixed_values[c]` and
    /// right-hand side `rhs[c]` (zero when `rhs` is `None`). A non-finite
    /// solution is an error naming the unknown.
    ///
    /// # Errors
    /// [`MeshError::Dimension`] for value or right-hand-side lengths that do not match;
    /// [`MeshError::Solver`] naming the first unknown whose solution is not finite.
    pub fn solve_many(&self, fixed_values: &[&[f64]], rhs: Option<&[&[f64]]>) -> Result<Vec<Vec<f64>>> {
        let k = fixed_values.len();
        if let Some(r) = rhs {
            if r.len() != k || r.iter().any(|b| b.len() != self.n) {
                return Err(MeshError::Dimension(format!("right-hand sides must be {k} vectors of length {}", self.n)));
            }
        }
        let nf = self.free.len();
        let mut b = vec![0.0; nf * k];
        for (c, values) in fixed_values.iter().enumerate() {
            if values.len() != self.fixed.len() {
                return Err(MeshError::Dimension(format!(
                    "{} fixed values for {} fixed unknowns",
                    values.len(),
                    self.fixed.len()
                )));
            }
            let inputs = values.iter().chain(rhs.map_or(&[][..], |r| r[c]));
            if let Some(bad) = inputs.into_iter().find(|v| !v.is_finite()) {
                return Err(MeshError::Solver(format!("non-finite input value {bad}")));
            }
            let col = &mut b[c * nf..(c + 1) * nf];
            if let Some(r) = rhs {
                for (fi, &i) in self.free.iter().enumerate() {
                    col[fi] = r[c][i];
                }
            }
            for (fi, row) in self.coupling.outer_iterator().enumerate() {
                col[fi] -= row.iter().map(|(j, v)| v * values[j]).sum::<f64>();
            }
        }
        match &self.factor {
            Factor::Cholesky(c) => c.solve_in_place(&mut b)?,
            Factor::Lu(l) => l.solve_in_place(&mut b)?,
        }
        let mut out = Vec::with_capacity(k);
        for (c, values) in fixed_values.iter().enumerate() {
            let col = &b[c * nf..(c + 1) * nf];
            let mut x = vec![0.0; self.n];
            for (fi, &i) in self.free.iter().enumerate() {
                x[i] = col[fi];
            }
            for (slot, &i) in self.fixed.iter().enumerate() {
                x[i] = values[slot];
            }
            if let Some(i) = x.iter().position(|v| !v.is_finite()) {
                return Err(MeshError::Solver(format!("the solution is not finite at unknown {i}")));
            }
            out.push(x);
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sprs::TriMat;

    /// 1D Laplacian of a path with n vertices plus `shift` on the diagonal.
    fn path(n: usize, shift: f64) -> CsMat<f64> {
        let mut t = TriMat::new((n, n));
        for i in 0..n {
            t.add_triplet(i, i, shift);
            if i + 1 < n {
                t.add_triplet(i, i, 1.0);
                t.add_triplet(i + 1, i + 1, 1.0);
                t.add_triplet(i, i + 1, -1.0);
                t.add_triplet(i + 1, i, -1.0);
            }
        }
        t.to_csr()
    }

    fn residual(a: &CsMat<f64>, x: &[f64], b: &[f64]) -> f64 {
        a.outer_iterator()
            .enumerate()
            .map(|(i, row)| (row.iter().map(|(j, v)| v * x[j]).sum::<f64>() - b[i]).abs())
            .fold(0.0, f64::max)
    }

    #[test]
    fn cholesky_solves_and_refactors() {
        let a = path(50, 0.1);
        let mut c = Cholesky::new(&a).unwrap();
        let b: Vec<f64> = (0..50).map(|i| (i as f64).sin()).collect();
        let x = c.solve(&b).unwrap();
        assert!(residual(&a, &x, &b) < 1e-12);
        let a2 = path(50, 2.0);
        c.refactor(&a2).unwrap();
        assert!(c.refactor(&path(49, 2.0)).is_err());
        let mut other = TriMat::new((50, 50));
        (0..50).for_each(|i| other.add_triplet(i, i, 1.0));
        assert!(c.refactor(&other.to_csr()).is_err());
        let x = c.solve(&b).unwrap();
        assert!(residual(&a2, &x, &b) < 1e-12);
        // Two right-hand sides at once.
        let mut bb = b.clone();
        bb.extend(b.iter().map(|v| 2.0 * v));
        let xx = c.solve(&bb).unwrap();
        assert!((xx[50 + 7] - 2.0 * xx[7]).abs() < 1e-12);
        assert!(c.solve(&b[..10]).is_err());
    }

    #[test]
    fn cholesky_refuses_indefinite_and_nan() {
        assert!(matches!(Cholesky::new(&path(10, 0.0)), Err(MeshError::Solver(_))));
        let mut t = TriMat::new((2, 2));
        t.add_triplet(0, 0, f64::NAN);
        t.add_triplet(1, 1, 1.0);
        assert!(Cholesky::new(&t.to_csr()).is_err());
        assert!(Cholesky::new(&CsMat::zero((2, 3))).is_err());
    }

    #[test]
    fn lu_solves_nonsymmetric() {
        let mut t = TriMat::new((3, 3));
        for (i, j, v) in [(0, 0, 4.0), (0, 1, 1.0), (1, 0, 2.0), (1, 1, 5.0), (1, 2, 1.0), (2, 1, 3.0), (2, 2, 6.0)] {
            t.add_triplet(i, j, v);
        }
        let a: CsMat<f64> = t.to_csr();
        let b = [1.0, 2.0, 3.0];
        let x = Lu::new(&a).unwrap().solve(&b).unwrap();
        assert!(residual(&a, &x, &b) < 1e-14);
        // Symmetric indefinite: Cholesky fails, CholeskyOrLu falls back.
        let mut t = TriMat::new((2, 2));
        for (i, j, v) in [(0, 0, 1.0), (0, 1, 2.0), (1, 0, 2.0), (1, 1, 1.0)] {
            t.add_triplet(i, j, v);
        }
        let s = DirichletSolver::new(&t.to_csr(), &[], Factorization::CholeskyOrLu).unwrap();
        assert_eq!(s.factorization(), Factorization::Lu);
        let x = s.solve(&[], Some(&[3.0, 3.0])).unwrap();
        assert!((x[0] - 1.0).abs() < 1e-14 && (x[1] - 1.0).abs() < 1e-14);
        let mut s = TriMat::new((2, 2));
        s.add_triplet(0, 0, 1.0);
        s.add_triplet(0, 1, 1.0);
        s.add_triplet(1, 0, 1.0);
        s.add_triplet(1, 1, 1.0);
        assert!(Lu::new(&s.to_csr()).is_err());
    }

    #[test]
    fn dirichlet_interpolates_linearly_on_a_path() {
        // Harmonic on a path with ends fixed at 0 and 1: linear.
        let a = path(11, 0.0);
        for fact in [Factorization::Cholesky, Factorization::Lu] {
            let s = DirichletSolver::new(&a, &[10, 0], fact).unwrap();
            assert_eq!(s.fixed(), &[0, 10]);
            let x = s.solve(&[0.0, 1.0], None).unwrap();
            for (i, xi) in x.iter().enumerate() {
                assert!((xi - i as f64 / 10.0).abs() < 1e-13);
            }
            // Two systems at once: the second reversed.
            let both = s.solve_many(&[&[0.0, 1.0], &[1.0, 0.0]], None).unwrap();
            assert_eq!(both[0], x);
            assert!((both[1][3] - 0.7).abs() < 1e-13);
        }
        assert!(DirichletSolver::new(&a, &[11], Factorization::Cholesky).is_err());
    }
}
