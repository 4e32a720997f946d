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

use faer::{Mat, MatMut, MatRef, Side};
use sprs::CsMat;

use super::tall;
use crate::error::{Result, SpectralError};

/// Multiple of the unit roundoff in the rounding level (`gamma_d` for the
/// 7-10 non-zeros of a mesh Laplacian's row, and the error of `x` itself).
const ROUNDING: f64 = 16.0 * f64::EPSILON;

/// Columns of `x` multiplied together by [`Stiffness`]: each stored entry of
/// `L` is read once per group and applied to this many contiguous values.
const GROUP: usize = 8;

/// The symmetric `L` of one component, applied to blocks of vectors.
pub(crate) struct Stiffness<'a> {
    l: &'a CsMat<f64>,
}

/// `L x`, and the column norms of `|L| |x|` (for the rounding level).
pub(crate) struct Products {
    pub lx: Mat<f64>,
    abs_norms: Vec<f64>,
}

impl<'a> Stiffness<'a> {
    /// Wraps a symmetric `L` (its compressed columns are its rows).
    pub fn new(l: &'a CsMat<f64>) -> Self {
        Self { l }
    }

    /// `L x` and the norms of the columns of `|L| |x|` in one pass over
    /// `L`, O(nnz k).
    pub fn apply(&self, x: MatRef<'_, f64>) -> Products {
        self.apply_into(x, Mat::new())
    }

    /// [`Self::apply`] writing `L x` into `buffer` when it has the shape of
    /// `x` (a block no longer needed: at 1e5-1e6 vertices and k = 200 a
    /// fresh n x k block costs more in the kernel's page zeroing than the
    /// products themselves).
    ///
    /// By groups of [`GROUP`] columns: `x` copied row by row, every row of
    /// `L` applied to the group's values of its neighbours (an 8-wide
    /// multiply-add per stored entry), the result copied back by columns.
    /// Every copy walks the rows once with the group's columns side by side
    /// (a pass per column reads every row of 8 values 8 times). Groups of 32
    /// were measured slower (9.5 s against 7.6 for 200 columns at 470k
    /// vertices, most of either in the kernel's zeroing of two fresh n x k
    /// outputs, `L x` and `|L| |x|`, of which only the first is kept now).
    pub fn apply_into(&self, x: MatRef<'_, f64>, buffer: Mat<f64>) -> Products {
        let (n, k) = (x.nrows(), x.ncols());
        let mut lx = if buffer.shape() == (n, k) { buffer } else { Mat::zeros(n, k) };
        let mut abs_norms = vec![0.0; k];
        let mut rows = vec![[0.0; GROUP]; n];
        let mut out = vec![[0.0; GROUP]; n];
        for g in (0..k).step_by(GROUP) {
            let width = GROUP.min(k - g);
            let cols: Vec<_> = (g..g + width).map(|j| tall::column(x, j)).collect();
            let cols: Vec<&[f64]> = cols.iter().map(|c| &c[..]).collect();
            to_rows(&cols, &mut rows);
            let mut squares = [0.0; GROUP];
            for (i, lane) in self.l.outer_iterator().enumerate() {
                let (mut acc, mut acc_abs) = ([0.0; GROUP], [0.0; GROUP]);
                for (r, &v) in lane.iter() {
                    let xr = &rows[r];
                    for c in 0..GROUP {
                        acc[c] += v * xr[c];
                        acc_abs[c] += v.abs() * xr[c].abs();
                    }
                }
                out[i] = acc;
                for c in 0..GROUP {
                    squares[c] += acc_abs[c] * acc_abs[c];
                }
            }
            from_rows(&out, lx.as_mut().subcols_mut(g, width));
            for (norm, sq) in abs_norms[g..g + width].iter_mut().zip(squares) {
                *norm = sq.sqrt();
            }
        }
        Products { lx, abs_norms }
    }
}

/// `rows[i][c] = cols[c][i]`, row after row (lanes past `cols.len()` keep
/// their values).
fn to_rows<const W: usize>(cols: &[&[f64]], rows: &mut [[f64; W]]) {
    for (i, row) in rows.iter_mut().enumerate() {
        for (lane, col) in row.iter_mut().zip(cols) {
            *lane = col[i];
        }
    }
}

