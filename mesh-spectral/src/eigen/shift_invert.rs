//! The shift-invert operator `B = M^1/2 (L - sigma M)^-1 M^1/2`.
//!
//! With `y = M^1/2 x` (on the vertices that carry mass) the pencil
//! `L x = lambda M x` has the same eigenvectors as the symmetric operator
//! `B`, with eigenvalues `theta = 1 / (lambda - sigma)`: for `sigma < 0`
//! below the spectrum the smallest `lambda` become the largest, well
//! separated `theta`, and `K = L - sigma M` is symmetric positive definite,
//! factored once by a sparse Cholesky. Working in `y` makes `B` symmetric in
//! the Euclidean inner product, so orthogonalization is plain matrix-matrix
//! work. Zero-mass vertices stay in `K` and drop out of `y`: `B` is then the
//! operator of the Schur-complement pencil, exactly.
//!
//! The coordinates of `y` follow the fill-reducing order of the factor, so
//! moving a block between the Krylov basis and the solver is a sequential
//! transposition, not a random gather.

use std::borrow::Cow;
use std::sync::Mutex;

use faer::{Mat, MatRef};
use mesh_kernel::solver::{Cholesky, FillOrdering};

use super::problem::Component;
use crate::error::{Result, SpectralError};

/// Right-hand sides per block solve: the width of one 512-bit vector of
/// doubles (two AVX2 registers).
pub(crate) const LANES: usize = 8;

/// The values of one unknown for [`LANES`] right-hand sides.
type Lane = [f64; LANES];

/// A factored `K = L - sigma M` with the mass scaling.
#[derive(Debug)]
pub(crate) struct ShiftInvert {
    chol: Cholesky,
    shift: f64,
    /// Per permuted unknown of `K`: its coordinate in `y` and `sqrt(mass)`,
    /// or `None` for a massless vertex.
    coords: Vec<Option<(usize, f64)>>,
    /// Component row of each coordinate of `y`.
    rows: Vec<usize>,
    /// Reused lane buffers of the block solves.
    scratch: Mutex<Vec<Vec<Lane>>>,
}

impl ShiftInvert {
    /// Factors `L - shift M`. Fails if it is not positive definite (the
    /// shift is not below the spectrum).
    ///
    /// # Errors
    /// `SpectralError::Mesh` (`MeshError::Solver`) when the shifted matrix cannot be factorized.
    pub fn new(c: &Component, shift: f64, ordering: &FillOrdering) -> Result<Self> {
        let k = &c.laplacian - &mesh_kernel::operators::mass::diagonal(c.mass.iter().map(|m| shift * m).collect());
        let chol = Cholesky::with_ordering(&k, ordering)?;
        let mut rows = Vec::with_capacity(c.massive);
        let coords = chol
            .order()
            .iter()
            .map(|&row| {
                let m = c.mass[row];
                (m > 0.0).then(|| {
                    rows.push(row);
                    (rows.len() - 1, m.sqrt())
                })
            })
            .collect();
        Ok(Self { chol, shift, coords, rows, scratch: Mutex::new(Vec::new()) })
    }

    /// The shift sigma.
    pub fn shift(&self) -> f64 {
        self.shift
    }

    /// Stored values of the Cholesky factor.
    pub fn factor_nonzeros(&self) -> usize {
        self.chol.factor_nonzeros()
    }

    /// Component row of each coordinate of `y` (the vertices with mass, in
    /// the factor's order).
    pub fn rows(&self) -> &[usize] {
        &self.rows
    }

    /// Dimension of `B` (vertices with mass).
    pub fn dim(&self) -> usize {
        self.rows.len()
    }

    /// `w = B q` for a block of columns: block solves of [`LANES`] columns
    /// (in parallel across lane groups with the `rayon` feature).
    ///
    /// # Errors
    /// `SpectralError::Mesh` (`MeshError::Dimension`) if a block does not match the factor.
    pub fn apply(&self, q: MatRef<'_, f64>, w: &mut Mat<f64>) -> Result<()> {
        let mut groups = self.take_scratch(q.ncols());
        self.gather(q, |_| 1.0, &mut groups);
        self.solve_groups(&mut groups)?;
        for (g, lanes) in groups.iter().enumerate() {
            let cols = LANES.min(q.ncols() - g * LANES);
            let mut outs: Vec<&mut [f64]> = Vec::with_capacity(cols);
            let (_, rest) = w.as_mut().split_at_col_mut(g * LANES);
            let mut rest = rest;
            for _ in 0..cols {
                let (head, tail) = rest.split_at_col_mut(1);
                if let Some(c) = head.col_mut(0).try_as_col_major_mut() {
                    outs.push(c.as_slice_mut());
                }
                rest = tail;
            }
            for (lane, coord) in lanes.iter().zip(&self.coords) {
                if let Some((i, s)) = *coord {
                    for (k, out) in outs.iter_mut().enumerate() {
                        out[i] = s * lane[k];
                    }
                }
            }
        }
        self.put_scratch(groups);
        Ok(())
    }

