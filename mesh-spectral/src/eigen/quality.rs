//! How good a pair is: residuals relative to the spectrum's scale, the level
//! rounding alone produces, and the final Rayleigh-Ritz on the pencil.
//!
//! For a pair `(lambda, x)` of a component whose spectral scale is `s`
//! (Weyl's law, see [`super::component::spectral_scale`]):
//!
//! ```text
//! relative residual  rho = ||L x - lambda M x|| / ((|lambda| + s) ||M x||)
//! rounding level     f   = 16 eps (|| |L| |x| || + |lambda| ||M x||) / ((|lambda| + s) ||M x||)
//! ```
//!
//! `rho` is what [`super::EigenOptions::tolerance`] bounds (the normwise
//! relative residual of ARPACK-style shift-invert tests, made independent of
//! the shift actually used). `f` is the error of evaluating the residual
//! itself in double precision (Higham 2002, "Accuracy and Stability of
//! Numerical Algorithms", sec. 3.5: `|fl(A x) - A x| <= gamma_d |A| |x|`):
//! no vector does better, so the target of a pair is `max(tolerance, f)`.
//! On meshes of 1e5-1e6 vertices `f` reaches 1e-11 for the smallest pairs.

use faer::sparse::linalg::matmul::sparse_dense_matmul;
use faer::sparse::SparseColMat;
use faer::{Accum, Mat, MatRef, Side};

use super::tall;
use crate::error::{Result, SpectralError};

/// Multiple of the unit roundoff in the rounding level (`gamma_d` for the
/// 7-10 non-zeros of a mesh Laplacian's row, and the error of `x` itself).
const ROUNDING: f64 = 16.0 * f64::EPSILON;

/// `L` of one component in faer form, with `|L|` for the rounding level.
pub(crate) struct Stiffness {
    pub l: SparseColMat<usize, f64>,
    abs: SparseColMat<usize, f64>,
}

impl Stiffness {
    /// `L` and `|L|` converted to faer. O(nnz).
    ///
    /// # Errors
    /// `MeshError::Solver` (through the crate error) when faer cannot hold
    /// the matrix.
    pub fn new(l: &sprs::CsMat<f64>) -> Result<Self> {
        let abs = l.map(|v| v.abs());
        Ok(Self { l: mesh_kernel::solver::to_faer(l)?, abs: mesh_kernel::solver::to_faer(&abs)? })
    }
}

/// Per pair: relative residual, absolute residual `||L x - lambda M x|| /
/// ||M x||` and the target `max(tolerance, rounding level)`.
#[derive(Debug, Clone, Default)]
pub(crate) struct Quality {
    pub relative: Vec<f64>,
    pub absolute: Vec<f64>,
    pub target: Vec<f64>,
}

impl Quality {
    /// Pairs that miss their target (NaN counts as a miss).
    pub fn misses(&self) -> usize {
        self.relative.iter().zip(&self.target).filter(|(r, t)| r.is_nan() || r > t).count()
    }

    /// Each relative residual divided by its target (<= 1 passes).
    pub fn ratios(&self) -> Vec<f64> {
        self.relative.iter().zip(&self.target).map(|(r, t)| if r.is_nan() { f64::INFINITY } else { r / t }).collect()
    }
}

/// Residuals and targets of the columns of `x` with values `values`.
/// Two sparse products. O(nnz k).
pub(crate) fn quality(
    st: &Stiffness,
    mass: &[f64],
    values: &[f64],
    x: MatRef<'_, f64>,
    scale: f64,
    tolerance: f64,
) -> Quality {
    let lx = sparse_times(&st.l, x);
    let ax = abs_times(&st.abs, x);
    let mut q = Quality::default();
    for (j, &lambda) in values.iter().enumerate() {
        let (mut r, mut mx, mut lax) = (0.0, 0.0, 0.0);
        let (lxj, axj) = (lx.col_as_slice(j), ax.col_as_slice(j));
        for i in 0..x.nrows() {
            let m = mass[i] * x[(i, j)];
            r += (lxj[i] - lambda * m).powi(2);
            mx += m * m;
            lax += axj[i] * axj[i];
        }
        let (r, mx, lax) = (r.sqrt(), mx.sqrt(), lax.sqrt());
        let denominator = (lambda.abs() + scale) * mx;
        let relative = if denominator > 0.0 { r / denominator } else { f64::INFINITY };
        let floor = if denominator > 0.0 { ROUNDING * (lax + lambda.abs() * mx) / denominator } else { 0.0 };
        q.relative.push(relative);
        q.absolute.push(if mx > 0.0 { r / mx } else { f64::INFINITY });
        q.target.push(tolerance.max(floor));
    }
    q
}

