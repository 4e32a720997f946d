//! The smallest eigenpairs of the generalized problem `L x = lambda M x`
//! ("Digital Shape Processing" thesis chapter, sec. 2.7): `L` a symmetric
//! positive semi-definite Laplacian (cotangent, eq. 2.15, or intrinsic
//! Delaunay), `M` a lumped (diagonal) mass matrix.
//!
//! [`eigenpairs`] checks the matrices and splits the problem into the
//! connected components of `L` (the spectrum of a block-diagonal pencil is
//! the union of its blocks'; pieces without mass are excluded). The
//! constant of each component is an exact null vector: it is returned as
//! the eigenvalue 0 (exactly), first, and deflated from the computation of
//! the rest, so a scan of 151 pieces gives 151 zeros and nothing negative.
//! Then per component, only as many pairs as can still rank among the k
//! smallest:
//!
//! - **dense** (`n <=` [`EigenOptions::dense_threshold`]): `M^-1/2 L M^-1/2`
//!   with the constant moved to the top, faer's dense self-adjoint
//!   eigensolver, O(n^3);
//! - **block Krylov-Schur shift-invert** otherwise: `K = L - sigma M` with a
//!   negative shift scaled to the piece (Weyl's law: `lambda_j ~ 4 pi j /
//!   area`) factored once by sparse Cholesky; block Lanczos with thick
//!   restarts and full reorthogonalization on `B = M^1/2 K^-1 M^1/2`
//!   projected onto the complement of the constant, where every step solves
//!   a block of right-hand sides at once and orthogonalization is
//!   matrix-matrix work; Ritz vectors purified by the last operator
//!   application (`x = K^-1 M y / theta`) and checked on the explicit
//!   residual; a final Rayleigh-Ritz on the pencil makes them M-orthonormal
//!   to rounding. Cost: one sparse Cholesky, O(k) block solves, O(n k^2)
//!   dense work per restart.
//!
//! Every returned pair meets the tolerance on its explicit relative
//! residual (see [`EigenOptions::tolerance`]); a component whose pairs miss it is
//! solved again with more restarts, a larger block and another shift, and
//! otherwise the call fails with [`SpectralError::NotConverged`]. Where a
//! returned cluster of equal values is as large as the block (which could
//! hide further copies), the number of eigenvalues below it is counted by
//! inertia, and a miss is solved again with a larger block.
//! Results are deterministic (seeded start block), eigenvalues ascending,
//! eigenvectors M-orthonormal.

mod component;
mod dense;
mod krylov;
mod merge;
mod narrow;
mod problem;
mod quality;
mod shift_invert;
pub(crate) mod tall;
mod tile;

use std::fmt;
use std::time::Instant;

use faer::{Mat, MatRef};
use mesh_kernel::solver::FillOrdering;
use sprs::CsMat;

use crate::error::{Result, SpectralError};

/// Which connected components the spectrum is computed on.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum ComponentSelection {
    /// Every component: the spectrum of the whole pencil (one zero per piece).
    #[default]
    All,
    /// Only the largest component (of `L`'s graph by total mass in
    /// [`eigenpairs`]; of the mesh by face count in
    /// [`crate::ManifoldHarmonics::new`]): one zero, then its own
    /// frequencies. What a scan's user usually wants: the small fragments of
    /// a scan only add zeros and very high frequencies.
    Largest,
}

impl ComponentSelection {
    /// Every choice; their [`name`](Self::name)s are what
    /// [`FromStr`](std::str::FromStr) accepts and [`Display`](fmt::Display)
    /// writes.
    pub const ALL: [Self; 2] = [Self::All, Self::Largest];

    /// The name used on the command line: `all`, `largest`.
    pub fn name(self) -> &'static str {
        match self {
            Self::All => "all",
            Self::Largest => "largest",
        }
    }
}

mesh_kernel::named_choice!(ComponentSelection, "component", SpectralError);