    /// Lane buffers for `b` columns, reused across applications.
    fn take_scratch(&self, b: usize) -> Vec<Vec<Lane>> {
        let mut groups = self.scratch.lock().map(|mut s| std::mem::take(&mut *s)).unwrap_or_default();
        groups.resize_with(b.div_ceil(LANES), Vec::new);
        groups.truncate(b.div_ceil(LANES));
        for g in &mut groups {
            g.resize(self.coords.len(), [0.0; LANES]);
        }
        groups
    }

    fn put_scratch(&self, groups: Vec<Vec<Lane>>) {
        if let Ok(mut s) = self.scratch.lock() {
            *s = groups;
        }
    }

    /// Block solves of every group, in the factor's order.
    fn solve_groups(&self, groups: &mut [Vec<Lane>]) -> Result<()> {
        #[cfg(feature = "rayon")]
        {
            use rayon::prelude::*;
            groups.par_iter_mut().try_for_each(|g| self.chol.solve_ordered_rows(g))?;
        }
        #[cfg(not(feature = "rayon"))]
        for g in groups.iter_mut() {
            self.chol.solve_ordered_rows(g)?;
        }
        Ok(())
    }

    /// Fills `groups` with `M^1/2 q`, column j scaled by `scale(j)`, as
    /// row-major groups of [`LANES`] columns in the factor's order
    /// (zero-padded): one sequential sweep per group.
    fn gather(&self, q: MatRef<'_, f64>, scale: impl Fn(usize) -> f64, groups: &mut [Vec<Lane>]) {
        let b = q.ncols();
        for (g, lanes) in groups.iter_mut().enumerate() {
            let cols: Vec<(Cow<'_, [f64]>, f64)> =
                (g * LANES..b.min(g * LANES + LANES)).map(|j| (column(q, j), scale(j))).collect();
            for (lane, coord) in lanes.iter_mut().zip(&self.coords) {
                *lane = [0.0; LANES];
                if let Some((i, s)) = *coord {
                    for (k, (col, sj)) in cols.iter().enumerate() {
                        lane[k] = s * sj * col[i];
                    }
                }
            }
        }
    }

    /// Eigenvectors of the pencil on the whole component (component row
    /// order) from Ritz vectors `y` of `B`, their purified form
    /// `u = B y / theta` and values `theta`: `x = K^-1 M^1/2 y / theta`,
    /// which is `M^-1/2 u` on massive vertices and the harmonic extension on
    /// massless ones (one extra block solve, only when such vertices exist).
    ///
    /// # Errors
    /// `SpectralError::Dense` when a Ritz value is zero or not finite (cannot be inverted).
    pub fn vectors(&self, y: MatRef<'_, f64>, u: MatRef<'_, f64>, theta: &[f64]) -> Result<Mat<f64>> {
        let n = self.coords.len();
        let mut x = Mat::zeros(n, u.ncols());
        if self.rows.len() == n {
            for (pi, coord) in self.coords.iter().enumerate() {
                if let Some((i, s)) = *coord {
                    let row = self.rows[i];
                    debug_assert_eq!(row, self.chol.order()[pi]);
                    for j in 0..u.ncols() {
                        x[(row, j)] = u[(i, j)] / s;
                    }
                }
            }
            return Ok(x);
        }
        if let Some(t) = theta.iter().find(|t| !(t.is_finite() && **t != 0.0)) {
            return Err(SpectralError::Dense(format!("Ritz value {t} cannot be inverted")));
        }
        let mut groups = self.take_scratch(y.ncols());
        self.gather(y, |j| 1.0 / theta[j], &mut groups);
        self.solve_groups(&mut groups)?;
        let perm = self.chol.order();
        for (g, lanes) in groups.iter().enumerate() {
            for k in 0..LANES.min(y.ncols() - g * LANES) {
                let out = x.col_as_slice_mut(g * LANES + k);
                for (lane, &row) in lanes.iter().zip(perm) {
                    out[row] = lane[k];
                }
            }
        }
        self.put_scratch(groups);
        Ok(x)
    }
}

/// Column j of `q` as a slice (copied only if it is not contiguous).
fn column<'a>(q: MatRef<'a, f64>, j: usize) -> Cow<'a, [f64]> {
    match q.col(j).try_as_col_major() {
        Some(c) => Cow::Borrowed(c.as_slice()),
        None => Cow::Owned(q.col(j).iter().copied().collect()),
    }
}