/// `cols[(i, c)] = rows[i][c]` for the columns of `cols`, row after row.
pub(crate) fn from_rows<const W: usize>(rows: &[[f64; W]], cols: MatMut<'_, f64>) {
    let mut dst: Vec<_> = cols.col_iter_mut().collect();
    for (i, row) in rows.iter().enumerate() {
        for (d, &v) in dst.iter_mut().zip(row) {
            d[i] = v;
        }
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

/// Residuals and targets of the columns of `x` with values `values`, from
/// their products `p` (see [`Stiffness::apply`]). O(n k).
pub(crate) fn quality(
    p: &Products,
    mass: &[f64],
    values: &[f64],
    x: MatRef<'_, f64>,
    scale: f64,
    tolerance: f64,
) -> Quality {
    let mut q = Quality::default();
    for (j, &lambda) in values.iter().enumerate() {
        let (mut r, mut mx) = (0.0, 0.0);
        let lxj = p.lx.col_as_slice(j);
        for (i, &xi) in x.col(j).iter().enumerate() {
            let m = mass[i] * xi;
            r += (lxj[i] - lambda * m).powi(2);
            mx += m * m;
        }
        let (r, mx, lax) = (r.sqrt(), mx.sqrt(), p.abs_norms[j]);
        let denominator = (lambda.abs() + scale) * mx;
        let relative = if denominator > 0.0 { r / denominator } else { f64::INFINITY };
        let floor = if denominator > 0.0 { ROUNDING * (lax + lambda.abs() * mx) / denominator } else { 0.0 };
        q.relative.push(relative);
        q.absolute.push(if mx > 0.0 { r / mx } else { f64::INFINITY });
        q.target.push(tolerance.max(floor));
    }
    q
}

/// Rayleigh quotients `x^T L x / x^T M x` of the columns, from `L x`.
pub(crate) fn rayleigh_quotients(lx: &Mat<f64>, mass: &[f64], x: MatRef<'_, f64>) -> Vec<f64> {
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
/// `X R`, `R = C^-T S`, are M-orthonormal to rounding. From `X` and its
/// products `p` (`L X` and `|L| |X|`, those of the acceptance test), it
/// returns the values, `X R` and the products of `X R` without another pass
/// over `L`: `(L X) R`, and for the rounding of `(L X) R` the bound
/// `|| |L| |X| |r_j| || <= sum_i |r_ij| || |L| |x_i| ||` (R is close to a
/// permutation, the bound close to the norm itself; an 8-wide pass over `L`
/// per 8 vectors cost 270 ms for 20 vectors at 470k vertices). O(n k^2).
pub(crate) fn final_rayleigh_ritz(
    mass: &[f64],
    mut x: Mat<f64>,
    mut p: Products,
) -> Result<(Vec<f64>, Mat<f64>, Products)> {
    let k = x.ncols();
    let mut gram = Mat::zeros(k, k);
    tall::gram_weighted(gram.as_mut(), x.as_ref(), mass);
    let mut stiff = Mat::zeros(k, k);
    tall::gram(stiff.as_mut(), x.as_ref(), p.lx.as_ref());
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
    // In place: each of the two n x k blocks (hundreds of MB at 1e5-1e6
    // vertices and k = 200) would otherwise be paid again in fresh pages.
    let rotation = cinv.transpose() * eig.U();
    p.abs_norms = (0..k).map(|j| (0..k).map(|i| rotation[(i, j)].abs() * p.abs_norms[i]).sum()).collect();
    tall::rotate_in_place(p.lx.as_mut(), rotation.as_ref());
    tall::rotate_in_place(x.as_mut(), rotation.as_ref());
    Ok((values, x, p))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Path graph Laplacian on 3 vertices.
    fn path() -> sprs::CsMat<f64> {
        crate::eigen::problem::graph_laplacian(3, &[(0, 1), (1, 2)])
    }

    #[test]
    fn products_match_a_dense_product_over_partial_groups() {
        // A cycle of 30 vertices with chords; 11 columns (a full group of 8
        // and 3 more) and 75 (nine groups and 3 more).
        let edges: Vec<(usize, usize)> =
            (0..30).map(|i| (i, (i + 1) % 30)).chain((0..10).map(|i| (i, i + 15))).collect();
        let l = crate::eigen::problem::graph_laplacian(30, &edges);
        let dense = Mat::from_fn(30, 30, |i, j| l.get(i, j).copied().unwrap_or(0.0));
        for k in [11, 75] {
            let x = Mat::from_fn(30, k, |i, j| ((i * 7 + j * 3) % 11) as f64 - 5.0);
            let want = &dense * &x;
            let abs_want =
                Mat::from_fn(30, 30, |i, j| dense[(i, j)].abs()) * Mat::from_fn(30, k, |i, j| x[(i, j)].abs());
            let p = Stiffness::new(&l).apply(x.as_ref());
            assert!((&p.lx - &want).norm_max() < 1e-12, "{k} columns");
            for (j, norm) in p.abs_norms.iter().enumerate() {
                assert!((norm - abs_want.col(j).norm_l2()).abs() < 1e-12 * norm.max(1.0), "{k} columns, {j}");
            }
        }
    }

    #[test]
    fn exact_pairs_sit_at_rounding_and_wrong_ones_do_not() {
        let l = path();
        let st = Stiffness::new(&l);
        let mass = [1.0; 3];
        // Eigenpairs of the path: 0 (constant), 1 (1, 0, -1), 3 (1, -2, 1).
        let x = Mat::from_fn(3, 3, |i, j| [[1.0, 1.0, 1.0], [1.0, 0.0, -1.0], [1.0, -2.0, 1.0]][j][i]);
        let p = st.apply(x.as_ref());
        let q = quality(&p, &mass, &[0.0, 1.0, 3.0], x.as_ref(), 1.0, 1e-12);
        assert_eq!(q.misses(), 0, "{q:?}");
        assert!(q.relative.iter().all(|r| *r == 0.0));
        let q = quality(&p, &mass, &[0.0, 1.1, 3.0], x.as_ref(), 1.0, 1e-12);
        assert_eq!(q.misses(), 1);
        assert!((q.absolute[1] - 0.1).abs() < 1e-15 && (q.relative[1] - 0.1 / 2.1).abs() < 1e-15);
    }
}