/// Options of [`eigenpairs`]. `None` means "chosen from the problem".
#[derive(Debug, Clone, PartialEq)]
pub struct EigenOptions {
    /// Shift sigma of `K = L - sigma M`; must lie below the smallest
    /// eigenvalue. `None`: `-s` with the spectral scale
    /// `s = max(lambda_est(k) / 20, lambda_est(1) / 2)` of each component
    /// (Weyl's estimate `lambda_est(j) = 4 pi j / area`), made ten times
    /// larger in magnitude (up to 8 times) while `K` fails to factor, and
    /// four times larger on the last attempt. A given shift is never changed.
    pub shift: Option<f64>,
    /// Relative tolerance on every returned pair:
    /// `||L x - lambda M x|| / ((|lambda| + s) ||M x||) <= tolerance`, with
    /// the component's spectral scale `s` above. Where evaluating the
    /// residual in double precision cannot do better (`16 eps || |L| |x| ||`,
    /// reached for the smallest pairs of meshes of 1e5-1e6 vertices), that
    /// level is the target instead and [`EigenStats::tolerance`] says so.
    pub tolerance: f64,
    /// Block size: how many vectors are solved and orthogonalized together.
    /// In exact arithmetic a block of b vectors holds at most b copies of a
    /// repeated eigenvalue (5 for icosahedral symmetry, 2 for rotational):
    /// when a returned cluster is as large as the block, the eigenvalues
    /// below it are counted by inertia (an `L D L^T` factorization of
    /// `L - mu M`, Sylvester's law) and the piece is solved again with a
    /// larger block only if copies are missing. `None`: 4 for
    /// `k + guard <= 32` (fewer solves in all than 8: 116-132 against
    /// 184-216 for k = 20), otherwise `8 ceil((k + guard) / 64)`, between 8
    /// and 32; grown on every retry.
    pub block_size: Option<usize>,
    /// Guard vectors computed beyond `k` (they speed up convergence and keep
    /// a cluster straddling the k-th value whole). `None`: `max(4, k / 10)`.
    pub guard: Option<usize>,
    /// Largest Krylov basis. `None`: `2 (k + guard) + 2 b`.
    pub basis_size: Option<usize>,
    /// Bound on thick restarts of the first attempt (each retry doubles it).
    pub max_restarts: usize,
    /// Components with at most this many vertices use the dense path.
    pub dense_threshold: usize,
    /// Seed of the random start block.
    pub seed: u64,
    /// Every component, or only the largest.
    pub component: ComponentSelection,
    /// Fill-reducing ordering of the shift-invert factor. For a mesh's
    /// pencil, the vertices' positions give the geometric nested dissection
    /// ([`FillOrdering::of_points`]), which factors and solves faster from
    /// tens of thousands of vertices. `None`: minimum degree in
    /// [`eigenpairs`] (which sees no mesh), the mesh's dissection in
    /// [`crate::ManifoldHarmonics`].
    pub ordering: Option<FillOrdering>,
}

impl Default for EigenOptions {
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
            component: ComponentSelection::All,
            ordering: None,
        }
    }
}

impl EigenOptions {
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

/// How the largest solved component was solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum EigenSolver {
    /// Nothing to solve: every returned pair is an exact null vector (a
    /// constant per component).
    NullSpace,
    /// Dense self-adjoint eigendecomposition.
    Dense,
    /// Block Krylov-Schur on the shift-inverted operator.
    BlockKrylovSchur,
}

impl fmt::Display for EigenSolver {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::NullSpace => "null-space",
            Self::Dense => "dense",
            Self::BlockKrylovSchur => "block-krylov-schur",
        })
    }
}

/// What the solve did and how long it took.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct EigenStats {
    /// Solver used for the largest component that needed a solve.
    pub method: EigenSolver,
    /// Connected components of `L` with mass.
    pub components: usize,
    /// Components the spectrum was computed on (all, or 1 with
    /// [`ComponentSelection::Largest`]).
    pub components_used: usize,
    /// Returned pairs that are exact null vectors (the constant of a
    /// component, eigenvalue exactly 0).
    pub zero_eigenvalues: usize,
    /// The tolerance the returned pairs meet: [`EigenOptions::tolerance`], or
    /// the rounding level of the residual where that is larger.
    pub tolerance: f64,
    /// Shift sigma of the largest solved component (`None` when dense).
    pub shift: Option<f64>,
    /// Block size of the largest solved component (0 when dense).
    pub block_size: usize,
    /// Largest basis of the largest solved component (0 when dense).
    pub basis_size: usize,
    /// Attempts for the largest solved component (1 when the first converged).
    pub attempts: usize,
    /// Whether no copy of a repeated eigenvalue can be missing. A block of
    /// b vectors sees at most b copies of one eigenvalue, so a returned
    /// cluster of equal values as large as the block is checked by counting
    /// the eigenvalues below it by inertia (Sylvester's law), and solved
    /// again with a larger block when the count differs. `false` when, on
    /// some component, the count still differed (or could not be trusted)
    /// with the largest block tried: the values from that cluster on may
    /// then be too large. `true` for dense solves, clusters smaller than the
    /// block, and counts that agree.
    pub clusters_verified: bool,
    /// Thick restarts, summed over components and attempts.
    pub restarts: usize,
    /// Shift-invert applications counted in columns (linear solves).
    pub operator_columns: usize,
    /// Stored values of the Cholesky factor of the largest solved component.
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

