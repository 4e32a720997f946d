//! The smallest eigenpairs of the generalized problem `L x = lambda M x`
//! (seed section 2.7): `L` a symmetric positive semi-definite Laplacian
//! (cotangent, eq. 2.15, or intrinsic Delaunay), `M` a lumped (diagonal)
//! mass matrix.
//!
//! [`eigenpairs`] checks the matrices, splits the problem into the
//! connected components of `L` (every copy of a repeated eigenvalue that
//! comes from repeated pieces is found that way, and pieces without mass are
//! excluded), then per component:
//!
//! - **dense** (`n <=` [`Options::dense_threshold`]): `M^-1/2 L M^-1/2`
//!   and faer's dense self-adjoint eigensolver, O(n^3);
//! - **block Krylov-Schur shift-invert** otherwise: `K = L - sigma M` with a
//!   negative shift scaled to the mesh (Weyl's law: `lambda_j ~ 4 pi j /
//!   area`) factored once by sparse Cholesky; block Lanczos with thick
//!   restarts and full reorthogonalization on `B = M^1/2 K^-1 M^1/2`, where
//!   every step solves a block of right-hand sides at once and
//!   orthogonalization is matrix-matrix work; Ritz vectors purified by the
//!   last operator application (`x = K^-1 M y / theta`) and checked on the
//!   explicit residual; a final Rayleigh-Ritz on the pencil makes them
//!   M-orthonormal to rounding. Cost: one sparse Cholesky, O(k) block
//!   solves, O(n k^2) dense work per restart.
//!
//! Results are deterministic (seeded start block), eigenvalues ascending,
//! eigenvectors M-orthonormal, with the residual
//! `||L x - lambda M x|| / ||M x||` of every pair.

mod block_cholesky;
mod dense;
mod krylov;
mod problem;
mod random;
mod shift_invert;
pub(crate) mod tall;

use std::f64::consts::PI;
use std::time::Instant;

use faer::sparse::linalg::matmul::sparse_dense_matmul;
use faer::sparse::SparseColMat;
use faer::{Accum, Mat, MatRef, Side};
use sprs::CsMat;

use crate::error::{Result, SpectralError};
use block_cholesky::LANES;
use krylov::{BlockOperator, Config, Verdict};
use problem::Component;
use shift_invert::ShiftInvert;

/// Options of [`eigenpairs`]. `None` means "chosen from the problem".
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Shift sigma of `K = L - sigma M`; must lie below the smallest
    /// eigenvalue. `None`: `-max(lambda_est(k) / 20, lambda_est(1) / 2)`
    /// with Weyl's estimate `lambda_est(j) = 4 pi j / area`, made ten times
    /// larger in magnitude (up to 8 times) while `K` fails to factor.
    pub shift: Option<f64>,
    /// Relative tolerance: each pair is accepted when
    /// `||L x - lambda M x|| / ||M x|| <= tolerance * (|lambda| + |sigma|)`.
    pub tolerance: f64,
    /// Block size: how many vectors are solved and orthogonalized together;
    /// must exceed the largest multiplicity of an eigenvalue inside one
    /// connected piece (5 for icosahedral symmetry, 2 for rotational).
    /// `None`: `8 ceil((k + guard) / 64)`, between 8 and 32; grown (and the
    /// solve repeated, at most twice) when a converged cluster is as large.
    pub block_size: Option<usize>,
    /// Guard vectors computed beyond `k` (they speed up convergence and keep
    /// a cluster straddling the k-th value whole). `None`: `max(4, k / 10)`.
    pub guard: Option<usize>,
    /// Largest Krylov basis. `None`: `2 (k + guard) + 2 b`.
    pub basis_size: Option<usize>,
    /// Bound on thick restarts.
    pub max_restarts: usize,
    /// Components with at most this many vertices use the dense path.
    pub dense_threshold: usize,
    /// Seed of the random start block.
    pub seed: u64,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            shift: None,
            tolerance: 1e-11,
            block_size: None,
            guard: None,
            basis_size: None,
            max_restarts: 200,
            dense_threshold: 300,
            seed: 0x5EED_5EC7,
        }
    }
}

