//! Linear systems with some unknowns fixed (Dirichlet conditions).

use sprs::CsMat;

use super::{check_square, Cholesky, Lu};
use crate::error::{MeshError, Result};

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
