//! The constrained solves of this crate: a thin front for
//! [`mesh_kernel::solver::DirichletSolver`], which cuts the free block out of
//! the CSR matrix in O(nnz) and solves u and v (or all systems) together.

use mesh_kernel::solver::{DirichletSolver, Factorization};
use mesh_kernel::sprs::CsMat;

use crate::error::Result;

/// Factors the free block of `a` (the unknowns not flagged in `is_fixed`):
/// Cholesky for symmetric weights (LU if the block is not positive definite),
/// LU otherwise.
pub(crate) fn dirichlet_solver(a: &CsMat<f64>, is_fixed: &[bool], symmetric: bool) -> Result<DirichletSolver> {
    let fixed: Vec<usize> = is_fixed.iter().enumerate().filter(|(_, f)| **f).map(|(i, _)| i).collect();
    let factorization = if symmetric { Factorization::CholeskyOrLu } else { Factorization::Lu };
    Ok(DirichletSolver::new(a, &fixed, factorization)?)
}