impl Options {
    fn validate(&self) -> Result<()> {
        let bad = |name, reason: String| Err(SpectralError::InvalidOption { name, reason });
        if !(self.tolerance > 0.0 && self.tolerance < 1.0) {
            return bad("tolerance", format!("{} is not in (0, 1)", self.tolerance));
        }
        if let Some(s) = self.shift {
            if !s.is_finite() {
                return bad("shift", format!("{s} is not finite"));
            }
        }
        if self.block_size == Some(0) {
            return bad("block_size", "must be at least 1".into());
        }
        Ok(())
    }
}

/// How a component was solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Dense self-adjoint eigendecomposition.
    Dense,
    /// Block Krylov-Schur on the shift-inverted operator.
    BlockKrylovSchur,
}

/// What the solve did and how long it took.
#[derive(Debug, Clone, PartialEq)]
pub struct Stats {
    /// Method used for the largest component.
    pub method: Method,
    /// Number of connected components with mass.
    pub components: usize,
    /// Shift sigma of the largest component (`None` when dense).
    pub shift: Option<f64>,
    /// Block size of the largest component (0 when dense).
    pub block_size: usize,
    /// Largest basis of the largest component (0 when dense).
    pub basis_size: usize,
    /// Thick restarts, summed over components.
    pub restarts: usize,
    /// Shift-invert applications counted in columns (linear solves).
    pub operator_columns: usize,
    /// Stored values of the Cholesky factor of the largest component.
    pub factor_nonzeros: usize,
    /// Seconds in sparse Cholesky factorizations.
    pub factor_seconds: f64,
    /// Seconds iterating (solves, orthogonalization, Rayleigh-Ritz) or in
    /// dense eigendecompositions.
    pub iterate_seconds: f64,
    /// Part of `iterate_seconds` spent in block solves.
    pub solve_seconds: f64,
    /// Part of `iterate_seconds` spent orthogonalizing.
    pub orthogonalize_seconds: f64,
    /// Seconds in the final Rayleigh-Ritz and residuals.
    pub finalize_seconds: f64,
    /// Wall-clock seconds of the whole call.
    pub total_seconds: f64,
}

/// The `k` smallest eigenpairs of `L x = lambda M x`.
#[derive(Debug, Clone)]
pub struct Eigenpairs {
    /// Eigenvalues, ascending.
    pub values: Vec<f64>,
    /// `||L x - lambda M x|| / ||M x||` of each pair.
    pub residuals: Vec<f64>,
    /// Vertices of components without mass (isolated vertices, pieces of
    /// zero area): every eigenvector is zero there.
    pub excluded: Vec<usize>,
    /// Solver statistics and timings.
    pub stats: Stats,
    vectors: Mat<f64>,
}

impl Eigenpairs {
    /// Number of pairs k.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// `true` when there is no pair (never returned by [`eigenpairs`]).
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// Length of each eigenvector (rows of `L`).
    pub fn vertex_count(&self) -> usize {
        self.vectors.nrows()
    }

    /// Eigenvector `j` (M-orthonormal: `x_i^T M x_j = delta_ij`).
    ///
    /// # Panics
    /// If `j >= self.len()`.
    pub fn vector(&self, j: usize) -> &[f64] {
        self.vectors.col_as_slice(j)
    }

    /// All eigenvectors as the columns of an n x k matrix.
    pub fn vectors(&self) -> MatRef<'_, f64> {
        self.vectors.as_ref()
    }

    /// Keeps the first `k` pairs (no-op if `k >= len`).
    pub fn truncate(&mut self, k: usize) {
        if k < self.len() {
            self.values.truncate(k);
            self.residuals.truncate(k);
            let n = self.vectors.nrows();
            self.vectors.truncate(n, k);
        }
    }
}

