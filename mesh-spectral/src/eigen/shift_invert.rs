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
use mesh_kernel::MeshError;

use super::problem::Component;
use super::tall::column;
use crate::error::{Result, SpectralError};

/// Widths of the block solves, narrowest first: the columns of a block go
/// to solves of the widest width the block calls for, and its last
/// columns to the narrowest width that holds them (zero-padded).
const WIDTHS: [usize; 4] = [4, 8, 16, 32];

/// The widest of [`WIDTHS`].
const WIDEST: usize = WIDTHS[WIDTHS.len() - 1];

/// The narrowest of [`WIDTHS`] that holds `b` columns (the widest if none).
fn width_for(b: usize) -> usize {
    WIDTHS.into_iter().find(|&w| w >= b).unwrap_or(WIDEST)
}

/// The widest solve for blocks of `b` columns: the factor's
/// ([`Cholesky::widest_block`]), narrowed so that each thread gets a
/// group when the block can be split (the groups are solved in parallel).
fn widest_for(b: usize) -> usize {
    #[cfg(feature = "rayon")]
    let threads = rayon::current_num_threads().max(1);
    #[cfg(not(feature = "rayon"))]
    let threads = 1;
    Cholesky::widest_block().min(width_for(b.div_ceil(threads)))
}

/// The groups `(first column, width)` of the block solves of `b` columns.
fn lane_groups(b: usize) -> impl Iterator<Item = (usize, usize)> {
    group_widths(b, widest_for(b))
}

/// The groups `(first column, width)` that cover `b` columns: of width
/// `widest`, the last one of the narrowest width that holds the rest.
fn group_widths(b: usize, widest: usize) -> impl Iterator<Item = (usize, usize)> {
    (0..b.div_ceil(widest)).map(move |g| {
        let first = g * widest;
        (first, width_for(b - first).min(widest))
    })
}

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
    /// Reused lane buffers of the block solves: per group of columns, its
    /// values row by row (`width` per unknown, in the factor's order).
    scratch: Mutex<Vec<Vec<f64>>>,
}

