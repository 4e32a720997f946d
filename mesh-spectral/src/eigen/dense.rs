//! Dense path for small components: the whole pencil at once.
//!
//! With `D = M^-1/2` on the vertices that carry mass (P) the pencil
//! `L x = lambda M x` becomes the symmetric standard problem
//! `D S D y = lambda y`, `x_P = D y`, where `S = L_PP` or, when some vertices
//! have zero mass (Z), the Schur complement `S = L_PP - L_PZ L_ZZ^-1 L_ZP`
//! with `x_Z = -L_ZZ^-1 L_ZP x_P` (the constraint rows `(L x)_Z = 0`).
//! faer's dense self-adjoint eigensolver (tridiagonalization + divide and
//! conquer) then gives every pair. Cost O(n^3); used for n up to a few
//! hundred, where it beats any iterative method.
//!
//! When the constant is a null vector (`y_0 = M^1/2 1 / sqrt(area)`), it is
//! deflated (Hotelling deflation, see Saad 2011, "Numerical Methods for
//! Large Eigenvalue Problems", sec. 4.2): `A + c y_0 y_0^T` with `c` above
//! the Gershgorin bound of `A` moves it to the top of the spectrum, so the
//! smallest pairs are those of the complement. Without it, the zero of a
//! small piece comes out as `+-eps lambda_max`, which for a fragment of a
//! scan (area 1e-11) is of order -1e-2.

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

use super::problem::Component;
use crate::error::{Result, SpectralError};

/// The `want` smallest pairs of a component (of the M-orthogonal complement
/// of the constant when `deflate`): ascending values and the eigenvectors
/// (component size x want), M-orthonormal.
pub(crate) fn smallest(c: &Component, want: usize, deflate: bool) -> Result<(Vec<f64>, Mat<f64>)> {
    let nc = c.vertices.len();
    let massive: Vec<usize> = (0..nc).filter(|&i| c.mass[i] > 0.0).collect();
    let massless: Vec<usize> = (0..nc).filter(|&i| c.mass[i] <= 0.0).collect();
    let full = dense(c);
    let pick = |rows: &[usize], cols: &[usize]| Mat::from_fn(rows.len(), cols.len(), |i, j| full[(rows[i], cols[j])]);
    let mut s = pick(&massive, &massive);
    // Harmonic extension operator E = -L_ZZ^-1 L_ZP (z x p), if needed.
    let extension = if massless.is_empty() {
        None
    } else {
        let lzz = pick(&massless, &massless);
        let lzp = pick(&massless, &massive);
        let llt = lzz
            .llt(Side::Lower)
            .map_err(|e| SpectralError::Dense(format!("the zero-mass block of L is not positive definite ({e:?})")))?;
        let e = -llt.solve(&lzp);
        // S = L_PP + L_PZ E
        s += pick(&massive, &massless) * &e;
        Some(e)
    };
    let d: Vec<f64> = massive.iter().map(|&i| 1.0 / c.mass[i].sqrt()).collect();
    let p = massive.len();
    let mut a = Mat::from_fn(p, p, |i, j| 0.5 * (s[(i, j)] + s[(j, i)]) * d[i] * d[j]);
    if deflate {
        let gershgorin = (0..p).map(|i| (0..p).map(|j| a[(i, j)].abs()).sum::<f64>()).fold(0.0, f64::max);
        // Relative to A (its unit is the pencil's): an absolute `+ 1` would
        // swamp a pencil of small eigenvalues with rounding.
        let c0 = if gershgorin > 0.0 { 2.0 * gershgorin } else { 1.0 };
        let y0: Vec<f64> = d.iter().map(|&di| 1.0 / (di * c.area.sqrt())).collect();
        a += Mat::from_fn(p, p, |i, j| c0 * y0[i] * y0[j]);
    }
    let eig = a.self_adjoint_eigen(Side::Lower).map_err(|e| SpectralError::Dense(format!("{e:?}")))?;
    let want = want.min(if deflate { p - 1 } else { p });
    let values: Vec<f64> = (0..want).map(|j| eig.S()[j]).collect();
    let xp = Mat::from_fn(p, want, |i, j| eig.U()[(i, j)] * d[i]);
    let mut x = Mat::zeros(nc, want);
    for (i, &v) in massive.iter().enumerate() {
        for j in 0..want {
            x[(v, j)] = xp[(i, j)];
        }
    }
    if let Some(e) = extension {
        let xz = e * &xp;
        for (i, &v) in massless.iter().enumerate() {
            for j in 0..want {
                x[(v, j)] = xz[(i, j)];
            }
        }
    }
    Ok((values, x))
}

fn dense(c: &Component) -> Mat<f64> {
    let nc = c.vertices.len();
    let mut full = Mat::zeros(nc, nc);
    for (i, row) in c.laplacian.outer_iterator().enumerate() {
        for (j, &v) in row.iter() {
            full[(i, j)] += v;
        }
    }
    full
}