/// The `k` smallest eigenpairs of `L x = lambda M x` (see the module
/// documentation for the method). `L`: symmetric (checked), typically
/// positive semi-definite; `M`: diagonal with non-negative entries.
///
/// Cost for one component of n vertices: a sparse Cholesky of `L - sigma M`
/// plus about 3-6 k solves done in blocks, and O(n k^2) dense work per
/// restart (a handful); O(n^3) for `n <=` [`Options::dense_threshold`].
///
/// Errors: malformed matrices, `k = 0`, `k` above the number of vertices
/// carrying mass ([`SpectralError::TooManyPairs`]), a shift that is not
/// below the spectrum, no convergence within [`Options::max_restarts`].
pub fn eigenpairs(l: &CsMat<f64>, m: &CsMat<f64>, k: usize, options: &Options) -> Result<Eigenpairs> {
    let start = Instant::now();
    options.validate()?;
    if k == 0 {
        return Err(SpectralError::InvalidOption { name: "k", reason: "at least one eigenpair is needed".into() });
    }
    let problem = problem::split(l, m)?;
    let available = problem.available();
    if k > available {
        return Err(SpectralError::TooManyPairs { requested: k, available });
    }
    let partials =
        problem.components.iter().map(|c| solve_component(c, k.min(c.massive), options)).collect::<Result<Vec<_>>>()?;
    let mut out = merge(&problem.components, &partials, problem.n, k);
    out.excluded = problem.excluded;
    out.stats.total_seconds = start.elapsed().as_secs_f64();
    Ok(out)
}

/// The pairs of one component, before merging.
struct Partial {
    values: Vec<f64>,
    vectors: Mat<f64>,
    residuals: Vec<f64>,
    stats: Stats,
}

/// Vertex count up to which the dense path is still taken when the Krylov
/// basis would not fit (k close to n).
const DENSE_LIMIT: usize = 4000;

fn solve_component(c: &Component, want: usize, options: &Options) -> Result<Partial> {
    let sizes = KrylovSizes::new(want, c.massive, options);
    match sizes {
        Some(sizes) if c.vertices.len() > options.dense_threshold => krylov_component(c, want, sizes, options),
        _ if c.massive <= DENSE_LIMIT.max(options.dense_threshold) => dense_component(c, want),
        _ => Err(SpectralError::InvalidOption {
            name: "k",
            reason: format!("{want} pairs of a {}-vertex piece: use k below {}", c.massive, c.massive / 3),
        }),
    }
}

fn dense_component(c: &Component, want: usize) -> Result<Partial> {
    let t = Instant::now();
    let (values, vectors) = dense::smallest(c, want)?;
    let iterate_seconds = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let lf = mesh_core::solver::to_faer(&c.laplacian)?;
    let residuals = residuals(&lf, &c.mass, &values, vectors.as_ref());
    let stats = Stats {
        method: Method::Dense,
        components: 1,
        shift: None,
        block_size: 0,
        basis_size: 0,
        restarts: 0,
        operator_columns: 0,
        factor_nonzeros: 0,
        factor_seconds: 0.0,
        iterate_seconds,
        solve_seconds: 0.0,
        orthogonalize_seconds: 0.0,
        finalize_seconds: t.elapsed().as_secs_f64(),
        total_seconds: 0.0,
    };
    Ok(Partial { values, vectors, residuals, stats })
}

/// Guard, block and basis sizes of a Krylov run.
#[derive(Debug, Clone, Copy)]
struct KrylovSizes {
    nev: usize,
    block: usize,
    basis: usize,
}

impl KrylovSizes {
    /// `None` when the basis would not fit in the dimension `dim`.
    fn new(want: usize, dim: usize, o: &Options) -> Option<Self> {
        let nev = want + o.guard.unwrap_or((want / 10).max(4));
        let block = o.block_size.unwrap_or((LANES * nev.div_ceil(64)).clamp(LANES, 4 * LANES));
        Self::with_block(want, dim, o, block)
    }

    fn with_block(want: usize, dim: usize, o: &Options, block: usize) -> Option<Self> {
        let nev = want + o.guard.unwrap_or((want / 10).max(4));
        let basis = o.basis_size.unwrap_or(2 * nev + 2 * block).max(nev + 2 * block);
        (basis + block <= dim).then_some(Self { nev, block, basis })
    }
}

