//! A Dirichlet-constrained sparse solve tuned for this crate: the free and
//! coupling blocks are cut out of a CSR matrix in O(nnz) (the renumbering is
//! monotone, so rows stay sorted: no triplet sort), and all right-hand sides
//! go through the factorization together.
//!
//! This is what `mesh_core::solver::DirichletSolver` does, minus its
//! triplet round trip (a third of the time of a harmonic map on 8k
//! vertices), with several right-hand sides per call, and with the
//! supernodal Cholesky forced from 2000 unknowns on: faer's automatic choice
//! keeps the simplicial one for 2D meshes up to ~50k vertices, where the
//! supernodal one factors up to 1.7x faster (measured crossover 2.5k-3.5k
//! unknowns on jittered disks, below 2.3k on cgal_mushroom).

use std::sync::Arc;

use mesh_core::faer::dyn_stack::{MemBuffer, MemStack};
use mesh_core::faer::linalg::cholesky::llt::factor::LltRegularization;
use mesh_core::faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use mesh_core::faer::sparse::linalg::SupernodalThreshold;
use mesh_core::faer::{Conj, MatMut, Par, Side, Spec};
use mesh_core::solver::{to_faer, Factorization, Lu};
use mesh_core::sprs::CsMat;
use mesh_core::MeshError;

use crate::error::{ParamError, Result};

/// Unknowns from which the supernodal Cholesky is forced.
const SUPERNODAL_FROM: usize = 2000;

/// Unknowns below which the factorization runs on one thread: on the 2-core
/// machines measured, threads made 8k-unknown factorizations 1.5x slower.
const PARALLEL_FROM: usize = 100_000;

/// faer's global parallelism for large systems, one thread for small ones.
fn parallelism(n: usize) -> Par {
    if n >= PARALLEL_FROM {
        mesh_core::faer::get_global_parallelism()
    } else {
        Par::Seq
    }
}

#[derive(Debug, Clone)]
enum Factor {
    Cholesky(Llt),
    Lu(Box<Lu>),
}

/// A sparse LL^T factorization (faer, AMD ordering) that picks the
/// supernodal variant for large systems.
#[derive(Debug, Clone)]
struct Llt {
    symbolic: Arc<SymbolicCholesky<usize>>,
    values: Vec<f64>,
}

impl Llt {
    /// Factors the symmetric matrix `a` (CSC, lower triangle read).
    fn new(a: &CsMat<f64>) -> Result<Self> {
        let a = to_faer(a)?;
        let threshold = if a.nrows() >= SUPERNODAL_FROM {
            SupernodalThreshold::FORCE_SUPERNODAL
        } else {
            SupernodalThreshold::AUTO
        };
        let params = CholeskySymbolicParams { supernodal_flop_ratio_threshold: threshold, ..Default::default() };
        let symbolic = factorize_symbolic_cholesky(a.symbolic(), Side::Lower, SymmetricOrdering::Amd, params)
            .map_err(|e| MeshError::Solver(format!("symbolic Cholesky failed: {e:?}")))?;
        let par = parallelism(a.nrows());
        let mut values = vec![0.0; symbolic.len_val()];
        let mut mem = MemBuffer::try_new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Spec::default()))
            .map_err(|_| MeshError::Solver("out of memory for the Cholesky factorization".into()))?;
        symbolic
            .factorize_numeric_llt(
                &mut values,
                a.as_ref(),
                Side::Lower,
                LltRegularization::default(),
                par,
                MemStack::new(&mut mem),
                Spec::default(),
            )
            .map_err(|e| MeshError::Solver(format!("Cholesky failed, the matrix is not positive definite ({e:?})")))?;
        Ok(Self { symbolic: Arc::new(symbolic), values })
    }

    /// Solves in place for `b.len() / n` stacked right-hand sides.
    fn solve_in_place(&self, b: &mut [f64]) -> Result<()> {
        let n = self.symbolic.nrows();
        if n == 0 {
            return Ok(());
        }
        let k = b.len() / n;
        let par = parallelism(n);
        let mut mem = MemBuffer::try_new(self.symbolic.solve_in_place_scratch::<f64>(k, par))
            .map_err(|_| MeshError::Solver("out of memory for the Cholesky solve".into()))?;
        LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(b, n, k),
            par,
            MemStack::new(&mut mem),
        );
        Ok(())
    }
}

/// `A x = b` with the unknowns flagged in `is_fixed` given: the free block
/// A_ff is factored once, A_fc moves the fixed values to the right side.
#[derive(Debug, Clone)]
pub(crate) struct Dirichlet {
    n: usize,
    /// Position among the free unknowns, `usize::MAX` for fixed ones.
    free_index: Vec<usize>,
    /// Fixed unknowns, increasing.
    fixed: Vec<usize>,
    /// A_fc in CSR, columns numbered as in `fixed`.
    coupling: CsMat<f64>,
    factor: Factor,
}

