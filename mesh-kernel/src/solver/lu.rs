//! Sparse LU with partial pivoting (faer), for square non-symmetric systems.

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::Lu as FaerLu;
use faer::MatMut;
use sprs::CsMat;

use super::{check_rhs, check_square, to_faer};
use crate::error::{MeshError, Result};

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