impl EigenStats {
    /// What a caller should tell its user about these pairs: `Some` when
    /// [`EigenStats::clusters_verified`] is false.
    pub fn caveat(&self) -> Option<&'static str> {
        (!self.clusters_verified).then_some(
            "a cluster of equal eigenvalues filled the largest block tried and the inertia count of the \
             eigenvalues below it disagreed: copies of a repeated eigenvalue may be missing, and the values \
             from that cluster on may be too large",
        )
    }

    /// Zero counts and times.
    pub(crate) fn empty(method: EigenSolver) -> Self {
        Self {
            method,
            components: 1,
            components_used: 1,
            zero_eigenvalues: 0,
            tolerance: 0.0,
            shift: None,
            block_size: 0,
            basis_size: 0,
            attempts: 0,
            clusters_verified: true,
            restarts: 0,
            operator_columns: 0,
            factor_nonzeros: 0,
            factor_seconds: 0.0,
            iterate_seconds: 0.0,
            solve_seconds: 0.0,
            orthogonalize_seconds: 0.0,
            finalize_seconds: 0.0,
            total_seconds: 0.0,
        }
    }
}

/// The `k` smallest eigenpairs of `L x = lambda M x`.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct Eigenpairs {
    /// Eigenvalues, ascending; the null vectors' are exactly 0.
    pub values: Vec<f64>,
    /// Relative residual `||L x - lambda M x|| / ((|lambda| + s) ||M x||)`
    /// of each pair (see [`EigenOptions::tolerance`]); each is at most
    /// [`EigenStats::tolerance`].
    pub residuals: Vec<f64>,
    /// Absolute residual `||L x - lambda M x|| / ||M x||` of each pair (in
    /// the units of lambda).
    pub absolute_residuals: Vec<f64>,
    /// Vertices where every eigenvector is zero: components without mass
    /// (isolated vertices, pieces of zero area), and every component but the
    /// largest with [`ComponentSelection::Largest`].
    pub excluded: Vec<usize>,
    /// Solver statistics and timings.
    pub stats: EigenStats,
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
            self.absolute_residuals.truncate(k);
            let n = self.vectors.nrows();
            self.vectors.truncate(n, k);
        }
    }

    /// The same pairs on a parent of `n` vertices: row `i` goes to row
    /// `rows[i]`, the other rows are zero (and excluded). O(n k).
    pub(crate) fn scatter(self, rows: &[usize], n: usize) -> Result<Self> {
        if rows.len() != self.vertex_count() || rows.iter().any(|&r| r >= n) {
            return Err(SpectralError::Dimension(format!(
                "{} rows mapped into {n} for eigenvectors of length {}",
                rows.len(),
                self.vertex_count()
            )));
        }
        let mut vectors = Mat::zeros(n, self.len());
        for j in 0..self.len() {
            let (src, dst) = (self.vectors.col_as_slice(j), vectors.col_as_slice_mut(j));
            rows.iter().zip(src).for_each(|(&r, &x)| dst[r] = x);
        }
        let mut inside = vec![false; n];
        rows.iter().for_each(|&r| inside[r] = true);
        let mut excluded: Vec<usize> = self.excluded.iter().map(|&i| rows[i]).collect();
        excluded.extend((0..n).filter(|&i| !inside[i]));
        excluded.sort_unstable();
        Ok(Self { vectors, excluded, ..self })
    }
}