impl Dirichlet {
    /// Splits the square CSR matrix `a` and factors its free block: Cholesky
    /// when `symmetric` (LU if that fails), else LU.
    pub(crate) fn new(a: &CsMat<f64>, is_fixed: &[bool], symmetric: bool) -> Result<Self> {
        let n = a.rows();
        if a.cols() != n || is_fixed.len() != n || !a.is_csr() {
            return Err(
                MeshError::Dimension(format!("{} x {} CSR matrix, {} flags", n, a.cols(), is_fixed.len())).into()
            );
        }
        let mut free_index = vec![usize::MAX; n];
        let mut fixed_index = vec![usize::MAX; n];
        let mut fixed = Vec::new();
        let mut nf = 0;
        for i in 0..n {
            if is_fixed[i] {
                fixed_index[i] = fixed.len();
                fixed.push(i);
            } else {
                free_index[i] = nf;
                nf += 1;
            }
        }
        let (mut ff_ptr, mut ff_idx, mut ff_val) = (vec![0], Vec::new(), Vec::new());
        let (mut fc_ptr, mut fc_idx, mut fc_val) = (vec![0], Vec::new(), Vec::new());
        for (i, row) in a.outer_iterator().enumerate() {
            if is_fixed[i] {
                continue;
            }
            for (j, &v) in row.iter() {
                if is_fixed[j] {
                    fc_idx.push(fixed_index[j]);
                    fc_val.push(v);
                } else {
                    ff_idx.push(free_index[j]);
                    ff_val.push(v);
                }
            }
            ff_ptr.push(ff_idx.len());
            fc_ptr.push(fc_idx.len());
        }
        let coupling = CsMat::new((nf, fixed.len()), fc_ptr, fc_idx, fc_val);
        let factor = if symmetric {
            // A symmetric CSR block is its own CSC.
            let ff = CsMat::new_csc((nf, nf), ff_ptr, ff_idx, ff_val);
            match Llt::new(&ff) {
                Ok(c) => Factor::Cholesky(c),
                Err(_) => Factor::Lu(Box::new(Lu::new(&ff)?)),
            }
        } else {
            let ff = CsMat::new((nf, nf), ff_ptr, ff_idx, ff_val).to_csc();
            Factor::Lu(Box::new(Lu::new(&ff)?))
        };
        Ok(Self { n, free_index, fixed, coupling, factor })
    }

    /// The fixed unknowns, increasing.
    pub(crate) fn fixed(&self) -> &[usize] {
        &self.fixed
    }

    /// Which factorization was used.
    pub(crate) fn factorization(&self) -> Factorization {
        match self.factor {
            Factor::Cholesky(_) => Factorization::Cholesky,
            Factor::Lu(_) => Factorization::Lu,
        }
    }

    /// Solves for k systems at once: `fixed_values[c]` holds the values of the
    /// fixed unknowns (in the order of [`Dirichlet::fixed`]) and `rhs[c]`,
    /// if given, the full right-hand side of system c. Returns the k full
    /// solutions; fails on a non-finite result.
    pub(crate) fn solve(&self, fixed_values: &[&[f64]], rhs: Option<&[&[f64]]>) -> Result<Vec<Vec<f64>>> {
        let k = fixed_values.len();
        let nf = self.n - self.fixed.len();
        let mut b = vec![0.0; nf * k];
        for (c, values) in fixed_values.iter().enumerate() {
            if values.len() != self.fixed.len() {
                return Err(
                    MeshError::Dimension(format!("{} values for {} fixed", values.len(), self.fixed.len())).into()
                );
            }
            let col = &mut b[c * nf..(c + 1) * nf];
            if let Some(r) = rhs.and_then(|r| r.get(c)) {
                for (i, &fi) in self.free_index.iter().enumerate() {
                    if fi != usize::MAX {
                        col[fi] = r.get(i).copied().unwrap_or(0.0);
                    }
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
            for (i, &fi) in self.free_index.iter().enumerate() {
                if fi != usize::MAX {
                    x[i] = col[fi];
                }
            }
            for (slot, &i) in self.fixed.iter().enumerate() {
                x[i] = values[slot];
            }
            if let Some(vertex) = x.iter().position(|v| !v.is_finite()) {
                return Err(ParamError::NonFinite { vertex: vertex % self.n });
            }
            out.push(x);
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_core::solver::DirichletSolver;
    use mesh_core::sprs::TriMat;

    /// A random-ish non-symmetric diagonally dominant matrix.
    fn matrix(n: usize, symmetric: bool) -> CsMat<f64> {
        let mut t = TriMat::new((n, n));
        for i in 0..n {
            t.add_triplet(i, i, 4.0 + (i % 3) as f64);
            for j in [(i + 1) % n, (i + 5) % n] {
                if j != i {
                    let v = -0.5 - 0.1 * ((i * 7 + j) % 4) as f64;
                    t.add_triplet(i, j, v);
                    t.add_triplet(j, i, if symmetric { v } else { v * 0.7 });
                }
            }
        }
        t.to_csr()
    }

    #[test]
    fn agrees_with_mesh_core() {
        for symmetric in [true, false] {
            let a = matrix(40, symmetric);
            let fixed = [3usize, 17, 0, 39];
            let mut is_fixed = vec![false; 40];
            fixed.iter().for_each(|&i| is_fixed[i] = true);
            let ours = Dirichlet::new(&a, &is_fixed, symmetric).unwrap();
            let fact = if symmetric { Factorization::Cholesky } else { Factorization::Lu };
            assert_eq!(ours.factorization(), fact);
            let theirs = DirichletSolver::new(&a, &fixed, fact).unwrap();
            assert_eq!(ours.fixed(), theirs.fixed());
            let v1 = [1.0, -2.0, 0.5, 3.0];
            let v2 = [0.0, 1.0, 1.0, -1.0];
            let b: Vec<f64> = (0..40).map(|i| (i as f64).cos()).collect();
            let got = ours.solve(&[&v1, &v2], Some(&[&b, &b])).unwrap();
            for (x, v) in got.iter().zip([v1, v2]) {
                let want = theirs.solve(&v, Some(&b)).unwrap();
                assert!(x.iter().zip(&want).all(|(p, q)| (p - q).abs() < 1e-13));
            }
            assert!(ours.solve(&[&v1[..2]], None).is_err());
        }
        let a = matrix(5, true);
        assert!(Dirichlet::new(&a, &[false; 4], true).is_err());
    }
}