/// The shift-invert operator seen by the Krylov iteration.
impl BlockOperator for ShiftInvert {
    fn dim(&self) -> usize {
        ShiftInvert::dim(self)
    }
    fn apply(&self, q: MatRef<'_, f64>, w: &mut Mat<f64>) -> Result<()> {
        ShiftInvert::apply(self, q, w)
    }
}

/// Default shift: `-max(lambda_est(k) / 20, lambda_est(1) / 2)` with
/// Weyl's law `lambda_est(j) = 4 pi j / area`. Close to zero, the wanted
/// eigenvalues are well separated after inversion (convergence); not too
/// close, so that the largest wanted ones keep their accuracy (the error of
/// `lambda` grows like `((lambda - sigma) / sigma)^2` times rounding).
fn auto_shift(area: f64, want: usize) -> f64 {
    let weyl = 4.0 * PI / area;
    -(weyl * want as f64 / 20.0).max(weyl / 2.0)
}

fn factor(c: &Component, want: usize, options: &Options) -> Result<ShiftInvert> {
    if let Some(shift) = options.shift {
        return ShiftInvert::new(c, shift);
    }
    let mut shift = auto_shift(c.area, want);
    let mut last = None;
    for _ in 0..8 {
        match ShiftInvert::new(c, shift) {
            Ok(op) => return Ok(op),
            Err(e) => last = Some(e),
        }
        shift *= 10.0;
    }
    Err(last.unwrap_or_else(|| SpectralError::Dense("no shift could be factored".into())))
}

/// Most shift-invert runs per component: a converged cluster of nearly
/// equal eigenvalues as large as the block may hide further copies (a block
/// of b vectors sees at most b copies), so the run is repeated with a larger
/// block when that happens and the block size is automatic.
const MAX_RUNS: usize = 3;

fn krylov_component(c: &Component, want: usize, sizes: KrylovSizes, options: &Options) -> Result<Partial> {
    let t = Instant::now();
    let op = factor(c, want, options)?;
    let factor_seconds = t.elapsed().as_secs_f64();
    let lf = mesh_core::solver::to_faer(&c.laplacian)?;
    let floor = rounding_floor(&c.laplacian, &c.mass);
    let mut sizes = sizes;
    let mut stats = Stats {
        method: Method::BlockKrylovSchur,
        components: 1,
        shift: Some(op.shift()),
        block_size: 0,
        basis_size: 0,
        restarts: 0,
        operator_columns: 0,
        factor_nonzeros: op.factor_nonzeros(),
        factor_seconds,
        iterate_seconds: 0.0,
        solve_seconds: 0.0,
        orthogonalize_seconds: 0.0,
        finalize_seconds: 0.0,
        total_seconds: 0.0,
    };
    for run in 1..=MAX_RUNS {
        let (values, vectors, residuals) = krylov_run(c, &op, &lf, floor, want, sizes, options, &mut stats)?;
        let cluster = largest_cluster(&values, op.shift());
        let grown = KrylovSizes::with_block(want, c.massive, options, (cluster + 2).next_multiple_of(LANES));
        match grown {
            Some(next) if options.block_size.is_none() && cluster >= sizes.block && run < MAX_RUNS => sizes = next,
            _ => return Ok(Partial { values, vectors, residuals, stats }),
        }
    }
    Err(SpectralError::NotConverged { converged: 0, wanted: want, restarts: stats.restarts, worst: f64::NAN })
}