/// Rayleigh quotients `x^T L x / x^T M x` of the columns (one sparse product).
pub(crate) fn rayleigh_quotients(l: &SparseColMat<usize, f64>, mass: &[f64], x: MatRef<'_, f64>) -> Vec<f64> {
    let lx = sparse_times(l, x);
    (0..x.ncols())
        .map(|j| {
            let (mut num, mut den) = (0.0, 0.0);
            for (i, (&xi, &lxi)) in x.col(j).iter().zip(lx.col_as_slice(j)).enumerate() {
                num += xi * lxi;
                den += mass[i] * xi * xi;
            }
            if den > 0.0 {
                num / den
            } else {
                f64::NAN
            }
        })
        .collect()
}

/// Rayleigh-Ritz of the pencil on span(X): with `X^T M X = C C^T`
/// (Cholesky) and `C^-1 X^T L X C^-T = S Lambda S^T`, the Ritz vectors
/// `X C^-T S` are M-orthonormal to rounding. O(n k^2).
pub(crate) fn final_rayleigh_ritz(
    l: &SparseColMat<usize, f64>,
    mass: &[f64],
    x: Mat<f64>,
) -> Result<(Vec<f64>, Mat<f64>)> {
    let (n, k) = (x.nrows(), x.ncols());
    let mut mx = x.clone();
    for j in 0..k {
        mx.col_as_slice_mut(j).iter_mut().zip(mass).for_each(|(v, m)| *v *= m);
    }
    let mut gram = Mat::zeros(k, k);
    tall::gram(gram.as_mut(), x.as_ref(), mx.as_ref());
    let lx = sparse_times(l, x.as_ref());
    let mut stiff = Mat::zeros(k, k);
    tall::gram(stiff.as_mut(), x.as_ref(), lx.as_ref());
    let sym = Mat::from_fn(k, k, |i, j| 0.5 * (gram[(i, j)] + gram[(j, i)]));
    let llt = sym
        .llt(Side::Lower)
        .map_err(|e| SpectralError::Dense(format!("eigenvectors are numerically dependent ({e:?})")))?;
    let mut cinv = Mat::zeros(k, k);
    faer::linalg::triangular_inverse::invert_lower_triangular(cinv.as_mut(), llt.L(), faer::Par::Seq);
    let a = &cinv * &stiff * cinv.transpose();
    let a = Mat::from_fn(k, k, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]));
    let eig = a.self_adjoint_eigen(Side::Lower).map_err(|e| SpectralError::Dense(format!("{e:?}")))?;
    let values = (0..k).map(|j| eig.S()[j]).collect();
    let rotation = cinv.transpose() * eig.U();
    let mut out = Mat::zeros(n, k);
    tall::mul(out.as_mut(), Accum::Replace, x.as_ref(), rotation.as_ref(), 1.0);
    Ok((values, out))
}

pub(crate) fn sparse_times(l: &SparseColMat<usize, f64>, x: MatRef<'_, f64>) -> Mat<f64> {
    let mut lx = Mat::zeros(x.nrows(), x.ncols());
    sparse_dense_matmul(lx.as_mut(), Accum::Replace, l.as_ref(), x, 1.0, faer::get_global_parallelism());
    lx
}

/// `|L| |x|` column by column.
fn abs_times(abs: &SparseColMat<usize, f64>, x: MatRef<'_, f64>) -> Mat<f64> {
    let ax = Mat::from_fn(x.nrows(), x.ncols(), |i, j| x[(i, j)].abs());
    sparse_times(abs, ax.as_ref())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Path graph Laplacian on 3 vertices.
    fn path() -> sprs::CsMat<f64> {
        crate::eigen::problem::graph_laplacian(3, &[(0, 1), (1, 2)])
    }

    #[test]
    fn exact_pairs_sit_at_rounding_and_wrong_ones_do_not() {
        let st = Stiffness::new(&path()).unwrap();
        let mass = [1.0; 3];
        // Eigenpairs of the path: 0 (constant), 1 (1, 0, -1), 3 (1, -2, 1).
        let x = Mat::from_fn(3, 3, |i, j| [[1.0, 1.0, 1.0], [1.0, 0.0, -1.0], [1.0, -2.0, 1.0]][j][i]);
        let q = quality(&st, &mass, &[0.0, 1.0, 3.0], x.as_ref(), 1.0, 1e-12);
        assert_eq!(q.misses(), 0, "{q:?}");
        assert!(q.relative.iter().all(|r| *r == 0.0));
        let q = quality(&st, &mass, &[0.0, 1.1, 3.0], x.as_ref(), 1.0, 1e-12);
        assert_eq!(q.misses(), 1);
        assert!((q.absolute[1] - 0.1).abs() < 1e-15 && (q.relative[1] - 0.1 / 2.1).abs() < 1e-15);
    }
}