impl ShiftInvert {
    /// Factors `L - shift M`. Fails if it is not positive definite (the
    /// shift is not below the spectrum).
    ///
    /// # Errors
    /// `SpectralError::Mesh` (`MeshError::Solver`) when the shifted matrix cannot be factorized.
    pub fn new(c: &Component, shift: f64, ordering: &FillOrdering) -> Result<Self> {
        let chol = Cholesky::with_ordering(&shifted(c, shift), ordering)?;
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

    /// How many eigenvalues of the component's pencil lie below `mu`: the
    /// negative eigenvalues of `L - mu M` (Sylvester's law of inertia,
    /// through this factor's analysis); `None` when the count cannot be
    /// trusted ([`Cholesky::negative_eigenvalues`]: a pivot near zero, as
    /// where a diagonal entry cancels) or `L - mu M` lost an entry of the
    /// analysed pattern.
    ///
    /// # Errors
    /// `SpectralError::Mesh` when the workspace cannot be allocated.
    pub fn eigenvalues_below(&self, c: &Component, mu: f64) -> Result<Option<usize>> {
        match self.chol.negative_eigenvalues(&shifted(c, mu)) {
            Ok(count) => Ok(count),
            Err(MeshError::Dimension(_)) => Ok(None),
            Err(e) => Err(e.into()),
        }
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

    /// `w = B q` for a block of columns, or `w = (I - y y^T) B q` with
    /// `project = Some(y)` (`y` of unit length, in the coordinates of `y`):
    /// block solves of up to 32 columns ([`lane_groups`]; in parallel
    /// across groups with the `rayon` feature). The projection's products
    /// `y^T B q` are read from the solves' lanes, and `w` is written once,
    /// projected: at 470,274 vertices and k = 200 the operator's
    /// applications took 7.8 s in all, against 8.3-8.9 s when two passes
    /// over each column of `w` projected it after it was written.
    ///
    /// # Errors
    /// `SpectralError::Mesh` (`MeshError::Dimension`) if a block does not match the factor.
    pub fn apply(&self, q: MatRef<'_, f64>, w: &mut Mat<f64>, project: Option<&[f64]>) -> Result<()> {
        let mut groups = self.take_scratch(q.ncols());
        self.gather(q, |_| 1.0, &mut groups);
        self.solve_groups(q.ncols(), &mut groups)?;
        // Row after row, the group's columns side by side (a pass per
        // column would read every lane `width` times).
        for ((first, width), lanes) in lane_groups(q.ncols()).zip(&groups) {
            let mut along = [0.0; WIDEST];
            if let Some(y) = project {
                for (row, coord) in lanes.chunks_exact(width).zip(&self.coords) {
                    if let Some((i, s)) = *coord {
                        let weight = y[i] * s;
                        for (d, &v) in along.iter_mut().zip(row) {
                            *d += weight * v;
                        }
                    }
                }
            }
            let mut outs: Vec<_> = w.as_mut().subcols_mut(first, width.min(q.ncols() - first)).col_iter_mut().collect();
            for (row, coord) in lanes.chunks_exact(width).zip(&self.coords) {
                if let Some((i, s)) = *coord {
                    let yi = project.map_or(0.0, |y| y[i]);
                    for ((out, &v), &d) in outs.iter_mut().zip(row).zip(&along) {
                        out[i] = s * v - d * yi;
                    }
                }
            }
        }
        self.put_scratch(groups);
        Ok(())
    }

    /// Lane buffers for `b` columns, reused across applications.
    fn take_scratch(&self, b: usize) -> Vec<Vec<f64>> {
        let mut groups = self.scratch.lock().map(|mut s| std::mem::take(&mut *s)).unwrap_or_default();
        let widths: Vec<usize> = lane_groups(b).map(|(_, width)| width).collect();
        groups.resize_with(widths.len(), Vec::new);
        for (g, width) in groups.iter_mut().zip(widths) {
            g.resize(self.coords.len() * width, 0.0);
        }
        groups
    }

    fn put_scratch(&self, groups: Vec<Vec<f64>>) {
        if let Ok(mut s) = self.scratch.lock() {
            *s = groups;
        }
    }

    /// Block solves of every group of the `b` columns, in the factor's order.
    fn solve_groups(&self, b: usize, groups: &mut [Vec<f64>]) -> Result<()> {
        let solve = |(_, width): (usize, usize), g: &mut Vec<f64>| -> Result<()> {
            match width {
                4 => self.chol.solve_ordered_rows(g.as_chunks_mut::<4>().0),
                8 => self.chol.solve_ordered_rows(g.as_chunks_mut::<8>().0),
                16 => self.chol.solve_ordered_rows(g.as_chunks_mut::<16>().0),
                _ => self.chol.solve_ordered_rows(g.as_chunks_mut::<32>().0),
            }
            .map_err(SpectralError::from)
        };
        let widths: Vec<(usize, usize)> = lane_groups(b).collect();
        #[cfg(feature = "rayon")]
        {
            use rayon::prelude::*;
            widths.into_par_iter().zip(groups.par_iter_mut()).try_for_each(|(w, g)| solve(w, g))?;
        }
        #[cfg(not(feature = "rayon"))]
        for (w, g) in widths.into_iter().zip(groups.iter_mut()) {
            solve(w, g)?;
        }
        Ok(())
    }

    /// Fills `groups` with `M^1/2 q`, column j scaled by `scale(j)`, as
    /// row-major groups of columns in the factor's order (zero-padded): one
    /// sequential sweep per group.
    fn gather(&self, q: MatRef<'_, f64>, scale: impl Fn(usize) -> f64, groups: &mut [Vec<f64>]) {
        let b = q.ncols();
        for ((first, width), lanes) in lane_groups(b).zip(groups.iter_mut()) {
            let cols: Vec<(Cow<'_, [f64]>, f64)> =
                (first..b.min(first + width)).map(|j| (column(q, j), scale(j))).collect();
            for (row, coord) in lanes.chunks_exact_mut(width).zip(&self.coords) {
                row.fill(0.0);
                if let Some((i, s)) = *coord {
                    for (k, (col, sj)) in cols.iter().enumerate() {
                        row[k] = s * sj * col[i];
                    }
                }
            }
        }
    }

    /// Eigenvectors of the pencil on the whole component, rows in the
    /// factor's order ([`Self::order`]), from Ritz vectors `y` of `B`, their
    /// purified form `u = B y / theta` and values `theta`:
    /// `x = K^-1 M^1/2 y / theta`, which is `M^-1/2 u` on massive vertices
    /// and the harmonic extension on massless ones (one extra block solve,
    /// only when such vertices exist). In the factor's order the former is
    /// done in place on `u` and the latter is a sequential sweep.
    ///
    /// # Errors
    /// `SpectralError::Dense` when a Ritz value is zero or not finite (cannot be inverted).
    pub fn vectors(&self, y: MatRef<'_, f64>, mut u: Mat<f64>, theta: &[f64]) -> Result<Mat<f64>> {
        let n = self.coords.len();
        if self.rows.len() == n {
            // Every unknown has mass: coordinate i of `y` is unknown i.
            for j in 0..u.ncols() {
                for (o, coord) in u.col_as_slice_mut(j).iter_mut().zip(&self.coords) {
                    if let Some((_, s)) = *coord {
                        *o /= s;
                    }
                }
            }
            return Ok(u);
        }
        let mut x = Mat::zeros(n, u.ncols());
        if let Some(t) = theta.iter().find(|t| !(t.is_finite() && **t != 0.0)) {
            return Err(SpectralError::Dense(format!("Ritz value {t} cannot be inverted")));
        }
        let mut groups = self.take_scratch(y.ncols());
        self.gather(y, |j| 1.0 / theta[j], &mut groups);
        self.solve_groups(y.ncols(), &mut groups)?;
        for ((first, width), lanes) in lane_groups(y.ncols()).zip(&groups) {
            let mut outs: Vec<_> = x.as_mut().subcols_mut(first, width.min(y.ncols() - first)).col_iter_mut().collect();
            for (i, row) in lanes.chunks_exact(width).enumerate() {
                for (out, &v) in outs.iter_mut().zip(row) {
                    out[i] = v;
                }
            }
        }
        self.put_scratch(groups);
        Ok(x)
    }

    /// The factor's order: the component row of each of its unknowns.
    pub fn order(&self) -> &[usize] {
        self.chol.order()
    }
}

/// `L - shift M` of a component.
fn shifted(c: &Component, shift: f64) -> sprs::CsMat<f64> {
    // L's own pattern, with `shift * m` taken off its diagonal in place
    // (sprs's difference of two matrices merged every row, twice a solve:
    // 0.9% of a 20-pair solve at 40,962 vertices). A row without a
    // diagonal entry gets one through that difference.
    let mut a = c.laplacian.clone();
    for i in 0..a.rows() {
        let row = a.indptr().outer_inds_sz(i);
        let Ok(k) = a.indices()[row.clone()].binary_search(&i) else {
            a = &c.laplacian - &mesh_kernel::operators::mass::diagonal(c.mass.iter().map(|m| shift * m).collect());
            break;
        };
        a.data_mut()[row.start + k] -= shift * c.mass[i];
    }
    // Symmetric (`problem::split` checks L, to 1e-10 of its largest
    // entry): its transpose, the same arrays in the other storage order,
    // is itself to that tolerance, and the factorization takes compressed
    // columns without converting. The factor and the inertia count both
    // read it so, on the same pattern.
    a.transpose_into()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eigen::problem::{graph_laplacian, split};
    use mesh_kernel::operators::mass::diagonal;

    #[test]
    fn the_projected_product_is_the_product_projected() {
        // A path of 50 with a chord, uneven masses, two massless vertices.
        let edges: Vec<(usize, usize)> = (0..49).map(|i| (i, i + 1)).chain([(3, 30)]).collect();
        let mass: Vec<f64> =
            (0..50).map(|i| if i == 7 || i == 21 { 0.0 } else { 1.0 + (i % 5) as f64 * 0.3 }).collect();
        let problem = split(&graph_laplacian(50, &edges), &diagonal(mass)).unwrap();
        let si = ShiftInvert::new(&problem.components[0], -0.2, &FillOrdering::MinimumDegree).unwrap();
        let n = si.dim();
        let norm = (0..n).map(|i| ((i % 7) as f64 + 1.0).powi(2)).sum::<f64>().sqrt();
        let y: Vec<f64> = (0..n).map(|i| ((i % 7) as f64 + 1.0) / norm).collect();
        for b in [3, 20, 37] {
            let q = Mat::from_fn(n, b, |i, j| ((i * 3 + j * 5) % 11) as f64 - 5.0);
            let (mut plain, mut projected) = (Mat::zeros(n, b), Mat::zeros(n, b));
            si.apply(q.as_ref(), &mut plain, None).unwrap();
            si.apply(q.as_ref(), &mut projected, Some(&y)).unwrap();
            for j in 0..b {
                let col = plain.col_as_slice(j);
                let d: f64 = col.iter().zip(&y).map(|(a, b)| a * b).sum();
                let scale = col.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                for i in 0..n {
                    let expect = col[i] - d * y[i];
                    assert!((projected[(i, j)] - expect).abs() <= 1e-13 * scale, "{b} {j} {i}");
                }
                let along: f64 = projected.col_as_slice(j).iter().zip(&y).map(|(a, b)| a * b).sum();
                assert!(along.abs() <= 1e-13 * scale, "{b} {j}: {along:e}");
            }
        }
    }

    #[test]
    fn lane_groups_cover_the_block_with_the_narrowest_width_last() {
        let widths = |b, widest| group_widths(b, widest).collect::<Vec<_>>();
        assert_eq!(widths(4, 32), vec![(0, 4)]);
        assert_eq!(widths(3, 32), vec![(0, 4)]);
        assert_eq!(widths(12, 32), vec![(0, 16)]);
        assert_eq!(widths(32, 32), vec![(0, 32)]);
        assert_eq!(widths(32, 16), vec![(0, 16), (16, 16)]);
        assert_eq!(widths(12, 8), vec![(0, 8), (8, 4)]);
        assert_eq!(widths(14, 8), vec![(0, 8), (8, 8)]);
        assert_eq!(widths(20, 8), vec![(0, 8), (8, 8), (16, 4)]);
        assert_eq!(widths(40, 32), vec![(0, 32), (32, 8)]);
        for b in 1..100 {
            let w = widest_for(b);
            assert!(WIDTHS.contains(&w) && w <= Cholesky::widest_block());
            let groups = widths(b, w);
            assert!(groups.windows(2).all(|p| p[1].0 == p[0].0 + p[0].1));
            let (first, last) = groups[groups.len() - 1];
            assert!(first + last >= b && first < b);
        }
    }
}