/// One block Krylov-Schur run and the final Rayleigh-Ritz; adds its counts
/// and timings to `stats`.
fn krylov_run(
    c: &Component,
    op: &ShiftInvert,
    lf: &SparseColMat<usize, f64>,
    floor: f64,
    want: usize,
    sizes: KrylovSizes,
    options: &Options,
    stats: &mut Stats,
) -> Result<(Vec<f64>, Mat<f64>, Vec<f64>)> {
    let t = Instant::now();
    let (shift, tol) = (op.shift(), options.tolerance);
    let cfg = Config {
        want,
        nev: sizes.nev.min(sizes.basis - 2 * sizes.block),
        block: sizes.block,
        basis: sizes.basis,
        tol,
        max_restarts: options.max_restarts,
        seed: options.seed,
    };
    let outcome = krylov::solve(op, &cfg, |theta, y, u| {
        let x = op.vectors(y, u, theta)?;
        let (values, res) = rayleigh_quotients_and_residuals(lf, &c.mass, x.as_ref());
        let ratios = res.iter().zip(&values).map(|(r, v)| r / (tol * (v.abs() + shift.abs())).max(floor)).collect();
        Ok(Verdict { ratios, vectors: x })
    })?;
    stats.iterate_seconds += t.elapsed().as_secs_f64();
    let t = Instant::now();
    let (values, vectors) = final_rayleigh_ritz(lf, &c.mass, outcome.vectors)?;
    let residuals = residuals(lf, &c.mass, &values, vectors.as_ref());
    stats.finalize_seconds += t.elapsed().as_secs_f64();
    stats.block_size = cfg.block;
    stats.basis_size = cfg.basis;
    stats.restarts += outcome.restarts;
    stats.operator_columns += outcome.columns;
    stats.solve_seconds += outcome.timings.apply;
    stats.orthogonalize_seconds += outcome.timings.orthogonalize;
    Ok((values, vectors, residuals))
}

/// Size of the largest run of ascending values closer than
/// `1e-8 (|lambda| + |sigma|)` to their neighbour.
fn largest_cluster(values: &[f64], shift: f64) -> usize {
    let mut best = usize::from(!values.is_empty());
    let mut run = 1;
    for w in values.windows(2) {
        if (w[1] - w[0]).abs() <= 1e-8 * (w[1].abs() + shift.abs()) {
            run += 1;
            best = best.max(run);
        } else {
            run = 1;
        }
    }
    best
}

/// Rayleigh-Ritz of the pencil on span(X): with `X^T M X = C C^T`
/// (Cholesky) and `C^-1 X^T L X C^-T = S Lambda S^T`, the Ritz vectors
/// `X C^-T S` are M-orthonormal to rounding. O(n k^2).
fn final_rayleigh_ritz(lf: &SparseColMat<usize, f64>, mass: &[f64], x: Mat<f64>) -> Result<(Vec<f64>, Mat<f64>)> {
    let (n, k) = (x.nrows(), x.ncols());
    let mut mx = x.clone();
    for j in 0..k {
        mx.col_as_slice_mut(j).iter_mut().zip(mass).for_each(|(v, m)| *v *= m);
    }
    let mut gram = Mat::zeros(k, k);
    tall::gram(gram.as_mut(), x.as_ref(), mx.as_ref());
    let lx = sparse_times(lf, x.as_ref());
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

/// Residual level that rounding alone produces: `16 eps` times the
/// Gershgorin bound `max_i sum_j |L_ij| / m_i` of the largest eigenvalue.
/// The acceptance target never goes below it, so the test always terminates.
fn rounding_floor(l: &CsMat<f64>, mass: &[f64]) -> f64 {
    let bound = l
        .outer_iterator()
        .zip(mass)
        .filter(|(_, &m)| m > 0.0)
        .map(|(row, &m)| row.iter().map(|(_, v)| v.abs()).sum::<f64>() / m)
        .fold(0.0, f64::max);
    16.0 * f64::EPSILON * bound
}

/// Rayleigh quotients `x^T L x / x^T M x` and residuals
/// `||L x - lambda M x|| / ||M x||` of the columns (one sparse product).
fn rayleigh_quotients_and_residuals(
    lf: &SparseColMat<usize, f64>,
    mass: &[f64],
    x: MatRef<'_, f64>,
) -> (Vec<f64>, Vec<f64>) {
    let lx = sparse_times(lf, x);
    (0..x.ncols())
        .map(|j| {
            let (xj, lxj) = (column(x, j), lx.col_as_slice(j));
            let (mut num, mut den) = (0.0, 0.0);
            for i in 0..xj.len() {
                num += xj[i] * lxj[i];
                den += mass[i] * xj[i] * xj[i];
            }
            let lambda = if den > 0.0 { num / den } else { f64::NAN };
            (lambda, residual(&xj, lxj, mass, lambda))
        })
        .unzip()
}

fn sparse_times(lf: &SparseColMat<usize, f64>, x: MatRef<'_, f64>) -> Mat<f64> {
    let mut lx = Mat::zeros(x.nrows(), x.ncols());
    sparse_dense_matmul(lx.as_mut(), Accum::Replace, lf.as_ref(), x, 1.0, faer::get_global_parallelism());
    lx
}

fn column<'a>(x: MatRef<'a, f64>, j: usize) -> std::borrow::Cow<'a, [f64]> {
    match x.col(j).try_as_col_major() {
        Some(c) => std::borrow::Cow::Borrowed(c.as_slice()),
        None => std::borrow::Cow::Owned(x.col(j).iter().copied().collect()),
    }
}