/// The `k` smallest eigenpairs of `L x = lambda M x` (see the module
/// documentation for the method). `L`: symmetric (checked), typically
/// positive semi-definite; `mass`: the diagonal of the lumped mass matrix
/// `M` (non-negative, finite), the form [`crate::laplace_beltrami`],
/// [`crate::Pencil`] and `mesh_kernel::operators::lumped_mass` return.
///
/// Cost for one component of n vertices: a sparse Cholesky of `L - sigma M`
/// plus about 3-6 k solves done in blocks, and O(n k^2) dense work per
/// restart (a handful); O(n^3) for `n <=` [`EigenOptions::dense_threshold`];
/// nothing but O(nnz) checks for pairs that are null vectors.
///
/// Errors: malformed matrices, `k = 0`, `k` above the number of vertices
/// carrying mass ([`SpectralError::TooManyPairs`]), a shift that is not
/// below the spectrum, a pair that misses the tolerance after every retry
/// ([`SpectralError::NotConverged`], with the residuals).
///
/// # Errors
/// `SpectralError::InvalidOption` (`k` for 0, `tolerance`, `shift`, `block_size`, `component`) for invalid
/// options; `SpectralError::InvalidMatrix` for a Laplacian that is not square or symmetric, or masses that
/// are negative or not finite; `SpectralError::Dimension` when `mass` does not have one entry per row of `L`; `SpectralError::TooManyPairs` when `k` exceeds the vertices
/// carrying mass; `SpectralError::NotConverged` with the residuals when the tolerance is not reached;
/// `SpectralError::Mesh` (`MeshError::Solver`) or `SpectralError::Dense` when a factorization fails.
pub fn eigenpairs(l: &CsMat<f64>, mass: &[f64], k: usize, options: &EigenOptions) -> Result<Eigenpairs> {
    let start = Instant::now();
    options.validate()?;
    let m = &mesh_kernel::operators::mass::diagonal(mass.to_vec());
    if k == 0 {
        return Err(SpectralError::InvalidOption { name: "k", reason: "at least one eigenpair is needed".into() });
    }
    let units = Units::of(l, m);
    if units.is_identity() {
        return solve(l, m, k, options, start);
    }
    let options = EigenOptions { shift: options.shift.map(|s| s / units.lambda()), ..options.clone() };
    let mut out = solve(&l.map(|x| x / units.l), &m.map(|x| x / units.m), k, &options, start)?;
    units.restore(&mut out);
    Ok(out)
}

/// Powers of two by which the pencil is divided. `M` always: a mesh's mass
/// matrix carries the square of its unit of length, and the solver works on
/// masses whose largest lies in [1, 4) (an even power of two, so that its
/// square root is exact) whatever that unit is, so that every step (the
/// shift and the residual scale from Weyl's law, the deflation of the
/// constant, the tolerances) sees numbers of the same size, within a factor
/// of 4, for a mesh in millimetres and in metres. `L` only when its entries
/// lie outside `[2^-100, 2^100]`: a mesh Laplacian's weights do not depend
/// on the unit of length (cotangents), and dividing them by their largest
/// (a sliver's huge cotangent on a scan) would move the spectrum away from
/// Weyl's estimate of it. Division by powers of two changes no digit of the
/// answer. Costs one copy of `L` and `M`.
struct Units {
    l: f64,
    m: f64,
}

impl Units {
    fn of(l: &CsMat<f64>, m: &CsMat<f64>) -> Self {
        let unit = |a: &CsMat<f64>| mesh_kernel::units::unit_of(a.data().iter().copied());
        let safe = |x: f64| (2f64.powi(-100)..=2f64.powi(100)).contains(&x);
        let lu = unit(l);
        let even = 2f64.powi(unit(m).log2().round() as i32 & !1);
        Self { l: if safe(lu) { 1.0 } else { lu }, m: even }
    }

    fn is_identity(&self) -> bool {
        self.l == 1.0 && self.m == 1.0
    }

    /// The eigenvalues of the given pencil per eigenvalue of the scaled one.
    fn lambda(&self) -> f64 {
        self.l / self.m
    }

    /// Pairs of the scaled pencil to pairs of the given one: values times
    /// `l / m`, vectors divided by `sqrt(m)` (so that `x^T M x` stays 1).
    fn restore(&self, out: &mut Eigenpairs) {
        let (lambda, root) = (self.lambda(), self.m.sqrt());
        out.values.iter_mut().chain(&mut out.absolute_residuals).for_each(|x| *x *= lambda);
        out.stats.shift = out.stats.shift.map(|s| s * lambda);
        for j in 0..out.vectors.ncols() {
            out.vectors.col_as_slice_mut(j).iter_mut().for_each(|x| *x /= root);
        }
    }
}

/// [`eigenpairs`] on a pencil of moderate size.
fn solve(l: &CsMat<f64>, m: &CsMat<f64>, k: usize, options: &EigenOptions, start: Instant) -> Result<Eigenpairs> {
    let mut problem = problem::split(l, m)?;
    let components = problem.components.len();
    if options.component == ComponentSelection::Largest {
        problem.keep_largest();
    }
    let available = problem.available();
    if k > available {
        return Err(SpectralError::TooManyPairs { requested: k, available });
    }
    let mut out = merge::solve_all(&problem, k, options)?;
    out.excluded = problem.excluded;
    out.stats.components = components;
    out.stats.total_seconds = start.elapsed().as_secs_f64();
    Ok(out)
}