/// `||L x - lambda M x|| / ||M x||` from `x` and `L x`.
fn residual(x: &[f64], lx: &[f64], mass: &[f64], lambda: f64) -> f64 {
    let (mut r, mut mx) = (0.0, 0.0);
    for i in 0..x.len() {
        let m = mass[i] * x[i];
        r += (lx[i] - lambda * m).powi(2);
        mx += m * m;
    }
    if mx > 0.0 {
        (r / mx).sqrt()
    } else {
        f64::INFINITY
    }
}

/// `||L x - lambda M x|| / ||M x||` for each column.
fn residuals(lf: &SparseColMat<usize, f64>, mass: &[f64], values: &[f64], x: MatRef<'_, f64>) -> Vec<f64> {
    let lx = sparse_times(lf, x);
    values.iter().enumerate().map(|(j, &lambda)| residual(&column(x, j), lx.col_as_slice(j), mass, lambda)).collect()
}

/// The `k` smallest pairs over all components, ties broken by component
/// then position: deterministic.
fn merge(components: &[Component], partials: &[Partial], n: usize, k: usize) -> Eigenpairs {
    let mut order: Vec<(f64, usize, usize)> = partials
        .iter()
        .enumerate()
        .flat_map(|(ci, p)| p.values.iter().enumerate().map(move |(j, &v)| (v, ci, j)))
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    order.truncate(k);
    let mut vectors = Mat::zeros(n, order.len());
    let mut values = Vec::with_capacity(order.len());
    let mut residuals = Vec::with_capacity(order.len());
    for (col, &(v, ci, j)) in order.iter().enumerate() {
        values.push(v);
        residuals.push(partials[ci].residuals[j]);
        let src = partials[ci].vectors.col_as_slice(j);
        let dst = vectors.col_as_slice_mut(col);
        for (li, &g) in components[ci].vertices.iter().enumerate() {
            dst[g] = src[li];
        }
    }
    let largest = (0..components.len()).max_by_key(|&i| components[i].vertices.len()).unwrap_or(0);
    let mut stats = partials.get(largest).map(|p| p.stats.clone()).unwrap_or(Stats {
        method: Method::Dense,
        components: 0,
        shift: None,
        block_size: 0,
        basis_size: 0,
        restarts: 0,
        operator_columns: 0,
        factor_nonzeros: 0,
        factor_seconds: 0.0,
        iterate_seconds: 0.0,
        solve_seconds: 0.0,
        orthogonalize_seconds: 0.0,
        finalize_seconds: 0.0,
        total_seconds: 0.0,
    });
    stats.components = components.len();
    stats.restarts = partials.iter().map(|p| p.stats.restarts).sum();
    stats.operator_columns = partials.iter().map(|p| p.stats.operator_columns).sum();
    stats.factor_seconds = partials.iter().map(|p| p.stats.factor_seconds).sum();
    stats.iterate_seconds = partials.iter().map(|p| p.stats.iterate_seconds).sum();
    stats.solve_seconds = partials.iter().map(|p| p.stats.solve_seconds).sum();
    stats.orthogonalize_seconds = partials.iter().map(|p| p.stats.orthogonalize_seconds).sum();
    stats.finalize_seconds = partials.iter().map(|p| p.stats.finalize_seconds).sum();
    Eigenpairs { values, residuals, excluded: Vec::new(), stats, vectors }
}
